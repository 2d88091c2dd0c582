//! `bar`: bars, one per category of `x`, vertical or horizontal, grouped side by side or stacked
//! (to totals or to 100%) by a categorical `color`, categories in data order or sorted by their
//! totals.
//!
//! Rows with the same x category (and colour group) are summed into one bar. Bars encode length,
//! so they start at zero unless the spec leaves zero out of the value axis (`zero = false`, or a
//! fixed `domain` that excludes it); then they are drawn honestly from the end of the axis nearest
//! zero, and lint rule DI001 reports the exaggeration. Negative sums hang below zero.

use crate::data::{Column, Table};
use crate::guide::axis::title_with_unit;
use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::Symbol;
use crate::guide::scale::Scale;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode;
use crate::mark::grouped::Orientation;
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, bands, frame};
use crate::scene::{Color, Item, PathCmd, Point, Rect, Role, Shape, Style};
use crate::spec::{Channel, Chart, ColorChannel, ScaleKind};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "bar"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct BarOptions {
    /// The categories along the horizontal axis: a text column, or numbers treated as categories
    /// (one band each, in ascending order).
    #[schemars(example = &"state")]
    pub x: Channel,
    /// The bar length: a numeric column; rows with the same `x` (and `color`) are summed. Bars
    /// start at zero unless `zero = false` or a `domain` leaves zero out (lint rule DI001).
    #[schemars(example = &"flights")]
    pub y: Channel,
    /// Group bars side by side within each category by a categorical column, with a legend.
    #[serde(default)]
    #[schemars(example = &"origin")]
    pub color: Option<ColorChannel>,
    /// Bar colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
    /// How the colour groups of a category share it: `"dodge"` (default: side by side),
    /// `"stack"` (on top of each other: the stack is the category's total; negative sums stack
    /// down from zero) or `"normalize"` (stacked to 100% of the category's total).
    #[serde(default)]
    pub stack: Option<BarStack>,
    /// Order of the categories: `"data"` (default: as `x` gives them), `"descending"` or
    /// `"ascending"` by each category's total.
    #[serde(default)]
    pub sort: Option<BarSort>,
    /// `"vertical"` (default: categories along the bottom, bars rising) or `"horizontal"`
    /// (categories down the left, the first on top, bars running right: room for long names).
    #[serde(default)]
    pub orientation: Option<Orientation>,
}

/// How a bar chart's colour groups share a category.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum BarStack {
    /// Side by side.
    #[default]
    Dodge,
    /// On top of each other.
    Stack,
    /// On top of each other, as shares of the category's total.
    Normalize,
}

/// The order of a bar chart's categories.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum BarSort {
    /// As the `x` column gives them.
    #[default]
    Data,
    /// Largest total first.
    Descending,
    /// Smallest total first.
    Ascending,
}

/// Bars narrower than this many pixels get a warning: they are hard to see and compare.
const NARROW_BAR: f64 = 2.0;

/// One drawn bar: its category and group, the sum of its rows' values, where it starts and
/// ends on the value axis (0 and the sum unless stacked) and its rows.
struct Bar {
    x: usize,
    group: usize,
    sum: f64,
    from: f64,
    to: f64,
    rows: Vec<u32>,
}

