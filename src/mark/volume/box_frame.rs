//! The box of a volume as 3-D kinds draw it around their picture: the view keys shared by the
//! 3-D volume kinds and their light, the box seen through the camera and fitted into the plot
//! room with its ticked axes ([`BoxView`]), its twelve edges split into those behind the data
//! (drawn first) and those in front (drawn last), and each world axis named beside an outer
//! edge running along it (the orientation inset's labels).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::enrich::camera::{Camera, Light, Projection, Specular, View, axis_lines, equal_extent};
use crate::enrich::volume::{Interpolation, Sampler};
use crate::guide::Theme;
use crate::guide::axis::title_with_unit;
use crate::guide::format::format_value;
use crate::guide::layout::LayoutError;
use crate::mark::frame::PanelCanvas;
use crate::mark::{MarkError, axis3d};
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Rect, Role, Shape, Style, Text};

/// The title of the values in the legend.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ValueLabel {
    /// Legend title (default `value`).
    #[serde(default)]
    pub title: Option<String>,
    /// Unit of the values.
    #[serde(default)]
    pub unit: Option<String>,
}

/// The camera's projection.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ProjectionKind {
    /// Parallel projection.
    Orthographic,
    /// Central projection.
    Perspective,
}

/// A light from above and to the left of the viewer, turning with the view.
pub fn light_for(view: &View, specular: bool) -> Light {
    Light {
        azimuth_deg: view.azimuth_deg - 50.0,
        elevation_deg: (view.elevation_deg + 30.0).min(85.0),
        ambient: 0.3,
        diffuse: 0.95,
        specular: specular.then_some(Specular { strength: 0.35, shininess: 40.0 }),
    }
}

/// The view of the 3-D volume kinds' `azimuth`, `elevation`, `zoom`, `projection` and `fov`
/// keys, with their defaults (−60°, 25°, 1, orthographic, 30°).
pub fn view(
    azimuth: Option<f64>,
    elevation: Option<f64>,
    zoom: Option<f64>,
    projection: Option<ProjectionKind>,
    fov: Option<f64>,
) -> View {
    let projection = match projection.unwrap_or(ProjectionKind::Orthographic) {
        ProjectionKind::Orthographic => Projection::Orthographic,
        ProjectionKind::Perspective => Projection::Perspective { fov_deg: fov.unwrap_or(30.0) },
    };
    View {
        azimuth_deg: azimuth.unwrap_or(-60.0),
        elevation_deg: elevation.unwrap_or(25.0),
        zoom: zoom.unwrap_or(1.0),
        projection,
    }
}

/// A volume's box seen through a camera, fitted into a chart's plot room with space around it
/// for the axes.
pub struct BoxView {
    /// The camera on the box.
    pub camera: Camera,
    /// The box: the world span of the voxel centres along x, y and z.
    pub ranges: [(f64, f64); 3],
    /// Where the unit square of the camera's screen is drawn.
    pub square: Rect,
}

impl BoxView {
    /// The box of `sampler`'s volume seen from `view`, placed in `canvas`'s plot room; an error
    /// for a bad view or a canvas too small.
    pub fn new(sampler: &Sampler<'_>, view: View, canvas: &PanelCanvas) -> Result<BoxView, MarkError> {
        let corners = sampler.corners(Interpolation::Trilinear);
        let ranges = [0, 1, 2].map(|a| {
            corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| (lo.min(c[a]), hi.max(c[a])))
        });
        let camera = Camera::new(ranges, equal_extent(ranges), view)
            .map_err(|e| MarkError::at(&["azimuth"], format!("{e}"), "check the view settings"))?;
        let theme = &canvas.theme;
        let m = theme.margin;
        // Room around the box for tick labels and axis titles, as the surface kind leaves.
        let pad = theme.font_size * 5.0;
        let room_w = canvas.width - 2.0 * m - canvas.legend_room() - 2.0 * pad;
        let room_h = canvas.room - 1.5 * pad;
        if room_w < 40.0 || room_h < 40.0 {
            return Err(MarkError::layout(LayoutError::TooSmall {
                plot_width: room_w.max(0.0),
                plot_height: room_h.max(0.0),
            }));
        }
        let side = room_w.min(room_h);
        let square =
            Rect::new(m + pad + (room_w - side) / 2.0, canvas.top() + 0.5 * pad + (room_h - side) / 2.0, side, side);
        Ok(BoxView { camera, ranges, square })
    }

    /// The canvas point of world point `p`.
    pub fn to_px(&self, p: [f64; 3]) -> Point {
        let (sx, sy) = self.camera.project(p);
        Point::new(self.square.x + sx * self.square.w, self.square.y + (1.0 - sy) * self.square.h)
    }

    /// The ticked x, y and z axes along the box edges the camera picks, titled with `unit`.
    pub fn axes(&self, unit: Option<&str>, theme: &Theme) -> Vec<Item> {
        let [tx, ty, tz] = ["x", "y", "z"].map(|name| title_with_unit(name, unit));
        let to_px = |p: [f64; 3]| self.to_px(p);
        axis3d::draw_all(&axis_lines(&self.camera), [&tx, &ty, &tz], self.ranges, &to_px, theme)
    }
}

