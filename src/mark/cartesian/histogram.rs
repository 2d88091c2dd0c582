//! `histogram`: the distribution of one numeric column as bars over equal-width bins.
//!
//! The bins come from a rule (numpy's `auto`, Freedman–Diaconis, Sturges), a count or a width,
//! and are snapped to round numbers unless `nice = false`, which gives numpy's own edges (from
//! the minimum to the maximum). Bars show counts, percentages or densities, optionally
//! cumulative; a categorical `color` splits them into groups drawn stacked, layered or side by
//! side. A selection is drawn over the whole distribution in grey, as the splom's diagonal does.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::data::density::Bins as TallyBins;
use crate::data::density::plan::PlanRows;
use crate::data::density::tally::Tally;
use crate::data::transform::bin::Bins;
use crate::data::{Column, Table};
use crate::enrich::histogram::{BinRule, OUTSIDE, bin_count_of, bins_of_rows, equal_edges, stepped_edges};
use crate::guide::axis::title_with_unit;
use crate::guide::format::format_value;
use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode;
use crate::mark::geometry::{Geometry, Plot};
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, categorical, frame, highlight};
use crate::scene::{Color, Item, LineBatch, PerPoint, Point, Rect, Role, Shape, Stroke, Style};
use crate::selection::Highlight;
use crate::spec::{Channel, Chart, ColorChannel, ScaleKind};

/// Options of `kind = "histogram"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct HistogramOptions {
    /// The numeric column to bin: a column name or a table with `field`, `title`, `unit`,
    /// `domain` (bin only this range; rows outside it are left out with a note), `ticks`, `grid`.
    #[schemars(example = &"temp_max")]
    pub x: Channel,
    /// How many bins: `"auto"` (default: the larger count of Freedman–Diaconis and Sturges, as
    /// numpy's `bins="auto"`), `"fd"` (Freedman–Diaconis: width 2·IQR·n^(−1/3)), `"sturges"`
    /// (log2 n + 1), or a count from 1 to 1000. With `nice` (default) the count is an upper
    /// bound and the edges are round numbers.
    #[serde(default)]
    #[schemars(example = &"fd")]
    pub bins: Option<BinCount>,
    /// Bin width in the column's units (instead of `bins`); at most 1000 bins.
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0), example = 0.5)]
    pub step: Option<f64>,
    /// Snap the bins to round numbers (default true); `false` spaces them evenly from the
    /// smallest to the largest value, as numpy's `histogram` does.
    #[serde(default)]
    pub nice: Option<bool>,
    /// What a bar's height shows: `"count"` (default), `"percent"` of the rows, or `"density"`
    /// (count / (rows × bin width), so the bars' area is 1).
    #[serde(default)]
    pub stat: Option<HistogramStat>,
    /// Accumulate the bars from left to right; with `stat = "density"` the last bar reaches 1
    /// (the cumulative proportion).
    #[serde(default)]
    pub cumulative: Option<bool>,
    /// Split the bars into groups by a categorical column, with a legend.
    #[serde(default)]
    #[schemars(example = &"weather")]
    pub color: Option<ColorChannel>,
    /// How groups share a bin: `"stack"` (default: on top of each other, percentages and
    /// densities of all rows), `"layer"` (overlapping and translucent, each group's percentages
    /// and densities of its own rows) or `"dodge"` (side by side, as `"layer"`).
    #[serde(default)]
    pub position: Option<GroupPosition>,
    /// Draw a rug: a short tick at each value along the bottom of the plot.
    #[serde(default)]
    pub rug: Option<bool>,
    /// Bar colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
    /// Opacity of layered bars, above 0 and at most 1 (default 0.5 with `position = "layer"`, else 1).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 1), example = 0.5)]
    pub opacity: Option<f64>,
}

/// The number of bins: a rule or a count.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum BinCount {
    /// At most this many bins (1 to 1000).
    Count(#[schemars(range(min = 1, max = 1000))] u32),
    /// A rule for the count.
    Rule(BinRuleName),
}

