//! Encodings shared by chart kinds: columns for channels, the non-finite row policy, positional
//! axes from channels, and colour encodings with their legends.

use crate::data::{Categories, Column, NonFinite, Table};
use crate::guide::axis::title_with_unit;
use crate::guide::color::{self, ContinuousMap};
use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::{Legend, Symbol};
use crate::guide::scale::Scale;
use crate::scene::Color;
use crate::spec::{ChannelOptions, ColorChannel, ColorType, ScaleKind};

use crate::mark::warning::{ColumnLoss, Warning};
use crate::mark::{MarkError, categorical};

/// Grey used for rows whose colour value is missing.
pub const MISSING_COLOR: Color = Color::rgb(0xa0, 0xa0, 0xa0);
/// Default mark colour when nothing encodes colour (the first categorical colour).
pub const DEFAULT_MARK_COLOR: Color = Color::rgb(0x00, 0x72, 0xb2);

/// The message and hint for a column name that is not in the table.
pub fn missing_column(data: &str, field: &str, table: &Table) -> (String, String) {
    let names = table.column_names();
    let message = format!("data \"{data}\" has no column `{field}`");
    (message, crate::spec::suggest::hint(field, &names, "columns", true))
}

/// The column a channel names, or an error pointing at the channel's key.
pub fn column<'t>(
    chart: &crate::spec::Chart,
    key: &str,
    field: &str,
    table: &'t Table,
) -> Result<&'t Column, MarkError> {
    table.column(field).ok_or_else(|| {
        let (message, hint) = missing_column(&chart.data, field, table);
        MarkError::at(&[key], message, hint)
    })
}

/// The columns of a list-of-channels key (`columns` of splom, parallel, ...) with their options.
pub fn columns<'t>(
    chart: &crate::spec::Chart,
    key: &str,
    channels: &[crate::spec::Channel],
    table: &'t Table,
) -> Result<Vec<(ChannelOptions, &'t Column)>, MarkError> {
    channels
        .iter()
        .map(|c| {
            let options = c.options();
            let col = column(chart, key, &options.field, table)?;
            Ok((options, col))
        })
        .collect()
}

/// An error unless `column` is numeric; `what` names what needs the numbers.
pub fn require_numeric(key: &str, column: &Column, what: &str, hint: &str) -> Result<(), MarkError> {
    if column.numbers().is_some() {
        return Ok(());
    }
    Err(MarkError::at(&[key], format!("column `{}` holds text; {what} needs numbers", column.name), hint))
}

/// Rows whose numeric channel values are all finite, plus the warning that counts the rest.
///
/// This is the one non-finite policy of every chart kind: a row with a missing, NaN or infinite
/// value in any numeric column the chart uses is dropped, and a warning says how many rows were
/// dropped and why. Text columns never drop rows (missing text is its own category).
pub fn finite_rows(chart: &str, rows: usize, numeric: &[(&str, &Column)]) -> (Vec<u32>, Option<Warning>) {
    placeable_rows(chart, rows, numeric, &[])
}

/// [`finite_rows`] for a chart with log axes: a value ≤ 0 in a column named in `log` (the fields
/// on a log-scaled axis, see [`log_fields`]) cannot be placed either, so its row is dropped and
/// counted in the same warning.
pub fn placeable_rows(
    chart: &str,
    rows: usize,
    numeric: &[(&str, &Column)],
    log: &[&str],
) -> (Vec<u32>, Option<Warning>) {
    let slices: Vec<(&[f64], bool)> =
        numeric.iter().filter_map(|(name, c)| Some((c.numbers()?, log.contains(name)))).collect();
    let placeable = |v: &f64, on_log: bool| v.is_finite() && (!on_log || *v > 0.0);
    if slices.iter().all(|(s, on_log)| s.len() == rows && s.iter().all(|v| placeable(v, *on_log))) {
        return ((0..rows as u32).collect(), None);
    }
    let mut kept = Vec::with_capacity(rows);
    for row in 0..rows {
        if slices.iter().all(|(s, on_log)| s.get(row).is_some_and(|v| placeable(v, *on_log))) {
            kept.push(row as u32);
        }
    }
    if kept.len() == rows {
        return (kept, None);
    }
    let columns = numeric
        .iter()
        .filter_map(|(name, c)| {
            let values = c.numbers()?;
            let n = NonFinite::count(values);
            let non_positive =
                if log.contains(name) { values.iter().filter(|v| v.is_finite() && **v <= 0.0).count() } else { 0 };
            let loss = ColumnLoss { field: (*name).to_string(), missing: n.nan, infinite: n.infinite, non_positive };
            (n.total() + non_positive > 0).then_some(loss)
        })
        .collect();
    let warning = Warning::DroppedRows { chart: chart.to_string(), dropped: rows - kept.len(), rows, columns };
    (kept, Some(warning))
}

