//! `line`: one or more series drawn as polylines through (x, y), sorted by x, broken at dropped rows.

use crate::data::{Categories, Column, Table};
use crate::guide::axis::title_with_unit;
use crate::guide::layout::Domain;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode;
use crate::mark::geometry::{Geometry, Plot};
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::spread::{Spread, Summary};
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
    /// transform), shaded in the series' colour; or a spread of the rows themselves, `"stdev"`,
    /// `"sem"`, `"ci95"` or `"minmax"` (`{ spread, opacity }` as a table): the rows of a series
    /// that share an x are then drawn as their mean, with the band around it. Needs a single `y`
    /// column.
    #[serde(default)]
    pub band: Option<LineBand>,
}

/// The interval shaded around a line: a spread computed from the rows, or a table of options.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum LineBand {
    /// `"stdev"`, `"sem"`, `"ci95"` or `"minmax"` of the rows at each x, around their mean.
    Spread(Spread),
    /// `{ lower, upper, opacity }` or `{ spread, opacity }`.
    Detailed(LineBandOptions),
}

/// The interval shaded around a line: two columns, or a spread of the rows at each x.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct LineBandOptions {
    /// The column of the band's lower edge (with `upper`).
    #[serde(default)]
    #[schemars(example = &"low")]
    pub lower: Option<String>,
    /// The column of the band's upper edge (with `lower`).
    #[serde(default)]
    #[schemars(example = &"high")]
    pub upper: Option<String>,
    /// Instead of `lower` and `upper`: the spread of the rows sharing an x, around their mean
    /// (`"stdev"`, `"sem"`, `"ci95"` or `"minmax"`).
    #[serde(default)]
    pub spread: Option<Spread>,
    /// Fill opacity, above 0 and at most 1 (default 0.25).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 1), example = 0.25)]
    pub opacity: Option<f64>,
}

