//! `violin`: the kernel density of a numeric column, mirrored about each group's centre line, one
//! per category of `x` (and colour group, dodged side by side), vertical or horizontal.
//!
//! Each group's density is a Gaussian kernel estimate (`enrich::distribution`) with Silverman's
//! bandwidth of that group, or one `bandwidth` for all; the bandwidth is stated in a note beside
//! the plot. Violins have the same greatest width (`scale = "width"`) or areas proportional to
//! their counts (`scale = "count"`), and hold a slim box plot of their quartiles by default.
//! Grouping, the frame and the counts come from the shared `grouped` module, as for `box`.

use crate::data::Table;
use crate::enrich::distribution::{DensityCurve, density_curve, silverman_bandwidth};
use crate::guide::format::format_value;
use crate::guide::legend::Legend;
use crate::mark::derived::DerivedColumn;
use crate::mark::grouped::{self, Group, Grouped, Layout, Orientation, Quantiles};
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError};
use crate::scene::{Color, Item, PathCmd, Role, Shape, Stroke, Style};
use crate::selection::Highlight;
use crate::spec::{Channel, Chart, ColorChannel};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "violin"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ViolinOptions {
    /// The values whose densities are drawn: a numeric column, on a linear scale.
    #[schemars(example = &"temp_max")]
    pub y: Channel,
    /// The categories, one violin each, as for `box` (without `x`, one violin of every row).
    #[serde(default)]
    #[schemars(example = &"weather")]
    pub x: Option<Channel>,
    /// A categorical column dodging violins side by side within each category, as for `box`.
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// The Gaussian kernel's bandwidth in the units of `y`, the same for every violin (default:
    /// Silverman's rule of thumb 0.9·min(σ, IQR/1.34)·n^(−1/5), for each violin from its own
    /// values). The chart states the bandwidth used.
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0), example = 0.25)]
    pub bandwidth: Option<f64>,
    /// How many bandwidths the density extends past each violin's smallest and largest value
    /// (default 0: the violin ends at the data; seaborn's default is 2).
    #[serde(default)]
    #[schemars(range(min = 0), example = 2)]
    pub cut: Option<f64>,
    /// `"width"` (default): every violin as wide at its widest; `"count"`: areas proportional to
    /// the number of values, so a group of twice the rows is twice the ink.
    #[serde(default)]
    pub scale: Option<ViolinScale>,
    /// Inside each violin: `"box"` (default: a slim box from the first to the third quartile,
    /// whiskers to 1.5 IQR and a white dot at the median), `"quartiles"` (lines across at the
    /// quartiles, the median solid) or `"none"`.
    #[serde(default)]
    pub inner: Option<Inner>,
    /// `"vertical"` (default) or `"horizontal"` (categories down the vertical axis), as for `box`.
    #[serde(default)]
    pub orientation: Option<Orientation>,
    /// How the quartiles of the inner box are interpolated: `"linear"` (default, Hyndman &
    /// Fan's type 7 as numpy's `percentile`), `"hazen"`, `"weibull"` or `"median-unbiased"`, as
    /// for `box`.
    #[serde(default)]
    pub quantiles: Option<Quantiles>,
    /// Violin colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// How violins are scaled against each other.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ViolinScale {
    /// Every violin as wide at its widest.
    #[default]
    Width,
    /// Areas proportional to the number of values.
    Count,
}

/// What is drawn inside each violin.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Inner {
    /// A slim box plot: quartiles, whiskers to 1.5 IQR, the median as a white dot.
    #[default]
    Box,
    /// Lines across at the quartiles (dashed) and the median (solid).
    Quartiles,
    /// Nothing.
    None,
}

/// Points along each density curve.
const CURVE_POINTS: usize = 256;
/// Whiskers of the inner box, in interquartile ranges.
const WHISKER: f64 = 1.5;

/// One group's density, or `None` when it has none (too few values or no spread without a
/// given bandwidth), with the bandwidth used.
struct Density {
    curve: Option<DensityCurve>,
    bandwidth: Option<f64>,
}

