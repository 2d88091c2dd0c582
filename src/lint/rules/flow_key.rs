//! TQ004 `flow-without-key`: a flow chart whose speed the reader cannot read.
//!
//! Streamlines, particle traces and line integral convolution show only the direction of the
//! flow. Its speed needs a speed image with a colour bar, or arrows whose lengths a key arrow
//! calibrates. The rule fires when
//! - arrows are drawn (`arrows` layer, any arrow of non-zero speed) but the scene has no key
//!   arrow (a filled legend path), or
//! - lines or textures are drawn (`streamlines`, `pathlines`, `streaklines`, `lic`) and the
//!   scene shows speed nowhere: no colour bar (a legend ramp image) and no key arrow.
//!
//! `timelines` count as showing speed: particles released together and drawn at equal time
//! steps are spaced by how fast they move. `topology` alone is not judged here: it shows the
//! field's structure, not its speed.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::DerivedColumn;
use crate::mark::vector::flow::FlowLayer;
use crate::scene::{Role, Shape};
use crate::spec::ChartKind;

/// The rule.
pub static RULE: Rule = Rule {
    code: "TQ004",
    name: "flow-without-key",
    category: Category::Technique,
    severity: Severity::Warning,
    summary: "A flow chart draws arrows without a key arrow, or draws lines or LIC with its speed shown nowhere.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let ChartKind::Flow(options) = &s.chart.kind else { return Vec::new() };
    let layers = options.layers.clone().unwrap_or_else(|| vec![FlowLayer::Speed, FlowLayer::Streamlines]);
    let (mut colour_bar, mut key_arrow) = (false, false);
    s.output.scene.walk(|item| {
        if item.role == Role::Legend {
            colour_bar |= matches!(item.shape, Shape::Image(_));
            key_arrow |= matches!(item.shape, Shape::Path(_)) && item.style.fill.is_some();
        }
    });
    if layers.contains(&FlowLayer::Arrows) && !key_arrow && moving_arrows(s) {
        return vec![Issue::new(
            "arrow key",
            "layers",
            "arrows are drawn with lengths proportional to speed, but no key arrow says what length means what speed",
            "draw the arrows with their key (the `arrows` layer adds one in the plot's top-right corner), or add \
             `speed` to `layers` for a colour bar",
        )];
    }
    let direction_only: Vec<&str> = [
        (FlowLayer::Streamlines, "streamlines"),
        (FlowLayer::Pathlines, "pathlines"),
        (FlowLayer::Streaklines, "streaklines"),
        (FlowLayer::Lic, "lic"),
    ]
    .iter()
    .filter(|(l, _)| layers.contains(l))
    .map(|(_, name)| *name)
    .collect();
    if direction_only.is_empty() || colour_bar || key_arrow || layers.contains(&FlowLayer::Timelines) {
        return Vec::new();
    }
    vec![Issue::new(
        "speed",
        "layers",
        format!(
            "the flow's speed is shown nowhere: {} show its direction only, with no speed colour bar and no arrows",
            direction_only.join(", ")
        ),
        "add `speed` (a colour image with a colour bar) or `arrows` (with a key arrow) to `layers`",
    )]
}

/// Whether the derived table holds an arrow of non-zero speed.
fn moving_arrows(s: &Subject<'_>) -> bool {
    let column = |name: &str| s.output.derived.column(name);
    let (Some(DerivedColumn::Text(element)), Some(DerivedColumn::Number(speed))) = (column("element"), column("param"))
    else {
        return false;
    };
    element.iter().zip(speed).any(|(e, v)| e == "arrow" && *v > 0.0)
}
