//! One column of a source's plan, counted without holding its rows: tallies over 1-D bins
//! (each bin's count, smallest and largest value), and order statistics (the values a quantile
//! is made of) found by narrowing tallies — a few streaming scans, whatever the row count, and
//! memory for the bins only.

use super::plan::{ColumnsFold, Fold, PlanRows};
use super::{Bins, Coord};

/// One tally per column, each filled on its own thread.
struct ColumnTallies(Vec<Tally>);

impl ColumnsFold for ColumnTallies {
    fn fold(&mut self, columns: &[&[f64]]) {
        use rayon::prelude::*;
        self.0.par_iter_mut().zip(columns.par_iter()).for_each(|(tally, values)| {
            for &v in *values {
                tally.add(v);
            }
        });
    }
}

/// One bin of a [`Tally`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BinTally {
    /// Values in the bin.
    pub count: u64,
    /// The smallest of them (+∞ when the bin is empty).
    pub min: f64,
    /// The largest of them (−∞ when the bin is empty).
    pub max: f64,
    /// How many of them equal the smallest.
    pub at_min: u64,
}

impl BinTally {
    const EMPTY: BinTally = BinTally { count: 0, min: f64::INFINITY, max: f64::NEG_INFINITY, at_min: 0 };

    fn add(&mut self, v: f64) {
        self.count += 1;
        if v < self.min {
            self.min = v;
            self.at_min = 1;
        } else if v == self.min {
            self.at_min += 1;
        }
        if v > self.max {
            self.max = v;
        }
    }

    /// Add another bin's values.
    fn merge(&mut self, other: &BinTally) {
        self.at_min = match self.min.total_cmp(&other.min) {
            std::cmp::Ordering::Less => self.at_min,
            std::cmp::Ordering::Equal => self.at_min + other.at_min,
            std::cmp::Ordering::Greater => other.at_min,
        };
        self.count += other.count;
        self.min = self.min.min(other.min);
        self.max = self.max.max(other.max);
    }
}

/// A column's values counted into bins, with the values no bin holds.
#[derive(Clone, Debug, PartialEq)]
pub struct Tally {
    /// The bins.
    pub bins: Bins,
    /// One entry per bin.
    pub per_bin: Vec<BinTally>,
    /// Values missing or NaN.
    pub missing: u64,
    /// Values ±∞.
    pub infinite: u64,
    /// Finite values outside the bins (or outside the range kept).
    pub outside: u64,
    /// Only values in this closed range are placed, when given.
    kept: Option<(f64, f64)>,
}

impl Tally {
    /// Nothing counted yet.
    pub fn new(bins: Bins) -> Tally {
        let per_bin = vec![BinTally::EMPTY; bins.len()];
        Tally { bins, per_bin, missing: 0, infinite: 0, outside: 0, kept: None }
    }

    /// The first tally of values in `[lo, hi]`: [`OPENING_BINS`] bins over the range (one bin
    /// around a single value), values outside it counted apart; `None` for no finite range.
    pub fn opening(lo: f64, hi: f64) -> Option<Tally> {
        let whole = Bins::new(lo, hi, OPENING_BINS, false).or_else(|| Bins::new(lo, lo.next_up(), 1, false))?;
        Some(Tally::new(whole).keeping(lo, hi))
    }

    /// The same tally placing only values from `lo` to `hi` (a histogram's domain, narrower
    /// than its rounded edges); the others count as outside.
    pub fn keeping(mut self, lo: f64, hi: f64) -> Tally {
        self.kept = Some((lo, hi));
        self
    }

    /// Count value `v`.
    pub fn add(&mut self, v: f64) {
        if v.is_nan() {
            self.missing += 1;
        } else if v.is_infinite() {
            self.infinite += 1;
        } else if self.kept.is_some_and(|(lo, hi)| !(lo..=hi).contains(&v)) {
            self.outside += 1;
        } else {
            match self.bins.index(v) {
                Some(k) => self.per_bin[k].add(v),
                None => self.outside += 1,
            }
        }
    }

    /// Add another tally over the same bins.
    fn merge(&mut self, other: &Tally) {
        for (a, b) in self.per_bin.iter_mut().zip(&other.per_bin) {
            a.merge(b);
        }
        self.missing += other.missing;
        self.infinite += other.infinite;
        self.outside += other.outside;
    }

    /// The count of each bin.
    pub fn counts(&self) -> Vec<u64> {
        self.per_bin.iter().map(|b| b.count).collect()
    }

    /// Values the bins hold.
    pub fn placed(&self) -> u64 {
        self.per_bin.iter().map(|b| b.count).sum()
    }

