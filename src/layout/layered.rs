//! Layered drawing of directed graphs in the framework of Sugiyama, Tagawa & Toda (1981):
//! nodes sit on horizontal layers, edges point downwards, long edges bend once per layer they cross.
//!
//! The phases, in order:
//!
//! 1. **Cycle removal.** The greedy heuristic of Eades, Lin & Smyth (1993) orders the nodes
//!    (sinks to the back, sources to the front, otherwise the node with the largest weighted
//!    out-degree minus in-degree to the front; ties go to the smaller index). Edges that point
//!    backwards in that order form the feedback arc set and are drawn reversed. Self-loops are
//!    ignored; duplicate edges (and the two edges of a 2-cycle) share one drawn path, and their
//!    multiplicity weights the degrees.
//! 2. **Layer assignment.** Longest path from the sources, then edge shortening: each node with
//!    more outgoing than incoming edges moves down as far as its successors allow, each with more
//!    incoming than outgoing moves up as far as its predecessors allow. Every move shortens the
//!    total edge span, so the passes (at most [`SHORTEN_PASSES`]) stop. This is the single-node
//!    move of network simplex, without its tree exchanges. Each connected component then starts
//!    at layer 0.
//! 3. **Dummy nodes** subdivide every edge spanning several layers, so that all segments join
//!    adjacent layers.
//! 4. **Crossing reduction.** A depth-first initial order, then sweeps alternating downwards and
//!    upwards; each sweep sorts every layer by the barycenter of its neighbours in the previous
//!    layer (nodes without such neighbours keep their slot; ties keep the current order), then
//!    swaps adjacent nodes while that removes crossings (the transposition step of Gansner,
//!    Koutsofios, North & Vo 1993). Crossings are counted exactly after each sweep with the
//!    accumulator method of Barth, Jünger & Mutzel (2002), and the best ordering found is kept.
//! 5. **Coordinate assignment** after Brandes & Köpf (2001): segments between dummies are
//!    preferred (type-1 conflicts), four vertical alignments to the median neighbours (up/down,
//!    left/right) are compacted, aligned to the narrowest, and each node takes the mean of its two
//!    median candidates. Compaction runs as a longest path over the graph of blocks followed by a
//!    pull towards right-hand neighbours, which sidesteps the class-shifting flaws described by
//!    Brandes, Walter & Zink (2020). Coordinates are whole multiples of half the node gap, so
//!    neighbours in a layer are at least `node_gap` apart, and long edges run straight between
//!    their first and last bend wherever no other long edge is in the way.
//!
//! Connected components are laid out separately (in order of their smallest node index) and
//! placed side by side, `node_gap` apart. Coordinates: x grows to the right, y downwards, layer 0
//! at y = 0.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};
use std::fmt;

/// Largest number of nodes plus dummy nodes that [`layered_layout`] accepts.
pub const MAX_LAYOUT_NODES: usize = 200_000;
/// Largest number of crossing-reduction sweeps accepted in [`LayeredOptions::sweeps`].
pub const MAX_SWEEPS: u32 = 10_000;
/// Cap on the passes of the edge-shortening step of the layer assignment.
pub const SHORTEN_PASSES: usize = 64;
/// Cap on the rounds of adjacent swaps after each crossing-reduction sweep.
const TRANSPOSE_ROUNDS: usize = 8;

/// Settings for [`layered_layout`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayeredOptions {
    /// Vertical distance between consecutive layers (finite, > 0). Default 1.
    pub layer_gap: f64,
    /// Smallest horizontal distance between neighbours in a layer, dummy nodes included
    /// (finite, > 0). Default 1.
    pub node_gap: f64,
    /// Crossing-reduction sweeps, alternating downwards and upwards (at most [`MAX_SWEEPS`]);
    /// 0 keeps the depth-first initial order. Default 24.
    pub sweeps: u32,
}

impl Default for LayeredOptions {
    fn default() -> Self {
        Self { layer_gap: 1.0, node_gap: 1.0, sweeps: 24 }
    }
}

/// A layered drawing. Node and edge indices are those of the input.
#[derive(Clone, Debug, PartialEq)]
pub struct Layered {
    /// Position of each node: x across the layer, y = layer × `layer_gap` (downwards).
    pub positions: Vec<[f64; 2]>,
    /// Layer of each node (0 at the top of its component).
    pub layers: Vec<u32>,
    /// One polyline per input edge: source position, one bend per layer crossed, target
    /// position. Empty for self-loops. Duplicate edges get identical paths.
    pub edge_paths: Vec<Vec<[f64; 2]>>,
    /// Per input edge: true when it was reversed to break a cycle (its path points up).
    pub reversed: Vec<bool>,
    /// Crossings between segments joining adjacent layers in the final ordering (edges that
    /// share a drawn path count once).
    pub crossings: usize,
}

/// Why [`layered_layout`] refused its input.
#[derive(Clone, Debug, PartialEq)]
pub enum LayeredError {
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
    /// `layer_gap` or `node_gap` is not a finite positive number.
    BadGap {
        /// Which option.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// More sweeps than [`MAX_SWEEPS`].
    TooManySweeps(u32),
    /// Nodes plus dummy nodes exceed [`MAX_LAYOUT_NODES`].
    TooLarge {
        /// Nodes of the input.
        nodes: usize,
        /// Dummy nodes that long edges need (0 when the nodes alone are too many).
        dummies: usize,
    },
}

impl fmt::Display for LayeredError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::EdgeOutOfRange { edge, source, target, node_count } => write!(
                f,
                "edge {edge} ({source} -> {target}) names a node outside 0..{node_count}; \
                 use node indices below the node count"
            ),
            Self::BadGap { name, value } => {
                write!(f, "{name} is {value}; it must be a finite number greater than 0")
            }
            Self::TooManySweeps(sweeps) => {
                write!(f, "sweeps is {sweeps}; at most {MAX_SWEEPS} crossing-reduction sweeps are supported")
            }
            Self::TooLarge { nodes, dummies } => write!(
                f,
                "the layered drawing needs {nodes} nodes + {dummies} dummy nodes = {}, more than the limit \
                 of {MAX_LAYOUT_NODES}; draw fewer nodes, or a graph with shorter edges",
                nodes + dummies
            ),
        }
    }
}

impl std::error::Error for LayeredError {}

