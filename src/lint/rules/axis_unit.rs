//! SC002 `axis-title-without-unit`: when the column's name says its unit (`temp_c`,
//! `length_mm`, `price [USD]`), the axis title should show it.

use crate::lint::chart_info::cartesian_axes;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{Role, Shape};

/// The rule.
pub static RULE: Rule = Rule {
    code: "SC002",
    name: "axis-title-without-unit",
    category: Category::Scale,
    severity: Severity::Warning,
    summary: "An axis title shows no unit although the column's name carries one.",
    check,
};

/// Unit suffixes recognised at the end of a column name after `_`, with how to print them.
const SUFFIXES: &[(&str, &str)] = &[
    ("mm", "mm"),
    ("cm", "cm"),
    ("m", "m"),
    ("km", "km"),
    ("in", "in"),
    ("ft", "ft"),
    ("mi", "mi"),
    ("mg", "mg"),
    ("g", "g"),
    ("kg", "kg"),
    ("t", "t"),
    ("lb", "lb"),
    ("ms", "ms"),
    ("s", "s"),
    ("sec", "s"),
    ("min", "min"),
    ("h", "h"),
    ("hr", "h"),
    ("days", "days"),
    ("hz", "Hz"),
    ("khz", "kHz"),
    ("mhz", "MHz"),
    ("w", "W"),
    ("kw", "kW"),
    ("mw", "MW"),
    ("kwh", "kWh"),
    ("v", "V"),
    ("a", "A"),
    ("pa", "Pa"),
    ("hpa", "hPa"),
    ("kpa", "kPa"),
    ("bar", "bar"),
    ("c", "°C"),
    ("degc", "°C"),
    ("f", "°F"),
    ("degf", "°F"),
    ("k", "K"),
    ("pct", "%"),
    ("percent", "%"),
    ("usd", "USD"),
    ("eur", "EUR"),
    ("gbp", "GBP"),
    ("mph", "mph"),
    ("kmh", "km/h"),
    ("kph", "km/h"),
    ("mps", "m/s"),
    ("kt", "kn"),
    ("db", "dB"),
    ("l", "l"),
    ("ml", "ml"),
    ("mol", "mol"),
    ("ppm", "ppm"),
    ("bytes", "bytes"),
    ("mb", "MB"),
    ("gb", "GB"),
];

/// The unit a column name announces: a `[unit]` or `(unit)` at its end, or a known suffix.
pub fn unit_in_name(field: &str) -> Option<String> {
    let f = field.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if f.ends_with(close)
            && let Some(start) = f.rfind(open)
        {
            let unit = f[start + 1..f.len() - 1].trim();
            if !unit.is_empty() {
                return Some(unit.to_string());
            }
        }
    }
    let (_, suffix) = f.rsplit_once('_')?;
    let lower = suffix.to_ascii_lowercase();
    SUFFIXES.iter().find(|(s, _)| *s == lower).map(|(_, u)| u.to_string())
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let mut out = Vec::new();
    for axis in cartesian_axes(s.chart) {
        if axis.options.unit.as_deref().is_some_and(|u| !u.trim().is_empty()) {
            continue;
        }
        let Some(unit) = unit_in_name(&axis.options.field) else { continue };
        // The title the reader sees on this axis.
        let mut shown = None;
        s.output.scene.walk(|item| {
            if item.role == Role::AxisTitle
                && item.label.as_deref() == Some(axis.name)
                && let Shape::Text(t) = &item.shape
            {
                shown = Some(t.content.clone());
            }
        });
        let Some(title) = shown else { continue };
        let lower = title.to_lowercase();
        if lower.contains(&unit.to_lowercase()) || title.contains(&axis.options.field) {
            continue;
        }
        out.push(Issue::new(
            axis.name,
            axis.key,
            format!(
                "the {} title \"{title}\" shows no unit, but the column `{}` is in {unit}",
                axis.name, axis.options.field
            ),
            format!("add `unit = \"{unit}\"` to `{}` so the title reads \"{title} ({unit})\"", axis.key),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::unit_in_name;

    #[test]
    fn units_are_read_from_suffixes_and_brackets() {
        assert_eq!(unit_in_name("temp_c").as_deref(), Some("°C"));
        assert_eq!(unit_in_name("Length_MM").as_deref(), Some("mm"));
        assert_eq!(unit_in_name("price [USD]").as_deref(), Some("USD"));
        assert_eq!(unit_in_name("speed (m/s)").as_deref(), Some("m/s"));
        assert_eq!(unit_in_name("petal_length"), None);
        assert_eq!(unit_in_name("species"), None);
        assert_eq!(unit_in_name("model_year"), None);
    }
}
