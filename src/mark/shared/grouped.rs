//! Distributions by group, the half that `box` and `violin` share: a numeric value column split
//! by an optional category column (`x`) and a categorical colour (dodged within each category),
//! each group's box-plot statistics, the frame with the categories on one axis and the values on
//! the other (either way round), the count of each group at its mark, the rows of a selection as
//! points over grey marks, and one derived CSV row per group.

use crate::data::{Column, Table};
use crate::enrich::distribution::{BoxStats, QuantileMethod, box_stats};
use crate::guide::Theme;
use crate::guide::axis::title_with_unit;
use crate::guide::layout::{Domain, Frame, PositionAxis};
use crate::guide::legend::{Legend, Symbol};
use crate::guide::scale::{BandScale, Scale};
use crate::layout::split_mix::mix64;
use crate::mark::bands::{self, Keys};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode::{self, ColorEncoding};
use crate::mark::geometry::{Geometry, Plot};
use crate::mark::registry::AxisSpec;
use crate::mark::warning::Warning;
use crate::mark::{MarkError, frame, highlight};
use crate::scene::{
    Anchor, Baseline, Color, Item, PerPoint, Point, PointBatch, Rect, Role, Scene, Shape, Stroke, Style, Text,
};
use crate::selection::Highlight;
use crate::spec::{Channel, ChannelOptions, Chart, ColorChannel, ScaleKind};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Which axis holds the values.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Orientation {
    /// Categories along the horizontal axis, values up the vertical one.
    #[default]
    Vertical,
    /// Categories down the vertical axis (the first at the top), values along the horizontal one.
    Horizontal,
}

/// How quartiles are interpolated between the sorted values (Hyndman & Fan 1996), under the
/// names of numpy's `percentile(..., method=...)`.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Quantiles {
    /// Type 7, numpy's default and R's: quantile p at position p·(n − 1) of the n sorted values
    /// (counted from 0), linearly interpolated between its neighbours.
    #[default]
    Linear,
    /// Type 5: position p·n − 1/2.
    Hazen,
    /// Type 6 (Minitab, SPSS): position p·(n + 1) − 1.
    Weibull,
    /// Type 8 (numpy's `median_unbiased`): position p·(n + 1/3) − 2/3.
    MedianUnbiased,
}

impl Quantiles {
    /// The interpolation the numeric core applies.
    pub fn method(self) -> QuantileMethod {
        match self {
            Quantiles::Linear => QuantileMethod::Linear,
            Quantiles::Hazen => QuantileMethod::Hazen,
            Quantiles::Weibull => QuantileMethod::Weibull,
            Quantiles::MedianUnbiased => QuantileMethod::MedianUnbiased,
        }
    }
}

/// Opacity of a group's colour filling its box or violin: a tint that dark outlines, medians
/// and text stay readable on.
pub const FILL_OPACITY: f64 = 0.55;
/// Outlines, whiskers and medians.
pub const INK: Color = Color::rgb(0x33, 0x33, 0x33);
/// Outlines of grey context marks (under a selection).
const CONTEXT_INK: Color = Color::rgb(0x90, 0x90, 0x90);
/// A group's mark needs at least this many pixels across.
const MIN_SLOT: f64 = 3.0;
/// A group's mark is at most this many pixels across (a lone box need not fill the plot).
const MAX_SLOT: f64 = 160.0;
/// Radius of a selected row's point.
const SELECTED_RADIUS: f64 = 2.5;
/// Radius of a value drawn on its own (an outlier, a value of a group without a density).
const DOT_RADIUS: f64 = 2.5;

/// What a distribution chart reads of its spec.
pub struct Spec<'a> {
    /// The category column, if any.
    pub x: Option<&'a Channel>,
    /// The values.
    pub y: &'a Channel,
    /// The colour groups within each category.
    pub color: Option<&'a ColorChannel>,
    /// The colour without `color`.
    pub mark_color: Option<&'a str>,
    /// Which axis holds the values.
    pub orientation: Orientation,
    /// How quartiles are interpolated.
    pub quantiles: QuantileMethod,
    /// Whiskers reach this many interquartile ranges beyond the box.
    pub whisker: f64,
    /// The marks in the plural, for messages (`"boxes"`).
    pub marks: &'static str,
    /// Whether the values may lie on a log scale.
    pub log_scale: bool,
}