/// The box's edges seen by `camera`: those with both neighbouring faces turned away (behind
/// everything inside) and the others, as two path items.
pub fn edges(
    camera: &Camera,
    ranges: [(f64, f64); 3],
    to_px: &impl Fn([f64; 3]) -> Point,
    theme: &Theme,
) -> (Item, Item) {
    let toward = camera.toward_camera();
    // Face (axis, side) faces the viewer when its outward normal points toward the camera.
    let facing = |axis: usize, high: bool| if high { toward[axis] > 0.0 } else { toward[axis] < 0.0 };
    let (mut back, mut front) = (Vec::new(), Vec::new());
    for a in 0..3 {
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        for (hb, hc) in [(false, false), (true, false), (false, true), (true, true)] {
            let mut from = [0.0; 3];
            from[b] = if hb { ranges[b].1 } else { ranges[b].0 };
            from[c] = if hc { ranges[c].1 } else { ranges[c].0 };
            let mut to = from;
            from[a] = ranges[a].0;
            to[a] = ranges[a].1;
            let target = if facing(b, hb) || facing(c, hc) { &mut front } else { &mut back };
            target.push(PathCmd::MoveTo(to_px(from)));
            target.push(PathCmd::LineTo(to_px(to)));
        }
    }
    let style = Style::stroke(theme.muted_text.with_opacity(0.7), 0.8);
    (
        Item::new(Role::Axis, Shape::Path(back), style.clone()).labelled("volume box (behind)"),
        Item::new(Role::Axis, Shape::Path(front), style).labelled("volume box (in front)"),
    )
}

/// Each world axis named beside the middle of the outermost box edge running along it, outside
/// the box; with `extent`, the box's low and high coordinate at that edge's ends.
pub fn axis_labels(
    ranges: [(f64, f64); 3],
    to_px: &impl Fn([f64; 3]) -> Point,
    role: Role,
    color: Color,
    size: f64,
    extent: bool,
) -> Vec<Item> {
    let centre = to_px(ranges.map(|r| (r.0 + r.1) / 2.0));
    let away = |p: &Point| (p.x - centre.x).hypot(p.y - centre.y);
    let outward = |p: Point, by: f64| {
        let d = away(&p).max(1e-9);
        Point::new(p.x + (p.x - centre.x) / d * by, p.y + (p.y - centre.y) / d * by)
    };
    let text = |at: Point, content: String, size: f64| {
        Item::text(
            role,
            Text { at, content, size, anchor: Anchor::Middle, baseline: Baseline::Middle, angle: 0.0, color },
        )
    };
    let mut items = Vec::new();
    for (a, name) in ["x", "y", "z"].into_iter().enumerate() {
        // The four edges along axis a, as (low end, high end); the outermost on screen.
        let edge = |c: usize| {
            let mut p = [0.0; 3];
            for (bit, b) in [(a + 1) % 3, (a + 2) % 3].into_iter().enumerate() {
                p[b] = if c >> bit & 1 == 1 { ranges[b].1 } else { ranges[b].0 };
            }
            let (mut lo, mut hi) = (p, p);
            lo[a] = ranges[a].0;
            hi[a] = ranges[a].1;
            (to_px(lo), to_px(hi))
        };
        let middle = |(l, h): (Point, Point)| Point::new((l.x + h.x) / 2.0, (l.y + h.y) / 2.0);
        let Some((lo, hi)) = (0..4).map(edge).max_by(|p, q| away(&middle(*p)).total_cmp(&away(&middle(*q)))) else {
            continue;
        };
        items.push(
            text(outward(middle((lo, hi)), size * 1.1), name.to_string(), size).labelled(format!("box {name} axis")),
        );
        if extent {
            for (end, value) in [(lo, ranges[a].0), (hi, ranges[a].1)] {
                items.push(
                    Item::text(
                        if role == Role::AxisTitle { Role::TickLabel } else { role },
                        Text {
                            at: outward(end, size * 1.1),
                            content: format_value(value),
                            size: size * 0.85,
                            anchor: Anchor::Middle,
                            baseline: Baseline::Middle,
                            angle: 0.0,
                            color,
                        },
                    )
                    .labelled(format!("box {name} axis")),
                );
            }
        }
    }
    items
}