/// Rules for the number of bins.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum BinRuleName {
    /// The larger count of Freedman–Diaconis and Sturges (numpy's `"auto"`).
    Auto,
    /// Freedman–Diaconis: bin width 2·IQR·n^(−1/3).
    Fd,
    /// Sturges: log2 n + 1 bins.
    Sturges,
}

/// What a histogram bar's height shows.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum HistogramStat {
    /// Rows in the bin.
    #[default]
    Count,
    /// Percent of the rows.
    Percent,
    /// Rows / (all rows × bin width): the bars' total area is 1.
    Density,
}

/// How the groups of a histogram share a bin.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum GroupPosition {
    /// On top of each other.
    #[default]
    Stack,
    /// Overlapping, translucent.
    Layer,
    /// Side by side within the bin.
    Dodge,
}

/// The most bins a histogram draws.
pub const MAX_BINS: usize = 1000;
/// Bars at least this wide (pixels) are drawn with a one-pixel gap between them.
const GAP_FROM: f64 = 4.0;
/// Bins narrower than this many pixels get a note.
const NARROW_BIN: f64 = 1.5;
/// Height of a rug tick, in pixels.
const RUG_TICK: f64 = 7.0;
/// Colour of rug ticks: dark enough to show on the bars they overlap.
const RUG_SHADE: Color = Color::rgb(0x22, 0x22, 0x22);

/// The binned rows of a histogram: the edges, and per group the rows in each bin.
struct Binned {
    edges: Vec<f64>,
    /// `rows[g][k]`: the rows of group `g` in bin `k` (none listed when the rows stay in their
    /// source's plan and were only counted).
    rows: Vec<Vec<Vec<u32>>>,
    /// `counts[g][k]`: how many rows of group `g` lie in bin `k`.
    counts: Vec<Vec<usize>>,
}

impl Binned {
    fn bins(&self) -> usize {
        self.edges.len() - 1
    }

    fn width(&self, k: usize) -> f64 {
        self.edges[k + 1] - self.edges[k]
    }

    /// Rows of group `g` over all bins.
    fn group_size(&self, g: usize) -> usize {
        self.counts[g].iter().sum()
    }
}

/// How bar heights are computed from counts.
#[derive(Clone, Copy)]
struct Heights {
    stat: HistogramStat,
    cumulative: bool,
}

impl Heights {
    /// The heights of one group's bars from its `counts` per bin, normalised by `total` rows.
    fn of(&self, counts: &[usize], widths: &[f64], total: usize) -> Vec<f64> {
        let total = total.max(1) as f64;
        let mut running = 0.0;
        counts
            .iter()
            .zip(widths)
            .map(|(&c, &w)| {
                let c = c as f64;
                if self.cumulative {
                    running += c;
                    match self.stat {
                        HistogramStat::Count => running,
                        HistogramStat::Percent => 100.0 * running / total,
                        HistogramStat::Density => running / total,
                    }
                } else {
                    match self.stat {
                        HistogramStat::Count => c,
                        HistogramStat::Percent => 100.0 * c / total,
                        HistogramStat::Density => c / (total * w),
                    }
                }
            })
            .collect()
    }

    /// The value axis title (`per_group`: percentages and densities are of each group's rows).
    fn title(&self, per_group: bool, unit: Option<&str>) -> String {
        let of = if per_group { " of group" } else { "" };
        match (self.stat, self.cumulative) {
            (HistogramStat::Count, false) => "Count".to_string(),
            (HistogramStat::Count, true) => "Cumulative count".to_string(),
            (HistogramStat::Percent, false) => format!("Percent{of}"),
            (HistogramStat::Percent, true) => format!("Cumulative percent{of}"),
            (HistogramStat::Density, false) => match unit {
                Some(u) => format!("Density{of} (per {u})"),
                None => format!("Density{of}"),
            },
            (HistogramStat::Density, true) => format!("Cumulative proportion{of}"),
        }
    }
}

