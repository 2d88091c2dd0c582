//! `segments`: Keim's circle segments. A disk split into one wedge per column; the rows, sorted
//! by a column, fill every wedge pixel by pixel from the centre outward, each pixel coloured by
//! its row's value (the mean of its rows when there are more rows than pixels). Drawn as one
//! embedded raster, so a million rows cost no more in SVG than a thousand.

use std::sync::Arc;

use rayon::prelude::*;

use crate::data::{Column, Table};
use crate::enrich::segments::{SegmentLayout, mid_angle, paint};
use crate::guide::Theme;
use crate::guide::color::parse_color;
use crate::guide::format::format_value;
use crate::guide::layout::{LayoutError, MIN_PLOT_SIDE};
use crate::guide::legend::{Legend, Symbol, truncate_to_width};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode;
use crate::mark::frame;
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, highlight, with_default_size};
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Raster, Rect, Role, Shape, Style, Text};
use crate::selection::Highlight;
use crate::spec::{Channel, Chart};
use crate::text::measure;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "segments"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SegmentsOptions {
    /// The numeric columns, 2 to 64, one segment each, clockwise from the top.
    #[schemars(length(min = 2, max = 64), example = crate::spec::types::example_columns())]
    pub columns: Vec<Channel>,
    /// Column the rows are sorted by before they are laid out from the centre outward
    /// (default: the rows' order in the data).
    #[serde(default)]
    pub order_by: Option<String>,
    /// Sort `order_by` from high to low (default false).
    #[serde(default)]
    pub descending: Option<bool>,
    /// Continuous colour map (default `viridis`; append `_r` to reverse).
    #[serde(default)]
    pub scheme: Option<String>,
    /// `column` (default: each column scaled from its own minimum to maximum) or `shared` (one
    /// scale over all columns, for columns in the same unit).
    #[serde(default)]
    pub scale: Option<SegmentScale>,
    /// Colour of pixels whose rows are all missing (default light grey, `#d9d9d9`).
    #[serde(default)]
    pub nan_color: Option<String>,
}

/// How circle-segment colours are scaled.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SegmentScale {
    /// Each column from its own minimum (bottom of the colour bar) to its maximum (top).
    Column,
    /// One domain over all columns.
    Shared,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [760.0, 640.0];
/// Largest disk diameter in pixels.
const MAX_DIAMETER: u32 = 4096;
/// Default colour of pixels whose rows are all missing.
const NAN_COLOR: Color = Color::rgb(0xd9, 0xd9, 0xd9);

