//! Pointer geometry of a drawn chart: which plot or axis is under the pointer, which row is
//! nearest to it and how to describe that row, and zoom and pan as new axis domains that the
//! chart is redrawn with.

use std::collections::BTreeMap;

use serde_json::Value;

use crate::data::Table;
use crate::guide::format::format_value;
use crate::guide::scale::Scale;
use crate::mark::geometry::{Disk, Geometry, ParallelAxis, Plot};
use crate::scene::Point;
use crate::spec::Chart;

/// How far from an axis line a drag still brushes it, in canvas units.
pub const AXIS_REACH: f64 = 12.0;

/// The plot under `p`, by index into `geometry.plots`.
pub fn plot_at(geometry: &Geometry, p: Point) -> Option<usize> {
    geometry.plots.iter().position(|plot| {
        let r = plot.rect;
        p.x >= r.x && p.x <= r.right() && p.y >= r.y && p.y <= r.bottom()
    })
}

/// The parallel-coordinates axis within [`AXIS_REACH`] of `p`, by index into `geometry.axes`.
pub fn axis_at(geometry: &Geometry, p: Point) -> Option<usize> {
    let near =
        |a: &ParallelAxis| (p.x - a.x).abs() <= AXIS_REACH && p.y >= a.top - AXIS_REACH && p.y <= a.bottom + AXIS_REACH;
    (0..geometry.axes.len())
        .filter(|&i| near(&geometry.axes[i]))
        .min_by(|&a, &b| (p.x - geometry.axes[a].x).abs().total_cmp(&(p.x - geometry.axes[b].x).abs()))
}

/// Pixel positions of the rows of one column on a scale (band scales place categories), with
/// the column looked up once.
struct Positions<'a> {
    column: Option<&'a crate::data::Column>,
    scale: &'a Scale,
}

impl<'a> Positions<'a> {
    fn new(table: &'a Table, field: &str, scale: &'a Scale) -> Positions<'a> {
        Positions { column: table.column(field), scale }
    }

    /// Pixel position of `row`, if it has a finite one.
    fn at(&self, row: usize) -> Option<f64> {
        let column = self.column?;
        let px = match (column.numbers(), self.scale) {
            (Some(values), _) => self.scale.map(*values.get(row)?),
            (None, Scale::Band(band)) => {
                let cats = column.categories()?;
                band.center(band.band_of(cats.value(row)?)?)
            }
            (None, _) => return None,
        };
        px.is_finite().then_some(px)
    }
}

/// The row drawn nearest to `p` in `plot`, if one lies within `reach` canvas units. Ties go to
/// the row drawn last (on top). `None` in plots that do not place rows by both columns.
pub fn nearest_point(plot: &Plot, table: &Table, p: Point, reach: f64) -> Option<u32> {
    let (x, y) = (plot.x.as_ref()?, plot.y.as_ref()?);
    let (px, py) = (Positions::new(table, &x.field, &x.scale), Positions::new(table, &y.field, &y.scale));
    let mut best: Option<(f64, usize)> = None;
    for row in 0..table.rows {
        let Some(y) = py.at(row).filter(|y| (y - p.y).abs() <= reach) else { continue };
        let Some(x) = px.at(row) else { continue };
        let d = (x - p.x).hypot(y - p.y);
        if d <= reach && best.is_none_or(|(bd, _)| d <= bd) {
            best = Some((d, row));
        }
    }
    best.map(|(_, r)| r as u32)
}

/// The row whose parallel-coordinates polyline passes nearest to `p`, within `reach` canvas
/// units vertically.
pub fn nearest_line(axes: &[ParallelAxis], table: &Table, p: Point, reach: f64) -> Option<u32> {
    let k = axes.windows(2).position(|w| p.x >= w[0].x && p.x <= w[1].x)?;
    let (a, b) = (&axes[k], &axes[k + 1]);
    let t = if b.x > a.x { (p.x - a.x) / (b.x - a.x) } else { 0.0 };
    let (pa, pb) = (Positions::new(table, &a.field, &a.scale), Positions::new(table, &b.field, &b.scale));
    let mut best: Option<(f64, usize)> = None;
    for row in 0..table.rows {
        let (Some(ya), Some(yb)) = (pa.at(row), pb.at(row)) else { continue };
        let d = (ya + t * (yb - ya) - p.y).abs();
        if d <= reach && best.is_none_or(|(bd, _)| d <= bd) {
            best = Some((d, row));
        }
    }
    best.map(|(_, r)| r as u32)
}

