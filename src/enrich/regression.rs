//! Trend lines through scattered (x, y): the least-squares line with its coefficient of
//! determination, and LOESS (locally weighted linear regression with tricube weights, as
//! Cleveland's lowess without robustness iterations).

/// A least-squares line y = intercept + slope·x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearFit {
    /// Change of y per unit of x.
    pub slope: f64,
    /// y at x = 0.
    pub intercept: f64,
    /// Coefficient of determination R² (1 − residual / total sum of squares); 1 when y is
    /// constant and the line fits it exactly.
    pub r2: f64,
    /// Points fitted.
    pub n: usize,
}

impl LinearFit {
    /// y on the line at `x`.
    pub fn at(&self, x: f64) -> f64 {
        self.intercept + self.slope * x
    }
}

/// The least-squares line through the finite pairs of `points`; `None` for fewer than two
/// points or no spread in x. Sums are taken about the means, so large offsets (dates in
/// milliseconds) keep their precision.
pub fn linear_fit(points: &[(f64, f64)]) -> Option<LinearFit> {
    let finite: Vec<(f64, f64)> = points.iter().copied().filter(|(x, y)| x.is_finite() && y.is_finite()).collect();
    let n = finite.len();
    if n < 2 {
        return None;
    }
    let (mx, my) = finite.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (mx / n as f64, my / n as f64);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (x, y) in &finite {
        let (dx, dy) = (x - mx, y - my);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if !(sxx > 0.0) {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let residual = (syy - slope * sxy).max(0.0);
    let r2 = if syy > 0.0 { 1.0 - residual / syy } else { 1.0 };
    Some(LinearFit { slope, intercept, r2, n })
}

/// LOESS: at each of `at`, the weighted least-squares line through the `span` fraction of
/// `points` nearest in x (at least 2 and at most all), weighted by the tricube of distance over
/// the largest distance among them, evaluated there. `points` must be sorted by x and finite.
pub fn loess(points: &[(f64, f64)], span: f64, at: &[f64]) -> Vec<f64> {
    let n = points.len();
    if n < 2 {
        return vec![f64::NAN; at.len()];
    }
    let k = ((span * n as f64 + 1e-10).floor() as usize).clamp(2, n);
    at.iter()
        .map(|&x0| {
            // The window of k points nearest x0: start k before x0's place and slide right while
            // the next point beyond the window is strictly nearer than its first.
            let mut lo = points.partition_point(|p| p.0 < x0).saturating_sub(k).min(n - k);
            while lo + k < n && (x0 - points[lo].0) > (points[lo + k].0 - x0) {
                lo += 1;
            }
            let window = &points[lo..lo + k];
            let reach = window.iter().map(|(x, _)| (x - x0).abs()).fold(0.0, f64::max);
            local_line(window, x0, reach)
        })
        .collect()
}

/// The tricube-weighted least-squares line through `window` evaluated at `x0`; `reach` is the
/// largest distance in the window (all weights 1 when it is 0).
fn local_line(window: &[(f64, f64)], x0: f64, reach: f64) -> f64 {
    let weight = |x: f64| {
        if reach <= 0.0 {
            return 1.0;
        }
        let u = ((x - x0).abs() / reach).min(1.0);
        (1.0 - u * u * u).powi(3)
    };
    let (mut sw, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for &(x, y) in window {
        let w = weight(x);
        sw += w;
        sx += w * x;
        sy += w * y;
    }
    if sw <= 0.0 {
        return f64::NAN;
    }
    let (mx, my) = (sx / sw, sy / sw);
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for &(x, y) in window {
        let w = weight(x);
        sxx += w * (x - mx) * (x - mx);
        sxy += w * (x - mx) * (y - my);
    }
    if sxx > 0.0 { my + sxy / sxx * (x0 - mx) } else { my }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_through_anscombes_first_set() {
        // Anscombe (1973), set I: y = 3.00 + 0.500 x, R² = 0.667 (published to three places).
        let x = [10.0, 8.0, 13.0, 9.0, 11.0, 14.0, 6.0, 4.0, 12.0, 7.0, 5.0];
        let y = [8.04, 6.95, 7.58, 8.81, 8.33, 9.96, 7.24, 4.26, 10.84, 4.82, 5.68];
        let points: Vec<(f64, f64)> = x.iter().copied().zip(y).collect();
        let fit = linear_fit(&points).unwrap();
        assert!((fit.slope - 0.5001).abs() < 1e-4, "{fit:?}");
        assert!((fit.intercept - 3.0001).abs() < 1e-4, "{fit:?}");
        assert!((fit.r2 - 0.6665).abs() < 1e-4, "{fit:?}");
        assert_eq!(fit.n, 11);
    }

    #[test]
    fn exact_lines_degenerate_inputs_and_large_offsets() {
        let t0 = 1.7e12; // milliseconds since 1970, as dates are held
        let points: Vec<(f64, f64)> = (0..5).map(|i| (t0 + i as f64 * 1000.0, 2.0 * i as f64 + 1.0)).collect();
        let fit = linear_fit(&points).unwrap();
        assert!((fit.slope - 0.002).abs() < 1e-12);
        assert!((fit.at(t0) - 1.0).abs() < 1e-6);
        assert!((fit.r2 - 1.0).abs() < 1e-12);
        assert_eq!(linear_fit(&[(1.0, 2.0)]), None);
        assert_eq!(linear_fit(&[(1.0, 2.0), (1.0, 3.0)]), None, "no spread in x");
        assert_eq!(linear_fit(&[(0.0, 2.0), (1.0, 2.0)]).unwrap().r2, 1.0, "constant y fitted exactly");
    }

    /// (Horsepower, Miles_per_Gallon) of the cars in examples/data/cars.json with both, in file order.
    fn cars() -> Vec<(f64, f64)> {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/data/cars.json");
        let cars: Vec<serde_json::Value> = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        cars.iter().filter_map(|c| Some((c["Horsepower"].as_f64()?, c["Miles_per_Gallon"].as_f64()?))).collect()
    }

    #[test]
    fn loess_and_the_line_match_statsmodels_and_numpy_on_the_cars() {
        // Known answers from scripts/loess_reference.py: statsmodels' lowess(frac=0.5, it=0,
        // delta=0) at the first ten cars, and np.polyfit / np.corrcoef.
        let pairs = cars();
        assert_eq!(pairs.len(), 392);
        let at: Vec<f64> = pairs.iter().take(10).map(|p| p.0).collect();
        let mut sorted = pairs.clone();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        let expected = [
            17.7928074273,
            14.3226291334,
            15.5615648888,
            15.5615648888,
            16.5618819235,
            12.8479967293,
            11.9011758561,
            12.1087617905,
            11.6997046027,
            13.2045927912,
        ];
        for ((x, got), want) in at.iter().zip(loess(&sorted, 0.5, &at)).zip(expected) {
            assert!((got - want).abs() < 1e-8, "at {x}: {got} vs statsmodels {want}");
        }
        let fit = linear_fit(&pairs).unwrap();
        assert!((fit.slope - -0.15784473335365373).abs() < 1e-12, "{fit:?}");
        assert!((fit.intercept - 39.93586102117046).abs() < 1e-10, "{fit:?}");
        assert!((fit.r2 - 0.6059482578894343).abs() < 1e-12, "{fit:?}");
    }

    #[test]
    fn loess_reproduces_a_line_and_follows_a_curve_locally() {
        let line: Vec<(f64, f64)> = (0..50).map(|i| (i as f64, 3.0 - 0.5 * i as f64)).collect();
        for (x, y) in loess(&line, 0.3, &[0.0, 10.5, 49.0]).iter().zip([3.0, -2.25, -21.5]) {
            assert!((x - y).abs() < 1e-9, "{x} vs {y}");
        }
        // A parabola: a local line with a narrow span stays close to it; the global line does not.
        let curve: Vec<(f64, f64)> = (0..101).map(|i| (i as f64 / 10.0, (i as f64 / 10.0 - 5.0).powi(2))).collect();
        let fitted = loess(&curve, 0.1, &[5.0]);
        assert!(fitted[0] < 0.6, "{fitted:?}");
        assert!(linear_fit(&curve).unwrap().at(5.0) > 8.0);
    }
}
