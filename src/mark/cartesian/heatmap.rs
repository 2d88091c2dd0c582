//! `heatmap`: a category × category matrix of a value, one coloured cell per pair that has rows,
//! with a colour bar, and the value written in each cell where it fits, in black or white,
//! whichever contrasts more with the cell.
//!
//! A cell's value is an aggregate of its rows (`mean` by default, or the row count without
//! `z`); pairs without rows stay empty (the background shows). Rows and columns follow the
//! data's order, their labels' order, or their mean value.

use std::collections::HashMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::data::density::groups::GroupQuery;
use crate::data::density::plan::PlanRows;
use crate::data::{Column, Table};
use crate::guide::axis::title_with_unit;
use crate::guide::color::text_color_on;
use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::Legend;
use crate::guide::scale::Scale;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode::{self, MISSING_LABEL};
use crate::mark::geometry::{Geometry, Plot};
use crate::mark::plan_rows::PlanGroups;
use crate::mark::registry::{AxisSpec, ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, frame};
use crate::scene::{Anchor, Baseline, Item, Rect, Role, Shape, Style, Text};
use crate::spec::{Channel, Chart, ColorChannel, ScaleKind};

/// Options of `kind = "heatmap"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct HeatmapOptions {
    /// The columns of the matrix: a text column, or numbers and dates taken as categories.
    #[schemars(example = &"month")]
    pub x: Channel,
    /// The rows of the matrix: a text column, or numbers and dates taken as categories.
    #[schemars(example = &"year")]
    pub y: Channel,
    /// The value coloured: a numeric column, or `{ field, title, unit, scheme, midpoint }`.
    /// Without it each cell counts its rows.
    #[serde(default)]
    #[schemars(example = &"temp_max")]
    pub z: Option<ColorChannel>,
    /// How a cell's rows make its value: `"mean"` (default), `"sum"`, `"median"`, `"min"`,
    /// `"max"` or `"count"`.
    #[serde(default)]
    pub aggregate: Option<CellAggregate>,
    /// Order of the columns: `"data"` (default: first appearance; numbers ascending),
    /// `"label"` (alphabetical) or `"value"` (highest mean first).
    #[serde(default)]
    pub order_x: Option<CellOrder>,
    /// Order of the rows from the top, as `order_x`.
    #[serde(default)]
    pub order_y: Option<CellOrder>,
    /// Write each cell's value in it: `true`, `false`, or by default where every label fits.
    #[serde(default)]
    pub labels: Option<bool>,
}

/// How a heatmap cell's rows are combined.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum CellAggregate {
    /// The mean.
    #[default]
    Mean,
    /// The sum.
    Sum,
    /// The median.
    Median,
    /// The smallest value.
    Min,
    /// The largest value.
    Max,
    /// The number of rows.
    Count,
}

/// The order of a heatmap's rows or columns.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum CellOrder {
    /// As the data has them (numbers and dates ascending).
    #[default]
    Data,
    /// By label.
    Label,
    /// By mean cell value, highest first.
    Value,
}

/// Most categories on one side of a heatmap.
pub const MAX_CATEGORIES: usize = 500;
/// Font size of cell labels, relative to the chart's font size.
const LABEL_SCALE: f64 = 0.9;

/// The categories of one side: their labels and each row's category.
struct Side {
    labels: Vec<String>,
    of_row: Vec<usize>,
}

