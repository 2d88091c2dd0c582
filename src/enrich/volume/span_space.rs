//! A span-space index of a volume's cells, for finding the cells an isosurface crosses without
//! scanning every cell, built once and queried for any number of levels.
//!
//! The idea is that of Y. Livnat, H.-W. Shen and C. R. Johnson, *A near optimal isosurface
//! extraction algorithm using the span space* (IEEE TVCG 2(1), 1996): each element is the point
//! `(min, max)` of its values, and the elements a level `iso` crosses are the points with
//! `min ≤ iso ≤ max`, a quarter-plane of that space. The elements here are meta-cells (as in
//! Y.-J. Chiang, C. T. Silva and W. J. Schroeder, *Interactive out-of-core isosurface extraction*,
//! IEEE Visualization 1998): bricks of 4 × 4 × 4 cells, each the point of the smallest and
//! largest present voxel among its 5 × 5 × 5, so the index is one pass over the voxels to build
//! and about a sixtieth of the cells to store and search.
//!
//! The span space is cut into a lattice of buckets (up to 255 × 255), with bucket boundaries at
//! quantiles of the bricks' minima and of their maxima, so each row and each column of buckets
//! holds about the same number of bricks; a value that many bricks share (a flat background)
//! gets a bucket of its own. The brick numbers are stored grouped by bucket (offsets and one
//! `u32` array, increasing within a bucket). A query takes the bricks of the buckets strictly
//! inside the quarter-plane whole, checks those of the one row and one column of buckets on its
//! edges against their stored ranges, and then decides the 64 cells of each brick it found
//! exactly, from the brick's voxels with the rule of
//! [`active_cells`](super::isosurface::active_cells) (as three bit sets of the 125 voxels) —
//! the answer is that function's, cell for cell, for every level, in the same order.
//!
//! Cells with a missing corner (NaN) are never active; a brick whose voxels are all missing is
//! not stored.

use rayon::prelude::*;

use crate::data::volume::{Volume, Voxels};

use super::isosurface::LevelTest;

/// Most buckets along each axis of the lattice (so a bucket number fits in a `u16`).
const MAX_BUCKETS: usize = 255;

/// Cells along each side of a brick (so a brick's cells fit the bits of a `u64`).
const BRICK: usize = 4;

/// Voxels along each side of a whole brick.
const SIDE: usize = BRICK + 1;

/// About how many bricks are sampled to place the bucket boundaries.
const SAMPLE: usize = 1 << 16;

/// A span-space index of the bricks of cells of one volume (see the module docs). It does not
/// hold the volume: queries are given it again, to decide the cells of the bricks they find.
#[derive(Clone, Debug)]
pub struct SpanSpace {
    /// Cells along x, y and z.
    cells: [usize; 3],
    /// Bricks along x, y and z (`⌈cells / 4⌉`).
    bricks: [usize; 3],
    /// The smallest present voxel of each brick (`∞` when none is present).
    brick_lo: Vec<f64>,
    /// The largest present voxel of each brick (`−∞` when none is present).
    brick_hi: Vec<f64>,
    /// Boundaries of the buckets of brick minima: bucket `b` holds `edges[b − 1] ≤ min < edges[b]`.
    lo_edges: Vec<f64>,
    /// Boundaries of the buckets of brick maxima.
    hi_edges: Vec<f64>,
    /// The smallest and largest brick minimum in each row (bucket of minima); `(∞, −∞)` if empty.
    lo_range: Vec<(f64, f64)>,
    /// The smallest and largest brick maximum in each column (bucket of maxima).
    hi_range: Vec<(f64, f64)>,
    /// Where each bucket `row · columns + column` starts in `ids`, and the end.
    offsets: Vec<u32>,
    /// Brick numbers `(z · bricks_y + y) · bricks_x + x`, bucket after bucket, increasing within each.
    ids: Vec<u32>,
}

/// The bucket of `v` among `edges`: how many boundaries are `≤ v`. Monotone, so `a ≤ b` gives
/// `bucket(a) ≤ bucket(b)`, and `bucket(a) < bucket(b)` gives `a < b`.
#[inline]
fn bucket(edges: &[f64], v: f64) -> usize {
    edges.partition_point(|&e| e <= v)
}

