//! Counting rows into a grid of bins, for density views of more rows than marks can show: the
//! bins of each axis ([`Bins`]), the count grid ([`CountGrid`]) and the extent of the rows
//! ([`Extent`]), computed from columns in memory ([`count_columns`], [`extent_of_columns`]) or
//! from a source's lazy plan ([`plan`]) — the same arithmetic either way, so both give the same
//! grid bit for bit.

pub mod columns;
pub mod footer;
pub mod groups;
pub mod plan;
pub mod remote;
pub mod tally;

use rayon::prelude::*;

/// One axis of a count grid: `n` equal bins from `lo` to `hi` (equal in `log10` of the values on
/// a log axis).
///
/// Bin `k` holds the values `v` with `edge(k) ≤ v < edge(k + 1)`, where
/// `edge(k) = lo + (hi − lo) · k / n` (in `log10` on a log axis); the last bin also holds
/// `v = hi`, so every value from `lo` to `hi` has exactly one bin. Values outside, NaN, ±∞ and, on a
/// log axis, values ≤ 0 have none.
#[derive(Clone, Debug, PartialEq)]
pub struct Bins {
    /// The bins' edges in the axis' own terms (`log10` of the values on a log axis), `n + 1` of
    /// them, ascending.
    edges: Vec<f64>,
    log: bool,
    /// Bins per unit of the axis' terms: `n / (hi − lo)`, for the first guess of a bin.
    per_unit: f64,
}

impl Bins {
    /// `n` bins (at least one, at most [`MAX_BINS`]) from `lo` to `hi`; `None` unless `lo < hi`, both finite (and
    /// positive on a log axis).
    pub fn new(lo: f64, hi: f64, n: usize, log: bool) -> Option<Bins> {
        let (a, b) = if log { (lo.log10(), hi.log10()) } else { (lo, hi) };
        if !(a.is_finite() && b.is_finite() && a < b) {
            return None;
        }
        let n = n.clamp(1, MAX_BINS);
        let edges = (0..=n).map(|k| if k == n { b } else { a + (b - a) * k as f64 / n as f64 }).collect();
        Some(Bins { edges, log, per_unit: n as f64 / (b - a) })
    }

    /// Linear bins with the given `edges` (at least two, ascending, finite, equally spaced up to
    /// rounding, as a histogram's are), so a value's bin is decided by these very edges; `None`
    /// unless the edges span a range.
    pub fn from_edges(edges: Vec<f64>) -> Option<Bins> {
        let n = edges.len().checked_sub(1).filter(|n| (1..=MAX_BINS).contains(n))?;
        let (a, b) = (edges[0], edges[n]);
        let ascending = edges.windows(2).all(|w| w[0] <= w[1]);
        (a.is_finite() && b.is_finite() && a < b && ascending).then(|| Bins {
            per_unit: n as f64 / (b - a),
            edges,
            log: false,
        })
    }

    /// Number of bins.
    pub fn len(&self) -> usize {
        self.edges.len() - 1
    }

    /// Whether the axis has no bins (never: [`Bins::new`] makes at least one).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether the bins are equal in `log10` of the values.
    pub fn is_log(&self) -> bool {
        self.log
    }

    /// The value at edge `k` (0 to `len()`), in data units.
    pub fn edge(&self, k: usize) -> f64 {
        let e = self.edges[k.min(self.len())];
        if self.log { 10f64.powf(e) } else { e }
    }

    /// The value in the axis' own terms, if it can be placed on the axis at all.
    fn term(&self, v: f64) -> Option<f64> {
        let t = if self.log { if v > 0.0 { v.log10() } else { return None } } else { v };
        t.is_finite().then_some(t)
    }

    /// The bin holding `v`, as documented on [`Bins`].
    pub fn index(&self, v: f64) -> Option<usize> {
        self.index_of_term(self.term(v)?)
    }

    #[inline]
    fn index_of_term(&self, t: f64) -> Option<usize> {
        let n = self.len();
        let (lo, hi) = (self.edges[0], self.edges[n]);
        if !(t >= lo && t <= hi) {
            return None;
        }
        // The arithmetic guess is off by at most one near an edge (by rounding a few units in the
        // last place of `f`); away from an edge it is the bin, and near one the edges settle it.
        let f = (t - lo) * self.per_unit;
        // Through `i32` (one instruction; `n` is far below 2³¹ bins): `f` lies in 0..=n here.
        let mut k = f as i32 as usize;
        let frac = f - k as f64;
        if frac > CLEAR_OF_EDGE && frac < 1.0 - CLEAR_OF_EDGE && k < n {
            return Some(k);
        }
        k = k.min(n - 1);
        if t < self.edges[k] {
            k -= 1;
        } else if k + 1 < n && t >= self.edges[k + 1] {
            k += 1;
        }
        Some(k)
    }
}

