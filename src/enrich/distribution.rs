//! One-dimensional distributions: sample quantiles (Hyndman & Fan's continuous types), Tukey's
//! box-plot statistics with McGill's notches, histogram bins (Freedman–Diaconis), binned counts,
//! and Gaussian kernel density estimates (Silverman's bandwidth) computed on a fine binned grid.

/// How a sample quantile is interpolated between the order statistics: the continuous types of
/// Hyndman & Fan (1996), under the names numpy's `percentile(..., method=...)` gives them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum QuantileMethod {
    /// Type 7 (numpy's default `"linear"`, R's default): position p·(n − 1) in the sorted
    /// values, counted from 0.
    #[default]
    Linear,
    /// Type 5 (`"hazen"`): position p·n − 1/2.
    Hazen,
    /// Type 6 (`"weibull"`, Minitab and SPSS): position p·(n + 1) − 1.
    Weibull,
    /// Type 8 (`"median_unbiased"`, recommended by Hyndman & Fan): position p·(n + 1/3) − 2/3.
    MedianUnbiased,
}

impl QuantileMethod {
    /// The 0-based position of quantile `p` among `n` sorted values (before clamping).
    fn position(self, p: f64, n: usize) -> f64 {
        let n = n as f64;
        match self {
            QuantileMethod::Linear => p * (n - 1.0),
            QuantileMethod::Hazen => p * n - 0.5,
            QuantileMethod::Weibull => p * (n + 1.0) - 1.0,
            QuantileMethod::MedianUnbiased => p * (n + 1.0 / 3.0) - 2.0 / 3.0,
        }
    }
}

/// Quantile `p` (in 0..=1) of values sorted ascending, all finite, interpolated linearly between
/// the two order statistics around `method`'s position; positions outside the sample take its
/// smallest or largest value. `None` for no values.
pub fn quantile_sorted(sorted: &[f64], p: f64, method: QuantileMethod) -> Option<f64> {
    let last = sorted.len().checked_sub(1)?;
    let pos = method.position(p.clamp(0.0, 1.0), sorted.len()).clamp(0.0, last as f64);
    let i = (pos.floor() as usize).min(last);
    let frac = pos - i as f64;
    let lo = sorted[i];
    Some(match sorted.get(i + 1) {
        Some(&hi) if frac > 0.0 => lo + frac * (hi - lo),
        _ => lo,
    })
}

/// The finite values of `values`, sorted ascending.
pub fn sorted_finite(values: &[f64]) -> Vec<f64> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    v
}

/// Quartiles (25th and 75th percentile, linear interpolation: type 7) of finite values.
pub fn quartiles(values: &[f64]) -> Option<(f64, f64)> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    quartiles_in_place(&mut v)
}

/// [`quartiles`] of values that are all finite, found by selection in O(n) rather than by
/// sorting; reorders them.
pub fn quartiles_in_place(v: &mut [f64]) -> Option<(f64, f64)> {
    if v.is_empty() {
        return None;
    }
    let q1 = percentile_in_place(v, 0.25);
    let q3 = percentile_in_place(v, 0.75);
    Some((q1, q3))
}

/// Where the `q` quantile (type 7) of `n` sorted values lies: between the values at 0-based
/// ranks `i` and `i + 1`, a fraction `frac` of the way (`frac` is 0 at a value).
pub fn type7_position(q: f64, n: usize) -> (usize, f64) {
    let pos = q * n.saturating_sub(1) as f64;
    let i = pos.floor() as usize;
    (i, pos - i as f64)
}

/// The `q` quantile (0 ≤ q ≤ 1, type 7) of finite, non-empty `v`, reordering it.
fn percentile_in_place(v: &mut [f64], q: f64) -> f64 {
    let (i, frac) = type7_position(q, v.len());
    let (_, &mut at, above) = v.select_nth_unstable_by(i, f64::total_cmp);
    match above.iter().copied().min_by(f64::total_cmp) {
        Some(next) if frac > 0.0 => at + frac * (next - at),
        _ => at,
    }
}