/// Lays out a directed graph on layers. `edges` are `(source, target)` node indices; cycles are
/// broken by reversing a small set of edges (reported in [`Layered::reversed`]). No nodes give an
/// empty drawing.
pub fn layered_layout(
    node_count: usize,
    edges: &[(u32, u32)],
    options: &LayeredOptions,
) -> Result<Layered, LayeredError> {
    validate(node_count, edges, options)?;
    let arcs = weighted_arcs(edges);
    let rank = greedy_fas_rank(node_count, &arcs);
    let oriented = orient_arcs(&arcs, &rank);
    let component = components(node_count, &oriented);
    let layer = assign_layers(node_count, &oriented, &rank, &component);
    let proper = ProperGraph::build(node_count, &oriented, &layer, &component)?;
    let mut drawing = Drawing::new(proper.vertex_count());
    let mut crossings = 0u64;
    for members in proper.component_members() {
        let mut layers = initial_order(&proper, &members, &mut drawing.pos);
        crossings += reduce_crossings(&proper, &mut layers, &mut drawing.pos, options.sweeps);
        drawing.place_component(&proper, &layers);
    }
    Ok(assemble(edges, &rank, &oriented, &proper, &drawing, options, crossings))
}

/// Checks options and edge endpoints.
fn validate(node_count: usize, edges: &[(u32, u32)], options: &LayeredOptions) -> Result<(), LayeredError> {
    for (name, value) in [("layer_gap", options.layer_gap), ("node_gap", options.node_gap)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(LayeredError::BadGap { name, value });
        }
    }
    if options.sweeps > MAX_SWEEPS {
        return Err(LayeredError::TooManySweeps(options.sweeps));
    }
    if node_count > MAX_LAYOUT_NODES {
        return Err(LayeredError::TooLarge { nodes: node_count, dummies: 0 });
    }
    for (edge, &(source, target)) in edges.iter().enumerate() {
        if source as usize >= node_count || target as usize >= node_count {
            return Err(LayeredError::EdgeOutOfRange { edge, source, target, node_count });
        }
    }
    Ok(())
}

/// Distinct directed pairs `(u, v)`, `u != v`, sorted, with their multiplicity.
fn weighted_arcs(edges: &[(u32, u32)]) -> Vec<(u32, u32, u64)> {
    let mut pairs: Vec<(u32, u32)> = edges.iter().copied().filter(|&(u, v)| u != v).collect();
    pairs.sort_unstable();
    let mut arcs: Vec<(u32, u32, u64)> = Vec::with_capacity(pairs.len());
    for (u, v) in pairs {
        match arcs.last_mut() {
            Some(last) if last.0 == u && last.1 == v => last.2 += 1,
            _ => arcs.push((u, v, 1)),
        }
    }
    arcs
}

/// Compressed adjacency: the neighbours of `v` are `items[offsets[v]..offsets[v + 1]]`, in the
/// order the pairs were given; `tags` carries one number per item (a weight or a segment id).
struct Csr {
    offsets: Vec<usize>,
    items: Vec<u32>,
    tags: Vec<u64>,
}

impl Csr {
    /// Builds from `(from, to, tag)` triples over `n` vertices.
    fn build(n: usize, triples: impl Iterator<Item = (u32, u32, u64)> + Clone) -> Self {
        let mut offsets = vec![0usize; n + 1];
        for (from, _, _) in triples.clone() {
            offsets[from as usize + 1] += 1;
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let total = offsets[n];
        let mut fill = offsets.clone();
        let mut items = vec![0u32; total];
        let mut tags = vec![0u64; total];
        for (from, to, tag) in triples {
            let slot = &mut fill[from as usize];
            items[*slot] = to;
            tags[*slot] = tag;
            *slot += 1;
        }
        Self { offsets, items, tags }
    }

    /// Neighbours of `v`.
    fn of(&self, v: u32) -> &[u32] {
        &self.items[self.offsets[v as usize]..self.offsets[v as usize + 1]]
    }

    /// Neighbours of `v` with their tags.
    fn tagged(&self, v: u32) -> impl Iterator<Item = (u32, u64)> + '_ {
        let range = self.offsets[v as usize]..self.offsets[v as usize + 1];
        self.items[range.clone()].iter().copied().zip(self.tags[range].iter().copied())
    }
}

/// Eades–Lin–Smyth greedy order; returns the rank of every node. Arcs from a higher to a lower
/// rank form the feedback arc set.
fn greedy_fas_rank(n: usize, arcs: &[(u32, u32, u64)]) -> Vec<u32> {
    let out = Csr::build(n, arcs.iter().map(|&(u, v, w)| (u, v, w)));
    let inc = Csr::build(n, arcs.iter().map(|&(u, v, w)| (v, u, w)));
    let mut out_w = vec![0u64; n];
    let mut in_w = vec![0u64; n];
    for &(u, v, w) in arcs {
        out_w[u as usize] += w;
        in_w[v as usize] += w;
    }
    let delta = |o: u64, i: u64| o as i128 - i as i128;
    let mut removed = vec![false; n];
    let mut sinks: VecDeque<u32> = VecDeque::new();
    let mut sources: VecDeque<u32> = VecDeque::new();
    let mut heap: BinaryHeap<(i128, Reverse<u32>)> = BinaryHeap::with_capacity(n);
    for v in 0..n as u32 {
        if out_w[v as usize] == 0 {
            sinks.push_back(v);
        } else if in_w[v as usize] == 0 {
            sources.push_back(v);
        }
        heap.push((delta(out_w[v as usize], in_w[v as usize]), Reverse(v)));
    }
    let mut front: Vec<u32> = Vec::with_capacity(n);
    let mut back: Vec<u32> = Vec::new();
    loop {
        let pick = if let Some(v) = pop_live(&mut sinks, &removed) {
            back.push(v);
            v
        } else if let Some(v) = pop_live(&mut sources, &removed) {
            front.push(v);
            v
        } else {
            let mut found = None;
            while let Some((d, Reverse(v))) = heap.pop() {
                if !removed[v as usize] && d == delta(out_w[v as usize], in_w[v as usize]) {
                    found = Some(v);
                    break;
                }
            }
            match found {
                Some(v) => {
                    front.push(v);
                    v
                }
                None => break,
            }
        };
        removed[pick as usize] = true;
        for (w, weight) in out.tagged(pick) {
            if !removed[w as usize] {
                in_w[w as usize] -= weight;
                if in_w[w as usize] == 0 {
                    sources.push_back(w);
                }
                heap.push((delta(out_w[w as usize], in_w[w as usize]), Reverse(w)));
            }
        }
        for (u, weight) in inc.tagged(pick) {
            if !removed[u as usize] {
                out_w[u as usize] -= weight;
                if out_w[u as usize] == 0 {
                    sinks.push_back(u);
                }
                heap.push((delta(out_w[u as usize], in_w[u as usize]), Reverse(u)));
            }
        }
    }
    front.extend(back.iter().rev());
    let mut rank = vec![0u32; n];
    for (r, &v) in front.iter().enumerate() {
        rank[v as usize] = r as u32;
    }
    rank
}