/// The visible tree node under `p` (within its drawn radius plus `slack`), nearest first.
pub fn node_at(disk: &Disk, p: Point, slack: f64) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for (n, node) in disk.nodes.iter().enumerate() {
        if node.radius <= 0.0 {
            continue;
        }
        let c = disk.to_canvas(node.position);
        let d = (c.x - p.x).hypot(c.y - p.y);
        if d <= node.radius + slack && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, n));
        }
    }
    best.map(|(_, n)| n)
}

/// One line describing `row`: its number and its values in `fields` (in the order given, each
/// once).
pub fn describe(table: &Table, row: u32, fields: &[&str]) -> String {
    let mut seen: Vec<&str> = Vec::new();
    let mut parts = vec![format!("row {row}")];
    for &f in fields {
        if seen.contains(&f) {
            continue;
        }
        seen.push(f);
        let Some(col) = table.column(f) else { continue };
        let value = match (col.numbers(), col.categories()) {
            (Some(v), _) if col.is_time() => v
                .get(row as usize)
                .and_then(|ms| chrono::DateTime::from_timestamp_millis(*ms as i64))
                .map(|t| t.format("%Y-%m-%d %H:%M").to_string()),
            (Some(v), _) => v.get(row as usize).map(|x| format_value(*x)),
            (None, Some(c)) => Some(c.value(row as usize).unwrap_or("(missing)").to_string()),
            (None, None) => None,
        };
        if let Some(value) = value {
            parts.push(format!("{f} = {value}"));
        }
    }
    parts.join(" · ")
}

/// The domain after zooming `scale` by `factor` (below 1 zooms in) about pixel `at`, keeping
/// the value under `at` in place. Log scales zoom in log space. `None` for band scales.
pub fn zoomed(scale: &Scale, at: f64, factor: f64) -> Option<[f64; 2]> {
    if !(factor.is_finite() && factor > 0.0) {
        return None;
    }
    let (lo, hi) = scale.domain();
    let p = scale.invert(at)?;
    let out = match scale {
        Scale::Band(_) => return None,
        Scale::Log(_) => {
            if lo <= 0.0 || p <= 0.0 {
                return None;
            }
            let (l, h, c) = (lo.log10(), hi.log10(), p.log10());
            [10f64.powf(c + (l - c) * factor), 10f64.powf(c + (h - c) * factor)]
        }
        _ => [p + (lo - p) * factor, p + (hi - p) * factor],
    };
    (out[0].is_finite() && out[1].is_finite() && out[1] > out[0]).then_some(out)
}

/// The domain after dragging `scale`'s contents from pixel `from` to pixel `to`. `None` for
/// band scales.
pub fn panned(scale: &Scale, from: f64, to: f64) -> Option<[f64; 2]> {
    let (lo, hi) = scale.domain();
    let (a, b) = (scale.invert(from)?, scale.invert(to)?);
    let out = match scale {
        Scale::Band(_) => return None,
        Scale::Log(_) => {
            if a <= 0.0 || b <= 0.0 {
                return None;
            }
            let k = a / b;
            [lo * k, hi * k]
        }
        _ => [lo + (a - b), hi + (a - b)],
    };
    (out[0].is_finite() && out[1].is_finite() && out[1] > out[0]).then_some(out)
}

/// The chart with each column in `domains` drawn over that fixed domain (no nice rounding),
/// wherever a positional channel (`x`, `y`, `columns`) names the column. The chart is changed
/// through its serialized form, so every kind with those keys takes part.
pub fn with_domains(chart: &Chart, domains: &BTreeMap<String, [f64; 2]>) -> Chart {
    if domains.is_empty() {
        return chart.clone();
    }
    let Ok(mut value) = serde_json::to_value(chart) else { return chart.clone() };
    for key in ["x", "y", "columns"] {
        if let Some(v) = value.get_mut(key) {
            set_domains(v, domains);
        }
    }
    serde_json::from_value(value).unwrap_or_else(|_| chart.clone())
}

