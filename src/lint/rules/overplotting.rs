//! CM002 `overplotting`: when most point marks cover one another the reader cannot see how many
//! rows there are where; transparency or a density view restores the comparison. Transparency
//! alone runs out: where enough translucent marks stack, the ink saturates and a hundred rows
//! look like ten thousand, which only a density view shows.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{Point, Role, Shape};

/// The rule.
pub static RULE: Rule = Rule {
    code: "CM002",
    name: "overplotting",
    category: Category::Comparison,
    severity: Severity::Warning,
    summary: "More than half of the point marks overlap another while drawn at opacity above 0.5, or lie where stacked marks saturate the ink.",
    check,
};

/// Share of overlapping marks above which the rule fires.
const MAX_SHARE: f64 = 0.5;
/// Marks at least this transparent (alpha at most) show overlaps as darker ink, which is fine:
/// two overlapping marks at 0.5 read as 0.75, clearly darker than one.
const SEE_THROUGH_ALPHA: f64 = 0.5;
/// Charts with fewer point marks than this are not checked.
const MIN_MARKS: usize = 50;
/// Opacity of stacked marks at which the ink is saturated: more rows there change it by at most
/// 2% of the way to full ink.
const SATURATED: f64 = 0.98;
/// Share of the marks lying where the ink is saturated above which the rule fires.
const MAX_SATURATED_SHARE: f64 = 0.5;

/// How many marks at opacity `alpha` stack to at least [`SATURATED`] opacity:
/// the least `k` with `1 − (1 − alpha)^k ≥ SATURATED` (at least 2: one mark alone says nothing
/// about density).
pub fn saturating_stack(alpha: f64) -> usize {
    if !(alpha < 1.0) {
        return 2;
    }
    if !(alpha > 0.0) {
        return usize::MAX;
    }
    let k = ((1.0 - SATURATED).ln() / (1.0 - alpha).ln()).ceil();
    // Guard the rounding of the logarithms: the stack of k marks must reach the level.
    let k = if 1.0 - (1.0 - alpha).powf(k - 1.0) >= SATURATED { k - 1.0 } else { k };
    (k.min(1e9) as usize).max(2)
}

