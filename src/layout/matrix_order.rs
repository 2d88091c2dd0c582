//! Row/column order for an adjacency-matrix view of a network, chosen by clustering so that
//! densely linked groups show up as blocks along the diagonal.
//!
//! 1. The weighted adjacency is made symmetric (weights of `(i, j)` and `(j, i)` add up, self
//!    loops are ignored) and every linked node gets a self-weight on the diagonal equal to its
//!    largest link weight, so that two linked nodes share entries and come out close.
//! 2. The distance between two nodes is `1 − cos` of the angle between their adjacency rows
//!    (in [0, 1]; 1 for nodes with no neighbour in common). The dot products take O(Σ deg²) for
//!    sparse graphs, or O(n³/2) vectorised multiply-adds for dense ones (seconds for a complete
//!    graph at the node cap).
//! 3. Average-linkage (UPGMA) agglomerative clustering, with the nearest-neighbour chain
//!    algorithm (Benzécri 1982; see Müllner 2011, "Modern hierarchical, agglomerative clustering
//!    algorithms"): O(n²) time and memory, and since average linkage is reducible it builds the
//!    same dendrogram as the naive algorithm. Ties go to the lower index (and, in the chain, to
//!    the previous chain element, which guarantees termination).
//! 4. The leaf order comes from the dendrogram. At each merge the two subtrees' leaf sequences
//!    are joined in the orientation (each may be reversed) that puts the two most similar end
//!    leaves next to each other. This is a greedy, local stand-in for the optimal leaf ordering of
//!    Bar-Joseph, Gifford & Jaakkola (2001), which minimises the sum over all neighbours at
//!    O(n³) cost; the greedy choice costs O(n) a merge.
//!
//! Nodes without any positive-weight link to another node go at the end, in index order.
//! Output is deterministic: it depends only on the set of weighted edges, not on their order.

use std::fmt;

/// Most nodes accepted: a matrix with more rows than this is unreadable on any screen, and the
/// O(n²) distance table would take over 36 MB.
pub const MAX_MATRIX_NODES: usize = 3000;

/// Why no order could be computed.
#[derive(Clone, Debug, PartialEq)]
pub enum MatrixOrderError {
    /// More nodes than [`MAX_MATRIX_NODES`].
    TooManyNodes {
        /// Nodes given.
        count: usize,
        /// The cap.
        cap: usize,
    },
    /// An edge names a node that does not exist.
    EndpointOutOfRange {
        /// Position of the edge in the list.
        edge: usize,
        /// The bad endpoint.
        endpoint: u32,
        /// Number of nodes.
        node_count: usize,
    },
    /// An edge weight is negative, NaN or infinite.
    BadWeight {
        /// Position of the edge in the list.
        edge: usize,
        /// The bad weight.
        weight: f64,
    },
}

impl fmt::Display for MatrixOrderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooManyNodes { count, cap } => write!(
                f,
                "the matrix would have {count} rows; at most {cap} are ordered, since a matrix beyond that is \
                 unreadable anyway (filter or aggregate the nodes first)"
            ),
            Self::EndpointOutOfRange { edge, endpoint, node_count } => write!(
                f,
                "edge {edge} names node {endpoint}, but there are only {node_count} nodes (valid ids are 0..{node_count})"
            ),
            Self::BadWeight { edge, weight } => {
                write!(f, "edge {edge} has weight {weight}; weights must be finite and not negative")
            }
        }
    }
}

impl std::error::Error for MatrixOrderError {}

/// A permutation of `0..node_count` for the matrix rows and columns (see the module
/// documentation): clustered nodes first, isolated nodes last in index order.
pub fn cluster_order(node_count: usize, edges: &[(u32, u32, f64)]) -> Result<Vec<usize>, MatrixOrderError> {
    validate(node_count, edges)?;
    let links = symmetric_links(node_count, edges);
    let (linked, isolated): (Vec<usize>, Vec<usize>) = (0..node_count).partition(|&v| !links[v].is_empty());
    let rows = rows_with_diagonal(&links, &linked);
    let order = average_linkage_order(&rows);
    Ok(order.into_iter().map(|k| linked[k]).chain(isolated).collect())
}