/// Draw a histogram of the rows of `table`, or of the rows left in the source's `plan` (then
/// `table` has the columns and no rows, and the bins are counted by streaming scans).
pub fn draw(
    chart: &Chart,
    options: &HistogramOptions,
    table: &Table,
    highlight: Option<&Highlight>,
    plan: Option<&PlanRows>,
) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    check_column(options, x_col)?;
    let counted = plan.map(|plan| counted_bins(chart, options, plan)).transpose()?;
    if counted.is_none() && table.rows == 0 {
        return Err(encode::no_rows(chart, table, None));
    }
    let color = crate::mark::bands::grouping_channel(chart, options.color.as_ref(), table, "histogram bars")?;
    let values = x_col.numbers().unwrap_or(&[]);
    let (rows, mut warnings) = match &counted {
        Some((_, warnings)) => (Vec::new(), warnings.clone()),
        None => {
            let (mut rows, mut warnings) =
                encode::drawn_rows(chart, table, vec![(x_opts.field.as_str(), x_col)], color.as_ref())?;
            // Rows outside a fixed domain are not binned.
            if let Some([a, b]) = x_opts.domain {
                let (lo, hi) = (a.min(b), a.max(b));
                let before = rows.len();
                rows.retain(|&r| values.get(r as usize).is_some_and(|v| (lo..=hi).contains(v)));
                if rows.is_empty() {
                    return Err(empty_domain(&x_opts.field, lo, hi));
                }
                warnings.extend(Warning::outside_domain(&x_opts.field, before - rows.len(), before, [lo, hi]));
            }
            (rows, warnings)
        }
    };

    let (colors, color_legend) =
        encode::color_encoding(chart, color.as_ref(), options.mark_color.as_deref(), table, &rows, Symbol::Square)?;
    let (group_of_row, groups) = categorical::row_groups(&colors, color.as_ref(), &rows)?;
    let group_colors: Vec<Color> = groups.iter().map(|(_, c)| *c).collect();
    let ng = groups.len();
    let binned = match counted {
        Some((binned, _)) => binned,
        None => bin_rows(edges_of_rows(options, values, &rows, x_opts.domain)?, values, &rows, &group_of_row, ng),
    };

    let position = if ng > 1 { options.position.unwrap_or_default() } else { GroupPosition::Stack };
    let per_group = position != GroupPosition::Stack;
    let heights = Heights { stat: options.stat.unwrap_or_default(), cumulative: options.cumulative.unwrap_or(false) };
    let widths: Vec<f64> = (0..binned.bins()).map(|k| binned.width(k)).collect();
    let total_rows: usize = (0..ng).map(|g| binned.group_size(g)).sum();
    let norm = |g: usize| if per_group { binned.group_size(g) } else { total_rows };
    let counts_of = |g: usize, selected: Option<&Highlight>| -> Vec<usize> {
        match selected {
            None => binned.counts[g].clone(),
            Some(h) => binned.rows[g].iter().map(|b| b.iter().filter(|&&r| h.contains(r)).count()).collect(),
        }
    };
    let group_heights: Vec<Vec<f64>> = (0..ng).map(|g| heights.of(&counts_of(g, None), &widths, norm(g))).collect();

    let top = match position {
        GroupPosition::Stack => {
            (0..binned.bins()).map(|k| group_heights.iter().map(|h| h[k]).sum::<f64>()).fold(0.0, f64::max)
        }
        _ => group_heights.iter().flatten().copied().fold(0.0, f64::max),
    };
    let x_axis = PositionAxis {
        title: title_with_unit(x_opts.title.as_deref().unwrap_or(&x_opts.field), x_opts.unit.as_deref()),
        kind: ScaleKind::Linear,
        domain: Domain::Continuous(binned.edges[0], binned.edges[binned.bins()]),
        nice: false,
        ticks: x_opts.ticks,
        grid: x_opts.grid.unwrap_or(false),
        inset: 0.0,
    };
    let y_axis = PositionAxis {
        title: heights.title(per_group, x_opts.unit.as_deref()),
        kind: ScaleKind::Linear,
        domain: Domain::Continuous(0.0, if top > 0.0 { top } else { 1.0 }),
        nice: true,
        ticks: None,
        grid: true,
        inset: 0.0,
    };
    let mut legends: Vec<Legend> = color_legend.into_iter().collect();
    if let Some(h) = highlight {
        legends.push(highlight::legend(h, &rows, Symbol::Square));
    }
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, legends)?;

    let opacity = options.opacity.unwrap_or(if position == GroupPosition::Layer { 0.5 } else { 1.0 });
    let stat_name = heights.title(per_group, None).to_lowercase();
    let bars = BarLayout {
        frame: &frame,
        binned: &binned,
        position,
        ng,
        field: &x_opts.field,
        group: color.as_ref().map(|c| (c.field(), groups.as_slice())),
        stat_name: &stat_name,
    };
    let mut marks = Vec::new();
    match highlight {
        Some(h) => {
            // The whole distribution in grey, the selection's part of it in colour.
            let whole: Vec<Vec<f64>> = group_heights.clone();
            marks.extend(bars.items(&whole, &|_| highlight::CONTEXT, 1.0, None, "all rows"));
            let selected: Vec<Vec<f64>> =
                (0..ng).map(|g| heights.of(&counts_of(g, Some(h)), &widths, norm(g))).collect();
            marks.extend(bars.items(&selected, &|g| group_colors[g], opacity, Some(h), "selected"));
        }
        None => marks.extend(bars.items(&group_heights, &|g| group_colors[g], opacity, None, "")),
    }
    if options.rug == Some(true) {
        marks.extend(rug(&frame, values, &rows, &group_of_row, &group_colors));
    }
    let narrowest = (0..binned.bins())
        .map(|k| (frame.x.map(binned.edges[k + 1]) - frame.x.map(binned.edges[k])).abs() / ng_side(position, ng))
        .fold(f64::INFINITY, f64::min);
    if narrowest < NARROW_BIN {
        warnings.push(Warning::from(format!(
            "{} bins are {narrowest:.1} px wide, too narrow to see; use fewer `bins`, a wider `step`, or a wider `size`",
            binned.bins()
        )));
    }
    let geometry = Geometry::of_plot(Plot::of_frame(&frame, Some((&x_opts.field, x_col)), None));
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);
    let derived = derived_table(&binned, &group_heights, color.as_ref().map(|c| (c.field(), groups.as_slice())));
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// How many bars share a bin side by side.
fn ng_side(position: GroupPosition, ng: usize) -> f64 {
    if position == GroupPosition::Dodge { ng.max(1) as f64 } else { 1.0 }
}