/// The rows of one category and colour group, with their statistics.
pub struct Group {
    /// Index of the category among [`Grouped::x`]'s labels.
    pub x: usize,
    /// Index of the colour group among [`Grouped::groups`]' labels.
    pub group: usize,
    /// The table rows, in table order.
    pub rows: Vec<u32>,
    /// Their values, in the same order.
    pub values: Vec<f64>,
    /// Box-plot statistics of the values.
    pub stats: BoxStats,
}

/// A chart's rows split into groups.
pub struct Grouped {
    /// The categories (one, unlabelled, without `x`).
    pub x: Keys,
    /// The colour groups (one, unlabelled, without `color`).
    pub groups: Keys,
    /// The non-empty groups, category by category.
    pub list: Vec<Group>,
    /// Every drawn row.
    pub rows: Vec<u32>,
    /// Each row's colour.
    pub colors: ColorEncoding,
    /// The colour legend, if `color` is given.
    pub legend: Option<Legend>,
    /// Rows dropped, and other notes.
    pub warnings: Vec<Warning>,
    /// The value channel.
    pub y: ChannelOptions,
    /// The category channel.
    pub x_channel: Option<ChannelOptions>,
    /// The colour column's name.
    pub color_field: Option<String>,
    /// Which axis holds the values.
    pub orientation: Orientation,
    /// Whether colour groups sit side by side within a category (some category has several).
    pub dodge: bool,
}

/// Errors for scales a distribution chart cannot draw: a category axis on a continuous scale,
/// values that are text, dates, on a band scale, or (where not allowed) on a log scale.
fn check_columns(spec: &Spec<'_>, y_col: &Column) -> Result<(), MarkError> {
    let marks = spec.marks;
    if let Some(kind) = spec.x.and_then(|x| x.options().scale).filter(|k| *k != ScaleKind::Band) {
        return Err(MarkError::at(
            &["x", "scale"],
            format!(
                "{marks} place every x value in its own band, so x cannot have a {} scale",
                encode::scale_name(kind)
            ),
            "remove `scale` from x (or set `scale = \"band\"`); to plot values against a number, use a scatter chart",
        ));
    }
    encode::require_numeric("y", y_col, "a distribution", "use a numeric column for y, and put categories on x")?;
    if y_col.is_time() {
        return Err(MarkError::at(
            &["y"],
            format!("y column `{}` holds dates or times, whose distribution {marks} do not summarise", y_col.name),
            "use a numeric column for y (a duration or a count, for example); put dates on x, where each becomes a category",
        ));
    }
    match spec.y.options().scale {
        None | Some(ScaleKind::Linear) => Ok(()),
        Some(ScaleKind::Log) if spec.log_scale => Ok(()),
        Some(kind) => Err(MarkError::at(
            &["y", "scale"],
            format!("the values of {marks} need a continuous scale, not a {} scale", encode::scale_name(kind)),
            if spec.log_scale {
                "remove `scale` from y, or use `scale = \"log\"`"
            } else {
                "remove `scale` from y: the density is estimated on a linear scale (for values spanning decades, \
                 take their logarithm in a `transform` first)"
            },
        )),
    }
}

