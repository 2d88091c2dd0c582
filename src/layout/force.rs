//! Force-directed layout of undirected graphs: the multilevel spring–electrical method of Hu
//! (2005, "Efficient and high quality force-directed graph drawing", the algorithm of Graphviz
//! `sfdp`), with Barnes–Hut repulsion (Barnes and Hut, 1986; see [`super::quadtree`]) and
//! ForceAtlas2's degree-weighted charges (Jacomy et al., 2014).
//!
//! **Model.** Nodes `i`, `j` at distance `d` repel with force `C·K²·q_i·q_j / d` (`K` = 1 the
//! natural length, `C` = [`REPULSION`]), where the charge `q_i` is 1 + degree, scaled to mean 1
//! (as in ForceAtlas2, so hubs get room and leaves stay near their neighbour). The ends of an edge
//! of weight `w` attract with Fruchterman and Reingold's (1991) force `w·d²/K` up to
//! [`SPRING_REACH`] node spacings, and as `w·√d` (continuously) beyond: in dense, expander-like
//! graphs most edges are long, and the softer pull of long edges keeps them from crushing the
//! core, which lowers stress and crossings there while leaving sparse, local structures (meshes,
//! trees, cycles) in the `d²` regime. The node spacing is `√(area / n)` with the area of the
//! positions' covariance ellipse. Repulsion from far-away cells comes from the quadtree when
//! `cell side < theta · distance`.
//!
//! **Iteration.** All forces are computed from the same positions, in parallel with rayon, each
//! node independently (so the result does not depend on the thread count). A node moves `step`
//! along its force, or proportionally less when its force is below both the median force and
//! the repulsion of two nodes one spacing apart (the temperature-limited move of Fruchterman and
//! Reingold, which lets nodes near equilibrium settle). The step adapts as in Hu (2005): after
//! five iterations in a row that lower the energy (the sum of squared forces) it grows by 1/0.9;
//! after any that does not, it shrinks by 0.9. It starts at one node spacing and a level stops
//! when it falls below `tolerance` node spacings, or after `iterations` iterations.
//!
//! **Multilevel.** The graph is coarsened repeatedly by heavy-edge matching (Walshaw, 2000; Hu,
//! 2005): in a seeded random order each unmatched node merges with the unmatched neighbour that
//! stands for the fewest original nodes (ties: most collapsed edges), and nodes left unmatched
//! then pair up with other unmatched neighbours of a common node ("two-hop" matching, which keeps
//! stars and other hub-heavy graphs coarsening). Coarsening stops at [`COARSEST`] nodes or when a
//! round removes fewer than a tenth of them. The coarsest graph starts from seeded random
//! positions; each finer level starts from its coarser level's layout, spread out by the square
//! root of the node-count ratio, each node at its group's place plus a seeded jitter of a tenth
//! of a node spacing (so merged nodes never coincide).
//!
//! **Input and output.** Self-loops are ignored; multi-edges are merged, their weights added;
//! edges of weight 0 are dropped. Each connected component is laid out on its own, turned so its
//! principal axis is horizontal, scaled so its median edge length is 1, and the components are
//! packed in rows, larger first, with a gap of one edge length, into a roughly square
//! arrangement centred on the origin. Isolated nodes are one-node components. All randomness
//! comes from `ForceOptions::seed`, so a given input and seed give bit-identical positions.

use std::fmt;

use rayon::prelude::*;

use super::split_mix::{SplitMix64 as Rng, mix64};

use super::quadtree::{Body, QuadTree};

/// Natural spring length of the model; positions are rescaled at the end anyway.
const K: f64 = 1.0;
/// Relative strength of repulsion (Hu's `C`).
pub const REPULSION: f64 = 0.2;
/// Springs pull as `d²` up to this many node spacings and as `√d` beyond.
pub const SPRING_REACH: f64 = 8.0;
/// Step factor of the adaptive cooling schedule.
const COOLING: f64 = 0.9;
/// Initial step of every level, in node spacings.
const INITIAL_STEP: f64 = 1.0;
/// Coarsening stops at this many nodes.
pub const COARSEST: usize = 4;
/// Coarsening stops after this many levels whatever the size.
const MAX_LEVELS: usize = 60;
/// Half-width of the square in which prolonged nodes are scattered, in node spacings.
const JITTER: f64 = 0.1;
/// Distance under which two nodes count as coincident for repulsion.
const MIN_DISTANCE: f64 = 1e-9 * K;
/// Graphs with at least this many nodes compute forces in parallel.
const PARALLEL_MIN: usize = 256;
/// Gap between packed components, in edge lengths.
const PACKING_GAP: f64 = 1.0;

const NONE: u32 = u32::MAX;

/// Settings of [`force_layout`].
#[derive(Clone, Debug, PartialEq)]
pub struct ForceOptions {
    /// Seed of every random choice (initial positions, coarsening order, jitter).
    pub seed: u64,
    /// Largest number of iterations at each level of the multilevel scheme (0 keeps the
    /// seeded starting positions, refined by nothing).
    pub iterations: u32,
    /// Barnes–Hut opening parameter: a cell is approximated by its centre of mass when its side
    /// is below `theta` times its distance. 0 is exact (and O(n²)); 0.9 is fast and accurate.
    pub theta: f64,
    /// A level stops once the adaptive step is below `tolerance` node spacings (about edge
    /// lengths in sparse graphs).
    pub tolerance: f64,
    /// Whether to coarsen the graph (recommended; without it large graphs tangle).
    pub multilevel: bool,
}

