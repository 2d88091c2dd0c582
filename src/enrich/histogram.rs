//! Histogram bins: the number of bins by a rule (Freedman–Diaconis, Sturges, or numpy's "auto",
//! the larger of the two), equal-width edges, and each value's bin found as numpy's
//! `histogram` finds it, so counts over the same edges are the same.

/// How many bins of equal width cover `[lo, hi]` for `n` values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BinRule {
    /// Bin width 2·IQR·n^(−1/3) (Freedman–Diaconis); Sturges' count when the IQR is zero.
    FreedmanDiaconis,
    /// log2(n) + 1 bins, rounded up (Sturges).
    Sturges,
    /// The larger count of the two rules (numpy's `bins="auto"`).
    Auto,
    /// This many bins.
    Count(usize),
}

/// The number of bins `rule` gives for the `finite` values over `[lo, hi]`, at least 1 and at
/// most `max_bins`. The values are reordered (the quartiles are found by selection).
pub fn bin_count(rule: BinRule, finite: &mut [f64], lo: f64, hi: f64, max_bins: usize) -> usize {
    let n = finite.len();
    bin_count_of(rule, n, || super::distribution::quartiles_in_place(finite), lo, hi, max_bins)
}

/// [`bin_count`] for `n` finite values whose quartiles `quartiles` gives (asked only by the
/// rules that need them), for values that are not held in memory.
pub fn bin_count_of(
    rule: BinRule,
    n: usize,
    quartiles: impl FnOnce() -> Option<(f64, f64)>,
    lo: f64,
    hi: f64,
    max_bins: usize,
) -> usize {
    let sturges = || if n == 0 { 1 } else { ((n as f64).log2() + 1.0).ceil() as usize };
    let fd = || {
        let (q1, q3) = quartiles()?;
        let width = 2.0 * (q3 - q1) / (n as f64).cbrt();
        (width > 0.0 && hi > lo).then(|| ((hi - lo) / width).ceil()).filter(|c| c.is_finite()).map(|c| c as usize)
    };
    let count = match rule {
        BinRule::Count(c) => c,
        BinRule::Sturges => sturges(),
        BinRule::FreedmanDiaconis => fd().unwrap_or_else(sturges),
        BinRule::Auto => fd().map_or_else(sturges, |f| f.max(sturges())),
    };
    count.clamp(1, max_bins.max(1))
}

/// `bins + 1` equally spaced edges from `lo` to `hi`, both exact (as numpy's `linspace`). An
/// empty range is widened to `lo − 0.5 .. lo + 0.5`, as numpy does.
pub fn equal_edges(lo: f64, hi: f64, bins: usize) -> Vec<f64> {
    let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 0.5, lo + 0.5) };
    let bins = bins.max(1);
    let step = (hi - lo) / bins as f64;
    let mut edges: Vec<f64> = (0..bins).map(|k| lo + step * k as f64).collect();
    edges.push(hi);
    edges
}

/// Edges `start, start + step, …` up to `stop` (nice bins, whose ends are multiples of the step).
pub fn stepped_edges(start: f64, stop: f64, step: f64) -> Vec<f64> {
    let bins = (((stop - start) / step).round() as usize).max(1);
    let mut edges: Vec<f64> = (0..bins).map(|k| start + step * k as f64).collect();
    edges.push(stop);
    edges
}

/// The bin of `v` among increasing, equally spaced `edges`: bins are half-open `[e_k, e_k+1)`
/// except the last, which includes its right edge. `None` outside the edges or for NaN.
pub fn bin_of(edges: &[f64], v: f64) -> Option<usize> {
    let bins = edges.len().checked_sub(1).filter(|&b| b > 0)?;
    let (lo, hi) = (edges[0], edges[bins]);
    if !(v >= lo && v <= hi) {
        return None;
    }
    // The arithmetic guess can be one off at an edge; the edges themselves decide.
    let mut k = (((v - lo) / (hi - lo)) * bins as f64) as usize;
    k = k.min(bins - 1);
    if v < edges[k] {
        k = k.saturating_sub(1);
    } else if k + 1 < bins && v >= edges[k + 1] {
        k += 1;
    }
    Some(k)
}

/// The bin of each of `rows` (`values` indexed by row), [`OUTSIDE`] for a value outside the
/// edges; computed in parallel for large inputs.
pub fn bins_of_rows(edges: &[f64], values: &[f64], rows: &[u32]) -> Vec<u32> {
    use rayon::prelude::*;
    let bin = |&r: &u32| values.get(r as usize).and_then(|&v| bin_of(edges, v)).map_or(OUTSIDE, |k| k as u32);
    if rows.len() < 100_000 {
        rows.iter().map(bin).collect()
    } else {
        rows.par_iter().with_min_len(16_384).map(bin).collect()
    }
}

