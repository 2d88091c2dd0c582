//! `area`: the area under a series, or series stacked on each other: on zero, normalised to
//! shares of each x's total, centred (silhouette) or as a streamgraph (minimal wiggle).
//!
//! Stacking needs every series at every x: a series missing an x counts as zero there, or with
//! `fill = "linear"` is interpolated inside its own x range; a note says how many values were
//! filled in. Rows sharing an x within a series are summed.

use std::collections::HashMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::data::{Column, Table};
use crate::enrich::stack::{Offset, stack};
use crate::guide::axis::title_with_unit;
use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::Symbol;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode;
use crate::mark::geometry::{Geometry, Plot};
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, categorical, frame};
use crate::scene::{Color, Item, PathCmd, Point, Role, Shape, Stroke, Style};
use crate::spec::{Channel, Chart, ColorChannel, ScaleKind};

/// Options of `kind = "area"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct AreaOptions {
    /// Horizontal position: a numeric or date column (`title`, `unit`, `domain`, ...).
    #[schemars(example = &"date")]
    pub x: Channel,
    /// The height: a numeric column; rows of one series at the same x are summed.
    #[schemars(example = &"count")]
    pub y: Channel,
    /// Split the rows into series by a categorical column, one colour each, with a legend.
    #[serde(default)]
    #[schemars(example = &"series")]
    pub color: Option<ColorChannel>,
    /// How series are stacked: `"zero"` (default: on top of each other from zero),
    /// `"normalize"` (each x's total is 100%), `"center"` (symmetric about zero), `"wiggle"`
    /// (a streamgraph: the baseline that least tilts the layers) or `"none"` (each from zero,
    /// overlapping and translucent).
    #[serde(default)]
    pub stack: Option<StackOffset>,
    /// Order of the series from the bottom: `"legend"` (default: the colour order), `"sum"`
    /// (largest total at the bottom) or `"inside-out"` (largest in the middle, for streamgraphs).
    #[serde(default)]
    pub order: Option<StackOrder>,
    /// Fill opacity, above 0 and at most 1 (default 0.85 stacked, 0.35 with `stack = "none"`).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 1), example = 0.85)]
    pub opacity: Option<f64>,
    /// Area colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
    /// The value of a series at an x where it has no row but other series do: `"zero"`
    /// (default: right for counts and sums, where no row means none) or `"linear"`
    /// (interpolated between the series' neighbouring values, zero outside its own x range:
    /// right for measurements taken at different times).
    #[serde(default)]
    pub fill: Option<GapFill>,
}

/// How a stacked series' missing values are filled.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum GapFill {
    /// Zero.
    #[default]
    Zero,
    /// Linear interpolation inside the series' x range, zero outside.
    Linear,
}

/// How an area chart stacks its series.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum StackOffset {
    /// On top of each other from zero.
    #[default]
    Zero,
    /// Shares of each x's total, in percent.
    Normalize,
    /// Symmetric about zero.
    Center,
    /// A streamgraph baseline (Byron & Wattenberg).
    Wiggle,
    /// Not stacked: each series from zero.
    None,
}

/// The order of stacked series from the bottom.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum StackOrder {
    /// The colour legend's order.
    #[default]
    Legend,
    /// Largest total at the bottom.
    Sum,
    /// Largest total in the middle, smaller ones alternately above and below.
    InsideOut,
}

/// One series on the shared x positions.
struct Series {
    name: String,
    color: Color,
    /// Value at every x position (filled in where the series has no row).
    values: Vec<f64>,
    /// Its rows.
    rows: Vec<u32>,
}