/// Errors for a column or scale a histogram cannot bin.
fn check_column(options: &HistogramOptions, column: &Column) -> Result<(), MarkError> {
    encode::require_numeric(
        "x",
        column,
        "binning",
        "bin a numeric column; to count the rows of each category use a bar chart with an `aggregate` transform",
    )?;
    if column.is_time() {
        return Err(MarkError::at(
            &["x"],
            format!("x column `{}` holds dates or times, which a histogram does not bin", column.name),
            "count rows per period with a bar or line chart over a `timeunit` transform, or bin a numeric column",
        ));
    }
    match options.x.options().scale {
        None | Some(ScaleKind::Linear) => {}
        Some(kind) => {
            return Err(MarkError::at(
                &["x", "scale"],
                format!(
                    "a histogram's bins are equal widths on a linear axis, not a {} scale",
                    encode::scale_name(kind)
                ),
                "remove `scale`; for values spanning decades, bin their logarithm (a `calculate` transform with log10)",
            ));
        }
    }
    if options.bins.is_some() && options.step.is_some() {
        return Err(MarkError::at(
            &["step"],
            "`bins` and `step` both set the bins".to_string(),
            "keep one: `bins` for a count or rule, `step` for a bin width",
        ));
    }
    Ok(())
}

/// The options with the bins of the whole table fixed (a step, no rounding, and the edges'
/// span as the x domain), so that every facet panel bins its rows alike.
fn shared_bins(chart: &Chart, options: &HistogramOptions, table: &Table) -> Result<HistogramOptions, MarkError> {
    let mut x_opts = options.x.options();
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    check_column(options, x_col)?;
    let values = x_col.numbers().unwrap_or(&[]);
    let rows: Vec<u32> = (0..table.rows as u32)
        .filter(|&r| values.get(r as usize).is_some_and(|v| v.is_finite()))
        .filter(|&r| x_opts.domain.is_none_or(|[a, b]| (a.min(b)..=a.max(b)).contains(&values[r as usize])))
        .collect();
    let edges = edges_of_rows(options, values, &rows, x_opts.domain)?;
    let (Some(&first), Some(&last)) = (edges.first(), edges.last()) else { return Ok(options.clone()) };
    let mut shared = options.clone();
    if edges.len() >= 2 {
        shared.step = Some(edges[1] - edges[0]);
        shared.bins = None;
        shared.nice = Some(false);
        x_opts.domain = Some([first, last]);
        shared.x = Channel::Detailed(x_opts);
    }
    Ok(shared)
}

