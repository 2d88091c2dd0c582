//! Circular layout: nodes on the unit circle, edges drawn as straight chords.
//!
//! Two chords cross exactly when their end points interleave around the circle, so crossings
//! depend only on the cyclic order of the nodes; [`circular_crossings`] counts them exactly by
//! sweeping chords by their first slot with a Fenwick tree (O(m log m)).
//!
//! Ordering, in the spirit of Six & Tollis (1999): connected components are kept contiguous
//! (largest first, ties by smallest node index). Within a component a depth-first traversal from
//! a node of least degree (neighbours visited by ascending degree, then index) gives the start;
//! a depth-first order already draws every tree and every cycle without crossings. Then up to
//! [`IMPROVE_PASSES`] passes (fewer once a pass removes under 1% of the crossings left, see
//! [`IMPROVE_MIN_GAIN`]) move each node in turn to the gap that minimises the crossings of its
//! own chords; the cost of all gaps is found at once from the arcs each other chord cuts, in
//! O(n + m) per node, and a node moves only for a strict gain, ties going to the lowest gap.
//! Passes are budgeted so that a pass of a component with `k` nodes and `e` chords runs only
//! while the passes' total `k·(k+e)` stays under [`IMPROVE_BUDGET`]. If the result has more
//! crossings than the component's nodes in input order, that order is improved instead, so the
//! reduction never returns more crossings than the input order.
//!
//! Self-loops are ignored; duplicate edges are one chord that counts with its multiplicity.
//! Coordinates: y grows downwards (as on screen); slot 0 is at the top, (0, −1), and slots follow
//! clockwise at equal angles.

use std::fmt;

/// Largest node count accepted by [`circular_layout`] and [`circular_order`].
pub const MAX_CIRCULAR_NODES: usize = 10_000_000;
/// Cap on the node-moving passes per component.
pub const IMPROVE_PASSES: usize = 8;
/// A pass that removes less than `1 / IMPROVE_MIN_GAIN` of the crossings left is the last one.
pub const IMPROVE_MIN_GAIN: u64 = 100;
/// Work budget, in node·(node + chord) visits, for the node-moving passes of one component.
pub const IMPROVE_BUDGET: u64 = 400_000_000;

/// Settings for [`circular_layout`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CircularOptions {
    /// Reorder nodes to reduce crossings (default true); false keeps node `i` in slot `i`.
    pub reduce_crossings: bool,
}

impl Default for CircularOptions {
    fn default() -> Self {
        Self { reduce_crossings: true }
    }
}

/// Why [`circular_layout`] refused its input.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CircularError {
    /// An edge names a node that does not exist.
    EdgeOutOfRange {
        /// Index of the edge in the input list.
        edge: usize,
        /// Its source.
        source: u32,
        /// Its target.
        target: u32,
        /// Number of nodes given.
        node_count: usize,
    },
    /// More nodes than [`MAX_CIRCULAR_NODES`].
    TooManyNodes(usize),
}

impl fmt::Display for CircularError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::EdgeOutOfRange { edge, source, target, node_count } => write!(
                f,
                "edge {edge} ({source} -> {target}) names a node outside 0..{node_count}; \
                 use node indices below the node count"
            ),
            Self::TooManyNodes(n) => {
                write!(f, "{n} nodes are too many for a circular layout; at most {MAX_CIRCULAR_NODES} are supported")
            }
        }
    }
}

impl std::error::Error for CircularError {}

/// Positions on the unit circle: the node in slot `s` of [`circular_order`] sits at angle
/// `2πs/n` clockwise from the top, i.e. at `(sin θ, −cos θ)` with y downwards.
pub fn circular_layout(
    node_count: usize,
    edges: &[(u32, u32)],
    options: &CircularOptions,
) -> Result<Vec<[f64; 2]>, CircularError> {
    let order = circular_order(node_count, edges, options)?;
    let mut positions = vec![[0.0, 0.0]; node_count];
    let step = std::f64::consts::TAU / node_count.max(1) as f64;
    for (slot, &node) in order.iter().enumerate() {
        let angle = step * slot as f64;
        positions[node] = [angle.sin(), -angle.cos()];
    }
    Ok(positions)
}

