//! CM002 `overplotting`: when most point marks cover one another the reader cannot see how many
//! rows there are where; transparency or a density view restores the comparison.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{Role, Shape};

/// The rule.
pub static RULE: Rule = Rule {
    code: "CM002",
    name: "overplotting",
    category: Category::Comparison,
    severity: Severity::Warning,
    summary: "More than half of the point marks overlap another while drawn at opacity above 0.5.",
    check,
};

/// Share of overlapping marks above which the rule fires.
const MAX_SHARE: f64 = 0.5;
/// Marks at least this transparent (alpha at most) show overlaps as darker ink, which is fine:
/// two overlapping marks at 0.5 read as 0.75, clearly darker than one.
const SEE_THROUGH_ALPHA: f64 = 0.5;
/// Charts with fewer point marks than this are not checked.
const MIN_MARKS: usize = 50;

/// The share of marks whose centres lie closer than one radius to another mark's centre (their
/// disks overlap by more than a third of their area), counted on a grid of radius-sized cells.
pub fn overlap_share(centers: &[(f64, f64)], radius: f64) -> f64 {
    if centers.len() < 2 || radius <= 0.0 {
        return 0.0;
    }
    let cell = radius;
    let key = |x: f64, y: f64| ((x / cell).floor() as i64, (y / cell).floor() as i64);
    let mut grid: std::collections::HashMap<(i64, i64), Vec<usize>> = std::collections::HashMap::new();
    for (i, &(x, y)) in centers.iter().enumerate() {
        grid.entry(key(x, y)).or_default().push(i);
    }
    let mut overlapping = 0usize;
    for (i, &(x, y)) in centers.iter().enumerate() {
        let (cx, cy) = key(x, y);
        let hit = (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                grid.get(&(cx + dx, cy + dy)).is_some_and(|cands| {
                    cands.iter().any(|&j| j != i && centers.get(j).is_some_and(|&(a, b)| (a - x).hypot(b - y) < radius))
                })
            })
        });
        overlapping += hit as usize;
    }
    overlapping as f64 / centers.len() as f64
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    // Every opaque point batch of the chart; small multiples (splom cells) add up.
    let (mut marks, mut overlapping, mut alpha) = (0usize, 0.0f64, 0.0f64);
    s.output.scene.walk(|item| {
        let Shape::Points(batch) = &item.shape else { return };
        let a = batch.fill.at(0).map_or(1.0, |c| c.alpha());
        if item.role != Role::DataMark || a <= SEE_THROUGH_ALPHA + 1.0 / 255.0 || batch.centers.len() < 2 {
            return;
        }
        let centers: Vec<(f64, f64)> = batch.centers.iter().map(|p| (p.x, p.y)).collect();
        let share = overlap_share(&centers, batch.radius.at(0).unwrap_or(0.0));
        marks += centers.len();
        overlapping += share * centers.len() as f64;
        alpha = alpha.max(a);
    });
    if marks < MIN_MARKS || overlapping / (marks as f64) <= MAX_SHARE {
        return Vec::new();
    }
    vec![Issue::new(
        "points",
        "opacity",
        format!(
            "{:.0}% of {marks} points overlap another at opacity {alpha:.2}, hiding how many rows lie where",
            100.0 * overlapping / marks as f64
        ),
        "lower `opacity` (to 0.5 or less), shrink `radius`, or use a density view (splom `mode = \"density\"`)",
    )]
}

#[cfg(test)]
mod tests {
    use super::overlap_share;

    #[test]
    fn share_counts_marks_with_a_neighbour_within_one_radius() {
        // Two touching pairs and one loner: 4 of 5 overlap.
        let c = [(0.0, 0.0), (1.0, 0.0), (10.0, 10.0), (10.5, 10.0), (50.0, 50.0)];
        assert!((overlap_share(&c, 2.0) - 0.8).abs() < 1e-12);
        // Spread far apart: none.
        let far: Vec<(f64, f64)> = (0..10).map(|i| (i as f64 * 10.0, 0.0)).collect();
        assert_eq!(overlap_share(&far, 2.0), 0.0);
    }
}
