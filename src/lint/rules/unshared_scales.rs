//! CM001 `unshared-scales`: small multiples invite comparison across panels, which only works
//! when every panel uses the same scale; otherwise equal heights can mean very different values.
//!
//! The rule reads each panel's value axis from the scene (an axis line labelled `y axis` and the
//! tick labels beside it) and compares the panels' tick labels. It applies to `section` charts
//! with `layout = "multiples"`, whose panels all show the same field (`shared_scale = false` gives
//! each its own scale). The other small-multiple kinds share by construction: a scatter-plot
//! matrix uses one scale per column in every row and column of cells, and a hyperslice's panels
//! are slices of one grid under one colour scale. Faceted charts (`facet = ...`) share their
//! scales unless `resolve` makes one independent; their labelled panels are compared on x and y.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::grid::section::SectionLayout;
use crate::scene::{PathCmd, Role, Scene, Shape};
use crate::spec::ChartKind;

/// The rule.
pub static RULE: Rule = Rule {
    code: "CM001",
    name: "unshared-scales",
    category: Category::Comparison,
    severity: Severity::Warning,
    summary: "Small multiples whose panels do not share one value scale, so they cannot be compared by eye.",
    check,
};

/// The y-axis tick labels of each panel of a scene, top panel first: one list per axis line
/// labelled `y axis`, holding the labels beside it (left of it, within its vertical extent).
pub fn panel_tick_labels(scene: &Scene) -> Vec<Vec<String>> {
    axis_tick_labels(scene, "y axis")
}

/// The tick labels of each axis line labelled `axis` (`"x axis"` or `"y axis"`), in the order
/// of the lines (top to bottom, then left to right): the labels left of a y axis within its
/// vertical extent, or below an x axis within its horizontal extent.
pub fn axis_tick_labels(scene: &Scene, axis: &str) -> Vec<Vec<String>> {
    let vertical = axis == "y axis";
    // An axis line as (position across it, start, end along it).
    let mut axes: Vec<(f64, f64, f64)> = Vec::new();
    let mut labels: Vec<(f64, f64, String)> = Vec::new();
    scene.walk(|item| {
        if item.label.as_deref() != Some(axis) {
            return;
        }
        match (&item.role, &item.shape) {
            (Role::Axis, Shape::Path(cmds)) => {
                if let (Some(PathCmd::MoveTo(a)), Some(PathCmd::LineTo(b))) = (cmds.first(), cmds.get(1)) {
                    axes.push(if vertical {
                        (a.x, a.y.min(b.y), a.y.max(b.y))
                    } else {
                        (a.y, a.x.min(b.x), a.x.max(b.x))
                    });
                }
            }
            (Role::TickLabel, Shape::Text(t)) if !t.content.trim().is_empty() => {
                labels.push(if vertical {
                    (t.at.x, t.at.y, t.content.clone())
                } else {
                    (t.at.y, t.at.x, t.content.clone())
                });
            }
            _ => {}
        }
    });
    axes.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)));
    axes.iter()
        .map(|&(across, start, end)| {
            labels
                .iter()
                .filter(|(l_across, l_along, _)| {
                    let beside =
                        if vertical { *l_across <= across } else { *l_across >= across && *l_across <= across + 40.0 };
                    beside && *l_along >= start - 1.0 && *l_along <= end + 1.0
                })
                .map(|(_, _, text)| text.clone())
                .collect()
        })
        .collect()
}

/// CM001 for a faceted chart: the panels that label an axis should label it alike.
fn check_facets(s: &Subject<'_>) -> Vec<Issue> {
    let mut issues = Vec::new();
    for (axis, key) in [("x axis", "x"), ("y axis", "y")] {
        let panels: Vec<Vec<String>> =
            axis_tick_labels(&s.output.scene, axis).into_iter().filter(|p| !p.is_empty()).collect();
        let Some(first) = panels.first() else { continue };
        let differing = panels.iter().filter(|p| *p != first).count();
        if differing == 0 {
            continue;
        }
        issues.push(Issue::new(
            axis,
            "facet.resolve",
            format!(
                "the facet panels do not share their {key} scale ({differing} of {} labelled panels differ from the \
                 first), so equal positions in different panels mean different values",
                panels.len()
            ),
            format!(
                "remove `resolve.{key} = \"independent\"` so every panel uses one scale; if the panels' ranges differ \
                 too much for that, say in the title that each panel has its own {key} scale"
            ),
        ));
    }
    issues
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    if s.chart.facet.is_some() {
        return check_facets(s);
    }
    let ChartKind::Section(options) = &s.chart.kind else { return Vec::new() };
    if options.layout != Some(SectionLayout::Multiples) {
        return Vec::new();
    }
    let panels = panel_tick_labels(&s.output.scene);
    let Some(first) = panels.first() else { return Vec::new() };
    let differing = panels.iter().filter(|p| *p != first).count();
    if differing == 0 {
        return Vec::new();
    }
    let range = |p: &Vec<String>| match (p.first(), p.last()) {
        (Some(a), Some(b)) => format!("{a} to {b}"),
        _ => "no labels".to_string(),
    };
    let mut shown: Vec<String> = Vec::new();
    for (i, p) in panels.iter().enumerate() {
        let r = format!("panel {}: {}", i + 1, range(p));
        if shown.len() < 3 && !shown.iter().any(|s| s.ends_with(&range(p))) {
            shown.push(r);
        }
    }
    let key = if options.shared_scale == Some(false) { "shared_scale" } else { "layout" };
    vec![Issue::new(
        "panels",
        key,
        format!(
            "the {} panels do not share their value scale ({differing} differ{} from the first; {}), so equal \
             heights in different panels mean different values",
            panels.len(),
            if differing == 1 { "s" } else { "" },
            shown.join(", ")
        ),
        "remove `shared_scale = false` so every panel uses one scale; if the sections differ too much in size for \
         that, overlay them (`layout = \"overlay\"`) or say in the title that each panel has its own scale",
    )]
}