/// Checks the node cap, edge endpoints and weights.
fn validate(node_count: usize, edges: &[(u32, u32, f64)]) -> Result<(), MatrixOrderError> {
    if node_count > MAX_MATRIX_NODES {
        return Err(MatrixOrderError::TooManyNodes { count: node_count, cap: MAX_MATRIX_NODES });
    }
    for (edge, &(from, to, weight)) in edges.iter().enumerate() {
        for endpoint in [from, to] {
            if endpoint as usize >= node_count {
                return Err(MatrixOrderError::EndpointOutOfRange { edge, endpoint, node_count });
            }
        }
        if !weight.is_finite() || weight < 0.0 {
            return Err(MatrixOrderError::BadWeight { edge, weight });
        }
    }
    Ok(())
}

/// Each node's neighbours with summed symmetric weights, sorted by neighbour; self loops and
/// zero weights dropped. Weights are divided by the largest one first so sums cannot overflow
/// (cosine similarity does not depend on scale).
fn symmetric_links(node_count: usize, edges: &[(u32, u32, f64)]) -> Vec<Vec<(u32, f64)>> {
    let top = edges.iter().map(|e| e.2).fold(0.0, f64::max);
    let mut pairs: Vec<(u32, u32, f64)> = edges
        .iter()
        .filter(|&&(a, b, w)| a != b && w > 0.0)
        .flat_map(|&(a, b, w)| [(a, b, w / top), (b, a, w / top)])
        .collect();
    pairs.sort_unstable_by(|x, y| x.0.cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.total_cmp(&y.2)));
    let mut links: Vec<Vec<(u32, f64)>> = vec![Vec::new(); node_count];
    for (a, b, w) in pairs {
        let row = &mut links[a as usize];
        match row.last_mut() {
            Some(last) if last.0 == b => last.1 += w,
            _ => row.push((b, w)),
        }
    }
    links
}

/// A sparse adjacency row over the linked nodes (renumbered `0..linked.len()`), including the
/// self-weight, sorted by column, with its Euclidean norm.
struct Row {
    entries: Vec<(u32, f64)>,
    norm: f64,
}

/// Renumbers the linked nodes and adds each one's diagonal self-weight (its largest link).
fn rows_with_diagonal(links: &[Vec<(u32, f64)>], linked: &[usize]) -> Vec<Row> {
    let mut new_id = vec![u32::MAX; links.len()];
    for (k, &v) in linked.iter().enumerate() {
        new_id[v] = k as u32;
    }
    linked
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            let self_weight = links[v].iter().map(|e| e.1).fold(0.0, f64::max);
            let mut entries: Vec<(u32, f64)> = links[v].iter().map(|&(u, w)| (new_id[u as usize], w)).collect();
            entries.push((k as u32, self_weight));
            entries.sort_unstable_by_key(|e| e.0);
            let norm = entries.iter().map(|e| e.1 * e.1).sum::<f64>().sqrt();
            Row { entries, norm }
        })
        .collect()
}

/// Cosine similarity of two rows, by merging their sorted entries.
fn similarity(a: &Row, b: &Row) -> f64 {
    let (mut i, mut j, mut dot) = (0, 0, 0.0);
    while let (Some(&(ca, wa)), Some(&(cb, wb))) = (a.entries.get(i), b.entries.get(j)) {
        match ca.cmp(&cb) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                dot += wa * wb;
                i += 1;
                j += 1;
            }
        }
    }
    (dot / (a.norm * b.norm)).clamp(0.0, 1.0)
}

/// The strict upper triangle of a symmetric `n × n` distance matrix, row by row.
struct Condensed {
    n: usize,
    d: Vec<f64>,
}

impl Condensed {
    fn index(&self, i: usize, j: usize) -> usize {
        let (i, j) = if i < j { (i, j) } else { (j, i) };
        i * (2 * self.n - i - 1) / 2 + (j - i - 1)
    }

    fn get(&self, i: usize, j: usize) -> f64 {
        self.d[self.index(i, j)]
    }

    fn set(&mut self, i: usize, j: usize, value: f64) {
        let k = self.index(i, j);
        self.d[k] = value;
    }
}