/// Draw a heatmap (`plan`: its source's rows, when they stay in the plan and the table holds
/// none).
pub fn draw(
    chart: &Chart,
    options: &HeatmapOptions,
    table: &Table,
    plan: Option<&PlanRows>,
) -> Result<ChartOutput, MarkError> {
    let (x_opts, y_opts) = (options.x.options(), options.y.options());
    encode::column(chart, "x", &x_opts.field, table)?;
    encode::column(chart, "y", &y_opts.field, table)?;
    let z_opts = options.z.as_ref().map(ColorChannel::options);
    let z_col = match &z_opts {
        Some(z) => Some(encode::column(chart, "z", &z.field, table)?),
        None => None,
    };
    let aggregate = match (options.aggregate, z_col) {
        (Some(a), _) => a,
        (None, Some(_)) => CellAggregate::Mean,
        (None, None) => CellAggregate::Count,
    };
    if let (Some(col), true) = (z_col, aggregate != CellAggregate::Count) {
        encode::require_numeric(
            "z",
            col,
            "a cell's colour",
            "colour by a numeric column, or leave `z` out to count rows",
        )?;
    }
    if aggregate != CellAggregate::Count && z_col.is_none() {
        return Err(MarkError::at(
            &["aggregate"],
            "`aggregate` combines the `z` values of a cell's rows, but the chart has no `z`".to_string(),
            "name a numeric column in `z`, or remove `aggregate` to count rows",
        ));
    }
    let plan = plan.filter(|_| table.rows == 0);
    if table.rows == 0 && plan.is_none() {
        return Err(encode::no_rows(chart, table, None));
    }
    // The value, when a cell's rows need a finite one.
    let valued = z_opts.as_ref().filter(|_| aggregate != CellAggregate::Count).map(|z| z.field.as_str());
    // The rows are those of the table, or one per cell of the rows left in the plan.
    let grouped = match plan {
        Some(plan) => {
            let required: Vec<&str> = valued.into_iter().collect();
            let keys = [x_opts.field.as_str(), y_opts.field.as_str()];
            let query = GroupQuery {
                keys: &keys,
                value: valued,
                required: &required,
                median: aggregate == CellAggregate::Median,
            };
            Some(PlanGroups::of(chart, plan, query)?)
        }
        None => None,
    };
    let table = grouped.as_ref().map_or(table, |g| &g.table);
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    let (rows, mut warnings) = match &grouped {
        Some(g) => (g.rows.clone(), g.warnings.clone()),
        None => {
            let numeric: Vec<(&str, &Column)> = valued.zip(z_col).into_iter().collect();
            encode::drawn_rows(chart, table, numeric, None)?
        }
    };

    let mut x_side = side(x_col, &rows, "x")?;
    let mut y_side = side(y_col, &rows, "y")?;
    let mut cells = match &grouped {
        Some(g) => grouped_cells(&x_side, &y_side, &rows, g, aggregate),
        None => cell_values(&x_side, &y_side, &rows, z_col.and_then(Column::numbers).unwrap_or(&[]), aggregate),
    };
    let x_order = order(&x_side, options.order_x.unwrap_or_default(), |i| cells.column_mean(i));
    let y_order = order(&y_side, options.order_y.unwrap_or_default(), |j| cells.row_mean(j));
    x_side = reorder(x_side, &x_order);
    y_side = reorder(y_side, &y_order);
    cells = cells.permuted(&x_order, &y_order);

    let (lo, hi) =
        encode::finite_extent(cells.values.iter().flatten().flatten().map(|c| c.value)).unwrap_or((0.0, 1.0));
    // Facet panels share one colour range.
    let (lo, hi) = chart.panel.as_ref().and_then(|p| p.color).unwrap_or((lo, hi));
    let scheme = z_opts.as_ref().and_then(|z| z.scheme.as_deref());
    let map = encode::continuous_map(&["z", "scheme"], scheme)?;
    let midpoint = z_opts.as_ref().and_then(|z| z.midpoint);
    let (c_lo, c_hi) = encode::color_domain(&map, lo, hi, midpoint);
    let value_name = match (&z_opts, aggregate) {
        (Some(z), _) if z.title.is_some() => title_with_unit(z.title.as_deref().unwrap_or_default(), z.unit.as_deref()),
        (_, CellAggregate::Count) => "Rows".to_string(),
        (Some(z), a) => title_with_unit(&format!("{} of {}", aggregate_name(a), z.field), z.unit.as_deref()),
        (None, _) => "Rows".to_string(),
    };
    let legends = match &z_opts {
        Some(z) if z.legend == Some(false) => Vec::new(),
        _ => vec![Legend::ColorBar { title: value_name.clone(), map: map.clone(), domain: (c_lo, c_hi) }],
    };
    // The first row at the top: the y axis runs upwards, so its categories go in reverse.
    let y_axis_labels: Vec<String> = y_side.labels.iter().rev().cloned().collect();
    let axis = |opts: &crate::spec::ChannelOptions, labels: Vec<String>| PositionAxis {
        title: title_with_unit(opts.title.as_deref().unwrap_or(&opts.field), opts.unit.as_deref()),
        kind: ScaleKind::Band,
        domain: Domain::Categories(labels),
        nice: false,
        ticks: None,
        grid: false,
        inset: 0.0,
    };
    let (frame, theme) =
        frame::cartesian(chart, axis(&x_opts, x_side.labels.clone()), axis(&y_opts, y_axis_labels), legends)?;

    // Cells fill their bands without gaps: bands step evenly across the plot. A facet panel's
    // axes may hold more categories than the panel has, so cells are placed by name.
    let band_count = |scale: &Scale, own: usize| if let Scale::Band(b) = scale { b.len() } else { own };
    let (nx, ny) = (band_count(&frame.x, x_side.labels.len()), band_count(&frame.y, y_side.labels.len()));
    let column_of = |i: usize| match &frame.x {
        Scale::Band(b) => b.band_of(&x_side.labels[i]).unwrap_or(i),
        _ => i,
    };
    // The y bands run upwards; row `j` counts from the top.
    let row_of = |j: usize| match &frame.y {
        Scale::Band(b) => b.band_of(&y_side.labels[j]).map_or(j, |k| ny - 1 - k),
        _ => j,
    };
    let plot = frame.plot;
    let (w, h) = (plot.w / nx as f64, plot.h / ny as f64);
    let label_size = theme.font_size * LABEL_SCALE;
    let decimals = label_decimals(lo, hi, aggregate);
    let texts: Vec<Vec<String>> = cells
        .values
        .iter()
        .map(|row| {
            row.iter().map(|c| c.as_ref().map_or(String::new(), |c| format!("{:.decimals$}", c.value))).collect()
        })
        .collect();
    let fits =
        texts.iter().flatten().all(|t| crate::text::measure(t, label_size).width + 4.0 <= w) && label_size + 2.0 <= h;
    let write_labels = options.labels.unwrap_or(fits);
    let span = (c_hi - c_lo).max(f64::MIN_POSITIVE);
    let mut marks = Vec::new();
    let mut labels = Vec::new();
    for (j, row) in cells.values.iter().enumerate() {
        for (i, cell) in row.iter().enumerate() {
            let Some(Cell { value, n, rows: members }) = cell else { continue };
            let fill = map.at(((value - c_lo) / span).clamp(0.0, 1.0));
            let rect = Rect::new(plot.x + w * column_of(i) as f64, plot.y + h * row_of(j) as f64, w, h);
            let tooltip = format!(
                "{}: {}\n{}: {}\n{value_name}: {value} ({} rows)",
                x_opts.field, x_side.labels[i], y_opts.field, y_side.labels[j], n
            );
            marks.push(
                Item::new(Role::DataMark, Shape::Rect(rect), Style::fill(fill))
                    .with_rows(members.clone())
                    .labelled(format!("{}, {}", x_side.labels[i], y_side.labels[j]))
                    .with_tooltip(tooltip),
            );
            if write_labels {
                let ink = text_color_on(fill);
                let text = Text {
                    at: crate::scene::Point::new(rect.x + w / 2.0, rect.y + h / 2.0),
                    content: texts[j][i].clone(),
                    size: label_size,
                    anchor: Anchor::Middle,
                    baseline: Baseline::Middle,
                    angle: 0.0,
                    color: ink,
                };
                labels.push(Item::new(Role::Annotation, Shape::Text(text), Style::default()).labelled("cell value"));
            }
        }
    }
    marks.extend(labels);
    // Category axes brush their categories; binned axes (labelled by ranges) place no column.
    let geometry =
        Geometry::of_plot(Plot::of_frame(&frame, Some((&x_opts.field, x_col)), Some((&y_opts.field, y_col))));
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);
    let derived = derived_table(&x_opts.field, &y_opts.field, &x_side, &y_side, &cells);
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// Decimals of cell labels: counts none, other values about three significant digits of the
/// largest magnitude, the same for every cell so they compare at a glance.
fn label_decimals(lo: f64, hi: f64, aggregate: CellAggregate) -> usize {
    if aggregate == CellAggregate::Count {
        return 0;
    }
    crate::guide::format::decimals_for_three_digits(lo.abs().max(hi.abs()))
}

