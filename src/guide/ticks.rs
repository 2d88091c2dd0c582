//! Nice tick values for numeric axes: the extended Wilkinson algorithm of Talbot, Lin and
//! Hanrahan (2010), "An Extension of Wilkinson's Algorithm for Positioning Tick Labels on Axes".
//!
//! Candidate labelings are tick sequences `start·u, (start+j)·u, …` with `u = q·10^z`, `q` from
//! the nice-number list [`Q`]. Each is scored by simplicity, coverage, density and legibility
//! (legibility is constant here: one format per axis), and whole branches of the search are
//! skipped once their best possible score cannot beat the best labeling found so far.
//!
//! The search runs on the data divided by a power of ten so that the range lies in about 1..10;
//! this keeps every intermediate finite for ranges from 1e-300 to 1e308. Final tick values are
//! built from exact decimals (`25e-3`, not `0.025000000000000001`).

/// Nice step mantissas, most preferred first (the paper's Q).
const Q: [f64; 6] = [1.0, 5.0, 2.0, 2.5, 4.0, 3.0];
/// `Q` times ten, as integers, for exact tick arithmetic.
const Q10: [i128; 6] = [10, 50, 20, 25, 40, 30];
/// Weights of simplicity, coverage, density and legibility.
const W: [f64; 4] = [0.25, 0.2, 0.5, 0.05];
/// Requested tick counts are clamped to this (bounds work and output size).
pub const MAX_TARGET: usize = 50;
/// Hard cap on candidate labelings scored by one call (the pruning normally stops far earlier).
const MAX_EVALUATIONS: usize = 200_000;
/// Hard caps on the paper's unbounded loops over skip `j`, tick count `k` and exponent `z`.
const MAX_SKIP: i128 = 20;
const MAX_COUNT: i128 = 4 * MAX_TARGET as i128 + 8;
const MAX_EXPONENT_STEPS: i32 = 24;

/// Tick values in ascending order and the distance between neighbours.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct TickSet {
    /// Tick values, ascending, equally spaced by `step`.
    pub values: Vec<f64>,
    /// Distance between neighbouring ticks (0 when there are no ticks).
    pub step: f64,
}

impl TickSet {
    /// No ticks.
    pub fn empty() -> TickSet {
        TickSet { values: Vec::new(), step: 0.0 }
    }

    /// Whether there are no ticks.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }
}

/// The interval used in place of a degenerate (single-value) range `v..v`: `v ± 1` when `|v|/10`
/// is zero or subnormal, else `v ± |v|/10`; bounds are clamped to the finite `f64` range.
pub fn pad_degenerate(v: f64) -> (f64, f64) {
    let pad = v.abs() * 0.1;
    let pad = if pad.is_normal() { pad } else { 1.0 };
    ((v - pad).max(f64::MIN), (v + pad).min(f64::MAX))
}

/// Extended Wilkinson ticks for the data range `dmin..dmax`, aiming at `target` ticks.
///
/// With `only_loose`, the first tick is ≤ `dmin` and the last ≥ `dmax` (the ticks cover the data);
/// otherwise ticks may fall short of or beyond the data as the score decides. Reversed bounds are
/// swapped; equal bounds are widened by [`pad_degenerate`]; a non-finite bound or `target == 0`
/// gives no ticks; `target` is otherwise clamped to `2..=MAX_TARGET`. Ticks that would overflow
/// `f64` are dropped.
pub fn extended(dmin: f64, dmax: f64, target: usize, only_loose: bool) -> TickSet {
    if !dmin.is_finite() || !dmax.is_finite() || target == 0 {
        return TickSet::empty();
    }
    let (lo, hi) = if dmin <= dmax { (dmin, dmax) } else { (dmax, dmin) };
    let (lo, hi) = if (hi - lo).is_normal() || (hi - lo).is_infinite() { (lo, hi) } else { pad_degenerate(lo) };
    let e = range_exponent(lo, hi);
    let scale = exact_decimal(1, e);
    let (a, b) = (lo / scale, hi / scale);
    let m = target.clamp(2, MAX_TARGET) as f64;
    let best = search(a, b, m, only_loose).unwrap_or_else(|| fallback(a, b));
    materialize(&best, e)
}