/// The share of marks whose centres lie in a cell holding at least `stack` centres, the cells
/// squares of area `π·radius²` (a mark's area, so a cell's count is about how many marks cover
/// its middle), counted on a dense grid over the centres' bounding box (non-finite centres are
/// left out).
pub fn saturated_share(centers: &[Point], radius: f64, stack: usize) -> f64 {
    let finite = || centers.iter().filter(|p| p.x.is_finite() && p.y.is_finite());
    // One pass for the count and the bounding box.
    let (n, x0, y0, x1, y1) = finite().fold(
        (0usize, f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
        |(n, x0, y0, x1, y1), p| (n + 1, x0.min(p.x), y0.min(p.y), x1.max(p.x), y1.max(p.y)),
    );
    if n < stack || !(radius > 0.0) {
        return 0.0;
    }
    let side = radius * std::f64::consts::PI.sqrt();
    // Truncation floors what is not negative; the grid is at most a few million cells.
    let (nx, ny) = (((x1 - x0) / side) as usize + 1, ((y1 - y0) / side) as usize + 1);
    if nx.saturating_mul(ny) > 1 << 24 {
        return 0.0;
    }
    let mut counts = vec![0u32; nx * ny];
    for p in finite() {
        counts[((p.y - y0) / side) as usize * nx + ((p.x - x0) / side) as usize] += 1;
    }
    let stacked = counts.iter().filter(|&&c| c as usize >= stack).map(|&c| c as usize).sum::<usize>();
    stacked as f64 / n as f64
}

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
    // Every translucent point batch too: (marks, marks where the ink saturates, opacity, stack).
    let (mut all, mut saturated, mut faint, mut stack) = (0usize, 0.0f64, 1.0f64, 0usize);
    s.output.scene.walk(|item| {
        let Shape::Points(batch) = &item.shape else { return };
        let a = batch.fill.at(0).map_or(1.0, |c| c.alpha());
        if item.role != Role::DataMark || batch.centers.len() < 2 {
            return;
        }
        let radius = batch.radius.at(0).unwrap_or(0.0);
        if a <= SEE_THROUGH_ALPHA + 1.0 / 255.0 {
            // Read in place: a faint batch may hold a hundred million points.
            let k = saturating_stack(a);
            all += batch.centers.len();
            saturated += saturated_share(&batch.centers, radius, k) * batch.centers.len() as f64;
            faint = faint.min(a);
            stack = stack.max(k);
            return;
        }
        let centers: Vec<(f64, f64)> = batch.centers.iter().map(|p| (p.x, p.y)).collect();
        let share = overlap_share(&centers, radius);
        marks += centers.len();
        overlapping += share * centers.len() as f64;
        alpha = alpha.max(a);
    });
    let density = "use a density view: `mode = \"density\"` (scatter and splom) counts the rows in bins and shades each by its count";
    if marks >= MIN_MARKS && overlapping / (marks as f64) > MAX_SHARE {
        return vec![Issue::new(
            "points",
            "opacity",
            format!(
                "{:.0}% of {marks} points overlap another at opacity {alpha:.2}, hiding how many rows lie where",
                100.0 * overlapping / marks as f64
            ),
            format!("lower `opacity` (to 0.5 or less), shrink `radius`, or {density}"),
        )];
    }
    if all >= MIN_MARKS && saturated / (all as f64) > MAX_SATURATED_SHARE {
        return vec![Issue::new(
            "points",
            "opacity",
            format!(
                "{:.0}% of {all} points lie where {stack} or more marks at opacity {faint:.2} stack: the ink saturates \
                 there, so a hundred rows look like ten thousand",
                100.0 * saturated / all as f64
            ),
            format!("{density}; lowering `opacity` only moves the point where it saturates"),
        )];
    }
    Vec::new()
}

#[cfg(test)]
mod tests {
    use super::{SATURATED, overlap_share, saturated_share, saturating_stack};
    use crate::scene::Point;

    #[test]
    fn a_saturating_stack_is_the_fewest_marks_reaching_the_level() {
        // 1 − 0.8^k ≥ 0.98 ⇔ k ≥ ln 0.02 / ln 0.8 = 17.53: 18 marks at 0.2.
        assert_eq!(saturating_stack(0.2), 18);
        assert_eq!(saturating_stack(0.5), 6, "1 − 0.5^6 = 0.984; 0.5^5 leaves 0.969");
        assert_eq!(saturating_stack(1.0), 2);
        assert_eq!(saturating_stack(0.0), usize::MAX);
        for a in [0.01, 0.05, 0.1, 0.3, 0.45] {
            let k = saturating_stack(a) as f64;
            assert!(1.0 - (1.0 - a).powf(k) >= SATURATED && 1.0 - (1.0 - a).powf(k - 1.0) < SATURATED, "{a}");
        }
    }

    #[test]
    fn saturated_share_counts_marks_in_cells_with_a_full_stack() {
        // Cells of side 2·√π ≈ 3.54 for radius 2: 30 marks on one spot, 10 on another, 60
        // spread 10 apart. With stacks of 18, only the 30 count.
        let mut c = vec![Point::new(0.5, 0.5); 30];
        c.extend(vec![Point::new(100.2, 50.3); 10]);
        c.extend((0..60).map(|i| Point::new(200.0 + 10.0 * (i % 10) as f64, 10.0 * (i / 10) as f64)));
        assert!((saturated_share(&c, 2.0, 18) - 0.3).abs() < 1e-12);
        assert!((saturated_share(&c, 2.0, 10) - 0.4).abs() < 1e-12);
        assert_eq!(saturated_share(&c, 2.0, 31), 0.0);
        // Non-finite centres are left out.
        c.push(Point::new(f64::NAN, 1.0));
        assert!((saturated_share(&c, 2.0, 18) - 0.3).abs() < 1e-12);
    }

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
