//! LB003 `text-clipped`: text that runs off the canvas is cut in every output.

use crate::lint::geometry::texts;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::Rect;
use crate::spec::validate::shorten;

/// The rule.
pub static RULE: Rule = Rule {
    code: "LB003",
    name: "text-clipped",
    category: Category::Labelling,
    severity: Severity::Error,
    summary: "Text runs past the edge of the canvas and is cut off.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let scene = &s.output.scene;
    let canvas = Rect::new(0.0, 0.0, scene.width, scene.height);
    texts(scene)
        .into_iter()
        .filter(|t| !canvas.contains_rect(&t.bounds, 0.5))
        .take(5)
        .map(|t| {
            let b = t.bounds;
            let cut = [(-b.x), (b.right() - canvas.w), (-b.y), (b.bottom() - canvas.h)].into_iter().fold(0.0, f64::max);
            Issue::new(
                t.element(),
                "",
                format!(
                    "\"{}\" runs {cut:.0} px past the edge of the {}×{} canvas",
                    shorten(&t.text.content),
                    canvas.w,
                    canvas.h
                ),
                "make the chart larger (`size`) or the text shorter",
            )
        })
        .collect()
}