/// The nodes in circle order (`order[slot] = node`), as [`circular_layout`] places them.
pub fn circular_order(
    node_count: usize,
    edges: &[(u32, u32)],
    options: &CircularOptions,
) -> Result<Vec<usize>, CircularError> {
    validate(node_count, edges)?;
    if !options.reduce_crossings {
        return Ok((0..node_count).collect());
    }
    let chords = weighted_chords(edges);
    let adjacency = Adjacency::build(node_count, &chords);
    let mut order = Vec::with_capacity(node_count);
    let mut local = vec![u32::MAX; node_count];
    for members in components(&adjacency) {
        let component = Component::new(&members, &adjacency, &mut local);
        order.extend(component.arrange().into_iter().map(|i| members[i as usize] as usize));
    }
    Ok(order)
}

/// Number of crossing chord pairs when the nodes sit around a circle in `order`
/// (`order[slot] = node`). Chords cross iff their end points strictly interleave; chords sharing
/// an end point never cross. Self-loops and edges touching a node absent from `order` are
/// ignored; a node listed twice keeps its first slot; duplicate edges count separately.
pub fn circular_crossings(order: &[usize], edges: &[(u32, u32)]) -> usize {
    let mut slot_of: Vec<(usize, u32)> = order.iter().enumerate().map(|(s, &v)| (v, s as u32)).collect();
    slot_of.sort_unstable();
    slot_of.dedup_by_key(|&mut (v, _)| v);
    let find = |v: u32| slot_of.binary_search_by_key(&(v as usize), |&(w, _)| w).ok().map(|i| slot_of[i].1);
    let mut chords: Vec<(u32, u32, u64)> = Vec::with_capacity(edges.len());
    for &(u, v) in edges {
        if let (Some(a), Some(b)) = (find(u), find(v))
            && a != b
        {
            chords.push((a.min(b), a.max(b), 1));
        }
    }
    usize::try_from(count_crossings(order.len(), &mut chords)).unwrap_or(usize::MAX)
}

/// Weighted crossings of chords given as `(low slot, high slot, weight)`: the sum of
/// `w1 · w2` over interleaving pairs. Sorts `chords`.
fn count_crossings(slots: usize, chords: &mut [(u32, u32, u64)]) -> u64 {
    chords.sort_unstable();
    let mut tree = vec![0u64; slots + 1];
    let mut total = 0u64;
    let mut i = 0;
    while i < chords.len() {
        let low = chords[i].0;
        let mut j = i;
        while j < chords.len() && chords[j].0 == low {
            let (a, b, w) = chords[j];
            // Earlier chords (smaller low end) whose high end lies strictly inside (a, b).
            let inside = prefix(&tree, b as usize) - prefix(&tree, a as usize + 1);
            total += w * inside;
            j += 1;
        }
        for &(_, b, w) in &chords[i..j] {
            add(&mut tree, b as usize + 1, w);
        }
        i = j;
    }
    total
}

/// Sum of the first `i` entries of a 1-based Fenwick tree.
fn prefix(tree: &[u64], mut i: usize) -> u64 {
    let mut sum = 0;
    while i > 0 {
        sum += tree[i];
        i &= i - 1;
    }
    sum
}

/// Adds `w` at 1-based index `i`.
fn add(tree: &mut [u64], mut i: usize, w: u64) {
    while i < tree.len() {
        tree[i] += w;
        i += i & i.wrapping_neg();
    }
}

/// Checks the node count and edge end points.
fn validate(node_count: usize, edges: &[(u32, u32)]) -> Result<(), CircularError> {
    if node_count > MAX_CIRCULAR_NODES {
        return Err(CircularError::TooManyNodes(node_count));
    }
    for (edge, &(source, target)) in edges.iter().enumerate() {
        if source as usize >= node_count || target as usize >= node_count {
            return Err(CircularError::EdgeOutOfRange { edge, source, target, node_count });
        }
    }
    Ok(())
}

