//! `parallel`: parallel coordinates. Each column is a vertical axis with its own nice-ticked
//! scale (or one shared scale); each row is a polyline through its values on every axis.

use crate::data::{Column, Table};
use crate::guide::Theme;
use crate::guide::axis::{self, Side};
use crate::guide::layout::{Domain, LayoutError, MIN_PLOT_SIDE, PositionAxis, build_scale};
use crate::guide::legend::{Legend, Symbol, truncate_to_width};
use crate::guide::scale::Scale;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode::{self, Positioner};
use crate::mark::frame::{self, polylines};
use crate::mark::geometry::{Geometry, ParallelAxis};
use crate::mark::overplot::line_opacity;
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, highlight, with_default_size};
use crate::scene::{Anchor, Baseline, Item, PathCmd, Point, Rect, Role, Shape, Style, Text};
use crate::selection::Highlight;
use crate::spec::{Channel, ChannelOptions, Chart, ColorChannel};
use crate::text::measure;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "parallel"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ParallelOptions {
    /// The axes' columns, 2 to 64: numeric columns get nice-ticked scales, text columns one
    /// position per category.
    #[schemars(length(min = 2, max = 64), example = crate::spec::types::example_columns())]
    pub columns: Vec<Channel>,
    /// Colour lines by a column (categories get a legend, numbers a colour bar).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// `given` (default: as listed) or `correlation` (neighbouring axes strongly correlated,
    /// starting from the first column).
    #[serde(default)]
    pub order: Option<AxisOrder>,
    /// Columns whose axes run top to bottom (high values at the bottom).
    #[serde(default)]
    pub invert: Option<Vec<String>>,
    /// One scale shared by every numeric axis (default false: each axis its own).
    #[serde(default)]
    pub shared_scale: Option<bool>,
    /// Line opacity in 0..=1 (default: from the row count).
    #[serde(default)]
    #[schemars(range(min = 0, max = 1))]
    pub opacity: Option<f64>,
    /// Line width in pixels, at most 100 (default: from the row count).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100))]
    pub stroke_width: Option<f64>,
    /// Line colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// How the axes of parallel coordinates are ordered.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum AxisOrder {
    /// As listed in `columns`.
    Given,
    /// Greedy: each next axis is the remaining column most correlated (|Pearson r|) with the
    /// previous one.
    Correlation,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [820.0, 440.0];

/// Draw parallel coordinates.
/// Also returns the interactive geometry (for brushing and zooming).
pub fn draw(
    chart: &Chart,
    options: &ParallelOptions,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let mut columns = encode::columns(chart, "columns", &options.columns, table)?;
    let inverted = inverted_columns(options, &columns)?;
    let fields: Vec<(&str, &Column)> = columns.iter().map(|(o, c)| (o.field.as_str(), *c)).collect();
    let (rows, warnings) = encode::drawn_rows(chart, table, fields, options.color.as_ref())?;
    if options.order == Some(AxisOrder::Correlation) {
        let values: Vec<Option<Vec<f64>>> =
            columns.iter().map(|(_, c)| c.numbers().map(|_| encode::values_at(c, &rows))).collect();
        let order = correlation_order(&values);
        columns = order.into_iter().map(|i| columns[i].clone()).collect();
    }
    let inverted: Vec<bool> = columns.iter().map(|(o, _)| inverted.contains(&o.field)).collect();
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
    if options.shared_scale == Some(true) {
        share_domain(&mut axes);
    }
    let mut legends: Vec<Legend> = color_legend.into_iter().collect();
    legends.extend(highlight.map(|h| highlight::legend(h, &rows, Symbol::Line)));
    let canvas = frame::PanelCanvas::new(chart, legends);
    let layout = AxesLayout::lay_out(&canvas, &axes, &inverted).map_err(|e| MarkError::layout(e))?;

    let opacity = options.opacity.unwrap_or_else(|| line_opacity(n));
    let width = options.stroke_width.unwrap_or(if n > 1_000 { 1.0 } else { 1.4 });
    let positioners: Vec<Positioner> =
        layout.scales.iter().zip(&columns).map(|(s, (_, c))| Positioner::new(s, c)).collect();
    let marks = highlight::layers(&rows, highlight, |rows, context| {
        let vertices: Vec<Point> = rows
            .iter()
            .flat_map(|&r| layout.xs.iter().zip(&positioners).map(move |(&x, p)| Point::new(x, p.at(r))))
            .collect();
        polylines(vertices, columns.len(), rows, |r| highlight::row_color(&colors, r, context, opacity), width)
    });

    let mut items = vec![canvas.background()];
    items.push(Item::group(Role::DataMark, marks, None).labelled(chart.name.clone()));
    if let Some(h) = highlight {
        items.extend(brushes(h, &layout, &columns));
    }
    items.extend(layout.axes(&axes, &inverted, &canvas.theme));
    let derived = derived_vertices(&rows, &columns, &layout, highlight);
    let axes = columns
        .iter()
        .zip(layout.scales.iter().zip(&layout.xs))
        .map(|((o, _), (scale, &x))| ParallelAxis {
            field: o.field.clone(),
            x,
            top: layout.top,
            bottom: layout.top + layout.plot_h,
            scale: scale.clone(),
        })
        .collect();
    let geometry = Geometry { axes, ..Geometry::default() };
    Ok(ChartOutput {
        scene: canvas.scene(chart, items, None),
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry,
    })
}

/// The columns named in `invert`, each checked against `columns`.
fn inverted_columns(
    options: &ParallelOptions,
    columns: &[(ChannelOptions, &Column)],
) -> Result<Vec<String>, MarkError> {
    let fields: Vec<&str> = columns.iter().map(|(o, _)| o.field.as_str()).collect();
    let mut out = Vec::new();
    for name in options.invert.iter().flatten() {
        if !fields.contains(&name.as_str()) {
            let hint = crate::spec::suggest::hint(name, &fields, "axes", false);
            return Err(MarkError::at(
                &["invert"],
                format!("`invert` names `{name}`, which is not one of the axes"),
                hint,
            ));
        }
        out.push(name.clone());
    }
    Ok(out)
}

/// Give every numeric axis the union of their domains.
fn share_domain(axes: &mut [PositionAxis]) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for a in axes.iter() {
        if let Domain::Continuous(l, h) = a.domain {
            lo = lo.min(l);
            hi = hi.max(h);
        }
    }
    for a in axes.iter_mut() {
        if let Domain::Continuous(..) = a.domain {
            a.domain = Domain::Continuous(lo, hi);
        }
    }
}

