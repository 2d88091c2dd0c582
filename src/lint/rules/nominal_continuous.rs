//! CL005 `nominal-continuous-colour`: a column of names or identifiers coloured by a
//! continuous map. A continuous map says that close colours are close values and that the
//! colour bar's order means something; for station ids, postcodes or group numbers neither
//! holds, and neighbouring ids get colours the eye cannot tell apart.
//!
//! A column is nominal when it holds text, or whole numbers under a name that says they are
//! identifiers: its last word (split at `_`, `-`, spaces and lower-to-upper case changes) is
//! one of [`ID_WORDS`] (`station_id`, `zipCode`, `group`).

use crate::data::Column;
use crate::lint::chart_info::colour_encodings;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::categorical::is_categorical;

/// The rule.
pub static RULE: Rule = Rule {
    code: "CL005",
    name: "nominal-continuous-colour",
    category: Category::Colour,
    severity: Severity::Warning,
    summary: "A column of names or identifiers (text, or whole-number ids) is coloured by a continuous map.",
    check,
};

/// Last words of a column name that mark whole numbers as identifiers rather than quantities.
pub const ID_WORDS: [&str; 12] =
    ["id", "ids", "code", "codes", "group", "cluster", "class", "category", "zip", "fips", "key", "kind"];

/// The last word of a column name, lowercase (`station_id` → `id`, `zipCode` → `code`).
fn last_word(name: &str) -> String {
    let mut words: Vec<String> = vec![String::new()];
    let mut previous_lower = false;
    for ch in name.chars() {
        if !ch.is_alphanumeric() {
            words.push(String::new());
            previous_lower = false;
            continue;
        }
        if ch.is_uppercase() && previous_lower {
            words.push(String::new());
        }
        previous_lower = ch.is_lowercase() || ch.is_ascii_digit();
        if let Some(w) = words.last_mut() {
            w.extend(ch.to_lowercase());
        }
    }
    words.into_iter().rev().find(|w| !w.is_empty()).unwrap_or_default()
}

/// Why `column` is nominal, if it is: it holds text, or whole-number identifiers.
fn nominal(column: &Column) -> Option<&'static str> {
    if column.categories().is_some() {
        return Some("holds text");
    }
    let values = column.numbers().filter(|_| !column.is_time())?;
    let whole = values.iter().filter(|v| v.is_finite()).all(|v| v.fract() == 0.0);
    (whole && ID_WORDS.contains(&last_word(&column.name).as_str())).then_some("holds whole-number identifiers")
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    colour_encodings(s.chart)
        .into_iter()
        .filter_map(|e| {
            let column = s.table.column(&e.options.field)?;
            if is_categorical(&e.options, column) {
                return None;
            }
            let why = nominal(column)?;
            let distinct = match column.numbers() {
                Some(v) => {
                    let mut d: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
                    d.sort_by(f64::total_cmp);
                    d.dedup();
                    d.len()
                }
                None => column.categories().map_or(0, |c| c.levels.len()),
            };
            Some(Issue::new(
                format!("{} `{}`", e.key, e.options.field),
                e.key,
                format!(
                    "`{}` {why} ({distinct} distinct values) but is coloured by a continuous map, which reads \
                     as an order and makes neighbouring values look alike",
                    e.options.field
                ),
                format!(
                    "colour it as categories with `{} = {{ field = \"{}\", type = \"categorical\" }}` (at most about \
                     10 stay apart; group the rest, or show the column another way), or colour by a quantity",
                    e.key, e.options.field
                ),
            ))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn last_words() {
        for (name, word) in
            [("station_id", "id"), ("zipCode", "code"), ("group", "group"), ("Group ID", "id"), ("temp", "temp")]
        {
            assert_eq!(super::last_word(name), word, "{name}");
        }
    }
}
