//! `daisy`: a daisy chart. The columns sit on arcs around a circle, clockwise from the top, each
//! arc with its own value scale; every row is a closed curve that visits its value on each arc
//! and bends towards the centre between neighbouring arcs.

use std::f64::consts::TAU;

use super::derived::{Derived, DerivedColumn};
use super::encode::{self, Positioner};
use super::frame::{self, polar, polylines};
use super::{ChartOutput, MarkError, highlight, with_default_size};
use crate::data::{Column, Table};
use crate::guide::Theme;
use crate::guide::axis::{self, Side};
use crate::guide::layout::{LayoutError, MIN_PLOT_SIDE, PositionAxis, build_scale};
use crate::guide::legend::{Legend, Symbol, truncate_to_width};
use crate::guide::scale::Scale;
use crate::scene::{Anchor, Baseline, Item, PathCmd, Point, Role, Shape, Stroke, Style, Text};
use crate::selection::Highlight;
use crate::spec::{ChannelOptions, Chart, DaisyOptions};

/// Canvas size when the spec gives none.
const DEFAULT_SIZE: [f64; 2] = [800.0, 600.0];
/// Share of each column's sector left empty between arcs.
const ARC_GAP: f64 = 0.22;
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
    index: usize,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart, DEFAULT_SIZE);
    let columns = encode::columns(chart, index, "columns", &options.columns, table)?;
    let fields: Vec<(&str, &Column)> = columns.iter().map(|(o, c)| (o.field.as_str(), *c)).collect();
    let (rows, warnings) = encode::drawn_rows(chart, index, table, fields, options.color.as_ref())?;
    let n = rows.len();
    let (colors, color_legend) = encode::color_encoding(
        chart,
        index,
        options.color.as_ref(),
        options.mark_color.as_deref(),
        table,
        &rows,
        Symbol::Line,
    )?;
    let axes = encode::column_axes(chart, index, &columns, &rows)?;
    let mut legends: Vec<Legend> = color_legend.into_iter().collect();
    legends.extend(highlight.map(|h| highlight::legend(h, &rows, Symbol::Line)));
    let canvas = frame::PanelCanvas::new(chart, legends);
    let theme = &canvas.theme;
    let wheel = Wheel::lay_out(&canvas, &axes).map_err(|e| MarkError::layout(index, &chart.name, e))?;

    let k = columns.len();
    let positioners: Vec<Positioner> =
        wheel.scales.iter().zip(&columns).map(|(s, (_, c))| Positioner::new(s, c)).collect();
    let opacity = options.opacity.unwrap_or_else(|| super::parallel::default_opacity(n));
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
    Ok(ChartOutput { scene: canvas.scene(chart, items, None), derived, warnings, geojson: None })
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
            let mut ticks = Vec::new();
            for tick in axis::visible_ticks(scale, Side::Bottom, theme) {
                let angle = self.angle(tick.position);
                ticks.push(PathCmd::MoveTo(polar(self.center, self.radius, angle)));
                ticks.push(PathCmd::LineTo(polar(self.center, self.radius + theme.tick_length, angle)));
                let at = polar(self.center, self.radius + theme.tick_length + theme.font_size * 0.3, angle);
                let (anchor, baseline) = outward_anchor(angle);
                items.push(Item::text(
                    Role::TickLabel,
                    Text {
                        at,
                        content: tick.label,
                        size: theme.font_size * 0.9,
                        anchor,
                        baseline,
                        angle: 0.0,
                        color: theme.muted_text,
                    },
                ));
            }
            items.push(Item::new(Role::Axis, Shape::Path(ticks), Style::stroke(theme.axis, 1.0)));
            let mid = (a0 + a1) / 2.0;
            // Clear of the tick labels: their width counts sideways, their height up and down.
            let label_w = axis::visible_ticks(scale, Side::Bottom, theme)
                .iter()
                .map(|t| crate::text::measure(&t.label, theme.font_size * 0.9).width)
                .fold(0.0, f64::max);
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
