//! One-dimensional distributions: histogram bins (Freedman–Diaconis), binned counts, and
//! Gaussian kernel density estimates (Silverman's bandwidth) computed on a fine binned grid.

/// Quartiles (25th and 75th percentile, linear interpolation) of finite values.
pub fn quartiles(values: &[f64]) -> Option<(f64, f64)> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let at = |q: f64| {
        let pos = q * (v.len() - 1) as f64;
        let i = pos.floor() as usize;
        let frac = pos - i as f64;
        match v.get(i + 1) {
            Some(next) => v[i] + frac * (next - v[i]),
            None => v[i],
        }
    };
    Some((at(0.25), at(0.75)))
}

/// Number of histogram bins over `[lo, hi]` by the Freedman–Diaconis rule (bin width
/// 2·IQR·n^(−1/3)), clamped to `[min_bins, max_bins]`; Sturges' rule when the IQR is zero.
pub fn freedman_diaconis_bins(values: &[f64], lo: f64, hi: f64, min_bins: usize, max_bins: usize) -> usize {
    let n = values.iter().filter(|v| v.is_finite()).count();
    if n == 0 || hi <= lo {
        return min_bins;
    }
    let sturges = ((n as f64).log2().ceil() as usize + 1).clamp(min_bins, max_bins);
    let Some((q1, q3)) = quartiles(values) else { return sturges };
    let width = 2.0 * (q3 - q1) / (n as f64).cbrt();
    if width <= 0.0 || !width.is_finite() {
        return sturges;
    }
    (((hi - lo) / width).ceil() as usize).clamp(min_bins, max_bins)
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
        if !(v >= lo && v <= hi) {
            continue;
        }
        let k = (((v - lo) * scale) as usize).min(bins - 1);
        counts[k] += 1.0;
    }
    counts
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quartiles_interpolate_like_numpy() {
        // numpy.percentile([1, 2, 3, 4], [25, 75]) == [1.75, 3.25]
        assert_eq!(quartiles(&[4.0, 1.0, f64::NAN, 3.0, 2.0]), Some((1.75, 3.25)));
        assert_eq!(quartiles(&[]), None);
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
        // 1..=5: sd = 1.5811, IQR/1.34 = 2/1.34 = 1.4925 → h = 0.9 · 1.4925 · 5^(−0.2) = 1.0589.
        let h = silverman_bandwidth(&[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        assert!((h - 0.9 * (2.0 / 1.34) * 5f64.powf(-0.2)).abs() < 1e-12);
        assert_eq!(silverman_bandwidth(&[3.0]), None);
        assert_eq!(silverman_bandwidth(&[3.0, 3.0]), None);
    }
}
