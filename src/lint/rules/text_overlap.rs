//! LB002 `text-overlap`: two pieces of text whose glyph boxes overlap cannot both be read.

use crate::lint::geometry::{overlapping_pairs, texts};
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::spec::validate::shorten;

/// The rule.
pub static RULE: Rule = Rule {
    code: "LB002",
    name: "text-overlap",
    category: Category::Labelling,
    severity: Severity::Error,
    summary: "Two texts overlap (measured from their glyph boxes), so neither reads cleanly.",
    check,
};

/// At most this many overlaps are listed one by one; the rest are counted in one issue.
const LISTED: usize = 5;

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let all = texts(&s.output.scene);
    let pairs = overlapping_pairs(&all);
    let mut out: Vec<Issue> = pairs
        .iter()
        .take(LISTED)
        .map(|&(i, j)| {
            let (a, b) = (&all[i], &all[j]);
            Issue::new(
                a.element(),
                "",
                format!(
                    "the {} \"{}\" overlaps the {} \"{}\" at ({:.0}, {:.0})",
                    a.element(),
                    shorten(&a.text.content),
                    b.element(),
                    shorten(&b.text.content),
                    a.bounds.x.max(b.bounds.x),
                    a.bounds.y.max(b.bounds.y)
                ),
                "make the chart larger (`size`), the text smaller (`font_size`), or shorten the labels",
            )
        })
        .collect();
    if pairs.len() > LISTED {
        out.push(Issue::new(
            "text",
            "",
            format!("{} more pairs of overlapping texts", pairs.len() - LISTED),
            "make the chart larger (`size`) or the text smaller (`font_size`)",
        ));
    }
    out
}
