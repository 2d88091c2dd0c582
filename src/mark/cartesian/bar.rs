//! `bar`: bars, one per category of `x`, vertical or horizontal, grouped side by side or stacked
//! (to totals or to 100%) by a categorical `color`, categories in data order or sorted by their
//! totals.
//!
//! Rows with the same x category (and colour group) are summed into one bar. Bars encode length,
//! so they start at zero unless the spec leaves zero out of the value axis (`zero = false`, or a
//! fixed `domain` that excludes it); then they are drawn honestly from the end of the axis nearest
//! zero, and lint rule DI001 reports the exaggeration. Negative sums hang below zero.

use crate::data::density::groups::GroupQuery;
use crate::data::density::plan::PlanRows;
use crate::data::{Column, Table};
use crate::guide::axis::title_with_unit;
use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::Symbol;
use crate::guide::scale::Scale;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode;
use crate::mark::geometry::{self, Plot};
use crate::mark::grouped::Orientation;
use crate::mark::plan_rows::PlanGroups;
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::spread::{Spread, Summary};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, bands, frame};
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Rect, Role, Shape, Style, Text};
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
    /// How the rows of a bar combine into its length: `"sum"` (default), `"mean"`, `"median"`
    /// or `"count"` (the number of rows with a finite y).
    #[serde(default)]
    pub aggregate: Option<BarAggregate>,
    /// Whiskers with caps around each bar, from the rows it combines: `"stdev"` (± one sample
    /// standard deviation), `"sem"` (± the standard error), `"ci95"` (a 95% confidence
    /// interval, Student's t with n − 1 degrees of freedom) need `aggregate = "mean"`;
    /// `"minmax"` (the range of the rows) needs `"mean"` or `"median"`. Not with `stack`; a bar
    /// of one row gets no whisker.
    #[serde(default)]
    pub error: Option<Spread>,
    /// Each bar's value written at its end: `true`, or `{ position, decimals }`. Inside the bar
    /// in black or white, whichever contrasts more with it, where it fits, else just beyond the
    /// end; stacked segments are labelled in their middle where the label fits.
    #[serde(default)]
    pub labels: Option<BarLabels>,
}

/// How a bar combines its rows.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum BarAggregate {
    /// The sum of the values.
    #[default]
    Sum,
    /// The arithmetic mean.
    Mean,
    /// The median.
    Median,
    /// The number of rows.
    Count,
}

impl BarAggregate {
    /// The spec's word for it.
    fn name(self) -> &'static str {
        match self {
            BarAggregate::Sum => "sum",
            BarAggregate::Mean => "mean",
            BarAggregate::Median => "median",
            BarAggregate::Count => "count",
        }
    }

    /// The bar's value from its rows' statistics.
    fn of(self, s: &Summary) -> f64 {
        match self {
            BarAggregate::Sum => s.sum,
            BarAggregate::Mean => s.mean,
            BarAggregate::Median => s.median,
            BarAggregate::Count => s.n as f64,
        }
    }
}

/// Value labels on bars: on or off, or how to place and write them.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum BarLabels {
    /// `true`: labels placed automatically with the default number of decimals.
    Show(bool),
    /// `{ position, decimals }`.
    Detailed(BarLabelOptions),
}

/// How bar labels are placed and written.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct BarLabelOptions {
    /// `"auto"` (default: inside where the label fits, else outside), `"inside"` (only inside;
    /// a label that does not fit is left out) or `"outside"` (just beyond the bar's end, or its
    /// whisker's). Stacked segments are always labelled inside.
    #[serde(default)]
    pub position: Option<LabelPosition>,
    /// Digits after the decimal point, at most 12 (default: about three significant digits of
    /// the largest value, none for whole numbers).
    #[serde(default)]
    #[schemars(extend("maximum" = 12), example = 1)]
    pub decimals: Option<u32>,
}

/// Where a bar's label goes.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LabelPosition {
    /// Inside where it fits, else outside.
    #[default]
    Auto,
    /// Inside the bar, at its end.
    Inside,
    /// Beyond the bar's end.
    Outside,
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
/// Font size of bar labels, relative to the chart's font size.
const LABEL_SCALE: f64 = 0.9;
/// Pixels between a label and the end of its bar (or whisker), and around it inside a bar.
const LABEL_GAP: f64 = 4.0;
/// What the label of a whisker starts with; the rest is its bar's label.
pub const ERROR_PREFIX: &str = "error: ";
/// The label of a bar's value label in the scene.
pub const VALUE_LABEL: &str = "bar value";

