//! LB005 `low-contrast-text`: text must stand out from what is painted under it (WCAG 2:
//! 4.5:1 for normal text, 3:1 for large text).

use crate::guide::color::contrast_ratio;
use crate::lint::geometry::{colour_under, texts};
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::spec::validate::shorten;

/// Text at least this large (CSS pixels, 18 pt) needs only the large-text ratio.
const LARGE_TEXT_PX: f64 = 24.0;
/// WCAG AA ratio for normal text.
const NORMAL_RATIO: f64 = 4.5;
/// WCAG AA ratio for large text.
const LARGE_RATIO: f64 = 3.0;

/// The rule.
pub static RULE: Rule = Rule {
    code: "LB005",
    name: "low-contrast-text",
    category: Category::Labelling,
    severity: Severity::Warning,
    summary: "Text contrasts with its background less than WCAG's 4.5:1 (3:1 for large text).",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let scene = &s.output.scene;
    let placed = texts(scene);
    let mut low = Vec::new();
    for t in &placed {
        let (cx, cy) = (t.bounds.x + t.bounds.w / 2.0, t.bounds.y + t.bounds.h / 2.0);
        let under = colour_under(scene, cx, cy, t.item);
        let fg = crate::lint::geometry::blend(t.text.color, under);
        let ratio = contrast_ratio(fg, under);
        let needed = if t.text.size >= LARGE_TEXT_PX { LARGE_RATIO } else { NORMAL_RATIO };
        if ratio < needed {
            low.push((t, ratio, needed, under));
        }
    }
    low.iter()
        .take(5)
        .map(|(t, ratio, needed, under)| {
            Issue::new(
                t.element(),
                "",
                format!(
                    "\"{}\" ({} on {}) has a contrast of {ratio:.2}:1, below {needed}:1",
                    shorten(&t.text.content),
                    t.text.color.hex(),
                    under.hex()
                ),
                "use a darker or lighter colour scheme so labels stand out from the fill under them",
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::lint::test_support::issues;
    use crate::scene::{Anchor, Baseline, Color, Item, Point, Rect, Role, Scene, Shape, Style, Text};

    /// A 200 × 100 scene: a `fill` rectangle under a text of colour `ink`.
    fn scene(fill: Color, ink: Color) -> Scene {
        let text = Text {
            at: Point::new(50.0, 50.0),
            content: "label".into(),
            size: 12.0,
            anchor: Anchor::Middle,
            baseline: Baseline::Middle,
            angle: 0.0,
            color: ink,
        };
        Scene {
            width: 200.0,
            height: 100.0,
            background: Color::WHITE,
            title: None,
            items: vec![
                Item::new(Role::DataMark, Shape::Rect(Rect::new(0.0, 0.0, 100.0, 100.0)), Style::fill(fill)),
                Item::text(Role::Annotation, text),
            ],
        }
    }

    #[test]
    fn grey_on_dark_blue_is_reported_with_its_ratio() {
        // #777777 on #1f3a5f: luminances 0.184 and 0.0414, ratio 0.234 / 0.0914 ≈ 2.56.
        let found = issues(super::check, scene(Color::rgb(0x1f, 0x3a, 0x5f), Color::rgb(0x77, 0x77, 0x77)));
        assert_eq!(found.len(), 1);
        assert!(found[0].message.contains("2.56:1"), "{}", found[0].message);
        assert!(found[0].message.contains("#1f3a5f"), "{}", found[0].message);
    }

    #[test]
    fn white_on_dark_blue_and_text_on_the_bare_canvas_pass() {
        assert!(issues(super::check, scene(Color::rgb(0x1f, 0x3a, 0x5f), Color::WHITE)).is_empty());
        // #767676 on white is 4.54:1, just above AA.
        let mut s = scene(Color::WHITE, Color::rgb(0x76, 0x76, 0x76));
        s.items.remove(0);
        assert!(issues(super::check, s).is_empty());
    }

    #[test]
    fn a_halo_under_the_label_counts() {
        // Dark text on a dark fill, but a white rectangle (a halo) under the text.
        let mut s = scene(Color::rgb(0x1f, 0x3a, 0x5f), Color::rgb(0x22, 0x22, 0x22));
        s.items.insert(
            1,
            Item::new(Role::Annotation, Shape::Rect(Rect::new(30.0, 40.0, 40.0, 20.0)), Style::fill(Color::WHITE)),
        );
        assert!(issues(super::check, s).is_empty());
    }
}
