//! `box`: Tukey box plots of a numeric column, one per category of `x` (and colour group, dodged
//! side by side), vertical or horizontal.
//!
//! The box spans the first to the third quartile with a line at the median; whiskers reach the
//! most extreme values within `whisker` interquartile ranges of the box, and values beyond them
//! are drawn one by one as outliers. A notch shows median ± 1.57·IQR/√n (McGill, Tukey & Larsen
//! 1978), a diamond the mean. Each group's count is written at the low end of its box. The
//! statistics come from `enrich::distribution`; grouping, the frame and the counts from the
//! shared `grouped` module, which violins use too.

use crate::data::Table;
use crate::mark::derived::DerivedColumn;
use crate::mark::grouped::{self, Group, Grouped, Layout, Orientation, Quantiles};
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError};
use crate::scene::{Color, Item, PathCmd, Point, Role, Shape, Stroke, Style};
use crate::selection::Highlight;
use crate::spec::{Channel, Chart, ColorChannel};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "box"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct BoxOptions {
    /// The categories: one box per distinct value (text in the order values first appear,
    /// numbers and dates ascending). Without `x`, one box of every row.
    #[serde(default)]
    #[schemars(example = &"species")]
    pub x: Option<Channel>,
    /// The values: a numeric column, on a linear (default) or log scale.
    #[schemars(example = &"petal_length")]
    pub y: Channel,
    /// Dodge boxes side by side within each category by a categorical column, with a legend.
    #[serde(default)]
    #[schemars(example = &"origin")]
    pub color: Option<ColorChannel>,
    /// `"vertical"` (default: categories along the horizontal axis) or `"horizontal"`
    /// (categories down the vertical axis, the first on top; values along the horizontal axis).
    #[serde(default)]
    pub orientation: Option<Orientation>,
    /// How the quartiles are interpolated: `"linear"` (default) is Hyndman & Fan's type 7, the
    /// default of numpy's `percentile` and R's `quantile`: quantile p lies at position p·(n − 1)
    /// of the n sorted values, counted from 0, linearly interpolated between its neighbours.
    /// `"hazen"` (type 5), `"weibull"` (type 6) and `"median-unbiased"` (type 8) are numpy's
    /// methods of those names.
    #[serde(default)]
    pub quantiles: Option<Quantiles>,
    /// How far the whiskers reach, in interquartile ranges beyond the box (default 1.5, Tukey's):
    /// to the most extreme values within that reach; values beyond are drawn as outliers.
    #[serde(default)]
    #[schemars(range(min = 0), example = 1.5)]
    pub whisker: Option<f64>,
    /// Notch the box at the median ± 1.57·IQR/√n (McGill et al.): boxes whose notches do not
    /// overlap have medians that differ at roughly 95% confidence.
    #[serde(default)]
    pub notch: Option<bool>,
    /// Mark the mean with a diamond.
    #[serde(default)]
    pub mean: Option<bool>,
    /// Box colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// Tukey's whisker reach.
const DEFAULT_WHISKER: f64 = 1.5;
/// Half the width of the mean's diamond.
const MEAN_SIZE: f64 = 4.0;

/// Draw box plots.
pub fn draw(
    chart: &Chart,
    options: &BoxOptions,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let whisker = options.whisker.unwrap_or(DEFAULT_WHISKER);
    if !(whisker >= 0.0 && whisker.is_finite()) {
        return Err(MarkError::at(
            &["whisker"],
            format!("`whisker = {whisker}` is not a reach: it must be a number ≥ 0"),
            "use 1.5 (Tukey's whiskers), or a larger number for whiskers to the extremes",
        ));
    }
    let spec = grouped::Spec {
        x: options.x.as_ref(),
        y: &options.y,
        color: options.color.as_ref(),
        mark_color: options.mark_color.as_deref(),
        orientation: options.orientation.unwrap_or_default(),
        quantiles: options.quantiles.unwrap_or_default().method(),
        whisker,
        marks: "boxes",
        log_scale: true,
    };
    let grouped = Grouped::read(chart, table, &spec)?;
    let mut warnings = grouped.warnings.clone();
    let extent = grouped
        .list
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), g| (lo.min(g.stats.min), hi.max(g.stats.max)));
    let layout = grouped.layout(chart, extent, highlight, None)?;
    let notch = options.notch == Some(true);
    let context = highlight.is_some();
    let mut marks = Vec::new();
    let mut notch_past_box = Vec::new();
    for g in &grouped.list {
        let drawn = draw_box(&layout, &grouped, g, notch, context);
        if drawn.notch_past_box {
            notch_past_box.push(grouped.label(g));
        }
        marks.extend(drawn.items);
        if options.mean == Some(true) {
            marks.push(mean_mark(&layout, &grouped, g, context));
        }
    }
    let outliers: Vec<(&Group, usize)> =
        grouped.list.iter().flat_map(|g| g.stats.outliers.iter().map(move |&i| (g, i))).collect();
    marks.extend(layout.dots(&grouped, &outliers, context, "outliers"));
    marks.extend(layout.selection(&grouped, highlight));
    let (counts, note) = layout.counts(&grouped);
    marks.extend(counts);
    warnings.extend(note);
    if !notch_past_box.is_empty() {
        warnings.push(Warning::from(format!(
            "the notch of {} reaches past its box (few values or a small spread) and is drawn cut at the \
             quartiles; `--format csv` gives the whole notch",
            grouped::quoted(&notch_past_box)
        )));
    }
    let (scene, geometry) = layout.scene(chart, &grouped, table, marks, &mut warnings);
    let mut extra = Vec::new();
    if notch {
        extra.push(("notch_low", DerivedColumn::Number(grouped.list.iter().map(|g| g.stats.notch.0).collect())));
        extra.push(("notch_high", DerivedColumn::Number(grouped.list.iter().map(|g| g.stats.notch.1).collect())));
    }
    let derived = grouped.derived(extra);
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// The marks of one box, and whether its notch had to be cut at the quartiles.
struct DrawnBox {
    items: Vec<Item>,
    notch_past_box: bool,
}