/// One drawn bar: its category and group, its value (the rows' sum, mean, median or count),
/// where it starts and ends on the value axis (0 and the value unless stacked), its whisker's
/// interval, if any, and its rows.
struct Bar {
    x: usize,
    group: usize,
    value: f64,
    from: f64,
    to: f64,
    interval: Option<(f64, f64)>,
    /// How many rows it combines.
    n: usize,
    /// The row of the drawn table whose colour group it is in.
    color_row: u32,
    /// Its rows in the source's table (none when they stay in the plan).
    rows: Vec<u32>,
}

/// Label settings checked against the chart: where labels go and their decimals.
#[derive(Clone, Copy)]
struct LabelPlan {
    position: LabelPosition,
    decimals: Option<usize>,
}

/// A bar placed in the frame, in pixels: `across` its start and width across the category
/// axis; `start` and `end` along the value axis (clamped to the domain), `dir` the direction
/// from start to end (±1), `whisker` its interval's ends and `cut` whether it reaches past the
/// domain.
struct Placed {
    across: (f64, f64),
    start: f64,
    end: f64,
    dir: f64,
    whisker: Option<(f64, f64)>,
    cut: bool,
}

/// Draw a bar chart (`plan`: its source's rows, when they stay in the plan and the table
/// holds none).
pub fn draw(
    chart: &Chart,
    options: &BarOptions,
    table: &Table,
    plan: Option<&PlanRows>,
) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    let plan = plan.filter(|_| table.rows == 0);
    if table.rows == 0 && plan.is_none() {
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
    let aggregate = options.aggregate.unwrap_or_default();
    let error = check_error(options.error, aggregate, stack)?;
    let label_plan = check_labels(options.labels.as_ref(), stacked)?;
    let color = bands::grouping_channel(chart, options.color.as_ref(), table, "bars")?;

    // The rows are those of the table, or one per group of the rows left in the plan.
    let grouped = match plan {
        Some(plan) => Some(grouped_in_plan(chart, plan, (&x_opts.field, y_col), color.as_ref(), aggregate)?),
        None => None,
    };
    let table = grouped.as_ref().map_or(table, |g| &g.table);
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let color_col = match &color {
        Some(c) => Some(encode::column(chart, "color", c.field(), table)?),
        None => None,
    };
    let (rows, mut warnings) = match &grouped {
        Some(g) => (g.rows.clone(), g.warnings.clone()),
        None => {
            let mut numeric: Vec<(&str, &Column)> = vec![(y_opts.field.as_str(), y_col)];
            if x_col.numbers().is_some() {
                numeric.push((x_opts.field.as_str(), x_col));
            }
            encode::drawn_rows(chart, table, numeric, color.as_ref())?
        }
    };

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

    // Combine the rows of each (category, group) slot: the source's rows, or a group's statistics.
    let mut slot_rows: Vec<Vec<u32>> = vec![Vec::new(); slots];
    for (k, &r) in rows.iter().enumerate() {
        let (xi, gi) = (x_keys.of_row.get(k).copied().unwrap_or(0), groups.of_row.get(k).copied().unwrap_or(0));
        if let Some(slot) = slot_rows.get_mut(xi * ng + gi) {
            slot.push(r);
        }
    }
    let values = y_col.numbers().unwrap_or(&[]);
    let mut bars: Vec<Bar> = slot_rows
        .into_iter()
        .enumerate()
        .filter_map(|(slot, rows)| {
            let summary = match &grouped {
                Some(g) => g.summary(*rows.first()?)?,
                None => Summary::of(rows.iter().filter_map(|&r| values.get(r as usize).copied()))?,
            };
            let value = aggregate.of(&summary);
            let interval = error.and_then(|e| e.interval(&summary, value));
            let color_row = *rows.first()?;
            let rows = if grouped.is_some() { Vec::new() } else { rows };
            Some(Bar {
                x: slot / ng,
                group: slot % ng,
                value,
                from: 0.0,
                to: value,
                interval,
                n: summary.n,
                color_row,
                rows,
            })
        })
        .collect();
    if error.is_some() {
        let single = bars.iter().filter(|b| b.n < 2).count();
        if single > 0 {
            warnings.push(Warning::from(format!(
                "{single} of {} bars combine a single row and have no whisker: a spread needs at least two rows",
                bars.len()
            )));
        }
    }
    if stacked {
        stack_bars(&mut bars, nx, stack == BarStack::Normalize);
    }
    sort_categories(&mut bars, &mut x_keys, options.sort.unwrap_or_default());

    let summed = bars.iter().any(|b| b.n > 1);
    let value_axis = value_axis(&y_opts, &bars, summed, stack, aggregate, error);
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
    let legends: Vec<crate::guide::legend::Legend> = legend.into_iter().collect();
    let layout = |chart: &Chart, value_axis: PositionAxis| match orientation {
        Orientation::Vertical => frame::cartesian(chart, x_axis.clone(), value_axis, legends.clone()),
        Orientation::Horizontal => frame::cartesian(chart, value_axis, x_axis.clone(), legends.clone()),
    };
    let fill_of = |b: &Bar| colors.color_of(b.color_row);
    let label_texts = label_plan.map(|plan| label_texts(&bars, plan, stack == BarStack::Normalize));
    let label_size = (chart.font_size.unwrap_or(12.0) * LABEL_SCALE).max(crate::guide::theme::MIN_TEXT_SIZE);

    // Labels beyond the bars' ends need room on the value axis: lay the frame out, see how far
    // they reach, and widen the domain until they fit (a fixed `domain` stays as it is).
    let mut value_axis = value_axis;
    let outside_possible = !stacked && label_plan.is_some_and(|p| p.position != LabelPosition::Inside);
    if let (true, Some(texts), None) = (outside_possible, &label_texts, y_opts.domain) {
        // Probe without the facet panel, which records what it sees: the real frame comes after.
        let probe_chart = Chart { panel: None, ..chart.clone() };
        for _ in 0..3 {
            let (probe, _) = layout(&probe_chart, value_axis.clone())?;
            let Some(geo) = Geometry::new(&probe, orientation, stacked, &x_keys.labels, &groups.labels) else { break };
            let placed: Vec<Placed> = bars.iter().map(|b| geo.place(b)).collect();
            let plan = label_plan.map_or(LabelPosition::Auto, |p| p.position);
            let reach = bars.iter().zip(&placed).zip(texts).filter_map(|((b, p), text)| {
                let extent = geo.label_extent(text, label_size);
                let outside = plan == LabelPosition::Outside || !geo.fits_inside(b, p, extent);
                outside.then(|| geo.value.invert(p.far() + p.dir * (LABEL_GAP + extent.0 + 1.0))).flatten()
            });
            let Some((lo, hi)) = encode::finite_extent(reach) else { break };
            let Domain::Continuous(d0, d1) = value_axis.domain else { break };
            let (v0, v1) = geo.value.domain();
            if lo >= v0.min(v1) && hi <= v0.max(v1) {
                break;
            }
            value_axis.domain = Domain::Continuous(d0.min(lo), d1.max(hi));
        }
    }
    let (frame, theme) = layout(chart, value_axis)?;
    let Some(geo) = Geometry::new(&frame, orientation, stacked, &x_keys.labels, &groups.labels) else {
        return Err(MarkError::at(&["x"], "the categories are not on a band scale", ""));
    };
    let placed: Vec<Placed> = bars.iter().map(|b| geo.place(b)).collect();

    let (lo, hi) = geo.value_range();
    let mut marks = Vec::with_capacity(2 * bars.len() + 1);
    let mut whiskers = Vec::new();
    let mut narrowest = f64::INFINITY;
    let mut clipped = 0usize;
    for (b, p) in bars.iter().zip(&placed) {
        let (x, w) = p.across;
        narrowest = narrowest.min(w);
        let (y0, y1) = (p.start.min(p.end), p.start.max(p.end));
        // A zero value has no bar; a bar at a baseline other than zero stays, even with no
        // length, so that the scene (and lint rule DI001) still sees it.
        if b.value == 0.0 || (y1 - y0).is_nan() {
            continue;
        }
        let label = bar_label(b, &x_keys.labels, &groups.labels);
        let fill = fill_of(b);
        let plot_span =
            if horizontal { (frame.plot.x, frame.plot.right()) } else { (frame.plot.y, frame.plot.bottom()) };
        let cut = p.cut.then(|| clip_mark(orientation, (x, w), (p.end, p.start), plot_span, (fill, theme.background)));
        let mut tooltip = format!("{}: {}\n", x_opts.field, x_keys.labels.get(b.x).map_or("", String::as_str));
        if let (Some(c), Some(g)) = (&color, groups.labels.get(b.group)) {
            tooltip.push_str(&format!("{}: {g}\n", c.field()));
        }
        tooltip.push_str(&format!("{}: {}", y_opts.field, b.value));
        if b.n > 1 {
            tooltip.push_str(&format!(" ({} of {} rows)", aggregate.name(), b.n));
        }
        if let (Some(e), Some((l, u))) = (error, b.interval) {
            tooltip.push_str(&format!("\n{}: [{l}, {u}]", e.name()));
        }
        if stack == BarStack::Normalize {
            tooltip.push_str(&format!("\nshare of {}: {:.1}%", x_opts.field, (b.to - b.from).abs()));
        }
        marks.push(
            Item::new(Role::DataMark, Shape::Rect(geo.rect((x, x + w), (y0, y1))), Style::fill(fill))
                .with_rows(b.rows.clone())
                .labelled(label.clone())
                .with_tooltip(tooltip.clone()),
        );
        if let Some(mark) = cut {
            clipped += 1;
            let mark = mark.with_rows(b.rows.clone()).labelled(format!("{CLIPPED_PREFIX}{label}"));
            marks.push(mark.with_tooltip(format!("{tooltip}\ncut at the end of the y domain")));
        }
        if let Some(ends) = p.whisker {
            whiskers.push(
                whisker(&geo, p.across, ends, theme.text)
                    .with_rows(b.rows.clone())
                    .labelled(format!("{ERROR_PREFIX}{label}"))
                    .with_tooltip(tooltip),
            );
        }
    }
    marks.extend(whiskers);
    if clipped > 0 {
        let ends = bars.iter().map(|b| b.to).chain(bars.iter().filter(|b| b.from != 0.0).map(|b| b.from));
        let (min, max) = encode::finite_extent(ends).unwrap_or((lo, hi));
        warnings.push(Warning::from(format!(
            "{clipped} of {} bars reach past the y domain [{lo}, {hi}] and are cut at its end \
             (marked with a break); widen `domain` to cover [{min}, {max}], or remove it",
            bars.len()
        )));
    }
    let base = 0.0f64.clamp(lo, hi);
    if bars.iter().any(|b| b.to < 0.0) && base == 0.0 {
        // Bars on both sides of zero: a zero line separates them.
        let at = geo.value.map(base).round() + 0.5;
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
    if let (Some(plan), Some(texts)) = (label_plan, &label_texts) {
        let fills: Vec<Color> = bars.iter().map(fill_of).collect();
        let (labels, left_out) =
            geo.labels(&bars, &placed, texts, &fills, plan.position, (label_size, theme.text), frame.plot);
        marks.extend(labels);
        if left_out > 0 {
            warnings.push(Warning::from(format!(
                "{left_out} bar labels are left out: they would overlap other labels or bars, or leave the plot; \
                 make `size` larger, set `labels = {{ position = \"auto\" }}`, or use `orientation = \"horizontal\"`"
            )));
        }
    }
    if narrowest < NARROW_BAR {
        warnings.push(Warning::from(format!(
            "bars are {narrowest:.1} px wide, too narrow to see or compare; \
             aggregate into fewer categories or make `size` wider"
        )));
    }
    // Bar lengths are sums or statistics, not a column's values: a brush selects categories.
    let categories = Some((x_opts.field.as_str(), x_col));
    let geometry = geometry::Geometry::of_plot(match orientation {
        Orientation::Vertical => Plot::of_frame(&frame, categories, None),
        Orientation::Horizontal => Plot::of_frame(&frame, None, categories),
    });
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

    let mut derived = Derived::default();
    let label_of = |labels: &[String], i: usize| labels.get(i).cloned().unwrap_or_default();
    derived.push(&x_opts.field, DerivedColumn::Text(bars.iter().map(|b| label_of(&x_keys.labels, b.x)).collect()));
    if let Some(c) = &color {
        derived.push(c.field(), DerivedColumn::Text(bars.iter().map(|b| label_of(&groups.labels, b.group)).collect()));
    }
    derived.push(&y_opts.field, DerivedColumn::Number(bars.iter().map(|b| b.value).collect()));
    derived.push("rows", DerivedColumn::Number(bars.iter().map(|b| b.n as f64).collect()));
    if stacked {
        derived.push("from", DerivedColumn::Number(bars.iter().map(|b| b.from).collect()));
        derived.push("to", DerivedColumn::Number(bars.iter().map(|b| b.to).collect()));
    }
    if error.is_some() {
        let end = |pick: fn((f64, f64)) -> f64| bars.iter().map(|b| b.interval.map_or(f64::NAN, pick)).collect();
        derived.push("lower", DerivedColumn::Number(end(|(l, _)| l)));
        derived.push("upper", DerivedColumn::Number(end(|(_, u)| u)));
    }
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// The groups of the rows left in `plan`: one per category of `x` (and colour group), with the
/// statistics of `y` over the rows that are finite in `y`, in a numeric `x` and in a numeric
/// colour column (the policy for rows in memory).
fn grouped_in_plan(
    chart: &Chart,
    plan: &PlanRows,
    (x_field, y_col): (&str, &Column),
    color: Option<&ColorChannel>,
    aggregate: BarAggregate,
) -> Result<PlanGroups, MarkError> {
    let numeric = |field: &str| plan.is_number(field);
    let mut keys = vec![x_field];
    let mut required = vec![y_col.name.as_str()];
    if numeric(x_field) {
        required.push(x_field);
    }
    if let Some(c) = color {
        keys.push(c.field());
        if numeric(c.field()) {
            required.push(c.field());
        }
    }
    let query = GroupQuery {
        keys: &keys,
        value: Some(&y_col.name),
        required: &required,
        median: aggregate == BarAggregate::Median,
    };
    PlanGroups::of(chart, plan, query)
}

/// A bar's name in the scene: its category, and its group when there are several.
fn bar_label(b: &Bar, categories: &[String], groups: &[String]) -> String {
    let category = categories.get(b.x).map_or("", String::as_str);
    bar_name(category, groups.get(b.group).filter(|_| groups.len() > 1).map(String::as_str))
}

/// The name of the bar of `category` (and colour `group`, given when the chart has several) in
/// the scene: what lint rules find a bar of the derived table by.
pub fn bar_name(category: &str, group: Option<&str>) -> String {
    match group {
        Some(g) => format!("{category}, {g}"),
        None => category.to_string(),
    }
}

/// The text of each bar's label: its value, or its share in percent in a normalised stack,
/// all written with the same decimals.
fn label_texts(bars: &[Bar], plan: LabelPlan, normalized: bool) -> Vec<String> {
    let values: Vec<f64> = bars.iter().map(|b| if normalized { (b.to - b.from).abs() } else { b.value }).collect();
    let texts = crate::guide::format::format_labels(&values, plan.decimals);
    if normalized { texts.into_iter().map(|t| format!("{t}%")).collect() } else { texts }
}

/// The spread option checked against the aggregate and the stacking.
fn check_error(error: Option<Spread>, aggregate: BarAggregate, stack: BarStack) -> Result<Option<Spread>, MarkError> {
    let Some(e) = error else { return Ok(None) };
    if stack != BarStack::Dodge {
        return Err(MarkError::at(
            &["error"],
            format!(
                "`error = \"{}\"` draws whiskers at the end of each bar, but stacked bars end where the next begins",
                e.name()
            ),
            "remove `stack` (bars with whiskers stand side by side), or remove `error`",
        ));
    }
    let allowed = match e {
        Spread::Minmax => matches!(aggregate, BarAggregate::Mean | BarAggregate::Median),
        _ => aggregate == BarAggregate::Mean,
    };
    if !allowed {
        let needs =
            if e == Spread::Minmax { "`aggregate = \"mean\"` or `\"median\"`" } else { "`aggregate = \"mean\"`" };
        return Err(MarkError::at(
            &["error"],
            format!(
                "`error = \"{}\"` is a spread of the rows around a typical value, which a {} of the rows is not",
                e.name(),
                aggregate.name()
            ),
            &format!(
                "set {needs} (`stdev`, `sem` and `ci95` go with the mean; `minmax` with the mean or median), or remove `error`"
            ),
        ));
    }
    Ok(Some(e))
}

/// The labels option checked: `None` when there are no labels.
fn check_labels(labels: Option<&BarLabels>, stacked: bool) -> Result<Option<LabelPlan>, MarkError> {
    let options = match labels {
        None | Some(BarLabels::Show(false)) => return Ok(None),
        Some(BarLabels::Show(true)) => BarLabelOptions::default(),
        Some(BarLabels::Detailed(o)) => o.clone(),
    };
    let position = options.position.unwrap_or_default();
    if stacked && position == LabelPosition::Outside {
        return Err(MarkError::at(
            &["labels", "position"],
            "stacked segments are labelled inside, where the label fits; outside a segment lies the next one"
                .to_string(),
            "remove `position` (or set it to \"auto\"), or remove `stack`",
        ));
    }
    let decimals = match options.decimals {
        Some(d) if d > 12 => {
            return Err(MarkError::at(
                &["labels", "decimals"],
                format!("{d} decimals is more than a label can show (at most 12)"),
                "use at most 12 decimals, or leave `decimals` out for about three significant digits",
            ));
        }
        d => d.map(|d| d as usize),
    };
    Ok(Some(LabelPlan { position, decimals }))
}

/// The frame's scales as a bar chart uses them: which way round, the category bands and the
/// value scale.
struct Geometry<'f> {
    orientation: Orientation,
    stacked: bool,
    band: &'f crate::guide::scale::BandScale,
    value: &'f Scale,
    categories: &'f [String],
    groups: &'f [String],
}

impl<'f> Geometry<'f> {
    fn new(
        frame: &'f crate::guide::layout::Frame,
        orientation: Orientation,
        stacked: bool,
        categories: &'f [String],
        groups: &'f [String],
    ) -> Option<Geometry<'f>> {
        let (category, value) = match orientation {
            Orientation::Vertical => (&frame.x, &frame.y),
            Orientation::Horizontal => (&frame.y, &frame.x),
        };
        let Scale::Band(band) = category else { return None };
        Some(Geometry { orientation, stacked, band, value, categories, groups })
    }

    /// The value domain, ascending.
    fn value_range(&self) -> (f64, f64) {
        let (d0, d1) = self.value.domain();
        (d0.min(d1), d0.max(d1))
    }

    /// A rectangle from (across, along) extents: across the category axis, along the value axis.
    fn rect(&self, (a0, a1): (f64, f64), (v0, v1): (f64, f64)) -> Rect {
        match self.orientation {
            Orientation::Vertical => Rect::new(a0, v0, a1 - a0, v1 - v0),
            Orientation::Horizontal => Rect::new(v0, a0, v1 - v0, a1 - a0),
        }
    }

    /// A point from its position across and along.
    fn point(&self, across: f64, along: f64) -> Point {
        match self.orientation {
            Orientation::Vertical => Point::new(across, along),
            Orientation::Horizontal => Point::new(along, across),
        }
    }

    /// Where a bar goes, in pixels.
    fn place(&self, b: &Bar) -> Placed {
        // Bands by category name: a facet panel's axis may hold categories the panel has no bar for.
        let x = self.categories.get(b.x).and_then(|l| self.band.band_of(l)).unwrap_or(b.x);
        let across = if self.stacked {
            (self.band.start(x), self.band.bandwidth())
        } else {
            bands::dodged(self.band, x, self.groups, b.group)
        };
        let (lo, hi) = self.value_range();
        // The baseline: zero, or the end of the value axis nearest zero when zero is left out.
        let start =
            if b.from == 0.0 { self.value.map(0.0f64.clamp(lo, hi)) } else { self.value.map(b.from.clamp(lo, hi)) };
        // A value beyond the domain is drawn up to the domain's end and marked as cut there.
        let clamped = b.to.clamp(lo, hi);
        let end = self.value.map(clamped);
        let growing = if b.to >= b.from { 1.0 } else { -1.0 };
        let dir = if end != start {
            (end - start).signum()
        } else {
            (self.value.map(1.0) - self.value.map(0.0)).signum() * growing
        };
        let whisker = b.interval.map(|(l, u)| (self.value.map(l.clamp(lo, hi)), self.value.map(u.clamp(lo, hi))));
        Placed { across, start, end, dir, whisker, cut: clamped != b.to }
    }

    /// A label's size along the value axis and across it.
    fn label_extent(&self, text: &str, size: f64) -> (f64, f64) {
        let m = crate::text::measure(text, size);
        let height = m.ascent + m.descent;
        match self.orientation {
            Orientation::Vertical => (height, m.width),
            Orientation::Horizontal => (m.width, height),
        }
    }

    /// Whether a label of `extent` (along, across) fits inside the bar, between its base and
    /// its end or the whisker's near end, whichever is nearer the base.
    fn fits_inside(&self, b: &Bar, p: &Placed, (along, across): (f64, f64)) -> bool {
        if b.value == 0.0 || p.cut {
            return false;
        }
        let room = (p.inner() - p.start) * p.dir;
        across + 2.0 * LABEL_GAP <= p.across.1 && along + 2.0 * LABEL_GAP <= room
    }

    /// The value labels of the bars, and how many were left out because they would overlap
    /// another label or bar, or leave the plot. Stacked segments get a label centred in them
    /// where it fits; other bars inside their end (in black or white, whichever contrasts more
    /// with the fill) or beyond it, in the text colour.
    #[allow(clippy::too_many_arguments)]
    fn labels(
        &self,
        bars: &[Bar],
        placed: &[Placed],
        texts: &[String],
        fills: &[Color],
        position: LabelPosition,
        (size, ink): (f64, Color),
        plot: Rect,
    ) -> (Vec<Item>, usize) {
        let rects: Vec<Rect> = placed
            .iter()
            .map(|p| self.rect((p.across.0, p.across.0 + p.across.1), (p.start.min(p.end), p.start.max(p.end))))
            .collect();
        let mut items: Vec<Item> = Vec::new();
        let mut boxes: Vec<Rect> = Vec::new();
        let mut left_out = 0;
        for (i, ((b, p), text)) in bars.iter().zip(placed).zip(texts).enumerate() {
            if b.value == 0.0 || p.cut {
                continue;
            }
            let extent = self.label_extent(text, size);
            let centre_across = p.across.0 + p.across.1 / 2.0;
            let inside = self.fits_inside(b, p, extent);
            let (along, color) = if self.stacked {
                // A segment's label sits in its middle, where it fits; the others are skipped.
                if !inside {
                    continue;
                }
                ((p.start + p.end) / 2.0, crate::guide::color::text_color_on(fills[i]))
            } else if inside && position != LabelPosition::Outside {
                (p.inner() - p.dir * (LABEL_GAP + extent.0 / 2.0), crate::guide::color::text_color_on(fills[i]))
            } else if position == LabelPosition::Inside {
                left_out += 1;
                continue;
            } else {
                (p.far() + p.dir * (LABEL_GAP + extent.0 / 2.0), ink)
            };
            let label = Text {
                at: self.point(centre_across, along),
                content: text.clone(),
                size,
                anchor: Anchor::Middle,
                baseline: Baseline::Middle,
                angle: 0.0,
                color,
            };
            let bounds = crate::text::bounds(&label);
            let within = bounds.x >= plot.x - 0.5
                && bounds.right() <= plot.right() + 0.5
                && bounds.y >= plot.y - 0.5
                && bounds.bottom() <= plot.bottom() + 0.5;
            // A label beside its bar must not lie on another bar (its colour would be wrong there).
            let on_other_bar = !inside
                && rects.iter().enumerate().any(|(j, r)| j != i && r.w > 0.0 && r.h > 0.0 && r.intersects(&bounds));
            if !within || on_other_bar || boxes.iter().any(|other| crate::text::boxes_overlap(other, &bounds)) {
                left_out += 1;
                continue;
            }
            boxes.push(bounds);
            items.push(Item::new(Role::Annotation, Shape::Text(label), Style::default()).labelled(VALUE_LABEL));
        }
        (items, left_out)
    }
}