/// Draw an area chart.
pub fn draw(chart: &Chart, options: &AreaOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let (x_opts, y_opts) = (options.x.options(), options.y.options());
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    check_columns(options, x_col, y_col)?;
    if table.rows == 0 {
        return Err(encode::no_rows(chart, table, None));
    }
    let color = crate::mark::bands::grouping_channel(chart, options.color.as_ref(), table, "areas")?;
    let numeric = vec![(x_opts.field.as_str(), x_col), (y_opts.field.as_str(), y_col)];
    let (rows, mut warnings) = encode::drawn_rows(chart, table, numeric, color.as_ref())?;
    let (xv, yv) = (x_col.numbers().unwrap_or(&[]), y_col.numbers().unwrap_or(&[]));
    let offset = options.stack.unwrap_or_default();
    if offset != StackOffset::None
        && let Some(&r) = rows.iter().find(|&&r| yv[r as usize] < 0.0)
    {
        return Err(MarkError::at(
            &["y"],
            format!(
                "`{}` has negative values (row {r}: {}), which stacked areas cannot show",
                y_opts.field, yv[r as usize]
            ),
            "use `stack = \"none\"` to draw each series from zero, or a line chart",
        ));
    }

    let (colors, legend) =
        encode::color_encoding(chart, color.as_ref(), options.mark_color.as_deref(), table, &rows, Symbol::Square)?;
    let (group_of_row, groups) = categorical::row_groups(&colors, color.as_ref(), &rows)?;
    let mut positions: Vec<f64> = rows.iter().map(|&r| xv[r as usize]).collect();
    positions.sort_by(f64::total_cmp);
    positions.dedup();
    // −0 and 0 are one position.
    positions.iter_mut().for_each(|p| *p += 0.0);
    let fill = options.fill.unwrap_or_default();
    let (mut series, filled) = align(&groups, &group_of_row, &rows, (xv, yv), &positions, fill);
    // Said once the spec chooses a fill: the note is for a choice made by default.
    if filled > 0 && options.fill.is_none() {
        let how = match fill {
            GapFill::Zero => "as zero (`fill = \"linear\"` interpolates them instead)",
            GapFill::Linear => "linearly inside each series' own x range and as zero outside it",
        };
        warnings.push(Warning::from(format!(
            "{filled} series values were missing at x positions other series have; filled in {how}"
        )));
    }
    order_series(&mut series, options.order.unwrap_or_default());

    let layers: Vec<Vec<f64>> = series.iter().map(|s| s.values.clone()).collect();
    let bounds = match offset {
        StackOffset::None => layers.iter().map(|l| l.iter().map(|&v| (0.0, v)).collect()).collect(),
        StackOffset::Zero => stack(&layers, &positions, Offset::Zero),
        StackOffset::Normalize => stack(&layers, &positions, Offset::Normalize)
            .into_iter()
            .map(|l| l.into_iter().map(|(a, b)| (100.0 * a, 100.0 * b)).collect())
            .collect(),
        StackOffset::Center => stack(&layers, &positions, Offset::Center),
        StackOffset::Wiggle => stack(&layers, &positions, Offset::Wiggle),
    };

    let x_axis = encode::position_axis("x", &x_opts, x_col, &rows)?;
    let y_axis = value_axis(&y_opts, &bounds, offset);
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, legend.into_iter().collect())?;
    let opacity = options.opacity.unwrap_or(if offset == StackOffset::None { 0.35 } else { 0.85 });
    let to_px = |x: f64, y: f64| Point::new(frame.x.map(x), frame.y.map(y));
    let mut marks = Vec::with_capacity(series.len() * 2);
    for (s, layer) in series.iter().zip(&bounds) {
        let mut cmds: Vec<PathCmd> = Vec::with_capacity(2 * positions.len() + 1);
        for (j, (&x, &(_, y1))) in positions.iter().zip(layer).enumerate() {
            let p = to_px(x, y1);
            cmds.push(if j == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) });
        }
        for (&x, &(y0, _)) in positions.iter().zip(layer).rev() {
            cmds.push(PathCmd::LineTo(to_px(x, y0)));
        }
        cmds.push(PathCmd::Close);
        let label = if s.name.is_empty() { y_opts.field.clone() } else { s.name.clone() };
        let style = Style { fill: Some(s.color.with_opacity(opacity)), stroke: None };
        marks.push(
            Item::new(Role::DataMark, Shape::Path(cmds), style).with_rows(s.rows.clone()).labelled(label.clone()),
        );
        if offset == StackOffset::None {
            // Overlapping areas keep their own top line, so each stays traceable.
            let top: Vec<PathCmd> = positions
                .iter()
                .zip(layer)
                .enumerate()
                .map(
                    |(j, (&x, &(_, y1)))| {
                        if j == 0 { PathCmd::MoveTo(to_px(x, y1)) } else { PathCmd::LineTo(to_px(x, y1)) }
                    },
                )
                .collect();
            let line = Style { fill: None, stroke: Some(Stroke::solid(s.color, 1.5)) };
            marks.push(Item::new(Role::DataMark, Shape::Path(top), line).labelled(format!("{label} (top)")));
        }
    }
    // Stacked heights are sums, not the column's values: a brush selects by x alone then.
    let y_placed = (offset == StackOffset::None).then_some((y_opts.field.as_str(), y_col));
    let geometry = Geometry::of_plot(Plot::of_frame(&frame, Some((&x_opts.field, x_col)), y_placed));
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);
    let x_field = (x_opts.field.as_str(), x_col.is_time());
    let derived = derived_table(x_field, color.as_ref().map(ColorChannel::field), &positions, &series, &bounds);
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// Errors for columns an area chart cannot draw.
fn check_columns(options: &AreaOptions, x_col: &Column, y_col: &Column) -> Result<(), MarkError> {
    encode::require_numeric(
        "x",
        x_col,
        "an area's x positions",
        "use a numeric or date column for x; for categories use a bar chart (stacked bars)",
    )?;
    encode::require_numeric("y", y_col, "an area's height", "use a numeric column for y; put categories in `color`")?;
    if y_col.is_time() {
        return Err(MarkError::at(
            &["y"],
            format!("y column `{}` holds dates or times, which cannot be stacked into areas", y_col.name),
            "use a numeric column for y; put dates on x",
        ));
    }
    match options.y.options().scale {
        None | Some(ScaleKind::Linear) => Ok(()),
        Some(kind) => Err(MarkError::at(
            &["y", "scale"],
            format!("an area is measured from its baseline, which a {} scale does not keep", encode::scale_name(kind)),
            "remove `scale` from y; for values spanning decades use a line chart on a log scale",
        )),
    }
}

