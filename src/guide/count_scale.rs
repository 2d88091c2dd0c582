//! How a density view shades its counts — linearly, by their logarithm, or histogram-equalized —
//! and where any count falls along the colour bar under that shading, so the bar's ticks name
//! real counts whatever the shading (a histogram-equalized bar is not evenly spaced in counts).

use super::Theme;
use super::color::ContinuousMap;
use super::format::format_log_tick;
use super::legend::value_scale;
use crate::scene::Color;

/// How counts map to the colour ramp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// In proportion to the count, from 0 to the largest.
    Linear,
    /// By the logarithm of the count, from 1 to the largest.
    Log,
    /// By the share of non-empty bins holding at most that count, so each part of the ramp
    /// colours about as many bins (histogram equalization).
    EqHist,
}

/// The shading of one grid's counts.
#[derive(Clone, Debug, PartialEq)]
pub struct CountScale {
    shading: Shading,
    max: u64,
    /// For [`Shading::EqHist`]: each distinct non-zero count, ascending, with the ramp position
    /// of the bins holding it.
    steps: Vec<(u64, f64)>,
}

impl CountScale {
    /// The shading of `counts` (zeros are empty bins and take no part).
    pub fn new(counts: &[u64], shading: Shading) -> CountScale {
        let max = counts.iter().copied().max().unwrap_or(0);
        let steps = if shading == Shading::EqHist { equalized(counts) } else { Vec::new() };
        CountScale { shading, max, steps }
    }

    /// The shading.
    pub fn shading(&self) -> Shading {
        self.shading
    }

    /// The largest count.
    pub fn max(&self) -> u64 {
        self.max
    }

    /// Where count `c` falls along the ramp: 0 at the fewest the shading shows (0 for linear,
    /// 1 otherwise), 1 at the largest; between the counts a histogram-equalized grid holds, the
    /// position is interpolated linearly, so the bar's ticks can be placed at any count.
    pub fn position(&self, c: f64) -> f64 {
        let max = self.max as f64;
        let t = match self.shading {
            Shading::Linear => c / max,
            Shading::Log if self.max <= 1 => 1.0,
            Shading::Log => c.max(1.0).ln() / max.ln(),
            Shading::EqHist => {
                let k = self.steps.partition_point(|&(v, _)| (v as f64) < c);
                match (k.checked_sub(1).map(|i| self.steps[i]), self.steps.get(k)) {
                    (_, Some(&(v, t))) if v as f64 == c => t,
                    (Some((a, ta)), Some(&(b, tb))) => ta + (tb - ta) * (c - a as f64) / (b - a) as f64,
                    (None, Some(&(_, t))) => t,
                    (_, None) => 1.0,
                }
            }
        };
        if t.is_finite() { t.clamp(0.0, 1.0) } else { 1.0 }
    }

    /// The counts to label along a bar `length` pixels tall, with their positions (0 at the
    /// bottom, 1 at the top): nice counts (1, 2, 5, 10, ... on the log and equalized bars, whose
    /// labels would crowd at one end otherwise; linear ticks on a linear bar), no two labels
    /// closer than a line of text.
    pub fn ticks(&self, length: f64, theme: &Theme) -> Vec<(f64, String)> {
        if self.max == 0 {
            return Vec::new();
        }
        if self.shading == Shading::Linear {
            let Some(scale) = value_scale((0.0, self.max as f64), length, theme) else { return Vec::new() };
            return scale
                .ticks()
                .into_iter()
                .filter(|t| t.value >= 0.0 && t.value <= self.max as f64)
                .map(|t| (self.position(t.value), t.label))
                .collect();
        }
        let gap = theme.font_size * 1.3 / length.max(1.0);
        let mut candidates = Vec::new();
        let mut decade = 1u64;
        loop {
            for m in [1, 2, 5] {
                let Some(v) = decade.checked_mul(m) else { break };
                if v <= self.max {
                    candidates.push((v, m == 1));
                }
            }
            match decade.checked_mul(10) {
                Some(d) if d <= self.max => decade = d,
                _ => break,
            }
        }
        // Powers of ten first, then the 2s and 5s where they fit between.
        let mut chosen: Vec<(f64, u64)> = Vec::new();
        for pass in [true, false] {
            for &(v, power) in candidates.iter().filter(|c| c.1 == pass) {
                let _ = power;
                let t = self.position(v as f64);
                if chosen.iter().all(|&(u, _)| (u - t).abs() >= gap) {
                    chosen.push((t, v));
                }
            }
        }
        chosen.sort_by(|a, b| a.0.total_cmp(&b.0));
        chosen.into_iter().map(|(t, v)| (t, format_log_tick(v as f64))).collect()
    }
}

