//! Categorical colours: which colour encodings read their column as categories, the colour each
//! category gets (from the encoding's `domain` and `range`, or from a palette), and the
//! spec-wide order of a column's categories that gives each category the same colour in every
//! chart of a spec.

use std::collections::BTreeMap;

use crate::data::{Categories, Column, Table};
use crate::guide::color;
use crate::guide::format::format_value;
use crate::scene::Color;
use crate::spec::{CategoryValue, Chart, ColorChannel, ColorOptions, ColorType};

use crate::mark::MarkError;
use crate::mark::encode::{MISSING_COLOR, MISSING_LABEL, palette, used_levels};

/// Whole-number columns with at most this many distinct values (group numbers, codes, ratings)
/// are coloured as categories unless the encoding says `type = "continuous"`.
pub const FEW_INTEGERS: usize = 12;

/// Whether a colour encoding over `column` shows categories (a legend) rather than a
/// continuous map: `type` decides when given; otherwise text columns, encodings with a
/// `domain` or `range`, and columns of at most [`FEW_INTEGERS`] distinct whole numbers do.
pub fn is_categorical(options: &ColorOptions, column: &Column) -> bool {
    match options.r#type {
        Some(ColorType::Categorical) => true,
        Some(ColorType::Continuous) => false,
        None => {
            column.categories().is_some() || options.domain.is_some() || options.range.is_some() || few_integers(column)
        }
    }
}

/// Whether `column` holds whole numbers (not times) with between one and [`FEW_INTEGERS`]
/// distinct finite values.
pub fn few_integers(column: &Column) -> bool {
    let Some(values) = column.numbers().filter(|_| !column.is_time()) else { return false };
    let mut distinct: Vec<f64> = Vec::new();
    for &v in values.iter().filter(|v| v.is_finite()) {
        if v.fract() != 0.0 {
            return false;
        }
        if !distinct.contains(&v) {
            if distinct.len() == FEW_INTEGERS {
                return false;
            }
            distinct.push(v);
        }
    }
    !distinct.is_empty()
}

/// The categories of a colour column: its text levels, or its distinct numbers in ascending
/// order (labelled as the axes format them).
pub fn categories_of(column: &Column) -> Categories {
    match column.categories() {
        Some(c) => c.clone(),
        None => number_categories(column.numbers().unwrap_or(&[])),
    }
}

/// Distinct numbers as sorted categories.
fn number_categories(values: &[f64]) -> Categories {
    let mut distinct: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup();
    let levels: Vec<String> = distinct.iter().map(|&v| format_value(v)).collect();
    let codes = values
        .iter()
        .map(|v| distinct.binary_search_by(|d| d.total_cmp(v)).map(|i| i as u32).unwrap_or(Categories::MISSING))
        .collect();
    Categories { levels, codes }
}

/// A `domain` entry as the category label it matches (numbers formatted like the levels of a
/// numeric column).
fn label_of(value: &CategoryValue) -> String {
    match value {
        CategoryValue::Text(s) => s.clone(),
        CategoryValue::Number(n) => format_value(*n),
    }
}

/// Up to five labels quoted and joined, with a count of the rest.
fn quoted(labels: &[String]) -> String {
    let shown: Vec<String> =
        labels.iter().take(5).map(|l| format!("\"{}\"", crate::spec::validate::shorten(l))).collect();
    match labels.len().saturating_sub(5) {
        0 => shown.join(", "),
        more => format!("{} and {more} more", shown.join(", ")),
    }
}