/// Pops queue entries until one that is not yet removed.
fn pop_live(queue: &mut VecDeque<u32>, removed: &[bool]) -> Option<u32> {
    while let Some(v) = queue.pop_front() {
        if !removed[v as usize] {
            return Some(v);
        }
    }
    None
}

/// Turns every arc to point from lower to higher rank; the result is sorted and duplicate-free
/// (a 2-cycle becomes one arc).
fn orient_arcs(arcs: &[(u32, u32, u64)], rank: &[u32]) -> Vec<(u32, u32)> {
    let mut oriented: Vec<(u32, u32)> =
        arcs.iter().map(|&(u, v, _)| if rank[u as usize] < rank[v as usize] { (u, v) } else { (v, u) }).collect();
    oriented.sort_unstable();
    oriented.dedup();
    oriented
}

/// Connected component of every node (ignoring direction), numbered by smallest node index.
fn components(n: usize, arcs: &[(u32, u32)]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(parent: &mut [u32], mut v: u32) -> u32 {
        while parent[v as usize] != v {
            let up = parent[parent[v as usize] as usize];
            parent[v as usize] = up;
            v = up;
        }
        v
    }
    for &(u, v) in arcs {
        let (a, b) = (find(&mut parent, u), find(&mut parent, v));
        if a != b {
            let (low, high) = if a < b { (a, b) } else { (b, a) };
            parent[high as usize] = low;
        }
    }
    let mut id = vec![u32::MAX; n];
    let mut component = vec![0u32; n];
    let mut next = 0u32;
    for v in 0..n as u32 {
        let root = find(&mut parent, v) as usize;
        if id[root] == u32::MAX {
            id[root] = next;
            next += 1;
        }
        component[v as usize] = id[root];
    }
    component
}

/// Longest-path layering, then edge shortening, then each component shifted to start at 0.
fn assign_layers(n: usize, arcs: &[(u32, u32)], rank: &[u32], component: &[u32]) -> Vec<u32> {
    let succ = Csr::build(n, arcs.iter().map(|&(u, v)| (u, v, 0)));
    let pred = Csr::build(n, arcs.iter().map(|&(u, v)| (v, u, 0)));
    let mut topo = vec![0u32; n];
    for (v, &r) in rank.iter().enumerate() {
        topo[r as usize] = v as u32;
    }
    let mut layer = vec![0u32; n];
    for &v in &topo {
        for &w in succ.of(v) {
            layer[w as usize] = layer[w as usize].max(layer[v as usize] + 1);
        }
    }
    shorten_edges(&topo, &succ, &pred, &mut layer);
    let mut lowest = vec![u32::MAX; n];
    for v in 0..n {
        let c = component[v] as usize;
        lowest[c] = lowest[c].min(layer[v]);
    }
    for v in 0..n {
        layer[v] -= lowest[component[v] as usize];
    }
    layer
}

/// Moves single nodes to the end of their feasible layer range that shortens their edges.
fn shorten_edges(topo: &[u32], succ: &Csr, pred: &Csr, layer: &mut [u32]) {
    for _ in 0..SHORTEN_PASSES {
        let mut moved = false;
        for &v in topo.iter().rev() {
            let (ins, outs) = (pred.of(v), succ.of(v));
            let here = layer[v as usize];
            let target = if outs.len() > ins.len() {
                outs.iter().map(|&w| layer[w as usize]).min().map_or(here, |m| m - 1)
            } else if ins.len() > outs.len() {
                ins.iter().map(|&u| layer[u as usize]).max().map_or(here, |m| m + 1)
            } else {
                here
            };
            if target != here {
                layer[v as usize] = target;
                moved = true;
            }
        }
        if !moved {
            break;
        }
    }
}

/// The proper layered graph: real nodes `0..n`, then dummy nodes; every segment joins adjacent
/// layers.
struct ProperGraph {
    real: usize,
    layer: Vec<u32>,
    component: Vec<u32>,
    /// Per oriented arc, its vertices from top to bottom are
    /// `chain_nodes[chain_start[a]..chain_start[a + 1]]`.
    chain_start: Vec<usize>,
    chain_nodes: Vec<u32>,
    /// Upper neighbours, tagged with the segment id.
    up: Csr,
    /// Lower neighbours, tagged with the segment id.
    down: Csr,
    segment_count: usize,
}

impl ProperGraph {
    /// Subdivides long arcs; fails when the dummies would exceed the size cap.
    fn build(n: usize, arcs: &[(u32, u32)], layer: &[u32], component: &[u32]) -> Result<Self, LayeredError> {
        let dummies: usize = arcs.iter().map(|&(u, v)| (layer[v as usize] - layer[u as usize]) as usize - 1).sum();
        if n + dummies > MAX_LAYOUT_NODES {
            return Err(LayeredError::TooLarge { nodes: n, dummies });
        }
        let mut all_layer = layer.to_vec();
        let mut all_component = component.to_vec();
        let mut chain_start = Vec::with_capacity(arcs.len() + 1);
        let mut chain_nodes = Vec::with_capacity(2 * arcs.len() + dummies);
        let mut segments: Vec<(u32, u32)> = Vec::with_capacity(arcs.len() + dummies);
        for &(u, v) in arcs {
            chain_start.push(chain_nodes.len());
            chain_nodes.push(u);
            let mut previous = u;
            for l in layer[u as usize] + 1..layer[v as usize] {
                let dummy = all_layer.len() as u32;
                all_layer.push(l);
                all_component.push(component[u as usize]);
                chain_nodes.push(dummy);
                segments.push((previous, dummy));
                previous = dummy;
            }
            chain_nodes.push(v);
            segments.push((previous, v));
        }
        chain_start.push(chain_nodes.len());
        let total = all_layer.len();
        let tagged = segments.iter().enumerate().map(|(s, &(a, b))| (a, b, s as u64));
        let down = Csr::build(total, tagged.clone());
        let up = Csr::build(total, tagged.map(|(a, b, s)| (b, a, s)));
        Ok(Self {
            real: n,
            layer: all_layer,
            component: all_component,
            chain_start,
            chain_nodes,
            up,
            down,
            segment_count: segments.len(),
        })
    }

    fn vertex_count(&self) -> usize {
        self.layer.len()
    }

    fn is_dummy(&self, v: u32) -> bool {
        v as usize >= self.real
    }

    /// Vertices of each component, in index order.
    fn component_members(&self) -> Vec<Vec<u32>> {
        let count = self.component.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
        let mut members = vec![Vec::new(); count];
        for (v, &c) in self.component.iter().enumerate() {
            members[c as usize].push(v as u32);
        }
        members
    }