/// Bucket boundaries for the values `sample` (sorted, no NaN): about `target` quantiles, and a
/// bucket of its own for a value that fills more than one quantile step. At most
/// `MAX_BUCKETS − 1` boundaries.
fn edges_of(sample: &[f64], target: usize) -> Vec<f64> {
    let m = sample.len();
    let mut edges = Vec::new();
    if m == 0 {
        return edges;
    }
    let mut target = target.clamp(1, MAX_BUCKETS);
    loop {
        edges.clear();
        let mut previous: Option<f64> = None;
        for q in 1..target {
            let v = sample[q * m / target];
            if previous == Some(v) {
                // A value reached by two quantiles: it alone gets a bucket, [v, next_up(v)).
                edges.push(v.next_up());
            }
            edges.push(v);
            previous = Some(v);
        }
        edges.sort_by(f64::total_cmp);
        edges.dedup_by(|a, b| a == b);
        if edges.len() < MAX_BUCKETS {
            return edges;
        }
        target = target * 3 / 4;
    }
}

/// Tallies of the build: bricks per bucket and the value range of each row and column.
struct Tally {
    counts: Vec<u32>,
    lo_range: Vec<(f64, f64)>,
    hi_range: Vec<(f64, f64)>,
}

impl Tally {
    fn new(rows: usize, columns: usize) -> Tally {
        let empty = (f64::INFINITY, f64::NEG_INFINITY);
        Tally { counts: vec![0; rows * columns], lo_range: vec![empty; rows], hi_range: vec![empty; columns] }
    }

    /// Count a brick with range `(lo, hi)` in bucket `(r, c)`.
    fn add(&mut self, r: usize, c: usize, lo: f64, hi: f64) {
        self.counts[r * self.hi_range.len() + c] += 1;
        let lr = &mut self.lo_range[r];
        *lr = (lr.0.min(lo), lr.1.max(lo));
        let hr = &mut self.hi_range[c];
        *hr = (hr.0.min(hi), hr.1.max(hi));
    }
}

/// Bucket lookup for a row or column of the lattice: [`bucket`] through a table by the top 16
/// bits of a value's order-preserving bit pattern (sign, exponent and 4 bits of mantissa): the
/// table gives how many boundaries lie in lower parts of that order, and the few boundaries
/// sharing the value's part are then compared one by one.
struct Buckets {
    /// The boundaries, `-0.0` as `+0.0` (they compare equal, so `≤` is unchanged).
    edges: Vec<f64>,
    /// For each top-16-bit part, the number of boundaries in lower parts.
    below: Vec<u8>,
}

/// A `u64` whose order is the order of the non-NaN `v` (`-0.0` taken as `+0.0`).
#[inline]
fn ordered_bits(v: f64) -> u64 {
    let bits = (v + 0.0).to_bits();
    if bits >> 63 == 1 { !bits } else { bits | 1 << 63 }
}

impl Buckets {
    fn new(edges: &[f64]) -> Buckets {
        let edges: Vec<f64> = edges.iter().map(|e| e + 0.0).collect();
        let mut below = vec![0u8; 1 << 16];
        let mut count = 0;
        for (part, slot) in below.iter_mut().enumerate() {
            while count < edges.len() && ((ordered_bits(edges[count]) >> 48) as usize) < part {
                count += 1;
            }
            *slot = count as u8;
        }
        Buckets { edges, below }
    }

    /// How many boundaries are `≤ v` (at most 254, so a `u8` holds the count); 0 for NaN.
    #[inline]
    fn of(&self, v: f64) -> usize {
        if v.is_nan() {
            return 0;
        }
        let mut at = self.below[(ordered_bits(v) >> 48) as usize] as usize;
        while at < self.edges.len() && self.edges[at] <= v {
            at += 1;
        }
        at
    }
}