/// The colours of a categorical encoding: one per level of `categories` (indexed by level
/// code), and the legend entries of the levels `rows` use, in colour order (`(missing)` last).
///
/// The colour order is the encoding's `domain` when it has one (every category drawn must be
/// in it, else an error names the others), else the column's own level order. Colours come
/// from `range` (parsed colours; fewer colours than categories in that order is an error) or
/// from the `scheme` palette, which repeats when there are more categories than colours.
pub fn assign(
    options: &ColorOptions,
    categories: &Categories,
    rows: &[u32],
) -> Result<(Vec<Color>, Vec<(String, Color)>), MarkError> {
    let used = used_levels(categories, rows);
    let order: Vec<String> = match &options.domain {
        Some(domain) => domain.iter().map(label_of).collect(),
        None => categories.levels.clone(),
    };
    if options.domain.is_some() {
        let outside: Vec<String> =
            used.iter().filter(|l| *l != MISSING_LABEL && !order.contains(*l)).cloned().collect();
        if !outside.is_empty() {
            return Err(MarkError::at(
                &["color", "domain"],
                format!(
                    "{} of column `{}` {} not in the colour `domain`",
                    quoted(&outside),
                    options.field,
                    if outside.len() == 1 { "is" } else { "are" }
                ),
                "list every category the chart draws in `domain` (it sets their colour and legend order), or \
                 filter those rows out",
            ));
        }
    }
    let colours = match &options.range {
        Some(range) => parsed_range(range, order.len())?,
        None => palette(&["color", "scheme"], options.scheme.as_deref())?,
    };
    let colour_at = |i: usize| colours.get(i % colours.len().max(1)).copied().unwrap_or(MISSING_COLOR);
    let colour_of = |level: &str| order.iter().position(|l| l == level).map(colour_at).unwrap_or(MISSING_COLOR);
    let per_level = categories.levels.iter().map(|l| colour_of(l)).collect();
    // Legend entries in colour order; `(missing)`, in no order, last.
    let mut entries: Vec<(String, Color)> = used.into_iter().map(|l| (colour_of(&l), l)).map(|(c, l)| (l, c)).collect();
    entries.sort_by_key(|(l, _)| order.iter().position(|o| o == l).unwrap_or(usize::MAX));
    Ok((per_level, entries))
}

/// The colours of a `range`: each parsed, and at least `needed` of them.
fn parsed_range(range: &[String], needed: usize) -> Result<Vec<Color>, MarkError> {
    let mut colours = Vec::with_capacity(range.len());
    for (i, s) in range.iter().enumerate() {
        let c = color::parse_color(s).ok_or_else(|| {
            let mut e = MarkError::at(
                &["color", "range"],
                format!("`{}` in the colour `range` is not a colour", s),
                "use a hex colour such as \"#1f77b4\" or a CSS colour name such as \"steelblue\"",
            );
            e.path.push(crate::spec::PathSeg::Index(i));
            e
        })?;
        colours.push(c);
    }
    if colours.len() < needed {
        return Err(MarkError::at(
            &["color", "range"],
            format!(
                "the colour `range` has {} colour{} for {needed} categories",
                colours.len(),
                if colours.len() == 1 { "" } else { "s" }
            ),
            "give one colour per category; a column's categories are counted over every chart of the spec \
             that colours by it, unless `domain` lists them",
        ));
    }
    Ok(colours)
}

/// The colour channel of a chart and the data source it reads (the node table for a graph's
/// `nodes.color`), for mutation.
fn channel_mut(chart: &mut Chart) -> Option<(&mut ColorChannel, String)> {
    let own = chart.data.clone();
    let (channel, data) = crate::mark::registry::technique_mut(&mut chart.kind).color_channel_mut()?;
    Some((channel, data.unwrap_or(own)))
}