/// Assumed speed of one dense multiply-add relative to one sparse one, for choosing the path.
const DENSE_SPEEDUP: f64 = 8.0;

/// All pairwise `1 − cos` distances, by whichever is cheaper: walking neighbours of neighbours
/// (O(Σ deg²), for sparse graphs) or dense row-by-row dot products (O(n³/2), for dense ones;
/// it holds an n × n copy of the matrix while it runs). The choice depends only on the input.
fn cosine_distances(rows: &[Row]) -> Condensed {
    let n = rows.len();
    let mut dist = Condensed { n, d: vec![1.0; n * n.saturating_sub(1) / 2] };
    if n < 2 {
        return dist;
    }
    let sparse_cost: f64 = rows.iter().map(|r| (r.entries.len() as f64).powi(2)).sum();
    let dense_cost = (n as f64).powi(3) / 2.0 / DENSE_SPEEDUP;
    if sparse_cost <= dense_cost {
        sparse_similarities(rows, &mut dist);
    } else {
        dense_similarities(rows, &mut dist);
    }
    dist
}

/// Fills `dist` from sparse dot products accumulated in one dense row.
fn sparse_similarities(rows: &[Row], dist: &mut Condensed) {
    let mut acc = vec![0.0; rows.len()];
    let mut touched = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        for &(k, wik) in &row.entries {
            let others = &rows[k as usize].entries;
            let after_i = others.partition_point(|e| e.0 as usize <= i);
            for &(j, wkj) in &others[after_i..] {
                let j = j as usize;
                if acc[j] == 0.0 {
                    touched.push(j);
                }
                acc[j] += wik * wkj;
            }
        }
        for &j in &touched {
            dist.set(i, j, 1.0 - (acc[j] / (row.norm * rows[j].norm)).clamp(0.0, 1.0));
            acc[j] = 0.0;
        }
        touched.clear();
    }
}

/// Rows handled together by the dense kernel (each other row is read once per block).
const BLOCK: usize = 4;

/// Fills `dist` from dense dot products of unit-length rows, four rows against each later row.
fn dense_similarities(rows: &[Row], dist: &mut Condensed) {
    let n = rows.len();
    let width = n.div_ceil(4) * 4;
    let mut unit = vec![0.0; n.div_ceil(BLOCK) * BLOCK * width];
    for (row, out) in rows.iter().zip(unit.chunks_exact_mut(width)) {
        for &(j, w) in &row.entries {
            out[j as usize] = w / row.norm;
        }
    }
    for (block_index, block) in unit.chunks_exact(BLOCK * width).enumerate() {
        let first = block_index * BLOCK;
        for (j, other) in unit.chunks_exact(width).enumerate().take(n).skip(first + 1) {
            let dots = block_dots(block, other);
            for (r, dot) in dots.iter().enumerate() {
                if first + r < j {
                    dist.set(first + r, j, 1.0 - dot.clamp(0.0, 1.0));
                }
            }
        }
    }
}

/// Dot products of `BLOCK` consecutive rows (laid out in `block`) with `other` (which stays in
/// the L1 cache across the rows), four lanes at a time so the compiler can use vector registers.
fn block_dots(block: &[f64], other: &[f64]) -> [f64; BLOCK] {
    let width = other.len();
    let mut acc = [[0.0f64; 4]; BLOCK];
    let (other, _) = other.as_chunks::<4>();
    for (r, row) in block.chunks_exact(width).enumerate() {
        let (row, _) = row.as_chunks::<4>();
        for (x, y) in row.iter().zip(other) {
            for lane in 0..4 {
                acc[r][lane] += x[lane] * y[lane];
            }
        }
    }
    acc.map(|lanes| (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]))
}

