//! LB004 `text-too-small`: text below a legible size at the output scale.

use crate::lint::geometry::texts;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::spec::validate::shorten;

/// Smallest legible text in CSS pixels (about 6.75 pt); SVG and 1× PNG show it at this size.
pub const MIN_TEXT_PX: f64 = crate::guide::theme::MIN_TEXT_SIZE;

/// The rule.
pub static RULE: Rule = Rule {
    code: "LB004",
    name: "text-too-small",
    category: Category::Labelling,
    severity: Severity::Warning,
    summary: "Text is drawn smaller than 9 CSS pixels and is hard to read.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let small: Vec<_> = texts(&s.output.scene).into_iter().filter(|t| t.text.size < MIN_TEXT_PX).collect();
    let Some(smallest) = small.iter().min_by(|a, b| a.text.size.total_cmp(&b.text.size)) else {
        return Vec::new();
    };
    vec![Issue::new(
        "text",
        if s.chart.font_size.is_some() { "font_size" } else { "" },
        format!(
            "{} text{} smaller than {MIN_TEXT_PX} px; the smallest is \"{}\" at {:.1} px",
            small.len(),
            if small.len() == 1 { " is" } else { "s are" },
            shorten(&smallest.text.content),
            smallest.text.size
        ),
        "raise `font_size` (12 is the default) or make the chart larger",
    )]
}