/// Most bins along one axis.
pub const MAX_BINS: usize = 1 << 30;

/// How far (in bins) a value's arithmetic position must be from an edge for the guess to stand
/// without comparing the edges: far above the rounding of a position (n ≤ 2³² bins, `f64`).
const CLEAR_OF_EDGE: f64 = 1e-6;

/// A coordinate as a column holds it, widened to `f64` exactly.
pub trait Coord: Copy + Send + Sync {
    /// The value as `f64`.
    fn to_f64(self) -> f64;
}

impl Coord for f64 {
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
}

impl Coord for f32 {
    #[inline]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}

/// Whether a value can be placed on an axis at all: finite, and positive on a log axis.
pub fn placeable(v: f64, log: bool) -> bool {
    v.is_finite() && (!log || v > 0.0)
}

/// Rows counted in the bins of an x and a y axis.
#[derive(Clone, Debug, PartialEq)]
pub struct CountGrid {
    /// The horizontal bins.
    pub x: Bins,
    /// The vertical bins.
    pub y: Bins,
    /// Rows per bin, row-major from the lowest y bin up: bin (i, j) is `counts[j * nx + i]`.
    pub counts: Vec<u64>,
    /// Rows whose x or y cannot be placed (missing, not finite, ≤ 0 on a log axis).
    pub missing: u64,
    /// Placeable rows outside the grid's extent (a `domain` narrower than the data).
    pub outside: u64,
    /// What kept those rows out, per axis.
    pub losses: GridLosses,
}

/// Why rows missed a grid, per axis (`[x, y]`): the cells of each column that could not be
/// placed, and the rows placeable on both axes whose value lay outside one axis' bins. A row
/// lacking both values counts for both axes, so the sums can exceed the rows left out.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GridLosses {
    /// Missing or NaN cells.
    pub missing: [u64; 2],
    /// Infinite cells.
    pub infinite: [u64; 2],
    /// Finite values ≤ 0 on a log axis.
    pub non_positive: [u64; 2],
    /// Rows placeable on both axes whose value lies outside the axis' bins.
    pub outside: [u64; 2],
}

/// Why a value cannot be placed on an axis, if it cannot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unplaced {
    /// Missing or NaN.
    Missing,
    /// ±∞.
    Infinite,
    /// Finite and ≤ 0 on a log axis.
    NonPositive,
}

impl Unplaced {
    /// Why `v` cannot be placed on an axis (`log`: whether it is logarithmic); `None` when it can.
    pub fn of(v: f64, log: bool) -> Option<Unplaced> {
        if v.is_nan() {
            Some(Unplaced::Missing)
        } else if v.is_infinite() {
            Some(Unplaced::Infinite)
        } else if log && v <= 0.0 {
            Some(Unplaced::NonPositive)
        } else {
            None
        }
    }
}

impl GridLosses {
    /// Count `count` cells of axis `axis` (0 for x, 1 for y) lacking for `why`.
    pub fn lack(&mut self, axis: usize, why: Unplaced, count: u64) {
        let slot = match why {
            Unplaced::Missing => &mut self.missing,
            Unplaced::Infinite => &mut self.infinite,
            Unplaced::NonPositive => &mut self.non_positive,
        };
        slot[axis] += count;
    }

    fn merge(&mut self, other: &GridLosses) {
        for axis in 0..2 {
            self.missing[axis] += other.missing[axis];
            self.infinite[axis] += other.infinite[axis];
            self.non_positive[axis] += other.non_positive[axis];
            self.outside[axis] += other.outside[axis];
        }
    }
}

impl CountGrid {
    /// An empty grid over `x` and `y`.
    pub fn new(x: Bins, y: Bins) -> CountGrid {
        let cells = x.len() * y.len();
        CountGrid { x, y, counts: vec![0; cells], missing: 0, outside: 0, losses: GridLosses::default() }
    }