/// Draw circle segments.
pub fn draw(
    chart: &Chart,
    options: &SegmentsOptions,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let columns = encode::columns(chart, "columns", &options.columns, table)?;
    for (_, col) in &columns {
        encode::require_numeric("columns", col, "a circle segment", "colour pixels by numeric columns")?;
    }
    if table.rows == 0 {
        return Err(encode::no_rows(chart, table, None));
    }
    let order = row_order(chart, options, table)?;
    let mut warnings = Vec::new();

    // Per column: values in row order, scaled to [0, 1]; missing cells stay NaN (their pixels
    // take `nan_color`, the row keeps its place in the order).
    let raw: Vec<Vec<f64>> = columns.iter().map(|(_, c)| encode::values_at(c, &order)).collect();
    let extents: Vec<Option<(f64, f64)>> = raw.iter().map(|v| encode::finite_extent(v.iter().copied())).collect();
    let shared = extents
        .iter()
        .flatten()
        .fold(None, |acc: Option<(f64, f64)>, &(lo, hi)| Some(acc.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi)))));
    let scale_kind = options.scale.unwrap_or(SegmentScale::Column);
    let mut scaled = Vec::with_capacity(raw.len());
    for ((opts, _), (values, extent)) in columns.iter().zip(raw.iter().zip(&extents)) {
        let (lo, hi) = match scale_kind {
            SegmentScale::Column => extent.unwrap_or((0.0, 1.0)),
            SegmentScale::Shared => shared.unwrap_or((0.0, 1.0)),
        };
        if extent.is_none() {
            warnings.push(Warning::from(format!("column `{}` has no finite values", opts.field)));
        } else if hi <= lo {
            warnings.push(Warning::from(format!("column `{}` is constant; its segment is one colour", opts.field)));
        }
        let span = if hi > lo { hi - lo } else { 1.0 };
        scaled.push(
            values
                .iter()
                .map(|v| {
                    if hi > lo {
                        (v - lo) / span
                    } else if v.is_finite() {
                        0.5
                    } else {
                        f64::NAN
                    }
                })
                .collect::<Vec<f64>>(),
        );
    }

    let map = encode::continuous_map(&["scheme"], options.scheme.as_deref())?;
    let nan = match &options.nan_color {
        Some(s) => parse_color(s).ok_or_else(|| {
            MarkError::at(&["nan_color"], format!("`{s}` is not a colour"), "use a CSS colour name or `#rrggbb`")
        })?,
        None => NAN_COLOR,
    };
    let (legend, scale_note) = match (scale_kind, shared) {
        (SegmentScale::Shared, Some((lo, hi))) => {
            (Legend::ColorBar { title: "value".into(), map: map.clone(), domain: (lo, hi.max(lo + 1e-12)) }, None)
        }
        _ => (
            Legend::ColorBar { title: "% of column's range".into(), map: map.clone(), domain: (0.0, 100.0) },
            Some("each column coloured from its minimum (0 %) to its maximum (100 %)"),
        ),
    };
    let mut legends = vec![legend];
    legends.extend(highlight.map(|h| highlight::legend(h, &order, Symbol::Circle)));
    let selected: Option<Vec<bool>> = highlight.map(|h| order.iter().map(|&r| h.contains(r)).collect());

    // Without a caption of its own, the chart says how to read it there.
    let order_note = match &options.order_by {
        Some(c) => format!(
            "Rows ordered by {c}{}, from the centre outward",
            if options.descending == Some(true) { " (descending)" } else { "" }
        ),
        None => "Rows in data order, from the centre outward".to_string(),
    };
    let mut chart = chart.clone();
    chart.caption.get_or_insert(match scale_note {
        Some(s) => format!("{order_note}; {s}."),
        None => format!("{order_note}."),
    });
    let chart = &chart;
    let canvas = frame::PanelCanvas::new(chart, legends);
    let theme = &canvas.theme;
    let labels: Vec<(String, Option<String>)> = columns
        .iter()
        .zip(&extents)
        .map(|((opts, _), extent)| {
            let title =
                crate::guide::axis::title_with_unit(opts.title.as_deref().unwrap_or(&opts.field), opts.unit.as_deref());
            (title, extent.map(|(lo, hi)| format!("{} to {}", format_value(lo), format_value(hi))))
        })
        .collect();
    let widths: Vec<(f64, f64)> = labels
        .iter()
        .enumerate()
        .map(|(s, (title, range))| (mid_angle(s, labels.len()), Disk::label_width(title, range.as_deref(), theme)))
        .collect();
    let disk = Disk::lay_out(&canvas, &widths).map_err(|e| MarkError::layout(e))?;
    let layout = SegmentLayout::new(disk.diameter, columns.len());
    let value_refs: Vec<&[f64]> = scaled.iter().map(Vec::as_slice).collect();
    let to_rgba = |t: f64| {
        let c = map.at(t);
        [c.r, c.g, c.b, c.a]
    };
    let grey = |c: [u8; 4]| {
        let l = (0.299 * c[0] as f64 + 0.587 * c[1] as f64 + 0.114 * c[2] as f64) * 0.35 + 255.0 * 0.65;
        let l = l.round() as u8;
        [l, l, l, c[3]]
    };
    let rgba = paint(&layout, &value_refs, &to_rgba, [nan.r, nan.g, nan.b, nan.a], selected.as_deref(), &grey);
    let raster = Raster {
        dest: Rect::new(disk.center.x - disk.radius, disk.center.y - disk.radius, 2.0 * disk.radius, 2.0 * disk.radius),
        width: disk.diameter,
        height: disk.diameter,
        rgba: Arc::new(rgba),
        smooth: false,
    };

    let mut items = vec![canvas.background()];
    items.push(
        Item::new(Role::DataMark, Shape::Image(raster), Style::default())
            .with_rows(order.clone())
            .labelled(chart.name.clone()),
    );
    items.push(disk.borders(&layout));
    for (s, (title, range)) in labels.iter().enumerate() {
        items.extend(disk.label(layout.mid_angle(s), title, range.as_deref(), theme));
    }
    let ranks: Vec<f64> = (0..order.len()).map(|k| k as f64).collect();
    let mut derived = Derived::over(order);
    derived.push("row", DerivedColumn::RowIndex);
    derived.push("rank", DerivedColumn::Number(ranks));
    if let Some(c) = &options.order_by {
        derived.push(c, DerivedColumn::Source(c.clone()));
    }
    if let Some(h) = highlight {
        derived.push("selected", DerivedColumn::Selected(h.selected.clone()));
    }
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