impl Default for ForceOptions {
    fn default() -> Self {
        ForceOptions { seed: 0, iterations: 100, theta: 0.9, tolerance: 0.03, multilevel: true }
    }
}

/// Why [`force_layout`] rejected its input.
#[derive(Clone, Debug, PartialEq)]
pub enum ForceError {
    /// An edge names a node that does not exist.
    EdgeOutOfRange {
        /// Position of the edge in the edge list.
        index: usize,
        /// The edge's first endpoint as given.
        source: u32,
        /// The edge's second endpoint as given.
        target: u32,
        /// The number of nodes.
        node_count: usize,
    },
    /// The weight list is not as long as the edge list.
    WeightCountMismatch {
        /// Length of the weight list.
        weights: usize,
        /// Length of the edge list.
        edges: usize,
    },
    /// An edge weight is negative, infinite or NaN.
    InvalidWeight {
        /// Position of the edge in the edge list.
        index: usize,
        /// The bad weight.
        weight: f64,
    },
    /// `theta` is negative or not finite.
    InvalidTheta(f64),
    /// `tolerance` is not positive and finite.
    InvalidTolerance(f64),
}

impl fmt::Display for ForceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::EdgeOutOfRange { index, source, target, node_count } => write!(
                f,
                "edge {index} ({source} -> {target}) names a node outside 0..{node_count}; \
                 node indices must be below the node count"
            ),
            Self::WeightCountMismatch { weights, edges } => {
                write!(f, "{weights} weights for {edges} edges; give one weight per edge or none")
            }
            Self::InvalidWeight { index, weight } => {
                write!(f, "edge {index} has weight {weight}; weights must be finite and at least 0")
            }
            Self::InvalidTheta(theta) => write!(f, "theta is {theta}; use a finite value of at least 0 (0.9 is usual)"),
            Self::InvalidTolerance(tol) => {
                write!(f, "tolerance is {tol}; use a finite value above 0 (0.03 is usual)")
            }
        }
    }
}

impl std::error::Error for ForceError {}

/// Lays out an undirected graph of `node_count` nodes with the given edges (node index pairs)
/// and optional non-negative edge weights (stronger edges pull their ends closer; weight 0
/// drops the edge). Returns one position per node: finite, typical edge length about 1,
/// components packed side by side, bit-identical for the same input and seed (whatever the
/// number of rayon threads). No nodes give an empty list and one node sits at the origin.
///
/// Fails, naming the culprit, on an edge endpoint `>= node_count`, a weight list of the wrong
/// length, a negative or non-finite weight, or a bad `theta` or `tolerance`.
pub fn force_layout(
    node_count: usize,
    edges: &[(u32, u32)],
    weights: Option<&[f64]>,
    options: &ForceOptions,
) -> Result<Vec<[f64; 2]>, ForceError> {
    check_options(options)?;
    let merged = merge_edges(node_count, edges, weights)?;
    let whole = Level::new(node_count, &merged, vec![1.0; node_count]);
    let components = connected_components(&whole);
    let layouts: Vec<Vec<[f64; 2]>> = components
        .par_iter()
        .enumerate()
        .map(|(k, nodes)| {
            let sub = whole.induced(nodes);
            let mut positions = layout_connected(&sub, mix_seed(options.seed, k as u64), options);
            normalize(&mut positions, &sub);
            positions
        })
        .collect();
    Ok(pack(node_count, &components, &layouts))
}

fn check_options(options: &ForceOptions) -> Result<(), ForceError> {
    if !(options.theta.is_finite() && options.theta >= 0.0) {
        return Err(ForceError::InvalidTheta(options.theta));
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(ForceError::InvalidTolerance(options.tolerance));
    }
    Ok(())
}

/// Checks the edges and weights and returns the simple graph's edges `(u, v, weight)` with
/// `u < v`, sorted, multi-edges merged (weights added), self-loops and weight-0 edges dropped.
fn merge_edges(
    node_count: usize,
    edges: &[(u32, u32)],
    weights: Option<&[f64]>,
) -> Result<Vec<(u32, u32, f64)>, ForceError> {
    if let Some(w) = weights
        && w.len() != edges.len()
    {
        return Err(ForceError::WeightCountMismatch { weights: w.len(), edges: edges.len() });
    }
    let mut list = Vec::with_capacity(edges.len());
    for (index, &(source, target)) in edges.iter().enumerate() {
        if source as usize >= node_count || target as usize >= node_count {
            return Err(ForceError::EdgeOutOfRange { index, source, target, node_count });
        }
        let weight = weights.and_then(|w| w.get(index).copied()).unwrap_or(1.0);
        if !(weight.is_finite() && weight >= 0.0) {
            return Err(ForceError::InvalidWeight { index, weight });
        }
        if source != target && weight > 0.0 {
            list.push((source.min(target), source.max(target), weight));
        }
    }
    list.sort_by_key(|&(u, v, _)| (u, v));
    let mut merged: Vec<(u32, u32, f64)> = Vec::with_capacity(list.len());
    for (u, v, w) in list {
        match merged.last_mut() {
            Some(last) if last.0 == u && last.1 == v => last.2 += w,
            _ => merged.push((u, v, w)),
        }
    }
    Ok(merged)
}

/// One level of the multilevel hierarchy: a simple undirected graph in adjacency-list form.
#[derive(Clone, Debug)]
struct Level {
    /// Neighbours of node `i` are `links[offsets[i]..offsets[i + 1]]`.
    offsets: Vec<usize>,
    links: Vec<Link>,
    /// Number of original nodes each node stands for.
    node_weight: Vec<f64>,
    /// Repulsion charge of each node.
    charge: Vec<f64>,
}

