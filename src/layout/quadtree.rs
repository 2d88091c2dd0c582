//! A Barnes–Hut quadtree (Barnes and Hut, 1986) over weighted 2-D points, for
//! approximating sums of pairwise interactions (such as repulsion in a force-directed layout) in
//! O(n log n) instead of O(n²).
//!
//! The tree is built top-down: the bounding square of the points is split into four quadrants
//! until a cell holds at most [`LEAF_CAPACITY`] points or is [`MAX_DEPTH`] levels deep (so
//! coincident points end up together in one leaf instead of recursing forever). Every cell keeps
//! its total mass and centre of mass. A query from a point walks the tree and treats a
//! cell as one body at its centre of mass when `side < theta · distance` and the cell does not
//! contain the excluded point; otherwise it opens the cell, and in a leaf it visits the points one
//! by one.
//!
//! The build and every query visit cells and points in a fixed order, so results are
//! bit-identical from run to run. Points with a non-finite coordinate or a negative or
//! non-finite mass are left out of the tree.

/// Largest number of points a leaf holds before it is split (unless [`MAX_DEPTH`] is reached).
pub const LEAF_CAPACITY: usize = 8;

/// Deepest level of the tree; cells at this depth stay leaves whatever their size.
pub const MAX_DEPTH: u32 = 40;

const NONE: u32 = u32::MAX;

/// Enough for a depth-first walk: at most three pending siblings per level plus the root.
const STACK_SIZE: usize = 4 * (MAX_DEPTH as usize + 2);

/// What a query meets on its walk: a single point, or a far cell taken as one body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Body {
    /// A point visited on its own.
    Point {
        /// Its index in the input.
        index: usize,
        /// Its position.
        position: [f64; 2],
        /// Its mass.
        mass: f64,
    },
    /// A cell approximated by its total mass at its centre of mass.
    Cell {
        /// Centre of mass of the cell's points.
        centre: [f64; 2],
        /// Total mass of the cell's points.
        mass: f64,
    },
}

/// One square cell of the tree.
#[derive(Clone, Debug)]
struct Cell {
    /// Centre of mass of the points below.
    centre: [f64; 2],
    /// Total mass of the points below.
    mass: f64,
    /// Side of the square.
    side: f64,
    /// Range of the cell's points in the permuted point list.
    start: u32,
    end: u32,
    /// Child cells by quadrant, `NONE` when empty; all `NONE` for a leaf.
    children: [u32; 4],
}

/// A Barnes–Hut quadtree over a fixed set of points.
#[derive(Clone, Debug)]
pub struct QuadTree {
    cells: Vec<Cell>,
    /// Points in tree order.
    points: Vec<Item>,
    /// For each input index, its position in `points` (`NONE` when left out as non-finite).
    rank: Vec<u32>,
}

impl QuadTree {
    /// Builds the tree over `points`, each of mass 1. Points with a non-finite coordinate are
    /// left out; an empty or all-non-finite input gives an empty tree.
    pub fn new(points: &[[f64; 2]]) -> Self {
        Self::build(points, |_| 1.0)
    }

    /// Builds the tree over `points` with the given masses (missing masses count as 1). Points
    /// with a non-finite coordinate or a negative or non-finite mass are left out.
    pub fn with_masses(points: &[[f64; 2]], masses: &[f64]) -> Self {
        Self::build(points, |i| masses.get(i).copied().unwrap_or(1.0))
    }

    fn build(points: &[[f64; 2]], mass_of: impl Fn(usize) -> f64) -> Self {
        let mut items: Vec<Item> = points
            .iter()
            .enumerate()
            .map(|(i, p)| Item { index: i as u32, position: *p, mass: mass_of(i) })
            .filter(|it| it.position[0].is_finite() && it.position[1].is_finite())
            .filter(|it| it.mass.is_finite() && it.mass >= 0.0)
            .collect();
        let mut tree = QuadTree { cells: Vec::new(), points: Vec::new(), rank: vec![NONE; points.len()] };
        if items.is_empty() {
            return tree;
        }
        let (origin, side) = bounding_square(&items);
        let mut scratch = items.clone();
        tree.cells.reserve(items.len() / 2 + 1);
        tree.build_cell(&mut items, &mut scratch, 0, origin, side, 0);
        for (rank, item) in items.iter().enumerate() {
            if let Some(slot) = tree.rank.get_mut(item.index as usize) {
                *slot = rank as u32;
            }
        }
        tree.points = items;
        tree
    }