    /// Count the rows `(xs[r], ys[r])`.
    pub fn add<X: Coord, Y: Coord>(&mut self, xs: &[X], ys: &[Y]) {
        let nx = self.x.len();
        if !self.x.log && !self.y.log {
            // Linear axes: a value is its own term, and only a non-finite one is missing. The bins
            // of a run of rows are found first, then counted, so the counting's scattered reads
            // and writes overlap instead of waiting on each row's arithmetic.
            const RUN: usize = 1024;
            let mut cells = [0usize; RUN];
            for (xr, yr) in xs.chunks(RUN).zip(ys.chunks(RUN)) {
                let mut found = 0;
                for (&a, &b) in xr.iter().zip(yr) {
                    let (vx, vy) = (a.to_f64(), b.to_f64());
                    match (self.x.index_of_term(vx), self.y.index_of_term(vy)) {
                        (Some(i), Some(j)) => {
                            cells[found] = j * nx + i;
                            found += 1;
                        }
                        _ => self.not_placed(vx, vy),
                    }
                }
                for &cell in &cells[..found] {
                    self.counts[cell] += 1;
                }
            }
            return;
        }
        for (&a, &b) in xs.iter().zip(ys) {
            let (vx, vy) = (a.to_f64(), b.to_f64());
            match (self.x.index(vx), self.y.index(vy)) {
                (Some(i), Some(j)) => self.counts[j * nx + i] += 1,
                _ => self.not_placed(vx, vy),
            }
        }
    }

    /// Count the row `(vx, vy)` that has no bin: missing from the grid (a value that cannot be
    /// placed) or outside it, with why, per axis.
    #[cold]
    pub fn not_placed(&mut self, vx: f64, vy: f64) {
        self.not_placed_times(vx, vy, 1);
    }

    /// [`CountGrid::not_placed`] for `count` rows with the same values.
    pub fn not_placed_times(&mut self, vx: f64, vy: f64, count: u64) {
        let why = [Unplaced::of(vx, self.x.log), Unplaced::of(vy, self.y.log)];
        if why == [None, None] {
            self.outside += count;
            self.losses.outside[0] += count * u64::from(self.x.index(vx).is_none());
            self.losses.outside[1] += count * u64::from(self.y.index(vy).is_none());
            return;
        }
        self.missing += count;
        for (axis, why) in why.into_iter().enumerate() {
            if let Some(why) = why {
                self.losses.lack(axis, why, count);
            }
        }
    }

    /// Count the rows `(xs[r], ys[r])` split over the grids `parts` (each over the same bins),
    /// one scoped thread each. Not on rayon's pool: the caller may be a thread of a query that a
    /// rayon worker waits on (a chart drawn on the pool), and with every worker waiting, work
    /// handed to the pool would never run.
    pub fn add_in_parts<X: Coord, Y: Coord>(parts: &mut [CountGrid], xs: &[X], ys: &[Y]) {
        let len = xs.len().min(ys.len());
        let chunk = len.div_ceil(parts.len().max(1)).max(1);
        std::thread::scope(|scope| {
            let mut parts = parts.iter_mut().enumerate();
            let first = parts.next();
            for (k, grid) in parts {
                let (start, end) = ((k * chunk).min(len), ((k + 1) * chunk).min(len));
                let (xs, ys) = (&xs[start..end], &ys[start..end]);
                scope.spawn(move || grid.add(xs, ys));
            }
            if let Some((_, grid)) = first {
                grid.add(&xs[..chunk.min(len)], &ys[..chunk.min(len)]);
            }
        });
    }

    /// Add another grid's counts (over the same bins) to this one.
    pub fn merge(&mut self, other: &CountGrid) {
        for (a, b) in self.counts.iter_mut().zip(&other.counts) {
            *a += b;
        }
        self.missing += other.missing;
        self.outside += other.outside;
        self.losses.merge(&other.losses);
    }

    /// Rows counted in bins.
    pub fn placed(&self) -> u64 {
        self.counts.iter().sum()
    }

    /// The largest count of any bin.
    pub fn max(&self) -> u64 {
        self.counts.iter().copied().max().unwrap_or(0)
    }
}