/// Draw violins.
pub fn draw(
    chart: &Chart,
    options: &ViolinOptions,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    if let Some(h) = options.bandwidth.filter(|h| !(*h > 0.0 && h.is_finite())) {
        return Err(MarkError::at(
            &["bandwidth"],
            format!("`bandwidth = {h}` is not a kernel width: it must be a number > 0"),
            "give the bandwidth in the units of y (e.g. a tenth of the values' spread), or remove it for \
             Silverman's rule",
        ));
    }
    let cut = options.cut.unwrap_or(0.0);
    if !(cut >= 0.0 && cut.is_finite()) {
        return Err(MarkError::at(
            &["cut"],
            format!("`cut = {cut}` must be a number of bandwidths ≥ 0"),
            "use 0 to end each violin at its data (the default), or 2 as seaborn does",
        ));
    }
    let spec = grouped::Spec {
        x: options.x.as_ref(),
        y: &options.y,
        color: options.color.as_ref(),
        mark_color: options.mark_color.as_deref(),
        orientation: options.orientation.unwrap_or_default(),
        quantiles: options.quantiles.unwrap_or_default().method(),
        whisker: WHISKER,
        marks: "violins",
        log_scale: false,
    };
    let grouped = Grouped::read(chart, table, &spec)?;
    let mut warnings = grouped.warnings.clone();
    let densities: Vec<Density> = grouped
        .list
        .iter()
        .map(|g| {
            let bandwidth = options.bandwidth.or_else(|| silverman_bandwidth(&g.values));
            let curve = bandwidth.and_then(|h| density_curve(&g.values, h, cut, CURVE_POINTS));
            Density { curve, bandwidth }
        })
        .collect();
    let flat: Vec<String> =
        grouped.list.iter().zip(&densities).filter(|(_, d)| d.curve.is_none()).map(|(g, _)| grouped.label(g)).collect();
    if !flat.is_empty() {
        warnings.push(Warning::from(format!(
            "{} {} too few values or no spread for Silverman's bandwidth: drawn as points; give `bandwidth` to \
             draw a density anyway",
            grouped::quoted(&flat),
            if flat.len() == 1 { "has" } else { "have" },
        )));
    }
    let extent = grouped.list.iter().zip(&densities).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (g, d)| {
        match &d.curve {
            Some(c) => (lo.min(c.lo), hi.max(c.hi)),
            None => (lo.min(g.stats.min), hi.max(g.stats.max)),
        }
    });
    let layout = grouped.layout(chart, extent, highlight, Some(bandwidth_note(options, &densities)))?;
    // The widest a violin may be drawn, as density (times count, for `scale = "count"`).
    let count = options.scale == Some(ViolinScale::Count);
    let weight = |g: &Group| if count { g.stats.n as f64 } else { 1.0 };
    let widest = grouped
        .list
        .iter()
        .zip(&densities)
        .filter_map(|(g, d)| Some(weight(g) * d.curve.as_ref()?.peak()))
        .fold(0.0, f64::max);
    let context = highlight.is_some();
    let inner = options.inner.unwrap_or_default();
    let mut marks = Vec::new();
    for (g, d) in grouped.list.iter().zip(&densities) {
        let (start, width) = layout.slot(&grouped, g);
        let centre = start + width / 2.0;
        let Some(curve) = &d.curve else {
            let values: Vec<(&Group, usize)> = (0..g.rows.len()).map(|i| (g, i)).collect();
            marks.extend(layout.dots(&grouped, &values, context, &grouped.label(g)));
            continue;
        };
        // Half widths in pixels along the curve.
        let peak = if count { widest } else { curve.peak() };
        let per_density = if peak > 0.0 { weight(g) * width / 2.0 / peak } else { 0.0 };
        let half: Vec<(f64, f64)> = curve.points().map(|(v, density)| (v, density * per_density)).collect();
        marks.push(outline(&layout, &grouped, g, centre, &half, context));
        marks.extend(match inner {
            Inner::Box => inner_box(&layout, g, centre, width, context),
            Inner::Quartiles => quartile_lines(&layout, g, centre, &half, context),
            Inner::None => Vec::new(),
        });
    }
    marks.extend(layout.selection(&grouped, highlight));
    let (counts, note) = layout.counts(&grouped);
    marks.extend(counts);
    warnings.extend(note);
    let (scene, geometry) = layout.scene(chart, &grouped, table, marks, &mut warnings);
    let bandwidths = densities.iter().map(|d| d.bandwidth.unwrap_or(f64::NAN)).collect();
    let derived = grouped.derived(vec![("bandwidth", DerivedColumn::Number(bandwidths))]);
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// `v` rounded to two significant digits, for the note.
fn two_digits(v: f64) -> String {
    if !(v.is_finite() && v != 0.0) {
        return format_value(v);
    }
    let unit = 10f64.powi(v.abs().log10().floor() as i32 - 1);
    format_value((v / unit).round() * unit)
}

