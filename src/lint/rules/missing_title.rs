//! LB001 `missing-title`: a chart without a title leaves the reader to guess what it shows.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{Role, Shape};

/// The rule.
pub static RULE: Rule = Rule {
    code: "LB001",
    name: "missing-title",
    category: Category::Labelling,
    severity: Severity::Warning,
    summary: "The chart has no title saying what it shows.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let mut titled = false;
    s.output.scene.walk(|item| {
        if item.role == Role::Title && matches!(&item.shape, Shape::Text(t) if !t.content.trim().is_empty()) {
            titled = true;
        }
    });
    if titled {
        return Vec::new();
    }
    vec![Issue::new(
        "title",
        "title",
        "the chart has no title",
        "add `title = \"...\"` saying what the chart shows (a finding, not just the variables)",
    )]
}