/// Draw a bar chart.
pub fn draw(chart: &Chart, options: &BarOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    if table.rows == 0 {
        return Err(encode::no_rows(chart, table, None));
    }
    check_scales(options, y_col)?;
    let stack = options.stack.unwrap_or_default();
    if stack == BarStack::Normalize && options.color.is_none() {
        return Err(MarkError::at(
            &["stack"],
            "`stack = \"normalize\"` shares each category among its colour groups, but the chart has no `color`"
                .to_string(),
            "add `color = \"COLUMN\"` to split the bars into groups, or remove `stack`",
        ));
    }
    let stacked = stack != BarStack::Dodge;
    let color = bands::grouping_channel(chart, options.color.as_ref(), table, "bars")?;
    let color_col = match &color {
        Some(c) => Some(encode::column(chart, "color", c.field(), table)?),
        None => None,
    };

    let mut numeric: Vec<(&str, &Column)> = vec![(y_opts.field.as_str(), y_col)];
    if x_col.numbers().is_some() {
        numeric.push((x_opts.field.as_str(), x_col));
    }
    let (rows, warnings) = encode::drawn_rows(chart, table, numeric, color.as_ref())?;
    let mut warnings = warnings;

    let mut x_keys = bands::keys(x_col, &rows);
    let groups = match color_col {
        Some(col) => bands::keys(col, &rows),
        None => bands::Keys::single("", rows.len()),
    };
    let (nx, ng) = (x_keys.labels.len(), groups.labels.len());
    let orientation = options.orientation.unwrap_or_default();
    let horizontal = orientation == Orientation::Horizontal;
    let [width, height] = chart.size.unwrap_or(crate::mark::FRAME_SIZE);
    let room = if horizontal { height } else { width };
    let slots = nx.saturating_mul(ng);
    let across = if stacked { nx } else { slots };
    if across as f64 > room {
        let what = if ng > 1 {
            format!("{nx} categories × {ng} colour groups = {slots} bars")
        } else {
            format!("{nx} categories")
        };
        return Err(MarkError::at(
            &["x"],
            format!(
                "{what} do not fit a {room} px {} chart (each bar would be narrower than a pixel)",
                if horizontal { "tall" } else { "wide" }
            ),
            "bar charts suit tens of categories: filter or aggregate the data into fewer categories, or make `size` larger",
        ));
    }

    // Sum the rows of each (category, group) slot.
    let values = y_col.numbers().unwrap_or(&[]);
    let mut slot_rows: Vec<Vec<u32>> = vec![Vec::new(); slots];
    for (k, &r) in rows.iter().enumerate() {
        let (xi, gi) = (x_keys.of_row.get(k).copied().unwrap_or(0), groups.of_row.get(k).copied().unwrap_or(0));
        if let Some(slot) = slot_rows.get_mut(xi * ng + gi) {
            slot.push(r);
        }
    }
    let mut bars: Vec<Bar> = slot_rows
        .into_iter()
        .enumerate()
        .filter(|(_, rows)| !rows.is_empty())
        .map(|(slot, rows)| {
            let sum = rows.iter().filter_map(|&r| values.get(r as usize)).sum();
            Bar { x: slot / ng, group: slot % ng, sum, from: 0.0, to: sum, rows }
        })
        .collect();
    if stacked {
        stack_bars(&mut bars, nx, stack == BarStack::Normalize);
    }
    sort_categories(&mut bars, &mut x_keys, options.sort.unwrap_or_default());

    let summed = bars.iter().any(|b| b.rows.len() > 1);
    let y_axis = value_axis(&y_opts, &bars, summed, stack);
    let mut category_labels = x_keys.labels.clone();
    if horizontal {
        // Band 0 is at the bottom of a vertical axis: reversed, the first category is on top.
        category_labels.reverse();
    }
    let x_axis = PositionAxis {
        title: title_with_unit(x_opts.title.as_deref().unwrap_or(&x_opts.field), x_opts.unit.as_deref()),
        kind: ScaleKind::Band,
        domain: Domain::Categories(category_labels),
        nice: false,
        ticks: None,
        grid: x_opts.grid.unwrap_or(false),
        inset: 0.0,
    };
    let (colors, legend) =
        encode::color_encoding(chart, color.as_ref(), options.mark_color.as_deref(), table, &rows, Symbol::Square)?;
    let legends = legend.into_iter().collect();
    let (frame, theme) = match orientation {
        Orientation::Vertical => frame::cartesian(chart, x_axis, y_axis, legends)?,
        Orientation::Horizontal => frame::cartesian(chart, y_axis, x_axis, legends)?,
    };
    let (Scale::Band(band), value) = (if horizontal { (&frame.y, &frame.x) } else { (&frame.x, &frame.y) }) else {
        return Err(MarkError::at(&["x"], "the categories are not on a band scale", ""));
    };
    // A rectangle from (across, along) extents: across the category axis, along the value axis.
    let rect = |(a0, a1): (f64, f64), (v0, v1): (f64, f64)| match orientation {
        Orientation::Vertical => Rect::new(a0, v0, a1 - a0, v1 - v0),
        Orientation::Horizontal => Rect::new(v0, a0, v1 - v0, a1 - a0),
    };

    // The baseline: zero, or the end of the value axis nearest zero when zero is left out.
    let (d0, d1) = value.domain();
    let base = 0.0f64.clamp(d0.min(d1), d0.max(d1));
    let base_px = value.map(base);
    // Bands by category name: a facet panel's axis may hold categories the panel has no bar for.
    let band_index = |b: &Bar| x_keys.labels.get(b.x).and_then(|l| band.band_of(l)).unwrap_or(b.x);
    let slot_of = |b: &Bar| {
        let x = band_index(b);
        if stacked { (band.start(x), band.bandwidth()) } else { bands::dodged(band, x, &groups.labels, b.group) }
    };
    let (lo, hi) = (d0.min(d1), d0.max(d1));
    let mut marks = Vec::with_capacity(bars.len() + 1);
    let mut narrowest = f64::INFINITY;
    let mut clipped = 0usize;
    for b in &bars {
        let (x, w) = slot_of(b);
        narrowest = narrowest.min(w);
        // A sum beyond the domain is drawn up to the domain's end and marked as cut there.
        let end = b.to.max(lo).min(hi);
        let top = value.map(end);
        let start_px = if b.from == 0.0 { base_px } else { value.map(b.from.max(lo).min(hi)) };
        let (y0, y1) = (start_px.min(top), start_px.max(top));
        // A zero sum has no bar; a bar at a baseline other than zero stays, even with no length,
        // so that the scene (and lint rule DI001) still sees it.
        if b.sum == 0.0 || (y1 - y0).is_nan() {
            continue;
        }
        let label = match groups.labels.get(b.group).filter(|_| ng > 1) {
            Some(g) => format!("{}, {g}", x_keys.labels.get(b.x).map_or("", String::as_str)),
            None => x_keys.labels.get(b.x).cloned().unwrap_or_default(),
        };
        let fill = b.rows.first().map_or(encode::DEFAULT_MARK_COLOR, |&r| colors.color_of(r));
        let plot_span =
            if horizontal { (frame.plot.x, frame.plot.right()) } else { (frame.plot.y, frame.plot.bottom()) };
        let cut =
            (end != b.to).then(|| clip_mark(orientation, (x, w), (top, start_px), plot_span, (fill, theme.background)));
        let mut tooltip = format!("{}: {}\n", x_opts.field, x_keys.labels.get(b.x).map_or("", String::as_str));
        if let (Some(c), Some(g)) = (&color, groups.labels.get(b.group)) {
            tooltip.push_str(&format!("{}: {g}\n", c.field()));
        }
        tooltip.push_str(&format!("{}: {}", y_opts.field, b.sum));
        if b.rows.len() > 1 {
            tooltip.push_str(&format!(" (sum of {} rows)", b.rows.len()));
        }
        if stack == BarStack::Normalize {
            tooltip.push_str(&format!("\nshare of {}: {:.1}%", x_opts.field, (b.to - b.from).abs()));
        }
        marks.push(
            Item::new(Role::DataMark, Shape::Rect(rect((x, x + w), (y0, y1))), Style::fill(fill))
                .with_rows(b.rows.clone())
                .labelled(label.clone())
                .with_tooltip(tooltip.clone()),
        );
        if let Some(mark) = cut {
            clipped += 1;
            let mark = mark.with_rows(b.rows.clone()).labelled(format!("{CLIPPED_PREFIX}{label}"));
            marks.push(mark.with_tooltip(format!("{tooltip}\ncut at the end of the y domain")));
        }
    }
    if clipped > 0 {
        let ends = bars.iter().map(|b| b.to).chain(bars.iter().filter(|b| b.from != 0.0).map(|b| b.from));
        let (min, max) = encode::finite_extent(ends).unwrap_or((lo, hi));
        warnings.push(Warning::from(format!(
            "{clipped} of {} bars reach past the y domain [{lo}, {hi}] and are cut at its end \
             (marked with a break); widen `domain` to cover [{min}, {max}], or remove it",
            bars.len()
        )));
    }
    if bars.iter().any(|b| b.to < 0.0) && base == 0.0 {
        // Bars on both sides of zero: a zero line separates them.
        let at = base_px.round() + 0.5;
        let (from, to) = match orientation {
            Orientation::Vertical => (Point::new(frame.plot.x, at), Point::new(frame.plot.right(), at)),
            Orientation::Horizontal => (Point::new(at, frame.plot.y), Point::new(at, frame.plot.bottom())),
        };
        marks.push(
            Item::new(
                Role::Axis,
                Shape::Path(vec![PathCmd::MoveTo(from), PathCmd::LineTo(to)]),
                Style::stroke(theme.axis, 1.0),
            )
            .labelled("baseline"),
        );
    }
    if narrowest < NARROW_BAR {
        warnings.push(Warning::from(format!(
            "bars are {narrowest:.1} px wide, too narrow to see or compare; \
             aggregate into fewer categories or make `size` wider"
        )));
    }
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

    let mut derived = Derived::default();
    let label_of = |labels: &[String], i: usize| labels.get(i).cloned().unwrap_or_default();
    derived.push(&x_opts.field, DerivedColumn::Text(bars.iter().map(|b| label_of(&x_keys.labels, b.x)).collect()));
    if let Some(c) = &color {
        derived.push(c.field(), DerivedColumn::Text(bars.iter().map(|b| label_of(&groups.labels, b.group)).collect()));
    }
    derived.push(&y_opts.field, DerivedColumn::Number(bars.iter().map(|b| b.sum).collect()));
    derived.push("rows", DerivedColumn::Number(bars.iter().map(|b| b.rows.len() as f64).collect()));
    if stacked {
        derived.push("from", DerivedColumn::Number(bars.iter().map(|b| b.from).collect()));
        derived.push("to", DerivedColumn::Number(bars.iter().map(|b| b.to).collect()));
    }
    Ok(ChartOutput { scene, derived, warnings, geojson: None, geometry: Default::default() })
}

