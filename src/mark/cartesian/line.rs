//! `line`: one or more series drawn as polylines through (x, y), sorted by x, broken at dropped rows.

use crate::data::{Categories, Column, Table};
use crate::guide::axis::title_with_unit;
use crate::guide::layout::Domain;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode;
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, frame};
use crate::scene::{Color, Item, PathCmd, PerPoint, Point, PointBatch, Role, Shape, Stroke, Style};
use crate::spec::{Channel, Chart, ColorChannel, ColorType, OneOrMany};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "line"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct LineOptions {
    /// Horizontal position: a column name or a table with `field`, `title`, `unit`, `scale`, ...
    #[schemars(example = &"date")]
    pub x: Channel,
    /// Vertical position: one column (long form, split by `series`) or several (one series each).
    #[schemars(example = &"price")]
    pub y: OneOrMany<Channel>,
    /// Column whose values split the rows into series (long-form data).
    #[serde(default)]
    pub series: Option<String>,
    /// Split the rows into series by a column's categories, one colour each, as `series` does
    /// (how Vega-Lite and ggplot write it); a table adds the colour options (`scheme`, `domain`,
    /// `range`, `title`, `legend`), and a category has the same colour as in the spec's other
    /// charts colouring by that column. Give this or `series`, not both.
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Title of the y axis when several y columns are drawn (their own titles name the series).
    #[serde(default)]
    pub y_title: Option<String>,
    /// Draw a marker at every data point.
    #[serde(default)]
    pub markers: Option<bool>,
    /// Line width in pixels, at most 100 (default 2).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100), example = 2)]
    pub stroke_width: Option<f64>,
    /// Categorical colour scheme for the series (default `okabe-ito`).
    #[serde(default)]
    pub scheme: Option<String>,
    /// Line colour when there is a single series (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
    /// An uncertainty band around each series: `{ lower = "COLUMN", upper = "COLUMN" }` (an
    /// interval per row, e.g. a confidence interval or a min–max range computed by a
    /// transform), shaded in the series' colour. Needs a single `y` column.
    #[serde(default)]
    pub band: Option<LineBand>,
}

/// The interval shaded around a line.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct LineBand {
    /// The column of the band's lower edge.
    #[schemars(example = &"low")]
    pub lower: String,
    /// The column of the band's upper edge.
    #[schemars(example = &"high")]
    pub upper: String,
    /// Fill opacity, above 0 and at most 1 (default 0.25).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 1), example = 0.25)]
    pub opacity: Option<f64>,
}

impl LineOptions {
    /// The column splitting the rows into series: `series`, else the `color` encoding's field.
    pub fn split_field(&self) -> Option<&str> {
        self.series.as_deref().or(self.color.as_ref().map(ColorChannel::field))
    }
}

/// One series: its name, colour, the rows it draws (sorted by x) and all rows that belong to it
/// (drawn or dropped), so that only its own missing values break its line.
struct Series<'t> {
    name: String,
    y: &'t Column,
    rows: Vec<u32>,
    members: Vec<u32>,
    color: Color,
}

