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

/// Fewest voxels per task.
const CHUNK: usize = 1 << 16;
/// Counters per bucket within a task, so runs of equal values (a volume's empty background) do
/// not wait on one counter after another.
const LANES: usize = 4;
/// Buckets of `f32` values: the top 16 bits of their bit patterns (sign, exponent and 7 bits of
/// the fraction), each a run of values at most 2⁻⁷ of its magnitude wide.
const BUCKETS: usize = 1 << 16;

/// Count `values` into `bins` equal bins over `(lo, hi)` (values outside fall into the end
/// bins) and count those `keep` accepts; missing (NaN) values are left out of both.
/// `keep_throughout(a, b)` says what `keep` gives every value from `a` to `b`, or `None` when it
/// does not know or the answers differ.
///
/// Most values are counted by their bucket (the top 16 bits of their `f32` bit pattern) alone:
/// a bucket whose values all fall in one bin and which `keep_throughout` decides is counted as
/// a whole. Values in the other buckets (straddling a bin edge or a change of `keep`, NaN and
/// infinities) are binned one by one. The counts are exact either way.
pub fn census(
    values: &[f32],
    (lo, hi): (f64, f64),
    bins: usize,
    keep: impl Fn(f64) -> bool + Sync,
    keep_throughout: impl Fn(f64, f64) -> Option<bool> + Sync,
) -> Census {
    let bins = bins.max(1);
    let width = if hi > lo { (hi - lo) / bins as f64 } else { 1.0 };
    // Truncation floors what is not negative; values below the range saturate to bin 0.
    let bin_of = |v: f64| (((v - lo) / width).max(0.0) as usize).min(bins - 1);
    // Per bucket: its bin and whether `keep` takes its values, when both hold for all of them.
    let whole: Vec<Option<(u32, bool)>> = (0..BUCKETS)
        .into_par_iter()
        .map(|bucket| {
            let (a, b) = bucket_bounds(bucket as u32)?;
            let bin = bin_of(a);
            (bin == bin_of(b)).then_some(())?;
            Some((bin as u32, keep_throughout(a, b)?))
        })
        .collect();
    let empty = || (Census { counts: vec![0; bins], present: 0, kept: 0 }, vec![[0u32; LANES]; BUCKETS]);
    // Few large tasks: each holds a megabyte of bucket counters.
    let task = values.len().div_ceil(4 * rayon::current_num_threads()).max(CHUNK);
    let (mut census, buckets) = values
        .par_chunks(task)
        .fold(empty, |(mut acc, mut buckets), chunk| {
            let mut take = |lane: usize, x: f32| {
                let bucket = (x.to_bits() >> 16) as usize;
                if whole[bucket].is_some() {
                    buckets[bucket][lane] += 1;
                    return;
                }
                let v = f64::from(x);
                if !v.is_nan() {
                    acc.counts[bin_of(v)] += 1;
                    acc.present += 1;
                    acc.kept += u64::from(keep(v));
                }
            };
            let groups = chunk.chunks_exact(LANES);
            let rest = groups.remainder();
            for group in groups {
                for (lane, &x) in group.iter().enumerate() {
                    take(lane, x);
                }
            }
            for &x in rest {
                take(0, x);
            }
            (acc, buckets)
        })
        .reduce(empty, |(mut a, mut buckets), (b, other)| {
            a.counts.iter_mut().zip(&b.counts).for_each(|(x, y)| *x += y);
            a.present += b.present;
            a.kept += b.kept;
            for (x, y) in buckets.iter_mut().zip(&other) {
                for lane in 0..LANES {
                    x[lane] += y[lane];
                }
            }
            (a, buckets)
        });
    for (bucket, lanes) in buckets.iter().enumerate() {
        let n: u64 = lanes.iter().map(|&c| u64::from(c)).sum();
        if let (Some((bin, kept)), true) = (whole[bucket], n > 0) {
            census.counts[bin as usize] += n;
            census.present += n;
            census.kept += if kept { n } else { 0 };
        }
    }
    census
}