impl Placed {
    /// The end of the room inside the bar: its end, or the whisker's end nearer the base.
    fn inner(&self) -> f64 {
        match self.whisker {
            Some((a, b)) => {
                let near = if (a - b) * self.dir > 0.0 { b } else { a };
                if (near - self.end) * self.dir < 0.0 { near } else { self.end }
            }
            None => self.end,
        }
    }

    /// The end of the bar or its whisker farthest from the base.
    fn far(&self) -> f64 {
        match self.whisker {
            Some((a, b)) => {
                let far = if (a - b) * self.dir > 0.0 { a } else { b };
                if (far - self.end) * self.dir > 0.0 { far } else { self.end }
            }
            None => self.end,
        }
    }
}

/// Half the width of a whisker's caps, at most, in pixels.
const CAP_HALF: f64 = 6.0;

/// A whisker across the middle of a bar (`slot`: its start and width across the category
/// axis) from one end of its interval to the other (`ends`, in pixels along the value axis),
/// with a cap at each end.
fn whisker(geo: &Geometry<'_>, (x, w): (f64, f64), (a, b): (f64, f64), color: Color) -> Item {
    let centre = x + w / 2.0;
    let half = (w * 0.25).min(CAP_HALF);
    let mut cmds = vec![PathCmd::MoveTo(geo.point(centre, a)), PathCmd::LineTo(geo.point(centre, b))];
    for end in [a, b] {
        cmds.push(PathCmd::MoveTo(geo.point(centre - half, end)));
        cmds.push(PathCmd::LineTo(geo.point(centre + half, end)));
    }
    Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(color, 1.5))
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

