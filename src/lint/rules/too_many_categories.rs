//! CL004 `too-many-categories`: more colour categories than a reader can tell apart and keep in
//! mind.
//!
//! Beyond about ten hues, categorical colours stop being distinguishable at a glance and the
//! reader has to go back and forth to the legend (Ware, "Information Visualization", recommends
//! at most 10–12 label colours; every palette dataink ships has at most 12, Okabe–Ito 8). The
//! count is read from each categorical legend of the scene, including entries it summarises as
//! "… and N more".

use super::colour_keys::{colour_keys, palette_keys};
use crate::lint::{Category, Issue, Rule, Severity, Subject};

/// Most colour categories one legend may have.
pub const MAX_CATEGORIES: usize = 10;

/// The rule.
pub static RULE: Rule = Rule {
    code: "CL004",
    name: "too-many-categories",
    category: Category::Colour,
    severity: Severity::Warning,
    summary: "More than 10 colour categories in one legend: the hues cannot be told apart or remembered.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let (key, _) = palette_keys(s.chart);
    colour_keys(&s.output.scene)
        .into_iter()
        .filter(|legend| legend.categories() > MAX_CATEGORIES)
        .map(|legend| {
            let n = legend.categories();
            let distinct = {
                let mut colors: Vec<_> = legend.entries.iter().map(|e| e.1).collect();
                colors.sort_by_key(|c| (c.r, c.g, c.b));
                colors.dedup();
                colors.len()
            };
            let repeats = if distinct < legend.entries.len() {
                format!(" (the {} shown use only {distinct} distinct colours)", legend.entries.len())
            } else {
                String::new()
            };
            Issue::new(
                legend.element(),
                key.clone(),
                format!(
                    "{n} colour categories, more than {MAX_CATEGORIES}{repeats}: readers cannot tell that many hues \
                     apart or match them to the legend"
                ),
                "group the smallest categories into \"other\", split the chart into small multiples, or label \
                 the marks directly",
            )
        })
        .collect()
}