/// The note stating the kernel and the bandwidth used: the given one, Silverman's of the one
/// group, or the range of Silverman's over the groups.
fn bandwidth_note(options: &ViolinOptions, densities: &[Density]) -> Legend {
    let used: Vec<f64> = densities.iter().filter(|d| d.curve.is_some()).filter_map(|d| d.bandwidth).collect();
    let (lo, hi) = used.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| (a.min(h), b.max(h)));
    let mut lines = vec![match (options.bandwidth, used.is_empty()) {
        (Some(h), _) => format!("bandwidth {} (given)", two_digits(h)),
        (None, true) => "no bandwidth (too few values)".to_string(),
        (None, false) if two_digits(lo) == two_digits(hi) => format!("bandwidth {} (Silverman)", two_digits(lo)),
        (None, false) => format!("bandwidth {}–{}", two_digits(lo), two_digits(hi)),
    }];
    if options.bandwidth.is_none() && two_digits(lo) != two_digits(hi) {
        lines.push("(Silverman, per violin)".to_string());
    }
    if options.scale == Some(ViolinScale::Count) {
        lines.push("areas proportional to counts".to_string());
    }
    Legend::Notes { title: "Kernel density".to_string(), lines }
}

/// A violin's outline: the half widths `half` (value, pixels) right of the centre line, then
/// mirrored back on the left, closed.
fn outline(layout: &Layout, grouped: &Grouped, g: &Group, centre: f64, half: &[(f64, f64)], context: bool) -> Item {
    let side = |(v, w): (f64, f64), sign: f64| layout.at(centre + sign * w, v);
    let mut cmds: Vec<PathCmd> = Vec::with_capacity(2 * half.len() + 1);
    for (k, &p) in half.iter().enumerate() {
        let at = side(p, 1.0);
        cmds.push(if k == 0 { PathCmd::MoveTo(at) } else { PathCmd::LineTo(at) });
    }
    cmds.extend(half.iter().rev().map(|&p| PathCmd::LineTo(side(p, -1.0))));
    cmds.push(PathCmd::Close);
    let style = Style { fill: Some(grouped.fill(g, context)), stroke: Some(Stroke::solid(Grouped::ink(context), 1.0)) };
    Item::new(Role::DataMark, Shape::Path(cmds), style).with_rows(g.rows.clone()).labelled(grouped.label(g))
}

/// The slim box inside a violin: whiskers as a thin line, the quartiles as a dark bar, the
/// median as a white dot.
fn inner_box(layout: &Layout, g: &Group, centre: f64, width: f64, context: bool) -> Vec<Item> {
    let s = &g.stats;
    let ink = Grouped::ink(context);
    let bar = (width * 0.08).clamp(3.0, 8.0);
    let whiskers =
        vec![PathCmd::MoveTo(layout.at(centre, s.whisker_low)), PathCmd::LineTo(layout.at(centre, s.whisker_high))];
    let median = Shape::Circle { center: layout.at(centre, s.median), radius: (bar / 2.0).max(1.5) };
    vec![
        Item::new(Role::DataMark, Shape::Path(whiskers), Style::stroke(ink, 1.2))
            .with_rows(g.rows.clone())
            .labelled("whiskers"),
        Item::new(
            Role::DataMark,
            Shape::Rect(layout.rect(centre - bar / 2.0, centre + bar / 2.0, s.q1, s.q3)),
            Style::fill(ink),
        )
        .with_rows(g.rows.clone())
        .labelled("quartiles"),
        Item::new(Role::DataMark, median, Style { fill: Some(Color::WHITE), stroke: Some(Stroke::solid(ink, 0.8)) })
            .with_rows(g.rows.clone())
            .labelled("median"),
    ]
}

