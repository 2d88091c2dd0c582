//! Text columns that hold dates in a non-ISO format (`Jun 12 1998`, `12/06/1998`): they would
//! silently become hundreds of categories, so each one gets a warning naming the `parse` rule
//! that reads it as times, with a format that fits the values.
//!
//! ISO dates (`1998-06-12`, also `1998/06/12`) need no warning: they are read as times anyway.

use super::table::{ColumnValues, Table};

/// Formats tried, most common first. Where month-first and day-first both fit every value, the
/// month-first one is suggested and the day-first one named beside it.
const FORMATS: [&str; 20] = [
    "%b %d %Y",
    "%b %d, %Y",
    "%B %d %Y",
    "%B %d, %Y",
    "%d %b %Y",
    "%d %B %Y",
    "%d-%b-%Y",
    "%d-%b-%y",
    "%a, %d %b %Y %H:%M:%S",
    "%m/%d/%Y",
    "%d/%m/%Y",
    "%m/%d/%Y %H:%M",
    "%d/%m/%Y %H:%M",
    "%m/%d/%Y %H:%M:%S",
    "%d/%m/%Y %H:%M:%S",
    "%d.%m.%Y",
    "%m-%d-%Y",
    "%d-%m-%Y",
    "%m/%d/%y",
    "%d/%m/%y",
];

/// Most distinct values looked at per column.
const SAMPLE: usize = 500;

/// Share of the sampled values a format must read (a few cells like `TBD` are tolerated; the
/// `parse` rule will then name them).
const MIN_SHARE: f64 = 0.9;

/// One warning per text column of `table` that `check` accepts whose values look like non-ISO
/// dates.
pub fn date_warnings(table: &Table, check: impl Fn(&str) -> bool) -> Vec<String> {
    let mut out = Vec::new();
    for column in &table.columns {
        let ColumnValues::Text(cats) = &column.values else { continue };
        if !check(&column.name) {
            continue;
        }
        let sample: Vec<&str> = cats.levels.iter().map(|l| l.trim()).filter(|l| !l.is_empty()).take(SAMPLE).collect();
        let Some((format, alternative)) = guess_format(&sample) else { continue };
        let key = toml_key(&column.name);
        let example = sample.first().map(|s| crate::spec::validate::shorten(s)).unwrap_or_default();
        let alt = alternative.map(|a| format!(" (or \"date:{a}\" if the day comes first)")).unwrap_or_default();
        out.push(format!(
            "column `{}` holds dates written like `{example}`, which are read as text ({} categories); \
             read them as times with parse = {{ {key} = \"date:{format}\" }}{alt}",
            column.name,
            cats.levels.len()
        ));
    }
    out
}

/// The format that reads (nearly) every value, and a day-first alternative that reads them too.
pub fn guess_format(sample: &[&str]) -> Option<(&'static str, Option<&'static str>)> {
    if sample.is_empty() {
        return None;
    }
    let fits = |format: &str| {
        let read = sample.iter().filter(|s| super::parse::parse_with(s, format).is_some()).count();
        read as f64 >= MIN_SHARE * sample.len() as f64
    };
    let index = FORMATS.iter().position(|f| fits(*f))?;
    let format = FORMATS.get(index)?;
    let alternative = format
        .contains("%m/%d")
        .then(|| format.replace("%m/%d", "%d/%m"))
        .and_then(|alt| FORMATS.iter().copied().find(|f| *f == alt && fits(f)));
    Some((format, alternative))
}

/// A column name as a TOML key: bare when it can be, else quoted.
fn toml_key(name: &str) -> String {
    if !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
        name.to_string()
    } else {
        serde_json::to_string(name).unwrap_or_else(|_| format!("\"{name}\""))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::table::{Categories, Column};

    fn table(name: &str, values: &[&str]) -> Table {
        Table {
            columns: vec![Column {
                name: name.into(),
                values: ColumnValues::Text(Categories::from_values(values.iter().map(|v| Some(*v)))),
            }],
            rows: values.len(),
        }
    }

    #[test]
    fn month_name_dates_get_the_parse_fix() {
        let t = table("Release Date", &["Jun 12 1998", "Aug 07 1998", "Jun 12 1998", "TBD"]);
        // 2 of 3 distinct values read; below 90% with TBD, so no warning...
        assert!(date_warnings(&t, |_| true).is_empty());
        let dates: Vec<String> = (1..=28).map(|d| format!("Feb {d:02} 2001")).collect();
        let mut values: Vec<&str> = dates.iter().map(String::as_str).collect();
        values.push("TBD");
        // ...but 28 of 29 do.
        assert_eq!(
            date_warnings(&table("Release Date", &values), |_| true),
            ["column `Release Date` holds dates written like `Feb 01 2001`, which are read as text (29 categories); \
              read them as times with parse = { \"Release Date\" = \"date:%b %d %Y\" }"]
        );
        assert!(date_warnings(&table("Release Date", &values), |c| c != "Release Date").is_empty());
    }

    #[test]
    fn slashed_dates_name_both_orders_when_both_fit() {
        assert_eq!(guess_format(&["12/06/1998", "01/02/2003"]), Some(("%m/%d/%Y", Some("%d/%m/%Y"))));
        assert_eq!(guess_format(&["12/26/1998", "01/02/2003"]), Some(("%m/%d/%Y", None)));
        assert_eq!(guess_format(&["26/12/1998", "01/02/2003"]), Some(("%d/%m/%Y", None)));
        assert_eq!(guess_format(&["31.12.1999"]), Some(("%d.%m.%Y", None)));
    }

    #[test]
    fn words_numbers_and_iso_dates_are_left_alone() {
        assert_eq!(guess_format(&["setosa", "versicolor"]), None);
        assert_eq!(guess_format(&["12", "1998"]), None);
        assert_eq!(guess_format(&["1998-06-12", "2001-01-01"]), None);
        assert_eq!(guess_format(&[]), None);
    }
}