impl Grouped {
    /// Read the value, category and colour columns of `chart`, drop the rows that cannot be
    /// drawn (the shared non-finite policy; values ≤ 0 on a log scale), and split the rest into
    /// groups with their statistics.
    pub fn read(chart: &Chart, table: &Table, spec: &Spec<'_>) -> Result<Grouped, MarkError> {
        let y = spec.y.options();
        let y_col = encode::column(chart, "y", &y.field, table)?;
        let x_channel = spec.x.map(Channel::options);
        let x_col = match &x_channel {
            Some(o) => Some(encode::column(chart, "x", &o.field, table)?),
            None => None,
        };
        if table.rows == 0 {
            return Err(encode::no_rows(chart, table, None));
        }
        check_columns(spec, y_col)?;
        let color = bands::grouping_channel(chart, spec.color, table, spec.marks)?;
        let color_col = match &color {
            Some(c) => Some(encode::column(chart, "color", c.field(), table)?),
            None => None,
        };

        let mut numeric: Vec<(&str, &Column)> = vec![(y.field.as_str(), y_col)];
        if let (Some(o), Some(col)) = (&x_channel, x_col) {
            numeric.push((o.field.as_str(), col));
        }
        if let (Some(c), Some(col)) = (&color, color_col) {
            numeric.push((c.field(), col));
        }
        numeric.retain(|(_, c)| c.numbers().is_some());
        let log = encode::log_fields(&[&y]);
        let (rows, warning) = encode::placeable_rows(&chart.name, table.rows, &numeric, &log);
        let warnings: Vec<Warning> = warning.into_iter().collect();
        if rows.is_empty() {
            return Err(encode::no_rows(chart, table, warnings.first()));
        }

        let x = match x_col {
            Some(col) => bands::keys(col, &rows),
            None => Keys::single("", rows.len()),
        };
        let groups = match color_col {
            Some(col) => bands::keys(col, &rows),
            None => Keys::single("", rows.len()),
        };
        let (nx, ng) = (x.labels.len(), groups.labels.len());
        let slots = nx.saturating_mul(ng);
        // Colour groups are dodged only when a category holds more than one of them (not when
        // colour repeats x, or each category has its own group).
        let mut seen = vec![usize::MAX; nx];
        let mut dodge = false;
        for (&xi, &gi) in x.of_row.iter().zip(&groups.of_row) {
            match seen.get_mut(xi) {
                Some(s) if *s == usize::MAX => *s = gi,
                Some(s) => dodge |= *s != gi,
                None => {}
            }
        }
        let [width, height] = chart.size.unwrap_or(crate::mark::FRAME_SIZE);
        let (across, side) = match spec.orientation {
            Orientation::Vertical => (width, "wide"),
            Orientation::Horizontal => (height, "tall"),
        };
        let drawn = if dodge { slots } else { nx };
        if drawn as f64 * MIN_SLOT > across {
            let what = if dodge {
                format!("{nx} categories × {ng} colour groups = {slots} {}", spec.marks)
            } else {
                format!("{nx} categories")
            };
            return Err(MarkError::at(
                &[if spec.x.is_some() { "x" } else { "color" }],
                format!(
                    "{what} do not fit a {across} px {side} chart (each needs at least {MIN_SLOT} px)",
                    across = across
                ),
                format!(
                    "{} suit tens of groups: filter the data into fewer categories, or make `size` {}",
                    spec.marks,
                    if side == "wide" { "wider" } else { "taller" }
                ),
            ));
        }

        let values = y_col.numbers().unwrap_or(&[]);
        let mut slot_rows: Vec<Vec<u32>> = vec![Vec::new(); slots];
        for (k, &r) in rows.iter().enumerate() {
            let (xi, gi) = (x.of_row.get(k).copied().unwrap_or(0), groups.of_row.get(k).copied().unwrap_or(0));
            if let Some(slot) = slot_rows.get_mut(xi * ng + gi) {
                slot.push(r);
            }
        }
        let list = slot_rows
            .into_iter()
            .enumerate()
            .filter_map(|(slot, rows)| {
                let values: Vec<f64> =
                    rows.iter().map(|&r| values.get(r as usize).copied().unwrap_or(f64::NAN)).collect();
                let stats = box_stats(&values, spec.quantiles, spec.whisker)?;
                Some(Group { x: slot / ng, group: slot % ng, rows, values, stats })
            })
            .collect();
        let (colors, legend) =
            encode::color_encoding(chart, color.as_ref(), spec.mark_color, table, &rows, Symbol::Square)?;
        let legend = legend.map(|l| match l {
            Legend::Categorical { title, entries, symbol } => Legend::Categorical {
                title,
                entries: entries.into_iter().map(|(label, c)| (label, c.with_opacity(FILL_OPACITY))).collect(),
                symbol,
            },
            other => other,
        });
        Ok(Grouped {
            x,
            groups,
            list,
            rows,
            colors,
            legend,
            warnings,
            y,
            x_channel,
            color_field: color.map(|c| c.field().to_string()),
            orientation: spec.orientation,
            dodge,
        })
    }