/// Every series' value at every x position, filling gaps; and how many values were filled.
fn align(
    groups: &[(String, Color)],
    group_of_row: &[usize],
    rows: &[u32],
    (xv, yv): (&[f64], &[f64]),
    positions: &[f64],
    fill: GapFill,
) -> (Vec<Series>, usize) {
    let index: HashMap<u64, usize> = positions.iter().enumerate().map(|(j, x)| (x.to_bits(), j)).collect();
    let mut sums = vec![vec![None::<f64>; positions.len()]; groups.len()];
    let mut members = vec![Vec::new(); groups.len()];
    for (&r, &g) in rows.iter().zip(group_of_row) {
        let x = xv[r as usize];
        if let (Some(&j), Some(series)) = (index.get(&(x + 0.0).to_bits()), sums.get_mut(g)) {
            let cell = &mut series[j];
            *cell = Some(cell.unwrap_or(0.0) + yv[r as usize]);
            members[g].push(r);
        }
    }
    let mut filled = 0;
    let series = groups
        .iter()
        .zip(sums)
        .zip(members)
        .map(|(((name, color), sums), rows)| {
            let present: Vec<usize> = (0..positions.len()).filter(|&j| sums[j].is_some()).collect();
            let values = (0..positions.len())
                .map(|j| match sums[j] {
                    Some(v) => v,
                    None => {
                        filled += 1;
                        match fill {
                            GapFill::Zero => 0.0,
                            GapFill::Linear => interpolate(&present, &sums, positions, j),
                        }
                    }
                })
                .collect();
            Series { name: name.clone(), color: *color, values, rows }
        })
        .collect();
    (series, filled)
}

/// The value at position `j` between the nearest present positions on either side (linear in
/// x), or zero outside the series' own range.
fn interpolate(present: &[usize], sums: &[Option<f64>], positions: &[f64], j: usize) -> f64 {
    let after = present.partition_point(|&p| p < j);
    match (after.checked_sub(1).and_then(|i| present.get(i)), present.get(after)) {
        (Some(&a), Some(&b)) => {
            let (ya, yb) = (sums[a].unwrap_or(0.0), sums[b].unwrap_or(0.0));
            let t = (positions[j] - positions[a]) / (positions[b] - positions[a]);
            ya + t * (yb - ya)
        }
        _ => 0.0,
    }
}

