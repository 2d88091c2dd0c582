//! TQ001 `tiny-treemap-leaves`: a treemap whose leaves are too small to see or label.
//!
//! A leaf counts as tiny when its rectangle is under [`MIN_SIDE`] px on its short side or under
//! [`MIN_AREA`] px² in area. Why these sizes: the tiling leaves 2 px of padding between siblings
//! by default, so a leaf thinner than that is no wider than the gaps around it and reads as part
//! of a border rather than as a rectangle; and a leaf under 3 × 3 px shows too few pixels for
//! its colour to be told apart from its neighbours' after anti-aliasing (let alone carry a label,
//! which needs a 7 px font). A few such leaves are the normal long tail of a hierarchy; when more
//! than [`MAX_SHARE`] of the drawn leaves are tiny, much of the data is not really shown.
//!
//! The rule reads the treemap's derived table (every drawn node with its rectangle in canvas
//! pixels): the drawn leaves are the nodes with a positive value that are nobody's parent there.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::{Derived, DerivedColumn};
use crate::spec::ChartKind;

/// Leaves thinner than this (in CSS px) on their short side are too small to see.
pub const MIN_SIDE: f64 = 2.0;
/// Leaves smaller than this area (in CSS px²) are too small to see.
pub const MIN_AREA: f64 = 9.0;
/// The rule fires when more than this share of the drawn leaves is tiny.
pub const MAX_SHARE: f64 = 0.10;

/// The rule.
pub static RULE: Rule = Rule {
    code: "TQ001",
    name: "tiny-treemap-leaves",
    category: Category::Technique,
    severity: Severity::Warning,
    summary: "More than 10% of a treemap's leaves are under 2 px on a side or 9 px² in area, too small to see or label.",
    check,
};

/// A numeric column of a derived table.
fn numbers<'d>(d: &'d Derived, name: &str) -> Option<&'d [f64]> {
    d.columns.iter().find(|(n, _)| n == name).and_then(|(_, c)| match c {
        DerivedColumn::Number(v) => Some(v.as_slice()),
        _ => None,
    })
}

/// A text column of a derived table.
fn texts<'d>(d: &'d Derived, name: &str) -> Option<&'d [String]> {
    d.columns.iter().find(|(n, _)| n == name).and_then(|(_, c)| match c {
        DerivedColumn::Text(v) => Some(v.as_slice()),
        _ => None,
    })
}

/// `(tiny, drawn)` leaf counts of a treemap's derived table.
pub fn tiny_leaves(d: &Derived) -> Option<(usize, usize)> {
    let (ids, parents) = (texts(d, "id")?, texts(d, "parent")?);
    let (values, depth) = (numbers(d, "value")?, numbers(d, "depth")?);
    let (x0, y0, x1, y1) = (numbers(d, "x0")?, numbers(d, "y0")?, numbers(d, "x1")?, numbers(d, "y1")?);
    let parents_set: std::collections::HashSet<&str> =
        parents.iter().map(String::as_str).filter(|p| !p.is_empty()).collect();
    let (mut tiny, mut drawn) = (0, 0);
    for (i, id) in ids.iter().enumerate() {
        let at = |v: &[f64]| v.get(i).copied().unwrap_or(f64::NAN);
        let is_leaf = !parents_set.contains(id.as_str()) && at(depth) > 0.0;
        let value = at(values);
        if !is_leaf || value.is_nan() || value <= 0.0 {
            continue;
        }
        drawn += 1;
        let (w, h) = ((at(x1) - at(x0)).max(0.0), (at(y1) - at(y0)).max(0.0));
        // A missing rectangle (NaN edges) becomes 0 × 0: tiny.
        let visible = w.min(h) >= MIN_SIDE && w * h >= MIN_AREA;
        if !visible {
            tiny += 1;
        }
    }
    Some((tiny, drawn))
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    if !matches!(s.chart.kind, ChartKind::Treemap(_)) {
        return Vec::new();
    }
    let Some((tiny, drawn)) = tiny_leaves(&s.output.derived) else { return Vec::new() };
    let share = tiny as f64 / drawn.max(1) as f64;
    if drawn == 0 || share <= MAX_SHARE {
        return Vec::new();
    }
    vec![Issue::new(
        "leaves",
        "size",
        format!(
            "{tiny} of {drawn} leaves ({:.0}%) are under {MIN_SIDE} px on their short side or {MIN_AREA} px² in area, \
             too small to see or label (at most {:.0}% is expected)",
            share * 100.0,
            MAX_SHARE * 100.0
        ),
        "make the canvas larger (`size`), draw fewer levels (`depth`), or aggregate the smallest leaves into an \
         \"other\" node",
    )]
}