/// The word for an aggregate in titles.
fn aggregate_name(a: CellAggregate) -> &'static str {
    match a {
        CellAggregate::Mean => "Mean",
        CellAggregate::Sum => "Sum",
        CellAggregate::Median => "Median",
        CellAggregate::Min => "Min",
        CellAggregate::Max => "Max",
        CellAggregate::Count => "Count",
    }
}

/// The categories of one side over `rows`: text in first-appearance order (missing last),
/// numbers and dates ascending.
fn side(column: &Column, rows: &[u32], key: &str) -> Result<Side, MarkError> {
    let mut index: HashMap<String, usize> = HashMap::new();
    let mut labels: Vec<String> = Vec::new();
    let mut of_row = Vec::with_capacity(rows.len());
    let numbers = column.numbers();
    let mut keyed: Vec<(f64, String)> = Vec::new();
    for &r in rows {
        let label = match (numbers, column.categories()) {
            (Some(v), _) => {
                let x = v.get(r as usize).copied().unwrap_or(f64::NAN);
                if x.is_finite() {
                    crate::mark::tooltip::cell_text(column, r as usize)
                } else {
                    MISSING_LABEL.to_string()
                }
            }
            (None, Some(cats)) => cats.value(r as usize).unwrap_or(MISSING_LABEL).to_string(),
            (None, None) => MISSING_LABEL.to_string(),
        };
        let next = labels.len();
        let k = *index.entry(label.clone()).or_insert_with(|| {
            let sort_key = numbers.and_then(|v| v.get(r as usize).copied()).unwrap_or(f64::INFINITY);
            keyed.push((sort_key, label.clone()));
            next
        });
        if k == labels.len() {
            labels.push(label);
        }
        of_row.push(k);
        if labels.len() > MAX_CATEGORIES {
            return Err(MarkError::at(
                &[key],
                format!(
                    "`{}` has more than {MAX_CATEGORIES} distinct values; a heatmap draws one cell per pair",
                    column.name
                ),
                "aggregate or bin the column first (a `bin` transform), or use `image` for a numeric grid",
            ));
        }
    }
    let mut side = Side { labels, of_row };
    if numbers.is_some() {
        // Numbers and dates ascending; a missing value last.
        let mut by_value: Vec<usize> = (0..side.labels.len()).collect();
        by_value.sort_by(|&a, &b| keyed[a].0.total_cmp(&keyed[b].0));
        side = reorder(side, &by_value);
    } else if let Some(missing) = side.labels.iter().position(|l| l == MISSING_LABEL) {
        let mut order: Vec<usize> = (0..side.labels.len()).filter(|&i| i != missing).collect();
        order.push(missing);
        side = reorder(side, &order);
    }
    Ok(side)
}