/// Pearson correlation of two equally long samples (0 when either has no spread).
pub fn pearson(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len()) as f64;
    if n < 2.0 {
        return 0.0;
    }
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    if saa <= 0.0 || sbb <= 0.0 { 0.0 } else { sab / (saa * sbb).sqrt() }
}

/// An axis order that puts strongly correlated columns side by side: starting from the first
/// column, each next axis is the remaining numeric column with the largest |r| to the previous
/// one (ties keep the given order); text columns (`None`) follow in their given order.
pub fn correlation_order(values: &[Option<Vec<f64>>]) -> Vec<usize> {
    let numeric: Vec<usize> = (0..values.len()).filter(|&i| values[i].is_some()).collect();
    let mut order = Vec::with_capacity(values.len());
    let mut left: Vec<usize> = numeric.clone();
    if let Some(&first) = numeric.first() {
        order.push(first);
        left.retain(|&i| i != first);
    }
    while !left.is_empty() {
        let prev = *order.last().expect("order starts non-empty");
        let r = |i: usize| match (&values[prev], &values[i]) {
            (Some(a), Some(b)) => pearson(a, b).abs(),
            _ => 0.0,
        };
        let (pos, _) = left.iter().enumerate().fold((0, -1.0), |best, (pos, &i)| {
            let ri = r(i);
            if ri > best.1 { (pos, ri) } else { best }
        });
        order.push(left.remove(pos));
    }
    order.extend((0..values.len()).filter(|&i| values[i].is_none()));
    order
}

/// Where the axes go and their scales.
struct AxesLayout {
    /// Top of the axes.
    top: f64,
    plot_h: f64,
    /// x position of each axis.
    xs: Vec<f64>,
    scales: Vec<Scale>,
    /// Room between neighbouring axes.
    spacing: f64,
}

