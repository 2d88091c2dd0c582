//! CL002 `diverging-midpoint`: a diverging colour map must be centred on a value that means
//! something.
//!
//! A diverging map (`rdbu`, `brbg`, `spectral`, ...) tells the reader "light is the centre,
//! the two hues are the two sides". Without `midpoint` the centre is the middle of the data's
//! range, an accident of the sample; a midpoint outside the range leaves one arm of the map
//! unused and no value at its centre. Kinds whose chart-level `scheme` has no `midpoint`
//! (segments, treemaps, graphs, link maps, flow) always centre on the middle of the colour
//! range.

use crate::guide::color::{self, ContinuousMap};
use crate::guide::format::format_value;
use crate::lint::chart_info::{colour_encodings, scheme_of};
use crate::lint::{Category, Issue, Rule, Severity, Subject};

/// The rule.
pub static RULE: Rule = Rule {
    code: "CL002",
    name: "diverging-midpoint",
    category: Category::Colour,
    severity: Severity::Warning,
    summary: "A diverging colour map is centred on the middle of the data (no `midpoint`) or on a midpoint outside it.",
    check,
};

const SEQUENTIAL_HINT: &str = "if no value is special, use a sequential map such as `scheme = \"viridis\"`";

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let mut issues = Vec::new();
    let encodings = colour_encodings(s.chart);
    for enc in &encodings {
        let Some(map) = enc.options.scheme.as_deref().and_then(color::continuous).filter(ContinuousMap::is_diverging)
        else {
            continue;
        };
        let field = &enc.options.field;
        let Some(values) = s.table.column(field).and_then(|c| c.numbers()) else { continue };
        let Some((lo, hi)) = finite_range(values) else { continue };
        let range = format!("{} to {}", format_value(lo), format_value(hi));
        let name = map.name();
        match enc.options.midpoint {
            None if hi > lo => issues.push(Issue::new(
                "colour map",
                format!("{}.scheme", enc.key),
                format!(
                    "diverging `{name}` is centred on {}, the middle of `{field}`'s range {range}, not on a \
                     value that means something",
                    format_value((lo + hi) / 2.0)
                ),
                format!(
                    "set `midpoint` in `{}` to the value the two colours diverge from (zero, a target, a \
                     reference year); {SEQUENTIAL_HINT}",
                    enc.key
                ),
            )),
            None => {}
            Some(m) if !m.is_finite() => issues.push(Issue::new(
                "colour map",
                format!("{}.midpoint", enc.key),
                format!("the midpoint of diverging `{name}` is {m}, not a number the map can be centred on"),
                "set `midpoint` to a finite value inside the data's range",
            )),
            Some(m) if m < lo || m > hi => issues.push(Issue::new(
                "colour map",
                format!("{}.midpoint", enc.key),
                format!(
                    "the midpoint {} of diverging `{name}` lies outside `{field}`'s range {range}: only one \
                     arm of the map is used and no value sits at its centre",
                    format_value(m)
                ),
                format!("set `midpoint` to a value inside {range}; for values all on one side, {SEQUENTIAL_HINT}"),
            )),
            Some(_) => {}
        }
    }
    if encodings.is_empty()
        && let Some((key, name)) = scheme_of(s.chart)
        && let Some(map) = color::continuous(name).filter(ContinuousMap::is_diverging)
    {
        issues.push(Issue::new(
            "colour map",
            key,
            format!(
                "diverging `{}` has no `midpoint` in this chart kind: its centre falls on the middle of the \
                 colour range, which marks no particular value",
                map.name()
            ),
            "use a sequential map such as `scheme = \"viridis\"`",
        ));
    }
    issues
}

/// The smallest and largest finite values, if any.
fn finite_range(values: &[f64]) -> Option<(f64, f64)> {
    values.iter().filter(|v| v.is_finite()).fold(None, |acc, &v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_skips_non_finite_values() {
        assert_eq!(finite_range(&[f64::NAN, 3.0, -1.0, f64::INFINITY, 2.0]), Some((-1.0, 3.0)));
        assert_eq!(finite_range(&[f64::NAN]), None);
        assert_eq!(finite_range(&[]), None);
    }
}