    /// Whether the placed values of 0-based ranks `a` < `b` surely differ: they lie in
    /// different bins. `false` when the bins cannot tell.
    pub fn ranks_differ(&self, a: u64, b: u64) -> bool {
        let bin_of = |rank: u64| {
            let mut seen = 0u64;
            self.per_bin.iter().position(|bin| {
                seen += bin.count;
                seen > rank
            })
        };
        a < b && matches!((bin_of(a), bin_of(b)), (Some(x), Some(y)) if x != y)
    }
}

/// Tallies of one column over several sets of bins, filled by one scan: one set per thread,
/// each batch split between them (on scoped threads, as [`super::CountGrid::add_in_parts`]
/// explains), merged at the end.
struct TallyFold {
    parts: Vec<Vec<Tally>>,
}

impl TallyFold {
    fn new(tallies: Vec<Tally>) -> TallyFold {
        let threads = rayon::current_num_threads().max(1);
        TallyFold { parts: vec![tallies; threads] }
    }

    fn merged(self) -> Vec<Tally> {
        let mut parts = self.parts.into_iter();
        let mut total = parts.next().unwrap_or_default();
        for part in parts {
            for (a, b) in total.iter_mut().zip(&part) {
                a.merge(b);
            }
        }
        total
    }
}

/// Count `xs` into each of `tallies`.
fn add_all<X: Coord>(tallies: &mut [Tally], xs: &[X]) {
    for tally in tallies {
        for &x in xs {
            tally.add(x.to_f64());
        }
    }
}

impl Fold for TallyFold {
    fn fold<X: Coord, Y: Coord>(&mut self, xs: &[X], _: &[Y]) {
        let chunk = xs.len().div_ceil(self.parts.len().max(1)).max(1);
        std::thread::scope(|scope| {
            let mut parts = self.parts.iter_mut().zip(xs.chunks(chunk));
            let first = parts.next();
            for (tallies, xs) in parts {
                scope.spawn(move || add_all(tallies, xs));
            }
            if let Some((tallies, xs)) = first {
                add_all(tallies, xs);
            }
        });
    }
}

/// Bins of a first tally for [`PlanRows::order_statistics`] to start from (more bins would
/// save a narrowing scan at 10⁹ values, but fall out of the processor's cache: measured
/// slower with 2¹⁸).
pub const OPENING_BINS: usize = 1 << 16;

/// Bins of each narrowing scan of [`PlanRows::order_statistics`].
pub const NARROWING_BINS: usize = 1 << 16;

/// Most narrowing scans before the search gives up (values from data need two or three).
const MAX_NARROWING_SCANS: usize = 40;

/// Where the search for one order statistic stands: its rank among the values still in
/// `[lo, hi]`, or the value found.
#[derive(Clone, Copy, Debug)]
struct Search {
    rank: u64,
    lo: f64,
    hi: f64,
    /// How many values lie in `[lo, hi]`.
    left: u64,
    found: Option<f64>,
}

impl Search {
    /// Narrow the search to the bin of `tally` (over `[lo, hi]`) that holds the rank; an error
    /// when no bin does (the rows changed between scans).
    fn narrow(&mut self, tally: &Tally) -> Result<(), String> {
        let mut below = 0;
        for bin in &tally.per_bin {
            if self.rank < below + bin.count {
                let within = self.rank - below;
                if within < bin.at_min {
                    self.found = Some(bin.min);
                } else {
                    // The bin's values above its smallest: the next scan looks only at them.
                    self.rank = within - bin.at_min;
                    self.left = bin.count - bin.at_min;
                    (self.lo, self.hi) = (bin.min.next_up(), bin.max);
                }
                return Ok(());
            }
            below += bin.count;
        }
        Err(format!("the rows changed while they were read: {below} values where more were counted before"))
    }

    /// The bins of the next scan: about four per value left (so most hold one value), and not
    /// so many that they leave the processor's cache.
    fn bins(&self) -> Option<Bins> {
        let n = (self.left.saturating_mul(4) as usize).clamp(16, NARROWING_BINS);
        Bins::new(self.lo, self.hi, n, false)
    }
}

impl PlanRows {
    /// The empty `tallies` filled with column `field` (numbers or times, as
    /// [`PlanRows::count`] places them), all in one scan.
    pub fn tally(&self, field: &str, tallies: Vec<Tally>) -> Result<Vec<Tally>, String> {
        let label = format!("tally of `{field}` over {} bins", tallies.iter().map(|t| t.per_bin.len()).sum::<usize>());
        let fold = crate::timing::timed(&label, || self.scan(field, field, TallyFold::new(tallies)))?;
        Ok(fold.merged())
    }