impl AxesLayout {
    /// Place one axis per entry of `axes` in the canvas' room, upward unless `inverted`.
    fn lay_out(
        canvas: &frame::PanelCanvas,
        axes: &[PositionAxis],
        inverted: &[bool],
    ) -> Result<AxesLayout, LayoutError> {
        let theme = &canvas.theme;
        let m = theme.margin;
        let k = axes.len();
        // Column titles above the axes, half a tick label below them.
        let top = canvas.top() + theme.label_size * 1.8;
        let plot_h = (canvas.height - top - m - canvas.caption_h - theme.font_size).floor();
        let target = ((plot_h / (theme.font_size * 3.0)).round() as usize).clamp(2, 10);
        let scales = axes
            .iter()
            .zip(inverted)
            .map(|(axis, &down)| {
                let range = if down { (top, top + plot_h) } else { (top + plot_h, top) };
                build_scale(axis, range, target).map_err(|error| LayoutError::Scale { axis: "y", error })
            })
            .collect::<Result<Vec<Scale>, LayoutError>>()?;
        let label_w = |s: &Scale| {
            axis::visible_ticks(s, Side::Left, theme)
                .iter()
                .map(|t| measure(&t.label, theme.font_size).width)
                .fold(0.0, f64::max)
        };
        let title_w = |a: &PositionAxis| measure(&a.title, theme.label_size).width;
        let left = m + (label_w(&scales[0]) + theme.tick_length + theme.font_size * 0.35).max(title_w(&axes[0]) / 2.0);
        let right = m + canvas.legend_room() + title_w(&axes[k - 1]).min(theme.font_size * 8.0) / 2.0;
        let plot_w = canvas.width - left - right;
        if plot_w < MIN_PLOT_SIDE * (k - 1) as f64 || plot_h < MIN_PLOT_SIDE {
            return Err(LayoutError::TooSmall { plot_width: plot_w.max(0.0), plot_height: plot_h.max(0.0) });
        }
        let spacing = plot_w / (k - 1) as f64;
        let xs = (0..k).map(|i| (left + spacing * i as f64).round()).collect();
        Ok(AxesLayout { top, plot_h, xs, scales, spacing })
    }

    /// Every axis with its ticks (labels on a light halo, as lines run beneath them), and the
    /// column titles above them; inverted axes get a small downward arrow after the title.
    fn axes(&self, axes: &[PositionAxis], inverted: &[bool], theme: &Theme) -> Vec<Item> {
        let mut items = Vec::new();
        for (i, (scale, &x)) in self.scales.iter().zip(&self.xs).enumerate() {
            let plot = Rect::new(x + 1.0, self.top, 0.0, self.plot_h);
            for item in axis::draw(scale, Side::Left, plot, None, theme) {
                if let Shape::Text(text) = &item.shape {
                    let b = crate::text::bounds(text);
                    let halo = Rect::new(b.x - 2.0, b.y - 1.0, b.w + 4.0, b.h + 2.0);
                    items.push(Item::new(
                        Role::Annotation,
                        Shape::Rect(halo),
                        Style::fill(theme.background.with_opacity(0.8)),
                    ));
                }
                items.push(item);
            }
            let arrow = if inverted[i] { theme.font_size * 0.9 } else { 0.0 };
            let title = truncate_to_width(&axes[i].title, self.spacing - 4.0 - arrow, theme.label_size);
            let title_w = measure(&title, theme.label_size).width;
            let baseline_y = self.top - theme.font_size * 0.6;
            items.push(Item::text(
                Role::AxisTitle,
                Text {
                    at: Point::new(x - arrow / 2.0, baseline_y),
                    content: title,
                    size: theme.label_size,
                    anchor: Anchor::Middle,
                    baseline: Baseline::Bottom,
                    angle: 0.0,
                    color: theme.text,
                },
            ));
            if inverted[i] {
                items.push(down_arrow(Point::new(x - arrow / 2.0 + title_w / 2.0 + arrow * 0.55, baseline_y), theme));
            }
        }
        items
    }
}

/// A small downward arrow whose tip sits at `tip_base` (bottom centre), marking an axis whose
/// values grow downwards.
fn down_arrow(tip_base: Point, theme: &Theme) -> Item {
    let s = theme.font_size * 0.35;
    let (x, y) = (tip_base.x, tip_base.y - theme.font_size * 0.1);
    let cmds = vec![
        PathCmd::MoveTo(Point::new(x - s, y - 1.6 * s)),
        PathCmd::LineTo(Point::new(x + s, y - 1.6 * s)),
        PathCmd::LineTo(Point::new(x, y)),
        PathCmd::Close,
    ];
    Item::new(Role::Annotation, Shape::Path(cmds), Style::fill(theme.text)).labelled("inverted axis")
}