/// The fields of the channels that sit on a log-scaled axis.
pub fn log_fields<'a>(channels: &[&'a ChannelOptions]) -> Vec<&'a str> {
    channels.iter().filter(|c| c.scale == Some(ScaleKind::Log)).map(|c| c.field.as_str()).collect()
}

/// The rows a chart draws: the rows finite in every numeric column of `numeric` and in the
/// colour column when it is numeric (the shared non-finite policy), with its warning; or the
/// no-rows error when none is left.
pub fn drawn_rows<'a>(
    chart: &crate::spec::Chart,
    table: &'a Table,
    mut numeric: Vec<(&'a str, &'a Column)>,
    color: Option<&'a ColorChannel>,
) -> Result<(Vec<u32>, Vec<Warning>), MarkError> {
    numeric.retain(|(_, c)| c.numbers().is_some());
    if let Some(c) = color
        && let Some(col) = table.column(c.field()).filter(|col| col.numbers().is_some())
    {
        numeric.push((c.field(), col));
    }
    let (rows, warning) = finite_rows(&chart.name, table.rows, &numeric);
    let warnings: Vec<Warning> = warning.into_iter().collect();
    if rows.is_empty() {
        return Err(no_rows(chart, table, warnings.first()));
    }
    Ok((rows, warnings))
}

/// The error for a chart left with no rows: an empty table, or every row dropped by the
/// non-finite policy (`dropped` is that warning, which names the columns).
pub fn no_rows(chart: &crate::spec::Chart, table: &Table, dropped: Option<&Warning>) -> MarkError {
    no_rows_of(chart, table.rows, dropped)
}

/// [`no_rows`] for a source of `rows` rows that are not held in a table.
pub fn no_rows_of(chart: &crate::spec::Chart, rows: usize, dropped: Option<&Warning>) -> MarkError {
    if rows == 0 {
        return MarkError::at(
            &["data"],
            format!("data \"{}\" has no rows", chart.data),
            "the source has a header but no records; check the file",
        );
    }
    let why =
        dropped.and_then(Warning::what_rows_lack).map(|lack| format!(": every row has {lack}")).unwrap_or_default();
    MarkError::at(
        &[],
        format!("no rows left to plot out of {rows}{why}"),
        "rows with missing or non-finite values in the charted columns are dropped; check those columns",
    )
}

/// A numeric column's values at `rows` (NaN for text columns or rows out of range).
pub fn values_at(column: &Column, rows: &[u32]) -> Vec<f64> {
    let v = column.numbers().unwrap_or(&[]);
    rows.iter().map(|&r| v.get(r as usize).copied().unwrap_or(f64::NAN)).collect()
}

/// The extent of `values` over `rows` (finite values only).
pub fn extent(values: &[f64], rows: &[u32]) -> Option<(f64, f64)> {
    if rows.len() == values.len() {
        // Rows are distinct and sorted, so this is every row: scan the values directly.
        return finite_extent(values.iter().copied());
    }
    finite_extent(rows.iter().filter_map(|&r| values.get(r as usize).copied()))
}