/// Draw a line chart.
pub fn draw(chart: &Chart, options: &LineOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_channels = options.y.as_slice();
    if y_channels.is_empty() {
        return Err(MarkError::at(
            &["y"],
            format!("`y` lists no columns"),
            "name at least one column, e.g. y = \"value\"",
        ));
    }
    // The chart's `scheme` colours the categories unless the encoding names its own.
    let color = options.color.as_ref().map(|c| {
        let mut o = c.options();
        o.scheme = o.scheme.or_else(|| options.scheme.clone());
        o
    });
    let split_key = if color.is_some() { "color" } else { "series" };
    if options.series.is_some() && color.is_some() {
        return Err(MarkError::at(
            &["color"],
            format!("`series` and `color` both split the rows into series"),
            "keep one: `color = \"COLUMN\"` (with colour options as a table) or `series = \"COLUMN\"`",
        ));
    }
    if color.as_ref().is_some_and(|c| c.r#type == Some(ColorType::Continuous)) {
        return Err(MarkError::at(
            &["color", "type"],
            format!("a line chart's `color` splits the rows into series by category"),
            "remove `type = \"continuous\"`; to show a quantity along the line, use a scatter chart's `color`",
        ));
    }
    let split_field = options.split_field();
    if split_field.is_some() && y_channels.len() > 1 {
        return Err(MarkError::at(
            &[split_key],
            format!("`{split_key}` splits one `y` column, but {} are given", y_channels.len()),
            "either list several y columns (wide data) or give one y column and `series` (long data)",
        ));
    }
    let mut y_cols = Vec::new();
    for (i, channel) in y_channels.iter().enumerate() {
        let key_path: &[&str] = &["y"];
        let col = encode::column(chart, key_path[0], channel.field(), table).map_err(|mut e| {
            if y_channels.len() > 1 {
                e.path.push(crate::spec::PathSeg::Index(i));
            }
            e
        })?;
        if col.numbers().is_none() {
            return Err(MarkError::at(
                &["y"],
                format!("y column `{}` holds text; a line needs numbers", channel.field()),
                "use a numeric column for y (put categories in `series`)",
            ));
        }
        y_cols.push((channel, col));
    }
    let series_col = match split_field {
        Some(field) => Some(encode::column(chart, split_key, field, table)?),
        None => None,
    };
    let band = band_columns(chart, options, table, y_cols.len())?;

    // Non-finite policy: rows with a non-finite x (or y) are dropped and counted.
    let mut numeric: Vec<(&str, &Column)> = Vec::new();
    if x_col.numbers().is_some() {
        numeric.push((x_opts.field.as_str(), x_col));
    }
    let mut warnings = Vec::new();
    let all_rows: Vec<u32> = (0..table.rows as u32).collect();
    let palette = encode::palette(&["scheme"], options.scheme.as_deref())?;
    let single_color = encode::fixed_color(options.mark_color.as_deref())?;

    let split_categories = series_col.map(|sc| sc.categories().cloned().unwrap_or_else(|| numeric_categories(sc)));
    let mut series: Vec<Series> = Vec::new();
    for (channel, col) in &y_cols {
        let mut used = numeric.clone();
        used.push((channel.field(), col));
        let y_opts = channel.options();
        let log = encode::log_fields(&[&x_opts, &y_opts]);
        let (kept, warning) = encode::placeable_rows(&chart.name, table.rows, &used, &log);
        warnings.extend((warning).into_iter().map(Warning::from));
        let title = channel.options().title.unwrap_or_else(|| channel.field().to_string());
        match &split_categories {
            Some(cats) => {
                // One pass over the rows buckets them by series (rows with no series are left out).
                let bucket = |rows: &mut dyn Iterator<Item = u32>| {
                    let mut by_code: Vec<Vec<u32>> = vec![Vec::new(); cats.levels.len()];
                    for r in rows {
                        if let Some(b) = cats.codes.get(r as usize).and_then(|&c| by_code.get_mut(c as usize)) {
                            b.push(r);
                        }
                    }
                    by_code
                };
                let members = bucket(&mut all_rows.iter().copied());
                let drawn = bucket(&mut kept.iter().copied());
                for ((level, rows), members) in cats.levels.iter().zip(drawn).zip(members) {
                    if !rows.is_empty() {
                        series.push(Series { name: level.clone(), y: col, rows, members, color: Color::BLACK });
                    }
                }
            }
            None => {
                series.push(Series { name: title, y: col, rows: kept, members: all_rows.clone(), color: Color::BLACK })
            }
        }
    }
    series.retain(|s| !s.rows.is_empty());
    if series.is_empty() {
        return Err(encode::no_rows(chart, table, warnings.first()));
    }
    let n_series = series.len();
    // With `color`, each category's colour follows the encoding (its domain, range or scheme).
    let by_category = match (&color, &split_categories) {
        (Some(options), Some(cats)) => {
            let drawn: Vec<u32> = series.iter().flat_map(|s| s.rows.iter().copied()).collect();
            let (per_level, entries) = crate::mark::categorical::assign(options, cats, &drawn)?;
            let colours: std::collections::HashMap<String, Color> =
                cats.levels.iter().cloned().zip(per_level).collect();
            Some((colours, entries))
        }
        _ => None,
    };
    for (i, s) in series.iter_mut().enumerate() {
        s.color = match &by_category {
            Some((colours, _)) => colours.get(&s.name).copied().unwrap_or(single_color),
            None if n_series == 1 => single_color,
            None => palette.get(i % palette.len().max(1)).copied().unwrap_or(single_color),
        };
    }
    let x_numbers = x_col.numbers();
    let band_order = x_col.categories();
    for s in &mut series {
        sort_rows(&mut s.rows, x_numbers, band_order);
    }

    // Axes: x from the x channel; y from the union of all series.
    let all_series_rows: Vec<u32> = {
        let mut v: Vec<u32> = series.iter().flat_map(|s| s.rows.iter().copied()).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let x_axis = encode::position_axis("x", &x_opts, x_col, &all_series_rows)?;
    let first_y = y_cols[0].0.options();
    let mut y_axis = encode::position_axis("y", &first_y, y_cols[0].1, &series[0].rows)?;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for s in &series {
        if let Some((a, b)) = encode::extent(s.y.numbers().unwrap_or(&[]), &s.rows) {
            lo = lo.min(a);
            hi = hi.max(b);
        }
    }
    if let Some((lower, upper, _)) = &band {
        for s in &series {
            for col in [lower, upper] {
                if let Some((a, b)) = encode::extent(col.numbers().unwrap_or(&[]), &s.rows) {
                    lo = lo.min(a);
                    hi = hi.max(b);
                }
            }
        }
    }
    if first_y.domain.is_none() && lo <= hi {
        if first_y.zero == Some(true) {
            lo = lo.min(0.0);
            hi = hi.max(0.0);
        }
        y_axis.domain = Domain::Continuous(lo, hi);
    }
    if y_cols.len() > 1 {
        // Several y columns: the channel titles name the series (in the legend); the axis gets
        // `y_title` or the joined names, with the first unit any channel gives.
        let names: Vec<String> =
            y_cols.iter().map(|(c, _)| c.options().title.unwrap_or_else(|| c.field().to_string())).collect();
        let unit = y_cols.iter().find_map(|(c, _)| c.options().unit);
        let title = options.y_title.clone().unwrap_or_else(|| names.join(", "));
        y_axis.title = title_with_unit(&title, unit.as_deref());
    } else if let Some(t) = &options.y_title {
        y_axis.title = title_with_unit(t, first_y.unit.as_deref());
    }
    let stroke_width = options.stroke_width.unwrap_or(2.0);
    let markers = options.markers.unwrap_or(false);
    let inset = if markers { stroke_width * 1.6 + 1.5 } else { stroke_width / 2.0 + 0.5 };
    y_axis.inset = inset;
    let mut x_axis = x_axis;
    x_axis.inset = inset;
    let legends = match (&color, by_category) {
        (Some(options), Some((_, entries))) => {
            let title = title_with_unit(options.title.as_deref().unwrap_or(&options.field), options.unit.as_deref());
            encode::shown_legends(Legend::Categorical { title, entries, symbol: Symbol::Line }, options)
        }
        _ if n_series > 1 => vec![Legend::Categorical {
            title: options.series.clone().unwrap_or_default(),
            entries: series.iter().map(|s| (s.name.clone(), s.color)).collect(),
            symbol: Symbol::Line,
        }],
        _ => Vec::new(),
    };

    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, legends)?;

    let mut marks = Vec::new();
    if let Some((lower, upper, opacity)) = &band {
        for s in &series {
            marks.extend(band_marks(&frame, x_col, (lower, upper), s, *opacity));
        }
    }
    let mut derived_series = Vec::new();
    let mut derived_y = Vec::new();
    let mut derived_rows = Vec::new();
    for s in &series {
        let dropped = dropped_between(&s.rows, &s.members, x_numbers, s.y.numbers());
        let mut cmds = Vec::with_capacity(s.rows.len() + 1);
        let mut centers = Vec::new();
        let mut pen_down = false;
        let x_at = encode::Positioner::new(&frame.x, x_col);
        let y_at = encode::Positioner::new(&frame.y, s.y);
        for (k, &r) in s.rows.iter().enumerate() {
            let p = Point::new(x_at.at(r), y_at.at(r));
            if dropped.get(k).copied().unwrap_or(false) {
                pen_down = false;
            }
            cmds.push(if pen_down { PathCmd::LineTo(p) } else { PathCmd::MoveTo(p) });
            pen_down = true;
            centers.push(p);
            derived_series.push(s.name.clone());
            derived_rows.push(r);
            derived_y.push(s.y.numbers().and_then(|v| v.get(r as usize)).copied().unwrap_or(f64::NAN));
        }
        let mut style = Style::stroke(s.color, stroke_width);
        if let Some(stroke) = style.stroke.as_mut() {
            stroke.width = stroke_width;
        }
        marks.push(
            Item::new(Role::DataMark, Shape::Path(cmds), style).with_rows(s.rows.clone()).labelled(s.name.clone()),
        );
        if markers {
            marks.push(
                Item::new(
                    Role::DataMark,
                    Shape::Points(PointBatch {
                        centers,
                        radius: PerPoint::Uniform(stroke_width * 1.6),
                        fill: PerPoint::Uniform(s.color),
                        stroke: Some(Stroke::solid(Color::WHITE, 1.0)),
                    }),
                    Style::default(),
                )
                .with_rows(s.rows.clone())
                .labelled(s.name.clone()),
            );
        }
    }
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

    let mut derived = Derived::over(derived_rows);
    derived.push("series", DerivedColumn::Text(derived_series));
    derived.push("row", DerivedColumn::RowIndex);
    derived.push(&x_opts.field, DerivedColumn::Source(x_opts.field.clone()));
    derived.push("y", DerivedColumn::Number(derived_y));
    Ok(ChartOutput { scene, derived, warnings, geojson: None, geometry: Default::default() })
}