/// `floor(log10(hi - lo))`, computed without overflowing when `hi - lo` exceeds `f64::MAX`.
fn range_exponent(lo: f64, hi: f64) -> i32 {
    let d = hi - lo;
    let log = if d.is_finite() { d.log10() } else { (hi * 0.5 - lo * 0.5).log10() + std::f64::consts::LOG10_2 };
    log.floor() as i32
}

/// The nearest `f64` to the decimal `mantissa × 10^exp`.
pub(crate) fn exact_decimal(mantissa: i128, exp: i32) -> f64 {
    format!("{mantissa}e{exp}").parse().unwrap_or(f64::NAN)
}

/// One candidate labeling: ticks at `(start + i·j)·q·10^z` for `i` in `0..k`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Candidate {
    /// Index into `Q`.
    qi: usize,
    /// Skip: only every j-th multiple of `q·10^z` is a tick.
    j: i128,
    /// Number of ticks.
    k: i128,
    /// Exponent of the unit `q·10^z`.
    z: i32,
    /// First tick, in units of `q·10^z`.
    start: i128,
}

fn score(s: f64, c: f64, d: f64, l: f64) -> f64 {
    W[0] * s + W[1] * c + W[2] * d + W[3] * l
}

/// Simplicity: earlier `q` and smaller skip are simpler; including zero adds one.
fn simplicity(qi: usize, j: i128, start: i128, k: i128) -> f64 {
    let has_zero = start.rem_euclid(j) == 0 && start <= 0 && start.saturating_add((k - 1) * j) >= 0;
    simplicity_max(qi, j) - if has_zero { 0.0 } else { 1.0 }
}

fn simplicity_max(qi: usize, j: i128) -> f64 {
    let n = Q.len() as f64;
    2.0 - qi as f64 / (n - 1.0) - j as f64
}

/// Coverage: penalises labelings that extend beyond (or fall short of) the data.
fn coverage(a: f64, b: f64, lmin: f64, lmax: f64) -> f64 {
    let r = 0.1 * (b - a);
    1.0 - 0.5 * ((b - lmax).powi(2) + (a - lmin).powi(2)) / (r * r)
}

fn coverage_max(a: f64, b: f64, span: f64) -> f64 {
    let range = b - a;
    if span > range {
        let half = (span - range) / 2.0;
        let r = 0.1 * range;
        1.0 - half * half / (r * r)
    } else {
        1.0
    }
}

/// Density: how close the tick density is to the target density `m` ticks over the shown range.
fn density(k: f64, m: f64, a: f64, b: f64, lmin: f64, lmax: f64) -> f64 {
    let r = (k - 1.0) / (lmax - lmin);
    let rt = (m - 1.0) / (lmax.max(b) - a.min(lmin));
    2.0 - (r / rt).max(rt / r)
}

fn density_max(k: f64, m: f64) -> f64 {
    if k >= m { 2.0 - (k - 1.0) / (m - 1.0) } else { 1.0 }
}

/// The paper's search with pruning, over scaled data `a < b`. `None` if nothing scored above −2
/// (or, with `only_loose`, nothing covered the data).
fn search(a: f64, b: f64, m: f64, only_loose: bool) -> Option<Candidate> {
    let mut best: Option<Candidate> = None;
    let mut best_score = -2.0;
    let mut budget = MAX_EVALUATIONS;
    let eps = 1e-12 * a.abs().max(b.abs()).max(b - a);
    for j in 1..=MAX_SKIP {
        let mut any_q = false;
        for (qi, &q) in Q.iter().enumerate() {
            let sm = simplicity_max(qi, j);
            if score(sm, 1.0, 1.0, 1.0) < best_score {
                break;
            }
            any_q = true;
            for k in 2..=MAX_COUNT {
                let dm = density_max(k as f64, m);
                if score(sm, 1.0, dm, 1.0) < best_score {
                    break;
                }
                let delta = (b - a) / (k + 1) as f64 / j as f64 / q;
                let z0 = delta.log10().ceil() as i32;
                for z in z0..z0 + MAX_EXPONENT_STEPS {
                    let unit = q * 10f64.powi(z);
                    let step = unit * j as f64;
                    let cm = coverage_max(a, b, step * (k - 1) as f64);
                    if score(sm, cm, dm, 1.0) < best_score {
                        break;
                    }
                    // Float-to-int casts saturate; the arithmetic saturates too.
                    let min_start = ((b / step).floor() as i128).saturating_mul(j).saturating_sub((k - 1) * j);
                    let max_start = ((a / step).ceil() as i128).saturating_mul(j);
                    let mut start = min_start;
                    while start <= max_start {
                        if budget == 0 {
                            return best;
                        }
                        budget -= 1;
                        let lmin = start as f64 * unit;
                        let lmax = lmin + step * (k - 1) as f64;
                        let s = simplicity(qi, j, start, k);
                        let c = coverage(a, b, lmin, lmax);
                        let g = density(k as f64, m, a, b, lmin, lmax);
                        let total = score(s, c, g, 1.0);
                        let loose = lmin <= a + eps && lmax >= b - eps;
                        if total > best_score && (!only_loose || loose) {
                            best_score = total;
                            best = Some(Candidate { qi, j, k, z, start });
                        }
                        let Some(next) = start.checked_add(1) else { break };
                        start = next;
                    }
                }
            }
        }
        if !any_q {
            break;
        }
    }
    best
}