/// The smallest and largest present voxel of every brick, brick layer by brick layer in
/// parallel: per voxel column over the layer's planes, then per row over each brick's run of
/// columns, then over each brick's rows.
fn brick_ranges(volume: &Volume, cells: [usize; 3], bricks: [usize; 3]) -> (Vec<f64>, Vec<f64>) {
    let [nx, ny, _] = volume.dims();
    let [bx, by, bz] = bricks;
    let layer = bx * by;
    let (mut lo, mut hi) = (vec![f64::INFINITY; layer * bz], vec![f64::NEG_INFINITY; layer * bz]);
    // Brick b of an axis with `c` cells covers voxels `BRICK·b ..= min(BRICK·(b + 1), c)`.
    let span = |b: usize, c: usize| BRICK * b..=(BRICK * (b + 1)).min(c);
    lo.par_chunks_mut(layer.max(1)).zip(hi.par_chunks_mut(layer.max(1))).enumerate().for_each_init(
        || (vec![0.0; nx * ny], vec![0.0; nx * ny], vec![0.0; nx * ny], vec![0.0; ny * bx], vec![0.0; ny * bx]),
        |(values, col_lo, col_hi, row_lo, row_hi), (z, (lo, hi))| {
            col_lo.fill(f64::INFINITY);
            col_hi.fill(f64::NEG_INFINITY);
            for p in span(z, cells[2]) {
                volume.read_run(p * nx * ny, values);
                for ((v, l), h) in values.iter().zip(col_lo.iter_mut()).zip(col_hi.iter_mut()) {
                    // `min` and `max` pass over NaN: missing voxels widen nothing.
                    *l = l.min(*v);
                    *h = h.max(*v);
                }
            }
            for y in 0..ny {
                let (l, h) = (&col_lo[y * nx..(y + 1) * nx], &col_hi[y * nx..(y + 1) * nx]);
                for b in 0..bx {
                    let xs = span(b, cells[0]);
                    row_lo[y * bx + b] = l[xs.clone()].iter().fold(f64::INFINITY, |a, &v| a.min(v));
                    row_hi[y * bx + b] = h[xs].iter().fold(f64::NEG_INFINITY, |a, &v| a.max(v));
                }
            }
            for b_y in 0..by {
                let (l, h) = (&mut lo[b_y * bx..(b_y + 1) * bx], &mut hi[b_y * bx..(b_y + 1) * bx]);
                for y in span(b_y, cells[1]) {
                    for b in 0..bx {
                        l[b] = l[b].min(row_lo[y * bx + b]);
                        h[b] = h[b].max(row_hi[y * bx + b]);
                    }
                }
            }
        },
    );
    (lo, hi)
}

/// Slots for a brick's voxels, slot `(z·5 + y)·5 + x` (125 used).
const ROOM: usize = 128;

/// A thread's room for the voxels of one brick: stored `f32`s or numbers.
struct Room {
    narrow: [f32; ROOM],
    wide: [f64; ROOM],
}

impl Default for Room {
    fn default() -> Room {
        Room { narrow: [0.0; ROOM], wide: [0.0; ROOM] }
    }
}

/// The level tests `[≤ iso, ≥ iso, missing]` of a brick's slots, bit `i` for slot `i`.
fn brick_bits<T: Copy + PartialOrd>(test: LevelTest<T>, values: &[T; ROOM]) -> [u128; 3] {
    let (low, high) = (test.bits(&values[..64]), test.bits(&values[64..]));
    std::array::from_fn(|t| u128::from(low[t]) | u128::from(high[t]) << 64)
}

/// The active cells of brick `brick` for `iso`, as bits `k·16 + j·4 + i` of its cells: those
/// with some corner `≤ iso`, some corner `≥ iso` and none missing (the rule of
/// [`active_cells`](super::isosurface::active_cells)). The brick's voxels are gathered as up to
/// 25 runs into `room` (slot `(z·5 + y)·5 + x`; `f32` voxels without a scale as stored, others as
/// numbers), become three bit sets, and a cell's bits are those of its eight corners ORed, by
/// shifts. Slots outside a partial brick hold anything: no cell of the brick reads them.
fn brick_mask(volume: &Volume, cells: [usize; 3], brick: [usize; 3], iso: f64, room: &mut Room) -> u64 {
    let [nx, ny, _] = volume.dims();
    let origin = brick.map(|b| b * BRICK);
    let width: [usize; 3] = std::array::from_fn(|a| (cells[a] - origin[a]).min(BRICK));
    let run = width[0] + 1;
    let start = |z: usize, y: usize| ((origin[2] + z) * ny + origin[1] + y) * nx + origin[0];
    let slot = |z: usize, y: usize| (z * SIDE + y) * SIDE;
    let [le, ge, missing] = match (volume.voxels(), volume.scale()) {
        (Voxels::F32(stored), None) => {
            if run == SIDE {
                // Runs of a constant length: copies the compiler writes out in place.
                for z in 0..=width[2] {
                    for y in 0..=width[1] {
                        let (from, to) = (start(z, y), slot(z, y));
                        room.narrow[to..to + SIDE].copy_from_slice(&stored[from..from + SIDE]);
                    }
                }
            } else {
                for z in 0..=width[2] {
                    for y in 0..=width[1] {
                        let (from, to) = (start(z, y), slot(z, y));
                        room.narrow[to..to + run].copy_from_slice(&stored[from..from + run]);
                    }
                }
            }
            brick_bits(LevelTest::stored_f32(iso), &room.narrow)
        }
        _ => {
            if width == [BRICK; 3] {
                let mut starts = [0usize; SIDE * SIDE];
                for (r, s) in starts.iter_mut().enumerate() {
                    *s = start(r / SIDE, r % SIDE);
                }
                volume.read_runs(&starts, &mut room.wide[..SIDE * SIDE * SIDE]);
            } else {
                for z in 0..=width[2] {
                    for y in 0..=width[1] {
                        let to = slot(z, y);
                        volume.read_run(start(z, y), &mut room.wide[to..to + run]);
                    }
                }
            }
            brick_bits(LevelTest::numbers(iso), &room.wide)
        }
    };
    let corners = |s: u128| {
        let x = s | s >> 1;
        let xy = x | x >> SIDE;
        xy | xy >> (SIDE * SIDE)
    };
    let active = corners(le) & corners(ge) & !corners(missing);
    let run_bits = (1u128 << width[0]) - 1;
    let mut mask = 0u64;
    for k in 0..width[2] {
        for j in 0..width[1] {
            let bits = (active >> ((k * SIDE + j) * SIDE)) & run_bits;
            mask |= (bits as u64) << (k * BRICK * BRICK + j * BRICK);
        }
    }
    mask
}