/// What the label of a clip mark starts with; the rest is its bar's label.
pub const CLIPPED_PREFIX: &str = "clipped: ";
/// Distance of a clip mark from the cut end of a bar, in pixels.
const CLIP_INSET: f64 = 7.0;
/// Height of a clip mark's teeth, in pixels.
const CLIP_TOOTH: f64 = 3.0;

/// The mark of a bar cut at the end of the value axis: a zig-zag across the bar (`slot`: its
/// start and width across the category axis) near the cut end (`ends`: the cut end and the
/// base, in pixels along the value axis), in the background colour so that the bar looks
/// broken; a bar too short to hold it gets the zig-zag in its own colour beside the cut, inside
/// the plot (`plot`: its pixel span along the value axis).
fn clip_mark(
    orientation: Orientation,
    slot: (f64, f64),
    ends: (f64, f64),
    plot: (f64, f64),
    colors: (Color, Color),
) -> Item {
    let ((x, width), (end_px, base_px)) = (slot, ends);
    let (fill, background) = colors;
    let towards_base = if base_px >= end_px { 1.0 } else { -1.0 };
    let room = (base_px - end_px).abs();
    let (y, color) = if room >= 2.0 * CLIP_INSET {
        (end_px + towards_base * CLIP_INSET, background)
    } else {
        let (top, bottom) = (plot.0 + CLIP_TOOTH, plot.1 - CLIP_TOOTH);
        ((end_px - towards_base * CLIP_TOOTH).max(top).min(bottom), fill)
    };
    let teeth = ((width / (2.0 * CLIP_TOOTH)).round() as usize).max(2);
    let step = width / teeth as f64;
    let cmds = (0..=teeth)
        .map(|k| {
            let side = if k % 2 == 0 { -0.5 } else { 0.5 };
            let (across, along) = (x + step * k as f64, y + side * CLIP_TOOTH);
            let p = match orientation {
                Orientation::Vertical => Point::new(across, along),
                Orientation::Horizontal => Point::new(along, across),
            };
            if k == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) }
        })
        .collect();
    Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(color, 2.0))
}