/// The band's lower and upper columns and its opacity, checked: numeric, and a single `y`.
fn band_columns<'t>(
    chart: &Chart,
    options: &LineOptions,
    table: &'t Table,
    y_count: usize,
) -> Result<Option<(&'t Column, &'t Column, f64)>, MarkError> {
    let Some(band) = &options.band else { return Ok(None) };
    if y_count > 1 {
        return Err(MarkError::at(
            &["band"],
            format!("a band surrounds one y column's line, but {y_count} y columns are given"),
            "give one y column (long data split by `series` or `color` gets a band per series)",
        ));
    }
    let mut columns = Vec::new();
    for (key, field) in [("lower", &band.lower), ("upper", &band.upper)] {
        let col = encode::column(chart, "band", field, table).map_err(|mut e| {
            e.path.push(crate::spec::PathSeg::Key(key.into()));
            e
        })?;
        if col.numbers().is_none() || col.is_time() {
            return Err(MarkError::at(
                &["band", key],
                format!(
                    "band {key} column `{field}` holds {}; a band's edges are numbers on the y scale",
                    col.type_name()
                ),
                "name numeric columns computed for the interval (a `calculate` or `aggregate` transform)",
            ));
        }
        columns.push(col);
    }
    Ok(Some((columns[0], columns[1], band.opacity.unwrap_or(0.25))))
}