    /// Vertices of the drawn path of oriented arc `arc`, top to bottom.
    fn chain(&self, arc: usize) -> &[u32] {
        &self.chain_nodes[self.chain_start[arc]..self.chain_start[arc + 1]]
    }
}

/// Depth-first initial ordering of one component: layers filled in visiting order, starting
/// from its real nodes by (layer, index). Sets `pos`.
fn initial_order(g: &ProperGraph, members: &[u32], pos: &mut [u32]) -> Vec<Vec<u32>> {
    let height = members.iter().map(|&v| g.layer[v as usize] as usize + 1).max().unwrap_or(0);
    let mut layers: Vec<Vec<u32>> = vec![Vec::new(); height];
    let mut starts: Vec<u32> = members.iter().copied().filter(|&v| !g.is_dummy(v)).collect();
    starts.sort_by_key(|&v| (g.layer[v as usize], v));
    let mut seen = vec![false; members.len()];
    let local = |v: u32| members.binary_search(&v).unwrap_or(0);
    let mut stack: Vec<u32> = Vec::new();
    for start in starts {
        stack.push(start);
        while let Some(v) = stack.pop() {
            let i = local(v);
            if seen[i] {
                continue;
            }
            seen[i] = true;
            let row = &mut layers[g.layer[v as usize] as usize];
            pos[v as usize] = row.len() as u32;
            row.push(v);
            let next = g.down.of(v).iter().chain(g.up.of(v)).rev();
            stack.extend(next.filter(|&&w| !seen[local(w)]));
        }
    }
    layers
}

/// Barycenter sweeps with transposition; leaves the best ordering found in `layers`/`pos` and
/// returns its crossing count.
fn reduce_crossings(g: &ProperGraph, layers: &mut [Vec<u32>], pos: &mut [u32], sweeps: u32) -> u64 {
    let mut best = total_crossings(g, layers, pos);
    let mut best_layers = layers.to_vec();
    for sweep in 0..sweeps {
        if best == 0 {
            break;
        }
        let downward = sweep % 2 == 0;
        barycenter_sweep(g, layers, pos, downward);
        transpose(g, layers, pos);
        let count = total_crossings(g, layers, pos);
        if count < best {
            best = count;
            best_layers.clone_from_slice(layers);
        }
    }
    layers.clone_from_slice(&best_layers);
    set_positions(layers, pos);
    best
}

/// Writes each vertex's slot into `pos`.
fn set_positions(layers: &[Vec<u32>], pos: &mut [u32]) {
    for row in layers {
        for (k, &v) in row.iter().enumerate() {
            pos[v as usize] = k as u32;
        }
    }
}

/// One pass over the layers, sorting each by the barycenter of its neighbours in the layer
/// visited before.
fn barycenter_sweep(g: &ProperGraph, layers: &mut [Vec<u32>], pos: &mut [u32], downward: bool) {
    let height = layers.len();
    let order: Vec<usize> =
        if downward { (1..height).collect() } else { (0..height.saturating_sub(1)).rev().collect() };
    let fixed_side = if downward { &g.up } else { &g.down };
    for li in order {
        sort_by_barycenter(&mut layers[li], fixed_side, pos);
    }
}

/// Sorts one layer by barycenter; vertices without neighbours keep their slots.
fn sort_by_barycenter(row: &mut [u32], side: &Csr, pos: &mut [u32]) {
    let mut movable: Vec<(f64, u32, u32)> = Vec::with_capacity(row.len());
    let mut is_fixed = vec![false; row.len()];
    for (k, &v) in row.iter().enumerate() {
        let neighbours = side.of(v);
        if neighbours.is_empty() {
            is_fixed[k] = true;
        } else {
            let sum: f64 = neighbours.iter().map(|&u| f64::from(pos[u as usize])).sum();
            movable.push((sum / neighbours.len() as f64, k as u32, v));
        }
    }
    movable.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut next = movable.iter();
    for (k, slot) in row.iter_mut().enumerate() {
        if !is_fixed[k]
            && let Some(&(_, _, v)) = next.next()
        {
            *slot = v;
        }
        pos[*slot as usize] = k as u32;
    }
}

/// Swaps adjacent vertices while that strictly lowers crossings, for a capped number of rounds.
fn transpose(g: &ProperGraph, layers: &mut [Vec<u32>], pos: &mut [u32]) {
    let mut scratch = (Vec::new(), Vec::new());
    for _ in 0..TRANSPOSE_ROUNDS {
        let mut improved = false;
        for row in layers.iter_mut() {
            for k in 1..row.len() {
                let (u, w) = (row[k - 1], row[k]);
                let (up_uw, up_wu) = pair_crossings(&g.up, u, w, pos, &mut scratch);
                let (down_uw, down_wu) = pair_crossings(&g.down, u, w, pos, &mut scratch);
                if up_wu + down_wu < up_uw + down_uw {
                    row.swap(k - 1, k);
                    pos[u as usize] = k as u32;
                    pos[w as usize] = k as u32 - 1;
                    improved = true;
                }
            }
        }
        if !improved {
            break;
        }
    }
}

/// Crossings among the segments of `u` and `w` to one side: `(u left of w, w left of u)`.
fn pair_crossings(side: &Csr, u: u32, w: u32, pos: &[u32], scratch: &mut (Vec<u32>, Vec<u32>)) -> (u64, u64) {
    let (a, b) = scratch;
    a.clear();
    b.clear();
    a.extend(side.of(u).iter().map(|&x| pos[x as usize]));
    b.extend(side.of(w).iter().map(|&x| pos[x as usize]));
    a.sort_unstable();
    b.sort_unstable();
    (count_greater_pairs(a, b), count_greater_pairs(b, a))
}

/// Number of pairs `(x in a, y in b)` with `x > y`; both slices sorted.
fn count_greater_pairs(a: &[u32], b: &[u32]) -> u64 {
    let mut below = 0usize;
    let mut total = 0u64;
    for &x in a {
        while below < b.len() && b[below] < x {
            below += 1;
        }
        total += below as u64;
    }
    total
}

/// Crossings of a component over all pairs of adjacent layers.
fn total_crossings(g: &ProperGraph, layers: &[Vec<u32>], pos: &[u32]) -> u64 {
    let mut tree = Vec::new();
    let mut sequence = Vec::new();
    layers.windows(2).map(|pair| count_between(g, &pair[0], pair[1].len(), pos, &mut tree, &mut sequence)).sum()
}

