//! A span-space index of a volume's cells, for finding the cells an isosurface crosses without
//! scanning every cell, built once and queried for any number of levels.
//!
//! The idea is that of Y. Livnat, H.-W. Shen and C. R. Johnson, *A near optimal isosurface
//! extraction algorithm using the span space* (IEEE TVCG 2(1), 1996): each cell is the point
//! `(min, max)` of its corner values, and the cells a level `iso` crosses are the points with
//! `min ≤ iso ≤ max`, a quarter-plane of that space. Here the span space is cut into a lattice of
//! buckets (up to 255 × 255), with bucket boundaries at quantiles of the cells' minima and of
//! their maxima, so each row and each column of buckets holds about the same number of cells; a
//! value that many cells share (a flat background) gets a bucket of its own. The cell numbers
//! are stored grouped by bucket (offsets and one `u32` array, 4 bytes a cell, increasing within
//! a bucket). A query takes the buckets strictly inside the quarter-plane whole and checks the
//! cells of the one row and one column of buckets on its edges against their exact corner
//! values, read from the volume with the same rule as
//! [`active_cells`](super::isosurface::active_cells) — the answer is that function's, cell for
//! cell, for every level.
//!
//! Cells with a missing corner (NaN) are never active and are not stored.

use rayon::prelude::*;

use crate::data::volume::Volume;

use super::isosurface::{PlanePair, corner_offsets, corner_range};

/// Most buckets along each axis of the lattice (so a bucket number fits in a `u16`).
const MAX_BUCKETS: usize = 255;

/// The bucket number of a cell with a missing corner.
const MISSING: u16 = u16::MAX;

/// About how many cells are sampled to place the bucket boundaries.
const SAMPLE: usize = 1 << 16;

/// A span-space index of the cells of one volume (see the module docs). It does not hold the
/// volume: queries are given it again, to check cells at the edge of a query exactly.
#[derive(Clone, Debug)]
pub struct SpanSpace {
    /// Cells along x, y and z.
    cells: [usize; 3],
    /// Boundaries of the buckets of cell minima: bucket `b` holds `edges[b − 1] ≤ min < edges[b]`.
    lo_edges: Vec<f64>,
    /// Boundaries of the buckets of cell maxima.
    hi_edges: Vec<f64>,
    /// The smallest and largest cell minimum in each row (bucket of minima); `(∞, −∞)` if empty.
    lo_range: Vec<(f64, f64)>,
    /// The smallest and largest cell maximum in each column (bucket of maxima).
    hi_range: Vec<(f64, f64)>,
    /// Where each bucket `row · columns + column` starts in `ids`, and the end.
    offsets: Vec<u32>,
    /// Cell numbers, bucket after bucket, increasing within each.
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

/// Per-thread tallies of the build: cells per bucket and the value range of each row and column.
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