/// Count the rows `rows` (all rows when `None`) of the columns `xs` and `ys` into a grid over
/// `x` and `y`, in parallel.
pub fn count_columns(xs: &[f64], ys: &[f64], rows: Option<&[u32]>, x: &Bins, y: &Bins) -> CountGrid {
    let threads = rayon::current_num_threads().max(1);
    let len = rows.map_or(xs.len().min(ys.len()), <[u32]>::len);
    let chunk = len.div_ceil(threads).max(1 << 16);
    let starts: Vec<usize> = (0..len).step_by(chunk).collect();
    let empty = || CountGrid::new(x.clone(), y.clone());
    starts
        .into_par_iter()
        .map(|start| {
            let end = (start + chunk).min(len);
            let mut grid = empty();
            match rows {
                None => grid.add(&xs[start..end], &ys[start..end]),
                Some(rows) => {
                    // Gather in short runs so the counting loop stays the one above.
                    let (mut bx, mut by) = (Vec::with_capacity(4096), Vec::with_capacity(4096));
                    for part in rows[start..end].chunks(4096) {
                        bx.clear();
                        by.clear();
                        bx.extend(part.iter().map(|&r| xs[r as usize]));
                        by.extend(part.iter().map(|&r| ys[r as usize]));
                        grid.add(&bx, &by);
                    }
                }
            }
            grid
        })
        .reduce(empty, |mut a, b| {
            a.merge(&b);
            a
        })
}

/// Rows counted per bin and per category (the codes of a text column).
#[derive(Clone, Debug, PartialEq)]
pub struct CategoryGrid {
    /// Every row counted, whatever its category.
    pub totals: CountGrid,
    /// Categories counted: the column's levels, plus one for rows whose category is missing.
    pub categories: usize,
    /// Rows per bin and category: bin `k`, category `c` is `by_category[k * categories + c]`.
    pub by_category: Vec<u64>,
}

/// Count rows `(xs[r], ys[r])` into a grid over `x` and `y`, per category `codes[r]` (below
/// `levels`; any other code, such as a missing cell's, counts in category `levels`), in
/// parallel.
pub fn count_by_category(xs: &[f64], ys: &[f64], codes: &[u32], levels: usize, x: &Bins, y: &Bins) -> CategoryGrid {
    let categories = levels + 1;
    let len = xs.len().min(ys.len()).min(codes.len());
    let chunk = len.div_ceil(rayon::current_num_threads().max(1)).max(1 << 16);
    let starts: Vec<usize> = (0..len).step_by(chunk).collect();
    let empty = || CategoryGrid {
        totals: CountGrid::new(x.clone(), y.clone()),
        categories,
        by_category: vec![0; x.len() * y.len() * categories],
    };
    starts
        .into_par_iter()
        .map(|start| {
            let end = (start + chunk).min(len);
            let mut grid = empty();
            let nx = x.len();
            for r in start..end {
                let (vx, vy) = (xs[r], ys[r]);
                match (x.index(vx), y.index(vy)) {
                    (Some(i), Some(j)) => {
                        let cell = j * nx + i;
                        grid.totals.counts[cell] += 1;
                        let c = (codes[r] as usize).min(levels);
                        grid.by_category[cell * categories + c] += 1;
                    }
                    _ => grid.totals.not_placed(vx, vy),
                }
            }
            grid
        })
        .reduce(empty, |mut a, b| {
            a.totals.merge(&b.totals);
            for (p, q) in a.by_category.iter_mut().zip(&b.by_category) {
                *p += q;
            }
            a
        })
}

/// The extent of each axis: the smallest and largest placeable value of its column (see
/// [`placeable`]), each column on its own (a row whose other coordinate is missing still widens
/// an axis; the counts report it as missing). `None` for an axis without a placeable value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extent {
    /// Smallest and largest placeable x.
    pub x: Option<(f64, f64)>,
    /// Smallest and largest placeable y.
    pub y: Option<(f64, f64)>,
}

impl Extent {
    /// No values yet.
    pub const EMPTY: Extent = Extent { x: None, y: None };

    /// Both extents together.
    pub fn merge(self, other: Extent) -> Extent {
        let join = |a: Option<(f64, f64)>, b: Option<(f64, f64)>| match (a, b) {
            (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
            (a, b) => a.or(b),
        };
        Extent { x: join(self.x, other.x), y: join(self.y, other.y) }
    }
}

/// The smallest and largest placeable value of `values`, in parallel.
pub fn range_of<X: Coord>(values: &[X], log: bool) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .par_chunks(1 << 16)
        .map(|part| {
            part.iter()
                .map(|v| v.to_f64())
                .filter(|&v| placeable(v, log))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
        })
        .reduce(|| (f64::INFINITY, f64::NEG_INFINITY), |a, b| (a.0.min(b.0), a.1.max(b.1)));
    (lo <= hi).then_some((lo, hi))
}