/// Put the series in stacking order from the bottom.
fn order_series(series: &mut Vec<Series>, order: StackOrder) {
    let total = |s: &Series| s.values.iter().sum::<f64>();
    match order {
        StackOrder::Legend => {}
        StackOrder::Sum => series.sort_by(|a, b| total(b).total_cmp(&total(a))),
        StackOrder::InsideOut => {
            series.sort_by(|a, b| total(b).total_cmp(&total(a)));
            // Largest in the middle: alternate the rest above and below it.
            let mut below = Vec::new();
            let mut above = Vec::new();
            for (i, s) in series.drain(..).enumerate() {
                if i % 2 == 0 { above.push(s) } else { below.push(s) }
            }
            below.reverse();
            series.extend(below);
            series.extend(above);
        }
    }
}

/// The value axis over the stacked bounds: from zero for `zero` and `none` stacks, 0–100 % for
/// normalised ones, the bounds' extent for centred ones; a fixed `domain` wins.
fn value_axis(y_opts: &crate::spec::ChannelOptions, bounds: &[Vec<(f64, f64)>], offset: StackOffset) -> PositionAxis {
    let (lo, hi) = encode::finite_extent(bounds.iter().flatten().flat_map(|&(a, b)| [a, b])).unwrap_or((0.0, 1.0));
    let (mut lo, mut hi) = match offset {
        StackOffset::Normalize => (0.0, 100.0),
        StackOffset::Zero | StackOffset::None => (lo.min(0.0), hi.max(0.0)),
        StackOffset::Center | StackOffset::Wiggle => (lo, hi),
    };
    if let Some([a, b]) = y_opts.domain {
        (lo, hi) = (a, b);
    }
    let name = y_opts.title.clone().unwrap_or_else(|| y_opts.field.clone());
    let title = match offset {
        StackOffset::Normalize => format!("Share of {name} (%)"),
        _ => title_with_unit(&name, y_opts.unit.as_deref()),
    };
    PositionAxis {
        title,
        kind: ScaleKind::Linear,
        domain: Domain::Continuous(lo, if hi > lo { hi } else { lo + 1.0 }),
        nice: offset != StackOffset::Normalize && y_opts.domain.is_none(),
        ticks: y_opts.ticks,
        grid: y_opts.grid.unwrap_or(true),
        inset: 0.0,
    }
}

/// One row per series and x: the x, the series, its value and its band's edges.
fn derived_table(
    (x_field, time): (&str, bool),
    color_field: Option<&str>,
    positions: &[f64],
    series: &[Series],
    bounds: &[Vec<(f64, f64)>],
) -> Derived {
    let (mut x, mut name, mut value, mut y0, mut y1) = (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (s, layer) in series.iter().zip(bounds) {
        for (j, &(a, b)) in layer.iter().enumerate() {
            x.push(positions[j]);
            name.push(s.name.clone());
            value.push(s.values[j]);
            y0.push(a);
            y1.push(b);
        }
    }
    let mut d = Derived::default();
    if time {
        d.push(x_field, DerivedColumn::Text(x.iter().map(|&ms| crate::guide::time::format_timestamp(ms)).collect()));
    } else {
        d.push(x_field, DerivedColumn::Number(x));
    }
    if let Some(field) = color_field {
        d.push(field, DerivedColumn::Text(name));
    }
    d.push("value", DerivedColumn::Number(value));
    d.push("y0", DerivedColumn::Number(y0));
    d.push("y1", DerivedColumn::Number(y1));
    d
}

/// `kind = "area"`.
pub static KIND: KindInfo =
    KindInfo::new("area", &["x", "y", "color"]).faceted(crate::mark::registry::Faceting::Frame).drawing_annotations();

impl Technique for AreaOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        AxisSpec::pair(&self.x, &self.y)
    }

    crate::mark::registry::color_key!();
}