/// Tukey's fences: the values `k` interquartile ranges below the first and above the third
/// quartile (`k = 1.5` for the classic box plot's inner fences).
pub fn tukey_fences(q1: f64, q3: f64, k: f64) -> (f64, f64) {
    let iqr = q3 - q1;
    (q1 - k * iqr, q3 + k * iqr)
}

/// McGill, Tukey & Larsen's (1978) notch around a median: median ± 1.57·IQR/√n, roughly a 95%
/// interval for comparing two medians (non-overlapping notches suggest different medians).
pub fn median_notch(median: f64, iqr: f64, n: usize) -> (f64, f64) {
    let half = 1.57 * iqr / (n.max(1) as f64).sqrt();
    (median - half, median + half)
}

/// The statistics a box plot draws of one sample.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxStats {
    /// Number of finite values.
    pub n: usize,
    /// Smallest value.
    pub min: f64,
    /// First quartile.
    pub q1: f64,
    /// Median.
    pub median: f64,
    /// Third quartile.
    pub q3: f64,
    /// Largest value.
    pub max: f64,
    /// Arithmetic mean.
    pub mean: f64,
    /// End of the lower whisker: the smallest value at or above the lower fence (the first
    /// quartile when there is none between the fence and the box).
    pub whisker_low: f64,
    /// End of the upper whisker: the largest value at or below the upper fence (the third
    /// quartile when there is none between the box and the fence).
    pub whisker_high: f64,
    /// Positions in the input of the values beyond the whiskers, in input order.
    pub outliers: Vec<usize>,
    /// The median's notch (see [`median_notch`]).
    pub notch: (f64, f64),
}

impl BoxStats {
    /// The interquartile range.
    pub fn iqr(&self) -> f64 {
        self.q3 - self.q1
    }
}

/// Box-plot statistics of `values` (non-finite ones ignored): quartiles by `method`, whiskers to
/// the most extreme values within `whisker` interquartile ranges of the box (Tukey), values
/// beyond them as outliers. `None` without finite values.
pub fn box_stats(values: &[f64], method: QuantileMethod, whisker: f64) -> Option<BoxStats> {
    let sorted = sorted_finite(values);
    let (&min, &max) = (sorted.first()?, sorted.last()?);
    let at = |p: f64| quantile_sorted(&sorted, p, method);
    let (q1, median, q3) = (at(0.25)?, at(0.5)?, at(0.75)?);
    let (low_fence, high_fence) = tukey_fences(q1, q3, whisker);
    // As matplotlib and R do: a whisker never reaches into the box.
    let whisker_low = sorted.iter().copied().find(|&v| v >= low_fence).map_or(q1, |v| v.min(q1));
    let whisker_high = sorted.iter().rev().copied().find(|&v| v <= high_fence).map_or(q3, |v| v.max(q3));
    let outliers = values
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_finite() && (**v < whisker_low || **v > whisker_high))
        .map(|(i, _)| i)
        .collect();
    let n = sorted.len();
    let mean = sorted.iter().sum::<f64>() / n as f64;
    let notch = median_notch(median, q3 - q1, n);
    Some(BoxStats { n, min, q1, median, q3, max, mean, whisker_low, whisker_high, outliers, notch })
}

/// Number of histogram bins over `[lo, hi]` by the Freedman–Diaconis rule (bin width
/// 2·IQR·n^(−1/3)), clamped to `[min_bins, max_bins]`; Sturges' rule when the IQR is zero.
pub fn freedman_diaconis_bins(values: &[f64], lo: f64, hi: f64, min_bins: usize, max_bins: usize) -> usize {
    let n = values.iter().filter(|v| v.is_finite()).count();
    freedman_diaconis_bins_of(n, || quartiles(values), (lo, hi), (min_bins, max_bins))
}