/// The bin edges of the finite `values` at `rows`, over the domain or their extent.
fn edges_of_rows(
    options: &HistogramOptions,
    values: &[f64],
    rows: &[u32],
    domain: Option<[f64; 2]>,
) -> Result<Vec<f64>, MarkError> {
    let (lo, hi) = match domain {
        Some([a, b]) => (a.min(b), a.max(b)),
        None => encode::extent(values, rows).unwrap_or((0.0, 1.0)),
    };
    let mut kept: Vec<f64> = rows.iter().filter_map(|&r| values.get(r as usize).copied()).collect();
    edges(options, lo, hi, kept.len(), || crate::enrich::distribution::quartiles_in_place(&mut kept))
}

/// The bin edges over `[lo, hi]` (the domain, or the values' extent) for `n` values whose
/// quartiles `quartiles` gives: from `step` or the bin rule, nice or exact.
fn edges(
    options: &HistogramOptions,
    lo: f64,
    hi: f64,
    n: usize,
    quartiles: impl FnOnce() -> Option<(f64, f64)>,
) -> Result<Vec<f64>, MarkError> {
    let nice = options.nice.unwrap_or(true);
    if let Some(step) = options.step {
        // A span that is a whole number of steps up to rounding is that many bins.
        let bins = ((hi - lo) / step - 1e-9).ceil();
        if !(bins <= MAX_BINS as f64) {
            return Err(MarkError::at(
                &["step"],
                format!("a step of {step} makes {bins} bins over [{lo}, {hi}]; a histogram draws at most {MAX_BINS}"),
                "use a wider `step`, or `bins` for a count",
            ));
        }
        return Ok(if nice {
            let b = Bins::nice(lo, hi, MAX_BINS as u32, Some(step));
            stepped_edges(b.start, b.stop, b.step)
        } else {
            stepped_edges(lo, lo + bins.max(1.0) * step, step)
        });
    }
    let rule = match options.bins {
        None | Some(BinCount::Rule(BinRuleName::Auto)) => BinRule::Auto,
        Some(BinCount::Rule(BinRuleName::Fd)) => BinRule::FreedmanDiaconis,
        Some(BinCount::Rule(BinRuleName::Sturges)) => BinRule::Sturges,
        Some(BinCount::Count(c)) => BinRule::Count(c as usize),
    };
    let count = bin_count_of(rule, n, quartiles, lo, hi, MAX_BINS);
    Ok(if nice {
        let b = Bins::nice(lo, hi, count as u32, None);
        stepped_edges(b.start, b.stop, b.step)
    } else {
        equal_edges(lo, hi, count)
    })
}

/// The rows of each group in each bin.
fn bin_rows(edges: Vec<f64>, values: &[f64], rows: &[u32], group_of_row: &[usize], groups: usize) -> Binned {
    let bins = edges.len() - 1;
    let bin_of_row = bins_of_rows(&edges, values, rows);
    // Count first, so that each bin's rows are allocated once.
    let mut sizes = vec![vec![0usize; bins]; groups];
    for (&k, &g) in bin_of_row.iter().zip(group_of_row) {
        if k != OUTSIDE && g < groups {
            sizes[g][k as usize] += 1;
        }
    }
    let mut binned: Vec<Vec<Vec<u32>>> =
        sizes.iter().map(|group| group.iter().map(|&n| Vec::with_capacity(n)).collect()).collect();
    for ((&r, &k), &g) in rows.iter().zip(&bin_of_row).zip(group_of_row) {
        if k != OUTSIDE && g < groups {
            binned[g][k as usize].push(r);
        }
    }
    let counts = binned.iter().map(|group| group.iter().map(Vec::len).collect()).collect();
    Binned { edges, rows: binned, counts }
}