/// Distinct undirected chords `(low, high)` with their multiplicity, self-loops dropped.
fn weighted_chords(edges: &[(u32, u32)]) -> Vec<(u32, u32, u64)> {
    let mut pairs: Vec<(u32, u32)> =
        edges.iter().filter(|&&(u, v)| u != v).map(|&(u, v)| (u.min(v), u.max(v))).collect();
    pairs.sort_unstable();
    let mut chords: Vec<(u32, u32, u64)> = Vec::with_capacity(pairs.len());
    for (u, v) in pairs {
        match chords.last_mut() {
            Some(last) if (last.0, last.1) == (u, v) => last.2 += 1,
            _ => chords.push((u, v, 1)),
        }
    }
    chords
}

/// Undirected weighted adjacency; each node's neighbours sorted by (degree, index).
struct Adjacency {
    offsets: Vec<usize>,
    neighbours: Vec<(u32, u64)>,
}

impl Adjacency {
    fn build(n: usize, chords: &[(u32, u32, u64)]) -> Self {
        let mut offsets = vec![0usize; n + 1];
        for &(u, v, _) in chords {
            offsets[u as usize + 1] += 1;
            offsets[v as usize + 1] += 1;
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut neighbours = vec![(0u32, 0u64); offsets[n]];
        for &(u, v, w) in chords {
            for (a, b) in [(u, v), (v, u)] {
                neighbours[fill[a as usize]] = (b, w);
                fill[a as usize] += 1;
            }
        }
        let degree: Vec<usize> = (0..n).map(|v| offsets[v + 1] - offsets[v]).collect();
        for v in 0..n {
            neighbours[offsets[v]..offsets[v + 1]].sort_unstable_by_key(|&(w, _)| (degree[w as usize], w));
        }
        Self { offsets, neighbours }
    }

    fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    fn of(&self, v: u32) -> &[(u32, u64)] {
        &self.neighbours[self.offsets[v as usize]..self.offsets[v as usize + 1]]
    }
}

/// Connected components as sorted node lists, largest first, ties by smallest node.
fn components(adjacency: &Adjacency) -> Vec<Vec<u32>> {
    let n = adjacency.len();
    let mut seen = vec![false; n];
    let mut found: Vec<Vec<u32>> = Vec::new();
    let mut stack = Vec::new();
    for start in 0..n as u32 {
        if seen[start as usize] {
            continue;
        }
        seen[start as usize] = true;
        stack.push(start);
        let mut members = Vec::new();
        while let Some(v) = stack.pop() {
            members.push(v);
            for &(w, _) in adjacency.of(v) {
                if !seen[w as usize] {
                    seen[w as usize] = true;
                    stack.push(w);
                }
            }
        }
        members.sort_unstable();
        found.push(members);
    }
    found.sort_by_key(|m| std::cmp::Reverse(m.len()));
    found
}

/// One component with local node indices `0..k` (in node index order).
struct Component {
    /// Local adjacency: `(neighbour, weight)`, sorted by (degree, index).
    neighbours: Vec<Vec<(u32, u64)>>,
    /// Chords `(a, b, weight)` with `a < b`, local indices.
    chords: Vec<(u32, u32, u64)>,
}

impl Component {
    /// Extracts the component; `local` is scratch space of the global node count.
    fn new(members: &[u32], adjacency: &Adjacency, local: &mut [u32]) -> Self {
        for (i, &v) in members.iter().enumerate() {
            local[v as usize] = i as u32;
        }
        let neighbours: Vec<Vec<(u32, u64)>> =
            members.iter().map(|&v| adjacency.of(v).iter().map(|&(w, wt)| (local[w as usize], wt)).collect()).collect();
        let mut chords = Vec::new();
        for (a, list) in neighbours.iter().enumerate() {
            chords.extend(list.iter().filter(|&&(b, _)| b as usize > a).map(|&(b, w)| (a as u32, b, w)));
        }
        Self { neighbours, chords }
    }