/// Errors for scales a bar chart cannot draw honestly: a non-band x, a y that is text, time,
/// logarithmic or a band.
fn check_scales(options: &BarOptions, y_col: &Column) -> Result<(), MarkError> {
    let x_opts = options.x.options();
    if let Some(kind) = x_opts.scale.filter(|k| *k != ScaleKind::Band) {
        return Err(MarkError::at(
            &["x", "scale"],
            format!("bars place every x value in its own band, so x cannot have a {} scale", encode::scale_name(kind)),
            "remove `scale` from x (or set `scale = \"band\"`); for a numeric x axis use a line or scatter chart",
        ));
    }
    encode::require_numeric(
        "y",
        y_col,
        "a bar's length",
        "use a numeric column for y, and put categories on x or in `color`",
    )?;
    if y_col.is_time() {
        return Err(MarkError::at(
            &["y"],
            format!("y column `{}` holds dates or times, which cannot be summed into bars", y_col.name),
            "use a numeric column for y; put dates on x, where each becomes a category",
        ));
    }
    match options.y.options().scale {
        None | Some(ScaleKind::Linear) => Ok(()),
        Some(kind) => Err(MarkError::at(
            &["y", "scale"],
            format!("a bar's length is measured from zero, which a {} scale does not have", encode::scale_name(kind)),
            "remove `scale` from y (bars need a linear scale); for values spanning decades use a scatter or line chart on a log scale",
        )),
    }
}

