//! The spread of a group of values around its mean: standard deviation, standard error, a 95%
//! confidence interval from Student's t distribution, or the range. Bars draw it as whiskers,
//! lines as a shaded band; both summarise their groups here.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How far an interval around a group's centre reaches.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Spread {
    /// The mean ± one sample standard deviation (n − 1 in the denominator).
    Stdev,
    /// The mean ± one standard error of the mean (stdev / √n).
    Sem,
    /// The mean ± the half-width of a 95% confidence interval: t(0.975, n − 1) · stdev / √n.
    Ci95,
    /// From the smallest to the largest value.
    Minmax,
}

impl Spread {
    /// The spec's word for it.
    pub fn name(self) -> &'static str {
        match self {
            Spread::Stdev => "stdev",
            Spread::Sem => "sem",
            Spread::Ci95 => "ci95",
            Spread::Minmax => "minmax",
        }
    }

    /// How a title says what the interval is, after the centre: "± 1 SD", "± SEM", "± 95% CI",
    /// "min–max".
    pub fn describe(self) -> &'static str {
        match self {
            Spread::Stdev => "± 1 SD",
            Spread::Sem => "± SEM",
            Spread::Ci95 => "± 95% CI",
            Spread::Minmax => "with min–max",
        }
    }

    /// Whether the interval is built around the mean (every spread but the range).
    pub fn needs_mean(self) -> bool {
        self != Spread::Minmax
    }

    /// The interval `[lower, upper]` of a group around `centre` (its mean, or for `minmax` any
    /// centre: the range does not depend on it). `None` for a group of fewer than two values,
    /// whose spread is unknown.
    pub fn interval(self, s: &Summary, centre: f64) -> Option<(f64, f64)> {
        if s.n < 2 {
            return None;
        }
        let half = match self {
            Spread::Minmax => return Some((s.min, s.max)),
            Spread::Stdev => s.stdev,
            Spread::Sem => s.sem(),
            Spread::Ci95 => t_quantile(0.975, (s.n - 1) as f64) * s.sem(),
        };
        Some((centre - half, centre + half))
    }
}

/// Summary statistics of one group of finite values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// How many values.
    pub n: usize,
    /// Their sum.
    pub sum: f64,
    /// Their mean.
    pub mean: f64,
    /// Their median (the mean of the two middle values for an even count).
    pub median: f64,
    /// The sample standard deviation (n − 1 in the denominator); 0 for a single value.
    pub stdev: f64,
    /// The smallest value.
    pub min: f64,
    /// The largest value.
    pub max: f64,
}

impl Summary {
    /// The statistics of the finite values among `values`; `None` when there are none.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Summary> {
        let mut v: Vec<f64> = values.into_iter().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return None;
        }
        // The sum in the order given, as a running total would add the rows.
        let sum: f64 = v.iter().sum();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let mean = sum / n as f64;
        // Two passes: the squared deviations from the mean, not the cancelling sum of squares.
        let ss: f64 = v.iter().map(|x| (x - mean) * (x - mean)).sum();
        let stdev = if n > 1 { (ss / (n - 1) as f64).sqrt() } else { 0.0 };
        let median = if n % 2 == 1 { v[n / 2] } else { (v[n / 2 - 1] + v[n / 2]) / 2.0 };
        Some(Summary { n, sum, mean, median, stdev, min: v[0], max: v[n - 1] })
    }

    /// The standard error of the mean, stdev / √n.
    pub fn sem(&self) -> f64 {
        self.stdev / (self.n as f64).sqrt()
    }
}

/// The `p` quantile of Student's t distribution with `df` degrees of freedom (`df > 0`,
/// `0 < p < 1`): the `t` with P(T ≤ t) = p. NaN outside that range. Accurate to about 1e-12
/// relative: the distribution function is evaluated through the regularised incomplete beta
/// function and inverted by bisection refined with Newton steps.
pub fn t_quantile(p: f64, df: f64) -> f64 {
    if !(p > 0.0 && p < 1.0 && df > 0.0) {
        return f64::NAN;
    }
    if p == 0.5 {
        return 0.0;
    }
    if df == 1.0 {
        // The Cauchy distribution has a closed form.
        return (std::f64::consts::PI * (p - 0.5)).tan();
    }
    // Solve for the upper tail and mirror: the distribution is symmetric about zero.
    let upper = p > 0.5;
    let tail = if upper { 1.0 - p } else { p };
    // Bracket: P(T > t) falls from 1/2 at 0; double the upper end until it drops below `tail`.
    let (mut lo, mut hi) = (0.0f64, 2.0f64);
    while t_upper_tail(hi, df) > tail && hi < 1e300 {
        lo = hi;
        hi *= 2.0;
    }
    let mut t = 0.5 * (lo + hi);
    for _ in 0..200 {
        let f = t_upper_tail(t, df) - tail;
        if f > 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        // Newton: d/dt P(T > t) = −density(t); fall back to bisection when it leaves the bracket.
        let step = f / t_density(t, df);
        let next = t + step;
        t = if next > lo && next < hi { next } else { 0.5 * (lo + hi) };
        if (hi - lo) <= 1e-15 * t.abs() || step.abs() <= 1e-15 * t.abs() {
            break;
        }
    }
    if upper { t } else { -t }
}

/// P(T > t) for `t ≥ 0`: half the regularised incomplete beta I_x(df/2, 1/2) at x = df/(df + t²).
fn t_upper_tail(t: f64, df: f64) -> f64 {
    0.5 * incomplete_beta(df / (df + t * t), df / 2.0, 0.5)
}