    fn len(&self) -> usize {
        self.neighbours.len()
    }

    /// Local order: depth-first start improved by node moves, or the improved input order if
    /// that one has fewer crossings.
    fn arrange(&self) -> Vec<u32> {
        let input: Vec<u32> = (0..self.len() as u32).collect();
        let passes = self.pass_budget();
        let candidate = self.improve(self.depth_first(), passes);
        if self.crossings(&candidate) <= self.crossings(&input) { candidate } else { self.improve(input, passes) }
    }

    /// Passes allowed by [`IMPROVE_BUDGET`] (at most [`IMPROVE_PASSES`]).
    fn pass_budget(&self) -> usize {
        let k = self.len() as u64;
        let work = k.saturating_mul(k + self.chords.len() as u64).max(1);
        usize::try_from(IMPROVE_BUDGET / work).unwrap_or(usize::MAX).min(IMPROVE_PASSES)
    }

    /// Weighted crossings of `order` (local indices).
    fn crossings(&self, order: &[u32]) -> u64 {
        let slot = slots_of(order);
        let mut chords: Vec<(u32, u32, u64)> = self
            .chords
            .iter()
            .map(|&(a, b, w)| {
                let (sa, sb) = (slot[a as usize], slot[b as usize]);
                (sa.min(sb), sa.max(sb), w)
            })
            .collect();
        count_crossings(order.len(), &mut chords)
    }

    /// Depth-first preorder from a node of least degree (smallest index on ties).
    fn depth_first(&self) -> Vec<u32> {
        let k = self.len();
        let start = (0..k).min_by_key(|&v| (self.neighbours[v].len(), v)).unwrap_or(0);
        let mut order = Vec::with_capacity(k);
        let mut seen = vec![false; k];
        let mut stack: Vec<(u32, usize)> = vec![(start as u32, 0)];
        seen[start] = true;
        order.push(start as u32);
        while let Some(top) = stack.last_mut() {
            let (v, next) = *top;
            match self.neighbours[v as usize].get(next) {
                Some(&(w, _)) => {
                    top.1 += 1;
                    if !seen[w as usize] {
                        seen[w as usize] = true;
                        order.push(w);
                        stack.push((w, 0));
                    }
                }
                None => {
                    stack.pop();
                }
            }
        }
        order
    }

    /// Node-moving passes: each node goes to the gap minimising its own chords' crossings.
    fn improve(&self, mut order: Vec<u32>, passes: usize) -> Vec<u32> {
        let k = order.len();
        if k < 4 {
            return order;
        }
        let mut slot = slots_of(&order);
        let mut scratch = MoveScratch::new(k);
        let mut remaining = self.crossings(&order);
        for _ in 0..passes {
            let mut saved = 0u64;
            for v in 0..k as u32 {
                let Some((gap, gain)) = self.best_gap(v, &order, &slot, &mut scratch) else {
                    continue;
                };
                let from = slot[v as usize] as usize;
                order.remove(from);
                order.insert(gap, v);
                for (s, &w) in order.iter().enumerate() {
                    slot[w as usize] = s as u32;
                }
                saved += gain;
            }
            if saved == 0 || saved.saturating_mul(IMPROVE_MIN_GAIN) < remaining {
                break;
            }
            remaining -= saved.min(remaining);
        }
        order
    }