/// Crossings between one layer and the next (Barth, Jünger & Mutzel 2002): the lower slots of
/// the segments, sorted by upper then lower slot, are counted for inversions in a Fenwick tree.
fn count_between(
    g: &ProperGraph,
    upper: &[u32],
    lower_len: usize,
    pos: &[u32],
    tree: &mut Vec<u64>,
    sequence: &mut Vec<u32>,
) -> u64 {
    sequence.clear();
    for &u in upper {
        let start = sequence.len();
        sequence.extend(g.down.of(u).iter().map(|&w| pos[w as usize]));
        sequence[start..].sort_unstable();
    }
    tree.clear();
    tree.resize(lower_len + 1, 0);
    let mut crossings = 0u64;
    for (inserted, &p) in sequence.iter().enumerate() {
        let at_most = fenwick_prefix(tree, p as usize + 1);
        crossings += inserted as u64 - at_most;
        fenwick_add(tree, p as usize + 1);
    }
    crossings
}

/// Sum of the first `i` entries of a 1-based Fenwick tree.
fn fenwick_prefix(tree: &[u64], mut i: usize) -> u64 {
    let mut sum = 0;
    while i > 0 {
        sum += tree[i];
        i &= i - 1;
    }
    sum
}

/// Adds one at 1-based index `i`.
fn fenwick_add(tree: &mut [u64], mut i: usize) {
    while i < tree.len() {
        tree[i] += 1;
        i += i & i.wrapping_neg();
    }
}

/// One of the four Brandes–Köpf passes: which neighbours to align to, and which side to pack to.
#[derive(Clone, Copy)]
struct Direction {
    /// Align to lower neighbours, visiting layers bottom-up.
    down: bool,
    /// Visit each layer right to left and pack to the right.
    right: bool,
}

/// Coordinates under construction, indexed by vertex of the proper graph.
struct Drawing {
    /// Slot of each vertex within its layer.
    pos: Vec<u32>,
    /// Twice the x coordinate, in units of `node_gap`.
    x2: Vec<i64>,
    /// Next free doubled x for a component.
    cursor: i64,
}

impl Drawing {
    fn new(vertices: usize) -> Self {
        Self { pos: vec![0; vertices], x2: vec![0; vertices], cursor: 0 }
    }

    /// Brandes–Köpf coordinates for one ordered component, placed right of the previous one.
    fn place_component(&mut self, g: &ProperGraph, layers: &[Vec<u32>]) {
        let members: Vec<u32> = layers.iter().flatten().copied().collect();
        let marked = mark_type1_conflicts(g, layers, &self.pos);
        let mut candidates: Vec<Vec<i64>> = Vec::with_capacity(4);
        for (down, right) in [(false, false), (false, true), (true, false), (true, true)] {
            let dir = Direction { down, right };
            candidates.push(single_layout(g, layers, &self.pos, &marked, dir));
        }
        let local = balance(&mut candidates, members.len());
        let min = local.iter().copied().min().unwrap_or(0);
        let max = local.iter().copied().max().unwrap_or(0);
        for (&v, &x) in members.iter().zip(&local) {
            self.x2[v as usize] = x - min + self.cursor;
        }
        self.cursor += max - min + 2;
    }
}

/// Marks segments that cross a segment between two dummies (type-1 conflicts), so alignment
/// leaves long edges straight. Indexed by segment id.
fn mark_type1_conflicts(g: &ProperGraph, layers: &[Vec<u32>], pos: &[u32]) -> Vec<bool> {
    let mut marked = vec![false; g.segment_count];
    for pair in layers.windows(2) {
        let (upper, lower) = (&pair[0], &pair[1]);
        let mut k0 = 0i64;
        let mut l = 0usize;
        for (l1, &v) in lower.iter().enumerate() {
            let inner = inner_upper_neighbour(g, v);
            if l1 + 1 != lower.len() && inner.is_none() {
                continue;
            }
            let k1 = inner.map_or(upper.len() as i64 - 1, |u| i64::from(pos[u as usize]));
            while l <= l1 {
                for (u, segment) in g.up.tagged(lower[l]) {
                    let k = i64::from(pos[u as usize]);
                    if k < k0 || k > k1 {
                        marked[segment as usize] = true;
                    }
                }
                l += 1;
            }
            k0 = k1;
        }
    }
    marked
}

/// The upper neighbour of `v` when both are dummies (an inner segment).
fn inner_upper_neighbour(g: &ProperGraph, v: u32) -> Option<u32> {
    if !g.is_dummy(v) {
        return None;
    }
    g.up.of(v).first().copied().filter(|&u| g.is_dummy(u))
}

/// Alignment and compaction in one direction; returns x per vertex (in half node gaps), in the
/// order of `layers` flattened.
fn single_layout(g: &ProperGraph, layers: &[Vec<u32>], pos: &[u32], marked: &[bool], dir: Direction) -> Vec<i64> {
    let index = LocalIndex::new(layers);
    let (root, align) = vertical_alignment(g, layers, pos, marked, dir, &index);
    match compact(layers, &root, &align, dir, &index) {
        Some(x) => x,
        None => layers
            .iter()
            .flat_map(|row| (0..row.len() as i64).map(|k| if dir.right { -2 * k } else { 2 * k }))
            .collect(),
    }
}

/// Maps the vertices of one component to `0..count` (layer by layer, left to right).
struct LocalIndex {
    /// Sorted `(vertex, local index)` pairs.
    sorted: Vec<(u32, u32)>,
    /// Local index of the first vertex of each layer.
    row_start: Vec<usize>,
}

impl LocalIndex {
    fn new(layers: &[Vec<u32>]) -> Self {
        let mut sorted = Vec::new();
        let mut row_start = Vec::with_capacity(layers.len() + 1);
        for row in layers {
            row_start.push(sorted.len());
            for &v in row {
                sorted.push((v, sorted.len() as u32));
            }
        }
        row_start.push(sorted.len());
        sorted.sort_unstable();
        Self { sorted, row_start }
    }

    fn of(&self, v: u32) -> usize {
        match self.sorted.binary_search_by_key(&v, |&(w, _)| w) {
            Ok(i) => self.sorted[i].1 as usize,
            Err(_) => 0,
        }
    }

    fn len(&self) -> usize {
        self.sorted.len()
    }
}

