//! Quality measures of a straight-line graph drawing.
//!
//! **Normalized stress** (the stress of Kamada and Kawai, 1989, with the weights of Gansner,
//! Koren and North, 2004, made scale-free by optimal scaling). For each pair of nodes `i ≠ j` joined by a path, let
//! `d_ij` be the graph-theoretic distance (fewest edges, by breadth-first search) and `e_ij` the
//! Euclidean distance in the drawing. With weights `w_ij = d_ij⁻²`,
//!
//! ```text
//! stress = min over α > 0 of  Σ w_ij (α·e_ij − d_ij)²  /  (number of connected pairs)
//! ```
//!
//! i.e. the layout is first scaled by the best uniform factor, so the value does not depend on
//! the drawing's units. Writing `r_ij = e_ij / d_ij`, the minimum is `1 − (Σr)² / (P·Σr²)` =
//! `var(r) / mean(r²)` over the `P` pairs: 0 when every distance is exactly proportional to the
//! graph distance, at most 1 (all nodes at one point). Pairs in different components are left
//! out; a graph with no connected pair scores 0. The sum runs over ordered pairs (each unordered
//! pair twice), which does not change the value. [`normalized_stress`] runs one BFS from every
//! node (O(n·m), parallel over sources); [`normalized_stress_sampled`] runs it from a seeded
//! random subset of sources instead: an estimate for big graphs (exact when every node is a
//! source), whose error shrinks as the sample grows.
//!
//! **Edge crossings.** The number of pairs of straight edges that cross properly: each edge's
//! endpoints lie strictly on opposite sides of the other's line. Pairs sharing an endpoint
//! node, touching or collinear segments, self-loops and zero-length edges do not count; a
//! duplicated edge counts once per copy. The edges are bucketed in a uniform grid (each edge in
//! every cell it passes through, with a tiny margin), only pairs sharing a cell are tested, and a
//! crossing is counted in the one cell holding its intersection point, so near-linear time for
//! drawings with short edges. Orientation tests use plain `f64` arithmetic: near-degenerate
//! configurations may go either way.

use std::fmt;

use rayon::prelude::*;

/// Largest number of (edge, cell) entries the crossing grid may hold; coarser grids are used
/// beyond it.
const MAX_GRID_ENTRIES: usize = 16_000_000;

/// Why a quality measure could not be computed.
#[derive(Clone, Debug, PartialEq)]
pub enum QualityError {
    /// The number of positions differs from the number of nodes.
    PositionCount {
        /// Length of the position list.
        positions: usize,
        /// The stated node count.
        node_count: usize,
    },
    /// An edge names a node without a position.
    EdgeOutOfRange {
        /// Position of the edge in the edge list.
        index: usize,
        /// The edge's first endpoint.
        source: u32,
        /// The edge's second endpoint.
        target: u32,
        /// Number of nodes (positions).
        node_count: usize,
    },
    /// A position has a NaN or infinite coordinate.
    NonFinitePosition {
        /// The node.
        node: usize,
        /// Its position.
        position: [f64; 2],
    },
}

impl fmt::Display for QualityError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::PositionCount { positions, node_count } => {
                write!(f, "{positions} positions for {node_count} nodes; give one position per node")
            }
            Self::EdgeOutOfRange { index, source, target, node_count } => write!(
                f,
                "edge {index} ({source} -> {target}) names a node outside 0..{node_count}; \
                 node indices must be below the node count"
            ),
            Self::NonFinitePosition { node, position } => {
                write!(f, "node {node} is at ({}, {}); positions must be finite numbers", position[0], position[1])
            }
        }
    }
}

impl std::error::Error for QualityError {}

/// Normalized stress of the drawing over all connected pairs (see the module documentation).
/// Costs one breadth-first search per node.
pub fn normalized_stress(positions: &[[f64; 2]], node_count: usize, edges: &[(u32, u32)]) -> Result<f64, QualityError> {
    check_positions(positions, node_count)?;
    let adjacency = Adjacency::new(node_count, edges)?;
    let sources: Vec<u32> = (0..node_count as u32).collect();
    Ok(stress_from(positions, &adjacency, &sources))
}