/// The smallest and largest value of an `f32` bucket (see [`BUCKETS`]), or `None` for the
/// buckets of infinities and NaNs.
fn bucket_bounds(bucket: u32) -> Option<(f64, f64)> {
    let (first, last) = (bucket << 16, (bucket << 16) | 0xffff);
    let (a, b) = (f32::from_bits(first), f32::from_bits(last));
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    // Negative values grow in magnitude with their bit patterns.
    let (a, b) = (f64::from(a), f64::from(b));
    Some((a.min(b), a.max(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_equal_a_hand_count_with_ends_and_missing_values() {
        // 0, 1, ..., 199 and two NaNs, over (50, 150) in 4 bins of 25.
        let mut values: Vec<f32> = (0..200).map(|v| v as f32).collect();
        values.extend([f32::NAN, f32::NAN]);
        let c =
            census(&values, (50.0, 150.0), 4, |v| v >= 100.0, |a, b| (a >= 100.0 || b < 100.0).then_some(a >= 100.0));
        // Bin 0 takes 0..=74 (below the domain too), bin 3 takes 125..=199 (above it too).
        assert_eq!(c.counts, vec![75, 25, 25, 75]);
        assert_eq!((c.present, c.kept), (200, 100));
        assert!((c.kept_share() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn counting_by_bucket_equals_counting_value_by_value() {
        // Constant runs, zeros of both signs, subnormals, negatives, values on bin edges,
        // infinities and NaNs; a `keep` with steps, decided exactly where a bucket lies on one
        // side of them.
        let mut next = crate::enrich::volume::raycast::tests::xorshift(0x2545_f491_4f6c_dd1d);
        let special = [0.0, -0.0, 1e-40, -1e-40, 2.5, -2.5, 7.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN];
        let mut values: Vec<f32> = vec![0.0; CHUNK + 5];
        values.extend((0..2 * CHUNK).map(|i| match next() % 4 {
            0 => special[i % special.len()],
            1 => (next() % 2001) as f32 / 100.0 - 10.0,
            _ => f32::from_bits(next() as u32),
        }));
        let keep = |v: f64| (-3.0..1.5).contains(&v) || v >= 6.25;
        let throughout = |a: f64, b: f64| {
            let same = [-3.0, 1.5, 6.25].iter().all(|&edge| b < edge || a >= edge);
            same.then(|| keep(a))
        };
        let (domain, bins) = ((-10.0, 10.0), 8);
        let fast = census(&values, domain, bins, keep, throughout);
        let slow = census(&values, domain, bins, keep, |_, _| None);
        assert_eq!(fast, slow);
        // And by hand.
        let mut counts = vec![0u64; bins];
        let (mut present, mut kept) = (0, 0);
        for &x in &values {
            let v = f64::from(x);
            if v.is_nan() {
                continue;
            }
            let bin = if v < -10.0 { 0 } else { (((v + 10.0) / 2.5) as usize).min(bins - 1) };
            counts[bin] += 1;
            present += 1;
            kept += u64::from(keep(v));
        }
        assert_eq!(fast, Census { counts, present, kept });
        let whole = (0..BUCKETS as u32).filter(|&b| bucket_bounds(b).is_some()).count();
        assert_eq!(whole, BUCKETS - 2 * 128, "the buckets of infinities and NaNs are left to one by one");
    }

    #[test]
    fn large_volumes_are_counted_across_tasks() {
        let n = 3 * CHUNK + 17;
        let values: Vec<f32> = (0..n).map(|i| (i % 10) as f32).collect();
        let c = census(&values, (0.0, 10.0), 10, |v| v == 9.0, |_, _| None);
        assert_eq!(c.counts.iter().sum::<u64>(), n as u64);
        assert_eq!(c.counts[3], (0..n).filter(|i| i % 10 == 3).count() as u64);
        assert_eq!(c.kept, (0..n).filter(|i| i % 10 == 9).count() as u64);
    }
}