/// Brandes–Köpf vertical alignment: each vertex joins the block of a median neighbour (in the
/// layer visited before) unless that segment is marked or would cross an earlier alignment.
/// Returns `root` and the cyclic `align` successor, as local indices.
fn vertical_alignment(
    g: &ProperGraph,
    layers: &[Vec<u32>],
    pos: &[u32],
    marked: &[bool],
    dir: Direction,
    index: &LocalIndex,
) -> (Vec<u32>, Vec<u32>) {
    let count = index.len();
    let mut root: Vec<u32> = (0..count as u32).collect();
    let mut align: Vec<u32> = root.clone();
    let side = if dir.down { &g.down } else { &g.up };
    let rows: Vec<usize> = if dir.down { (0..layers.len()).rev().collect() } else { (0..layers.len()).collect() };
    let mut neighbours: Vec<(u32, u32, u64)> = Vec::new();
    for li in rows {
        let row = &layers[li];
        let mut limit: i64 = if dir.right { i64::MAX } else { -1 };
        for step in 0..row.len() {
            let k = if dir.right { row.len() - 1 - step } else { step };
            let v = row[k];
            let lv = index.of(v);
            neighbours.clear();
            neighbours.extend(side.tagged(v).map(|(u, s)| (pos[u as usize], u, s)));
            if neighbours.is_empty() {
                continue;
            }
            neighbours.sort_unstable();
            let d = neighbours.len();
            let (lo, hi) = ((d - 1) / 2, d / 2);
            let medians = if dir.right { [hi, lo] } else { [lo, hi] };
            for (i, &m) in medians.iter().enumerate() {
                if i == 1 && lo == hi {
                    break;
                }
                if align[lv] as usize != lv {
                    break;
                }
                let (pu, u, segment) = neighbours[m];
                let pu = i64::from(pu);
                let free = if dir.right { pu < limit } else { pu > limit };
                if free && !marked[segment as usize] {
                    let lu = index.of(u);
                    align[lu] = lv as u32;
                    root[lv] = root[lu];
                    align[lv] = root[lv];
                    limit = pu;
                }
            }
        }
    }
    (root, align)
}

/// Places blocks, in half node gaps: a longest path over the "left of" graph of blocks, then each block pulled
/// towards its right-hand neighbours. For `dir.right` the layers are read mirrored and the
/// result negated. Returns None if the block graph has a cycle (cannot happen for alignments
/// built by [`vertical_alignment`]).
fn compact(layers: &[Vec<u32>], root: &[u32], align: &[u32], dir: Direction, index: &LocalIndex) -> Option<Vec<i64>> {
    let count = index.len();
    // Local indices run layer by layer, left to right; `next` is the neighbour in packing order.
    let mut next = vec![u32::MAX; count];
    let mut indegree = vec![0u32; count];
    for (li, row) in layers.iter().enumerate() {
        let start = index.row_start[li];
        for k in 1..row.len() {
            let (left, right) = ((start + k - 1) as u32, (start + k) as u32);
            let (from, to) = if dir.right { (right, left) } else { (left, right) };
            next[from as usize] = to;
            indegree[root[to as usize] as usize] += 1;
        }
    }
    let block_members = |b: usize| {
        let mut members = vec![b];
        let mut w = align[b] as usize;
        while w != b && members.len() <= count {
            members.push(w);
            w = align[w] as usize;
        }
        members
    };
    let mut x = vec![0i64; count];
    let mut queue: VecDeque<usize> = (0..count).filter(|&v| root[v] as usize == v && indegree[v] == 0).collect();
    let mut topo: Vec<usize> = Vec::new();
    while let Some(b) = queue.pop_front() {
        topo.push(b);
        for member in block_members(b) {
            let to = next[member];
            if to != u32::MAX {
                let target = root[to as usize] as usize;
                x[target] = x[target].max(x[b] + 2);
                indegree[target] -= 1;
                if indegree[target] == 0 {
                    queue.push_back(target);
                }
            }
        }
    }
    let blocks = (0..count).filter(|&v| root[v] as usize == v).count();
    if topo.len() != blocks {
        return None;
    }
    for &b in topo.iter().rev() {
        let pull = block_members(b)
            .into_iter()
            .filter(|&m| next[m] != u32::MAX)
            .map(|m| x[root[next[m] as usize] as usize] - 2)
            .min();
        if let Some(limit) = pull {
            x[b] = x[b].max(limit);
        }
    }
    let sign = if dir.right { -1 } else { 1 };
    Some((0..count).map(|v| sign * x[root[v] as usize]).collect())
}

/// Aligns the four candidate layouts to the narrowest (left ones by their minimum, right ones by
/// their maximum) and returns, per vertex, the mean of its two median candidates. Candidates
/// are even (in half node gaps), so the mean is exact.
fn balance(candidates: &mut [Vec<i64>], count: usize) -> Vec<i64> {
    let extent = |xs: &[i64]| {
        let min = xs.iter().copied().min().unwrap_or(0);
        let max = xs.iter().copied().max().unwrap_or(0);
        (min, max)
    };
    let extents: Vec<(i64, i64)> = candidates.iter().map(|xs| extent(xs)).collect();
    let narrowest = (0..extents.len()).min_by_key(|&k| (extents[k].1 - extents[k].0, k)).unwrap_or(0);
    let (target_min, target_max) = extents.get(narrowest).copied().unwrap_or((0, 0));
    for (k, xs) in candidates.iter_mut().enumerate() {
        let right = k % 2 == 1;
        let shift = if right { target_max - extents[k].1 } else { target_min - extents[k].0 };
        xs.iter_mut().for_each(|x| *x += shift);
    }
    (0..count)
        .map(|v| {
            let mut four = [0i64; 4];
            for (slot, xs) in four.iter_mut().zip(candidates.iter()) {
                *slot = xs.get(v).copied().unwrap_or(0);
            }
            four.sort_unstable();
            (four[1] + four[2]) / 2
        })
        .collect()
}