impl SpanSpace {
    /// The index of the cells of `volume` (cell numbers as in
    /// [`isosurface`](super::isosurface)); the bricks' ranges in parallel over brick layers.
    pub fn build(volume: &Volume) -> SpanSpace {
        let cells = volume.dims().map(|n| n.saturating_sub(1));
        let bricks = if cells.contains(&0) { [0; 3] } else { cells.map(|c| c.div_ceil(BRICK)) };
        let count: usize = bricks.iter().product();
        let (brick_lo, brick_hi) = brick_ranges(volume, cells, bricks);

        // Bucket boundaries from a sample of the bricks with a present voxel.
        let stride = count.div_ceil(SAMPLE).max(1);
        let (mut los, mut his): (Vec<f64>, Vec<f64>) = (0..count)
            .step_by(stride)
            .filter(|&b| brick_lo[b] <= brick_hi[b])
            .map(|b| (brick_lo[b], brick_hi[b]))
            .unzip();
        los.sort_by(f64::total_cmp);
        his.sort_by(f64::total_cmp);
        // About ∛(2 · bricks) buckets a side: a query visits up to half the lattice's buckets and
        // checks the bricks of one row and one column, and this balances the two.
        let target = (2.0 * count as f64).cbrt().ceil() as usize;
        let lo_edges = edges_of(&los, target);
        let hi_edges = edges_of(&his, target);
        let (rows, columns) = (lo_edges.len() + 1, hi_edges.len() + 1);

        // Each brick's bucket, then the brick numbers grouped by bucket (a counting sort).
        let (find_lo, find_hi) = (Buckets::new(&lo_edges), Buckets::new(&hi_edges));
        let mut tally = Tally::new(rows, columns);
        let keys: Vec<Option<u32>> = (0..count)
            .map(|b| {
                let (lo, hi) = (brick_lo[b], brick_hi[b]);
                (lo <= hi).then(|| {
                    let (r, c) = (find_lo.of(lo), find_hi.of(hi));
                    tally.add(r, c, lo, hi);
                    (r * columns + c) as u32
                })
            })
            .collect();
        let mut starts = Vec::with_capacity(rows * columns + 1);
        let mut total = 0u32;
        starts.push(0);
        for &c in &tally.counts {
            total += c;
            starts.push(total);
        }
        let mut cursor = starts[..rows * columns].to_vec();
        let mut ids = vec![0u32; total as usize];
        for (b, key) in keys.iter().enumerate() {
            if let Some(key) = key {
                let at = &mut cursor[*key as usize];
                ids[*at as usize] = b as u32;
                *at += 1;
            }
        }
        SpanSpace {
            cells,
            bricks,
            brick_lo,
            brick_hi,
            lo_edges,
            hi_edges,
            lo_range: tally.lo_range,
            hi_range: tally.hi_range,
            offsets: starts,
            ids,
        }
    }