/// Joins two leaf sequences in the orientation whose junction pair is most similar; ties keep
/// the earliest of `a·b`, `a·rev(b)`, `rev(a)·b`, `b·a`.
fn join_oriented(mut a: Vec<u32>, mut b: Vec<u32>, rows: &[Row]) -> Vec<u32> {
    let (Some(&a0), Some(&a1), Some(&b0), Some(&b1)) = (a.first(), a.last(), b.first(), b.last()) else {
        a.append(&mut b);
        return a;
    };
    let sim = |x: u32, y: u32| similarity(&rows[x as usize], &rows[y as usize]);
    let options = [sim(a1, b0), sim(a1, b1), sim(a0, b0), sim(a0, b1)];
    let mut best = 0;
    for (k, &s) in options.iter().enumerate() {
        if s > options[best] {
            best = k;
        }
    }
    match best {
        0 => {}
        1 => b.reverse(),
        2 => a.reverse(),
        _ => std::mem::swap(&mut a, &mut b),
    }
    a.append(&mut b);
    a
}

/// The nearest active cluster to `a`: the previous chain element if it is among the nearest,
/// else the lowest index among the nearest.
fn nearest(dist: &Condensed, active: &[bool], a: usize, prev: Option<usize>) -> Option<usize> {
    let mut best = prev.map(|p| (p, dist.get(a, p)));
    for (k, _) in active.iter().enumerate().filter(|&(k, &on)| on && k != a) {
        let d = dist.get(a, k);
        if best.is_none_or(|(_, bd)| d < bd) {
            best = Some((k, d));
        }
    }
    best.map(|(k, _)| k)
}

/// Average-linkage clustering by nearest-neighbour chain; returns the oriented leaf order.
fn average_linkage_order(rows: &[Row]) -> Vec<usize> {
    let n = rows.len();
    let mut dist = cosine_distances(rows);
    let mut active = vec![true; n];
    let mut size = vec![1.0f64; n];
    let mut leaves: Vec<Vec<u32>> = (0..n as u32).map(|k| vec![k]).collect();
    let mut chain: Vec<usize> = Vec::new();
    let mut remaining = n;
    // Each step pushes or merges; a chain never revisits a cluster, so 2n steps a merge is ample.
    let mut budget = 2 * n * n + 16;
    while remaining > 1 && budget > 0 {
        budget -= 1;
        if chain.is_empty() {
            chain.extend(active.iter().position(|&on| on));
        }
        let Some(&a) = chain.last() else { break };
        let prev = chain.len().checked_sub(2).and_then(|k| chain.get(k)).copied();
        let Some(b) = nearest(&dist, &active, a, prev) else {
            break;
        };
        if Some(b) != prev {
            chain.push(b);
            continue;
        }
        chain.truncate(chain.len() - 2);
        let (keep, gone) = (a.min(b), a.max(b));
        merge_distances(&mut dist, &active, &size, keep, gone);
        active[gone] = false;
        size[keep] += size[gone];
        let joined = join_oriented(std::mem::take(&mut leaves[keep]), std::mem::take(&mut leaves[gone]), rows);
        leaves[keep] = joined;
        remaining -= 1;
    }
    // Normally one cluster is left; should the budget run out, remaining clusters follow by index.
    leaves.into_iter().zip(active).filter(|(_, on)| *on).flat_map(|(l, _)| l).map(|k| k as usize).collect()
}