/// Normalized stress estimated from `sources` breadth-first searches from distinct nodes
/// drawn with `seed` (all nodes when `sources >= node_count`, which gives
/// [`normalized_stress`] exactly).
pub fn normalized_stress_sampled(
    positions: &[[f64; 2]],
    node_count: usize,
    edges: &[(u32, u32)],
    sources: usize,
    seed: u64,
) -> Result<f64, QualityError> {
    check_positions(positions, node_count)?;
    let adjacency = Adjacency::new(node_count, edges)?;
    let chosen = sample_sources(node_count, sources, seed);
    Ok(stress_from(positions, &adjacency, &chosen))
}

/// Number of proper crossings between straight edges (see the module documentation).
pub fn edge_crossings(positions: &[[f64; 2]], edges: &[(u32, u32)]) -> Result<usize, QualityError> {
    let n = positions.len();
    let mut segments = Vec::with_capacity(edges.len());
    for (index, &(source, target)) in edges.iter().enumerate() {
        let (Some(&p), Some(&q)) = (positions.get(source as usize), positions.get(target as usize)) else {
            return Err(QualityError::EdgeOutOfRange { index, source, target, node_count: n });
        };
        for (node, point) in [(source, p), (target, q)] {
            if !(point[0].is_finite() && point[1].is_finite()) {
                return Err(QualityError::NonFinitePosition { node: node as usize, position: point });
            }
        }
        if source != target && p != q {
            segments.push(Segment { ends: [source, target], p, q });
        }
    }
    Ok(Grid::build(&segments).map_or(0, |grid| grid.count_crossings(&segments)))
}

fn check_positions(positions: &[[f64; 2]], node_count: usize) -> Result<(), QualityError> {
    if positions.len() != node_count {
        return Err(QualityError::PositionCount { positions: positions.len(), node_count });
    }
    match positions.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        Some(node) => Err(QualityError::NonFinitePosition { node, position: positions[node] }),
        None => Ok(()),
    }
}

/// Undirected adjacency lists (self-loops left out; duplicates kept, harmless for BFS).
struct Adjacency {
    offsets: Vec<usize>,
    targets: Vec<u32>,
}

impl Adjacency {
    fn new(node_count: usize, edges: &[(u32, u32)]) -> Result<Self, QualityError> {
        let mut offsets = vec![0usize; node_count + 1];
        for (index, &(source, target)) in edges.iter().enumerate() {
            if source as usize >= node_count || target as usize >= node_count {
                return Err(QualityError::EdgeOutOfRange { index, source, target, node_count });
            }
            if source != target {
                offsets[source as usize + 1] += 1;
                offsets[target as usize + 1] += 1;
            }
        }
        for i in 0..node_count {
            offsets[i + 1] += offsets[i];
        }
        let mut next = offsets.clone();
        let mut targets = vec![0u32; offsets[node_count]];
        for &(source, target) in edges {
            if source != target {
                for (from, to) in [(source, target), (target, source)] {
                    let slot = &mut next[from as usize];
                    targets[*slot] = to;
                    *slot += 1;
                }
            }
        }
        Ok(Adjacency { offsets, targets })
    }

    fn neighbours(&self, i: usize) -> &[u32] {
        match (self.offsets.get(i), self.offsets.get(i + 1)) {
            (Some(&a), Some(&b)) => self.targets.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }
}

/// Running count, mean and sum of squared deviations of the ratios `e/d` (Welford, 1962),
/// mergeable (Chan, Golub and LeVeque, 1979).
#[derive(Clone, Copy, Default)]
struct Moments {
    count: f64,
    mean: f64,
    m2: f64,
}

impl Moments {
    fn push(&mut self, r: f64) {
        self.count += 1.0;
        let delta = r - self.mean;
        self.mean += delta / self.count;
        self.m2 += delta * (r - self.mean);
    }