/// Builds the public result from the placed proper graph.
fn assemble(
    edges: &[(u32, u32)],
    rank: &[u32],
    oriented: &[(u32, u32)],
    g: &ProperGraph,
    drawing: &Drawing,
    options: &LayeredOptions,
    crossings: u64,
) -> Layered {
    let point = |v: u32| {
        let x = drawing.x2[v as usize] as f64 * 0.5 * options.node_gap;
        let y = f64::from(g.layer[v as usize]) * options.layer_gap;
        [x, y]
    };
    let positions: Vec<[f64; 2]> = (0..g.real as u32).map(point).collect();
    let layers = g.layer[..g.real].to_vec();
    let mut edge_paths = Vec::with_capacity(edges.len());
    let mut reversed = Vec::with_capacity(edges.len());
    for &(u, v) in edges {
        if u == v {
            edge_paths.push(Vec::new());
            reversed.push(false);
            continue;
        }
        let flip = rank[u as usize] > rank[v as usize];
        let key = if flip { (v, u) } else { (u, v) };
        let mut path: Vec<[f64; 2]> = match oriented.binary_search(&key) {
            Ok(arc) => g.chain(arc).iter().map(|&w| point(w)).collect(),
            Err(_) => Vec::new(),
        };
        if flip {
            path.reverse();
        }
        edge_paths.push(path);
        reversed.push(flip);
    }
    let crossings = usize::try_from(crossings).unwrap_or(usize::MAX);
    Layered { positions, layers, edge_paths, reversed, crossings }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::layout::split_mix::SplitMix64 as Rng;

    /// `m` distinct edges from a lower to a higher index.
    fn random_dag(n: u32, m: usize, seed: u64) -> Vec<(u32, u32)> {
        let mut rng = Rng(seed);
        let mut edges = Vec::new();
        while edges.len() < m {
            let (a, b) = (rng.below(n), rng.below(n));
            let e = (a.min(b), a.max(b));
            if a != b && !edges.contains(&e) {
                edges.push(e);
            }
        }
        edges
    }

    /// `m` random edges, at most one per unordered pair, in either direction (so with cycles).
    fn random_digraph(n: u32, m: usize, seed: u64) -> Vec<(u32, u32)> {
        let mut rng = Rng(seed);
        let mut edges: Vec<(u32, u32)> = Vec::new();
        while edges.len() < m {
            let (a, b) = (rng.below(n), rng.below(n));
            if a != b && !edges.iter().any(|&(u, v)| (u, v) == (a, b) || (u, v) == (b, a)) {
                edges.push((a, b));
            }
        }
        edges
    }

    fn layout(n: usize, edges: &[(u32, u32)]) -> Layered {
        layered_layout(n, edges, &LayeredOptions::default()).unwrap()
    }

    /// Crossings recomputed from the drawn paths: segments between the same two layers cross
    /// when their end points swap order.
    fn crossings_from_paths(paths: &[Vec<[f64; 2]>]) -> usize {
        let mut segments: Vec<([f64; 2], [f64; 2])> = Vec::new();
        for path in paths {
            for pair in path.windows(2) {
                let (p, q) = if pair[0][1] < pair[1][1] { (pair[0], pair[1]) } else { (pair[1], pair[0]) };
                segments.push((p, q));
            }
        }
        let mut count = 0;
        for (i, a) in segments.iter().enumerate() {
            for b in &segments[i + 1..] {
                if a.0[1] == b.0[1] && (a.0[0] - b.0[0]) * (a.1[0] - b.1[0]) < 0.0 {
                    count += 1;
                }
            }
        }
        count
    }

    #[test]
    fn chain_is_a_vertical_line() {
        let edges: Vec<(u32, u32)> = (0..5).map(|i| (i, i + 1)).collect();
        let options = LayeredOptions { layer_gap: 2.5, ..LayeredOptions::default() };
        let out = layered_layout(6, &edges, &options).unwrap();
        for (i, p) in out.positions.iter().enumerate() {
            assert_eq!(p[0], out.positions[0][0]);
            assert_eq!(p[1], 2.5 * i as f64);
            assert_eq!(out.layers[i], i as u32);
        }
        assert_eq!(out.crossings, 0);
        assert!(out.reversed.iter().all(|&r| !r));
    }

    #[test]
    fn binary_tree_has_no_crossings_and_centred_parents() {
        // Depth 4: 31 nodes, node i has children 2i + 1 and 2i + 2.
        let edges: Vec<(u32, u32)> = (0..15).flat_map(|i| [(i, 2 * i + 1), (i, 2 * i + 2)]).collect();
        let out = layout(31, &edges);
        assert_eq!(out.crossings, 0);
        for i in 0..15 {
            let x = out.positions[i][0];
            let (a, b) = (out.positions[2 * i + 1][0], out.positions[2 * i + 2][0]);
            assert!(a.min(b) < x && x < a.max(b), "parent {i} at {x}, children at {a} and {b}");
            assert_eq!(out.layers[2 * i + 1], out.layers[i] + 1);
        }
    }

    #[test]
    fn dag_edges_all_point_down() {
        let edges = random_dag(60, 150, 7);
        let out = layout(60, &edges);
        for (k, &(s, t)) in edges.iter().enumerate() {
            assert!(!out.reversed[k]);
            assert!(out.layers[t as usize] > out.layers[s as usize], "edge {k}");
            assert!(out.edge_paths[k].windows(2).all(|w| w[1][1] > w[0][1]));
        }
    }

    #[test]
    fn only_reversed_edges_point_up() {
        let edges = random_digraph(50, 160, 11);
        let out = layout(50, &edges);
        let mut flipped = 0;
        for (k, &(s, t)) in edges.iter().enumerate() {
            let (ls, lt) = (out.layers[s as usize], out.layers[t as usize]);
            if out.reversed[k] {
                flipped += 1;
                assert!(lt < ls, "reversed edge {k} must point up");
            } else {
                assert!(lt > ls, "edge {k} must point down");
            }
        }
        // Eades, Lin & Smyth guarantee at most m/2 - n/6 reversed edges.
        assert!(flipped > 0 && flipped <= 160 / 2 - 50 / 6, "{flipped} reversed");
    }

    #[test]
    fn three_cycle_reverses_exactly_one_edge() {
        let out = layout(3, &[(0, 1), (1, 2), (2, 0)]);
        assert_eq!(out.reversed.iter().filter(|&&r| r).count(), 1);
        assert_eq!(out.crossings, 0);
        // The reversed edge spans two layers, so its path has one bend.
        let k = out.reversed.iter().position(|&r| r).unwrap();
        assert_eq!(out.edge_paths[k].len(), 3);
    }

    #[test]
    fn bipartite_examples_reach_their_minimum() {
        // K3,3 on two layers: every pair of top nodes and pair of bottom nodes crosses once,
        // in any order: 3 * 3 = 9.
        let k33: Vec<(u32, u32)> = (0..3).flat_map(|i| (3..6).map(move |j| (i, j))).collect();
        assert_eq!(layout(6, &k33).crossings, 9);
        // K3,3 minus a perfect matching (a 6-cycle a-y-c-x-b-z-a): two top nodes share one
        // bottom neighbour; they avoid crossing only if the left one's other neighbour lies left
        // of the shared one and the right one's right of it. The three pairs demand
        // incompatible bottom orders, so at most one pair is free: minimum 2.
        let c6 = [(0, 4), (0, 5), (1, 3), (1, 5), (2, 3), (2, 4)];
        let out = layout(6, &c6);
        assert_eq!(out.crossings, 2);
        assert_eq!(crossings_from_paths(&out.edge_paths), 2);
    }

    #[test]
    fn reported_crossings_match_the_drawn_paths() {
        for seed in 0..4 {
            let edges = random_digraph(40, 90, 100 + seed);
            let out = layout(40, &edges);
            assert_eq!(out.crossings, crossings_from_paths(&out.edge_paths), "seed {seed}");
        }
        let dag = random_dag(80, 200, 5);
        let out = layout(80, &dag);
        assert!(out.crossings > 0);
        assert_eq!(out.crossings, crossings_from_paths(&out.edge_paths));
    }

    #[test]
    fn crossing_reduction_improves_on_the_initial_order() {
        let dag = random_dag(80, 200, 5);
        let none = layered_layout(80, &dag, &LayeredOptions { sweeps: 0, ..LayeredOptions::default() }).unwrap();
        let some = layout(80, &dag);
        assert!(some.crossings < none.crossings, "{} vs {}", some.crossings, none.crossings);
    }

    #[test]
    fn nodes_and_bends_in_a_layer_keep_the_node_gap() {
        let edges = random_digraph(60, 130, 3);
        let options = LayeredOptions { layer_gap: 0.7, node_gap: 0.3, sweeps: 24 };
        let out = layered_layout(60, &edges, &options).unwrap();
        let mut points: Vec<[f64; 2]> = out.positions.clone();
        for path in &out.edge_paths {
            points.extend(path.iter().skip(1).take(path.len().saturating_sub(2)));
        }
        points.sort_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
        let mut rows = 0;
        for w in points.windows(2) {
            if w[0][1] == w[1][1] {
                rows += 1;
                assert!(w[1][0] - w[0][0] >= 0.3 * (1.0 - 1e-12), "{:?} and {:?}", w[0], w[1]);
            }
        }
        assert!(rows > 50);
    }

    #[test]
    fn long_edges_bend_once_per_layer_and_run_straight() {
        // Chain 0-1-2-3 plus the long edge 0 -> 3 (two dummies).
        let out = layout(4, &[(0, 1), (1, 2), (2, 3), (0, 3)]);
        let path = &out.edge_paths[3];
        assert_eq!(path.len(), 4);
        assert_eq!([path[0], path[3]], [out.positions[0], out.positions[3]]);
        assert_eq!(path[1][0], path[2][0], "the bends of a long edge line up");
        assert_ne!(path[1][0], out.positions[1][0]);
        // In general: one point per layer from source to target.
        let dag = random_dag(70, 160, 9);
        let out = layout(70, &dag);
        for (k, &(s, t)) in dag.iter().enumerate() {
            let span = (out.layers[t as usize] - out.layers[s as usize]) as usize;
            let path = &out.edge_paths[k];
            assert_eq!(path.len(), span + 1, "edge {k}");
            for (i, p) in path.iter().enumerate() {
                assert_eq!(p[1], f64::from(out.layers[s as usize]) + i as f64);
            }
        }
    }

    #[test]
    fn edge_shortening_moves_sources_down() {
        // Longest path alone puts 4 at layer 0; its only edge goes to 3 at layer 3.
        let out = layout(5, &[(0, 1), (1, 2), (2, 3), (4, 3)]);
        assert_eq!(out.layers, vec![0, 1, 2, 3, 2]);
        assert_eq!(out.edge_paths[3].len(), 2);
    }

    #[test]
    fn self_loops_and_duplicates() {
        let out = layout(2, &[(0, 1), (0, 1), (1, 1), (1, 0)]);
        assert_eq!(out.reversed, vec![false, false, false, true]);
        assert_eq!(out.edge_paths[0], out.edge_paths[1]);
        assert!(out.edge_paths[2].is_empty());
        let mut back = out.edge_paths[3].clone();
        back.reverse();
        assert_eq!(back, out.edge_paths[0]);
        assert_eq!(out.crossings, 0);
    }

    #[test]
    fn components_sit_side_by_side() {
        // Two chains and an isolated node, interleaved indices.
        let out = layout(6, &[(0, 2), (2, 4), (1, 3)]);
        let xs = |ids: &[usize]| ids.iter().map(|&i| out.positions[i][0]).collect::<Vec<_>>();
        let (a, b, c) = (xs(&[0, 2, 4]), xs(&[1, 3]), xs(&[5]));
        let max = |v: &[f64]| v.iter().copied().fold(f64::MIN, f64::max);
        let min = |v: &[f64]| v.iter().copied().fold(f64::MAX, f64::min);
        assert!(min(&b) - max(&a) >= 1.0 && min(&c) - max(&b) >= 1.0);
        assert_eq!(out.layers, vec![0, 0, 1, 1, 2, 0]);
    }

    #[test]
    fn deterministic() {
        let edges = random_digraph(70, 180, 21);
        let a = layout(70, &edges);
        let b = layout(70, &edges);
        let bits = |l: &Layered| {
            let mut v: Vec<u64> = l.positions.iter().flat_map(|p| [p[0].to_bits(), p[1].to_bits()]).collect();
            v.extend(l.edge_paths.iter().flatten().flat_map(|p| [p[0].to_bits(), p[1].to_bits()]));
            v
        };
        assert_eq!(bits(&a), bits(&b));
        assert_eq!((a.reversed, a.crossings), (b.reversed, b.crossings));
    }

    #[test]
    fn bad_input_is_refused() {
        let o = LayeredOptions::default();
        let err = layered_layout(3, &[(0, 1), (1, 3)], &o).unwrap_err();
        assert_eq!(err, LayeredError::EdgeOutOfRange { edge: 1, source: 1, target: 3, node_count: 3 });
        assert!(err.to_string().contains("edge 1 (1 -> 3)"));
        let nan = LayeredOptions { node_gap: f64::NAN, ..o };
        assert!(matches!(layered_layout(2, &[], &nan), Err(LayeredError::BadGap { name: "node_gap", .. })));
        let zero = LayeredOptions { layer_gap: 0.0, ..o };
        assert!(matches!(layered_layout(2, &[], &zero), Err(LayeredError::BadGap { name: "layer_gap", .. })));
        let many = LayeredOptions { sweeps: MAX_SWEEPS + 1, ..o };
        assert_eq!(layered_layout(2, &[], &many), Err(LayeredError::TooManySweeps(MAX_SWEEPS + 1)));
        let big = layered_layout(MAX_LAYOUT_NODES + 1, &[], &o).unwrap_err();
        assert_eq!(big, LayeredError::TooLarge { nodes: MAX_LAYOUT_NODES + 1, dummies: 0 });
        // A 1,000-node chain plus 300 edges to its end: sum of (998 - i) for i < 300 dummies.
        let mut edges: Vec<(u32, u32)> = (0..999).map(|i| (i, i + 1)).collect();
        edges.extend((0..300).map(|i| (i, 999)));
        let dummies = (0..300).map(|i| 998 - i).sum();
        assert_eq!(layered_layout(1000, &edges, &o), Err(LayeredError::TooLarge { nodes: 1000, dummies }));
        let empty = layered_layout(0, &[], &o).unwrap();
        assert!(empty.positions.is_empty() && empty.crossings == 0);
    }
}
