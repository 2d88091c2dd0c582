//! Per-column parse rules (`parse = { when = "date:%b %d %Y", id = "text" }`): how to read a
//! column instead of letting the reader guess.
//!
//! | rule | reads | empty cells |
//! |---|---|---|
//! | `"text"` | the cell's text as it is (CSV cells are not guessed first, so `007` stays `007`) | missing |
//! | `"number"` | a decimal number (`1.5`, `-2e3`, `inf`) | missing |
//! | `"boolean"` | `true`/`false`, `yes`/`no`, `1`/`0` (any case) | missing |
//! | `"date"` | an ISO 8601 date or date-time, as automatic detection does | missing |
//! | `"date:FORMAT"` | a strftime format as chrono reads it (`%b %d %Y`, `%d/%m/%Y %H:%M`, `%Y-%m-%dT%H:%M:%S%z`); without `%z` the time is UTC | missing |
//!
//! Any other cell that does not read is an error naming the column, the rule, how many cells
//! failed and the first of them (row number and at most 40 characters of its text).

use std::collections::{BTreeMap, HashMap};

use chrono::format::{Item, StrftimeItems};
use chrono::{DateTime, NaiveDate, NaiveDateTime};
use polars::prelude::*;

use crate::spec::suggest::did_you_mean;
use crate::spec::validate::shorten;

/// Rule names as written in the spec.
pub const RULES: [&str; 4] = ["text", "number", "boolean", "date"];

/// How one column is read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ColumnParse {
    /// Text as it is.
    Text,
    /// Decimal numbers.
    Number,
    /// true/false, yes/no, 1/0.
    Boolean,
    /// Dates or date-times: ISO 8601 without a format, else the strftime format.
    Date(Option<String>),
}

/// A parse rule that could not be applied.
#[derive(Debug, PartialEq)]
pub struct ParseError {
    /// The column.
    pub column: String,
    /// The rule as written.
    pub rule: String,
    /// What went wrong.
    pub message: String,
    /// How to fix it.
    pub hint: String,
}

impl ColumnParse {
    /// Read a rule as written in the spec.
    pub fn from_rule(rule: &str) -> Result<ColumnParse, String> {
        let (name, format) = match rule.split_once(':') {
            Some((name, format)) => (name.trim(), Some(format)),
            None => (rule.trim(), None),
        };
        match (name, format) {
            ("text", None) => Ok(ColumnParse::Text),
            ("number", None) => Ok(ColumnParse::Number),
            ("boolean", None) => Ok(ColumnParse::Boolean),
            ("date", None) => Ok(ColumnParse::Date(None)),
            ("date", Some(f)) => {
                if f.trim().is_empty() || StrftimeItems::new(f).any(|item| matches!(item, Item::Error)) {
                    Err(format!("`{}` is not a strftime format chrono can read", shorten(f)))
                } else {
                    Ok(ColumnParse::Date(Some(f.to_string())))
                }
            }
            ("text" | "number" | "boolean", Some(_)) => {
                Err(format!("`{name}` takes no format; only `date:FORMAT` does"))
            }
            (other, _) => Err(match did_you_mean(other, RULES) {
                Some(best) => format!("`{}` is not a parse rule; did you mean `{best}`?", shorten(other)),
                None => format!("`{}` is not a parse rule", shorten(other)),
            }),
        }
    }
}