/// [`freedman_diaconis_bins`] of `n` finite values whose quartiles `quartiles` gives (asked only
/// when the rule needs them).
pub fn freedman_diaconis_bins_of(
    n: usize,
    quartiles: impl FnOnce() -> Option<(f64, f64)>,
    (lo, hi): (f64, f64),
    (min_bins, max_bins): (usize, usize),
) -> usize {
    if n == 0 || hi <= lo {
        return min_bins;
    }
    let sturges = ((n as f64).log2().ceil() as usize + 1).clamp(min_bins, max_bins);
    let Some((q1, q3)) = quartiles() else { return sturges };
    let width = 2.0 * (q3 - q1) / (n as f64).cbrt();
    if width <= 0.0 || !width.is_finite() {
        return sturges;
    }
    (((hi - lo) / width).ceil() as usize).clamp(min_bins, max_bins)
}

/// Whether [`freedman_diaconis_bins_of`] gives `max_bins` for `n` values spread over `range`
/// (their largest minus smallest) in bins over `[lo, hi]` whatever their quartiles, as long as
/// these differ: the width 2·IQR/∛n is then at most 2·range/∛n, so there are at least
/// (hi − lo)·∛n / (2·range) bins (one spare for rounding).
pub fn freedman_diaconis_saturates(n: usize, range: f64, (lo, hi): (f64, f64), max_bins: usize) -> bool {
    range > 0.0 && (hi - lo) * (n as f64).cbrt() / (2.0 * range) >= (max_bins + 1) as f64
}

/// Counts of `values` in `bins` equal bins over `[lo, hi]`; values outside or non-finite are
/// not counted, and `hi` itself falls in the last bin.
pub fn bin_counts(values: impl IntoIterator<Item = f64>, lo: f64, hi: f64, bins: usize) -> Vec<f64> {
    let mut counts = vec![0.0; bins];
    if bins == 0 || hi <= lo {
        return counts;
    }
    let scale = bins as f64 / (hi - lo);
    for v in values {
        if let Some(k) = bin_index(v, (lo, hi), scale, bins) {
            counts[k] += 1.0;
        }
    }
    counts
}

/// The bin of `v` among `bins` equal bins over `[lo, hi]`, `scale` = bins / (hi − lo)
/// ([`bin_counts`]'s placing: `hi` in the last bin); `None` outside or for a non-finite value.
#[inline]
pub fn bin_index(v: f64, (lo, hi): (f64, f64), scale: f64, bins: usize) -> Option<usize> {
    (v >= lo && v <= hi).then(|| (((v - lo) * scale) as usize).min(bins - 1))
}

/// Silverman's rule-of-thumb bandwidth 0.9·min(σ, IQR/1.34)·n^(−1/5) (`None` for fewer than two
/// finite values or no spread).
pub fn silverman_bandwidth(values: &[f64]) -> Option<f64> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let n = finite.len();
    if n < 2 {
        return None;
    }
    let mean = finite.iter().sum::<f64>() / n as f64;
    let sd = (finite.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
    let (q1, q3) = quartiles(&finite)?;
    let iqr = (q3 - q1) / 1.34;
    let spread = if iqr > 0.0 { sd.min(iqr) } else { sd };
    let h = 0.9 * spread * (n as f64).powf(-0.2);
    (h > 0.0 && h.is_finite()).then_some(h)
}