/// The finite extent of a column over `rows` (sorted, distinct): a grid's coordinate column over
/// all its rows is read from its coordinates, without spreading them over the rows.
pub fn column_extent(column: &Column, rows: &[u32]) -> Option<(f64, f64)> {
    if let crate::data::ColumnValues::Axis(axis) = &column.values
        && rows.len() == axis.len()
    {
        return finite_extent(axis.coords().iter().copied());
    }
    extent(column.numbers().unwrap_or(&[]), rows)
}

/// The smallest and largest finite value (`None` when there is none).
pub fn finite_extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    (lo <= hi).then_some((lo, hi))
}

/// Resolve a positional axis from a channel, its column and the kept rows.
pub fn position_axis(
    key: &str,
    options: &ChannelOptions,
    column: &Column,
    rows: &[u32],
) -> Result<PositionAxis, MarkError> {
    let kind = match (options.scale, column.categories().is_some(), column.is_time()) {
        (Some(ScaleKind::Band), _, _) | (None, true, _) => ScaleKind::Band,
        (Some(kind), true, _) => {
            return Err(MarkError::at(
                &[key, "scale"],
                format!("column `{}` holds text, which a {} scale cannot place", options.field, scale_name(kind)),
                "use scale = \"band\" for categories, or a numeric column",
            ));
        }
        (None, false, true) => ScaleKind::Time,
        (None, false, false) => ScaleKind::Linear,
        (Some(kind), false, _) => kind,
    };
    match column.categories() {
        Some(cats) => Ok(axis_over(options, kind, Domain::Categories(used_levels(cats, rows)))),
        None => numeric_axis(key, options, kind, column_extent(column, rows)),
    }
}

/// A numeric axis of `kind` for channel `key` over `extent` (the values' smallest and largest;
/// the channel's own `domain` wins, and `zero` widens a linear axis to 0); an error when there is
/// neither.
pub fn numeric_axis(
    key: &str,
    options: &ChannelOptions,
    kind: ScaleKind,
    extent: Option<(f64, f64)>,
) -> Result<PositionAxis, MarkError> {
    let (mut lo, mut hi) = match (options.domain, extent) {
        (Some([a, b]), _) => (a, b),
        (None, Some(e)) => e,
        (None, None) => {
            return Err(MarkError::at(
                &[key],
                format!("column `{}` has no finite values to plot", options.field),
                "check the column's contents; non-finite cells are dropped",
            ));
        }
    };
    if options.zero == Some(true) && kind == ScaleKind::Linear {
        lo = lo.min(0.0);
        hi = hi.max(0.0);
    }
    Ok(axis_over(options, kind, Domain::Continuous(lo, hi)))
}

/// The axis of a channel over `domain`, with the channel's title, ticks and grid.
fn axis_over(options: &ChannelOptions, kind: ScaleKind, domain: Domain) -> PositionAxis {
    PositionAxis {
        title: title_with_unit(options.title.as_deref().unwrap_or(&options.field), options.unit.as_deref()),
        kind,
        domain,
        // Log axes keep the data extent: rounding out to whole decades can waste most of the plot.
        nice: options.nice.unwrap_or(kind != ScaleKind::Log) && options.domain.is_none(),
        ticks: options.ticks,
        grid: options.grid.unwrap_or(kind != ScaleKind::Band),
        inset: 0.0,
    }
}

/// One axis per entry of a `columns` list over the kept rows, whole-number columns ticked per
/// integer (parallel coordinates, daisy charts).
pub fn column_axes(columns: &[(ChannelOptions, &Column)], rows: &[u32]) -> Result<Vec<PositionAxis>, MarkError> {
    columns.iter().map(|(opts, col)| Ok(integer_ticks(position_axis("columns", opts, col, rows)?, col, rows))).collect()
}

