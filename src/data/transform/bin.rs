//! Nice bins as Vega-Lite makes them: a step of 1, 2 or 5 times a power of ten, chosen so the
//! extent is covered by at most `maxbins` bins, with the start and stop snapped to the step.

/// Bins covering an extent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bins {
    /// The first bin's start.
    pub start: f64,
    /// The last bin's end.
    pub stop: f64,
    /// The bin width.
    pub step: f64,
}

impl Bins {
    /// The nice bins of `[lo, hi]`: at most `maxbins` of them, or of width `step` when given.
    pub fn nice(lo: f64, hi: f64, maxbins: u32, step: Option<f64>) -> Bins {
        let maxbins = f64::from(maxbins.max(1));
        let span = if hi > lo {
            hi - lo
        } else if lo != 0.0 {
            lo.abs()
        } else {
            1.0
        };
        let step = match step {
            Some(s) if s > 0.0 && s.is_finite() => s,
            _ => {
                let level = maxbins.log10().ceil();
                let mut step = 10f64.powf((span.log10()).round() - level);
                // Too many bins: a larger power of ten.
                while (span / step).ceil() > maxbins {
                    step *= 10.0;
                }
                // Finer steps of a half or a fifth when they still fit.
                for divide in [5.0, 2.0] {
                    let finer = step / divide;
                    if span / finer <= maxbins {
                        step = finer;
                    }
                }
                step
            }
        };
        let precision = if step.log10() >= 0.0 { 0.0 } else { (-step.log10()).floor() + 1.0 };
        let eps = 10f64.powf(-precision - 1.0);
        let snapped = (lo / step + eps).floor() * step;
        let start = if lo < snapped { snapped - step } else { snapped };
        let mut stop = (hi / step).ceil() * step;
        if stop <= start {
            stop = start + step;
        }
        Bins { start, stop, step }
    }

    /// The start of the bin holding `v` (the maximum falls in the last bin), `None` outside.
    pub fn bin_of(&self, v: f64) -> Option<f64> {
        if !(self.start..=self.stop).contains(&v) {
            return None;
        }
        let clamped = v.min(self.stop - self.step);
        Some(self.start + self.step * ((clamped - self.start) / self.step + 1e-14).floor())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vega_lite_nice_bins() {
        // Values from vega-statistics' bin() with maxbins 10 (Vega-Lite's default).
        assert_eq!(Bins::nice(0.0, 1.0, 10, None), Bins { start: 0.0, stop: 1.0, step: 0.1 });
        assert_eq!(Bins::nice(46.0, 230.0, 10, None), Bins { start: 40.0, stop: 240.0, step: 20.0 });
        assert_eq!(Bins::nice(8.0, 24.8, 10, None), Bins { start: 8.0, stop: 26.0, step: 2.0 });
        assert_eq!(Bins::nice(1613.0, 5140.0, 10, None), Bins { start: 1500.0, stop: 5500.0, step: 500.0 });
        assert_eq!(Bins::nice(0.0, 100.0, 20, None), Bins { start: 0.0, stop: 100.0, step: 5.0 });
        assert_eq!(Bins::nice(3.0, 3.0, 10, None), Bins { start: 3.0, stop: 3.5, step: 0.5 });
        assert_eq!(Bins::nice(0.0, 95.0, 10, Some(25.0)), Bins { start: 0.0, stop: 100.0, step: 25.0 });
    }

    #[test]
    fn values_fall_in_half_open_bins_with_the_maximum_in_the_last() {
        let b = Bins::nice(0.0, 1.0, 10, None);
        let near = |v: f64, want: f64| (b.bin_of(v).unwrap_or(f64::NAN) - want).abs() < 1e-12;
        assert!(near(0.0, 0.0) && near(0.25, 0.2) && near(0.3, 0.3) && near(0.999, 0.9));
        assert!(near(1.0, 0.9), "the maximum belongs to the last bin");
        assert_eq!(b.bin_of(1.5), None);
        assert_eq!(b.bin_of(f64::NAN), None);
    }
}
