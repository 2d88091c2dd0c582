//! SC004 `colour-without-legend`: colour that encodes a column needs a legend or colour bar,
//! or the reader cannot decode it.

use crate::lint::chart_info::colour_encodings;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::Role;

/// The rule.
pub static RULE: Rule = Rule {
    code: "SC004",
    name: "colour-without-legend",
    category: Category::Scale,
    severity: Severity::Error,
    summary: "Colour encodes a column but the chart has no legend or colour bar to decode it.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let Some(enc) = colour_encodings(s.chart).into_iter().next() else { return Vec::new() };
    let mut legend = false;
    s.output.scene.walk(|item| legend |= item.role == Role::Legend);
    if legend {
        return Vec::new();
    }
    vec![Issue::new(
        "legend",
        format!("{}.legend", enc.key),
        format!("colour encodes `{}` but no legend or colour bar explains it", enc.options.field),
        format!("remove `legend = false` from `{}`", enc.key),
    )]
}
