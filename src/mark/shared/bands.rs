//! Categories along a band axis, for the kinds that place rows in bands by a column (bar, box,
//! violin): the category of each row, the colour channel read as groups, and the slot of a
//! group dodged side by side within its band.

use crate::data::{Categories, Column, Table};
use crate::guide::format::format_value;
use crate::guide::scale::BandScale;
use crate::guide::time::format_timestamp;
use crate::mark::MarkError;
use crate::mark::encode::{self, MISSING_LABEL};
use crate::spec::{Chart, ColorChannel, ColorOptions, ColorType};

/// Gap between the marks of one group, as a fraction of a mark's step.
pub const GROUP_PADDING: f64 = 0.1;

/// The distinct values of a column over some rows, as labelled categories, and the category of
/// each of those rows.
pub struct Keys {
    /// Category labels in display order (unique).
    pub labels: Vec<String>,
    /// Category index of each row, in the order of the rows given.
    pub of_row: Vec<usize>,
}

impl Keys {
    /// One category, labelled `label`, holding every one of `rows` rows.
    pub fn single(label: &str, rows: usize) -> Keys {
        Keys { labels: vec![label.to_string()], of_row: vec![0; rows] }
    }

    /// The label of category `i` (empty past the end).
    pub fn label(&self, i: usize) -> &str {
        self.labels.get(i).map_or("", String::as_str)
    }
}

/// The categories of `column` over `rows`: text in the table's order of levels (missing text is
/// its own category, last), numbers and times ascending.
pub fn keys(column: &Column, rows: &[u32]) -> Keys {
    if let Some(cats) = column.categories() {
        return text_keys(cats, rows);
    }
    let values = column.numbers().unwrap_or(&[]);
    let mut distinct: Vec<f64> = rows.iter().filter_map(|&r| values.get(r as usize).copied()).collect();
    distinct.sort_by(f64::total_cmp);
    // `==` merges -0 and 0, which are one category.
    distinct.dedup_by(|a, b| a == b);
    let of_row = rows
        .iter()
        .map(|&r| {
            let v = values.get(r as usize).copied().unwrap_or(f64::NAN);
            distinct.partition_point(|d| *d < v).min(distinct.len().saturating_sub(1))
        })
        .collect();
    Keys { labels: number_labels(&distinct, column.is_time()), of_row }
}

/// Categories of a text column over `rows`.
fn text_keys(cats: &Categories, rows: &[u32]) -> Keys {
    let labels = encode::used_levels(cats, rows);
    let index: std::collections::HashMap<&str, usize> =
        labels.iter().enumerate().map(|(i, l)| (l.as_str(), i)).collect();
    let position: Vec<Option<usize>> = cats.levels.iter().map(|l| index.get(l.as_str()).copied()).collect();
    let missing = labels.iter().position(|l| l == MISSING_LABEL).unwrap_or(0);
    let of_row = rows
        .iter()
        .map(|&r| match cats.codes.get(r as usize) {
            Some(&c) if c != Categories::MISSING => position.get(c as usize).copied().flatten().unwrap_or(missing),
            _ => missing,
        })
        .collect();
    Keys { labels, of_row }
}

/// Labels of distinct sorted numbers: short forms (`1.5k`), or dates for time columns; the full
/// round-trip form where short forms of two values would coincide.
fn number_labels(values: &[f64], time: bool) -> Vec<String> {
    let short: Vec<String> = values
        .iter()
        .map(|&v| {
            if time {
                let t = format_timestamp(v);
                t.strip_suffix(" 00:00:00").map(str::to_string).unwrap_or(t)
            } else {
                format_value(v)
            }
        })
        .collect();
    let mut sorted = short.clone();
    sorted.sort_unstable();
    let unique = sorted.windows(2).all(|w| w[0] != w[1]);
    if unique { short } else { values.iter().map(|v| v.to_string()).collect() }
}

/// The colour channel read as categories: a numeric column without `type` is grouped by its
/// distinct values; `type = "continuous"` is an error, since groups need categories. `marks`
/// names what is grouped, for the message ("bars").
pub fn grouping_channel(
    chart: &Chart,
    channel: Option<&ColorChannel>,
    table: &Table,
    marks: &str,
) -> Result<Option<ColorChannel>, MarkError> {
    let Some(channel) = channel else { return Ok(None) };
    let options = channel.options();
    if options.r#type == Some(ColorType::Continuous) {
        return Err(MarkError::at(
            &["color", "type"],
            format!("{marks} are grouped by colour, which needs categories, not a continuous scale"),
            "remove `type = \"continuous\"`: a numeric column is then grouped by its distinct values",
        ));
    }
    encode::column(chart, "color", &options.field, table)?;
    Ok(Some(ColorChannel::Detailed(ColorOptions { r#type: Some(ColorType::Categorical), ..options })))
}

/// The slot `(start, width)` in pixels of group `group` of `groups` side by side within band
/// `x` of `band`; a lone group fills the band.
pub fn dodged(band: &BandScale, x: usize, groups: &[String], group: usize) -> (f64, f64) {
    let start = band.start(x);
    if groups.len() <= 1 {
        return (start, band.bandwidth());
    }
    match BandScale::new(groups.to_vec(), (start, start + band.bandwidth()), GROUP_PADDING, 0.0) {
        Ok(inner) => (inner.start(group), inner.bandwidth()),
        Err(_) => (start, band.bandwidth() / groups.len() as f64),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_keys_are_sorted_and_merge_signed_zero() {
        let col =
            Column { name: "n".into(), values: crate::data::ColumnValues::Number(vec![3.0, -0.0, 1.0, 0.0, 3.0]) };
        let k = keys(&col, &[0, 1, 2, 3, 4]);
        assert_eq!(k.labels, vec!["0", "1", "3"]);
        assert_eq!(k.of_row, vec![2, 0, 1, 0, 2]);
    }

    #[test]
    fn colliding_short_labels_fall_back_to_full_numbers() {
        let labels = number_labels(&[1.000001, 1.000002], false);
        assert_eq!(labels, vec!["1.000001", "1.000002"]);
    }
}