    /// Number of points in the tree.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the tree holds no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Total mass and centre of mass of all points, or `None` for an empty tree.
    pub fn centre_of_mass(&self) -> Option<(f64, [f64; 2])> {
        self.cells.first().map(|c| (c.mass, c.centre))
    }

    /// Walks the tree from `query` with opening parameter `theta` (0 visits every point; larger
    /// is coarser, 0.5–1 is usual). The point with input index `exclude` (if any) is skipped, and
    /// no cell containing it is approximated. Calls `f` with every [`Body`] met, in a fixed
    /// order.
    pub fn visit(&self, query: [f64; 2], exclude: Option<usize>, theta: f64, mut f: impl FnMut(Body)) {
        if self.cells.is_empty() {
            return;
        }
        let excluded_rank = exclude.and_then(|i| self.rank.get(i).copied()).unwrap_or(NONE);
        let theta2 = theta * theta;
        let mut stack = [0u32; STACK_SIZE];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let Some(c) = self.cells.get(stack[top] as usize) else { continue };
            let contains_excluded = c.start <= excluded_rank && excluded_rank < c.end;
            let dx = query[0] - c.centre[0];
            let dy = query[1] - c.centre[1];
            let d2 = dx * dx + dy * dy;
            if !contains_excluded && d2 > 0.0 && c.side * c.side < theta2 * d2 {
                f(Body::Cell { centre: c.centre, mass: c.mass });
                continue;
            }
            if c.children[0] == NONE && c.children[1] == NONE && c.children[2] == NONE && c.children[3] == NONE {
                let range = c.start as usize..c.end as usize;
                for (item, rank) in self.points.get(range.clone()).unwrap_or(&[]).iter().zip(range) {
                    if rank as u32 != excluded_rank {
                        f(Body::Point { index: item.index as usize, position: item.position, mass: item.mass });
                    }
                }
                continue;
            }
            for &child in c.children.iter().rev() {
                if child != NONE && top < STACK_SIZE {
                    stack[top] = child;
                    top += 1;
                }
            }
        }
    }

    /// Builds the cell over `items` (a slice of the point list starting at `offset`) and its
    /// subtree; returns the cell's index.
    fn build_cell(
        &mut self,
        items: &mut [Item],
        scratch: &mut [Item],
        offset: usize,
        origin: [f64; 2],
        side: f64,
        depth: u32,
    ) -> u32 {
        let index = self.cells.len() as u32;
        let end = offset + items.len();
        self.cells.push(Cell {
            centre: [0.0; 2],
            mass: 0.0,
            side,
            start: offset as u32,
            end: end as u32,
            children: [NONE; 4],
        });
        let (mass, centre) = if items.len() <= LEAF_CAPACITY || depth >= MAX_DEPTH {
            centre_of_mass(items)
        } else {
            let half = 0.5 * side;
            let mid = [origin[0] + half, origin[1] + half];
            let bounds = partition_quadrants(items, scratch, mid);
            let mut children = [NONE; 4];
            for q in 0..4 {
                let (lo, hi) = (bounds[q], bounds[q + 1]);
                if lo == hi {
                    continue;
                }
                let child_origin = [origin[0] + half * (q & 1) as f64, origin[1] + half * (q >> 1) as f64];
                let (Some(sub), Some(sub_scratch)) = (items.get_mut(lo..hi), scratch.get_mut(lo..hi)) else {
                    continue;
                };
                children[q] = self.build_cell(sub, sub_scratch, offset + lo, child_origin, half, depth + 1);
            }
            if let Some(c) = self.cells.get_mut(index as usize) {
                c.children = children;
            }
            let parts = children.iter().filter_map(|&c| self.cells.get(c as usize)).map(|c| (c.mass, c.centre));
            combine(parts)
        };
        if let Some(c) = self.cells.get_mut(index as usize) {
            c.mass = mass;
            c.centre = centre;
        }
        index
    }
}