/// The spec-wide category order of every column that some chart colours by categories: each
/// chart's explicit `domain` first, then the categories every such chart's table holds, both
/// in chart order, each category where it first appears.
pub fn shared_domains(charts: &[Chart], tables: &BTreeMap<String, Table>) -> BTreeMap<String, Vec<String>> {
    let mut seen: Vec<(String, Option<Vec<String>>, Vec<String>)> = Vec::new();
    for chart in charts {
        let mut chart = chart.clone();
        let Some((channel, data)) = channel_mut(&mut chart) else { continue };
        let options = channel.options();
        let Some(column) = tables.get(&data).and_then(|t| t.column(&options.field)) else { continue };
        if !is_categorical(&options, column) {
            continue;
        }
        let explicit = options.domain.as_ref().map(|d| d.iter().map(label_of).collect());
        seen.push((options.field.clone(), explicit, categories_of(column).levels));
    }
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let explicit = seen.iter().filter_map(|(f, e, _)| Some((f, e.as_ref()?)));
    let own = seen.iter().map(|(f, _, levels)| (f, levels));
    for (field, levels) in explicit.chain(own) {
        let order = out.entry(field.clone()).or_default();
        for level in levels {
            if !order.contains(level) {
                order.push(level.clone());
            }
        }
    }
    out
}

/// Give the chart's categorical colour encoding without a `domain` its table's categories as
/// the domain, so parts of the table drawn apart (facet panels) colour each category alike.
/// Returns the domain's labels in order (`None` without a categorical colour encoding).
pub fn fix_domain(chart: &mut Chart, table: &Table) -> Option<Vec<String>> {
    let (channel, _) = channel_mut(chart)?;
    let mut options = channel.options();
    let column = table.column(&options.field)?;
    if !is_categorical(&options, column) {
        return None;
    }
    if options.domain.is_none() {
        options.domain = Some(categories_of(column).levels.into_iter().map(CategoryValue::Text).collect());
        *channel = ColorChannel::Detailed(options.clone());
    }
    options.domain.as_ref().map(|d| d.iter().map(label_of).collect())
}

/// Give every categorical colour encoding without a `domain` the spec-wide order of its
/// column's categories from [`shared_domains`], so a category has one colour in every chart.
pub fn share_domains(charts: &mut [Chart], tables: &BTreeMap<String, Table>) {
    let shared = shared_domains(charts, tables);
    for chart in charts {
        let Some((channel, data)) = channel_mut(chart) else { continue };
        let mut options = channel.options();
        let Some(column) = tables.get(&data).and_then(|t| t.column(&options.field)) else { continue };
        if options.domain.is_some() || !is_categorical(&options, column) {
            continue;
        }
        let Some(order) = shared.get(&options.field) else { continue };
        options.domain = Some(order.iter().cloned().map(CategoryValue::Text).collect());
        *channel = ColorChannel::Detailed(options);
    }
}

/// The groups of a categorical colour encoding over `rows`: the legend entries' labels in their
/// order (`entries` as [`assign`] returns them), and each row's group index in that list.
pub fn group_rows(categories: &Categories, entries: &[(String, Color)], rows: &[u32]) -> Vec<usize> {
    let group_of_level: Vec<usize> =
        categories.levels.iter().map(|l| entries.iter().position(|(e, _)| e == l).unwrap_or(usize::MAX)).collect();
    let missing = entries.iter().position(|(e, _)| e == MISSING_LABEL).unwrap_or(0);
    rows.iter()
        .map(|&r| match categories.codes.get(r as usize) {
            Some(&c) if c != Categories::MISSING => {
                group_of_level.get(c as usize).copied().filter(|&g| g != usize::MAX).unwrap_or(missing)
            }
            _ => missing,
        })
        .collect()
}

/// Each of `rows`' group and the groups' labels and colours, in legend order, for a colour
/// encoding that groups marks; one unlabelled group in the fixed colour without a channel.
pub fn row_groups(
    colors: &crate::mark::encode::ColorEncoding,
    channel: Option<&ColorChannel>,
    rows: &[u32],
) -> Result<(Vec<usize>, Vec<(String, Color)>), MarkError> {
    match (colors, channel) {
        (crate::mark::encode::ColorEncoding::Categorical { categories, .. }, Some(channel)) => {
            let (_, entries) = assign(&channel.options(), categories, rows)?;
            Ok((group_rows(categories, &entries, rows), entries))
        }
        _ => Ok((vec![0; rows.len()], vec![(String::new(), colors.color_of(rows.first().copied().unwrap_or(0)))])),
    }
}