/// The extent of columns `xs` and `ys`.
pub fn extent_of_columns(xs: &[f64], ys: &[f64], log: [bool; 2]) -> Extent {
    Extent { x: range_of(xs, log[0]), y: range_of(ys, log[1]) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bin by the definition: the last edge not above the value (the top edge belongs to the
    /// last bin), found by searching the edges.
    fn by_search(bins: &Bins, v: f64) -> Option<usize> {
        let t = bins.term(v)?;
        let n = bins.len();
        if t < bins.edges[0] || t > bins.edges[n] {
            return None;
        }
        let k = bins.edges.partition_point(|&e| e <= t);
        Some(k.saturating_sub(1).min(n - 1))
    }

    fn xorshift(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn every_value_has_the_bin_its_edges_say() {
        let mut s = 0x9e37_79b9_7f4a_7c15;
        for (lo, hi, n, log) in [(0.0, 10.0, 10, false), (-3.7, 12.9, 997, false), (0.1, 1e4, 333, true)] {
            let bins = Bins::new(lo, hi, n, log).unwrap();
            let mut values: Vec<f64> = (0..=n).map(|k| bins.edge(k)).collect();
            values.extend((0..=n).map(|k| bins.edges[k]).map(|e| if log { 10f64.powf(e) } else { e }));
            // Values a hair either side of every edge, and random ones over a wider range.
            values.extend((0..=n).flat_map(|k| [bins.edge(k).next_up(), bins.edge(k).next_down()]));
            values.extend((0..20_000).map(|_| lo - 1.0 + (hi - lo + 2.0) * xorshift(&mut s)));
            values.extend([f64::NAN, f64::INFINITY, f64::NEG_INFINITY, lo.next_down(), hi.next_up(), hi, lo]);
            for v in values {
                assert_eq!(bins.index(v), by_search(&bins, v), "value {v:e} on {lo}..{hi} in {n} bins");
            }
        }
    }

    #[test]
    fn the_top_edge_is_in_the_last_bin_and_outside_values_in_none() {
        let bins = Bins::new(0.0, 4.0, 4, false).unwrap();
        assert_eq!([0.0, 0.999, 1.0, 3.999, 4.0].map(|v| bins.index(v)), [Some(0), Some(0), Some(1), Some(3), Some(3)]);
        assert_eq!(bins.index(4.0f64.next_up()), None);
        assert_eq!(bins.index(-0.0), Some(0));
        assert_eq!(bins.index(0.0f64.next_down()), None);
        let log = Bins::new(1.0, 1000.0, 3, true).unwrap();
        assert_eq!(
            [1.0, 9.99, 10.0, 999.0, 1000.0, 0.0, -5.0].map(|v| log.index(v)),
            [Some(0), Some(0), Some(1), Some(2), Some(2), None, None]
        );
        assert!(Bins::new(1.0, 1.0, 4, false).is_none());
        assert!(Bins::new(0.0, 10.0, 4, true).is_none());
    }

    #[test]
    fn each_axis_says_why_its_rows_missed_the_grid() {
        // x on a linear axis over [0, 10], y on a log axis over [1, 100].
        let (x, y) = (Bins::new(0.0, 10.0, 5, false).unwrap(), Bins::new(1.0, 100.0, 2, true).unwrap());
        let rows = [
            (5.0, 10.0),           // placed
            (f64::NAN, 10.0),      // x missing
            (f64::INFINITY, -1.0), // x infinite, y ≤ 0 on the log axis
            (3.0, 0.0),            // y ≤ 0
            (f64::NAN, f64::NAN),  // both missing
            (11.0, 10.0),          // x outside
            (-1.0, 1000.0),        // both outside
            (2.0, 0.5),            // y outside (positive, below the log axis' 1)
            (10.0, 100.0),         // the top corner: placed
        ];
        let (xs, ys): (Vec<f64>, Vec<f64>) = rows.into_iter().unzip();
        let grid = count_columns(&xs, &ys, None, &x, &y);
        assert_eq!((grid.placed(), grid.missing, grid.outside), (2, 4, 3));
        let l = &grid.losses;
        assert_eq!((l.missing, l.infinite, l.non_positive, l.outside), ([2, 1], [1, 0], [0, 2], [2, 2]));
        // Counted by category, the same.
        let by_category = count_by_category(&xs, &ys, &[0; 9], 1, &x, &y);
        assert_eq!(by_category.totals, grid);
    }

    #[test]
    fn counts_equal_a_brute_force_count_and_every_row_is_accounted_for() {
        let mut s = 7u64;
        let n = 300_000;
        let mut xs: Vec<f64> = (0..n).map(|_| -1.0 + 12.0 * xorshift(&mut s)).collect();
        let ys: Vec<f64> = (0..n).map(|_| (xorshift(&mut s) * 5.0).floor()).collect();
        xs[10] = f64::NAN;
        xs[11] = f64::INFINITY;
        let (x, y) = (Bins::new(0.0, 10.0, 40, false).unwrap(), Bins::new(0.0, 4.0, 4, false).unwrap());
        let grid = count_columns(&xs, &ys, None, &x, &y);
        let mut brute = vec![0u64; 40 * 4];
        let (mut missing, mut outside) = (0, 0);
        for (&a, &b) in xs.iter().zip(&ys) {
            if !(a.is_finite() && b.is_finite()) {
                missing += 1;
                continue;
            }
            // Search the edges one by one.
            let i = (0..40).find(|&k| a >= x.edge(k) && (a < x.edge(k + 1) || (k == 39 && a <= x.edge(40))));
            let j = (0..4).find(|&k| b >= y.edge(k) && (b < y.edge(k + 1) || (k == 3 && b <= y.edge(4))));
            match (i, j) {
                (Some(i), Some(j)) => brute[j * 40 + i] += 1,
                _ => outside += 1,
            }
        }
        assert_eq!(grid.counts, brute);
        assert_eq!((grid.missing, grid.outside), (missing, outside));
        assert_eq!(grid.placed() + grid.missing + grid.outside, n as u64);
        // y = 4.0 is the top edge: its rows are in the top row of bins, not outside.
        assert!(ys.contains(&4.0) && grid.counts[3 * 40..].iter().sum::<u64>() > 0);
        // Counting a subset of rows counts exactly those.
        let rows: Vec<u32> = (0..n as u32).filter(|r| r % 3 == 0).collect();
        let some = count_columns(&xs, &ys, Some(&rows), &x, &y);
        let picked: Vec<f64> = rows.iter().map(|&r| xs[r as usize]).collect();
        let picked_y: Vec<f64> = rows.iter().map(|&r| ys[r as usize]).collect();
        let mut serial = CountGrid::new(x.clone(), y.clone());
        serial.add(&picked, &picked_y);
        assert_eq!(some, serial);
    }

    #[test]
    fn categories_split_the_totals_exactly() {
        let mut s = 11u64;
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|_| xorshift(&mut s) * 10.0).collect();
        let ys: Vec<f64> = (0..n).map(|i| if i % 50 == 0 { f64::NAN } else { xorshift(&mut s) * 3.0 }).collect();
        let codes: Vec<u32> = (0..n as u32).map(|i| if i % 7 == 0 { u32::MAX } else { i % 3 }).collect();
        let (x, y) = (Bins::new(0.0, 10.0, 20, false).unwrap(), Bins::new(0.0, 3.0, 6, false).unwrap());
        let split = count_by_category(&xs, &ys, &codes, 3, &x, &y);
        assert_eq!(split.totals, count_columns(&xs, &ys, None, &x, &y));
        for (k, &total) in split.totals.counts.iter().enumerate() {
            assert_eq!(split.by_category[k * 4..k * 4 + 4].iter().sum::<u64>(), total);
        }
        // Category 1's grid is the grid of its rows alone; the missing ones count in the last.
        let ones: Vec<u32> = (0..n as u32).filter(|&r| codes[r as usize] == 1).collect();
        let alone = count_columns(&xs, &ys, Some(&ones), &x, &y);
        assert!(alone.counts.iter().enumerate().all(|(k, &c)| split.by_category[k * 4 + 1] == c));
        assert!(split.by_category.iter().skip(3).step_by(4).sum::<u64>() > 0);
    }

    #[test]
    fn the_extent_skips_what_cannot_be_placed() {
        let xs = [3.0, -2.0, f64::NAN, 8.0, 0.5];
        let ys = [1.0, 5.0, 2.0, f64::NEG_INFINITY, 0.0];
        let e = extent_of_columns(&xs, &ys, [false, false]);
        assert_eq!((e.x, e.y), (Some((-2.0, 8.0)), Some((0.0, 5.0))));
        let log = extent_of_columns(&xs, &ys, [true, true]);
        assert_eq!((log.x, log.y), (Some((0.5, 8.0)), Some((1.0, 5.0))));
        assert_eq!(extent_of_columns(&[], &[], [false, false]), Extent::EMPTY);
        assert_eq!(range_of(&[f32::NAN, -1.0f32], true), None);
    }
}