    /// The cells of `volume` (the one the index was built from) whose corners are all present
    /// and whose corner minimum `≤ iso ≤` maximum, in increasing order: exactly
    /// [`active_cells`](super::isosurface::active_cells)`(volume, iso)`, which it falls back to
    /// for a volume of other dimensions. Empty when `iso` is not finite.
    pub fn active_cells(&self, volume: &Volume, iso: f64) -> Vec<u32> {
        if volume.dims().map(|n| n.saturating_sub(1)) != self.cells {
            return super::isosurface::active_cells(volume, iso);
        }
        let Some(plan) = self.plan(iso) else {
            return Vec::new();
        };
        let found = self.bricks_of(&plan, iso);
        // Brick layer by brick layer in parallel: each layer's bricks decided, then its cells
        // listed in order; the layers' lists joined.
        let [bx, by, _] = self.bricks;
        let mut layers = Vec::new();
        let mut first = 0;
        for t in 1..=found.len() {
            if t == found.len() || found[t] as usize / (bx * by) != found[first] as usize / (bx * by) {
                layers.push(first..t);
                first = t;
            }
        }
        let parts: Vec<Vec<u32>> = layers
            .par_iter()
            .map_init(
                || (Room::default(), Vec::new()),
                |(room, masks), range| {
                    let bricks = &found[range.clone()];
                    masks.clear();
                    masks.extend(bricks.iter().map(|&b| {
                        let b = b as usize;
                        brick_mask(volume, self.cells, [b % bx, b / bx % by, b / (bx * by)], iso, room)
                    }));
                    self.cells_in_order(bricks, masks)
                },
            )
            .collect();
        parts.concat()
    }