    /// A group's name in labels and messages: its category, its colour group, or both.
    pub fn label(&self, g: &Group) -> String {
        let (x, c) = (self.x.label(g.x), self.groups.label(g.group));
        match (x.is_empty(), c.is_empty()) {
            (false, false) if x != c => format!("{x}, {c}"),
            (true, false) => c.to_string(),
            (false, _) => x.to_string(),
            (true, true) => self.y.field.clone(),
        }
    }

    /// The fill of a group's mark: its colour as a tint, or grey context under a selection.
    pub fn fill(&self, g: &Group, context: bool) -> Color {
        let color = g.rows.first().map_or(encode::DEFAULT_MARK_COLOR, |&r| self.colors.color_of(r));
        if context { highlight::CONTEXT.with_opacity(FILL_OPACITY) } else { color.with_opacity(FILL_OPACITY) }
    }

    /// The ink of outlines, whiskers and medians: dark, or grey context under a selection.
    pub fn ink(context: bool) -> Color {
        if context { CONTEXT_INK } else { INK }
    }

    /// The frame: categories on one axis, values over `extent` on the other (with room at the
    /// low end for the counts), the colour legend, a selection's legend and `notes`.
    pub fn layout(
        &self,
        chart: &Chart,
        extent: (f64, f64),
        highlight: Option<&Highlight>,
        notes: Option<Legend>,
    ) -> Result<Layout, MarkError> {
        let theme = Theme::with_font_size(chart.font_size.unwrap_or(12.0));
        let count_room = match self.orientation {
            Orientation::Vertical => theme.caption_size * 2.0,
            Orientation::Horizontal => {
                let widest = self.list.iter().map(|g| g.stats.n).max().unwrap_or(0);
                crate::text::measure(&count_text(widest, true), theme.caption_size).width + 8.0
            }
        };
        let y = &self.y;
        let (mut lo, mut hi) = extent;
        if y.zero == Some(true) && y.scale != Some(ScaleKind::Log) {
            lo = lo.min(0.0);
            hi = hi.max(0.0);
        }
        if let Some([a, b]) = y.domain {
            (lo, hi) = (a, b);
        }
        let kind = y.scale.unwrap_or(ScaleKind::Linear);
        let values = PositionAxis {
            title: title_with_unit(y.title.as_deref().unwrap_or(&y.field), y.unit.as_deref()),
            kind,
            domain: Domain::Continuous(lo, hi),
            nice: y.nice.unwrap_or(kind != ScaleKind::Log) && y.domain.is_none(),
            ticks: y.ticks,
            grid: y.grid.unwrap_or(true),
            inset: count_room,
        };
        let mut labels = self.x.labels.clone();
        if self.orientation == Orientation::Horizontal {
            // Band 0 is at the bottom of a vertical axis: reversed, the first category is on top.
            labels.reverse();
        }
        let x = self.x_channel.as_ref();
        let categories = PositionAxis {
            title: x
                .map(|o| title_with_unit(o.title.as_deref().unwrap_or(&o.field), o.unit.as_deref()))
                .unwrap_or_default(),
            kind: ScaleKind::Band,
            domain: Domain::Categories(labels),
            nice: false,
            ticks: None,
            grid: x.and_then(|o| o.grid).unwrap_or(false),
            inset: 0.0,
        };
        let mut legends: Vec<Legend> = self.legend.iter().cloned().collect();
        if let Some(h) = highlight {
            legends.push(highlight::legend(h, &self.rows, Symbol::Circle));
        }
        legends.extend(notes);
        let (frame, theme) = match self.orientation {
            Orientation::Vertical => frame::cartesian(chart, categories, values, legends)?,
            Orientation::Horizontal => frame::cartesian(chart, values, categories, legends)?,
        };
        let (band, value) = match (self.orientation, &frame.x, &frame.y) {
            (Orientation::Vertical, Scale::Band(b), v) | (Orientation::Horizontal, v, Scale::Band(b)) => {
                (b.clone(), v.clone())
            }
            _ => return Err(MarkError::at(&["x"], "the categories are not on a band scale", "")),
        };
        Ok(Layout { frame, theme, band, value, orientation: self.orientation })
    }