/// For a column of few distinct whole numbers (counts, codes, years) on a linear axis without a
/// requested tick count: one tick per whole number, so no tick claims a value like 3.5.
pub fn integer_ticks(mut axis: PositionAxis, column: &Column, rows: &[u32]) -> PositionAxis {
    let (Domain::Continuous(lo, hi), ScaleKind::Linear, None) = (&axis.domain, axis.kind, axis.ticks) else {
        return axis;
    };
    let values = column.numbers().unwrap_or(&[]);
    let whole = rows.iter().all(|&r| values.get(r as usize).is_some_and(|v| v.fract() == 0.0));
    if whole && hi - lo >= 1.0 && hi - lo <= 12.0 {
        axis.ticks = Some((hi - lo) as u32 + 1);
    }
    axis
}

/// The spec's name of a scale kind, for messages.
pub fn scale_name(kind: ScaleKind) -> &'static str {
    match kind {
        ScaleKind::Linear => "linear",
        ScaleKind::Log => "log",
        ScaleKind::Time => "time",
        ScaleKind::Band => "band",
    }
}

/// Category levels that occur in `rows`, in order of first appearance in the data.
pub fn used_levels(cats: &Categories, rows: &[u32]) -> Vec<String> {
    let mut used = vec![false; cats.levels.len()];
    let mut any_missing = false;
    for &r in rows {
        match cats.codes.get(r as usize) {
            Some(&c) if c != Categories::MISSING => {
                if let Some(u) = used.get_mut(c as usize) {
                    *u = true;
                }
            }
            _ => any_missing = true,
        }
    }
    let mut levels: Vec<String> = cats.levels.iter().zip(&used).filter(|(_, u)| **u).map(|(l, _)| l.clone()).collect();
    if any_missing {
        levels.push(MISSING_LABEL.to_string());
    }
    levels
}

/// A cell as text for derived output: a number in its shortest round-trip form, or the
/// category (`(missing)` for a missing one).
pub fn cell_text(column: &Column, row: u32) -> String {
    match (column.numbers(), column.categories()) {
        (Some(v), _) => v.get(row as usize).map(|x| x.to_string()).unwrap_or_default(),
        (_, Some(c)) => c.value(row as usize).unwrap_or(MISSING_LABEL).to_string(),
        _ => String::new(),
    }
}

/// Label of the category of missing text cells.
pub const MISSING_LABEL: &str = "(missing)";

/// Maps rows of one column to pixel positions on a scale, with the per-column work (band
/// lookups, type dispatch) done once rather than per row.
pub enum Positioner<'a> {
    /// A numeric or time column on a continuous scale.
    Numbers {
        /// The column's values.
        values: &'a [f64],
        /// The scale.
        scale: &'a Scale,
    },
    /// A text column on a band scale: the band centre of each category code.
    Codes {
        /// Category code per row.
        codes: &'a [u32],
        /// Pixel centre per code (NaN for codes not on the scale).
        centers: Vec<f64>,
        /// Centre of the `(missing)` band, if there is one.
        missing: f64,
    },
}

impl<'a> Positioner<'a> {
    /// A positioner for `column` on `scale`.
    pub fn new(scale: &'a Scale, column: &'a Column) -> Positioner<'a> {
        match (scale, column.categories()) {
            (Scale::Band(band), Some(cats)) => Positioner::Codes {
                codes: &cats.codes,
                centers: cats
                    .levels
                    .iter()
                    .map(|l| band.band_of(l).map(|i| band.center(i)).unwrap_or(f64::NAN))
                    .collect(),
                missing: band.band_of(MISSING_LABEL).map(|i| band.center(i)).unwrap_or(f64::NAN),
            },
            _ => Positioner::Numbers { values: column.numbers().unwrap_or(&[]), scale },
        }
    }

    /// Pixel position of `row` (NaN if it has none).
    #[inline]
    pub fn at(&self, row: u32) -> f64 {
        match self {
            Positioner::Numbers { values, scale } => {
                values.get(row as usize).map(|&v| scale.map(v)).unwrap_or(f64::NAN)
            }
            Positioner::Codes { codes, centers, missing } => match codes.get(row as usize) {
                Some(&c) if c != Categories::MISSING => centers.get(c as usize).copied().unwrap_or(f64::NAN),
                _ => *missing,
            },
        }
    }
}