/// One group's box (notched or not), whiskers with caps, and median line.
fn draw_box(layout: &Layout, grouped: &Grouped, g: &Group, notch: bool, context: bool) -> DrawnBox {
    let s = &g.stats;
    let (start, width) = layout.slot(grouped, g);
    let (end, centre) = (start + width, start + width / 2.0);
    let label = grouped.label(g);
    let ink = Grouped::ink(context);
    let outline = Some(Stroke::solid(ink, 1.0));
    let style = Style { fill: Some(grouped.fill(g, context)), stroke: outline };
    let (lo, hi) = (s.notch.0.max(s.q1), s.notch.1.min(s.q3));
    let notch_past_box = notch && (s.notch.0 < s.q1 || s.notch.1 > s.q3);
    let inset = width / 4.0;
    let body = if notch {
        let p = |a: f64, v: f64| layout.at(a, v);
        Shape::Path(vec![
            PathCmd::MoveTo(p(start, s.q1)),
            PathCmd::LineTo(p(end, s.q1)),
            PathCmd::LineTo(p(end, lo)),
            PathCmd::LineTo(p(end - inset, s.median)),
            PathCmd::LineTo(p(end, hi)),
            PathCmd::LineTo(p(end, s.q3)),
            PathCmd::LineTo(p(start, s.q3)),
            PathCmd::LineTo(p(start, hi)),
            PathCmd::LineTo(p(start + inset, s.median)),
            PathCmd::LineTo(p(start, lo)),
            PathCmd::Close,
        ])
    } else {
        Shape::Rect(layout.rect(start, end, s.q1, s.q3))
    };
    let cap = width / 4.0;
    let line =
        |a0: f64, v0: f64, a1: f64, v1: f64| [PathCmd::MoveTo(layout.at(a0, v0)), PathCmd::LineTo(layout.at(a1, v1))];
    let mut whiskers = Vec::new();
    whiskers.extend(line(centre, s.q1, centre, s.whisker_low));
    whiskers.extend(line(centre - cap, s.whisker_low, centre + cap, s.whisker_low));
    whiskers.extend(line(centre, s.q3, centre, s.whisker_high));
    whiskers.extend(line(centre - cap, s.whisker_high, centre + cap, s.whisker_high));
    let median_inset = if notch { inset } else { 0.0 };
    let median = line(start + median_inset, s.median, end - median_inset, s.median).to_vec();
    let items = vec![
        Item::new(Role::DataMark, Shape::Path(whiskers), Style::stroke(ink, 1.2))
            .with_rows(g.rows.clone())
            .labelled(format!("whiskers: {label}")),
        Item::new(Role::DataMark, body, style).with_rows(g.rows.clone()).labelled(label.clone()),
        Item::new(Role::DataMark, Shape::Path(median), Style::stroke(ink, 2.0))
            .with_rows(g.rows.clone())
            .labelled(format!("median: {label}")),
    ];
    DrawnBox { items, notch_past_box }
}

/// A diamond at a group's mean.
fn mean_mark(layout: &Layout, grouped: &Grouped, g: &Group, context: bool) -> Item {
    let (start, width) = layout.slot(grouped, g);
    let size = MEAN_SIZE.min(width / 2.0);
    let c = layout.px(start + width / 2.0, layout.value_px(g.stats.mean));
    let cmds = vec![
        PathCmd::MoveTo(Point::new(c.x, c.y - size)),
        PathCmd::LineTo(Point::new(c.x + size, c.y)),
        PathCmd::LineTo(Point::new(c.x, c.y + size)),
        PathCmd::LineTo(Point::new(c.x - size, c.y)),
        PathCmd::Close,
    ];
    let style = Style { fill: Some(Color::WHITE), stroke: Some(Stroke::solid(Grouped::ink(context), 1.2)) };
    Item::new(Role::DataMark, Shape::Path(cmds), style)
        .with_rows(g.rows.clone())
        .labelled(format!("mean: {}", grouped.label(g)))
}

/// `kind = "box"`.
pub static KIND: KindInfo = KindInfo::new("box", &["x", "y", "color"])
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Frame)
    .drawing_annotations();

impl Technique for BoxOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.highlight)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        grouped::axes(self.x.as_ref(), &self.y, self.orientation.unwrap_or_default())
    }

    crate::mark::registry::color_key!();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::ColumnValues;
    use crate::spec::{ChartKind, PathSeg};

    #[test]
    fn a_negative_or_infinite_whisker_reach_is_an_error_at_its_key() {
        let table = Table::from_columns([("v", ColumnValues::Number(vec![1.0, 2.0, 3.0]))]);
        for (reach, shown) in [(-1.0, "-1"), (f64::INFINITY, "inf")] {
            let spec = serde_json::json!({ "name": "c", "data": "d", "kind": "box", "y": "v", "whisker": 1.0 });
            let mut chart: Chart = serde_json::from_value(spec).expect("a box chart");
            let ChartKind::Box(options) = &mut chart.kind else { panic!("a box") };
            options.whisker = Some(reach);
            let options = options.clone();
            let e = draw(&chart, &options, &table, None).err().expect("an error");
            assert_eq!(e.path, [PathSeg::Key("whisker".into())]);
            assert!(e.message.starts_with(&format!("`whisker = {shown}` is not a reach")), "{}", e.message);
        }
    }
}