/// The bins of a histogram whose rows stay in their source's plan, counted by streaming scans
/// (the extent unless a domain is given, a first tally, the quartiles when the rule needs them,
/// the counts): the edges and counts the same rows give in memory, and the same warnings.
fn counted_bins(
    chart: &Chart,
    options: &HistogramOptions,
    plan: &PlanRows,
) -> Result<(Binned, Vec<Warning>), MarkError> {
    let x_opts = options.x.options();
    let field = x_opts.field.as_str();
    let scanned = |message: String| {
        MarkError::at(&["data"], message, "`dataink data SPEC NAME` shows the rows after the source's transforms")
    };
    let extent = match x_opts.domain {
        Some([a, b]) => Some((a.min(b), a.max(b))),
        None => plan.extent(field, field, [false, false]).map_err(scanned)?.x,
    };
    let (lo, hi) = extent.unwrap_or((0.0, 1.0));
    // A count or a width needs only the range; the rules size the bins by the values' number
    // (and quartiles), which a first tally gives.
    let by_values = options.step.is_none() && !matches!(options.bins, Some(BinCount::Count(_)));
    let edges = if by_values {
        let tally = plan.opening_tally(field, (lo, hi)).map_err(scanned)?;
        let n = placed_or_error(chart, field, plan, &tally, (lo, hi))?;
        let mut failed = None;
        let quartiles = || match crate::mark::plan_rows::quartiles(plan, field, &tally) {
            Ok(q) => Some(q),
            Err(e) => {
                failed = Some(e);
                None
            }
        };
        let edges = edges(options, lo, hi, n, quartiles)?;
        if let Some(message) = failed {
            return Err(scanned(message));
        }
        edges
    } else {
        edges(options, lo, hi, 0, || None)?
    };
    let bins =
        TallyBins::from_edges(edges.clone()).ok_or_else(|| scanned(format!("the bins of `{field}` span no range")))?;
    let counted = plan.tally(field, vec![Tally::new(bins).keeping(lo, hi)]).map_err(scanned)?.remove(0);
    let n = placed_or_error(chart, field, plan, &counted, (lo, hi))?;
    let mut warnings: Vec<Warning> = dropped_rows(chart, field, plan, &counted).into_iter().collect();
    warnings.extend(Warning::outside_domain(field, counted.outside as usize, n + counted.outside as usize, [lo, hi]));
    let counts: Vec<usize> = counted.counts().into_iter().map(|c| c as usize).collect();
    let rows = vec![vec![Vec::new(); counts.len()]];
    Ok((Binned { edges, rows, counts: vec![counts] }, warnings))
}

/// The shared warning for the rows `tally` found no value in (missing or not finite), if any.
fn dropped_rows(chart: &Chart, field: &str, plan: &PlanRows, tally: &Tally) -> Option<Warning> {
    let dropped = (tally.missing + tally.infinite) as usize;
    (dropped > 0).then(|| Warning::DroppedRows {
        chart: chart.name.clone(),
        dropped,
        rows: plan.rows() as usize,
        columns: vec![crate::mark::warning::ColumnLoss {
            field: field.to_string(),
            missing: tally.missing as usize,
            infinite: tally.infinite as usize,
            non_positive: 0,
        }],
    })
}

/// How many values `tally` (over the histogram's range `[lo, hi]`) placed; the error a table
/// of the same rows gives when it placed none.
fn placed_or_error(
    chart: &Chart,
    field: &str,
    plan: &PlanRows,
    tally: &Tally,
    (lo, hi): (f64, f64),
) -> Result<usize, MarkError> {
    match tally.placed() as usize {
        0 if tally.outside > 0 => Err(empty_domain(field, lo, hi)),
        0 => Err(encode::no_rows_of(chart, plan.rows() as usize, dropped_rows(chart, field, plan, tally).as_ref())),
        n => Ok(n),
    }
}