impl LineOptions {
    /// Whether the line draws the mean of the rows at each x (a band computed from their spread).
    pub fn averages_rows(&self) -> bool {
        matches!(
            &self.band,
            Some(LineBand::Spread(_)) | Some(LineBand::Detailed(LineBandOptions { spread: Some(_), .. }))
        )
    }

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
    let band = band_spec(chart, options, table, y_cols.len())?;

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
    // The points each line passes through: one per row, or with a spread band one per x, the
    // mean of the rows there.
    let spread = match &band {
        Some((Band::Spread(spread), _)) => Some(*spread),
        _ => None,
    };
    let vertices: Vec<Vec<Vertex>> = series.iter().map(|s| vertices(s, x_col, band.as_ref().map(|b| &b.0))).collect();
    if spread.is_some() {
        let single = vertices.iter().flatten().filter(|v| v.span.len() < 2).count();
        if single > 0 {
            warnings.push(Warning::from(format!(
                "{single} of {} points rest on a single row and have no band there: a spread needs at least two rows at an x",
                vertices.iter().map(Vec::len).sum::<usize>()
            )));
        }
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
    if spread.is_some() {
        // The means and the band's edges.
        let ends = vertices.iter().flatten().flat_map(|v| [Some(v.y), v.band.map(|b| b.0), v.band.map(|b| b.1)]);
        if let Some((a, b)) = encode::finite_extent(ends.flatten()) {
            (lo, hi) = (a, b);
        }
    } else {
        for s in &series {
            if let Some((a, b)) = encode::extent(s.y.numbers().unwrap_or(&[]), &s.rows) {
                lo = lo.min(a);
                hi = hi.max(b);
            }
        }
    }
    if let Some((Band::Columns(lower, upper), _)) = &band {
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
    if let Some(spread) = spread {
        // Say that the line is a mean, and what the band is.
        y_axis.title = match first_y.title.is_some() || options.y_title.is_some() {
            true => format!("{}, mean {}", y_axis.title, spread.describe()),
            false => format!(
                "{} {}",
                title_with_unit(&format!("Mean of {}", first_y.field), first_y.unit.as_deref()),
                spread.describe()
            ),
        };
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
    if let Some((_, opacity)) = &band {
        for (s, vs) in series.iter().zip(&vertices) {
            marks.extend(band_marks(&frame, x_col, s, vs, *opacity));
        }
    }
    let mut derived_series = Vec::new();
    let mut derived_y = Vec::new();
    let mut derived_rows = Vec::new();
    let mut derived_band: (Vec<f64>, Vec<f64>, Vec<f64>) = Default::default();
    let x_at = encode::Positioner::new(&frame.x, x_col);
    for (s, vs) in series.iter().zip(&vertices) {
        let firsts: Vec<u32> = vs.iter().map(|v| s.rows[v.span.start]).collect();
        let dropped = dropped_between(&firsts, &s.members, x_numbers, s.y.numbers());
        let mut cmds = Vec::with_capacity(vs.len() + 1);
        let mut centers = Vec::new();
        let mut pen_down = false;
        for (k, (v, &r)) in vs.iter().zip(&firsts).enumerate() {
            let p = Point::new(x_at.at(r), frame.y.map(v.y));
            if dropped.get(k).copied().unwrap_or(false) {
                pen_down = false;
            }
            cmds.push(if pen_down { PathCmd::LineTo(p) } else { PathCmd::MoveTo(p) });
            pen_down = true;
            centers.push(p);
            derived_series.push(s.name.clone());
            derived_rows.push(r);
            derived_y.push(v.y);
            derived_band.0.push(v.band.map_or(f64::NAN, |b| b.0));
            derived_band.1.push(v.band.map_or(f64::NAN, |b| b.1));
            derived_band.2.push(v.span.len() as f64);
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
    // One y column drawn row by row places its values; means of rows (a spread band) and several
    // y columns do not, and a brush selects by x alone then.
    let y_placed = match y_cols.as_slice() {
        [(channel, col)] if spread.is_none() => Some((channel.field(), *col)),
        _ => None,
    };
    let geometry = Geometry::of_plot(Plot::of_frame(&frame, Some((&x_opts.field, x_col)), y_placed));
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

    let mut derived = Derived::over(derived_rows);
    derived.push("series", DerivedColumn::Text(derived_series));
    if spread.is_some() {
        // One row per point: the mean of the rows at an x, the band around it and their count.
        derived.push(&x_opts.field, DerivedColumn::Source(x_opts.field.clone()));
        derived.push("y", DerivedColumn::Number(derived_y));
        derived.push("lower", DerivedColumn::Number(derived_band.0));
        derived.push("upper", DerivedColumn::Number(derived_band.1));
        derived.push("rows", DerivedColumn::Number(derived_band.2));
    } else {
        derived.push("row", DerivedColumn::RowIndex);
        derived.push(&x_opts.field, DerivedColumn::Source(x_opts.field.clone()));
        derived.push("y", DerivedColumn::Number(derived_y));
    }
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// Where a line's band comes from: two columns, or a spread of the rows at each x.
enum Band<'t> {
    Columns(&'t Column, &'t Column),
    Spread(Spread),
}

/// The band option checked, with its opacity: numeric edge columns or a spread, and a single
/// `y`.
fn band_spec<'t>(
    chart: &Chart,
    options: &LineOptions,
    table: &'t Table,
    y_count: usize,
) -> Result<Option<(Band<'t>, f64)>, MarkError> {
    let Some(band) = &options.band else { return Ok(None) };
    if y_count > 1 {
        return Err(MarkError::at(
            &["band"],
            format!("a band surrounds one y column's line, but {y_count} y columns are given"),
            "give one y column (long data split by `series` or `color` gets a band per series)",
        ));
    }
    let detailed = match band {
        LineBand::Spread(spread) => return Ok(Some((Band::Spread(*spread), 0.25))),
        LineBand::Detailed(d) => d,
    };
    let opacity = detailed.opacity.unwrap_or(0.25);
    let (lower, upper) = match (&detailed.lower, &detailed.upper, detailed.spread) {
        (None, None, Some(spread)) => return Ok(Some((Band::Spread(spread), opacity))),
        (Some(lower), Some(upper), None) => (lower, upper),
        (_, _, Some(spread)) => {
            return Err(MarkError::at(
                &["band", "spread"],
                format!(
                    "`spread = \"{}\"` computes the band from the rows, so it takes no `lower` or `upper` column",
                    spread.name()
                ),
                "keep `spread` (the band around the mean of the rows at each x) or `lower` and `upper` (columns holding the band's edges)",
            ));
        }
        (lower, _, None) => {
            let missing = if lower.is_none() { "lower" } else { "upper" };
            return Err(MarkError::at(
                &["band"],
                format!("the band has no `{missing}` edge"),
                "give both `lower` and `upper` columns, or a `spread` of the rows (\"stdev\", \"sem\", \"ci95\" or \"minmax\")",
            ));
        }
    };
    let mut columns = Vec::new();
    for (key, field) in [("lower", lower), ("upper", upper)] {
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
    Ok(Some((Band::Columns(columns[0], columns[1]), opacity)))
}

/// One point a line passes through: the span of its series' sorted rows it stands for (one row,
/// or all rows at its x when a spread band averages them), its y value and its band interval.
struct Vertex {
    span: std::ops::Range<usize>,
    y: f64,
    band: Option<(f64, f64)>,
}

/// The points of one series (its rows sorted by x): a row each, its band from the edge
/// columns where both are finite; or, with a spread band, the mean of each run of rows with the
/// same x, the spread around it where the run has two rows or more.
fn vertices(s: &Series<'_>, x_col: &Column, band: Option<&Band<'_>>) -> Vec<Vertex> {
    let ys = s.y.numbers().unwrap_or(&[]);
    let y_of = |r: u32| ys.get(r as usize).copied().unwrap_or(f64::NAN);
    match band {
        Some(Band::Spread(spread)) => {
            let mut out = Vec::new();
            let mut start = 0;
            while start < s.rows.len() {
                let key = x_col.key(s.rows[start] as usize);
                let len = s.rows[start..].iter().take_while(|&&r| x_col.key(r as usize) == key).count().max(1);
                let span = start..start + len;
                if let Some(summary) = Summary::of(s.rows[span.clone()].iter().map(|&r| y_of(r))) {
                    out.push(Vertex {
                        span: span.clone(),
                        y: summary.mean,
                        band: spread.interval(&summary, summary.mean),
                    });
                }
                start = span.end;
            }
            out
        }
        Some(Band::Columns(lower, upper)) => {
            let (lo, hi) = (lower.numbers().unwrap_or(&[]), upper.numbers().unwrap_or(&[]));
            let edge = |v: &[f64], r: u32| v.get(r as usize).copied().filter(|e| e.is_finite());
            (s.rows.iter().enumerate())
                .map(|(k, &r)| Vertex { span: k..k + 1, y: y_of(r), band: edge(lo, r).zip(edge(hi, r)) })
                .collect()
        }
        None => (s.rows.iter().enumerate()).map(|(k, &r)| Vertex { span: k..k + 1, y: y_of(r), band: None }).collect(),
    }
}

/// The shaded band of one series: one polygon per run of points with a band interval, upper
/// edge forward and lower edge back.
fn band_marks(
    frame: &crate::guide::layout::Frame,
    x_col: &Column,
    s: &Series<'_>,
    vertices: &[Vertex],
    opacity: f64,
) -> Vec<Item> {
    let x_at = encode::Positioner::new(&frame.x, x_col);
    let mut items = Vec::new();
    for run in vertices.split(|v| v.band.is_none()).filter(|run| !run.is_empty()) {
        let edges: Vec<(f64, (f64, f64))> =
            run.iter().filter_map(|v| Some((x_at.at(s.rows[v.span.start]), v.band?))).collect();
        let mut cmds: Vec<PathCmd> = Vec::with_capacity(2 * edges.len() + 1);
        for (k, &(x, (_, hi))) in edges.iter().enumerate() {
            let p = Point::new(x, frame.y.map(hi));
            cmds.push(if k == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) });
        }
        for &(x, (lo, _)) in edges.iter().rev() {
            cmds.push(PathCmd::LineTo(Point::new(x, frame.y.map(lo))));
        }
        cmds.push(PathCmd::Close);
        let rows = match (run.first(), run.last()) {
            (Some(first), Some(last)) => s.rows.get(first.span.start..last.span.end).unwrap_or(&[]).to_vec(),
            _ => Vec::new(),
        };
        items.push(
            Item::new(Role::DataMark, Shape::Path(cmds), Style::fill(s.color.with_opacity(opacity)))
                .with_rows(rows)
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
