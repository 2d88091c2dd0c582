//! The cell texts CSV files write for a missing value, read as missing (null) in every column:
//! one documented list, replaced per source by `null_values`.

use polars::prelude::{NullValues, PlSmallStr};

/// Texts read as missing by default: empty, and the spellings of R, pandas, spreadsheets and
/// databases. `NaN` in a numeric column is missing either way.
pub const MISSING_TEXTS: &[&str] =
    &["", "NA", "N/A", "n/a", "NaN", "nan", "-nan", "-NaN", "null", "NULL", "None", "#N/A", "<NA>"];

/// The polars null values for a source: its own list (`null_values`), or [`MISSING_TEXTS`].
pub fn csv_null_values(own: Option<&[String]>) -> Option<NullValues> {
    let texts: Vec<PlSmallStr> = match own {
        Some(list) => list.iter().map(|t| PlSmallStr::from(t.as_str())).collect(),
        None => MISSING_TEXTS.iter().map(|t| PlSmallStr::from(*t)).collect(),
    };
    (!texts.is_empty()).then_some(NullValues::AllColumns(texts))
}