/// One direction of an edge.
#[derive(Clone, Copy, Debug)]
struct Link {
    target: u32,
    /// Spring strength (the user's weight, averaged over collapsed edges).
    strength: f64,
    /// Number of original edges collapsed into this one.
    multiplicity: f64,
}

impl Level {
    /// Builds a graph from sorted, distinct `(u, v, weight)` edges with `u < v < n`.
    fn new(n: usize, edges: &[(u32, u32, f64)], node_weight: Vec<f64>) -> Self {
        let with_counts: Vec<(u32, u32, f64, f64)> = edges.iter().map(|&(u, v, w)| (u, v, w, 1.0)).collect();
        Self::with_multiplicity(n, &with_counts, node_weight)
    }

    /// Builds a graph from sorted, distinct `(u, v, strength, multiplicity)` edges.
    fn with_multiplicity(n: usize, edges: &[(u32, u32, f64, f64)], node_weight: Vec<f64>) -> Self {
        let mut offsets = vec![0usize; n + 1];
        for &(u, v, _, _) in edges {
            for end in [u, v] {
                if let Some(c) = offsets.get_mut(end as usize + 1) {
                    *c += 1;
                }
            }
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut next = offsets.clone();
        let placeholder = Link { target: NONE, strength: 0.0, multiplicity: 0.0 };
        let mut links = vec![placeholder; offsets[n]];
        for &(u, v, strength, multiplicity) in edges {
            for (from, to) in [(u, v), (v, u)] {
                if let Some(slot) = next.get_mut(from as usize)
                    && let Some(link) = links.get_mut(*slot)
                {
                    *link = Link { target: to, strength, multiplicity };
                    *slot += 1;
                }
            }
        }
        let mut level = Level { offsets, links, node_weight, charge: Vec::new() };
        level.charge = level.charges();
        level
    }

    /// Repulsion charges as in ForceAtlas2: 1 + degree (at coarser levels, 1 + the number of
    /// original edges leaving the group per original node), scaled to mean 1.
    fn charges(&self) -> Vec<f64> {
        let n = self.len();
        let raw: Vec<f64> = (0..n)
            .map(|i| {
                let leaving: f64 = self.neighbours(i).iter().map(|l| l.multiplicity).sum();
                1.0 + leaving / self.node_weight.get(i).copied().unwrap_or(1.0).max(1.0)
            })
            .collect();
        let mean = raw.iter().sum::<f64>() / n.max(1) as f64;
        raw.iter().map(|r| r / mean).collect()
    }

    fn len(&self) -> usize {
        self.node_weight.len()
    }

    fn neighbours(&self, i: usize) -> &[Link] {
        match (self.offsets.get(i), self.offsets.get(i + 1)) {
            (Some(&a), Some(&b)) => self.links.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }

    /// The subgraph on `nodes` (sorted ascending), renumbered `0..nodes.len()`.
    fn induced(&self, nodes: &[u32]) -> Level {
        let local = |g: u32| nodes.binary_search(&g).ok().map(|k| k as u32);
        let mut edges = Vec::new();
        for (a, &g) in nodes.iter().enumerate() {
            for link in self.neighbours(g as usize) {
                if let Some(b) = local(link.target)
                    && (a as u32) < b
                {
                    edges.push((a as u32, b, link.strength, link.multiplicity));
                }
            }
        }
        edges.sort_by_key(|&(a, b, _, _)| (a, b));
        Level::with_multiplicity(nodes.len(), &edges, vec![1.0; nodes.len()])
    }
}

/// Connected components, each a sorted node list, largest first (ties: smallest node first).
fn connected_components(graph: &Level) -> Vec<Vec<u32>> {
    let n = graph.len();
    let mut seen = vec![false; n];
    let mut components = Vec::new();
    let mut queue = Vec::new();
    for start in 0..n {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        queue.clear();
        queue.push(start as u32);
        let mut head = 0;
        while let Some(&u) = queue.get(head) {
            head += 1;
            for link in graph.neighbours(u as usize) {
                if let Some(s) = seen.get_mut(link.target as usize)
                    && !*s
                {
                    *s = true;
                    queue.push(link.target);
                }
            }
        }
        let mut nodes = queue.clone();
        nodes.sort_unstable();
        components.push(nodes);
    }
    components.sort_by_key(|c| std::cmp::Reverse(c.len()));
    components
}

fn mix_seed(seed: u64, salt: u64) -> u64 {
    mix64(seed ^ mix64(salt.wrapping_add(0x632b_e59b_d9b4_e019)))
}

/// Lays out one connected graph with the multilevel scheme; positions in model units.
fn layout_connected(graph: &Level, seed: u64, options: &ForceOptions) -> Vec<[f64; 2]> {
    let n = graph.len();
    if n <= 1 {
        return vec![[0.0, 0.0]; n];
    }
    let mut rng = Rng(seed);
    let (coarser, maps) = if options.multilevel { coarsen_all(graph, &mut rng) } else { (Vec::new(), Vec::new()) };
    let coarsest = coarser.last().unwrap_or(graph);
    let side = (coarsest.len() as f64).sqrt() * K;
    let mut positions: Vec<[f64; 2]> =
        (0..coarsest.len()).map(|_| [side * rng.uniform(), side * rng.uniform()]).collect();
    refine(coarsest, &mut positions, options, seed);
    for k in (0..maps.len()).rev() {
        let fine = if k == 0 { graph } else { coarser.get(k - 1).unwrap_or(graph) };
        positions = prolong(&positions, maps.get(k).map_or(&[][..], |m| &m[..]), &mut rng);
        refine(fine, &mut positions, options, seed);
    }
    positions
}

/// Coarsens until [`COARSEST`] nodes or until coarsening stalls. Returns the coarser graphs
/// (finest first) and for each step the map from finer to coarser node.
fn coarsen_all(graph: &Level, rng: &mut Rng) -> (Vec<Level>, Vec<Vec<u32>>) {
    let mut levels: Vec<Level> = Vec::new();
    let mut maps = Vec::new();
    while levels.len() < MAX_LEVELS {
        let current = levels.last().unwrap_or(graph);
        if current.len() <= COARSEST {
            break;
        }
        let Some((coarse, map)) = coarsen(current, rng) else { break };
        levels.push(coarse);
        maps.push(map);
    }
    (levels, maps)
}

/// One round of heavy-edge plus two-hop matching; `None` when it would remove under a tenth of
/// the nodes.
fn coarsen(graph: &Level, rng: &mut Rng) -> Option<(Level, Vec<u32>)> {
    let n = graph.len();
    let order = rng.permutation(n);
    let mut mate = vec![NONE; n];
    for &u in &order {
        if mate.get(u as usize) != Some(&NONE) {
            continue;
        }
        if let Some(v) = best_mate(graph, u, &mate) {
            mate[u as usize] = v;
            mate[v as usize] = u;
        }
    }
    for &hub in &order {
        let mut pending = NONE;
        for link in graph.neighbours(hub as usize) {
            let v = link.target;
            if mate.get(v as usize) != Some(&NONE) {
                continue;
            }
            if pending == NONE {
                pending = v;
            } else {
                mate[pending as usize] = v;
                mate[v as usize] = pending;
                pending = NONE;
            }
        }
    }
    let mut map = vec![NONE; n];
    let mut coarse_n = 0u32;
    for u in 0..n {
        if map[u] != NONE {
            continue;
        }
        map[u] = coarse_n;
        if let Some(slot) = map.get_mut(mate[u] as usize) {
            *slot = coarse_n;
        }
        coarse_n += 1;
    }
    if coarse_n as usize * 10 > n * 9 {
        return None;
    }
    Some((collapse(graph, &map, coarse_n as usize), map))
}

/// The unmatched neighbour of `u` standing for the fewest original nodes (ties: most collapsed
/// edges, then first in adjacency order).
fn best_mate(graph: &Level, u: u32, mate: &[u32]) -> Option<u32> {
    let mut best: Option<(u32, f64, f64)> = None;
    for link in graph.neighbours(u as usize) {
        let v = link.target;
        if v == u || mate.get(v as usize) != Some(&NONE) {
            continue;
        }
        let weight = graph.node_weight.get(v as usize).copied().unwrap_or(1.0);
        let better = match best {
            None => true,
            Some((_, w, m)) => weight < w || (weight == w && link.multiplicity > m),
        };
        if better {
            best = Some((v, weight, link.multiplicity));
        }
    }
    best.map(|(v, _, _)| v)
}

/// The coarse graph whose nodes are the groups of `map`: parallel edges merged (strengths
/// averaged by multiplicity), edges inside a group dropped.
fn collapse(graph: &Level, map: &[u32], coarse_n: usize) -> Level {
    let mut node_weight = vec![0.0; coarse_n];
    let mut edges = Vec::with_capacity(graph.links.len() / 2);
    for u in 0..graph.len() {
        let cu = map.get(u).copied().unwrap_or(NONE);
        if let Some(w) = node_weight.get_mut(cu as usize) {
            *w += graph.node_weight.get(u).copied().unwrap_or(1.0);
        }
        for link in graph.neighbours(u) {
            let cv = map.get(link.target as usize).copied().unwrap_or(NONE);
            if (u as u32) < link.target && cu != cv && cu != NONE && cv != NONE {
                edges.push((cu.min(cv), cu.max(cv), link.strength * link.multiplicity, link.multiplicity));
            }
        }
    }
    edges.sort_by_key(|&(a, b, _, _)| (a, b));
    let mut merged: Vec<(u32, u32, f64, f64)> = Vec::with_capacity(edges.len());
    for (a, b, sm, m) in edges {
        match merged.last_mut() {
            Some(last) if last.0 == a && last.1 == b => {
                last.2 += sm;
                last.3 += m;
            }
            _ => merged.push((a, b, sm, m)),
        }
    }
    for e in &mut merged {
        e.2 /= e.3;
    }
    Level::with_multiplicity(coarse_n, &merged, node_weight)
}

/// Positions of the finer level: each node starts at its group's position, spread by the square
/// root of the node-count ratio (clamped to [1, 2]), plus a seeded jitter.
fn prolong(coarse: &[[f64; 2]], map: &[u32], rng: &mut Rng) -> Vec<[f64; 2]> {
    let ratio = map.len() as f64 / coarse.len().max(1) as f64;
    let spread = ratio.sqrt().clamp(1.0, 2.0);
    let jitter = JITTER * node_spacing(coarse) * spread / ratio.sqrt().max(1.0);
    map.iter()
        .map(|&c| {
            let p = coarse.get(c as usize).copied().unwrap_or([0.0, 0.0]);
            let jx = jitter * (2.0 * rng.uniform() - 1.0);
            let jy = jitter * (2.0 * rng.uniform() - 1.0);
            [p[0] * spread + jx, p[1] * spread + jy]
        })
        .collect()
}

/// Hu's force-directed iteration with adaptive step on one level.
fn refine(graph: &Level, positions: &mut [[f64; 2]], options: &ForceOptions, seed: u64) {
    let unit = node_spacing(positions).max(MIN_DISTANCE);
    let mut step = INITIAL_STEP * unit;
    let unit_force = REPULSION * K * K / unit;
    let mut energy = f64::INFINITY;
    let mut progress = 0u32;
    for _ in 0..options.iterations {
        let tree = QuadTree::with_masses(positions, &graph.charge);
        let forces = all_forces(graph, positions, &tree, options.theta, seed);
        let new_energy = move_nodes(positions, &forces, step, unit_force);
        if new_energy < energy {
            progress += 1;
            if progress >= 5 {
                progress = 0;
                step /= COOLING;
            }
        } else {
            progress = 0;
            step *= COOLING;
        }
        energy = new_energy;
        if step < options.tolerance * unit {
            break;
        }
    }
}

/// Moves each node `step` along its force, or proportionally less when the force is below both
/// the median force magnitude and `unit_force` (so nodes near equilibrium settle instead of
/// jittering); returns the energy (sum of squared forces).
fn move_nodes(positions: &mut [[f64; 2]], forces: &[[f64; 2]], step: f64, unit_force: f64) -> f64 {
    let magnitudes: Vec<f64> = forces.iter().map(|f| (f[0] * f[0] + f[1] * f[1]).sqrt()).collect();
    let energy: f64 = magnitudes.iter().filter(|m| m.is_finite()).map(|m| m * m).sum();
    let reference = median(&mut magnitudes.clone()).unwrap_or(0.0).max(unit_force);
    for ((p, f), &m) in positions.iter_mut().zip(forces).zip(&magnitudes) {
        if m > 0.0 && m.is_finite() {
            let scale = step / m.max(reference);
            p[0] += f[0] * scale;
            p[1] += f[1] * scale;
        }
    }
    energy
}

/// Total force on every node (springs plus Barnes–Hut repulsion), each computed independently.
fn all_forces(graph: &Level, positions: &[[f64; 2]], tree: &QuadTree, theta: f64, seed: u64) -> Vec<[f64; 2]> {
    let reach = SPRING_REACH * node_spacing(positions);
    let force = |i: usize| {
        let a = attraction(graph, positions, i, reach);
        let r = repulsion(tree, positions, i, theta, seed);
        let q = graph.charge.get(i).copied().unwrap_or(1.0);
        [a[0] + q * r[0], a[1] + q * r[1]]
    };
    if positions.len() >= PARALLEL_MIN {
        (0..positions.len()).into_par_iter().map(force).collect()
    } else {
        (0..positions.len()).map(force).collect()
    }
}

/// Typical distance between neighbouring nodes: the square root of the area per node, the area
/// taken as that of the ellipse of the positions' covariance (4π·√det).
fn node_spacing(positions: &[[f64; 2]]) -> f64 {
    let n = positions.len().max(1) as f64;
    let mean = positions.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for p in positions {
        let (x, y) = (p[0] - mean[0], p[1] - mean[1]);
        sxx += x * x / n;
        syy += y * y / n;
        sxy += x * y / n;
    }
    let det = (sxx * syy - sxy * sxy).max(0.0);
    let planar = (4.0 * std::f64::consts::PI * det.sqrt() / n).sqrt();
    let linear = (12.0 * (sxx + syy)).sqrt() / n;
    planar.max(linear)
}

/// Spring pull on node `i` towards each neighbour ([`spring_magnitude`]).
fn attraction(graph: &Level, positions: &[[f64; 2]], i: usize, reach: f64) -> [f64; 2] {
    let Some(&p) = positions.get(i) else { return [0.0, 0.0] };
    let mut f = [0.0, 0.0];
    for link in graph.neighbours(i) {
        let Some(&q) = positions.get(link.target as usize) else { continue };
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let d = (dx * dx + dy * dy).sqrt();
        if d > 0.0 {
            let s = spring_magnitude(link.strength, d, reach) / d;
            f[0] += s * dx;
            f[1] += s * dy;
        }
    }
    f
}

/// Spring force of strength `strength` at length `d`: `strength·d²/K` up to `reach`, growing as
/// `√d` beyond (continuously).
fn spring_magnitude(strength: f64, d: f64, reach: f64) -> f64 {
    if d <= reach { strength * d * d / K } else { strength * reach * (reach * d).sqrt() / K }
}

/// Electrical push on node `i`: `C·K²/d` away from every other node (far groups approximated).
/// Coincident nodes push each other apart along a direction fixed by the pair and the seed.
fn repulsion(tree: &QuadTree, positions: &[[f64; 2]], i: usize, theta: f64, seed: u64) -> [f64; 2] {
    let Some(&p) = positions.get(i) else { return [0.0, 0.0] };
    let c = REPULSION * K * K;
    let mut f = [0.0, 0.0];
    tree.visit(p, Some(i), theta, |body| {
        let (q, mass, j) = match body {
            Body::Point { index, position, mass } => (position, mass, index),
            Body::Cell { centre, mass } => (centre, mass, usize::MAX),
        };
        let (dx, dy) = (p[0] - q[0], p[1] - q[1]);
        let d2 = dx * dx + dy * dy;
        if d2 > MIN_DISTANCE * MIN_DISTANCE {
            let s = mass * c / d2;
            f[0] += s * dx;
            f[1] += s * dy;
        } else {
            // Only single points come this close (the tree never approximates a cell at distance 0).
            let u = pair_direction(i, j, seed);
            f[0] += mass * c * u[0] / MIN_DISTANCE;
            f[1] += mass * c * u[1] / MIN_DISTANCE;
        }
    });
    f
}

/// A unit vector fixed by the unordered pair `{i, j}` and the seed, pointing one way for the
/// smaller index and the opposite way for the larger.
fn pair_direction(i: usize, j: usize, seed: u64) -> [f64; 2] {
    let (a, b) = (i.min(j) as u64, i.max(j) as u64);
    let h = mix64(seed ^ mix64(a.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ b));
    let angle = (h >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU;
    let sign = if i < j { 1.0 } else { -1.0 };
    [sign * angle.cos(), sign * angle.sin()]
}

/// Centres the layout, turns its principal axis horizontal and scales its median edge length
/// to 1 (layouts without edges keep their scale).
fn normalize(positions: &mut [[f64; 2]], graph: &Level) {
    let n = positions.len().max(1) as f64;
    let mean = positions.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for p in positions.iter() {
        let (x, y) = (p[0] - mean[0], p[1] - mean[1]);
        sxx += x * x;
        syy += y * y;
        sxy += x * y;
    }
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let (sin, cos) = (-angle).sin_cos();
    let mut lengths: Vec<f64> = Vec::with_capacity(graph.links.len() / 2);
    for u in 0..graph.len() {
        for link in graph.neighbours(u) {
            if (u as u32) < link.target
                && let (Some(p), Some(q)) = (positions.get(u), positions.get(link.target as usize))
            {
                lengths.push(((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt());
            }
        }
    }
    let scale = match median(&mut lengths) {
        Some(m) if m > 0.0 && m.is_finite() => 1.0 / m,
        _ => 1.0,
    };
    for p in positions.iter_mut() {
        let (x, y) = (p[0] - mean[0], p[1] - mean[1]);
        *p = [(x * cos - y * sin) * scale, (x * sin + y * cos) * scale];
    }
}

/// The lower median, or `None` for an empty list.
fn median(values: &mut [f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let mid = (values.len() - 1) / 2;
    let (_, m, _) = values.select_nth_unstable_by(mid, f64::total_cmp);
    Some(*m)
}

/// Places the components (already largest first) in rows of a roughly square arrangement, a
/// gap of [`PACKING_GAP`] between bounding boxes, and centres the whole on the origin.
fn pack(node_count: usize, components: &[Vec<u32>], layouts: &[Vec<[f64; 2]>]) -> Vec<[f64; 2]> {
    let boxes: Vec<([f64; 2], [f64; 2])> = layouts.iter().map(|l| bounding_box(l)).collect();
    let area: f64 = boxes.iter().map(|(lo, hi)| (hi[0] - lo[0] + PACKING_GAP) * (hi[1] - lo[1] + PACKING_GAP)).sum();
    let widest = boxes.iter().map(|(lo, hi)| hi[0] - lo[0] + PACKING_GAP).fold(0.0, f64::max);
    let row_width = area.sqrt().max(widest);
    let (mut x, mut y, mut row_height) = (0.0f64, 0.0f64, 0.0f64);
    let mut out = vec![[0.0, 0.0]; node_count];
    let mut overall = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for ((nodes, layout), (lo, hi)) in components.iter().zip(layouts).zip(&boxes) {
        let (w, h) = (hi[0] - lo[0] + PACKING_GAP, hi[1] - lo[1] + PACKING_GAP);
        if x > 0.0 && x + w > row_width {
            x = 0.0;
            y -= row_height;
            row_height = 0.0;
        }
        let shift = [x - lo[0], y - hi[1]];
        for (&node, p) in nodes.iter().zip(layout) {
            if let Some(slot) = out.get_mut(node as usize) {
                let q = [p[0] + shift[0], p[1] + shift[1]];
                *slot = q;
                overall.0 = [overall.0[0].min(q[0]), overall.0[1].min(q[1])];
                overall.1 = [overall.1[0].max(q[0]), overall.1[1].max(q[1])];
            }
        }
        x += w;
        row_height = row_height.max(h);
    }
    if node_count > 0 {
        let centre = [0.5 * (overall.0[0] + overall.1[0]), 0.5 * (overall.0[1] + overall.1[1])];
        for p in &mut out {
            *p = [p[0] - centre[0], p[1] - centre[1]];
        }
    }
    out
}

fn bounding_box(points: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if points.is_empty() { ([0.0; 2], [0.0; 2]) } else { (lo, hi) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::quality::{edge_crossings, normalized_stress};

    fn layout(n: usize, edges: &[(u32, u32)]) -> Vec<[f64; 2]> {
        force_layout(n, edges, None, &ForceOptions::default()).expect("valid input")
    }

    fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
    }

    fn grid_edges(w: u32, h: u32) -> Vec<(u32, u32)> {
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
        edges
    }

    fn random_edges(n: u32, m: usize, seed: u64) -> Vec<(u32, u32)> {
        let mut rng = Rng(seed);
        let mut edges = Vec::with_capacity(m);
        while edges.len() < m {
            let (s, t) = ((rng.next_u64() % n as u64) as u32, (rng.next_u64() % n as u64) as u32);
            if s != t {
                edges.push((s, t));
            }
        }
        edges
    }

    fn bounding_box_of(positions: &[[f64; 2]], nodes: std::ops::Range<usize>) -> ([f64; 2], [f64; 2]) {
        bounding_box(&positions[nodes])
    }

    #[test]
    fn empty_and_single_node_graphs() {
        assert_eq!(layout(0, &[]), Vec::<[f64; 2]>::new());
        assert_eq!(layout(1, &[]), vec![[0.0, 0.0]]);
        assert_eq!(layout(1, &[(0, 0), (0, 0)]), vec![[0.0, 0.0]]);
    }

    #[test]
    fn path_of_three_is_straight_with_unit_edges() {
        let p = layout(3, &[(0, 1), (1, 2)]);
        let (a, b) = (distance(p[0], p[1]), distance(p[1], p[2]));
        assert!((a - b).abs() < 0.02 * a, "edges {a} and {b}");
        assert!((a.min(b) - 1.0).abs() < 1e-9, "median edge length {}", a.min(b));
        assert!(distance(p[0], p[2]) > 0.999 * (a + b), "bent path {p:?}");
    }

    #[test]
    fn cycle_of_twelve_is_nearly_a_circle() {
        let edges: Vec<(u32, u32)> = (0..12).map(|i| (i, (i + 1) % 12)).collect();
        let p = layout(12, &edges);
        let centre = p.iter().fold([0.0, 0.0], |c, q| [c[0] + q[0] / 12.0, c[1] + q[1] / 12.0]);
        let radii: Vec<f64> = p.iter().map(|&q| distance(q, centre)).collect();
        let (lo, hi) = radii.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
        assert!(hi < 1.1 * lo, "radii from {lo} to {hi}");
        assert_eq!(edge_crossings(&p, &edges), Ok(0));
    }

    #[test]
    fn grid_graph_is_untangled_with_low_stress() {
        let edges = grid_edges(10, 10);
        let p = layout(100, &edges);
        let crossings = edge_crossings(&p, &edges).expect("valid");
        let stress = normalized_stress(&p, 100, &edges).expect("valid");
        assert_eq!(crossings, 0);
        assert!(stress < 0.04, "stress {stress}");
    }

    #[test]
    fn deterministic_for_a_seed_whatever_the_thread_count() {
        let edges = random_edges(1500, 4000, 7);
        let options = ForceOptions { seed: 42, ..ForceOptions::default() };
        let run = |threads: usize, options: &ForceOptions| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a pool");
            pool.install(|| force_layout(1500, &edges, None, options).expect("valid"))
        };
        let one = run(1, &options);
        let two = run(2, &options);
        assert!(
            one.iter().zip(&two).all(|(a, b)| a[0].to_bits() == b[0].to_bits() && a[1].to_bits() == b[1].to_bits())
        );
        assert!(one.iter().all(|p| p[0].is_finite() && p[1].is_finite()));
        let other = run(2, &ForceOptions { seed: 43, ..options.clone() });
        assert!(one.iter().zip(&other).any(|(a, b)| a != b));
    }

    #[test]
    fn components_are_packed_without_overlap_larger_first() {
        // A 4×4 grid (nodes 0..16), a 6-cycle (16..22), a triangle (22..25), an edge (25..27),
        // and three isolated nodes (27..30).
        let mut edges = grid_edges(4, 4);
        edges.extend((0..6).map(|i| (16 + i, 16 + (i + 1) % 6)));
        edges.extend([(22, 23), (23, 24), (24, 22), (25, 26)]);
        let p = layout(30, &edges);
        let groups = [0..16, 16..22, 22..25, 25..27, 27..28, 28..29, 29..30];
        let boxes: Vec<_> = groups.iter().map(|g| bounding_box_of(&p, g.clone())).collect();
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                let apart = a.1[0] < b.0[0] || b.1[0] < a.0[0] || a.1[1] < b.0[1] || b.1[1] < a.0[1];
                assert!(apart, "boxes {a:?} and {b:?} overlap");
            }
        }
        // The largest component comes first: top-left of the arrangement.
        let all = bounding_box(&p);
        assert!((boxes[0].0[0] - all.0[0]).abs() < 1e-9 && (boxes[0].1[1] - all.1[1]).abs() < 1e-9);
        let centre = [0.5 * (all.0[0] + all.1[0]), 0.5 * (all.0[1] + all.1[1])];
        assert!(centre[0].abs() < 1e-9 && centre[1].abs() < 1e-9, "not centred: {centre:?}");
    }

    #[test]
    fn many_equal_components_pack_roughly_square() {
        let edges: Vec<(u32, u32)> = (0..36).flat_map(|k| [(3 * k, 3 * k + 1), (3 * k + 1, 3 * k + 2)]).collect();
        let p = layout(108, &edges);
        let (lo, hi) = bounding_box(&p);
        let aspect = (hi[0] - lo[0]) / (hi[1] - lo[1]);
        assert!((0.5..2.0).contains(&aspect), "aspect {aspect}");
    }

    #[test]
    fn twins_and_multi_edges_never_coincide() {
        // K(2,40): forty nodes with the same two neighbours, every edge doubled.
        let mut edges = Vec::new();
        for v in 2..42 {
            edges.extend([(0, v), (1, v), (v, 0)]);
        }
        let p = layout(42, &edges);
        assert!(p.iter().all(|q| q[0].is_finite() && q[1].is_finite()));
        let mut closest = f64::INFINITY;
        for i in 0..42 {
            for j in i + 1..42 {
                closest = closest.min(distance(p[i], p[j]));
            }
        }
        assert!(closest > 0.05, "two nodes {closest} apart");
    }

    #[test]
    fn coincident_nodes_push_apart_in_opposite_seeded_directions() {
        let positions = [[2.0, 3.0], [2.0, 3.0]];
        let tree = QuadTree::new(&positions);
        let a = repulsion(&tree, &positions, 0, 0.9, 5);
        let b = repulsion(&tree, &positions, 1, 0.9, 5);
        assert!(a.iter().chain(&b).all(|v| v.is_finite()) && a != [0.0, 0.0]);
        assert_eq!(a, [-b[0], -b[1]]);
        assert_ne!(repulsion(&tree, &positions, 0, 0.9, 6), a, "the direction depends on the seed");
    }

    #[test]
    fn self_loops_and_duplicates_are_merged_like_weights() {
        let edges = grid_edges(3, 3);
        let base = layout(9, &edges);
        let mut with_loops = edges.clone();
        with_loops.extend([(4, 4), (0, 0)]);
        assert_eq!(layout(9, &with_loops), base);
        let doubled: Vec<(u32, u32)> = edges.iter().flat_map(|&(u, v)| [(u, v), (v, u)]).collect();
        let twice: Vec<f64> = vec![2.0; edges.len()];
        let options = ForceOptions::default();
        assert_eq!(force_layout(9, &doubled, None, &options), force_layout(9, &edges, Some(&twice), &options),);
    }

    #[test]
    fn heavier_edges_are_shorter_and_zero_weight_edges_are_dropped() {
        let p = force_layout(3, &[(0, 1), (1, 2), (2, 0)], Some(&[4.0, 1.0, 1.0]), &ForceOptions::default())
            .expect("valid");
        assert!(distance(p[0], p[1]) < 0.8 * distance(p[1], p[2]), "{p:?}");
        // The zero-weight middle edge splits the path 0-1-2-3 into two packed components.
        let q = force_layout(4, &[(0, 1), (1, 2), (2, 3)], Some(&[1.0, 0.0, 1.0]), &ForceOptions::default())
            .expect("valid");
        assert!((distance(q[0], q[1]) - 1.0).abs() < 1e-9 && (distance(q[2], q[3]) - 1.0).abs() < 1e-9);
        assert!(distance(q[1], q[2]) >= PACKING_GAP, "{q:?}");
    }

    #[test]
    fn large_random_graph_has_unit_median_edge_and_finite_positions() {
        let edges = random_edges(3000, 9000, 11);
        let p = layout(3000, &edges);
        assert!(p.iter().all(|q| q[0].is_finite() && q[1].is_finite()));
        let mut lengths: Vec<f64> = edges.iter().map(|&(u, v)| distance(p[u as usize], p[v as usize])).collect();
        lengths.sort_by(f64::total_cmp);
        let median = lengths[lengths.len() / 2];
        assert!((0.9..1.1).contains(&median), "median edge {median}");
    }

    #[test]
    fn node_spacing_and_spring_law_known_values() {
        // A 10×10 unit grid: variances (10² − 1)/12 = 8.25, area 4π·8.25, spacing √(area/100).
        let grid: Vec<[f64; 2]> = (0..100).map(|i| [(i % 10) as f64, (i / 10) as f64]).collect();
        let expected = (4.0 * std::f64::consts::PI * 8.25 / 100.0).sqrt();
        assert!((node_spacing(&grid) - expected).abs() < 1e-12);
        // Ten collinear points one apart: the one-dimensional estimate √(12·8.25)/10.
        let line: Vec<[f64; 2]> = (0..10).map(|i| [i as f64, 0.0]).collect();
        assert!((node_spacing(&line) - 99f64.sqrt() / 10.0).abs() < 1e-12);
        // d² up to the reach, then continuous and growing as √d.
        assert_eq!(spring_magnitude(2.0, 3.0, 8.0), 18.0);
        assert!((spring_magnitude(1.0, 8.0, 8.0) - 64.0).abs() < 1e-12);
        assert!((spring_magnitude(1.0, 32.0, 8.0) - 128.0).abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_rejected_with_the_culprit() {
        let options = ForceOptions::default();
        let err = force_layout(3, &[(0, 1), (1, 2), (2, 3)], None, &options).unwrap_err();
        assert_eq!(err, ForceError::EdgeOutOfRange { index: 2, source: 2, target: 3, node_count: 3 });
        assert!(err.to_string().contains("edge 2 (2 -> 3)"));
        assert_eq!(
            force_layout(3, &[(0, 1)], Some(&[1.0, 2.0]), &options),
            Err(ForceError::WeightCountMismatch { weights: 2, edges: 1 })
        );
        let err = force_layout(3, &[(0, 1), (1, 2)], Some(&[1.0, -0.5]), &options).unwrap_err();
        assert_eq!(err, ForceError::InvalidWeight { index: 1, weight: -0.5 });
        assert!(err.to_string().contains("-0.5"));
        let nan = force_layout(2, &[(0, 1)], Some(&[f64::NAN]), &options);
        assert!(matches!(nan, Err(ForceError::InvalidWeight { index: 0, weight }) if weight.is_nan()));
        let theta = ForceOptions { theta: -1.0, ..options.clone() };
        assert_eq!(force_layout(2, &[(0, 1)], None, &theta), Err(ForceError::InvalidTheta(-1.0)));
        let tolerance = ForceOptions { tolerance: 0.0, ..options };
        assert_eq!(force_layout(2, &[(0, 1)], None, &tolerance), Err(ForceError::InvalidTolerance(0.0)));
    }
}