    fn merge(mut self, other: Tally) -> Tally {
        self.counts.iter_mut().zip(&other.counts).for_each(|(a, b)| *a += b);
        let widen = |a: &mut (f64, f64), b: &(f64, f64)| *a = (a.0.min(b.0), a.1.max(b.1));
        self.lo_range.iter_mut().zip(&other.lo_range).for_each(|(a, b)| widen(a, b));
        self.hi_range.iter_mut().zip(&other.hi_range).for_each(|(a, b)| widen(a, b));
        self
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

/// The corner minimum and maximum of each cell of one layer, and whether a corner is missing,
/// found from its two voxel planes (each read once by a thread going up the layers): first the
/// two planes' minimum and maximum per voxel column, then over each cell's four columns (the
/// same values as [`corner_range`]).
#[derive(Default)]
struct LayerRanges {
    planes: PlanePair<Vec<f64>>,
    column_lo: Vec<f64>,
    column_hi: Vec<f64>,
    column_missing: Vec<bool>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    missing: Vec<bool>,
}

impl LayerRanges {
    /// The ranges of the cells of layer `k` (between voxel planes `k` and `k + 1`).
    fn read(&mut self, volume: &Volume, k: usize) {
        let [nx, ny, _] = volume.dims();
        let (cx, cy) = (nx - 1, ny - 1);
        let plane = nx * ny;
        self.planes.hold(k, |p, values| {
            values.resize(plane, 0.0);
            volume.read_run(p * plane, values);
        });
        let (near, far) = (&self.planes.near, &self.planes.far);
        self.column_lo.clear();
        self.column_hi.clear();
        self.column_missing.clear();
        for (&a, &b) in near.iter().zip(far) {
            self.column_lo.push(a.min(b));
            self.column_hi.push(a.max(b));
            self.column_missing.push(a.is_nan() || b.is_nan());
        }
        self.lo.resize(cx * cy, 0.0);
        self.hi.resize(cx * cy, 0.0);
        self.missing.resize(cx * cy, false);
        for j in 0..cy {
            let (row, next) = (j * nx, (j + 1) * nx);
            let cells = j * cx..(j + 1) * cx;
            let (lo, hi, missing) =
                (&mut self.lo[cells.clone()], &mut self.hi[cells.clone()], &mut self.missing[cells]);
            let (lo0, lo1) = (&self.column_lo[row..row + nx], &self.column_lo[next..next + nx]);
            let (hi0, hi1) = (&self.column_hi[row..row + nx], &self.column_hi[next..next + nx]);
            let (m0, m1) = (&self.column_missing[row..row + nx], &self.column_missing[next..next + nx]);
            for i in 0..cx {
                lo[i] = lo0[i].min(lo0[i + 1]).min(lo1[i].min(lo1[i + 1]));
                hi[i] = hi0[i].max(hi0[i + 1]).max(hi1[i].max(hi1[i + 1]));
                missing[i] = m0[i] | m0[i + 1] | m1[i] | m1[i + 1];
            }
        }
    }
}

impl SpanSpace {
    /// The index of the cells of `volume` (cell numbers as in
    /// [`isosurface`](super::isosurface)); in parallel over z-slabs of cells.
    pub fn build(volume: &Volume) -> SpanSpace {
        let cells = volume.dims().map(|n| n.saturating_sub(1));
        let [cx, cy, cz] = cells;
        let count = cx * cy * cz;
        let [nx, ny, _] = volume.dims();
        let offsets = corner_offsets(volume);
        let base_of = |n: usize| ((n / (cx * cy)) * ny + n / cx % cy) * nx + n % cx;

        // Bucket boundaries from a sample of cells, one at a jittered place in each stretch.
        let stride = count.div_ceil(SAMPLE).max(1);
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let (mut los, mut his) = (Vec::new(), Vec::new());
        for start in (0..count).step_by(stride) {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let n = start + (state % stride as u64) as usize;
            if let Some((lo, hi)) = corner_range(volume, base_of(n.min(count - 1)), &offsets) {
                los.push(lo);
                his.push(hi);
            }
        }
        los.sort_by(f64::total_cmp);
        his.sort_by(f64::total_cmp);
        // About ∛cells buckets a side: the boundary row and column then hold about as many cells
        // as there are buckets to look at.
        let target = (count as f64).cbrt().ceil() as usize;
        let lo_edges = edges_of(&los, target);
        let hi_edges = edges_of(&his, target);
        let (rows, columns) = (lo_edges.len() + 1, hi_edges.len() + 1);

        // Each cell's bucket, in parallel over layers of cells (their corner ranges read a
        // voxel plane at a time).
        let (find_lo, find_hi) = (Buckets::new(&lo_edges), Buckets::new(&hi_edges));
        let slab = (cx * cy).max(1);
        let mut keys = vec![MISSING; count];
        let tally = keys
            .par_chunks_mut(slab)
            .enumerate()
            .fold(
                || (Tally::new(rows, columns), LayerRanges::default()),
                |(mut tally, mut ranges), (k, chunk)| {
                    ranges.read(volume, k);
                    for (n, key) in chunk.iter_mut().enumerate() {
                        if ranges.missing[n] {
                            continue;
                        }
                        let (lo, hi) = (ranges.lo[n], ranges.hi[n]);
                        let (r, c) = (find_lo.of(lo), find_hi.of(hi));
                        let at = r * columns + c;
                        *key = at as u16;
                        tally.counts[at] += 1;
                        let lr = &mut tally.lo_range[r];
                        *lr = (lr.0.min(lo), lr.1.max(lo));
                        let hr = &mut tally.hi_range[c];
                        *hr = (hr.0.min(hi), hr.1.max(hi));
                    }
                    (tally, ranges)
                },
            )
            .map(|(tally, _)| tally)
            .reduce(|| Tally::new(rows, columns), Tally::merge);

        // Cell numbers grouped by bucket, increasing within each (a counting sort).
        let mut starts = Vec::with_capacity(rows * columns + 1);
        let mut total = 0u32;
        starts.push(0);
        for &c in &tally.counts {
            total += c;
            starts.push(total);
        }
        let mut cursor = starts[..rows * columns].to_vec();
        let mut ids = vec![0u32; total as usize];
        for (n, &key) in keys.iter().enumerate() {
            if key != MISSING {
                let at = &mut cursor[key as usize];
                ids[*at as usize] = n as u32;
                *at += 1;
            }
        }
        SpanSpace {
            cells,
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
        // Many cells: mark them in a bitmap of all cells and read it out in order; few: collect
        // and sort (the runs from whole buckets are already increasing).
        let bitmap = plan.estimate > self.cell_count() / 256;
        self.collect(volume, iso, &plan, bitmap)
    }

    /// The number of cells indexed (those without a missing corner).
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether no cell is indexed (a volume one voxel thick, or every cell missing a corner).
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// The bytes the index takes in memory (not counting the volume).
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + (self.lo_edges.len() + self.hi_edges.len()) * 8
            + (self.lo_range.len() + self.hi_range.len()) * 16
            + (self.offsets.len() + self.ids.len()) * 4
    }

    /// The lattice's size in buckets: rows (minima) and columns (maxima).
    pub fn buckets(&self) -> [usize; 2] {
        [self.lo_range.len(), self.hi_range.len()]
    }

    fn cell_count(&self) -> usize {
        self.cells.iter().product()
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

    /// The cells of `plan` for `iso`, in increasing order, gathered in a bitmap or a sorted list.
    fn collect(&self, volume: &Volume, iso: f64, plan: &Plan, bitmap: bool) -> Vec<u32> {
        let mut out = Vec::with_capacity(if bitmap { 0 } else { plan.estimate });
        let mut bits = if bitmap { vec![0u64; self.cell_count().div_ceil(64)] } else { Vec::new() };
        let mut take = |id: u32| {
            if bitmap {
                bits[id as usize >> 6] |= 1u64 << (id & 63);
            } else {
                out.push(id);
            }
        };
        let [cx, cy, _] = self.cells;
        let [nx, ny, _] = volume.dims();
        let offsets = corner_offsets(volume);
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
                let cells = &self.ids[self.offsets[key] as usize..self.offsets[key + 1] as usize];
                if row_edge == Edge::Whole && column_edge == Edge::Whole {
                    cells.iter().for_each(|&id| take(id));
                    continue;
                }
                for &id in cells {
                    let n = id as usize;
                    let base = ((n / (cx * cy)) * ny + n / cx % cy) * nx + n % cx;
                    if let Some((lo, hi)) = corner_range(volume, base, &offsets)
                        && lo <= iso
                        && iso <= hi
                    {
                        take(id);
                    }
                }
            }
        }
        if bitmap {
            for (w, &word) in bits.iter().enumerate() {
                let mut word = word;
                while word != 0 {
                    out.push((w * 64) as u32 + word.trailing_zeros());
                    word &= word - 1;
                }
            }
        } else {
            // Stable sort: merges the increasing runs of whole buckets.
            out.sort();
        }
        out
    }
}

/// How a query treats the edge row or column of its quarter-plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Edge {
    /// Every cell in it qualifies on this side.
    Whole,
    /// No cell in it qualifies.
    Skip,
    /// Its cells are checked one by one.
    Check,
}

/// The buckets a query reads: rows `..= row`, columns `column ..`, how the edge row and column
/// are treated, and how many cells those buckets hold.
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
            if let Some(plan) = index.plan(iso) {
                for bitmap in [false, true] {
                    assert_eq!(index.collect(vol, iso, &plan, bitmap), expected, "iso {iso}, bitmap {bitmap}");
                }
            }
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
    fn a_larger_lattice_matches_the_scan_and_reads_few_cells() {
        let vol = blobs([48, 40, 36]);
        let found = agrees(&vol, &[0.5, 0.001, 1e-3f32 as f64, 0.9], 9);
        assert!(found > 10);
        let index = SpanSpace::build(&vol);
        let [rows, columns] = index.buckets();
        assert!(rows > 8 && columns > 8, "lattice {rows} × {columns}");
        assert_eq!(index.len(), 47 * 39 * 35);
        assert!(index.memory_bytes() < index.len() * 4 + 300_000);
        // At a level few cells cross, the query reads few more buckets' cells than it returns.
        let plan = index.plan(0.9).expect("finite");
        let active = active_cells(&vol, 0.9).len();
        assert!(active > 0 && plan.estimate < active * 4 + index.len() / 8, "{} for {active}", plan.estimate);
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