/// One point as stored in the tree.
#[derive(Clone, Copy, Debug)]
struct Item {
    index: u32,
    position: [f64; 2],
    mass: f64,
}

/// Total mass and centre of mass of the items.
fn centre_of_mass(items: &[Item]) -> (f64, [f64; 2]) {
    combine(items.iter().map(|it| (it.mass, it.position)))
}

/// Total mass and mass-weighted centre of `(mass, centre)` parts; the plain mean of the
/// centres when the total mass is 0.
fn combine(parts: impl Iterator<Item = (f64, [f64; 2])>) -> (f64, [f64; 2]) {
    let (mut mass, mut weighted, mut count, mut plain) = (0.0f64, [0.0f64; 2], 0.0f64, [0.0f64; 2]);
    for (m, c) in parts {
        mass += m;
        weighted = [weighted[0] + m * c[0], weighted[1] + m * c[1]];
        count += 1.0;
        plain = [plain[0] + c[0], plain[1] + c[1]];
    }
    if mass > 0.0 {
        (mass, [weighted[0] / mass, weighted[1] / mass])
    } else {
        let k = count.max(1.0);
        (0.0, [plain[0] / k, plain[1] / k])
    }
}

/// Smallest axis-aligned square holding all points: its lower-left corner and side (at least a
/// tiny positive value, so a cloud of coincident points still has a cell).
fn bounding_square(items: &[Item]) -> ([f64; 2], f64) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for Item { position: p, .. } in items {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let side = if side > 0.0 { side * (1.0 + 1e-12) } else { 1.0 };
    (lo, side)
}