/// Apply every rule to its column of `df`. Rules naming no column are errors listing the columns.
pub fn apply(mut df: DataFrame, rules: &BTreeMap<String, String>) -> Result<DataFrame, ParseError> {
    for (column, rule) in rules {
        let fail =
            |message: String, hint: String| ParseError { column: column.clone(), rule: rule.clone(), message, hint };
        let parse = ColumnParse::from_rule(rule).map_err(|m| {
            fail(
                m,
                "write \"text\", \"number\", \"boolean\", \"date\" or \"date:FORMAT\", e.g. \"date:%d/%m/%Y\"".into(),
            )
        })?;
        let names: Vec<String> = df.get_column_names().iter().map(|n| n.to_string()).collect();
        let Some(found) = names.iter().find(|n| n.trim_start_matches('\u{feff}') == column.as_str()) else {
            let listed: Vec<&str> = names.iter().map(String::as_str).collect();
            return Err(fail(
                "the source has no such column".into(),
                crate::spec::suggest::hint(column, &listed, "columns", true),
            ));
        };
        let text = df.column(found).and_then(|c| c.cast(&DataType::String)).map_err(|e| {
            fail(format!("cannot read it as text first: {}", super::load::first_line(&e)), String::new())
        })?;
        let text = text.as_materialized_series().str().map_err(|e| fail(super::load::first_line(&e), String::new()))?;
        let name = PlSmallStr::from(found.as_str());
        let series = parse_column(text, &parse, name).map_err(|Bad { count, row, value }| {
            fail(
                format!(
                    "{count} of {} values do not read as `{rule}`, e.g. `{}` in row {}",
                    text.len(),
                    shorten(&value),
                    row + 1
                ),
                format!("fix those cells, or change the rule for `{column}`"),
            )
        })?;
        df.with_column(series.into_column()).map_err(|e| fail(super::load::first_line(&e), String::new()))?;
    }
    Ok(df)
}

/// Cells that did not read: how many, and the first (row index, text).
struct Bad {
    count: usize,
    row: usize,
    value: String,
}

fn parse_column(text: &StringChunked, parse: &ColumnParse, name: PlSmallStr) -> Result<Series, Bad> {
    match parse {
        ColumnParse::Text => Ok(text.clone().with_name(name).into_series()),
        ColumnParse::Number => {
            let values = each(text, |s| s.parse::<f64>().ok())?;
            Ok(Float64Chunked::from_iter_options(name, values.into_iter()).into_series())
        }
        ColumnParse::Boolean => {
            let values = each(text, |s| match s.to_ascii_lowercase().as_str() {
                "true" | "yes" | "1" => Some(true),
                "false" | "no" | "0" => Some(false),
                _ => None,
            })?;
            Ok(BooleanChunked::from_iter_options(name, values.into_iter()).into_series())
        }
        ColumnParse::Date(format) => {
            let mut cache: HashMap<&str, Option<i64>> = HashMap::new();
            let mut values = Vec::with_capacity(text.len());
            let mut bad: Option<Bad> = None;
            for (row, cell) in text.iter().enumerate() {
                let Some(cell) = cell.map(str::trim).filter(|s| !s.is_empty()) else {
                    values.push(None);
                    continue;
                };
                let ms = *cache.entry(cell).or_insert_with(|| match format {
                    Some(f) => parse_with(cell, f),
                    None => super::time::parse_iso(cell).map(|ms| ms as i64),
                });
                if ms.is_none() {
                    note_bad(&mut bad, row, cell);
                }
                values.push(ms);
            }
            if let Some(bad) = bad {
                return Err(bad);
            }
            let ms = Int64Chunked::from_iter_options(name, values.into_iter());
            Ok(ms.into_datetime(TimeUnit::Milliseconds, None).into_series())
        }
    }
}

/// Milliseconds since the epoch of `text` read with a strftime format: with an offset when the
/// format has one, else a date-time in UTC, else a date at midnight UTC.
pub fn parse_with(text: &str, format: &str) -> Option<i64> {
    if let Ok(dt) = DateTime::parse_from_str(text, format) {
        return Some(dt.timestamp_millis());
    }
    if let Ok(dt) = NaiveDateTime::parse_from_str(text, format) {
        return Some(dt.and_utc().timestamp_millis());
    }
    let date = NaiveDate::parse_from_str(text, format).ok()?;
    Some(date.and_hms_opt(0, 0, 0)?.and_utc().timestamp_millis())
}

fn note_bad(bad: &mut Option<Bad>, row: usize, cell: &str) {
    match bad {
        Some(b) => b.count += 1,
        None => *bad = Some(Bad { count: 1, row, value: cell.to_string() }),
    }
}