    /// The number of bricks indexed (those with a present voxel).
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether no brick is indexed (a volume one voxel thick, or every voxel missing).
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// The bytes the index takes in memory (not counting the volume).
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + (self.lo_edges.len() + self.hi_edges.len() + self.brick_lo.len() + self.brick_hi.len()) * 8
            + (self.lo_range.len() + self.hi_range.len()) * 16
            + (self.offsets.len() + self.ids.len()) * 4
    }

    /// The lattice's size in buckets: rows (minima) and columns (maxima).
    pub fn buckets(&self) -> [usize; 2] {
        [self.lo_range.len(), self.hi_range.len()]
    }

    /// Which buckets a query for `iso` reads and how, or `None` when it finds nothing.
    fn plan(&self, iso: f64) -> Option<Plan> {
        if !iso.is_finite() || self.ids.is_empty() {
            return None;
        }
        let row = bucket(&self.lo_edges, iso);
        let column = bucket(&self.hi_edges, iso);
        let (lo_min, lo_max) = self.lo_range[row];
        let (hi_min, hi_max) = self.hi_range[column];
        // The edge row is taken whole when all its minima are ≤ iso, skipped when none is; the
        // same for the edge column's maxima against iso.
        let row_check = if lo_max <= iso {
            Edge::Whole
        } else if lo_min > iso {
            Edge::Skip
        } else {
            Edge::Check
        };
        let column_check = if hi_min >= iso {
            Edge::Whole
        } else if hi_max < iso {
            Edge::Skip
        } else {
            Edge::Check
        };
        let columns = self.hi_range.len();
        let mut estimate = 0usize;
        for r in 0..=row {
            let first = r * columns + column;
            estimate += (self.offsets[first + columns - column] - self.offsets[first]) as usize;
        }
        Some(Plan { row, column, row_check, column_check, estimate })
    }

    /// The bricks of `plan` whose range holds `iso`, in increasing order.
    fn bricks_of(&self, plan: &Plan, iso: f64) -> Vec<u32> {
        let mut out = Vec::with_capacity(plan.estimate);
        let columns = self.hi_range.len();
        for r in 0..=plan.row {
            let row_edge = if r == plan.row { plan.row_check } else { Edge::Whole };
            if row_edge == Edge::Skip {
                continue;
            }
            for c in plan.column..columns {
                let column_edge = if c == plan.column { plan.column_check } else { Edge::Whole };
                if column_edge == Edge::Skip {
                    continue;
                }
                let key = r * columns + c;
                let bricks = &self.ids[self.offsets[key] as usize..self.offsets[key + 1] as usize];
                if row_edge == Edge::Whole && column_edge == Edge::Whole {
                    out.extend_from_slice(bricks);
                } else {
                    out.extend(
                        bricks
                            .iter()
                            .filter(|&&b| self.brick_lo[b as usize] <= iso && iso <= self.brick_hi[b as usize]),
                    );
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// The cells set in `masks` of the bricks `found` (increasing), in increasing cell number:
    /// brick layer by brick layer, then cell layer, brick row, cell row, brick along x.
    fn cells_in_order(&self, found: &[u32], masks: &[u64]) -> Vec<u32> {
        let [cx, cy, cz] = self.cells;
        let [bx, by, _] = self.bricks;
        let count = masks.iter().map(|m| m.count_ones() as usize).sum();
        let mut out = Vec::with_capacity(count);
        // The found bricks of one brick layer, as runs sharing a brick row.
        let mut rows: Vec<(usize, usize)> = Vec::new();
        let mut t = 0;
        while t < found.len() {
            let bz = found[t] as usize / (bx * by);
            rows.clear();
            while t < found.len() && found[t] as usize / (bx * by) == bz {
                let (row, first) = (found[t] as usize / bx, t);
                while t < found.len() && found[t] as usize / bx == row {
                    t += 1;
                }
                rows.push((first, t));
            }
            for kl in 0..BRICK.min(cz - bz * BRICK) {
                let k = bz * BRICK + kl;
                for &(first, end) in &rows {
                    let b_y = found[first] as usize / bx % by;
                    for jl in 0..BRICK.min(cy - b_y * BRICK) {
                        let j = b_y * BRICK + jl;
                        let shift = kl * BRICK * BRICK + jl * BRICK;
                        for (&brick, &mask) in found[first..end].iter().zip(&masks[first..end]) {
                            let mut bits = (mask >> shift) & ((1 << BRICK) - 1);
                            let row_first = ((k * cy + j) * cx + brick as usize % bx * BRICK) as u32;
                            while bits != 0 {
                                out.push(row_first + bits.trailing_zeros());
                                bits &= bits - 1;
                            }
                        }
                    }
                }
            }
        }
        out
    }
}

/// How a query treats the edge row or column of its quarter-plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Edge {
    /// Every brick in it qualifies on this side.
    Whole,
    /// No brick in it qualifies.
    Skip,
    /// Its bricks are checked one by one.
    Check,
}

/// The buckets a query reads: rows `..= row`, columns `column ..`, how the edge row and column
/// are treated, and how many bricks those buckets hold.
struct Plan {
    row: usize,
    column: usize,
    row_check: Edge,
    column_check: Edge,
    estimate: usize,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::volume::{Scale, Voxels};
    use crate::enrich::volume::isosurface::active_cells;

    /// xorshift64*: deterministic noise.
    struct Rng(u64);

    impl Rng {
        fn new(seed: u64) -> Rng {
            Rng(seed.wrapping_mul(0x2545_F491_4F6C_DD1D) | 1)
        }

        /// A number in `[0, 1)`.
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
        }

        fn below(&mut self, n: usize) -> usize {
            (self.next() * n as f64) as usize
        }
    }

    fn volume(dims: [usize; 3], voxels: Voxels) -> Volume {
        Volume::new(dims, voxels, [1.0; 3]).expect("volume")
    }

    /// Levels that probe every way a query can go wrong: the voxel values and their
    /// neighbouring floats, the bucket boundaries, values between and outside the data.
    fn levels(vol: &Volume, index: &SpanSpace, rng: &mut Rng) -> Vec<f64> {
        let values: Vec<f64> = vol.values().filter(|v| !v.is_nan()).collect();
        let mut isos = vec![0.0, -0.0, 1e300, -1e300];
        if let (Some(lo), Some(hi)) =
            (values.iter().copied().min_by(f64::total_cmp), values.iter().copied().max_by(f64::total_cmp))
        {
            for v in [lo, hi] {
                isos.extend([v, v.next_up(), v.next_down()]);
            }
            for _ in 0..20 {
                let t = rng.next() * 1.2 - 0.1;
                isos.push(lo + (hi - lo) * t);
            }
        }
        for _ in 0..20.min(values.len()) {
            let v = values[rng.below(values.len())];
            isos.extend([v, v.next_up(), v.next_down()]);
        }
        for &e in index.lo_edges.iter().chain(&index.hi_edges) {
            isos.extend([e, e.next_down()]);
        }
        isos.retain(|v| v.is_finite());
        isos
    }

    /// The index agrees with the brute-force scan at `isos` and at probing levels, by both ways
    /// of gathering the answer; returns how many levels found cells.
    fn agrees(vol: &Volume, extra: &[f64], seed: u64) -> usize {
        let index = SpanSpace::build(vol);
        let mut rng = Rng::new(seed);
        let mut isos = levels(vol, &index, &mut rng);
        isos.extend(extra);
        let mut found = 0;
        for iso in isos {
            let expected = active_cells(vol, iso);
            assert_eq!(index.active_cells(vol, iso), expected, "iso {iso} dims {:?}", vol.dims());
            found += usize::from(!expected.is_empty());
        }
        for iso in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(index.active_cells(vol, iso).is_empty(), "iso {iso}");
        }
        found
    }

    const SHAPES: [[usize; 3]; 8] =
        [[2, 2, 2], [3, 2, 2], [7, 5, 3], [20, 17, 9], [2, 9, 30], [33, 2, 14], [1, 6, 6], [6, 6, 1]];

    #[test]
    fn random_volumes_match_the_scan() {
        for (s, dims) in SHAPES.into_iter().enumerate() {
            let mut rng = Rng::new(11 + s as u64);
            let n: usize = dims.iter().product();
            let vol = volume(dims, Voxels::F64((0..n).map(|_| rng.next() * 10.0 - 5.0).collect()));
            let found = agrees(&vol, &[], s as u64);
            let thin = dims.contains(&1);
            assert_eq!(found == 0, thin, "dims {dims:?}: {found} levels found cells");
        }
    }

    #[test]
    fn ties_flat_cells_and_constant_volumes_match_the_scan() {
        for (s, dims) in SHAPES.into_iter().enumerate() {
            let mut rng = Rng::new(40 + s as u64);
            let n: usize = dims.iter().product();
            // A few levels only: many cells flat, many corners exactly at a voxel level.
            let vol = volume(dims, Voxels::F32((0..n).map(|_| (rng.below(5) as f32) * 0.25).collect()));
            agrees(&vol, &[0.0, 0.25, 0.5, 0.75, 1.0, 0.125], s as u64);
        }
        let vol = volume([6, 5, 4], Voxels::F64(vec![3.0; 120]));
        agrees(&vol, &[3.0], 1);
        let index = SpanSpace::build(&vol);
        assert_eq!(index.active_cells(&vol, 3.0).len(), 5 * 4 * 3, "every flat cell holds its value");
        assert!(index.active_cells(&vol, 3.0f64.next_up()).is_empty());
        assert!(index.active_cells(&vol, 3.0f64.next_down()).is_empty());
    }

    #[test]
    fn missing_voxels_and_infinite_values_match_the_scan() {
        for (s, dims) in SHAPES.into_iter().enumerate() {
            let mut rng = Rng::new(70 + s as u64);
            let n: usize = dims.iter().product();
            let values = (0..n)
                .map(|_| match rng.below(12) {
                    0 => f64::NAN,
                    1 => f64::INFINITY,
                    2 => f64::NEG_INFINITY,
                    _ => rng.next(),
                })
                .collect();
            agrees(&volume(dims, Voxels::F64(values)), &[0.5], s as u64);
        }
        // Every voxel missing: nothing indexed, nothing found.
        let vol = volume([4, 4, 4], Voxels::F32(vec![f32::NAN; 64]));
        let index = SpanSpace::build(&vol);
        assert!(index.is_empty());
        assert!(index.active_cells(&vol, 0.0).is_empty());
        // Another volume's query is its full scan.
        let other = blobs([9, 8, 7]);
        assert_eq!(index.active_cells(&other, 0.5), active_cells(&other, 0.5));
        assert!(!active_cells(&other, 0.5).is_empty());
    }

    #[test]
    fn integer_and_scaled_voxels_match_the_scan() {
        let mut rng = Rng::new(5);
        let dims = [17, 13, 11];
        let n: usize = dims.iter().product();
        let bytes: Vec<u8> = (0..n).map(|_| rng.below(256) as u8).collect();
        let vol = volume(dims, Voxels::U8(bytes.clone()));
        agrees(&vol, &[0.0, 255.0, 127.5], 1);
        // A scale whose values are not exact in binary (0.1 · k − 3).
        let scaled = volume(dims, Voxels::U8(bytes)).with_scale(Some(Scale { slope: 0.1, inter: -3.0 }));
        let at_voxel = scaled.get(7);
        agrees(&scaled, &[at_voxel, -3.0, 0.1 * 255.0 - 3.0], 2);
        let shorts: Vec<i16> = (0..n).map(|_| (rng.below(2000) as i16) - 1000).collect();
        agrees(&volume(dims, Voxels::I16(shorts)), &[0.0, -1000.0], 3);
    }

    /// Four Gaussian blobs on a background of exact zeros: most cells share one value.
    fn blobs(dims: [usize; 3]) -> Volume {
        let centres = [[0.3, 0.3, 0.3], [0.7, 0.35, 0.6], [0.4, 0.7, 0.45], [0.65, 0.7, 0.25]];
        let mut values = Vec::new();
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let p = [i, j, k].map(|x| x as f64);
                    let p = [p[0] / (dims[0] - 1) as f64, p[1] / (dims[1] - 1) as f64, p[2] / (dims[2] - 1) as f64];
                    let f: f64 = centres
                        .iter()
                        .map(|c| (-(0..3).map(|a| (p[a] - c[a]).powi(2)).sum::<f64>() / 0.02).exp())
                        .sum();
                    values.push(if f < 1e-3 { 0.0 } else { f as f32 });
                }
            }
        }
        volume(dims, Voxels::F32(values))
    }

    #[test]
    fn a_larger_lattice_matches_the_scan_and_reads_few_bricks() {
        let vol = blobs([48, 40, 36]);
        let found = agrees(&vol, &[0.5, 0.001, 1e-3f32 as f64, 0.9], 9);
        assert!(found > 10);
        let index = SpanSpace::build(&vol);
        assert_eq!(index.len(), 12 * 10 * 9, "⌈47/4⌉ × ⌈39/4⌉ × ⌈35/4⌉ bricks");
        assert!(index.memory_bytes() < 60_000, "{} bytes", index.memory_bytes());

        let vol = blobs([97, 81, 73]);
        let index = SpanSpace::build(&vol);
        let [rows, columns] = index.buckets();
        assert!(rows > 12 && columns > 12, "lattice {rows} × {columns}");
        // Without missing voxels a brick whose range holds the level has an active cell (a path of
        // voxels from one ≤ iso to one ≥ iso crosses the level in some cell), so the bricks a
        // query finds are exactly those holding an active cell.
        let [bx, by, _] = index.bricks;
        for iso in [0.9, 0.5, 0.05] {
            let active = active_cells(&vol, iso);
            let mut holding: Vec<u32> = active
                .iter()
                .map(|&n| {
                    let [i, j, k] = [n as usize % 96, n as usize / 96 % 80, n as usize / (96 * 80)];
                    ((k / BRICK * by + j / BRICK) * bx + i / BRICK) as u32
                })
                .collect();
            holding.dedup();
            holding.sort_unstable();
            holding.dedup();
            let plan = index.plan(iso).expect("finite");
            assert_eq!(index.bricks_of(&plan, iso), holding, "iso {iso}");
            // The buckets it reads hold few more bricks than it finds.
            assert!(plan.estimate < holding.len() * 4 + index.len() / 8, "{} for {}", plan.estimate, holding.len());
            assert_eq!(index.active_cells(&vol, iso), active, "iso {iso}");
        }
        // The background value has a bucket of its own: a level just above it reads none of it.
        let plan = index.plan(1e-9).expect("finite");
        assert!(plan.estimate < index.len() / 4, "{}", plan.estimate);
    }

    #[test]
    fn the_table_bucket_search_counts_as_the_partition_point() {
        let mut rng = Rng::new(3);
        for n in [0, 1, 2, 7, 128, 200, MAX_BUCKETS - 1] {
            // Values over many magnitudes and signs, some sharing a table part, and zero.
            let mut edges: Vec<f64> = (0..n)
                .map(|k| if k == 3 { 0.0 } else { (rng.next() * 2.0 - 1.0) * 10f64.powf(rng.next() * 12.0 - 6.0) })
                .collect();
            edges.sort_by(f64::total_cmp);
            let search = Buckets::new(&edges);
            edges.dedup();
            let mut probes = vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -0.0, 2.0, -2.0, 1e300, -1e-300];
            probes.extend((0..200).map(|_| (rng.next() * 2.0 - 1.0) * 10f64.powf(rng.next() * 14.0 - 7.0)));
            for &e in &edges {
                probes.extend([e, e.next_up(), e.next_down()]);
            }
            for v in probes {
                assert_eq!(search.of(v), bucket(&edges, v), "{n} boundaries, value {v}");
            }
        }
    }
}
