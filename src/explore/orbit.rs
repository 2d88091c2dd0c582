//! Turning a 3-D chart (`isosurface`, `volume`) in the explorer: drag turns the camera about
//! the volume's centre, a slider moves an isosurface's value, and direct volume rendering is
//! drawn with fewer rays while the pointer is down and at full resolution on release. A slider
//! moves a one-plane `slice` chart's plane along its axis. The view is kept as overrides of the
//! chart's own keys, which the chart is redrawn with.

use serde_json::Value;

use crate::spec::Chart;

/// Degrees the camera turns per canvas unit dragged.
pub const DEGREES_PER_UNIT: f64 = 0.5;

/// Rays across the image of a volume rendering while the camera is being turned.
pub const PREVIEW_RAYS: u32 = 128;

/// The spec's defaults (those of `kind = "isosurface"` and `"volume"`).
const AZIMUTH: f64 = -60.0;
const ELEVATION: f64 = 25.0;

/// The explorer's view of a 3-D chart, over the spec's.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Orbit {
    /// Camera azimuth in degrees, when turned.
    pub azimuth: Option<f64>,
    /// Camera elevation in degrees, when turned.
    pub elevation: Option<f64>,
    /// The value of the first isosurface, when moved.
    pub level: Option<f64>,
    /// Where a slice chart's one axis-aligned plane crosses its axis, when moved.
    pub plane: Option<f64>,
    /// Drawn as a quick preview (a drag is under way).
    pub preview: bool,
}

/// Whether the explorer turns chart `chart` by dragging.
pub fn turns(chart: &Chart) -> bool {
    matches!(chart.kind.name(), "isosurface" | "volume")
}

/// The world axis (0, 1, 2 for x, y, z) of a `slice` chart drawing one axis-aligned plane,
/// whose plane a slider can move; `None` for lightboxes, oblique planes and other kinds.
pub fn sliding_axis(chart: &Chart) -> Option<usize> {
    if chart.kind.name() != "slice" {
        return None;
    }
    let value = serde_json::to_value(chart).ok()?;
    let present = |key: &str| value.get(key).is_some_and(|v| !v.is_null());
    let one_at = value.get("at").and_then(Value::as_array).is_none_or(|at| at.len() <= 1);
    let one_count = value.get("count").and_then(Value::as_u64).is_none_or(|n| n <= 1);
    if present("planes") || !one_at || !one_count {
        return None;
    }
    match value.get("axis").and_then(Value::as_str).unwrap_or("z") {
        "x" => Some(0),
        "y" => Some(1),
        _ => Some(2),
    }
}

fn number(value: &Value, key: &str) -> Option<f64> {
    value.get(key).and_then(Value::as_f64)
}

impl Orbit {
    /// The camera `[azimuth, elevation]` chart `chart` is drawn with under this view.
    pub fn camera(&self, chart: &Chart) -> [f64; 2] {
        let value = serde_json::to_value(chart).unwrap_or(Value::Null);
        [
            self.azimuth.or_else(|| number(&value, "azimuth")).unwrap_or(AZIMUTH),
            self.elevation.or_else(|| number(&value, "elevation")).unwrap_or(ELEVATION),
        ]
    }

    /// Turns the camera for a drag by `(dx, dy)` canvas units: right turns the volume to the
    /// right (the camera to the left), down tilts its top towards the viewer; the elevation
    /// stays within ±90°.
    pub fn turn(&mut self, chart: &Chart, dx: f64, dy: f64) {
        let [azimuth, elevation] = self.camera(chart);
        self.azimuth = Some((azimuth - DEGREES_PER_UNIT * dx + 180.0).rem_euclid(360.0) - 180.0);
        self.elevation = Some((elevation + DEGREES_PER_UNIT * dy).clamp(-90.0, 90.0));
    }

    /// The first isosurface value chart `chart` is drawn with under this view.
    pub fn level(&self, chart: &Chart) -> Option<f64> {
        if chart.kind.name() != "isosurface" {
            return None;
        }
        let value = serde_json::to_value(chart).ok()?;
        let spec = match value.get("levels")? {
            Value::Array(levels) => levels.first().and_then(Value::as_f64),
            other => other.as_f64(),
        };
        self.level.or(spec)
    }