/// Read every non-empty cell with `read`; empty and missing cells are missing.
fn each<T>(text: &StringChunked, read: impl Fn(&str) -> Option<T>) -> Result<Vec<Option<T>>, Bad> {
    let mut out = Vec::with_capacity(text.len());
    let mut bad: Option<Bad> = None;
    for (row, cell) in text.iter().enumerate() {
        match cell.map(str::trim).filter(|s| !s.is_empty()) {
            None => out.push(None),
            Some(s) => {
                let v = read(s);
                if v.is_none() {
                    note_bad(&mut bad, row, s);
                }
                out.push(v);
            }
        }
    }
    match bad {
        Some(b) => Err(b),
        None => Ok(out),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rules(pairs: &[(&str, &str)]) -> BTreeMap<String, String> {
        pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
    }

    fn frame() -> DataFrame {
        df!(
            "when" => ["Jun 12 1998", "Aug 07 1998", ""],
            "id" => [7i64, 8, 9],
            "n" => [" 1.5", "-2e3", ""],
            "flag" => ["true", "No", "1"],
        )
        .expect("frame")
    }

    #[test]
    fn rules_read_their_columns() {
        let df =
            apply(frame(), &rules(&[("when", "date:%b %d %Y"), ("id", "text"), ("n", "number"), ("flag", "boolean")]))
                .expect("every rule applies");
        let when = df.column("when").expect("when");
        assert_eq!(when.dtype(), &DataType::Datetime(TimeUnit::Milliseconds, None));
        let ms = when.cast(&DataType::Int64).expect("ms").as_materialized_series().i64().expect("i64").to_vec();
        // 1998-06-12 and 1998-08-07 at midnight UTC.
        assert_eq!(ms, [Some(897_609_600_000), Some(902_448_000_000), None]);
        let ids = df.column("id").expect("id").as_materialized_series().str().expect("text").iter().collect::<Vec<_>>();
        assert_eq!(ids, [Some("7"), Some("8"), Some("9")]);
        assert_eq!(
            df.column("n").expect("n").as_materialized_series().f64().expect("f64").to_vec(),
            [Some(1.5), Some(-2000.0), None]
        );
        let flags =
            df.column("flag").expect("flag").as_materialized_series().bool().expect("bool").iter().collect::<Vec<_>>();
        assert_eq!(flags, [Some(true), Some(false), Some(true)]);
    }

    #[test]
    fn formats_with_times_and_offsets() {
        assert_eq!(parse_with("12/06/1998 13:30", "%d/%m/%Y %H:%M"), Some(897_658_200_000));
        assert_eq!(parse_with("1998-06-12T13:30:00+0200", "%Y-%m-%dT%H:%M:%S%z"), Some(897_651_000_000));
        assert_eq!(parse_with("31/02/1998", "%d/%m/%Y"), None);
        let iso = apply(df!("d" => ["1998-06-12"]).expect("frame"), &rules(&[("d", "date")])).expect("ISO");
        let ms = iso
            .column("d")
            .expect("d")
            .cast(&DataType::Int64)
            .expect("ms")
            .as_materialized_series()
            .i64()
            .expect("i64")
            .get(0);
        assert_eq!(ms, Some(897_609_600_000));
    }

    #[test]
    fn a_failing_cell_names_column_rule_count_and_value() {
        let df = df!("when" => ["Jun 12 1998", "TBD", "soon", "Jun 13 1998"]).expect("frame");
        let err = apply(df, &rules(&[("when", "date:%b %d %Y")])).expect_err("TBD is no date");
        assert_eq!(err.column, "when");
        assert_eq!(err.message, "2 of 4 values do not read as `date:%b %d %Y`, e.g. `TBD` in row 2");
        let long = "x".repeat(100);
        let err = apply(df!("n" => [long.as_str()]).expect("frame"), &rules(&[("n", "number")])).expect_err("text");
        assert_eq!(err.message, format!("1 of 1 values do not read as `number`, e.g. `{}…` in row 1", "x".repeat(40)));
    }

    #[test]
    fn bad_rules_and_unknown_columns_are_errors() {
        assert_eq!(ColumnParse::from_rule("dat"), Err("`dat` is not a parse rule; did you mean `date`?".into()));
        assert_eq!(ColumnParse::from_rule("date:%Q"), Err("`%Q` is not a strftime format chrono can read".into()));
        assert_eq!(ColumnParse::from_rule("text:x"), Err("`text` takes no format; only `date:FORMAT` does".into()));
        let err = apply(frame(), &rules(&[("wen", "date")])).expect_err("no column");
        assert_eq!(err.message, "the source has no such column");
        assert_eq!(err.hint, "did you mean `when`? columns: `when`, `id`, `n`, `flag`");
    }
}