/// `side` with its categories in `order` (old indices, new order).
fn reorder(side: Side, order: &[usize]) -> Side {
    let mut new_of_old = vec![0; order.len()];
    for (new, &old) in order.iter().enumerate() {
        new_of_old[old] = new;
    }
    Side {
        labels: order.iter().map(|&old| side.labels[old].clone()).collect(),
        of_row: side.of_row.iter().map(|&old| new_of_old[old]).collect(),
    }
}

/// The value and rows of every cell, `values[row][column]`; `None` for a cell without rows.
struct Cells {
    values: Vec<Vec<Option<Cell>>>,
}

/// One cell: its value, how many rows it combines, and those rows of the source's table (none
/// when they stay in the plan).
struct Cell {
    value: f64,
    n: usize,
    rows: Vec<u32>,
}

impl Cells {
    fn row_mean(&self, j: usize) -> f64 {
        mean(self.values[j].iter().flatten().map(|c| c.value))
    }

    fn column_mean(&self, i: usize) -> f64 {
        mean(self.values.iter().filter_map(|row| row[i].as_ref().map(|c| c.value)))
    }

    /// The cells with columns and rows in the orders given (old indices, new order).
    fn permuted(mut self, x_order: &[usize], y_order: &[usize]) -> Cells {
        let values = y_order
            .iter()
            .map(|&j| {
                let mut row = std::mem::take(&mut self.values[j]);
                x_order.iter().map(|&i| row[i].take()).collect()
            })
            .collect();
        Cells { values }
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 { f64::NEG_INFINITY } else { sum / n as f64 }
}

/// Each cell's aggregate over its rows.
fn cell_values(x: &Side, y: &Side, rows: &[u32], z: &[f64], aggregate: CellAggregate) -> Cells {
    let mut members = vec![vec![Vec::new(); x.labels.len()]; y.labels.len()];
    for (k, &r) in rows.iter().enumerate() {
        members[y.of_row[k]][x.of_row[k]].push(r);
    }
    let values = members
        .into_iter()
        .map(|row| {
            row.into_iter()
                .map(|rows| {
                    if rows.is_empty() {
                        return None;
                    }
                    let mut v: Vec<f64> = rows.iter().filter_map(|&r| z.get(r as usize).copied()).collect();
                    let value = match aggregate {
                        CellAggregate::Count => rows.len() as f64,
                        CellAggregate::Sum => v.iter().sum(),
                        CellAggregate::Mean => v.iter().sum::<f64>() / v.len().max(1) as f64,
                        CellAggregate::Min => v.iter().copied().fold(f64::INFINITY, f64::min),
                        CellAggregate::Max => v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                        CellAggregate::Median => {
                            v.sort_by(f64::total_cmp);
                            let n = v.len();
                            if n % 2 == 1 { v[n / 2] } else { (v[n / 2 - 1] + v[n / 2]) / 2.0 }
                        }
                    };
                    Some(Cell { value, n: rows.len(), rows })
                })
                .collect()
        })
        .collect();
    Cells { values }
}

/// Each cell's aggregate from the statistics of its group of rows left in the plan (`rows`: the
/// groups, in the order the sides' `of_row` follow).
fn grouped_cells(x: &Side, y: &Side, rows: &[u32], groups: &PlanGroups, aggregate: CellAggregate) -> Cells {
    let mut values: Vec<Vec<Option<Cell>>> =
        (0..y.labels.len()).map(|_| (0..x.labels.len()).map(|_| None).collect()).collect();
    for (k, &r) in rows.iter().enumerate() {
        let Some(s) = groups.summary(r) else { continue };
        let value = match aggregate {
            CellAggregate::Count => s.n as f64,
            CellAggregate::Sum => s.sum,
            CellAggregate::Mean => s.mean,
            CellAggregate::Min => s.min,
            CellAggregate::Max => s.max,
            CellAggregate::Median => s.median,
        };
        values[y.of_row[k]][x.of_row[k]] = Some(Cell { value, n: s.n, rows: Vec::new() });
    }
    Cells { values }
}

/// The order of one side's categories (old indices in new order).
fn order(side: &Side, how: CellOrder, mean_of: impl Fn(usize) -> f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..side.labels.len()).collect();
    match how {
        CellOrder::Data => {}
        CellOrder::Label => order.sort_by(|&a, &b| side.labels[a].cmp(&side.labels[b])),
        CellOrder::Value => order.sort_by(|&a, &b| mean_of(b).total_cmp(&mean_of(a))),
    }
    order
}