/// Lines across a violin at its quartiles (dashed) and median (solid), as wide as the violin
/// there.
fn quartile_lines(layout: &Layout, g: &Group, centre: f64, half: &[(f64, f64)], context: bool) -> Vec<Item> {
    let s = &g.stats;
    let ink = Grouped::ink(context);
    [(s.q1, "first quartile", true), (s.median, "median", false), (s.q3, "third quartile", true)]
        .into_iter()
        .map(|(v, name, dashed)| {
            let w = half_width_at(half, v);
            let cmds = vec![PathCmd::MoveTo(layout.at(centre - w, v)), PathCmd::LineTo(layout.at(centre + w, v))];
            let dash = if dashed { vec![4.0, 3.0] } else { Vec::new() };
            let width = if dashed { 1.0 } else { 1.6 };
            Item::new(
                Role::DataMark,
                Shape::Path(cmds),
                Style { fill: None, stroke: Some(Stroke { color: ink, width, dash }) },
            )
            .with_rows(g.rows.clone())
            .labelled(name)
        })
        .collect()
}

/// The half width at value `v`, interpolated between the curve's points (0 outside it).
fn half_width_at(half: &[(f64, f64)], v: f64) -> f64 {
    let k = half.partition_point(|(x, _)| *x < v);
    match (k.checked_sub(1).and_then(|i| half.get(i)), half.get(k)) {
        (Some(&(x0, w0)), Some(&(x1, w1))) if x1 > x0 => w0 + (w1 - w0) * (v - x0) / (x1 - x0),
        (_, Some(&(x, w))) if x == v => w,
        (Some(&(x, w)), None) if x == v => w,
        _ => 0.0,
    }
}

/// `kind = "violin"`.
pub static KIND: KindInfo = KindInfo::new("violin", &["x", "y", "color"])
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Frame)
    .drawing_annotations();

impl Technique for ViolinOptions {
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

    /// A violin chart over a column `v` of 1, 2, 3 with the options in `json`.
    fn drawn(json: serde_json::Value) -> Result<ChartOutput, MarkError> {
        let table = Table::from_columns([("v", ColumnValues::Number(vec![1.0, 2.0, 3.0]))]);
        let mut spec = serde_json::json!({ "name": "c", "data": "d", "kind": "violin", "y": "v" });
        if let (Some(spec), Some(extra)) = (spec.as_object_mut(), json.as_object()) {
            spec.extend(extra.clone());
        }
        let chart: Chart = serde_json::from_value(spec).expect("a violin chart");
        let ChartKind::Violin(options) = &chart.kind else { panic!("a violin") };
        draw(&crate::mark::with_default_size(&chart), options, &table, None)
    }

    #[test]
    fn a_bandwidth_or_cut_out_of_range_is_an_error_at_its_key() {
        // The schema refuses these in a spec file; options built in code get the same answer.
        for (json, key, message) in [
            (serde_json::json!({ "bandwidth": 0.0 }), "bandwidth", "`bandwidth = 0` is not a kernel width"),
            (serde_json::json!({ "bandwidth": -2.0 }), "bandwidth", "`bandwidth = -2` is not a kernel width"),
            (serde_json::json!({ "cut": -1.0 }), "cut", "`cut = -1` must be a number of bandwidths ≥ 0"),
        ] {
            let e = drawn(json).err().expect("an error");
            assert_eq!(e.path, [PathSeg::Key(key.into())]);
            assert!(e.message.starts_with(message), "{}", e.message);
        }
        assert!(drawn(serde_json::json!({ "bandwidth": 0.5 })).is_ok());
    }

    #[test]
    fn half_widths_interpolate_inside_the_curve_only() {
        let half = [(0.0, 0.0), (1.0, 4.0), (2.0, 2.0)];
        assert_eq!(half_width_at(&half, 0.5), 2.0);
        assert_eq!(half_width_at(&half, 1.5), 3.0);
        assert_eq!(half_width_at(&half, 2.0), 2.0);
        assert_eq!(half_width_at(&half, 0.0), 0.0);
        assert_eq!(half_width_at(&half, 2.5), 0.0);
        assert_eq!(half_width_at(&[(1.0, 3.0)], 1.0), 3.0);
    }

    #[test]
    fn bandwidths_are_stated_to_two_digits() {
        assert_eq!(two_digits(0.4237), "0.42");
        assert_eq!(two_digits(1.0589), "1.1");
        assert_eq!(two_digits(12.34), "12");
        assert_eq!(two_digits(0.00987), "0.0099");
    }
}
