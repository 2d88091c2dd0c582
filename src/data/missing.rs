//! The cell texts CSV files write for a missing value, read as missing (null) in every column:
//! one documented list, replaced per source by `null_values`.

use polars::prelude::{DataFrame, DataType, NullValues, PlSmallStr};

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

/// Whether a text column of `df` (read without the list) holds one of [`MISSING_TEXTS`]: then the
/// file must be read with the list, which may also turn that column into numbers.
pub fn holds_missing_text(df: &DataFrame) -> bool {
    df.columns().iter().any(|column| {
        column.dtype() == &DataType::String
            && column
                .as_materialized_series()
                .str()
                .is_ok_and(|values| values.iter().flatten().any(|v| MISSING_TEXTS.contains(&v)))
    })
}

/// Whether a schema has a text column, which may hold missing texts: a lazy scan then compares
/// its cells with the list (a file of numbers and dates only is scanned as it is).
pub fn may_hold_missing_text(schema: &polars::prelude::Schema) -> bool {
    schema.iter_values().any(|dtype| dtype == &DataType::String)
}