/// The bin of a value outside the edges, in [`bins_of_rows`].
pub const OUTSIDE: u32 = u32::MAX;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enrich::distribution::{QuantileMethod, quantile_sorted, quartiles, sorted_finite};

    /// The 150 sepal lengths of the iris data set (examples/data/iris.csv), in file order.
    const SEPAL_LENGTH: [f64; 150] = [
        5.1, 4.9, 4.7, 4.6, 5.0, 5.4, 4.6, 5.0, 4.4, 4.9, 5.4, 4.8, 4.8, 4.3, 5.8, 5.7, 5.4, 5.1, 5.7, 5.1, 5.4, 5.1,
        4.6, 5.1, 4.8, 5.0, 5.0, 5.2, 5.2, 4.7, 4.8, 5.4, 5.2, 5.5, 4.9, 5.0, 5.5, 4.9, 4.4, 5.1, 5.0, 4.5, 4.4, 5.0,
        5.1, 4.8, 5.1, 4.6, 5.3, 5.0, 7.0, 6.4, 6.9, 5.5, 6.5, 5.7, 6.3, 4.9, 6.6, 5.2, 5.0, 5.9, 6.0, 6.1, 5.6, 6.7,
        5.6, 5.8, 6.2, 5.6, 5.9, 6.1, 6.3, 6.1, 6.4, 6.6, 6.8, 6.7, 6.0, 5.7, 5.5, 5.5, 5.8, 6.0, 5.4, 6.0, 6.7, 6.3,
        5.6, 5.5, 5.5, 6.1, 5.8, 5.0, 5.6, 5.7, 5.7, 6.2, 5.1, 5.7, 6.3, 5.8, 7.1, 6.3, 6.5, 7.6, 4.9, 7.3, 6.7, 7.2,
        6.5, 6.4, 6.8, 5.7, 5.8, 6.4, 6.5, 7.7, 7.7, 6.0, 6.9, 5.6, 7.7, 6.3, 6.7, 7.2, 6.2, 6.1, 6.4, 7.2, 7.4, 7.9,
        6.4, 6.3, 6.1, 7.7, 6.3, 6.4, 6.0, 6.9, 6.7, 6.9, 5.8, 6.8, 6.7, 6.7, 6.3, 6.5, 6.2, 5.9,
    ];

    fn counts(edges: &[f64], values: &[f64]) -> Vec<usize> {
        let mut c = vec![0; edges.len() - 1];
        for &v in values {
            if let Some(k) = bin_of(edges, v) {
                c[k] += 1;
            }
        }
        c
    }

    #[test]
    fn rules_and_counts_match_numpy_on_iris() {
        // Known answers from numpy 2.4 (scripts/histogram_reference.py):
        //   np.histogram(sepal_length, bins=b) for b in "fd", "sturges", "auto", 10.
        let (lo, hi) = (4.3, 7.9);
        let fd = bin_count(BinRule::FreedmanDiaconis, &mut SEPAL_LENGTH.clone(), lo, hi, 1000);
        let sturges = bin_count(BinRule::Sturges, &mut SEPAL_LENGTH.clone(), lo, hi, 1000);
        assert_eq!(fd, 8);
        assert_eq!(sturges, 9);
        assert_eq!(bin_count(BinRule::Auto, &mut SEPAL_LENGTH.clone(), lo, hi, 1000), 9);
        assert_eq!(counts(&equal_edges(lo, hi, fd), &SEPAL_LENGTH), [11, 30, 24, 24, 31, 17, 7, 6]);
        assert_eq!(counts(&equal_edges(lo, hi, sturges), &SEPAL_LENGTH), [9, 23, 20, 28, 28, 14, 17, 5, 6]);
        assert_eq!(counts(&equal_edges(lo, hi, 10), &SEPAL_LENGTH), [9, 23, 14, 27, 16, 26, 18, 6, 5, 6]);
    }

    #[test]
    fn values_on_edges_fall_in_the_bin_they_open_and_the_maximum_in_the_last() {
        // Edges of 0.1 steps are 3 * 0.1 = 0.30000000000000004 and so on (as numpy's linspace);
        // the arithmetic guess for such an edge can land one bin low, the comparison fixes it.
        let edges = equal_edges(0.0, 1.0, 10);
        for k in 0..10 {
            assert_eq!(bin_of(&edges, edges[k]), Some(k), "edge {k} = {}", edges[k]);
        }
        assert_eq!(bin_of(&edges, 1.0), Some(9));
        assert_eq!(bin_of(&edges, -1e-12), None);
        assert_eq!(bin_of(&edges, 1.0 + 1e-12), None);
        assert_eq!(bin_of(&edges, f64::NAN), None);
    }

    #[test]
    fn an_empty_range_is_widened_by_half_on_each_side() {
        assert_eq!(equal_edges(3.0, 3.0, 2), vec![2.5, 3.0, 3.5]);
        assert_eq!(counts(&equal_edges(3.0, 3.0, 2), &[3.0, 3.0]), [0, 2]);
    }

    #[test]
    fn counts_are_clamped_and_degenerate_spreads_fall_back_to_sturges() {
        // Most values equal: IQR 0, so Freedman–Diaconis has no width; Sturges for n = 8 is 4.
        let v = [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 9.0];
        let mut v = v;
        assert_eq!(bin_count(BinRule::FreedmanDiaconis, &mut v, 1.0, 9.0, 100), 4);
        assert_eq!(bin_count(BinRule::Count(500), &mut v, 1.0, 9.0, 100), 100);
        assert_eq!(bin_count(BinRule::Count(0), &mut v, 1.0, 9.0, 100), 1);
        assert_eq!(bin_count(BinRule::Sturges, &mut [], 0.0, 1.0, 100), 1);
    }

    #[test]
    fn selected_quartiles_equal_sorted_ones() {
        let mut state = 7u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in [1, 2, 3, 4, 5, 10, 101, 1000] {
            let v: Vec<f64> = (0..n).map(|_| (next() * 20.0).round() / 4.0).collect();
            let sorted = sorted_finite(&v);
            let at = |p| quantile_sorted(&sorted, p, QuantileMethod::Linear);
            assert_eq!(quartiles(&v), Some((at(0.25).unwrap(), at(0.75).unwrap())), "n = {n}");
        }
        assert_eq!(quartiles(&SEPAL_LENGTH), Some((5.1, 6.4)));
        assert_eq!(quartiles(&[f64::NAN]), None);
    }

    #[test]
    fn stepped_edges_end_on_the_stop() {
        let e = stepped_edges(4.0, 8.0, 0.5);
        assert_eq!(e.len(), 9);
        assert_eq!(e[8], 8.0);
        assert!((e[3] - 5.5).abs() < 1e-12);
    }
}