/// Each distinct non-zero count with its ramp position under histogram equalization: the share
/// of non-empty bins holding fewer, rescaled so the smallest count sits at 0 and the largest at 1.
fn equalized(counts: &[u64]) -> Vec<(u64, f64)> {
    let mut nonzero: Vec<u64> = counts.iter().copied().filter(|&c| c > 0).collect();
    nonzero.sort_unstable();
    let n = nonzero.len();
    let mut steps: Vec<(u64, f64)> = Vec::new();
    let mut start = 0;
    while start < n {
        let v = nonzero[start];
        let end = start + nonzero[start..].partition_point(|&c| c == v);
        steps.push((v, start as f64));
        start = end;
    }
    // The first count's bins come before every other, so the shares start at 0; the last
    // distinct count's share is rescaled to 1.
    let last = steps.last().map_or(1.0, |s| s.1).max(1.0);
    for s in &mut steps {
        s.1 /= last;
    }
    if let [only] = steps.as_mut_slice() {
        only.1 = 1.0;
    }
    steps
}

/// How a density raster colours a bin: by the ramp `map`, or, when bins take their colour from
/// elsewhere (the mix of their categories), by opacity alone, drawn in `fixed` on the legend;
/// opacity runs from `min_alpha` (the fewest rows, so a single row stays visible) to 1.
#[derive(Clone, Debug)]
pub struct CountColours {
    /// The colour map.
    pub map: ContinuousMap,
    /// The one colour of every bin on the legend, when the count shows as opacity only.
    pub fixed: Option<Color>,
    /// Opacity of the bins at ramp position 0.
    pub min_alpha: f64,
}

impl CountColours {
    /// The colour of a bin at ramp position `t` (0 to 1).
    pub fn at(&self, t: f64) -> Color {
        self.fixed.unwrap_or_else(|| self.map.at(t)).with_opacity(self.alpha(t))
    }

    /// The opacity of a bin at ramp position `t`.
    pub fn alpha(&self, t: f64) -> f64 {
        self.min_alpha + (1.0 - self.min_alpha) * t.clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_and_log_positions_are_the_published_formulas() {
        let counts = [0, 1, 10, 100, 1000];
        let linear = CountScale::new(&counts, Shading::Linear);
        assert_eq!([0.0, 500.0, 1000.0].map(|c| linear.position(c)), [0.0, 0.5, 1.0]);
        let log = CountScale::new(&counts, Shading::Log);
        for (c, t) in [(1.0, 0.0), (10.0, 1.0 / 3.0), (100.0, 2.0 / 3.0), (1000.0, 1.0)] {
            assert!((log.position(c) - t).abs() < 1e-12, "{c}");
        }
    }

    #[test]
    fn equalization_spreads_bins_evenly_over_the_ramp() {
        // 90 bins hold 1 row, 9 hold 2, one holds 1000: linear shading would put 99 bins at the
        // bottom of the ramp; equalized, the 1s sit at 0, the 2s at 90/99, the 1000 at 1.
        let mut counts = vec![1u64; 90];
        counts.extend([2; 9]);
        counts.push(1000);
        counts.extend([0; 50]);
        let eq = CountScale::new(&counts, Shading::EqHist);
        assert_eq!(eq.position(1.0), 0.0);
        assert!((eq.position(2.0) - 90.0 / 99.0).abs() < 1e-12);
        assert_eq!(eq.position(1000.0), 1.0);
        // Between held counts the position is interpolated, monotone.
        let mid = eq.position(501.0);
        assert!(mid > eq.position(2.0) && mid < 1.0);
        assert_eq!(CountScale::new(&[0, 4, 4], Shading::EqHist).position(4.0), 1.0);
    }

    #[test]
    fn ticks_name_counts_at_their_shaded_positions_and_do_not_crowd() {
        let theme = Theme::default();
        let counts: Vec<u64> = (0..5000u64).map(|i| 1 + i * i / 1000).collect();
        for shading in [Shading::Linear, Shading::Log, Shading::EqHist] {
            let scale = CountScale::new(&counts, shading);
            let ticks = scale.ticks(300.0, &theme);
            assert!(ticks.len() >= 3, "{shading:?}: {ticks:?}");
            for w in ticks.windows(2) {
                assert!((w[1].0 - w[0].0) * 300.0 >= theme.font_size * 1.3 - 1e-9, "{shading:?}: {ticks:?}");
            }
            if shading != Shading::Linear {
                assert_eq!(ticks[0], (0.0, "1".to_string()), "{shading:?}");
            }
        }
    }
}