/// The shaded band of one series: one polygon per run of rows whose edges are both finite,
/// upper edge forward and lower edge back.
fn band_marks(
    frame: &crate::guide::layout::Frame,
    x_col: &Column,
    (lower, upper): (&Column, &Column),
    s: &Series<'_>,
    opacity: f64,
) -> Vec<Item> {
    let (lo, hi) = (lower.numbers().unwrap_or(&[]), upper.numbers().unwrap_or(&[]));
    let x_at = encode::Positioner::new(&frame.x, x_col);
    let finite =
        |r: u32| lo.get(r as usize).is_some_and(|v| v.is_finite()) && hi.get(r as usize).is_some_and(|v| v.is_finite());
    let mut items = Vec::new();
    for run in s.rows.split(|&r| !finite(r)).filter(|run| !run.is_empty()) {
        let mut cmds: Vec<PathCmd> = Vec::with_capacity(2 * run.len() + 1);
        for (k, &r) in run.iter().enumerate() {
            let p = Point::new(x_at.at(r), frame.y.map(hi[r as usize]));
            cmds.push(if k == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) });
        }
        for &r in run.iter().rev() {
            cmds.push(PathCmd::LineTo(Point::new(x_at.at(r), frame.y.map(lo[r as usize]))));
        }
        cmds.push(PathCmd::Close);
        items.push(
            Item::new(Role::DataMark, Shape::Path(cmds), Style::fill(s.color.with_opacity(opacity)))
                .with_rows(run.to_vec())
                .labelled(format!("{} band", s.name)),
        );
    }
    items
}