    /// One derived row per group: its category and colour group, the count and the box-plot
    /// statistics, then `extra` columns (one value per group, in order).
    pub fn derived(&self, extra: Vec<(&str, DerivedColumn)>) -> Derived {
        let mut d = Derived::default();
        let text = |f: &dyn Fn(&Group) -> String| DerivedColumn::Text(self.list.iter().map(f).collect());
        if let Some(x) = &self.x_channel {
            d.push(&x.field, text(&|g| self.x.label(g.x).to_string()));
        }
        if let Some(c) = &self.color_field {
            d.push(c, text(&|g| self.groups.label(g.group).to_string()));
        }
        let number =
            |f: &dyn Fn(&BoxStats) -> f64| DerivedColumn::Number(self.list.iter().map(|g| f(&g.stats)).collect());
        d.push("n", number(&|s| s.n as f64));
        d.push("min", number(&|s| s.min));
        d.push("q1", number(&|s| s.q1));
        d.push("median", number(&|s| s.median));
        d.push("q3", number(&|s| s.q3));
        d.push("max", number(&|s| s.max));
        d.push("mean", number(&|s| s.mean));
        d.push("whisker_low", number(&|s| s.whisker_low));
        d.push("whisker_high", number(&|s| s.whisker_high));
        d.push("outliers", number(&|s| s.outliers.len() as f64));
        for (name, column) in extra {
            d.push(name, column);
        }
        d
    }
}

/// Up to five group names quoted, then how many more, for messages.
pub fn quoted(groups: &[String]) -> String {
    let shown: Vec<String> = groups.iter().take(5).map(|g| format!("`{g}`")).collect();
    match groups.len().saturating_sub(shown.len()) {
        0 => shown.join(", "),
        more => format!("{} and {more} more groups", shown.join(", ")),
    }
}

/// "n = 50", or "50" when `long` is false.
fn count_text(n: usize, long: bool) -> String {
    if long { format!("n = {n}") } else { n.to_string() }
}

/// The laid-out frame of a distribution chart.
pub struct Layout {
    /// The frame.
    pub frame: Frame,
    /// Its theme.
    pub theme: Theme,
    /// The categories' scale.
    band: BandScale,
    /// The values' scale.
    value: Scale,
    /// Which axis holds the values.
    orientation: Orientation,
}

impl Layout {
    /// The plot area.
    pub fn plot(&self) -> Rect {
        self.frame.plot
    }

    /// The span `(start, width)` of a group's slot across the category axis, in pixels.
    pub fn slot(&self, grouped: &Grouped, g: &Group) -> (f64, f64) {
        let band = self.band.band_of(grouped.x.label(g.x)).unwrap_or(0);
        let (start, width) = match grouped.dodge {
            true => bands::dodged(&self.band, band, &grouped.groups.labels, g.group),
            false => (self.band.start(band), self.band.bandwidth()),
        };
        let narrowed = width.min(MAX_SLOT);
        (start + (width - narrowed) / 2.0, narrowed)
    }

    /// The pixel position of value `v` along the value axis.
    pub fn value_px(&self, v: f64) -> f64 {
        self.value.map(v)
    }

    /// The canvas point `across` pixels along the category axis at value `v`.
    pub fn at(&self, across: f64, v: f64) -> Point {
        self.px(across, self.value_px(v))
    }

