//! `daisy`: a daisy chart. The columns sit on arcs around a circle, clockwise from the top, each
//! arc with its own value scale; every row is a closed curve that visits its value on each arc
//! and bends towards the centre between neighbouring arcs.

use std::f64::consts::TAU;

use crate::data::{Column, Table};
use crate::guide::Theme;
use crate::guide::layout::{LayoutError, MIN_PLOT_SIDE, PositionAxis, build_scale};
use crate::guide::legend::{Legend, Symbol, truncate_to_width};
use crate::guide::scale::Scale;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode::{self, Positioner};
use crate::mark::frame::{self, polar, polylines};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, highlight, with_default_size};
use crate::scene::{Anchor, Baseline, Item, PathCmd, Point, Role, Shape, Stroke, Style, Text};
use crate::selection::Highlight;
use crate::spec::{Channel, ChannelOptions, Chart, ColorChannel};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "daisy"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct DaisyOptions {
    /// The columns, 3 to 24, placed clockwise from the top, each on its own arc and scale.
    #[schemars(length(min = 3, max = 24), example = crate::spec::types::example_columns())]
    pub columns: Vec<Channel>,
    /// Colour curves by a column (categories get a legend, numbers a colour bar).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Curve opacity in 0..=1 (default: from the row count).
    #[serde(default)]
    #[schemars(range(min = 0, max = 1))]
    pub opacity: Option<f64>,
    /// Curve width in pixels, at most 100 (default: from the row count).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100))]
    pub stroke_width: Option<f64>,
    /// Curve colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [800.0, 600.0];
/// Share of each column's sector left empty between arcs.
const ARC_GAP: f64 = 0.22;
/// Most categories a text column's arc names all of (shortening labels rather than dropping some).
const NAMED_CATEGORIES: usize = 12;
/// Straight pieces per curve between two arcs.
const CURVE_STEPS: usize = 10;
/// How far towards the centre the curves between arcs bend (0: straight chords).
const BEND: f64 = 0.55;

/// The angular extent `(start, end)` of column `i`'s arc out of `k`, clockwise from the top.
pub fn arc_span(i: usize, k: usize) -> (f64, f64) {
    let sector = TAU / k as f64;
    let start = sector * i as f64 + sector * ARC_GAP / 2.0;
    (start, start + sector * (1.0 - ARC_GAP))
}

/// Draw a daisy chart.
pub fn draw(
    chart: &Chart,
    options: &DaisyOptions,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let columns = encode::columns(chart, "columns", &options.columns, table)?;
    let fields: Vec<(&str, &Column)> = columns.iter().map(|(o, c)| (o.field.as_str(), *c)).collect();
    let (rows, warnings) = encode::drawn_rows(chart, table, fields, options.color.as_ref())?;
    let n = rows.len();
    let (colors, color_legend) = encode::color_encoding(
        chart,
        options.color.as_ref(),
        options.mark_color.as_deref(),
        table,
        &rows,
        Symbol::Line,
    )?;
    let mut axes = encode::column_axes(&columns, &rows)?;
    if let Some(panel) = &chart.panel {
        panel.share_columns(&columns.iter().map(|(o, _)| o.field.as_str()).collect::<Vec<_>>(), &mut axes);
    }
    let mut legends: Vec<Legend> = color_legend.into_iter().collect();
    legends.extend(highlight.map(|h| highlight::legend(h, &rows, Symbol::Line)));
    let canvas = frame::PanelCanvas::new(chart, legends);
    let theme = &canvas.theme;
    let wheel = Wheel::lay_out(&canvas, &axes).map_err(|e| MarkError::layout(e))?;

    let k = columns.len();
    let positioners: Vec<Positioner> =
        wheel.scales.iter().zip(&columns).map(|(s, (_, c))| Positioner::new(s, c)).collect();
    let opacity = options.opacity.unwrap_or_else(|| crate::mark::overplot::line_opacity(n));
    let width = options.stroke_width.unwrap_or(if n > 1_000 { 1.0 } else { 1.3 });
    let marks = highlight::layers(&rows, highlight, |rows, context| {
        let mut vertices = Vec::with_capacity(rows.len() * (k * CURVE_STEPS + 1));
        let mut points: Vec<Point> = Vec::with_capacity(k);
        for &r in rows {
            points.clear();
            points.extend(positioners.iter().map(|p| polar(wheel.center, wheel.radius, wheel.angle(p.at(r)))));
            for i in 0..k {
                let (a, b) = (points[i], points[(i + 1) % k]);
                let mid = Point::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
                let c = Point::new(
                    wheel.center.x + (mid.x - wheel.center.x) * (1.0 - BEND),
                    wheel.center.y + (mid.y - wheel.center.y) * (1.0 - BEND),
                );
                for s in 0..CURVE_STEPS {
                    let t = s as f64 / CURVE_STEPS as f64;
                    let (u, v, w) = ((1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t);
                    vertices.push(Point::new(u * a.x + v * c.x + w * b.x, u * a.y + v * c.y + w * b.y));
                }
            }
            vertices.push(points[0]);
        }
        let color = |r| highlight::row_color(&colors, r, context, opacity);
        polylines(vertices, k * CURVE_STEPS + 1, rows, color, width)
    });

    let mut items = vec![canvas.background()];
    items.push(Item::group(Role::DataMark, marks, None).labelled(chart.name.clone()));
    items.extend(wheel.arcs(&axes, theme));
    if let Some(h) = highlight {
        items.extend(wheel.brushes(h, &columns));
    }
    let derived = derived_vertices(&rows, &columns, &positioners, &wheel, highlight);
    Ok(ChartOutput {
        scene: canvas.scene(chart, items, None),
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// The circle and the arc scales. Each scale maps a value to a length along its arc (0 at the
/// arc's start); [`Wheel::angle`] turns that into an angle.
struct Wheel {
    center: Point,
    radius: f64,
    scales: Vec<Scale>,
}

impl Wheel {
    /// The largest circle that leaves room for tick labels and column names in the canvas' room.
    fn lay_out(canvas: &frame::PanelCanvas, axes: &[PositionAxis]) -> Result<Wheel, LayoutError> {
        let theme = &canvas.theme;
        let m = theme.margin;
        let area_w = canvas.width - m - m - canvas.legend_room();
        // Room outside the circle for tick labels and column names.
        let outer = theme.font_size * 3.2 + theme.label_size * 1.6;
        let label_w = axes.iter().map(|a| crate::text::measure(&a.title, theme.label_size).width).fold(0.0, f64::max);
        let side = theme.font_size * 1.5 + (0.75 * label_w).min(theme.font_size * 8.0);
        let radius = (area_w / 2.0 - side).min(canvas.room / 2.0 - outer);
        if radius < MIN_PLOT_SIDE {
            return Err(LayoutError::TooSmall { plot_width: area_w.max(0.0), plot_height: canvas.room.max(0.0) });
        }
        let center = Point::new(m + area_w / 2.0, canvas.top() + canvas.room / 2.0);
        let k = axes.len();
        let mut scales = Vec::with_capacity(k);
        for (i, axis) in axes.iter().enumerate() {
            let (a0, a1) = arc_span(i, k);
            let length = radius * (a1 - a0);
            let target = ((length / (theme.font_size * 4.0)).round() as usize).clamp(2, 6);
            let range = (a0 * radius, a1 * radius);
            scales.push(build_scale(axis, range, target).map_err(|error| LayoutError::Scale { axis: "x", error })?);
        }
        Ok(Wheel { center, radius, scales })
    }

    /// The angle of a position from an arc's scale (which maps values to arc length from 12
    /// o'clock, so that the arc's start is built in).
    fn angle(&self, along: f64) -> f64 {
        along / self.radius
    }

    /// Arcs with ticks, tick labels and column names.
    fn arcs(&self, axes: &[PositionAxis], theme: &Theme) -> Vec<Item> {
        let mut items = Vec::new();
        let k = axes.len();
        for (i, (scale, axis)) in self.scales.iter().zip(axes).enumerate() {
            let (a0, a1) = arc_span(i, k);
            items.push(
                arc(self.center, self.radius, a0, a1, Stroke::solid(theme.axis, 1.5)).labelled(axis.title.clone()),
            );
            let labels = self.tick_labels(scale, theme);
            let mut ticks = Vec::new();
            for (angle, _) in &labels {
                ticks.push(PathCmd::MoveTo(polar(self.center, self.radius, *angle)));
                ticks.push(PathCmd::LineTo(polar(self.center, self.radius + theme.tick_length, *angle)));
            }
            // Clear of the tick labels: their width counts sideways, their height up and down.
            let label_w =
                labels.iter().map(|(_, t)| crate::text::measure(&t.content, t.size).width).fold(0.0, f64::max);
            items.extend(labels.into_iter().map(|(_, text)| Item::text(Role::TickLabel, text)));
            items.push(Item::new(Role::Axis, Shape::Path(ticks), Style::stroke(theme.axis, 1.0)));
            let mid = (a0 + a1) / 2.0;
            let clearance = mid.sin().abs() * label_w + mid.cos().abs() * theme.font_size;
            let at = polar(self.center, self.radius + theme.tick_length + theme.font_size * 0.9 + clearance, mid);
            let (anchor, baseline) = outward_anchor(mid);
            let title = truncate_to_width(&axis.title, theme.font_size * 12.0, theme.label_size);
            items.push(Item::text(
                Role::AxisTitle,
                Text { at, content: title, size: theme.label_size, anchor, baseline, angle: 0.0, color: theme.text },
            ));
        }
        items
    }

    /// The tick labels of one arc as drawn, each with its angle. Whether neighbours collide is
    /// judged on the labels' boxes where they sit around the circle (labels stack on the sides
    /// and stand side by side at the top and bottom): all ticks when none collide, else every
    /// k-th. An arc of a text column with up to [`NAMED_CATEGORIES`] categories names every
    /// category, shortening the labels that would collide instead of leaving some out.
    fn tick_labels(&self, scale: &Scale, theme: &Theme) -> Vec<(f64, Text)> {
        let size = theme.font_size * 0.9;
        let gap = theme.font_size * 0.3;
        let all: Vec<(f64, Text)> = scale
            .ticks()
            .into_iter()
            .map(|tick| {
                let angle = self.angle(tick.position);
                let at = polar(self.center, self.radius + theme.tick_length + theme.font_size * 0.3, angle);
                let (anchor, baseline) = outward_anchor(angle);
                let text =
                    Text { at, content: tick.label, size, anchor, baseline, angle: 0.0, color: theme.muted_text };
                (angle, text)
            })
            .collect();
        let apart = |a: &Text, b: &Text| !padded(crate::text::bounds(a), gap).intersects(&crate::text::bounds(b));
        if matches!(scale, Scale::Band(_)) && all.len() <= NAMED_CATEGORIES {
            return shorten_until_apart(all, &apart);
        }
        for step in 1..=all.len().max(1) {
            let kept: Vec<&(f64, Text)> = all.iter().step_by(step).collect();
            if kept.windows(2).all(|pair| apart(&pair[0].1, &pair[1].1)) {
                return kept.into_iter().cloned().collect();
            }
        }
        all.into_iter().take(1).collect()
    }

    /// Brushed ranges as wide translucent bands over their arcs.
    fn brushes(&self, h: &Highlight, columns: &[(ChannelOptions, &Column)]) -> Vec<Item> {
        let k = columns.len();
        let mut items = Vec::new();
        for (i, ((o, _), scale)) in columns.iter().zip(&self.scales).enumerate() {
            let (a0, a1) = arc_span(i, k);
            let bounds = (a0 * self.radius, a1 * self.radius);
            if let Some((lo, hi)) =
                h.range_on(&o.field).and_then(|r| highlight::pixel_span(r, |v| scale.map(v), bounds))
            {
                let stroke = Stroke::solid(highlight::BRUSH.with_opacity(0.35), 9.0);
                items.push(
                    arc(self.center, self.radius, self.angle(lo), self.angle(hi), stroke).labelled("brushed range"),
                );
            }
        }
        items
    }
}

/// A rectangle grown by `by` on every side.
fn padded(r: crate::scene::Rect, by: f64) -> crate::scene::Rect {
    crate::scene::Rect::new(r.x - by, r.y - by, r.w + 2.0 * by, r.h + 2.0 * by)
}

/// Labels with the longer of each colliding neighbour pair shortened (with an ellipsis) until no
/// neighbours collide or the labels cannot get shorter.
fn shorten_until_apart(mut labels: Vec<(f64, Text)>, apart: &dyn Fn(&Text, &Text) -> bool) -> Vec<(f64, Text)> {
    for _ in 0..64 {
        let mut shortened = false;
        for i in 1..labels.len() {
            let (a, b) = (&labels[i - 1].1, &labels[i].1);
            if apart(a, b) {
                continue;
            }
            let width = |t: &Text| crate::text::measure(&t.content, t.size).width;
            let longer = if width(a) >= width(b) { i - 1 } else { i };
            let text = &mut labels[longer].1;
            let before = text.content.clone();
            text.content = truncate_to_width(&text.content, width(text) * 0.8, text.size);
            shortened |= text.content != before && text.content.chars().count() > 1;
        }
        if !shortened {
            break;
        }
    }
    labels
}

/// Text anchoring for a label placed outside the circle at `angle`.
fn outward_anchor(angle: f64) -> (Anchor, Baseline) {
    let (s, c) = (angle.sin(), angle.cos());
    let anchor = if s > 0.25 {
        Anchor::Start
    } else if s < -0.25 {
        Anchor::End
    } else {
        Anchor::Middle
    };
    let baseline = if c > 0.25 {
        Baseline::Bottom
    } else if c < -0.25 {
        Baseline::Top
    } else {
        Baseline::Middle
    };
    (anchor, baseline)
}

/// A circular arc from `a0` to `a1` (clockwise from the top), as a fine polyline.
fn arc(center: Point, radius: f64, a0: f64, a1: f64, stroke: Stroke) -> Item {
    let steps = (((a1 - a0).abs() * radius / 3.0).ceil() as usize).clamp(2, 720);
    let cmds = (0..=steps)
        .map(|s| {
            let p = polar(center, radius, a0 + (a1 - a0) * s as f64 / steps as f64);
            if s == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) }
        })
        .collect();
    Item::new(Role::Axis, Shape::Path(cmds), Style { fill: None, stroke: Some(stroke) })
}

/// One output row per (row, column): the value, its angle in degrees clockwise from the top, and
/// its point on the unit circle (x right, y up).
fn derived_vertices(
    rows: &[u32],
    columns: &[(ChannelOptions, &Column)],
    positioners: &[Positioner],
    wheel: &Wheel,
    highlight: Option<&Highlight>,
) -> Derived {
    let mut source_rows = Vec::new();
    let (mut names, mut values, mut angles, mut xs, mut ys) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for &r in rows {
        for ((o, col), p) in columns.iter().zip(positioners) {
            let angle = wheel.angle(p.at(r));
            source_rows.push(r);
            names.push(o.field.clone());
            values.push(encode::cell_text(col, r));
            angles.push(angle.to_degrees());
            xs.push(angle.sin());
            ys.push(angle.cos());
        }
    }
    let mut d = Derived::over(source_rows);
    d.push("row", DerivedColumn::RowIndex);
    d.push("column", DerivedColumn::Text(names));
    d.push("value", DerivedColumn::Text(values));
    d.push("angle_deg", DerivedColumn::Number(angles));
    d.push("x", DerivedColumn::Number(xs));
    d.push("y", DerivedColumn::Number(ys));
    if let Some(h) = highlight {
        d.push("selected", DerivedColumn::Selected(h.selected.clone()));
    }
    d
}

/// `kind = "daisy"`.
pub static KIND: KindInfo = KindInfo::new("daisy", &["columns", "color"])
    .sized(DEFAULT_SIZE)
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Canvas);

impl Technique for DaisyOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.highlight)
    }

    crate::mark::registry::color_key!();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arcs_run_clockwise_from_the_top_without_overlap() {
        let c = Point::new(0.0, 0.0);
        let top = polar(c, 1.0, 0.0);
        assert!((top.x).abs() < 1e-12 && (top.y + 1.0).abs() < 1e-12, "angle 0 is straight up");
        let right = polar(c, 1.0, TAU / 4.0);
        assert!((right.x - 1.0).abs() < 1e-12 && right.y.abs() < 1e-12, "a quarter turn is to the right");
        for k in 3..10 {
            for i in 0..k {
                let (a0, a1) = arc_span(i, k);
                let (b0, _) = arc_span((i + 1) % k, k);
                assert!(a0 < a1);
                let next = if i + 1 == k { b0 + TAU } else { b0 };
                assert!(a1 < next, "arc {i} of {k} ends before the next starts");
            }
        }
    }
}