/// Set the domain of every channel in `value` (a name, a table or a list of those) whose column
/// is in `domains`.
fn set_domains(value: &mut Value, domains: &BTreeMap<String, [f64; 2]>) {
    match value {
        Value::String(field) => {
            if let Some(d) = domains.get(field.as_str()) {
                *value = serde_json::json!({ "field": field.clone(), "domain": d, "nice": false });
            }
        }
        Value::Object(map) => {
            let field = map.get("field").and_then(Value::as_str).map(str::to_string);
            if let Some(d) = field.and_then(|f| domains.get(&f)) {
                map.insert("domain".into(), serde_json::json!(d));
                map.insert("nice".into(), Value::Bool(false));
                map.insert("zero".into(), Value::Bool(false));
            }
        }
        Value::Array(items) => items.iter_mut().for_each(|v| set_domains(v, domains)),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::ColumnValues;
    use crate::guide::scale::{LinearScale, LogScale};
    use crate::mark::geometry::PlotScale;
    use crate::scene::Rect;
    use crate::spec::{Channel, ChartKind};

    fn lin(d: (f64, f64), r: (f64, f64)) -> Scale {
        Scale::Linear(LinearScale::new(d, r, false, 0).unwrap())
    }

    #[test]
    fn zoom_keeps_the_value_under_the_pointer_and_pan_moves_by_the_drag() {
        let s = lin((0.0, 10.0), (0.0, 100.0));
        assert_eq!(zoomed(&s, 20.0, 0.5), Some([1.0, 6.0]));
        assert_eq!(zoomed(&s, 20.0, 0.0), None);
        // Dragging the contents 10 px right shows values 1 unit lower.
        assert_eq!(panned(&s, 50.0, 60.0), Some([-1.0, 9.0]));
        let log = Scale::Log(LogScale::new((1.0, 1000.0), (0.0, 300.0), false).unwrap());
        let z = zoomed(&log, 100.0, 0.5).unwrap();
        assert!((z[0] - 10f64.powf(0.5)).abs() < 1e-9 && (z[1] - 10f64.powf(2.0)).abs() < 1e-9, "{z:?}");
        let p = panned(&log, 100.0, 200.0).unwrap();
        assert!((p[0] - 0.1).abs() < 1e-12 && (p[1] - 100.0).abs() < 1e-9, "{p:?}");
    }

    #[test]
    fn hit_tests_find_the_nearest_row() {
        let t = Table::from_columns([
            ("a", ColumnValues::Number(vec![1.0, 2.0, 3.0, f64::NAN])),
            ("b", ColumnValues::Number(vec![1.0, 2.0, 3.0, 2.0])),
        ]);
        let plot = Plot {
            rect: Rect::new(0.0, 0.0, 100.0, 100.0),
            x: Some(PlotScale { field: "a".into(), scale: lin((0.0, 4.0), (0.0, 100.0)) }),
            y: Some(PlotScale { field: "b".into(), scale: lin((0.0, 4.0), (100.0, 0.0)) }),
        };
        assert_eq!(nearest_point(&plot, &t, Point::new(52.0, 48.0), 6.0), Some(1));
        assert_eq!(nearest_point(&plot, &t, Point::new(10.0, 10.0), 6.0), None);
        let axes: Vec<ParallelAxis> = ["a", "b"]
            .iter()
            .enumerate()
            .map(|(i, f)| ParallelAxis {
                field: f.to_string(),
                x: 100.0 * i as f64,
                top: 0.0,
                bottom: 100.0,
                scale: lin((0.0, 4.0), (100.0, 0.0)),
            })
            .collect();
        // Row 2 runs at y = 25 across; row 1 at y = 50.
        assert_eq!(nearest_line(&axes, &t, Point::new(40.0, 27.0), 5.0), Some(2));
        assert_eq!(nearest_line(&axes, &t, Point::new(140.0, 27.0), 5.0), None);
        let g = Geometry { plots: vec![plot], axes, ..Geometry::default() };
        assert_eq!(plot_at(&g, Point::new(50.0, 50.0)), Some(0));
        assert_eq!(axis_at(&g, Point::new(95.0, 50.0)), Some(1));
        assert_eq!(axis_at(&g, Point::new(50.0, 50.0)), None);
        assert_eq!(describe(&t, 1, &["a", "b", "a"]), "row 1 · a = 2 · b = 2");
    }

    #[test]
    fn domains_are_set_on_every_channel_naming_the_column() {
        let chart: Chart = serde_json::from_value(serde_json::json!({
            "name": "c", "data": "d", "kind": "scatter",
            "x": "a", "y": { "field": "b", "title": "B" }
        }))
        .unwrap();
        let domains = [("a".to_string(), [1.0, 2.0]), ("b".to_string(), [3.0, 4.0])].into();
        let zoomed = with_domains(&chart, &domains);
        let ChartKind::Scatter(o) = &zoomed.kind else { panic!("scatter") };
        let (Channel::Detailed(x), Channel::Detailed(y)) = (&o.x, &o.y) else { panic!("detailed channels") };
        assert_eq!((x.field.as_str(), x.domain, x.nice), ("a", Some([1.0, 2.0]), Some(false)));
        assert_eq!((y.title.as_deref(), y.domain), (Some("B"), Some([3.0, 4.0])));
    }
}