    /// The canvas point `across` pixels along the category axis and `along` the value axis.
    pub fn px(&self, across: f64, along: f64) -> Point {
        match self.orientation {
            Orientation::Vertical => Point::new(across, along),
            Orientation::Horizontal => Point::new(along, across),
        }
    }

    /// The rectangle from `a0` to `a1` across and from value `v0` to `v1`.
    pub fn rect(&self, a0: f64, a1: f64, v0: f64, v1: f64) -> Rect {
        let (p, q) = (self.at(a0, v0), self.at(a1, v1));
        Rect::new(p.x.min(q.x), p.y.min(q.y), (p.x - q.x).abs(), (p.y - q.y).abs())
    }

    /// The count of each group at the low end of the value axis, centred on its slot: "n = 50",
    /// or "50" where that does not fit; none, with a note, where neither fits.
    pub fn counts(&self, grouped: &Grouped) -> (Vec<Item>, Option<Warning>) {
        let size = self.theme.caption_size;
        let plot = self.plot();
        let fits = |g: &Group, long: bool| {
            let (_, width) = self.slot(grouped, g);
            let m = crate::text::measure(&count_text(g.stats.n, long), size);
            match self.orientation {
                Orientation::Vertical => m.width <= width + 2.0,
                Orientation::Horizontal => (m.ascent + m.descent) <= width,
            }
        };
        let long = grouped.list.iter().all(|g| fits(g, true));
        if !long && !grouped.list.iter().all(|g| fits(g, false)) {
            let note = format!(
                "the {} are too narrow to show their counts; `--format csv` lists them (column `n`)",
                if grouped.list.len() > 1 { "groups" } else { "group" }
            );
            return (Vec::new(), Some(Warning::from(note)));
        }
        let items = grouped
            .list
            .iter()
            .map(|g| {
                let (start, width) = self.slot(grouped, g);
                let centre = start + width / 2.0;
                let (at, anchor, baseline) = match self.orientation {
                    Orientation::Vertical => {
                        (Point::new(centre, plot.bottom() - 3.0), Anchor::Middle, Baseline::Bottom)
                    }
                    Orientation::Horizontal => (Point::new(plot.x + 4.0, centre), Anchor::Start, Baseline::Middle),
                };
                Item::text(
                    Role::Annotation,
                    Text {
                        at,
                        content: count_text(g.stats.n, long),
                        size,
                        anchor,
                        baseline,
                        angle: 0.0,
                        color: self.theme.muted_text,
                    },
                )
                .labelled(format!("count: {}", grouped.label(g)))
            })
            .collect();
        (items, None)
    }