/// The density of Student's t distribution.
fn t_density(t: f64, df: f64) -> f64 {
    let log_norm = ln_gamma((df + 1.0) / 2.0) - ln_gamma(df / 2.0) - 0.5 * (df * std::f64::consts::PI).ln();
    (log_norm - (df + 1.0) / 2.0 * (1.0 + t * t / df).ln()).exp()
}

/// The regularised incomplete beta function I_x(a, b), by its continued fraction (modified
/// Lentz), on the side of `x` where the fraction converges fast.
fn incomplete_beta(x: f64, a: f64, b: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x >= 1.0 {
        return 1.0;
    }
    let front = (ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * (1.0 - x).ln()).exp();
    if x < (a + 1.0) / (a + b + 2.0) {
        front * beta_fraction(x, a, b) / a
    } else {
        1.0 - front * beta_fraction(1.0 - x, b, a) / b
    }
}

/// The continued fraction of the incomplete beta function.
fn beta_fraction(x: f64, a: f64, b: f64) -> f64 {
    const TINY: f64 = 1e-300;
    let tiny_guard = |v: f64| if v.abs() < TINY { TINY } else { v };
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 / tiny_guard(1.0 - qab * x / qap);
    let mut h = d;
    for m in 1..=1000 {
        let m = m as f64;
        let m2 = 2.0 * m;
        let even = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 / tiny_guard(1.0 + even * d);
        c = tiny_guard(1.0 + even / c);
        h *= d * c;
        let odd = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 / tiny_guard(1.0 + odd * d);
        c = tiny_guard(1.0 + odd / c);
        let delta = d * c;
        h *= delta;
        if (delta - 1.0).abs() < 1e-16 {
            break;
        }
    }
    h
}

/// ln Γ(x) for x > 0 (Lanczos approximation, g = 7, 9 terms; about 15 digits).
fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const COEF: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Γ(x) Γ(1 − x) = π / sin(πx).
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut sum = COEF[0];
    for (i, c) in COEF.iter().enumerate().skip(1) {
        sum += c / (x + i as f64);
    }
    let t = x + G + 0.5;
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t_quantiles_match_the_published_table() {
        // Two-sided 95% (p = 0.975) critical values as printed in the usual tables (3 decimals).
        for (df, want) in [
            (1.0, 12.706),
            (2.0, 4.303),
            (3.0, 3.182),
            (4.0, 2.776),
            (5.0, 2.571),
            (10.0, 2.228),
            (20.0, 2.086),
            (30.0, 2.042),
            (60.0, 2.000),
            (120.0, 1.980),
        ] {
            let t = t_quantile(0.975, df);
            assert!((t - want).abs() < 5e-4, "t(0.975, {df}) = {t}, table {want}");
        }
        // Other levels of the same table: 90% and 99% two-sided.
        assert!((t_quantile(0.95, 5.0) - 2.015).abs() < 5e-4);
        assert!((t_quantile(0.995, 10.0) - 3.169).abs() < 5e-4);
        // Large df: the normal quantile 1.959964.
        assert!((t_quantile(0.975, 1e7) - 1.959_964).abs() < 1e-5);
        // Symmetry, the centre, and more digits where they are known exactly.
        assert!((t_quantile(0.025, 5.0) + t_quantile(0.975, 5.0)).abs() < 1e-12);
        assert_eq!(t_quantile(0.5, 7.0), 0.0);
        // df = 2 has the closed form (2p − 1) / √(2p(1 − p)).
        let p: f64 = 0.975;
        let exact = (2.0 * p - 1.0) / (2.0 * p * (1.0 - p)).sqrt();
        assert!((t_quantile(p, 2.0) - exact).abs() < 1e-10, "{} vs {exact}", t_quantile(p, 2.0));
        assert!(t_quantile(0.0, 3.0).is_nan() && t_quantile(0.5, 0.0).is_nan());
    }

    #[test]
    fn summary_of_a_small_set_by_hand() {
        // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, squared deviations sum to 32, stdev √(32/7).
        let s = Summary::of([2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0, f64::NAN]).expect("values");
        assert_eq!((s.n, s.sum, s.mean, s.median, s.min, s.max), (8, 40.0, 5.0, 4.5, 2.0, 9.0));
        let sd = (32.0f64 / 7.0).sqrt();
        assert!((s.stdev - sd).abs() < 1e-12);
        assert!((s.sem() - sd / 8f64.sqrt()).abs() < 1e-12);
        // 95% CI: t(0.975, 7) = 2.364624 (table 2.365).
        let (lo, hi) = Spread::Ci95.interval(&s, s.mean).expect("n > 1");
        let half = 2.364_624_251_6 * sd / 8f64.sqrt();
        assert!((hi - 5.0 - half).abs() < 1e-8 && (5.0 - lo - half).abs() < 1e-8, "{lo} {hi}");
        assert_eq!(Spread::Minmax.interval(&s, s.mean), Some((2.0, 9.0)));
        assert_eq!(Spread::Stdev.interval(&s, 5.0), Some((5.0 - sd, 5.0 + sd)));
        // One value: no spread.
        let one = Summary::of([3.0]).expect("a value");
        assert_eq!((one.stdev, one.median), (0.0, 3.0));
        assert_eq!(Spread::Sem.interval(&one, 3.0), None);
        assert_eq!(Summary::of([f64::INFINITY]), None);
    }
}