/// Numbers as categories (a numeric `series` column).
fn numeric_categories(col: &Column) -> Categories {
    let texts: Vec<Option<String>> = col
        .numbers()
        .unwrap_or(&[])
        .iter()
        .map(|v| v.is_finite().then(|| crate::guide::format::format_value(*v)))
        .collect();
    Categories::from_values(texts.iter().map(|t| t.as_deref()))
}

/// Sort rows by x (numbers or category order), stable so ties keep data order.
fn sort_rows(rows: &mut [u32], x: Option<&[f64]>, cats: Option<&Categories>) {
    if let Some(values) = x {
        rows.sort_by(|&a, &b| {
            let va = values.get(a as usize).copied().unwrap_or(f64::NAN);
            let vb = values.get(b as usize).copied().unwrap_or(f64::NAN);
            va.total_cmp(&vb)
        });
    } else if let Some(c) = cats {
        rows.sort_by_key(|&r| c.codes.get(r as usize).copied().unwrap_or(u32::MAX));
    }
}

/// For each kept row (sorted by x), whether a dropped row lies between it and the previous kept
/// row in x order: the line is broken there rather than drawn across the missing data.
fn dropped_between(kept: &[u32], all: &[u32], x: Option<&[f64]>, y: Option<&[f64]>) -> Vec<bool> {
    let (Some(x), Some(y)) = (x, y) else { return vec![false; kept.len()] };
    // x positions of rows whose x is finite but y is not: gaps in the series.
    let mut gaps: Vec<f64> = all
        .iter()
        .filter_map(|&r| {
            let xv = *x.get(r as usize)?;
            let yv = *y.get(r as usize)?;
            (xv.is_finite() && !yv.is_finite()).then_some(xv)
        })
        .collect();
    gaps.sort_by(f64::total_cmp);
    let mut out = vec![false; kept.len()];
    for k in 1..kept.len() {
        let a = x.get(kept[k - 1] as usize).copied().unwrap_or(f64::NAN);
        let b = x.get(kept[k] as usize).copied().unwrap_or(f64::NAN);
        let i = gaps.partition_point(|g| *g <= a);
        if gaps.get(i).is_some_and(|g| *g < b || (*g == b && a < b)) {
            out[k] = true;
        }
    }
    out
}

/// `kind = "line"`.
pub static KIND: KindInfo = KindInfo::new("line", &["x", "y", "series", "color", "band"])
    .taking_aspect()
    .faceted(crate::mark::registry::Faceting::Frame)
    .drawing_annotations();

impl Technique for LineOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        // The y axis is the first y column's.
        self.y.as_slice().first().map_or_else(Vec::new, |y| AxisSpec::pair(&self.x, y))
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }

    crate::mark::registry::color_key!();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaps_break_the_line_only_where_y_is_missing() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let y = [1.0, f64::NAN, 2.0, 3.0];
        let kept = [0u32, 2, 3];
        let all = [0u32, 1, 2, 3];
        assert_eq!(dropped_between(&kept, &all, Some(&x), Some(&y)), vec![false, true, false]);
    }

    #[test]
    fn rows_sort_by_x_stably() {
        let x = [3.0, 1.0, 2.0, 1.0];
        let mut rows = vec![0u32, 1, 2, 3];
        sort_rows(&mut rows, Some(&x), None);
        assert_eq!(rows, vec![1, 3, 2, 0]);
    }
}