    /// The rows of a selection as points in their colours, spread across the middle of their
    /// group's slot (by a hash of the row, so the same row always lands in the same place), and
    /// the brushed range of the values; nothing without a selection.
    pub fn selection(&self, grouped: &Grouped, highlight: Option<&Highlight>) -> Vec<Item> {
        let Some(h) = highlight else { return Vec::new() };
        let (field, scale) = (&grouped.y.field, &self.value);
        let brushed = match self.orientation {
            Orientation::Vertical => highlight::brush(h, self.plot(), ("", &self.frame.x), Some((field, scale))),
            Orientation::Horizontal => highlight::brush(h, self.plot(), (field, scale), None),
        };
        let mut items: Vec<Item> = brushed.into_iter().collect();
        let (mut centers, mut rows) = (Vec::new(), Vec::new());
        for g in &grouped.list {
            let (start, width) = self.slot(grouped, g);
            for (&r, &v) in g.rows.iter().zip(&g.values).filter(|(r, _)| h.contains(**r)) {
                let spread = (mix64(u64::from(r)) >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                centers.push(self.at(start + width * (0.5 + 0.6 * spread), v));
                rows.push(r);
            }
        }
        if !rows.is_empty() {
            let fill = highlight::point_fill(&grouped.colors, &rows, false, 0.9);
            let stroke = Some(Stroke::solid(Color::WHITE.with_opacity(0.8), 0.6));
            let batch = PointBatch { centers, radius: PerPoint::Uniform(SELECTED_RADIUS), fill, stroke };
            items.push(
                Item::new(Role::DataMark, Shape::Points(batch), Default::default())
                    .with_rows(rows)
                    .labelled(format!("{} (selected)", h.name)),
            );
        }
        items
    }

    /// Values drawn one by one on their groups' centre lines (outliers, groups without a
    /// density), given as (group, position in the group): one point batch in the groups'
    /// colours; under a selection, grey circles each with its row, which a brush in the
    /// explorer leaves grey (the selection's own points stand for the selected rows).
    pub fn dots(&self, grouped: &Grouped, dots: &[(&Group, usize)], context: bool, label: &str) -> Vec<Item> {
        let (mut centers, mut rows, mut fills) = (Vec::new(), Vec::new(), Vec::new());
        for &(g, i) in dots {
            let (Some(&r), Some(&v)) = (g.rows.get(i), g.values.get(i)) else { continue };
            let (start, width) = self.slot(grouped, g);
            centers.push(self.at(start + width / 2.0, v));
            rows.push(r);
            fills.push(if context { highlight::CONTEXT } else { grouped.fill(g, false).with_opacity(1.0) });
        }
        let stroke = Stroke::solid(Grouped::ink(context), 0.8);
        if context {
            let style = Style { fill: Some(highlight::CONTEXT), stroke: Some(stroke) };
            return centers
                .into_iter()
                .zip(rows)
                .map(|(center, r)| {
                    Item::new(Role::DataMark, Shape::Circle { center, radius: DOT_RADIUS }, style.clone())
                        .with_rows(vec![r])
                        .labelled(label)
                })
                .collect();
        }
        let Some(&first) = fills.first() else { return Vec::new() };
        let fill = if fills.iter().all(|&f| f == first) { PerPoint::Uniform(first) } else { PerPoint::Each(fills) };
        let batch = PointBatch { centers, radius: PerPoint::Uniform(DOT_RADIUS), fill, stroke: Some(stroke) };
        vec![Item::new(Role::DataMark, Shape::Points(batch), Style::default()).with_rows(rows).labelled(label)]
    }

    /// The chart's scene with `marks` in the plot, noting in `warnings` a selection's points
    /// that the SVG carries as a raster (a selection of more rows than a vector layer holds),
    /// and its plot for the explorer: brushed by the values' column and the categories' column.
    pub fn scene(
        self,
        chart: &Chart,
        grouped: &Grouped,
        table: &Table,
        marks: Vec<Item>,
        warnings: &mut Vec<Warning>,
    ) -> (Scene, Geometry) {
        warnings.extend(frame::raster_note(&marks).map(Warning::from));
        let values = table.column(&grouped.y.field).map(|c| (grouped.y.field.as_str(), c));
        let categories = grouped.x_channel.as_ref().and_then(|x| table.column(&x.field).map(|c| (x.field.as_str(), c)));
        let (x, y) = match self.orientation {
            Orientation::Vertical => (categories, values),
            Orientation::Horizontal => (values, categories),
        };
        let plot = Plot::of_frame(&self.frame, x, y);
        (frame::scene(chart, self.frame, &self.theme, marks, warnings), Geometry::of_plot(plot))
    }
}

/// The cartesian axes of a distribution chart as the spec declares them (for lint): the values'
/// axis, and the categories' axis on a band scale when `x` is given.
pub fn axes(x: Option<&Channel>, y: &Channel, orientation: Orientation) -> Vec<AxisSpec> {
    let (categories, values) = match orientation {
        Orientation::Vertical => ("x axis", "y axis"),
        Orientation::Horizontal => ("y axis", "x axis"),
    };
    let mut axes = vec![AxisSpec { name: values, key: "y", options: y.options() }];
    if let Some(x) = x {
        let mut options = x.options();
        options.scale = Some(ScaleKind::Band);
        axes.push(AxisSpec { name: categories, key: "x", options });
    }
    axes
}