/// The value axis over the bars' extents: zero included unless `zero = false`; a fixed
/// `domain` wins; 0–100 % for normalised stacks. Its title says "Sum of" when some bar adds up
/// several rows, or "Share of … (%)" for normalised stacks, unless the spec names a title.
fn value_axis(y_opts: &crate::spec::ChannelOptions, bars: &[Bar], summed: bool, stack: BarStack) -> PositionAxis {
    // A bar's start counts only when stacked on another: zero is the axis's choice (`zero`).
    let ends = bars.iter().map(|b| b.to).chain(bars.iter().filter(|b| b.from != 0.0).map(|b| b.from));
    let (mut lo, mut hi) = encode::finite_extent(ends).unwrap_or((0.0, 0.0));
    if y_opts.zero != Some(false) {
        lo = lo.min(0.0);
        hi = hi.max(0.0);
    }
    if stack == BarStack::Normalize {
        (lo, hi) = (lo.min(0.0).max(-100.0), hi.max(0.0).min(100.0));
    }
    if let Some([a, b]) = y_opts.domain {
        (lo, hi) = (a, b);
    }
    let title = match &y_opts.title {
        Some(t) => t.clone(),
        None if stack == BarStack::Normalize => format!("Share of {} (%)", y_opts.field),
        None if summed => format!("Sum of {}", y_opts.field),
        None => y_opts.field.clone(),
    };
    PositionAxis {
        title: title_with_unit(&title, if stack == BarStack::Normalize { None } else { y_opts.unit.as_deref() }),
        kind: ScaleKind::Linear,
        domain: Domain::Continuous(lo, hi),
        nice: y_opts.nice.unwrap_or(true) && y_opts.domain.is_none() && stack != BarStack::Normalize,
        ticks: y_opts.ticks,
        grid: y_opts.grid.unwrap_or(true),
        inset: 0.0,
    }
}

/// Stack each category's bars in group order: positive sums upwards from zero, negative ones
/// downwards; with `normalize`, as percentages of the category's total of absolute sums.
fn stack_bars(bars: &mut [Bar], categories: usize, normalize: bool) {
    let mut totals = vec![0.0f64; categories];
    for b in bars.iter() {
        totals[b.x] += b.sum.abs();
    }
    let (mut up, mut down) = (vec![0.0f64; categories], vec![0.0f64; categories]);
    for b in bars.iter_mut() {
        let scale = if normalize && totals[b.x] > 0.0 { 100.0 / totals[b.x] } else { 1.0 };
        let v = b.sum * scale;
        let running = if v >= 0.0 { &mut up[b.x] } else { &mut down[b.x] };
        b.from = *running;
        b.to = *running + v;
        *running = b.to;
    }
}

/// Put the categories in `sort` order by their totals (ties keep their order).
fn sort_categories(bars: &mut [Bar], keys: &mut bands::Keys, sort: BarSort) {
    if sort == BarSort::Data {
        return;
    }
    let mut totals = vec![0.0f64; keys.labels.len()];
    for b in bars.iter() {
        totals[b.x] += b.sum;
    }
    let mut order: Vec<usize> = (0..totals.len()).collect();
    match sort {
        BarSort::Descending => order.sort_by(|&a, &b| totals[b].total_cmp(&totals[a])),
        BarSort::Ascending => order.sort_by(|&a, &b| totals[a].total_cmp(&totals[b])),
        BarSort::Data => {}
    }
    let mut new_of_old = vec![0; order.len()];
    for (new, &old) in order.iter().enumerate() {
        new_of_old[old] = new;
    }
    keys.labels = order.iter().map(|&old| keys.labels[old].clone()).collect();
    keys.of_row.iter_mut().for_each(|k| *k = new_of_old[*k]);
    bars.iter_mut().for_each(|b| b.x = new_of_old[b.x]);
    bars.sort_by_key(|b| (b.x, b.group));
}

/// `kind = "bar"`.
pub static KIND: KindInfo =
    KindInfo::new("bar", &["x", "y", "color"]).faceted(crate::mark::registry::Faceting::Frame).drawing_annotations();

impl Technique for BarOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        // Bars place every x value in a band, numbers included (`grouped::axes` says so).
        crate::mark::grouped::axes(Some(&self.x), &self.y, self.orientation.unwrap_or_default())
    }

    crate::mark::registry::color_key!();
}