    /// The first tally of `field` for its order statistics: [`OPENING_BINS`] bins over its range
    /// `[lo, hi]` (one bin around a single value), values outside the range counted apart.
    pub fn opening_tally(&self, field: &str, (lo, hi): (f64, f64)) -> Result<Tally, String> {
        let opening = Tally::opening(lo, hi).ok_or_else(|| format!("`{field}` has no finite range to bin"))?;
        Ok(self.tally(field, vec![opening])?.remove(0))
    }

    /// [`PlanRows::opening_tally`] of several columns over their ranges, in one scan (each
    /// column tallied on its own thread).
    pub fn opening_tallies(&self, fields: &[&str], ranges: &[(f64, f64)]) -> Result<Vec<Tally>, String> {
        let mut tallies = Vec::with_capacity(fields.len());
        for (field, &(lo, hi)) in fields.iter().zip(ranges) {
            tallies.push(Tally::opening(lo, hi).ok_or_else(|| format!("`{field}` has no finite range to bin"))?);
        }
        let label = format!("tallies of {} columns over {OPENING_BINS} bins", fields.len());
        Ok(crate::timing::timed(&label, || self.scan_columns(fields, ColumnTallies(tallies)))?.0)
    }

    /// The values at fractional 0-based ranks among those `first` placed: `(i, frac)` is the
    /// value of rank `i` plus `frac` of the way to the next one (how quantiles interpolate).
    pub fn at_ranks(&self, field: &str, first: &Tally, positions: &[(usize, f64)]) -> Result<Vec<f64>, String> {
        let n = first.placed() as usize;
        if n == 0 {
            return Err(format!("`{field}` has no values to rank"));
        }
        let next = |i: usize| (i + 1).min(n - 1) as u64;
        let ranks: Vec<u64> = positions.iter().flat_map(|&(i, _)| [i as u64, next(i)]).collect();
        let v = self.order_statistics(field, first, &ranks)?;
        Ok(positions
            .iter()
            .zip(v.chunks(2))
            .map(|(&(_, frac), pair)| if frac > 0.0 { pair[0] + frac * (pair[1] - pair[0]) } else { pair[0] })
            .collect())
    }