/// Lance–Williams update for average linkage: the merged cluster's distance to every other
/// active cluster is the size-weighted mean of the two parts' distances.
fn merge_distances(dist: &mut Condensed, active: &[bool], size: &[f64], keep: usize, gone: usize) {
    let (sk, sg) = (size[keep], size[gone]);
    for (k, &on) in active.iter().enumerate() {
        if on && k != keep && k != gone {
            let d = (sk * dist.get(keep, k) + sg * dist.get(gone, k)) / (sk + sg);
            dist.set(keep, k, d);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::layout::split_mix::SplitMix64 as Rng;

    fn is_permutation(order: &[usize], n: usize) -> bool {
        let mut seen = vec![false; n];
        order.len() == n && order.iter().all(|&v| v < n && !std::mem::replace(&mut seen[v], true))
    }

    /// How many times consecutive entries of `order` change group.
    fn group_changes(order: &[usize], group: impl Fn(usize) -> usize) -> usize {
        order.windows(2).filter(|w| group(w[0]) != group(w[1])).count()
    }

    fn clique(members: &[u32], weight: f64) -> Vec<(u32, u32, f64)> {
        let mut edges = Vec::new();
        for (i, &a) in members.iter().enumerate() {
            for &b in &members[i + 1..] {
                edges.push((a, b, weight));
            }
        }
        edges
    }

    #[test]
    fn random_graphs_give_a_permutation() {
        let mut rng = Rng(1);
        for n in [2, 17, 200] {
            let edges: Vec<_> =
                (0..3 * n).map(|_| (rng.index(n) as u32, rng.index(n) as u32, rng.index(5) as f64)).collect();
            assert!(is_permutation(&cluster_order(n, &edges).unwrap(), n));
        }
    }

    #[test]
    fn two_interleaved_cliques_come_out_as_two_blocks() {
        let even: Vec<u32> = (0..20).step_by(2).collect();
        let odd: Vec<u32> = (1..20).step_by(2).collect();
        let mut edges = clique(&even, 1.0);
        edges.extend(clique(&odd, 2.0));
        let order = cluster_order(20, &edges).unwrap();
        assert!(is_permutation(&order, 20));
        assert_eq!(group_changes(&order, |v| v % 2), 1, "{order:?}");
    }

    #[test]
    fn permuted_block_diagonal_matrix_is_recovered() {
        let mut rng = Rng(42);
        let sizes = [12usize, 25, 8];
        let n: usize = sizes.iter().sum();
        let mut label: Vec<usize> = sizes.iter().enumerate().flat_map(|(g, &s)| std::iter::repeat_n(g, s)).collect();
        rng.shuffle(&mut label);
        let mut edges = Vec::new();
        for a in 0..n {
            for b in a + 1..n {
                // Dense blocks (70 %), sparse noise between them (2 %).
                let p = if label[a] == label[b] { 70 } else { 2 };
                if rng.index(100) < p {
                    edges.push((a as u32, b as u32, 1.0 + rng.index(3) as f64));
                }
            }
        }
        let order = cluster_order(n, &edges).unwrap();
        assert!(is_permutation(&order, n));
        assert_eq!(group_changes(&order, |v| label[v]), 2, "{:?}", order.iter().map(|&v| label[v]).collect::<Vec<_>>());
    }

    #[test]
    fn a_shuffled_path_is_laid_out_along_the_path() {
        // Path p0 - p1 - ... - p9 under scrambled ids: neighbours in the order are linked.
        let ids = [7u32, 2, 9, 0, 5, 3, 8, 1, 6, 4];
        let edges: Vec<_> = ids.windows(2).map(|w| (w[0], w[1], 1.0)).collect();
        let order = cluster_order(10, &edges).unwrap();
        let pos = |v: usize| ids.iter().position(|&x| x as usize == v).unwrap();
        assert!(order.windows(2).all(|w| pos(w[0]).abs_diff(pos(w[1])) == 1), "{order:?}");
    }

    #[test]
    fn order_depends_only_on_the_edge_set() {
        let mut rng = Rng(9);
        let n = 150;
        let mut edges: Vec<_> = (0..600).map(|_| (rng.index(n) as u32, rng.index(n) as u32, 0.5)).collect();
        edges.sort_unstable_by_key(|e| (e.0.min(e.1), e.0.max(e.1)));
        edges.dedup_by_key(|e| (e.0.min(e.1), e.0.max(e.1)));
        let first = cluster_order(n, &edges).unwrap();
        assert_eq!(first, cluster_order(n, &edges).unwrap());
        rng.shuffle(&mut edges);
        let flipped: Vec<_> = edges.iter().map(|&(a, b, w)| (b, a, w)).collect();
        assert_eq!(first, cluster_order(n, &flipped).unwrap());
        // Scaling every weight changes nothing (cosine similarity is scale-free).
        let scaled: Vec<_> = edges.iter().map(|&(a, b, w)| (a, b, w * 1e300)).collect();
        assert_eq!(first, cluster_order(n, &scaled).unwrap());
    }

    #[test]
    fn isolated_nodes_go_last_in_index_order() {
        // Nodes 1, 4 and 6 have no positive link (6 has only a self loop, 4 a zero-weight edge).
        let edges = [(0, 2, 1.0), (2, 3, 1.0), (5, 0, 1.0), (6, 6, 3.0), (4, 3, 0.0)];
        let order = cluster_order(7, &edges).unwrap();
        assert!(is_permutation(&order, 7));
        assert_eq!(&order[4..], &[1, 4, 6]);
        assert_eq!(cluster_order(0, &[]).unwrap(), Vec::<usize>::new());
        assert_eq!(cluster_order(1, &[]).unwrap(), vec![0]);
        assert_eq!(cluster_order(1, &[(0, 0, 1.0)]).unwrap(), vec![0]);
        assert_eq!(cluster_order(3, &[]).unwrap(), vec![0, 1, 2]);
    }

    #[test]
    fn bad_input_is_refused_with_the_offending_value() {
        let err = cluster_order(3, &[(0, 1, 1.0), (1, 3, 1.0)]).unwrap_err();
        assert_eq!(err, MatrixOrderError::EndpointOutOfRange { edge: 1, endpoint: 3, node_count: 3 });
        assert!(err.to_string().contains("node 3"));
        for weight in [-0.5, f64::NAN, f64::INFINITY] {
            let err = cluster_order(3, &[(0, 1, weight)]).unwrap_err();
            assert!(matches!(err, MatrixOrderError::BadWeight { edge: 0, .. }));
            assert!(err.to_string().contains(&weight.to_string()), "{err}");
        }
        let err = cluster_order(MAX_MATRIX_NODES + 1, &[]).unwrap_err();
        assert_eq!(err, MatrixOrderError::TooManyNodes { count: 3001, cap: 3000 });
        assert!(err.to_string().contains("3001") && err.to_string().contains("3000"));
    }

    /// Distances by each of the two paths.
    fn both_paths(rows: &[Row]) -> [Condensed; 2] {
        let n = rows.len();
        let fresh = || Condensed { n, d: vec![1.0; n * n.saturating_sub(1) / 2] };
        let (mut sparse, mut dense) = (fresh(), fresh());
        sparse_similarities(rows, &mut sparse);
        dense_similarities(rows, &mut dense);
        [sparse, dense]
    }

    #[test]
    fn distances_match_cosine_by_hand_on_both_paths() {
        // Triangle 0-1-2 with weights 1 plus pendant 3 on 2 (weight 2). Rows with diagonal:
        // r0 = (1,1,1,0), r1 = (1,1,1,0), r2 = (1,1,2,2), r3 = (0,0,2,2).
        let links = symmetric_links(4, &[(0, 1, 1.0), (1, 2, 1.0), (2, 0, 1.0), (3, 2, 2.0)]);
        let rows = rows_with_diagonal(&links, &[0, 1, 2, 3]);
        for dist in both_paths(&rows) {
            let expect = |i: usize, j: usize, cos: f64| assert!((dist.get(i, j) - (1.0 - cos)).abs() < 1e-12);
            expect(0, 1, 1.0);
            expect(0, 2, 4.0 / (3f64.sqrt() * 10f64.sqrt()));
            expect(2, 3, 8.0 / (10f64.sqrt() * 8f64.sqrt()));
            expect(0, 3, 2.0 / (3f64.sqrt() * 8f64.sqrt()));
        }
        assert!((similarity(&rows[0], &rows[3]) - 2.0 / (3f64.sqrt() * 8f64.sqrt())).abs() < 1e-12);
        // On a random graph of 37 nodes (not a multiple of the block size) the paths agree.
        let mut rng = Rng(4);
        let edges: Vec<_> =
            (0..150).map(|_| (rng.index(37) as u32, rng.index(37) as u32, 1.0 + rng.index(4) as f64)).collect();
        let links = symmetric_links(37, &edges);
        let linked: Vec<usize> = (0..37).filter(|&v| !links[v].is_empty()).collect();
        let [sparse, dense] = both_paths(&rows_with_diagonal(&links, &linked));
        assert!(sparse.d.iter().zip(&dense.d).all(|(a, b)| (a - b).abs() < 1e-12));
        assert!(sparse.d.iter().any(|&d| d < 0.9));
    }
}