/// One row per cell with rows: its x and y categories, value and row count.
fn derived_table(x_field: &str, y_field: &str, x: &Side, y: &Side, cells: &Cells) -> Derived {
    let (mut xs, mut ys, mut values, mut counts) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (j, row) in cells.values.iter().enumerate() {
        for (i, cell) in row.iter().enumerate() {
            if let Some(cell) = cell {
                xs.push(x.labels[i].clone());
                ys.push(y.labels[j].clone());
                values.push(cell.value);
                counts.push(cell.n as f64);
            }
        }
    }
    let mut d = Derived::default();
    d.push(x_field, DerivedColumn::Text(xs));
    d.push(y_field, DerivedColumn::Text(ys));
    d.push("value", DerivedColumn::Number(values));
    d.push("rows", DerivedColumn::Number(counts));
    d
}

/// `kind = "heatmap"`.
pub static KIND: KindInfo = KindInfo::new("heatmap", &["x", "y", "z"])
    .counting_rows(crate::mark::registry::RowCounting { modes: None, unless: &["tooltip", "facet"], on_engine: false })
    .faceted(crate::mark::registry::Faceting::Frame)
    .drawing_annotations();

impl Technique for HeatmapOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.plan)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        let mut axes = AxisSpec::pair(&self.x, &self.y);
        axes.iter_mut().for_each(|a| a.options.scale = Some(ScaleKind::Band));
        axes
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        self.z.as_ref().map_or_else(Vec::new, ColourSpec::z)
    }
}