    /// The gap (index in the order without `v`) where `v`'s chords cross least and the
    /// crossings saved, if strictly better than where `v` is now. Gap `j` lies before the `j`-th remaining node; gap 0 is
    /// also the gap after the last one.
    fn best_gap(&self, v: u32, order: &[u32], slot: &[u32], scratch: &mut MoveScratch) -> Option<(usize, u64)> {
        let k = order.len();
        let gaps = k - 1;
        let own = slot[v as usize];
        let reduced = |s: u32| if s > own { s - 1 } else { s };
        let MoveScratch { weight_to_v, cumulative, diff } = scratch;
        for &(w, wt) in &self.neighbours[v as usize] {
            weight_to_v[w as usize] = wt;
        }
        cumulative[0] = 0;
        for (j, &w) in order.iter().filter(|&&w| w != v).enumerate() {
            cumulative[j + 1] = cumulative[j] + weight_to_v[w as usize];
        }
        let all = cumulative[gaps];
        diff[..=gaps].fill(0);
        let mut base = 0i64;
        for &(a, b, w) in &self.chords {
            if a == v || b == v {
                continue;
            }
            let (sa, sb) = (reduced(slot[a as usize]), reduced(slot[b as usize]));
            let (lo, hi) = (sa.min(sb) as usize, sa.max(sb) as usize);
            let inside = cumulative[hi] - cumulative[lo + 1];
            let ends = weight_to_v[a as usize] + weight_to_v[b as usize];
            let outside = all - inside - ends;
            // Gaps lo+1..=hi lie inside the chord's arc: there v's chords to outside nodes cross it.
            let (w, inside, outside) = (w as i64, inside as i64, outside as i64);
            base += w * inside;
            diff[lo + 1] += w * (outside - inside);
            diff[hi + 1] -= w * (outside - inside);
        }
        for &(w, _) in &self.neighbours[v as usize] {
            weight_to_v[w as usize] = 0;
        }
        let current = if own as usize == gaps { 0 } else { own as usize };
        let mut running = base;
        let mut best = (i64::MAX, 0usize);
        let mut here = 0i64;
        for (gap, &d) in diff[..gaps].iter().enumerate() {
            running += d;
            if gap == current {
                here = running;
            }
            if running < best.0 {
                best = (running, gap);
            }
        }
        (best.0 < here).then(|| (best.1, (here - best.0) as u64))
    }
}

/// Reused buffers for [`Component::best_gap`].
struct MoveScratch {
    weight_to_v: Vec<u64>,
    cumulative: Vec<u64>,
    diff: Vec<i64>,
}

impl MoveScratch {
    fn new(k: usize) -> Self {
        Self { weight_to_v: vec![0; k], cumulative: vec![0; k + 1], diff: vec![0; k + 1] }
    }
}

/// Slot of each local node in `order`.
fn slots_of(order: &[u32]) -> Vec<u32> {
    let mut slot = vec![0u32; order.len()];
    for (s, &v) in order.iter().enumerate() {
        slot[v as usize] = s as u32;
    }
    slot
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::layout::split_mix::SplitMix64 as Rng;

    fn random_edges(n: u32, m: usize, seed: u64) -> Vec<(u32, u32)> {
        let mut rng = Rng(seed);
        (0..m).map(|_| (rng.below(n), rng.below(n))).collect()
    }

    fn order(n: usize, edges: &[(u32, u32)]) -> Vec<usize> {
        circular_order(n, edges, &CircularOptions::default()).unwrap()
    }

    /// Crossings by checking every pair of edges: chords interleave when exactly one end of one
    /// lies strictly between the ends of the other.
    fn brute_force(order: &[usize], edges: &[(u32, u32)]) -> usize {
        let mut slot = vec![0usize; order.len()];
        for (s, &v) in order.iter().enumerate() {
            slot[v] = s;
        }
        let chord = |&(u, v): &(u32, u32)| {
            let (a, b) = (slot[u as usize], slot[v as usize]);
            (a.min(b), a.max(b))
        };
        let between = |x: usize, (a, b): (usize, usize)| a < x && x < b;
        let mut count = 0;
        for (i, e) in edges.iter().enumerate() {
            for f in &edges[i + 1..] {
                let (p, q) = (chord(e), chord(f));
                let shared = p.0 == q.0 || p.0 == q.1 || p.1 == q.0 || p.1 == q.1;
                if p.0 != p.1 && q.0 != q.1 && !shared && (between(q.0, p) != between(q.1, p)) {
                    count += 1;
                }
            }
        }
        count
    }

    #[test]
    fn positions_are_equal_steps_on_the_unit_circle_clockwise_from_the_top() {
        let edges = random_edges(12, 20, 1);
        let positions = circular_layout(12, &edges, &CircularOptions::default()).unwrap();
        let slots = order(12, &edges);
        for (s, &v) in slots.iter().enumerate() {
            let [x, y] = positions[v];
            assert!((x.hypot(y) - 1.0).abs() < 1e-12);
            // Angle clockwise from the top with y pointing down.
            let angle = x.atan2(-y).rem_euclid(std::f64::consts::TAU);
            assert!((angle - std::f64::consts::TAU * s as f64 / 12.0).abs() < 1e-9, "slot {s}");
        }
        assert_eq!(positions[slots[0]], [0.0, -1.0]);
        assert!((positions[slots[3]][0] - 1.0).abs() < 1e-12, "a quarter turn clockwise is on the right");
    }

    #[test]
    fn shuffled_cycle_has_no_crossings() {
        let mut labels: Vec<u32> = (0..30).collect();
        Rng(5).shuffle(&mut labels);
        let edges: Vec<(u32, u32)> = (0..30).map(|i| (labels[i], labels[(i + 1) % 30])).collect();
        let identity: Vec<usize> = (0..30).collect();
        assert!(circular_crossings(&identity, &edges) > 0);
        assert_eq!(circular_crossings(&order(30, &edges), &edges), 0);
    }

    #[test]
    fn trees_have_no_crossings() {
        for seed in 0..5 {
            let mut rng = Rng(seed);
            let edges: Vec<(u32, u32)> = (1..60).map(|v| (rng.below(v), v)).collect();
            assert_eq!(circular_crossings(&order(60, &edges), &edges), 0, "seed {seed}");
        }
    }

    #[test]
    fn k4_has_one_crossing_in_every_order() {
        let k4 = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
        let mut count = 0;
        for a in 0..4 {
            for b in 0..4 {
                for c in 0..4 {
                    for d in 0..4 {
                        let perm = [a, b, c, d];
                        if (0..4).all(|v| perm.contains(&v)) {
                            assert_eq!(circular_crossings(&perm, &k4), 1, "{perm:?}");
                            count += 1;
                        }
                    }
                }
            }
        }
        assert_eq!(count, 24);
    }

    #[test]
    fn chord_count_matches_hand_count() {
        // Hexagon 0..5 in order with chords 0-3, 1-4, 2-5 (three diameters, pairwise crossing),
        // 0-2 (crosses 1-4) and the side 0-1 (crosses nothing): 3 + 1 = 4.
        let order: Vec<usize> = (0..6).collect();
        let edges = [(0, 3), (1, 4), (2, 5), (0, 2), (0, 1)];
        assert_eq!(circular_crossings(&order, &edges), 4);
        // A duplicate of 1-4 crosses 0-3, 2-5 and 0-2 again; self-loops and the reversed copy
        // of a side add nothing new beyond its own duplicate (sides cross nothing).
        let more = [(0, 3), (1, 4), (2, 5), (0, 2), (0, 1), (4, 1), (3, 3), (1, 0)];
        assert_eq!(circular_crossings(&order, &more), 7);
        // A node missing from the order drops its chords (without 5: 1-4 crosses 0-3 and 0-2);
        // a repeated node keeps its first slot.
        assert_eq!(circular_crossings(&[0, 1, 2, 3, 4, 5, 0], &edges), 4);
        assert_eq!(circular_crossings(&[0, 1, 2, 3, 4], &edges), 2);
        let random = random_edges(40, 120, 9);
        let shuffled: Vec<usize> = (0..40).map(|i| (i * 17) % 40).collect();
        assert_eq!(circular_crossings(&shuffled, &random), brute_force(&shuffled, &random));
    }

    #[test]
    fn reduction_is_never_worse_than_input_order() {
        let identity: Vec<usize> = (0..50).collect();
        let mut strictly_better = 0;
        for seed in 0..12 {
            let edges = random_edges(50, 40 + 10 * seed as usize, seed);
            let before = circular_crossings(&identity, &edges);
            let after = circular_crossings(&order(50, &edges), &edges);
            assert!(after <= before, "seed {seed}: {after} > {before}");
            strictly_better += usize::from(after < before);
        }
        assert!(strictly_better >= 10);
        // An input order that is already crossing-free stays crossing-free.
        let outerplanar: Vec<(u32, u32)> =
            (0..20).map(|i| (i, (i + 1) % 20)).chain([(0, 5), (5, 10), (0, 10)]).collect();
        assert_eq!(circular_crossings(&order(20, &outerplanar), &outerplanar), 0);
    }

    #[test]
    fn improvement_never_raises_the_exact_count() {
        // The node-moving passes, checked against a brute-force count on every move's result.
        let edges = random_edges(30, 70, 3);
        let chords = weighted_chords(&edges);
        let adjacency = Adjacency::build(30, &chords);
        let members: Vec<u32> = (0..30).collect();
        let component = Component::new(&members, &adjacency, &mut [0; 30]);
        let mut current: Vec<u32> = (0..30).collect();
        let mut last = brute_force(&(0..30).collect::<Vec<_>>(), &edges);
        for _ in 0..4 {
            current = component.improve(current, 1);
            let now: Vec<usize> = current.iter().map(|&v| v as usize).collect();
            let count = brute_force(&now, &edges);
            assert!(count <= last);
            assert_eq!(count as u64, component.crossings(&current));
            last = count;
        }
    }

    #[test]
    fn components_are_contiguous_largest_first() {
        // A 4-cycle on {1, 3, 5, 7}, a path on {0, 6}, isolated 2 and 4.
        let edges = [(1, 3), (3, 5), (5, 7), (7, 1), (6, 0)];
        let out = order(8, &edges);
        let mut head: Vec<usize> = out[..4].to_vec();
        head.sort_unstable();
        assert_eq!(head, vec![1, 3, 5, 7]);
        let mut pair: Vec<usize> = out[4..6].to_vec();
        pair.sort_unstable();
        assert_eq!(pair, vec![0, 6]);
        assert_eq!(&out[6..], &[2, 4]);
    }

    #[test]
    fn input_order_kept_without_reduction() {
        let edges = random_edges(10, 15, 2);
        let options = CircularOptions { reduce_crossings: false };
        assert_eq!(circular_order(10, &edges, &options).unwrap(), (0..10).collect::<Vec<_>>());
        let positions = circular_layout(10, &edges, &options).unwrap();
        assert_eq!(positions[0], [0.0, -1.0]);
        assert!((positions[5][1] - 1.0).abs() < 1e-12, "slot 5 of 10 is at the bottom");
    }

    #[test]
    fn deterministic() {
        let edges = random_edges(200, 500, 8);
        let a = circular_layout(200, &edges, &CircularOptions::default()).unwrap();
        let b = circular_layout(200, &edges, &CircularOptions::default()).unwrap();
        let bits = |p: &[[f64; 2]]| p.iter().flat_map(|q| [q[0].to_bits(), q[1].to_bits()]).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
    }

    #[test]
    fn bad_input_is_refused() {
        let o = CircularOptions::default();
        let err = circular_layout(4, &[(0, 1), (2, 9)], &o).unwrap_err();
        assert_eq!(err, CircularError::EdgeOutOfRange { edge: 1, source: 2, target: 9, node_count: 4 });
        assert!(err.to_string().contains("edge 1 (2 -> 9)"));
        assert_eq!(
            circular_layout(MAX_CIRCULAR_NODES + 1, &[], &o),
            Err(CircularError::TooManyNodes(MAX_CIRCULAR_NODES + 1))
        );
        assert!(circular_layout(0, &[], &o).unwrap().is_empty());
        assert_eq!(circular_layout(1, &[(0, 0)], &o).unwrap(), vec![[0.0, -1.0]]);
        assert_eq!(circular_crossings(&[], &[(0, 1)]), 0);
    }
}