    fn merge(self, other: Moments) -> Moments {
        if other.count == 0.0 {
            return self;
        }
        if self.count == 0.0 {
            return other;
        }
        let count = self.count + other.count;
        let delta = other.mean - self.mean;
        Moments {
            count,
            mean: self.mean + delta * other.count / count,
            m2: self.m2 + other.m2 + delta * delta * self.count * other.count / count,
        }
    }

    /// `var(r) / mean(r²)`, the minimal normalized stress.
    fn stress(self) -> f64 {
        if self.count == 0.0 {
            return 0.0;
        }
        let variance = self.m2 / self.count;
        let mean_square = variance + self.mean * self.mean;
        if mean_square > 0.0 { (variance / mean_square).clamp(0.0, 1.0) } else { 1.0 }
    }
}

/// Stress over the pairs (source, reachable node) for the given sources; per-source moments
/// are computed in parallel and merged in source order, so the result is deterministic.
fn stress_from(positions: &[[f64; 2]], adjacency: &Adjacency, sources: &[u32]) -> f64 {
    let n = positions.len();
    let per_source: Vec<Moments> = sources
        .par_iter()
        .map_init(
            || (vec![u32::MAX; n], Vec::with_capacity(n)),
            |(distance, queue), &s| bfs_moments(positions, adjacency, s as usize, distance, queue),
        )
        .collect();
    per_source.into_iter().fold(Moments::default(), Moments::merge).stress()
}

/// Breadth-first search from `source`, accumulating `e/d` for every reached node. Leaves
/// `distance` all `u32::MAX` again.
fn bfs_moments(
    positions: &[[f64; 2]],
    adjacency: &Adjacency,
    source: usize,
    distance: &mut [u32],
    queue: &mut Vec<u32>,
) -> Moments {
    let mut moments = Moments::default();
    let Some(&origin) = positions.get(source) else { return moments };
    queue.clear();
    queue.push(source as u32);
    if let Some(d) = distance.get_mut(source) {
        *d = 0;
    }
    let mut head = 0;
    while let Some(&u) = queue.get(head) {
        head += 1;
        let du = distance.get(u as usize).copied().unwrap_or(0);
        if du > 0
            && let Some(p) = positions.get(u as usize)
        {
            let e = ((p[0] - origin[0]).powi(2) + (p[1] - origin[1]).powi(2)).sqrt();
            moments.push(e / du as f64);
        }
        for &v in adjacency.neighbours(u as usize) {
            if let Some(dv) = distance.get_mut(v as usize)
                && *dv == u32::MAX
            {
                *dv = du + 1;
                queue.push(v);
            }
        }
    }
    for &u in queue.iter() {
        if let Some(d) = distance.get_mut(u as usize) {
            *d = u32::MAX;
        }
    }
    moments
}

/// `count` distinct nodes drawn with `seed` (partial Fisher–Yates with SplitMix64), sorted.
fn sample_sources(node_count: usize, count: usize, seed: u64) -> Vec<u32> {
    let mut all: Vec<u32> = (0..node_count as u32).collect();
    if count >= node_count {
        return all;
    }
    let mut state = seed;
    for i in 0..count {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        let j = i + (z % (node_count - i) as u64) as usize;
        all.swap(i, j);
    }
    all.truncate(count);
    all.sort_unstable();
    all
}

/// A straight edge between two distinct positions.
#[derive(Clone, Copy, Debug)]
struct Segment {
    ends: [u32; 2],
    p: [f64; 2],
    q: [f64; 2],
}

/// Uniform grid of square cells with the segments passing through each.
struct Grid {
    origin: [f64; 2],
    cell: f64,
    columns: usize,
    rows: usize,
    /// Tolerance added around each segment when finding its cells.
    margin: f64,
    /// Segments of cell `c` are `entries[starts[c]..starts[c + 1]]`.
    starts: Vec<usize>,
    entries: Vec<u32>,
}

impl Grid {
    /// Grid over the segments' bounding box with about one cell per segment (fewer when the
    /// segments would fill more than [`MAX_GRID_ENTRIES`] cell entries); `None` when empty.
    fn build(segments: &[Segment]) -> Option<Grid> {
        let (lo, hi) = segments.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), s| {
            (
                [lo[0].min(s.p[0]).min(s.q[0]), lo[1].min(s.p[1]).min(s.q[1])],
                [hi[0].max(s.p[0]).max(s.q[0]), hi[1].max(s.p[1]).max(s.q[1])],
            )
        });
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if segments.len() < 2 || size.is_nan() || size <= 0.0 {
            return None;
        }
        let mut resolution = ((segments.len() as f64).sqrt().ceil() as usize).clamp(1, 2048);
        loop {
            let cell = size / resolution as f64;
            let mut grid = Grid {
                origin: lo,
                cell,
                columns: (((hi[0] - lo[0]) / cell) as usize + 1).min(resolution),
                rows: (((hi[1] - lo[1]) / cell) as usize + 1).min(resolution),
                margin: size * 1e-9,
                starts: Vec::new(),
                entries: Vec::new(),
            };
            let mut counts = vec![0usize; grid.columns * grid.rows + 1];
            let mut total = 0usize;
            for s in segments {
                grid.for_each_cell(s, |c| {
                    counts[c + 1] += 1;
                    total += 1;
                });
            }
            if total > MAX_GRID_ENTRIES && resolution > 1 {
                resolution /= 2;
                continue;
            }
            for c in 1..counts.len() {
                counts[c] += counts[c - 1];
            }
            let mut next = counts.clone();
            let mut entries = vec![0u32; total];
            for (k, s) in segments.iter().enumerate() {
                grid.for_each_cell(s, |c| {
                    entries[next[c]] = k as u32;
                    next[c] += 1;
                });
            }
            grid.starts = counts;
            grid.entries = entries;
            return Some(grid);
        }
    }

    fn column_of(&self, x: f64) -> usize {
        (((x - self.origin[0]) / self.cell).floor().max(0.0) as usize).min(self.columns - 1)
    }

    fn row_of(&self, y: f64) -> usize {
        (((y - self.origin[1]) / self.cell).floor().max(0.0) as usize).min(self.rows - 1)
    }

    /// Calls `f` once for every cell within `margin` of the segment (column by column, each
    /// column's rows from the segment's y-range over that column's x-range).
    fn for_each_cell(&self, s: &Segment, mut f: impl FnMut(usize)) {
        let (xmin, xmax) = (s.p[0].min(s.q[0]), s.p[0].max(s.q[0]));
        let (dx, dy) = (s.q[0] - s.p[0], s.q[1] - s.p[1]);
        let y_at = |x: f64| if dx == 0.0 { s.p[1] } else { s.p[1] + dy * ((x - s.p[0]) / dx).clamp(0.0, 1.0) };
        for column in self.column_of(xmin - self.margin)..=self.column_of(xmax + self.margin) {
            let left = self.origin[0] + column as f64 * self.cell;
            let (x0, x1) = ((left - self.margin).max(xmin), (left + self.cell + self.margin).min(xmax));
            let (ya, yb) = if dx == 0.0 { (s.p[1], s.q[1]) } else { (y_at(x0), y_at(x1)) };
            let (ylo, yhi) = (ya.min(yb) - self.margin, ya.max(yb) + self.margin);
            for row in self.row_of(ylo)..=self.row_of(yhi) {
                f(row * self.columns + column);
            }
        }
    }

    /// Proper crossings, each counted in the cell of its intersection point.
    fn count_crossings(&self, segments: &[Segment]) -> usize {
        (0..self.columns * self.rows)
            .into_par_iter()
            .map(|c| {
                let list = self.starts.get(c..c + 2).and_then(|r| self.entries.get(r[0]..r[1])).unwrap_or(&[]);
                let mut count = 0usize;
                for (k, &a) in list.iter().enumerate() {
                    for &b in list.get(k + 1..).unwrap_or(&[]) {
                        if let (Some(sa), Some(sb)) = (segments.get(a as usize), segments.get(b as usize))
                            && let Some(point) = proper_crossing(sa, sb)
                            && self.row_of(point[1]) * self.columns + self.column_of(point[0]) == c
                        {
                            count += 1;
                        }
                    }
                }
                count
            })
            .sum()
    }
}