/// A Gaussian kernel density estimate of `values` with bandwidth `h`, evaluated at `points`
/// equally spaced positions from `lo` to `hi` (both included). The values are first counted in
/// fine bins (a 1/8 bandwidth wide at most), so the cost is O(n + points·kernel) rather than
/// O(n·points); the density integrates to the share of values inside the window.
pub fn kde(values: &[f64], h: f64, lo: f64, hi: f64, points: usize) -> Vec<f64> {
    let n = values.iter().filter(|v| v.is_finite()).count();
    if points < 2 || hi <= lo || n == 0 || h <= 0.0 || !h.is_finite() {
        return vec![0.0; points];
    }
    // Count into fine bins covering the window plus four bandwidths each side.
    let (wlo, whi) = (lo - 4.0 * h, hi + 4.0 * h);
    let fine = (((whi - wlo) / (h / 8.0)).ceil() as usize).clamp(64, 1 << 16);
    let width = (whi - wlo) / fine as f64;
    let counts = bin_counts(values.iter().copied(), wlo, whi, fine);
    let norm = 1.0 / (n as f64 * h * (2.0 * std::f64::consts::PI).sqrt());
    let reach = (4.0 * h / width).ceil() as isize;
    let step = (hi - lo) / (points - 1) as f64;
    (0..points)
        .map(|k| {
            let x = lo + step * k as f64;
            let centre = ((x - wlo) / width - 0.5).round() as isize;
            let mut sum = 0.0;
            for b in (centre - reach).max(0)..=(centre + reach).min(fine as isize - 1) {
                let c = counts[b as usize];
                if c > 0.0 {
                    let u = (x - (wlo + (b as f64 + 0.5) * width)) / h;
                    sum += c * (-0.5 * u * u).exp();
                }
            }
            sum * norm
        })
        .collect()
}

/// A density evaluated at equally spaced points from `lo` to `hi` (both included).
#[derive(Clone, Debug, PartialEq)]
pub struct DensityCurve {
    /// The first evaluation point.
    pub lo: f64,
    /// The last evaluation point.
    pub hi: f64,
    /// The density at each point.
    pub density: Vec<f64>,
}

impl DensityCurve {
    /// The evaluation points with their densities.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let step = if self.density.len() > 1 { (self.hi - self.lo) / (self.density.len() - 1) as f64 } else { 0.0 };
        self.density.iter().enumerate().map(move |(k, &d)| (self.lo + step * k as f64, d))
    }

    /// The largest density.
    pub fn peak(&self) -> f64 {
        self.density.iter().copied().fold(0.0, f64::max)
    }

    /// The integral by the trapezoidal rule.
    pub fn integral(&self) -> f64 {
        let n = self.density.len();
        if n < 2 {
            return 0.0;
        }
        let step = (self.hi - self.lo) / (n - 1) as f64;
        let inner: f64 = self.density.iter().sum();
        step * (inner - 0.5 * (self.density[0] + self.density[n - 1]))
    }
}

/// The Gaussian kernel density of `values` with bandwidth `h` over the values' range extended by
/// `cut` bandwidths each side (seaborn's `cut`; 0 trims it to the data), at `points` points.
/// With `cut` ≥ 3 it integrates to 1 within a fraction of a percent. `None` without finite
/// values, or for a bandwidth that is not positive and finite.
pub fn density_curve(values: &[f64], h: f64, cut: f64, points: usize) -> Option<DensityCurve> {
    let (lo, hi) = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(None, |acc: Option<(f64, f64)>, v| Some(acc.map_or((v, v), |(a, b)| (a.min(v), b.max(v)))))?;
    if !(h > 0.0 && h.is_finite()) {
        return None;
    }
    let cut = if cut.is_finite() { cut.max(0.0) } else { 0.0 };
    let (lo, hi) = (lo - cut * h, hi + cut * h);
    if hi <= lo {
        // One distinct value, trimmed: the density is a spike of no width.
        return Some(DensityCurve { lo, hi, density: vec![kde_at(values, h, lo)] });
    }
    Some(DensityCurve { lo, hi, density: kde(values, h, lo, hi, points.max(2)) })
}