/// Table rows in drawing order: sorted by `order_by` (stable; missing values last), or as
/// given.
fn row_order(chart: &Chart, options: &SegmentsOptions, table: &Table) -> Result<Vec<u32>, MarkError> {
    let mut order: Vec<u32> = (0..table.rows as u32).collect();
    let Some(field) = &options.order_by else { return Ok(order) };
    let col: &Column = encode::column(chart, "order_by", field, table)?;
    let descending = options.descending == Some(true);
    if let Some(values) = col.numbers() {
        // Sort (value, row) pairs: no lookups inside the comparisons, and a stable parallel
        // sort keeps ties in data order.
        let mut keyed: Vec<(f64, u32)> = order.iter().map(|&r| (values[r as usize], r)).collect();
        keyed.par_sort_by(|(x, _), (y, _)| match (x.is_nan(), y.is_nan()) {
            (true, true) => std::cmp::Ordering::Equal,
            (true, false) => std::cmp::Ordering::Greater,
            (false, true) => std::cmp::Ordering::Less,
            _ if descending => y.total_cmp(x),
            _ => x.total_cmp(y),
        });
        order = keyed.into_iter().map(|(_, r)| r).collect();
    } else if let Some(cats) = col.categories() {
        // Rank the categories once; rows then sort by an integer (missing text last).
        let mut levels: Vec<usize> = (0..cats.levels.len()).collect();
        levels.sort_by(|&a, &b| cats.levels[a].cmp(&cats.levels[b]));
        let mut rank = vec![0u32; levels.len()];
        for (position, &level) in levels.iter().enumerate() {
            rank[level] = if descending { (levels.len() - 1 - position) as u32 } else { position as u32 };
        }
        let key =
            |r: &u32| cats.codes.get(*r as usize).and_then(|&c| rank.get(c as usize)).copied().unwrap_or(u32::MAX);
        order.par_sort_by_key(key);
    }
    Ok(order)
}

/// Where the disk goes.
struct Disk {
    center: Point,
    radius: f64,
    diameter: u32,
}