/// Pixel centres of `rows` from two positioners (in parallel for large inputs).
pub fn centers(x: &Positioner, y: &Positioner, rows: &[u32]) -> Vec<crate::scene::Point> {
    use rayon::prelude::*;
    let point = |&r: &u32| crate::scene::Point::new(x.at(r), y.at(r));
    if rows.len() < 50_000 { rows.iter().map(point).collect() } else { rows.par_iter().map(point).collect() }
}

/// How marks are coloured.
#[derive(Clone, Debug)]
pub enum ColorEncoding {
    /// One colour for every mark.
    Fixed(Color),
    /// A colour per category.
    Categorical {
        /// Codes per row.
        categories: Categories,
        /// Colour per level code.
        colors: Vec<Color>,
    },
    /// A continuous colour map over a numeric column.
    Continuous {
        /// Values per row.
        values: Vec<f64>,
        /// The map.
        map: ContinuousMap,
        /// Value at the low end.
        lo: f64,
        /// Value at the high end.
        hi: f64,
    },
}

impl ColorEncoding {
    /// The colour of `row`.
    pub fn color_of(&self, row: u32) -> Color {
        match self {
            ColorEncoding::Fixed(c) => *c,
            ColorEncoding::Categorical { categories, colors } => categories
                .codes
                .get(row as usize)
                .and_then(|&c| colors.get(c as usize))
                .copied()
                .unwrap_or(MISSING_COLOR),
            ColorEncoding::Continuous { values, map, lo, hi } => {
                let v = values.get(row as usize).copied().unwrap_or(f64::NAN);
                let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
                map.at(t)
            }
        }
    }
}

/// A fixed mark colour from the spec (`mark_color`), or the default.
pub fn fixed_color(value: Option<&str>) -> Result<Color, MarkError> {
    match value {
        None => Ok(DEFAULT_MARK_COLOR),
        Some(s) => color::parse_color(s).ok_or_else(|| {
            MarkError::at(
                &["mark_color"],
                format!("`{s}` is not a colour"),
                "use a CSS colour name such as \"steelblue\" or a hex colour such as \"#1f77b4\"",
            )
        }),
    }
}

/// A categorical palette by name (default Okabe–Ito), or an error listing the names.
pub fn palette(keys: &[&str], name: Option<&str>) -> Result<Vec<Color>, MarkError> {
    let name = name.unwrap_or(color::DEFAULT_CATEGORICAL);
    color::categorical(name).ok_or_else(|| {
        let names = color::categorical_names();
        let hint = crate::spec::suggest::hint(name, names, "categorical schemes", false);
        MarkError::at(keys, format!("unknown categorical colour scheme `{name}`"), hint)
    })
}