/// Stable in-place partition of `items` by quadrant around `mid` (quadrant = `(x ≥ mid.x) +
/// 2·(y ≥ mid.y)`); returns the five bounds of the four quadrant ranges.
fn partition_quadrants(items: &mut [Item], scratch: &mut [Item], mid: [f64; 2]) -> [usize; 5] {
    let quadrant = |p: &[f64; 2]| usize::from(p[0] >= mid[0]) + 2 * usize::from(p[1] >= mid[1]);
    let mut counts = [0usize; 4];
    for item in items.iter() {
        counts[quadrant(&item.position)] += 1;
    }
    let mut bounds = [0usize; 5];
    for q in 0..4 {
        bounds[q + 1] = bounds[q] + counts[q];
    }
    let mut next = [bounds[0], bounds[1], bounds[2], bounds[3]];
    for item in items.iter() {
        let q = quadrant(&item.position);
        if let Some(slot) = scratch.get_mut(next[q]) {
            *slot = *item;
        }
        next[q] += 1;
    }
    items.copy_from_slice(scratch);
    bounds
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sum of 1/d over all points but `i`, exact or through the tree.
    fn potential(tree: &QuadTree, points: &[[f64; 2]], i: usize, theta: f64) -> f64 {
        let q = points[i];
        let mut sum = 0.0;
        tree.visit(q, Some(i), theta, |b| {
            let (p, m) = match b {
                Body::Point { position, mass, .. } => (position, mass),
                Body::Cell { centre, mass } => (centre, mass),
            };
            sum += m / ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
        });
        sum
    }

    fn pseudo_random_points(n: usize) -> Vec<[f64; 2]> {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n).map(|_| [next() * 10.0, next() * 3.0]).collect()
    }

    #[test]
    fn theta_zero_visits_every_other_point_once() {
        let points = pseudo_random_points(500);
        let tree = QuadTree::new(&points);
        assert_eq!(tree.len(), 500);
        let mut seen = vec![0u32; 500];
        let mut cells = 0;
        tree.visit(points[17], Some(17), 0.0, |b| match b {
            Body::Point { index, position, .. } => {
                seen[index] += 1;
                assert_eq!(position, points[index]);
            }
            Body::Cell { .. } => cells += 1,
        });
        assert_eq!(cells, 0);
        assert_eq!(seen[17], 0);
        assert!(seen.iter().enumerate().all(|(j, &k)| j == 17 || k == 1));
    }

    #[test]
    fn approximation_is_close_to_exact_sum_and_mass_is_conserved() {
        let points = pseudo_random_points(2000);
        let tree = QuadTree::new(&points);
        let (mass, centre) = tree.centre_of_mass().expect("non-empty");
        assert_eq!(mass, 2000.0);
        let exact_centre = points.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0] / 2000.0, a[1] + p[1] / 2000.0]);
        assert!((centre[0] - exact_centre[0]).abs() < 1e-9 && (centre[1] - exact_centre[1]).abs() < 1e-9);
        for i in [0, 999, 1999] {
            let exact = potential(&tree, &points, i, 0.0);
            let fine = potential(&tree, &points, i, 0.5);
            let coarse = potential(&tree, &points, i, 0.9);
            assert!(((fine - exact) / exact).abs() < 0.01, "{fine} vs {exact}");
            assert!(((coarse - exact) / exact).abs() < 0.03, "{coarse} vs {exact}");
            let mut visited_mass = 0.0;
            tree.visit(points[i], Some(i), 0.9, |b| match b {
                Body::Point { .. } => visited_mass += 1.0,
                Body::Cell { mass, .. } => visited_mass += mass,
            });
            assert_eq!(visited_mass, 1999.0);
        }
    }

    #[test]
    fn masses_weight_the_centre_and_bad_masses_are_left_out() {
        let points = [[0.0, 0.0], [2.0, 0.0], [9.0, 9.0], [5.0, 5.0]];
        let tree = QuadTree::with_masses(&points, &[1.0, 3.0, -1.0, f64::NAN]);
        assert_eq!(tree.len(), 2);
        assert_eq!(tree.centre_of_mass(), Some((4.0, [1.5, 0.0])));
        let mut seen = Vec::new();
        tree.visit([100.0, 0.0], None, 0.0, |b| seen.push(b));
        let expected = [
            Body::Point { index: 0, position: [0.0, 0.0], mass: 1.0 },
            Body::Point { index: 1, position: [2.0, 0.0], mass: 3.0 },
        ];
        assert_eq!(seen, expected);
    }

    #[test]
    fn coincident_points_share_a_leaf_without_endless_splitting() {
        let points = vec![[3.0, -2.0]; 1000];
        let tree = QuadTree::new(&points);
        assert_eq!(tree.len(), 1000);
        assert!(tree.cells.len() <= 1 + MAX_DEPTH as usize);
        let mut bodies = 0;
        tree.visit([3.0, -2.0], Some(5), 0.9, |b| match b {
            Body::Point { .. } => bodies += 1,
            Body::Cell { .. } => panic!("a cell at distance 0"),
        });
        assert_eq!(bodies, 999);
    }

    #[test]
    fn non_finite_points_are_left_out_and_empty_tree_visits_nothing() {
        let tree = QuadTree::new(&[[0.0, 0.0], [f64::NAN, 1.0], [1.0, f64::INFINITY], [2.0, 2.0]]);
        assert_eq!(tree.len(), 2);
        let mut seen = Vec::new();
        tree.visit([5.0, 5.0], Some(1), 0.0, |b| {
            if let Body::Point { index, .. } = b {
                seen.push(index);
            }
        });
        assert_eq!(seen, vec![0, 3]);
        let empty = QuadTree::new(&[]);
        assert!(empty.is_empty() && empty.centre_of_mass().is_none());
        empty.visit([0.0, 0.0], None, 0.5, |b| panic!("met {b:?}"));
    }
}