/// The error for a domain that holds none of the values.
fn empty_domain(field: &str, lo: f64, hi: f64) -> MarkError {
    MarkError::at(
        &["x", "domain"],
        format!("no value of `{field}` lies in the domain [{lo}, {hi}]"),
        "widen `domain` to cover the data, or remove it",
    )
}

/// Where the bars of a histogram go.
struct BarLayout<'a> {
    frame: &'a crate::guide::layout::Frame,
    binned: &'a Binned,
    position: GroupPosition,
    ng: usize,
    /// The binned column, for hover texts.
    field: &'a str,
    /// The colour channel's field and the groups' labels, for hover texts.
    group: Option<(&'a str, &'a [(String, Color)])>,
    /// What the heights are, for hover texts (`count`, `percent`, `density`, ...).
    stat_name: &'a str,
}

impl BarLayout<'_> {
    /// The bars of `heights[g][k]`, coloured by `color(g)`; with a selection only its rows are
    /// attached. `what` is added to each bar's label.
    fn items(
        &self,
        heights: &[Vec<f64>],
        color: &dyn Fn(usize) -> Color,
        opacity: f64,
        selected: Option<&Highlight>,
        what: &str,
    ) -> Vec<Item> {
        let (frame, binned) = (self.frame, self.binned);
        let base = frame.y.map(0.0);
        let mut items = Vec::new();
        for k in 0..binned.bins() {
            let (x0, x1) = (frame.x.map(binned.edges[k]), frame.x.map(binned.edges[k + 1]));
            let gap = if (x1 - x0).abs() / ng_side(self.position, self.ng) >= GAP_FROM { 0.5 } else { 0.0 };
            let mut stacked = 0.0;
            for (g, group) in heights.iter().enumerate() {
                let h = group[k];
                if h <= 0.0 {
                    continue;
                }
                let (from, to) = match self.position {
                    GroupPosition::Stack => (stacked, stacked + h),
                    _ => (0.0, h),
                };
                stacked += h;
                let (left, width) = match self.position {
                    GroupPosition::Dodge => {
                        let w = (x1 - x0) / self.ng as f64;
                        (x0 + w * g as f64, w)
                    }
                    _ => (x0, x1 - x0),
                };
                let (y_top, y_bottom) = (frame.y.map(to), if from == 0.0 { base } else { frame.y.map(from) });
                let rect = Rect::new(left + gap, y_top, (width - 2.0 * gap).max(0.5), y_bottom - y_top);
                let fill = color(g).with_opacity(opacity);
                let style = if self.position == GroupPosition::Layer && opacity < 1.0 {
                    Style { fill: Some(fill), stroke: Some(Stroke::solid(color(g), 1.0)) }
                } else {
                    Style::fill(fill)
                };
                let (rows, count): (Vec<u32>, usize) = match selected {
                    Some(h) => {
                        let rows: Vec<u32> = binned.rows[g][k].iter().copied().filter(|&r| h.contains(r)).collect();
                        let count = rows.len();
                        (rows, count)
                    }
                    None => (binned.rows[g][k].clone(), binned.counts[g][k]),
                };
                let label = format!(
                    "[{}, {}{}: {}{}",
                    format_value(binned.edges[k]),
                    format_value(binned.edges[k + 1]),
                    if k + 1 == binned.bins() { "]" } else { ")" },
                    format_value(h),
                    if what.is_empty() { String::new() } else { format!(" ({what})") }
                );
                let tooltip = self.tooltip(k, g, h, count, what);
                items.push(
                    Item::new(Role::DataMark, Shape::Rect(rect), style)
                        .with_rows(rows)
                        .labelled(label)
                        .with_tooltip(tooltip),
                );
            }
        }
        items
    }
}