impl Disk {
    /// The largest disk, centred in the canvas' room, whose column labels (`(angle, width)`
    /// each, placed as [`Disk::label`] places them) stay inside the room.
    fn lay_out(canvas: &frame::PanelCanvas, labels: &[(f64, f64)]) -> Result<Disk, LayoutError> {
        let theme = &canvas.theme;
        let m = theme.margin;
        let area_w = canvas.width - 2.0 * m - canvas.legend_room();
        let (half_w, half_h) = (area_w / 2.0, canvas.room / 2.0);
        let gap = theme.font_size * 0.8;
        // Title and range are two lines above or below the anchor, or one either side of it.
        let (two_lines, one_line) = (theme.label_size * 2.6, theme.label_size * 1.35);
        let mut radius = half_w.min(half_h);
        for &(angle, width) in labels {
            let (s, c) = (angle.sin(), angle.cos());
            let reach_x = if s.abs() > 0.3 { width } else { width / 2.0 };
            let reach_y = if c.abs() > 0.3 { two_lines } else { one_line };
            for (t, room) in [(s.abs(), half_w - reach_x), (c.abs(), half_h - reach_y)] {
                if t > 1e-9 {
                    radius = radius.min(room / t - gap);
                }
            }
        }
        let radius = radius.floor();
        if radius < MIN_PLOT_SIDE {
            return Err(LayoutError::TooSmall { plot_width: area_w.max(0.0), plot_height: canvas.room.max(0.0) });
        }
        let diameter = ((2.0 * radius) as u32).min(MAX_DIAMETER);
        let center = Point::new((m + area_w / 2.0).round(), (canvas.top() + canvas.room / 2.0).round());
        Ok(Disk { center, radius, diameter })
    }

    /// The width [`Disk::label`] gives a column's title and value range.
    fn label_width(title: &str, range: Option<&str>, theme: &Theme) -> f64 {
        let max_w = theme.font_size * 10.0;
        let title = measure(&truncate_to_width(title, max_w, theme.label_size), theme.label_size).width;
        let range = range
            .map_or(0.0, |r| measure(&truncate_to_width(r, max_w, theme.font_size * 0.9), theme.font_size * 0.9).width);
        title.max(range)
    }

    /// Thin white lines along the segment borders.
    fn borders(&self, layout: &SegmentLayout) -> Item {
        let mut cmds = Vec::new();
        for s in 0..layout.segments() {
            let (start, _) = layout.span(s);
            cmds.push(PathCmd::MoveTo(self.center));
            cmds.push(PathCmd::LineTo(frame::polar(self.center, self.radius, start)));
        }
        Item::new(Role::Grid, Shape::Path(cmds), Style::stroke(Color::WHITE, 1.5)).labelled("segment borders")
    }

    /// A column's name and value range outside the disk at `angle`.
    fn label(&self, angle: f64, title: &str, range: Option<&str>, theme: &Theme) -> Vec<Item> {
        let r = self.radius + theme.font_size * 0.8;
        let at = frame::polar(self.center, r, angle);
        let (s, c) = (angle.sin(), angle.cos());
        let anchor = if s > 0.3 {
            Anchor::Start
        } else if s < -0.3 {
            Anchor::End
        } else {
            Anchor::Middle
        };
        let (title_base, range_base, dy) = if c < -0.3 {
            (Baseline::Top, Baseline::Top, theme.label_size * 1.25)
        } else if c > 0.3 {
            (Baseline::Bottom, Baseline::Bottom, -theme.label_size * 1.25)
        } else {
            (Baseline::Bottom, Baseline::Top, 0.0)
        };
        let (title_at, range_at) =
            if dy >= 0.0 { (at, Point::new(at.x, at.y + dy)) } else { (Point::new(at.x, at.y + dy), at) };
        let max_w = theme.font_size * 10.0;
        let mut items = vec![Item::text(
            Role::AxisTitle,
            Text {
                at: title_at,
                content: truncate_to_width(title, max_w, theme.label_size),
                size: theme.label_size,
                anchor,
                baseline: title_base,
                angle: 0.0,
                color: theme.text,
            },
        )];
        if let Some(range) = range {
            items.push(Item::text(
                Role::TickLabel,
                Text {
                    at: range_at,
                    content: truncate_to_width(range, max_w, theme.font_size * 0.9),
                    size: theme.font_size * 0.9,
                    anchor,
                    baseline: range_base,
                    angle: 0.0,
                    color: theme.muted_text,
                },
            ));
        }
        items
    }
}

/// `kind = "segments"`.
pub static KIND: KindInfo = KindInfo::new("segments", &["columns", "order_by"])
    .sized(DEFAULT_SIZE)
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Canvas);

impl Technique for SegmentsOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.highlight)
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }
}