/// The value axis over the bars' extents and their whiskers: zero included unless
/// `zero = false`; a fixed `domain` wins; 0–100 % for normalised stacks. Unless the spec names a
/// title, it says what the bars are: "Sum of COLUMN" when some bar adds up several rows, "Mean
/// of", "Median of", "Rows" for counts, or "Share of … (%)" for normalised stacks; whiskers add
/// what they show ("± 95% CI"), after a title the spec names too.
fn value_axis(
    y_opts: &crate::spec::ChannelOptions,
    bars: &[Bar],
    summed: bool,
    stack: BarStack,
    aggregate: BarAggregate,
    error: Option<Spread>,
) -> PositionAxis {
    // A bar's start counts only when stacked on another: zero is the axis's choice (`zero`).
    let ends = bars
        .iter()
        .map(|b| b.to)
        .chain(bars.iter().filter(|b| b.from != 0.0).map(|b| b.from))
        .chain(bars.iter().filter_map(|b| b.interval).flat_map(|(l, u)| [l, u]));
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
    let field = &y_opts.field;
    let unit =
        if stack == BarStack::Normalize || aggregate == BarAggregate::Count { None } else { y_opts.unit.as_deref() };
    let title = match &y_opts.title {
        Some(t) => {
            let t = title_with_unit(t, unit);
            match error {
                Some(e) => format!("{t}, {} {}", aggregate.name(), e.describe()),
                None => t,
            }
        }
        None => {
            let what = match aggregate {
                _ if stack == BarStack::Normalize => format!("Share of {field} (%)"),
                BarAggregate::Sum if summed => format!("Sum of {field}"),
                BarAggregate::Sum => field.clone(),
                BarAggregate::Mean => format!("Mean of {field}"),
                BarAggregate::Median => format!("Median of {field}"),
                BarAggregate::Count => "Rows".to_string(),
            };
            let what = title_with_unit(&what, unit);
            match error {
                Some(e) => format!("{what} {}", e.describe()),
                None => what,
            }
        }
    };
    PositionAxis {
        title,
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
        totals[b.x] += b.value.abs();
    }
    let (mut up, mut down) = (vec![0.0f64; categories], vec![0.0f64; categories]);
    for b in bars.iter_mut() {
        let scale = if normalize && totals[b.x] > 0.0 { 100.0 / totals[b.x] } else { 1.0 };
        let v = b.value * scale;
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
        totals[b.x] += b.value;
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
pub static KIND: KindInfo = KindInfo::new("bar", &["x", "y", "color"])
    .counting_rows(crate::mark::registry::RowCounting {
        modes: None,
        unless: &["highlight", "tooltip", "facet"],
        on_engine: false,
    })
    .faceted(crate::mark::registry::Faceting::Frame)
    .drawing_annotations();

impl Technique for BarOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.plan)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        // Bars place every x value in a band, numbers included (`grouped::axes` says so).
        crate::mark::grouped::axes(Some(&self.x), &self.y, self.orientation.unwrap_or_default())
    }

    crate::mark::registry::color_key!();
}