/// A loose labeling that always exists: multiples of the power of ten at or above the range.
fn fallback(a: f64, b: f64) -> Candidate {
    let z = (b - a).log10().ceil() as i32;
    let unit = 10f64.powi(z);
    let start = (a / unit).floor() as i128;
    let end = (b / unit).ceil() as i128;
    Candidate { qi: 0, j: 1, k: (end - start + 1).clamp(1, 3), z, start }
}

/// Real tick values of a candidate found on data scaled by `10^-e`.
fn materialize(c: &Candidate, e: i32) -> TickSet {
    let Some(q10) = Q10.get(c.qi).copied() else { return TickSet::empty() };
    // Tick i is (start + i·j)·q·10^(z+e) = (start + i·j)·q10 · 10^(z+e-1).
    let exp = c.z.saturating_add(e).saturating_sub(1);
    let mut values: Vec<f64> = Vec::new();
    for i in 0..c.k {
        let n = c.start.saturating_add(i.saturating_mul(c.j));
        let v = exact_decimal(n.saturating_mul(q10), exp);
        if v.is_finite() && values.last().is_none_or(|&last| v > last) {
            values.push(v);
        }
    }
    let step = exact_decimal(q10.saturating_mul(c.j), exp);
    TickSet { values, step: if step.is_finite() { step } else { 0.0 } }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vals(dmin: f64, dmax: f64, target: usize, loose: bool) -> Vec<f64> {
        extended(dmin, dmax, target, loose).values
    }

    fn assert_equally_spaced(t: &TickSet) {
        for w in t.values.windows(2) {
            assert!(w[1] > w[0], "not ascending: {:?}", t.values);
            let gap = w[1] - w[0];
            assert!(
                (gap - t.step).abs() <= 1e-9 * t.step.abs().max(w[1].abs()),
                "uneven: {:?} step {}",
                t.values,
                t.step
            );
        }
    }

    #[test]
    fn known_outputs() {
        // The paper's scoring for m = 5 over 0..100 prefers steps of 25 (simplicity 1.4, density 1)
        // over steps of 20 (simplicity 1.6 but six ticks, density 0.75): 1.1 vs 1.025.
        assert_eq!(vals(0.0, 100.0, 5, false), vec![0.0, 25.0, 50.0, 75.0, 100.0]);
        assert_eq!(vals(0.0, 100.0, 6, false), vec![0.0, 20.0, 40.0, 60.0, 80.0, 100.0]);
        assert_eq!(vals(0.0, 10.0, 6, true), vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert_eq!(vals(0.0, 1.0, 3, true), vec![0.0, 0.5, 1.0]);
    }

    #[test]
    fn loose_ticks_cover_awkward_ranges() {
        let t = extended(-1.3, 7.9, 5, true);
        assert_eq!(t.values, vec![-2.0, 0.0, 2.0, 4.0, 6.0, 8.0]);
        assert_eq!(t.step, 2.0);
        let t = extended(0.001, 0.0095, 5, true);
        assert_eq!(t.values, vec![0.0, 0.0025, 0.005, 0.0075, 0.01]);
        assert_eq!(t.step, 0.0025);
    }

    #[test]
    fn values_are_exact_decimals() {
        let t = extended(0.0, 0.9, 10, true);
        assert!(t.values.contains(&0.3), "{:?}", t.values);
        assert!(t.values.contains(&0.7), "{:?}", t.values);
        assert_eq!(t.step, 0.1);
    }

    #[test]
    fn reversed_input_gives_ascending_ticks() {
        assert_eq!(vals(100.0, 0.0, 5, false), vals(0.0, 100.0, 5, false));
    }

    #[test]
    fn degenerate_and_bad_input() {
        assert!(extended(f64::NAN, 1.0, 5, true).is_empty());
        assert!(extended(0.0, f64::INFINITY, 5, true).is_empty());
        assert!(extended(0.0, 1.0, 0, true).is_empty());
        // 5..5 is treated as 4.5..5.5.
        let t = extended(5.0, 5.0, 5, true);
        assert!(t.values.len() >= 2);
        assert!(t.values[0] <= 4.5 && *t.values.last().unwrap_or(&0.0) >= 5.5, "{:?}", t.values);
        // 0..0 is treated as −1..1.
        let t = extended(0.0, 0.0, 5, true);
        assert!(t.values.contains(&0.0) && t.values[0] <= -1.0, "{:?}", t.values);
        // A target of one still gives at least two ticks.
        assert!(extended(0.0, 10.0, 1, true).values.len() >= 2);
        assert_eq!(pad_degenerate(0.0), (-1.0, 1.0));
        assert_eq!(pad_degenerate(-10.0), (-11.0, -9.0));
        assert_eq!(pad_degenerate(f64::MAX).1, f64::MAX);
    }

    #[test]
    fn extreme_magnitudes_stay_finite() {
        let t = extended(0.0, 1e-300, 5, true);
        assert_eq!(t.values.first(), Some(&0.0));
        assert_eq!(t.values.last(), Some(&1e-300));
        assert_equally_spaced(&t);
        let t = extended(0.0, 1e300, 5, true);
        assert_eq!(t.values.last(), Some(&1e300));
        assert_equally_spaced(&t);
        let t = extended(-1e308, 1e308, 5, false);
        assert!(t.values.len() >= 2 && t.values.iter().all(|v| v.is_finite()), "{:?}", t.values);
        let t = extended(-f64::MAX, f64::MAX, 5, true);
        assert!(t.values.iter().all(|v| v.is_finite()));
        let t = extended(5e-324, 1e-323, 5, true);
        assert!(t.values.iter().all(|v| v.is_finite()));
    }

    #[test]
    fn far_from_zero_ranges() {
        let t = extended(1e9 + 0.1, 1e9 + 0.9, 5, true);
        assert!(t.values.len() >= 2, "{:?}", t.values);
        assert!(t.values[0] <= 1e9 + 0.1 && *t.values.last().unwrap_or(&0.0) >= 1e9 + 0.9);
        // Beyond f64 precision, ticks collapse but stay strictly ascending.
        let t = extended(1e17, 1e17 + 64.0, 5, false);
        assert_equally_spaced(&t);
    }

    #[test]
    fn properties_over_many_ranges() {
        // A deterministic pseudo-random sweep of ranges and targets.
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..400 {
            let mag = 10f64.powf(next() * 12.0 - 6.0);
            let a = (next() - 0.5) * 20.0 * mag;
            let b = a + (next() + 0.01) * 10.0 * mag;
            let target = 2 + (next() * 9.0) as usize;
            for loose in [false, true] {
                let t = extended(a, b, target, loose);
                let n = t.values.len();
                assert!(n >= 2 && n <= 2 * target + 2, "{a}..{b} target {target}: {:?}", t.values);
                assert_equally_spaced(&t);
                if loose {
                    assert!(t.values[0] <= a && t.values[n - 1] >= b, "{a}..{b}: {:?}", t.values);
                }
            }
        }
    }

    #[test]
    fn fallback_is_loose() {
        let c = fallback(2.3, 7.1);
        let t = materialize(&c, 0);
        assert_eq!(t.values, vec![0.0, 10.0]);
    }
}