    /// Chart `chart` with this view's camera, level and resolution in place of its own (the
    /// chart unchanged when it is not a 3-D chart or nothing is overridden).
    pub fn apply(&self, chart: &Chart) -> Chart {
        let slides = self.plane.is_some() && sliding_axis(chart).is_some();
        if !(turns(chart) || slides) || *self == Orbit::default() {
            return chart.clone();
        }
        let Ok(mut value) = serde_json::to_value(chart) else { return chart.clone() };
        let Some(map) = value.as_object_mut() else { return chart.clone() };
        if let (Some(at), true) = (self.plane, slides) {
            map.insert("at".into(), Value::Array(vec![at.into()]));
            map.remove("count");
            map.remove("between");
            return serde_json::from_value(value).unwrap_or_else(|_| chart.clone());
        }
        if let Some(a) = self.azimuth {
            map.insert("azimuth".into(), a.into());
        }
        if let Some(e) = self.elevation {
            map.insert("elevation".into(), e.into());
        }
        if let (Some(level), "isosurface") = (self.level, chart.kind.name()) {
            match map.get_mut("levels") {
                Some(Value::Array(levels)) if !levels.is_empty() => levels[0] = level.into(),
                _ => {
                    map.insert("levels".into(), level.into());
                }
            }
        }
        if self.preview && chart.kind.name() == "volume" {
            let rays =
                map.get("resolution").and_then(Value::as_u64).map_or(PREVIEW_RAYS, |r| (r as u32).min(PREVIEW_RAYS));
            map.insert("resolution".into(), rays.into());
        }
        serde_json::from_value(value).unwrap_or_else(|_| chart.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// A chart named `c` over data `v` with the keys of `options`.
    fn chart(options: Value) -> Chart {
        let mut value = json!({ "name": "c", "data": "v" });
        if let (Some(map), Value::Object(extra)) = (value.as_object_mut(), options) {
            map.extend(extra);
        }
        serde_json::from_value(value).expect("a chart")
    }

    #[test]
    fn a_drag_turns_the_camera_from_the_spec_s_and_keeps_the_elevation_in_range() {
        let c = chart(json!({ "kind": "isosurface", "levels": [0.5, 0.8], "azimuth": 30 }));
        let mut o = Orbit::default();
        assert_eq!(o.camera(&c), [30.0, 25.0], "the spec's azimuth, the default elevation");
        o.turn(&c, 20.0, -10.0);
        assert_eq!(o.camera(&c), [20.0, 20.0]);
        o.turn(&c, 0.0, 1000.0);
        assert_eq!(o.camera(&c)[1], 90.0);
        o.turn(&c, -400.0, 0.0);
        assert_eq!(o.camera(&c)[0], -140.0, "220° wraps to −140°");
        let turned = o.apply(&c);
        let v = serde_json::to_value(&turned).expect("json");
        assert_eq!(v["azimuth"], -140.0);
        assert_eq!(v["elevation"], 90.0);
        assert_eq!(v["levels"], json!([0.5, 0.8]), "levels untouched");
    }

    #[test]
    fn the_level_moves_the_first_surface_and_previews_cut_the_rays() {
        let c = chart(json!({ "kind": "isosurface", "levels": [0.5, 0.8] }));
        let o = Orbit { level: Some(0.25), ..Orbit::default() };
        assert_eq!(Orbit::default().level(&c), Some(0.5));
        assert_eq!(o.level(&c), Some(0.25));
        assert_eq!(serde_json::to_value(o.apply(&c)).expect("json")["levels"], json!([0.25, 0.8]));
        let one = chart(json!({ "kind": "isosurface", "levels": 3 }));
        assert_eq!(serde_json::to_value(o.apply(&one)).expect("json")["levels"], 0.25);
        let dvr = chart(json!({ "kind": "volume", "resolution": 512 }));
        let preview = Orbit { preview: true, ..Orbit::default() };
        assert_eq!(serde_json::to_value(preview.apply(&dvr)).expect("json")["resolution"], 128);
        let small = chart(json!({ "kind": "volume", "resolution": 64 }));
        assert_eq!(serde_json::to_value(preview.apply(&small)).expect("json")["resolution"], 64);
        assert_eq!(o.level(&dvr), None);
        let slice = chart(json!({ "kind": "slice", "axis": "y", "count": 1 }));
        assert_eq!(sliding_axis(&slice), Some(1));
        let moved = Orbit { plane: Some(4.5), ..Orbit::default() }.apply(&slice);
        let v = serde_json::to_value(&moved).expect("json");
        assert_eq!((v["at"].clone(), v.get("count").cloned()), (json!([4.5]), Some(Value::Null)));
        assert_eq!(sliding_axis(&chart(json!({ "kind": "slice" }))), Some(2));
        assert_eq!(sliding_axis(&chart(json!({ "kind": "slice", "count": 4 }))), None, "a lightbox");
        assert_eq!(sliding_axis(&chart(json!({ "kind": "slice", "at": [1, 2] }))), None);
        let oblique = json!({ "kind": "slice", "planes": [{ "point": [0, 0, 0], "normal": [1, 1, 0] }] });
        assert_eq!(sliding_axis(&chart(oblique)), None);
        let table = chart(json!({ "kind": "scatter", "x": "a", "y": "b" }));
        assert!(!turns(&table));
        assert_eq!(Orbit { azimuth: Some(3.0), ..Orbit::default() }.apply(&table), table);
    }
}
