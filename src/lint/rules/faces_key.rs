//! TQ005 `faces-without-key`: Chernoff faces without the key that says which column drives which
//! feature cannot be read at all: a wide mouth might mean high mileage or low weight.
//!
//! The rule looks for the feature key in the scene (a legend titled
//! [`KEY_TITLE`](crate::mark::faces::KEY_TITLE)); `key = false` leaves it out.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::multivariate::faces::KEY_TITLE;
use crate::scene::{Role, Shape};
use crate::spec::ChartKind;

/// The rule.
pub static RULE: Rule = Rule {
    code: "TQ005",
    name: "faces-without-key",
    category: Category::Technique,
    severity: Severity::Error,
    summary: "Chernoff faces are drawn without the key that says which column drives which feature.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    if !matches!(s.chart.kind, ChartKind::Faces(_)) {
        return Vec::new();
    }
    let mut keyed = false;
    s.output.scene.walk(|item| {
        keyed |= item.role == Role::Legend && matches!(&item.shape, Shape::Text(t) if t.content == KEY_TITLE);
    });
    if keyed {
        return Vec::new();
    }
    vec![Issue::new(
        "feature key",
        "key",
        "the faces have no feature key, so the reader cannot tell which column drives which feature, nor in which \
         direction",
        "remove `key = false`: the key lists each feature with its column and what its low and high values look like",
    )]
}
