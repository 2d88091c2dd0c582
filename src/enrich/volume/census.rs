//! Counts over a volume's values (as ray casting holds them) in one parallel pass: a histogram over a value range (the
//! transfer-function legend draws it) and how many voxels a predicate keeps (how much of the
//! volume a transfer function shows).

use rayon::prelude::*;

/// A histogram of the values that are not missing and how many of them a predicate kept.
#[derive(Clone, Debug, PartialEq)]
pub struct Census {
    /// Voxels per bin: equal bins over the domain asked for; the first and last bins also take
    /// the values below and above it.
    pub counts: Vec<u64>,
    /// Values that are not missing.
    pub present: u64,
    /// Values the predicate kept.
    pub kept: u64,
}

impl Census {
    /// The share of the values that are not missing which the predicate kept (0 when none is).
    pub fn kept_share(&self) -> f64 {
        if self.present == 0 { 0.0 } else { self.kept as f64 / self.present as f64 }
    }
}

/// Voxels per voxel-range task.
const CHUNK: usize = 1 << 16;

/// Count `values` into `bins` equal bins over `(lo, hi)` (values outside fall into the end
/// bins) and count those `keep` accepts; missing (NaN) values are left out of both.
pub fn census(values: &[f32], (lo, hi): (f64, f64), bins: usize, keep: impl Fn(f64) -> bool + Sync) -> Census {
    let bins = bins.max(1);
    let width = if hi > lo { (hi - lo) / bins as f64 } else { 1.0 };
    let empty = || Census { counts: vec![0; bins], present: 0, kept: 0 };
    values
        .par_chunks(CHUNK)
        .fold(empty, |mut acc, chunk| {
            for &v in chunk {
                let v = f64::from(v);
                if v.is_nan() {
                    continue;
                }
                // Truncation floors what is not negative; negative and NaN-free values below
                // the range saturate to bin 0.
                let bin = (((v - lo) / width).max(0.0) as usize).min(bins - 1);
                acc.counts[bin] += 1;
                acc.present += 1;
                acc.kept += u64::from(keep(v));
            }
            acc
        })
        .reduce(empty, |mut a, b| {
            a.counts.iter_mut().zip(&b.counts).for_each(|(x, y)| *x += y);
            a.present += b.present;
            a.kept += b.kept;
            a
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_equal_a_hand_count_with_ends_and_missing_values() {
        // 0, 1, ..., 199 and two NaNs, over (50, 150) in 4 bins of 25.
        let mut values: Vec<f32> = (0..200).map(|v| v as f32).collect();
        values.extend([f32::NAN, f32::NAN]);
        let c = census(&values, (50.0, 150.0), 4, |v| v >= 100.0);
        // Bin 0 takes 0..=74 (below the domain too), bin 3 takes 125..=199 (above it too).
        assert_eq!(c.counts, vec![75, 25, 25, 75]);
        assert_eq!((c.present, c.kept), (200, 100));
        assert!((c.kept_share() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn large_volumes_are_counted_across_tasks() {
        let n = 3 * CHUNK + 17;
        let values: Vec<f32> = (0..n).map(|i| (i % 10) as f32).collect();
        let c = census(&values, (0.0, 10.0), 10, |v| v == 9.0);
        assert_eq!(c.counts.iter().sum::<u64>(), n as u64);
        assert_eq!(c.counts[3], (0..n).filter(|i| i % 10 == 3).count() as u64);
        assert_eq!(c.kept, (0..n).filter(|i| i % 10 == 9).count() as u64);
    }
}