impl BarLayout<'_> {
    /// The hover text of group `g`'s bar in bin `k`: the bin, the group, the rows and the height.
    fn tooltip(&self, k: usize, g: usize, height: f64, rows: usize, what: &str) -> String {
        let e = &self.binned.edges;
        let close = if k + 1 == self.binned.bins() { "]" } else { ")" };
        let mut text = format!("{} in [{}, {}{close}", self.field, e[k], e[k + 1]);
        if let Some((field, label)) = self.group.and_then(|(f, labels)| labels.get(g).map(|(l, _)| (f, l))) {
            text.push_str(&format!("\n{field}: {label}"));
        }
        let what = if what.is_empty() { String::new() } else { format!(" ({what})") };
        text.push_str(&format!("\nrows: {rows}{what}"));
        if self.stat_name != "count" {
            text.push_str(&format!("\n{}: {}", self.stat_name, format_value(height)));
        }
        text
    }
}

/// A rug: one short tick per distinct pixel column of the values, per group, along the bottom.
fn rug(
    frame: &crate::guide::layout::Frame,
    values: &[f64],
    rows: &[u32],
    group_of_row: &[usize],
    group_colors: &[Color],
) -> Vec<Item> {
    let bottom = frame.plot.bottom();
    group_colors
        .iter()
        .enumerate()
        .map(|(g, &color)| {
            let shade = if group_colors.len() > 1 { color } else { RUG_SHADE };
            let mut xs: Vec<f64> = rows
                .iter()
                .zip(group_of_row)
                .filter(|(_, gr)| **gr == g)
                .filter_map(|(&r, _)| values.get(r as usize).map(|&v| (frame.x.map(v) * 2.0).round() / 2.0))
                .collect();
            xs.sort_by(f64::total_cmp);
            xs.dedup();
            let points = xs.iter().flat_map(|&x| [Point::new(x, bottom), Point::new(x, bottom - RUG_TICK)]).collect();
            let group_rows = rows.iter().zip(group_of_row).filter(|(_, gr)| **gr == g).map(|(&r, _)| r).collect();
            Item::new(
                Role::DataMark,
                Shape::Lines(LineBatch {
                    points,
                    stride: 2,
                    color: PerPoint::Uniform(shade.with_opacity(0.75)),
                    width: 1.0,
                }),
                Style::default(),
            )
            .with_rows(group_rows)
            .labelled("rug")
        })
        .collect()
}

/// One row per bin and group: its edges, group (with a colour channel: its field and the
/// groups' labels), rows and bar height.
fn derived_table(binned: &Binned, heights: &[Vec<f64>], groups: Option<(&str, &[(String, Color)])>) -> Derived {
    let mut start = Vec::new();
    let mut end = Vec::new();
    let mut group = Vec::new();
    let mut count = Vec::new();
    let mut height = Vec::new();
    for (g, bins) in binned.counts.iter().enumerate() {
        for (k, &rows) in bins.iter().enumerate() {
            start.push(binned.edges[k]);
            end.push(binned.edges[k + 1]);
            group.push(groups.and_then(|(_, labels)| labels.get(g)).map(|(l, _)| l.clone()).unwrap_or_default());
            count.push(rows as f64);
            height.push(heights[g][k]);
        }
    }
    let mut d = Derived::default();
    d.push("bin_start", DerivedColumn::Number(start));
    d.push("bin_end", DerivedColumn::Number(end));
    if let Some((field, _)) = groups {
        d.push(field, DerivedColumn::Text(group));
    }
    d.push("count", DerivedColumn::Number(count));
    d.push("height", DerivedColumn::Number(height));
    d
}

/// `kind = "histogram"`.
pub static KIND: KindInfo = KindInfo::new("histogram", &["x", "color"])
    .counting_rows(crate::mark::registry::RowCounting {
        modes: None,
        unless: &["color", "rug", "highlight", "tooltip", "facet"],
        on_engine: false,
    })
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Frame)
    .drawing_annotations();

impl Technique for HistogramOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.highlight, cx.plan)
    }

    fn facet_shared(&self, chart: &Chart, table: &Table) -> Result<Option<crate::spec::ChartKind>, MarkError> {
        Ok(Some(crate::spec::ChartKind::Histogram(shared_bins(chart, self, table)?)))
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        // The value axis counts rows; it reads no column.
        vec![AxisSpec { name: "x axis", key: "x", options: self.x.options() }]
    }

    crate::mark::registry::color_key!();
}