/// Brushed ranges and categories as bars along their axes.
fn brushes(h: &Highlight, layout: &AxesLayout, columns: &[(ChannelOptions, &Column)]) -> Vec<Item> {
    let mut items = Vec::new();
    let half = 5.0;
    let bounds = (layout.top, layout.top + layout.plot_h);
    for ((o, col), (scale, &x)) in columns.iter().zip(layout.scales.iter().zip(&layout.xs)) {
        if let Some(span) = h.range_on(&o.field).and_then(|r| highlight::pixel_span(r, |v| scale.map(v), bounds)) {
            items.push(highlight::brush_band(Rect::new(x - half, span.0, 2.0 * half, span.1 - span.0)));
        }
        if let (Some(set), Some(cats), Scale::Band(band)) = (h.categories_on(&o.field), col.categories(), scale) {
            let step = (band.range().1 - band.range().0).abs() / cats.levels.len().max(1) as f64;
            for tick in band.ticks().iter().filter(|t| set.contains(&t.label)) {
                let y = tick.position;
                let h2 = (step * 0.3).clamp(3.0, 12.0);
                items.push(highlight::brush_band(Rect::new(x - half, y - h2, 2.0 * half, 2.0 * h2)));
            }
        }
    }
    items
}

/// One output row per data row: each column's value, then each vertex' position along its
/// axis (`pos_<column>`, 0 at the bottom, 1 at the top), in axis order.
fn derived_vertices(
    rows: &[u32],
    columns: &[(ChannelOptions, &Column)],
    layout: &AxesLayout,
    highlight: Option<&Highlight>,
) -> Derived {
    let fields: Vec<&str> = columns.iter().map(|(o, _)| o.field.as_str()).collect();
    let mut d = Derived::of_rows(rows.to_vec(), &fields);
    let bottom = layout.top + layout.plot_h;
    for ((o, col), scale) in columns.iter().zip(&layout.scales) {
        let p = Positioner::new(scale, col);
        let positions = rows.iter().map(|&r| (bottom - p.at(r)) / layout.plot_h).collect();
        d.push(&format!("pos_{}", o.field), DerivedColumn::Number(positions));
    }
    if let Some(h) = highlight {
        d.push("selected", DerivedColumn::Selected(h.selected.clone()));
    }
    d
}

/// `kind = "parallel"`.
pub static KIND: KindInfo = KindInfo::new("parallel", &["columns", "color"])
    .sized(DEFAULT_SIZE)
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Canvas);

impl Technique for ParallelOptions {
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
    fn pearson_of_known_samples() {
        let a = [1.0, 2.0, 3.0, 4.0];
        assert!((pearson(&a, &[2.0, 4.0, 6.0, 8.0]) - 1.0).abs() < 1e-12);
        assert!((pearson(&a, &[8.0, 6.0, 4.0, 2.0]) + 1.0).abs() < 1e-12);
        // Hand-computed: x = 1..4, y = 1, 3, 2, 4 → r = 0.8.
        assert!((pearson(&a, &[1.0, 3.0, 2.0, 4.0]) - 0.8).abs() < 1e-12);
        assert_eq!(pearson(&a, &[5.0; 4]), 0.0);
    }

    #[test]
    fn correlation_order_chains_the_strongest_neighbours() {
        let x: Vec<f64> = (0..50).map(f64::from).collect();
        let noise: Vec<f64> = (0..50).map(|i| ((i * 37) % 11) as f64).collect();
        let anti: Vec<f64> = x.iter().map(|v| -2.0 * v).collect();
        let half: Vec<f64> = x.iter().zip(&noise).map(|(a, b)| a + 3.0 * b).collect();
        // Given: x, noise, text, half, anti. |r(x, anti)| = 1 comes next to x, then half, then noise.
        let values = vec![Some(x), Some(noise), None, Some(half), Some(anti)];
        assert_eq!(correlation_order(&values), vec![0, 4, 3, 1, 2]);
    }
}