    /// The values at 0-based `ranks` among the finite values of `field` that `first` (a tally of
    /// them over bins) placed, in ascending order: each rank is searched in the bin that holds
    /// it, by tallies over that bin's range until the rank falls on the smallest value of a bin.
    pub fn order_statistics(&self, field: &str, first: &Tally, ranks: &[u64]) -> Result<Vec<f64>, String> {
        let placed = first.placed();
        if let Some(&rank) = ranks.iter().find(|&&r| r >= placed) {
            return Err(format!("rank {rank} of `{field}` asked among {placed} values"));
        }
        let mut searches: Vec<Search> =
            ranks.iter().map(|&rank| Search { rank, lo: f64::NAN, hi: f64::NAN, left: 0, found: None }).collect();
        for search in &mut searches {
            search.narrow(first)?;
        }
        for _ in 0..MAX_NARROWING_SCANS {
            for s in searches.iter_mut().filter(|s| s.found.is_none() && s.lo >= s.hi) {
                // Nothing but `lo` is left in the range.
                s.found = Some(s.lo);
            }
            let open: Vec<usize> = (0..searches.len()).filter(|&i| searches[i].found.is_none()).collect();
            if open.is_empty() {
                return Ok(searches.iter().filter_map(|s| s.found).collect());
            }
            // Searches in the same range (a quantile's two neighbouring ranks, mostly) share bins.
            let mut windows: Vec<Bins> = Vec::new();
            let mut window_of = Vec::new();
            for &i in &open {
                let bins =
                    searches[i].bins().ok_or_else(|| format!("the values of `{field}` could not be narrowed"))?;
                let at = windows.iter().position(|w| *w == bins).unwrap_or_else(|| {
                    windows.push(bins);
                    windows.len() - 1
                });
                window_of.push(at);
            }
            let tallies = self.tally(field, windows.into_iter().map(Tally::new).collect())?;
            for (&i, &w) in open.iter().zip(&window_of) {
                searches[i].narrow(&tallies[w]).map_err(|e| format!("`{field}`: {e}"))?;
            }
        }
        Err(format!("the quantiles of `{field}` were not found in {MAX_NARROWING_SCANS} scans"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use polars::prelude::*;

    fn plan_of(values: Vec<Option<f64>>) -> PlanRows {
        PlanRows::new(df!("v" => values).unwrap().lazy(), "values").unwrap()
    }

    /// The order statistics of the finite values, sorted, against the narrowing search.
    fn check(values: Vec<Option<f64>>, lo: f64, hi: f64) {
        let mut sorted: Vec<f64> = values.iter().flatten().copied().filter(|v| v.is_finite()).collect();
        sorted.sort_by(f64::total_cmp);
        let plan = plan_of(values);
        let first = plan.tally("v", vec![Tally::new(Bins::new(lo, hi, 1000, false).unwrap())]).unwrap().remove(0);
        assert_eq!(first.placed() as usize, sorted.len());
        let n = sorted.len() as u64;
        let ranks: Vec<u64> = [0, 1, n / 4, n / 4 + 1, n / 2, 3 * n / 4, n - 2, n - 1].to_vec();
        let found = plan.order_statistics("v", &first, &ranks).unwrap();
        let expected: Vec<f64> = ranks.iter().map(|&r| sorted[r as usize]).collect();
        assert_eq!(found, expected);
    }

    #[test]
    fn order_statistics_equal_the_sorted_values() {
        // Continuous values, many ties, a far outlier (one coarse bin holds nearly all), nulls
        // and non-finite cells.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let smooth: Vec<Option<f64>> = (0..50_000).map(|_| Some(next() * 10.0 - 3.0)).collect();
        check(smooth, -3.0, 7.0);
        let ties: Vec<Option<f64>> = (0..30_000).map(|i| Some((i % 7) as f64 * 0.1)).collect();
        check(ties, 0.0, 0.6000000000000001);
        let mut outlier: Vec<Option<f64>> = (0..20_000).map(|_| Some(next() * 1e-9)).collect();
        outlier.extend([Some(1e12), None, Some(f64::NAN), Some(f64::INFINITY)]);
        check(outlier, 0.0, 1e12);
        // Neighbouring floats: a range no bins can split.
        let a = 1.0f64;
        let near: Vec<Option<f64>> = (0..1000).map(|i| Some(if i % 3 == 0 { a } else { a.next_up() })).collect();
        check(near, a, a.next_up());
    }

    #[test]
    fn ranks_differ_when_their_bins_do_and_fractional_ranks_interpolate() {
        let spread: Vec<Option<f64>> = (0..10_000).map(|i| Some(i as f64)).collect();
        let ties: Vec<Option<f64>> = (0..10_000).map(|i| Some(if i % 10 < 6 { 5000.0 } else { i as f64 })).collect();
        for (values, differ) in [(spread, true), (ties, false)] {
            let plan = plan_of(values);
            let first = plan.opening_tally("v", (0.0, 9999.0)).unwrap();
            assert_eq!(first.ranks_differ(2500, 7499), differ);
            let v = plan.at_ranks("v", &first, &[(2500, 0.0), (7499, 0.0)]).unwrap();
            assert_eq!(v[0] < v[1], differ, "{v:?}");
        }
        let plan =
            PlanRows::new(df!("a" => [1.0, 2.0, 3.0, 4.0], "b" => [5.0, 5.0, 5.0, 6.0]).unwrap().lazy(), "t").unwrap();
        let both = plan.opening_tallies(&["a", "b"], &[(1.0, 4.0), (5.0, 6.0)]).unwrap();
        assert_eq!(both.iter().map(Tally::placed).collect::<Vec<_>>(), [4, 4]);
        // numpy.percentile([1, 2, 3, 4], [25, 75]) == [1.75, 3.25]: ranks 0.75 and 2.25.
        assert_eq!(plan.at_ranks("a", &both[0], &[(0, 0.75), (2, 0.25)]).unwrap(), [1.75, 3.25]);
        assert!(!both[1].ranks_differ(0, 2) && both[1].ranks_differ(2, 3));
    }

    #[test]
    fn tallies_count_each_bin_with_its_extremes_and_the_rest_apart() {
        let plan = plan_of(vec![Some(0.5), Some(0.5), Some(1.5), Some(2.0), Some(9.0), None, Some(f64::NEG_INFINITY)]);
        let bins = Bins::new(0.0, 2.0, 2, false).unwrap();
        let t = plan.tally("v", vec![Tally::new(bins.clone())]).unwrap().remove(0);
        assert_eq!(t.counts(), [2, 2], "2.0 is the top edge, in the last bin");
        assert_eq!((t.per_bin[0].min, t.per_bin[0].max, t.per_bin[0].at_min), (0.5, 0.5, 2));
        assert_eq!((t.per_bin[1].min, t.per_bin[1].max, t.per_bin[1].at_min), (1.5, 2.0, 1));
        assert_eq!((t.missing, t.infinite, t.outside), (1, 1, 1));
        let kept = plan.tally("v", vec![Tally::new(bins).keeping(0.0, 1.5)]).unwrap().remove(0);
        assert_eq!((kept.counts(), kept.outside), (vec![2, 1], 2), "2.0 lies in the bins but outside the range kept");
    }
}
