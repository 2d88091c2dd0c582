//! SC005 `numbers-as-text`: a category (band) axis made by accident. A column whose cells are
//! numbers or dates written in a form the reader did not recognise ("1,234", "3.5%", "$12",
//! "12/06/1998") is read as text, so its axis places the values as categories in the order they
//! first appear, evenly spaced, instead of on a scale where distances mean differences.
//!
//! The rule looks at text columns on band axes (the default for text, and every bar x) and
//! fires when at least [`SHARE`] of the distinct values, and at least [`MIN_VALUES`] of them,
//! look like numbers or like dates.

use crate::lint::chart_info::cartesian_axes;
use crate::lint::{Category, Issue, Rule, Severity, Subject};

/// The rule.
pub static RULE: Rule = Rule {
    code: "SC005",
    name: "numbers-as-text",
    category: Category::Scale,
    severity: Severity::Warning,
    summary: "A band axis shows a text column whose values are numbers or dates the reader did not recognise.",
    check,
};

/// Share of a column's distinct values that must look like numbers or dates.
pub const SHARE: f64 = 0.9;
/// Fewer distinct values than this are left alone (two labels do not make a scale).
pub const MIN_VALUES: usize = 3;

/// Whether `s` reads as a number with thousands separators, a sign, a currency symbol or a
/// percent sign (`1,234`, `-3.5%`, `$12`, `1 000`, `1'000.5`).
pub fn looks_numeric(s: &str) -> bool {
    let t = s.trim();
    let t = t.strip_prefix(['+', '-', '−']).unwrap_or(t);
    let t = t.strip_prefix(['$', '€', '£', '¥']).unwrap_or(t);
    let t = t.strip_suffix('%').unwrap_or(t).trim_end();
    let starts_and_ends_with_digit =
        t.chars().next().is_some_and(|c| c.is_ascii_digit()) && t.chars().last().is_some_and(|c| c.is_ascii_digit());
    starts_and_ends_with_digit && t.chars().all(|c| c.is_ascii_digit() || matches!(c, ',' | '.' | ' ' | '\''))
}

/// Whether `s` reads as a date of three digit groups separated by `/`, `-` or `.`, day or month
/// first with a 2- or 4-digit year (`12/06/1998`, `6.12.98`) or year first (`1998/06/12`).
pub fn looks_like_date(s: &str) -> bool {
    let t = s.trim();
    let Some(sep) = t.chars().find(|c| matches!(c, '/' | '-' | '.')) else { return false };
    let parts: Vec<&str> = t.split(sep).collect();
    let [a, b, c] = parts.as_slice() else { return false };
    if ![a, b, c].iter().all(|p| !p.is_empty() && p.chars().all(|ch| ch.is_ascii_digit())) {
        return false;
    }
    let short = |p: &str| p.len() <= 2;
    (short(a) && short(b) && (c.len() == 2 || c.len() == 4)) || (a.len() == 4 && short(b) && short(c))
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    cartesian_axes(s.chart)
        .into_iter()
        .filter_map(|a| {
            let levels = &s.table.column(&a.options.field)?.categories()?.levels;
            let values: Vec<&str> = levels.iter().map(String::as_str).filter(|l| !l.trim().is_empty()).collect();
            let numbers: Vec<&str> = values.iter().copied().filter(|v| looks_numeric(v)).collect();
            let dates: Vec<&str> = values.iter().copied().filter(|v| looks_like_date(v)).collect();
            let (what, like, parse) =
                if dates.len() > numbers.len() { ("dates", dates, "date") } else { ("numbers", numbers, "number") };
            let enough = like.len() >= MIN_VALUES && like.len() as f64 >= SHARE * values.len() as f64;
            enough.then(|| {
                let examples: Vec<String> =
                    like.iter().take(3).map(|v| format!("\"{}\"", crate::spec::validate::shorten(v))).collect();
                let field = &a.options.field;
                Issue::new(
                    a.name,
                    a.key,
                    format!(
                        "`{field}` was read as text, but {} of its {} values look like {what} ({}), so the {} \
                         spaces them evenly as categories in the order they first appear instead of on a scale",
                        like.len(),
                        values.len(),
                        examples.join(", "),
                        a.name
                    ),
                    format!(
                        "parse the column as {what} when it is read (`parse = {{ {field} = \"{parse}\" }}` on the data \
                         source), or clean the values (no thousands separators, `%` or currency signs; dates as \
                         YYYY-MM-DD) so they read as {what}"
                    ),
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recognises_numbers_and_dates_written_for_people() {
        for s in ["1,234", "3.5%", "$12", "-1 000", "1'000.5", "42"] {
            assert!(looks_numeric(s), "{s}");
        }
        for s in ["USA", "1st", "A1", "3.5 kg", "", "%"] {
            assert!(!looks_numeric(s), "{s}");
        }
        for s in ["12/06/1998", "6.12.98", "1998/06/12", "1998-6-12"] {
            assert!(looks_like_date(s), "{s}");
        }
        for s in ["12/06", "1/2/3", "a/b/c", "1998-06-12T10:00"] {
            assert!(!looks_like_date(s), "{s}");
        }
    }
}
