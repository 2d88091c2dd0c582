//! TQ003 `contour-levels-unlabelled`: contour lines whose levels the reader cannot find out.
//!
//! A contour line says "the field equals this value here"; without the value the line is only a
//! shape. The value can come from an inline label on the line or from a colour bar (stepped for
//! filled bands, whose edges are the levels; continuous when the lines are coloured by level).
//! The rule fires for `contour` and `scattered` charts that draw contour lines (data-mark paths
//! labelled `z = …`) with no inline level label (an annotation text in the plot) and no colour
//! bar (a legend ramp image or stepped blocks).

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{Role, Shape};
use crate::spec::ChartKind;

/// The rule.
pub static RULE: Rule = Rule {
    code: "TQ003",
    name: "contour-levels-unlabelled",
    category: Category::Technique,
    severity: Severity::Warning,
    summary: "Contour lines carry no level labels and no colour bar tells their levels.",
    check,
};

/// What a scene shows of its contour lines: how many lines and levels are drawn, how many inline
/// labels, and whether a colour bar is drawn.
#[derive(Debug, Default, PartialEq)]
pub struct ContourKey {
    /// Contour lines drawn.
    pub lines: usize,
    /// Distinct levels among them.
    pub levels: usize,
    /// Inline text labels in the plot.
    pub labels: usize,
    /// Whether a continuous or stepped colour bar is drawn.
    pub colour_bar: bool,
}

/// Read the contour lines, their labels and the colour bar from a scene.
pub fn contour_key(scene: &crate::scene::Scene) -> ContourKey {
    let mut key = ContourKey::default();
    let mut levels: Vec<&str> = Vec::new();
    let mut steps = 0;
    scene.walk(|item| match (&item.role, &item.shape) {
        (Role::DataMark, Shape::Path(_)) => {
            if let Some(level) = item.label.as_deref().and_then(|l| l.strip_prefix("z = ")) {
                key.lines += 1;
                if !levels.contains(&level) {
                    levels.push(level);
                }
            }
        }
        (Role::Annotation, Shape::Text(t)) if !t.content.trim().is_empty() && !crate::mark::annotate::is_note(item) => {
            key.labels += 1
        }
        (Role::Legend, Shape::Image(_)) => key.colour_bar = true,
        (Role::Legend, Shape::Rect(_)) if item.style.fill.is_some() => steps += 1,
        _ => {}
    });
    key.levels = levels.len();
    key.colour_bar |= steps >= 2;
    key
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let (key, hint) = match &s.chart.kind {
        ChartKind::Contour(_) => (
            "labels",
            "keep `labels = true` (the default) so each level is written on its line, or show the colour bar \
             (remove `legend = false` from `z`)",
        ),
        ChartKind::Scattered(_) => (
            "levels",
            "show the colour bar (remove `legend = false` from `z`), or draw fewer `levels` so their labels fit \
             on the lines",
        ),
        _ => return Vec::new(),
    };
    let found = contour_key(&s.output.scene);
    if found.lines == 0 || found.labels > 0 || found.colour_bar {
        return Vec::new();
    }
    vec![Issue::new(
        "contour lines",
        key,
        format!(
            "{} contour lines at {} levels carry no value labels and no colour bar tells their levels",
            found.lines, found.levels
        ),
        hint,
    )]
}