/// Build the colour encoding and its legend for a colour channel over the kept rows.
pub fn color_encoding(
    chart: &crate::spec::Chart,
    channel: Option<&ColorChannel>,
    mark_color: Option<&str>,
    table: &Table,
    rows: &[u32],
    symbol: Symbol,
) -> Result<(ColorEncoding, Option<Legend>), MarkError> {
    let Some(channel) = channel else {
        return Ok((ColorEncoding::Fixed(fixed_color(mark_color)?), None));
    };
    let options = channel.options();
    let col = column(chart, "color", &options.field, table)?;
    let title = title_with_unit(options.title.as_deref().unwrap_or(&options.field), options.unit.as_deref());
    if options.r#type == Some(ColorType::Continuous) && col.categories().is_some() {
        return Err(MarkError::at(
            &["color", "type"],
            format!("column `{}` holds text and cannot be coloured continuously", options.field),
            "remove `type = \"continuous\"` or colour by a numeric column",
        ));
    }
    if categorical::is_categorical(&options, col) {
        let categories = categorical::categories_of(col);
        let (colors, entries) = categorical::assign(&options, &categories, rows)?;
        let legend = Legend::Categorical { title, entries, symbol };
        let legend = shown_legends(legend, &options).pop();
        return Ok((ColorEncoding::Categorical { categories, colors }, legend));
    }
    if options.domain.is_some() || options.range.is_some() {
        let key = if options.domain.is_some() { "domain" } else { "range" };
        return Err(MarkError::at(
            &["color", key],
            format!("`{key}` sets categorical colours, but `{}` is coloured continuously", options.field),
            "remove `type = \"continuous\"` to colour the column's values as categories, or remove `domain` and \
             `range`",
        ));
    }
    let values = col.numbers().unwrap_or(&[]).to_vec();
    let map = continuous_map(&["color", "scheme"], options.scheme.as_deref())?;
    let (mut lo, mut hi) = extent(&values, rows).unwrap_or((0.0, 1.0));
    if let Some(shared) = chart.panel.as_ref().and_then(|p| p.color) {
        (lo, hi) = shared;
    }
    if map.is_diverging() {
        let mid = options.midpoint.unwrap_or((lo + hi) / 2.0);
        let half = (hi - mid).abs().max((mid - lo).abs());
        lo = mid - half;
        hi = mid + half;
    }
    if lo == hi {
        lo -= 0.5;
        hi += 0.5;
    }
    let legend = Legend::ColorBar { title, map: map.clone(), domain: (lo, hi) };
    let legend = shown_legends(legend, &options).pop();
    Ok((ColorEncoding::Continuous { values, map, lo, hi }, legend))
}

/// The legends to draw for a colour encoding: none when its options say `legend = false`.
pub fn shown_legends(legend: Legend, options: &crate::spec::ColorOptions) -> Vec<Legend> {
    if options.legend == Some(false) { Vec::new() } else { vec![legend] }
}

/// The value range the colour map spans: the data range, or for diverging maps a range centred
/// on the midpoint (default: the middle of the data).
pub fn color_domain(map: &ContinuousMap, zmin: f64, zmax: f64, midpoint: Option<f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (zmin, zmax);
    if map.is_diverging() {
        let mid = midpoint.unwrap_or((lo + hi) / 2.0);
        let half = (hi - mid).abs().max((mid - lo).abs());
        lo = mid - half;
        hi = mid + half;
    }
    if hi <= lo {
        lo -= 0.5;
        hi += 0.5;
    }
    (lo, hi)
}

/// A continuous colour map by name (default viridis), or an error at `keys` listing the names.
pub fn continuous_map(keys: &[&str], name: Option<&str>) -> Result<ContinuousMap, MarkError> {
    let scheme = name.unwrap_or(color::DEFAULT_SEQUENTIAL);
    color::continuous(scheme).ok_or_else(|| {
        let names = color::continuous_names();
        let mut hint = crate::spec::suggest::hint(scheme, names, "continuous schemes", false);
        if let Some(note) = crate::spec::foreign::value(scheme) {
            hint = format!("{note}; {hint}");
        }
        MarkError::at(keys, format!("unknown continuous colour scheme `{scheme}`"), hint)
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_dropped_rows_warning_reads_back() {
        use crate::data::{ColumnValues, Table};
        let table = Table::from_columns([("v", ColumnValues::Number(vec![1.0, f64::NAN, 3.0, f64::INFINITY]))]);
        let column = table.column("v").expect("column v");
        let (kept, warning) = super::finite_rows("c", 4, &[("v", column)]);
        assert_eq!(kept, [0, 2]);
        let warning = warning.expect("a warning");
        assert_eq!(warning.dropped_rows(), Some((2, 4)));
        assert_eq!(
            warning.to_string(),
            "chart \"c\": dropped 2 of 4 rows with missing or non-finite values (`v`: 1 missing or NaN, 1 infinite)"
        );
    }
}