/// The Gaussian kernel density of `values` with bandwidth `h` at `x`, summed directly.
fn kde_at(values: &[f64], h: f64, x: f64) -> f64 {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let norm = 1.0 / (finite.len().max(1) as f64 * h * (2.0 * std::f64::consts::PI).sqrt());
    finite.iter().map(|v| (-0.5 * ((x - v) / h).powi(2)).exp()).sum::<f64>() * norm
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saturation_gives_the_bins_the_quartiles_would() {
        // A golden-ratio sequence: spread evenly over [0, 1), in no order.
        let mut k = 0u64;
        let mut next = || {
            k += 1;
            (k as f64 * 0.618_033_988_749_894_9).fract()
        };
        let n = 1_000_000;
        let spread: Vec<f64> = (0..n).map(|_| next() * 10.0).collect();
        // A long tail: the quartiles are close together, the range wide.
        let tail: Vec<f64> = (0..n).map(|_| (1.0 - next()).ln().abs().powi(3)).collect();
        // More than half the values equal: the quartiles agree.
        let ties: Vec<f64> = (0..n).map(|i| if i % 10 < 6 { 1.0 } else { next() * 10.0 }).collect();
        for values in [spread, tail, ties] {
            let (min, max) = values.iter().fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
            for (lo, hi) in [(min, max), (min - 1.0, max + 1.0), (min, min + (max - min) / 1000.0)] {
                let (q1, q3) = quartiles(&values).unwrap();
                let bins = freedman_diaconis_bins(&values, lo, hi, 8, 50);
                if freedman_diaconis_saturates(n, max - min, (lo, hi), 50) && q1 < q3 {
                    assert_eq!(bins, 50, "[{lo}, {hi}]");
                }
            }
        }
        assert!(!freedman_diaconis_saturates(1000, 1.0, (0.0, 1.0), 50), "few values do not");
        assert!(freedman_diaconis_saturates(2_000_000, 1.0, (0.0, 1.0), 50));
        assert!(!freedman_diaconis_saturates(2_000_000, 1.0, (0.0, 0.001), 50), "a narrow domain does not");
    }

    #[test]
    fn quartiles_interpolate_like_numpy() {
        // numpy.percentile([1, 2, 3, 4], [25, 75]) == [1.75, 3.25]
        assert_eq!(quartiles(&[4.0, 1.0, f64::NAN, 3.0, 2.0]), Some((1.75, 3.25)));
        assert_eq!(quartiles(&[]), None);
    }

    #[test]
    fn quantiles_of_a_hand_computed_set() {
        // 1..=8, type 7: positions 1.75, 3.5 and 5.25 (from 0) → 2.75, 4.5, 6.25.
        let v: Vec<f64> = (1..=8).map(f64::from).collect();
        let q = |p| quantile_sorted(&v, p, QuantileMethod::Linear);
        assert_eq!((q(0.25), q(0.5), q(0.75)), (Some(2.75), Some(4.5), Some(6.25)));
        assert_eq!((q(0.0), q(1.0)), (Some(1.0), Some(8.0)));
        assert_eq!(quantile_sorted(&[], 0.5, QuantileMethod::Linear), None);
        assert_eq!(quantile_sorted(&[3.0], 0.25, QuantileMethod::Hazen), Some(3.0));
    }

    #[test]
    fn quantiles_match_numpy() {
        let v = sorted_finite(&[2.5, 0.3, 9.1, 4.4, 7.7, 1.2, 6.6, 3.9, 8.8, 5.0, 0.9]);
        let close = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() < 1e-12);
        // python3 -c "import numpy as np; b=[2.5,0.3,9.1,4.4,7.7,1.2,6.6,3.9,8.8,5.0,0.9];
        //   print(np.percentile(b, [25,50,75]))"                              → [1.85, 4.4, 7.15]
        // ... method='hazen' → [1.525, 4.4, 7.425]; 'weibull' → [1.2, 4.4, 7.7];
        // 'median_unbiased' → [1.4166666666666665, 4.4, 7.5166666666666675]
        for (method, expected) in [
            (QuantileMethod::Linear, [1.85, 4.4, 7.15]),
            (QuantileMethod::Hazen, [1.525, 4.4, 7.425]),
            (QuantileMethod::Weibull, [1.2, 4.4, 7.7]),
            (QuantileMethod::MedianUnbiased, [1.4166666666666665, 4.4, 7.5166666666666675]),
        ] {
            for (p, want) in [0.25, 0.5, 0.75].into_iter().zip(expected) {
                let got = quantile_sorted(&v, p, method);
                assert!(close(got, want), "{method:?} p={p}: {got:?} vs {want}");
            }
        }
        // python3 -c "import numpy as np; print(np.percentile([7,15,36,39,40,41,42,43,47,49], [25,50,75]))"
        //   → [36.75, 40.5, 42.75]
        let s = box_stats(&[7.0, 15.0, 36.0, 39.0, 40.0, 41.0, 42.0, 43.0, 47.0, 49.0], QuantileMethod::Linear, 1.5);
        let s = s.expect("stats");
        assert_eq!((s.q1, s.median, s.q3), (36.75, 40.5, 42.75));
    }

    #[test]
    fn whiskers_end_at_the_last_values_inside_the_fences() {
        // Sorted: −20, 1..=8, 30. Q1 = 2.25, median 4.5, Q3 = 6.75 (numpy: [2.25, 4.5, 6.75]);
        // IQR 4.5, fences −4.5 and 13.5: whiskers at 1 and 8, outliers −20 and 30.
        let values = [5.0, 30.0, 1.0, 2.0, f64::NAN, 3.0, -20.0, 4.0, 6.0, 7.0, 8.0];
        let s = box_stats(&values, QuantileMethod::Linear, 1.5).expect("stats");
        assert_eq!(s.n, 10);
        assert_eq!((s.q1, s.median, s.q3), (2.25, 4.5, 6.75));
        assert_eq!(tukey_fences(s.q1, s.q3, 1.5), (-4.5, 13.5));
        assert_eq!((s.whisker_low, s.whisker_high), (1.0, 8.0));
        assert_eq!((s.min, s.max), (-20.0, 30.0));
        assert_eq!(s.outliers, vec![1, 6], "positions of 30 and −20 in the input");
        assert!((s.mean - 4.6).abs() < 1e-12);
        // A whisker factor of 10 reaches both: no outliers.
        let wide = box_stats(&values, QuantileMethod::Linear, 10.0).expect("stats");
        assert_eq!((wide.whisker_low, wide.whisker_high, wide.outliers.len()), (-20.0, 30.0, 0));
        // A gap right below the box: no value between the fence and Q1, the whisker stays at Q1.
        // [0, 10, 10, 10]: Q1 = 7.5, Q3 = 10, lower fence 3.75; 0 is an outlier.
        let gap = box_stats(&[0.0, 10.0, 10.0, 10.0], QuantileMethod::Linear, 1.5).expect("stats");
        assert_eq!((gap.q1, gap.whisker_low, gap.outliers.clone()), (7.5, 7.5, vec![0]));
        assert_eq!(box_stats(&[f64::NAN], QuantileMethod::Linear, 1.5), None);
    }

    #[test]
    fn notches_are_the_median_plus_minus_1_57_iqr_over_root_n() {
        // The set above: 4.5 ± 1.57 · 4.5 / √10 (python3 -c "import math; print(4.5 - 1.57*4.5/math.sqrt(10))"
        // → 2.26585083309104, and 6.73414916690896 above).
        let s = box_stats(&[-20.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 30.0], QuantileMethod::Linear, 1.5);
        let (lo, hi) = s.expect("stats").notch;
        assert!((lo - 2.26585083309104).abs() < 1e-12 && (hi - 6.73414916690896).abs() < 1e-12, "{lo} {hi}");
        assert_eq!(median_notch(10.0, 4.0, 1), (10.0 - 6.28, 10.0 + 6.28));
    }

    #[test]
    fn a_density_curve_integrates_to_one_over_its_support() {
        let values: Vec<f64> =
            (0..200).map(|i| ((i * 37) % 101) as f64 / 10.0 + if i % 3 == 0 { 4.0 } else { 0.0 }).collect();
        let h = silverman_bandwidth(&values).expect("a bandwidth");
        let curve = density_curve(&values, h, 3.0, 512).expect("a curve");
        assert_eq!(curve.density.len(), 512);
        let (min, max) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        assert!((curve.lo - (min - 3.0 * h)).abs() < 1e-12 && (curve.hi - (max + 3.0 * h)).abs() < 1e-12);
        let integral = curve.integral();
        assert!((integral - 1.0).abs() < 5e-3, "integral {integral}");
        // Trimmed to the data (cut 0), some mass of the end values lies outside.
        let trimmed = density_curve(&values, h, 0.0, 512).expect("a curve").integral();
        assert!(trimmed < integral - 1e-3, "{trimmed}");
        assert_eq!(density_curve(&values, 0.0, 3.0, 512), None);
        assert_eq!(density_curve(&[f64::NAN], 1.0, 3.0, 512), None);
        // One value with no spread and no cut: a single point of density 1/(h√2π).
        let spike = density_curve(&[2.0, 2.0], 0.5, 0.0, 64).expect("a curve");
        assert_eq!(spike.density.len(), 1);
        assert!((spike.peak() - 1.0 / (0.5 * (2.0 * std::f64::consts::PI).sqrt())).abs() < 1e-12);
    }

    #[test]
    fn freedman_diaconis_matches_hand_computation() {
        // 0..=999: IQR = 749.25 − 249.75 = 499.5, width = 999 / 10 = 99.9, bins = ceil(999/99.9) = 10.
        let v: Vec<f64> = (0..1000).map(f64::from).collect();
        assert_eq!(freedman_diaconis_bins(&v, 0.0, 999.0, 2, 100), 10);
        // A constant column has no IQR: Sturges' rule (log2(1000) → 10, + 1 = 11).
        assert_eq!(freedman_diaconis_bins(&[5.0; 1000], 4.0, 6.0, 2, 100), 11);
    }

    #[test]
    fn bin_counts_include_the_upper_edge_and_skip_outsiders() {
        let counts = bin_counts([0.0, 0.5, 1.0, 2.0, 2.0, -1.0, f64::NAN, 3.0], 0.0, 2.0, 2);
        assert_eq!(counts, vec![2.0, 3.0]);
    }

    #[test]
    fn kde_agrees_with_direct_sum_and_integrates_to_one() {
        let values: Vec<f64> = (0..500).map(|i| ((i * 7919) % 1000) as f64 / 100.0).collect();
        let h = silverman_bandwidth(&values).unwrap();
        let (lo, hi, points) = (-5.0, 15.0, 401);
        let density = kde(&values, h, lo, hi, points);
        let step = (hi - lo) / (points - 1) as f64;
        let integral: f64 = density.iter().sum::<f64>() * step;
        assert!((integral - 1.0).abs() < 2e-3, "integral {integral}");
        let norm = 1.0 / (values.len() as f64 * h * (2.0 * std::f64::consts::PI).sqrt());
        for k in (0..points).step_by(40) {
            let x = lo + step * k as f64;
            let direct: f64 = values.iter().map(|v| (-0.5 * ((x - v) / h).powi(2)).exp()).sum::<f64>() * norm;
            assert!((density[k] - direct).abs() < 0.01 * direct.max(0.01), "x {x}: {} vs {direct}", density[k]);
        }
    }

    #[test]
    fn silverman_bandwidth_of_a_known_sample() {
        // 1..=5: sd = 1.5811, IQR/1.34 = 2/1.34 = 1.4925 → h = 0.9 · 1.4925 · 5^(−0.2) = 0.9736.
        let h = silverman_bandwidth(&[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        assert!((h - 0.9 * (2.0 / 1.34) * 5f64.powf(-0.2)).abs() < 1e-12);
        assert_eq!(silverman_bandwidth(&[3.0]), None);
        assert_eq!(silverman_bandwidth(&[3.0, 3.0]), None);
    }
}