/// Twice the signed area of the triangle `a, b, c` (positive when counter-clockwise).
fn orientation(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The intersection point when the segments cross properly and share no endpoint node.
fn proper_crossing(a: &Segment, b: &Segment) -> Option<[f64; 2]> {
    if a.ends.iter().any(|e| b.ends.contains(e)) {
        return None;
    }
    if a.p[0].max(a.q[0]) < b.p[0].min(b.q[0])
        || b.p[0].max(b.q[0]) < a.p[0].min(a.q[0])
        || a.p[1].max(a.q[1]) < b.p[1].min(b.q[1])
        || b.p[1].max(b.q[1]) < a.p[1].min(a.q[1])
    {
        return None;
    }
    let (o1, o2) = (orientation(b.p, b.q, a.p), orientation(b.p, b.q, a.q));
    let (o3, o4) = (orientation(a.p, a.q, b.p), orientation(a.p, a.q, b.q));
    if !(o1 * o2 < 0.0 && o3 * o4 < 0.0) {
        return None;
    }
    let t = o1 / (o1 - o2);
    Some([a.p[0] + t * (a.q[0] - a.p[0]), a.p[1] + t * (a.q[1] - a.p[1])])
}

#[cfg(test)]
mod tests {
    use super::*;

    const K4: [(u32, u32); 6] = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3)];

    fn brute_force_crossings(positions: &[[f64; 2]], edges: &[(u32, u32)]) -> usize {
        let segments: Vec<Segment> = edges
            .iter()
            .map(|&(a, b)| Segment { ends: [a, b], p: positions[a as usize], q: positions[b as usize] })
            .collect();
        let mut count = 0;
        for i in 0..segments.len() {
            for j in i + 1..segments.len() {
                count += usize::from(proper_crossing(&segments[i], &segments[j]).is_some());
            }
        }
        count
    }

    #[test]
    fn k4_square_has_one_crossing_and_triangle_with_centre_none() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(edge_crossings(&square, &K4), Ok(1));
        let h = 3f64.sqrt() / 2.0;
        let triangle = [[0.0, 0.0], [1.0, 0.0], [0.5, h], [0.5, h / 3.0]];
        assert_eq!(edge_crossings(&triangle, &K4), Ok(0));
    }

    #[test]
    fn k4_stress_matches_hand_values() {
        // Square: ratios e/d are 1 (×4) and √2 (×2): 1 − (4 + 2√2)²/(6·8) = 1/2 − √2/3.
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let s = normalized_stress(&square, 4, &K4).expect("valid");
        assert!((s - (0.5 - 2f64.sqrt() / 3.0)).abs() < 1e-12, "{s}");
        // Triangle of side 1 with its centre: ratios 1 (×3) and 1/√3 (×3): 1/2 − √3/4.
        let h = 3f64.sqrt() / 2.0;
        let triangle = [[0.0, 0.0], [1.0, 0.0], [0.5, h], [0.5, h / 3.0]];
        let t = normalized_stress(&triangle, 4, &K4).expect("valid");
        assert!((t - (0.5 - 3f64.sqrt() / 4.0)).abs() < 1e-12, "{t}");
        assert!(s < t);
    }

    #[test]
    fn straight_path_has_zero_stress_at_any_scale_and_bent_path_more() {
        let edges: Vec<(u32, u32)> = (0..9).map(|i| (i, i + 1)).collect();
        let line: Vec<[f64; 2]> = (0..10).map(|i| [3.5 * i as f64 - 7.0, 2.0]).collect();
        assert_eq!(normalized_stress(&line, 10, &edges), Ok(0.0));
        let mut bent = line.clone();
        for p in &mut bent[5..] {
            *p = [p[1], p[0]];
        }
        let s = normalized_stress(&bent, 10, &edges).expect("valid");
        assert!(s > 0.01, "{s}");
        let scaled: Vec<[f64; 2]> = bent.iter().map(|p| [p[0] * 1e3, p[1] * 1e3]).collect();
        let s2 = normalized_stress(&scaled, 10, &edges).expect("valid");
        assert!((s - s2).abs() < 1e-12);
    }

    #[test]
    fn degenerate_drawings_have_documented_values() {
        let same = [[1.0, 1.0]; 3];
        assert_eq!(normalized_stress(&same, 3, &[(0, 1), (1, 2)]), Ok(1.0));
        assert_eq!(edge_crossings(&same, &[(0, 1), (1, 2)]), Ok(0));
        assert_eq!(normalized_stress(&[[0.0, 0.0], [1.0, 0.0]], 2, &[(0, 0)]), Ok(0.0));
        assert_eq!(normalized_stress(&[], 0, &[]), Ok(0.0));
        // Touching (T-junction), collinear overlap and duplicated edges are not proper crossings.
        let p = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, 0.0], [3.0, 0.0]];
        assert_eq!(edge_crossings(&p, &[(0, 1), (2, 3), (4, 5), (0, 1)]), Ok(0));
    }

    #[test]
    fn grid_count_matches_brute_force_on_random_drawings() {
        let mut state = 0x1234_5678_9abc_def1u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for round in 0..4 {
            let n = 60 + 40 * round;
            let positions: Vec<[f64; 2]> =
                (0..n).map(|_| [(next() % 1000) as f64 / 7.0, (next() % 600) as f64 / 3.0]).collect();
            let edges: Vec<(u32, u32)> =
                (0..3 * n).map(|_| ((next() % n as u64) as u32, (next() % n as u64) as u32)).collect();
            let expected = brute_force_crossings(&positions, &edges);
            assert!(expected > 100);
            assert_eq!(edge_crossings(&positions, &edges), Ok(expected));
        }
    }

    #[test]
    fn sampled_stress_equals_exact_with_all_sources_and_is_close_with_few() {
        let (w, h) = (12u32, 9u32);
        let mut edges = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                if x + 1 < w {
                    edges.push((i, i + 1));
                }
                if y + 1 < h {
                    edges.push((i, i + w));
                }
            }
        }
        let n = (w * h) as usize;
        // A grid drawn with a quadratic warp, so the stress is clearly above 0.
        let positions: Vec<[f64; 2]> =
            (0..n).map(|i| ((i % 12) as f64, (i / 12) as f64)).map(|(x, y)| [x + 0.05 * y * y, y]).collect();
        let exact = normalized_stress(&positions, n, &edges).expect("valid");
        assert_eq!(normalized_stress_sampled(&positions, n, &edges, n, 9), Ok(exact));
        let sampled = normalized_stress_sampled(&positions, n, &edges, 30, 9).expect("valid");
        assert_eq!(normalized_stress_sampled(&positions, n, &edges, 30, 9), Ok(sampled));
        assert!(exact > 0.005 && (sampled - exact).abs() < 0.3 * exact, "{sampled} vs {exact}");
    }

    #[test]
    fn bad_input_is_rejected_with_the_culprit() {
        let p = [[0.0, 0.0], [1.0, 0.0]];
        assert_eq!(
            normalized_stress(&p, 3, &[(0, 1)]),
            Err(QualityError::PositionCount { positions: 2, node_count: 3 })
        );
        let err = edge_crossings(&p, &[(0, 1), (1, 5)]).unwrap_err();
        assert_eq!(err, QualityError::EdgeOutOfRange { index: 1, source: 1, target: 5, node_count: 2 });
        assert!(err.to_string().contains("edge 1 (1 -> 5)"));
        let nan = [[0.0, 0.0], [f64::NAN, 1.0]];
        assert!(matches!(normalized_stress(&nan, 2, &[(0, 1)]), Err(QualityError::NonFinitePosition { node: 1, .. })));
        assert!(matches!(edge_crossings(&nan, &[(0, 1)]), Err(QualityError::NonFinitePosition { node: 1, .. })));
    }
}
