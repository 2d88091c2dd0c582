//! Voxels kept in the type their file stores them in: a 512³ volume of `u16` takes 256 MB, not
//! the 1 GB of `f64`. Reading a voxel converts it to `f64` on the way out.

use rayon::prelude::*;

use crate::spec::VoxelType;

/// The voxels of a volume, one vector per stored type, x fastest, then y, then z. Float voxels
/// that were not finite in the file are NaN (missing); integer voxels are never missing.
#[derive(Clone, Debug, PartialEq)]
pub enum Voxels {
    /// Unsigned 8-bit integers.
    U8(Vec<u8>),
    /// Signed 8-bit integers.
    I8(Vec<i8>),
    /// Unsigned 16-bit integers.
    U16(Vec<u16>),
    /// Signed 16-bit integers.
    I16(Vec<i16>),
    /// Unsigned 32-bit integers.
    U32(Vec<u32>),
    /// Signed 32-bit integers.
    I32(Vec<i32>),
    /// 32-bit floats.
    F32(Vec<f32>),
    /// 64-bit floats (also 64-bit integers, converted: exact up to 2⁵³).
    F64(Vec<f64>),
}

/// Runs `$body` with `$v` bound to the typed vector, whatever its type: one monomorphic copy of
/// the body per type, so a loop over the voxels neither branches on the type nor converts twice.
macro_rules! each_type {
    ($voxels:expr, $v:ident => $body:expr) => {
        match $voxels {
            Voxels::U8($v) => $body,
            Voxels::I8($v) => $body,
            Voxels::U16($v) => $body,
            Voxels::I16($v) => $body,
            Voxels::U32($v) => $body,
            Voxels::I32($v) => $body,
            Voxels::F32($v) => $body,
            Voxels::F64($v) => $body,
        }
    };
}

/// A type voxels are stored in: plain old data read straight from the file's bytes.
pub trait Sample: bytemuck::Pod + PartialOrd {
    /// Whether the type is a float (non-finite values are missing).
    const FLOAT: bool;
    /// The value with its bytes in the other order.
    fn swap_bytes(self) -> Self;
    /// The value as a number.
    fn to_f64(self) -> f64;
    /// NaN for a non-finite float; integers as they are.
    fn finite_or_nan(self) -> Self;
}

macro_rules! integer_sample {
    ($($t:ty),*) => {$(
        impl Sample for $t {
            const FLOAT: bool = false;
            fn swap_bytes(self) -> Self {
                <$t>::swap_bytes(self)
            }
            fn to_f64(self) -> f64 {
                self as f64
            }
            fn finite_or_nan(self) -> Self {
                self
            }
        }
    )*};
}
integer_sample!(u8, i8, u16, i16, u32, i32);

macro_rules! float_sample {
    ($($t:ty),*) => {$(
        impl Sample for $t {
            const FLOAT: bool = true;
            fn swap_bytes(self) -> Self {
                <$t>::from_bits(self.to_bits().swap_bytes())
            }
            fn to_f64(self) -> f64 {
                self as f64
            }
            fn finite_or_nan(self) -> Self {
                if self.is_finite() { self } else { <$t>::NAN }
            }
        }
    )*};
}
float_sample!(f32, f64);

impl Voxels {
    /// The stored type.
    pub fn voxel_type(&self) -> VoxelType {
        match self {
            Voxels::U8(_) => VoxelType::U8,
            Voxels::I8(_) => VoxelType::I8,
            Voxels::U16(_) => VoxelType::U16,
            Voxels::I16(_) => VoxelType::I16,
            Voxels::U32(_) => VoxelType::U32,
            Voxels::I32(_) => VoxelType::I32,
            Voxels::F32(_) => VoxelType::F32,
            Voxels::F64(_) => VoxelType::F64,
        }
    }

    /// The number of voxels.
    pub fn len(&self) -> usize {
        each_type!(self, v => v.len())
    }

    /// Whether there are no voxels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The stored value of voxel `index` as a number (NaN outside or missing).
    pub fn get(&self, index: usize) -> f64 {
        each_type!(self, v => v.get(index).map_or(f64::NAN, |x| x.to_f64()))
    }

    /// The stored values of voxels `start..start + out.len()` as numbers into `out` (NaN
    /// where missing or outside): one conversion loop per type, no branch on it per voxel.
    pub fn read_run(&self, start: usize, out: &mut [f64]) {
        each_type!(self, v => {
            let run = v.get(start..).unwrap_or_default();
            let inside = run.len().min(out.len());
            let (head, tail) = out.split_at_mut(inside);
            // Two plain loops (a chained iterator kept the conversion from vectorizing).
            head.iter_mut().zip(&run[..inside]).for_each(|(slot, x)| *slot = x.to_f64());
            tail.fill(f64::NAN);
        })
    }

    /// The stored values of several runs of voxels as numbers into `out`, run after run: run
    /// `r` is voxels `starts[r]..starts[r] + width` with `width = out.len() / starts.len()`
    /// (NaN where missing or outside). One dispatch on the type for all of them, for reads of
    /// many short runs (a small box of voxels).
    pub fn read_runs(&self, starts: &[usize], out: &mut [f64]) {
        let width = out.len() / starts.len().max(1);
        if width == 0 {
            return;
        }
        each_type!(self, v => {
            for (&start, row) in starts.iter().zip(out.chunks_exact_mut(width)) {
                match v.get(start..start + width) {
                    Some(run) => row.iter_mut().zip(run).for_each(|(slot, x)| *slot = x.to_f64()),
                    None => row.iter_mut().enumerate().for_each(|(i, slot)| {
                        *slot = v.get(start + i).map_or(f64::NAN, |x| x.to_f64())
                    }),
                }
            }
        })
    }

    /// The bytes the voxels take in memory.
    pub fn memory_bytes(&self) -> usize {
        self.len() * type_size(self.voxel_type())
    }

    /// The smallest and largest stored values that are not missing, and how many are missing;
    /// `None` for the range when every voxel is missing.
    pub fn stored_range(&self) -> (Option<(f64, f64)>, usize) {
        each_type!(self, v => range_of(v))
    }
}

/// Bytes per voxel of a type.
pub fn type_size(ty: VoxelType) -> usize {
    match ty {
        VoxelType::U8 | VoxelType::I8 => 1,
        VoxelType::U16 | VoxelType::I16 => 2,
        VoxelType::U32 | VoxelType::I32 | VoxelType::F32 => 4,
        VoxelType::F64 => 8,
    }
}

/// The name of a type as specs and summaries write it (`u16`).
pub fn type_name(ty: VoxelType) -> &'static str {
    match ty {
        VoxelType::U8 => "u8",
        VoxelType::I8 => "i8",
        VoxelType::U16 => "u16",
        VoxelType::I16 => "i16",
        VoxelType::U32 => "u32",
        VoxelType::I32 => "i32",
        VoxelType::F32 => "f32",
        VoxelType::F64 => "f64",
    }
}

/// The range and missing count of `values`, in parallel over runs: as numbers, a float NaN is
/// counted and never a bound (it fails every comparison).
fn range_of<T: Sample + Sync>(values: &[T]) -> (Option<(f64, f64)>, usize) {
    let empty = (f64::INFINITY, f64::NEG_INFINITY, 0usize);
    let (lo, hi, missing) =
        values.par_chunks(1 << 18).map(run_range).reduce(|| empty, |a, b| (a.0.min(b.0), a.1.max(b.1), a.2 + b.2));
    ((lo <= hi).then_some((lo, hi)), missing)
}

/// Lanes of [`run_range`]: independent bounds the compiler keeps in vector registers.
const RANGE_LANES: usize = 8;

/// The smallest and largest value of a run and how many of its values are NaN, in
/// [`RANGE_LANES`] lanes of compare-and-select (which vectorize, unlike `f64::min`'s NaN rule;
/// a NaN fails both comparisons, so it is never a bound).
fn run_range<T: Sample>(run: &[T]) -> (f64, f64, usize) {
    let mut lo = [f64::INFINITY; RANGE_LANES];
    let mut hi = [f64::NEG_INFINITY; RANGE_LANES];
    let mut missing = [0usize; RANGE_LANES];
    let mut take = |lane: usize, x: T| {
        let v = x.to_f64();
        lo[lane] = if v < lo[lane] { v } else { lo[lane] };
        hi[lane] = if v > hi[lane] { v } else { hi[lane] };
        missing[lane] += usize::from(v.is_nan());
    };
    let lanes = run.chunks_exact(RANGE_LANES);
    let rest = lanes.remainder();
    for group in lanes {
        for (lane, &x) in group.iter().enumerate() {
            take(lane, x);
        }
    }
    for (lane, &x) in rest.iter().enumerate() {
        take(lane, x);
    }
    (
        lo.into_iter().fold(f64::INFINITY, f64::min),
        hi.into_iter().fold(f64::NEG_INFINITY, f64::max),
        missing.iter().sum(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_skip_missing_floats_and_types_keep_their_size() {
        let v = Voxels::F32(vec![f32::NAN, 2.0, -1.5, f32::NAN]);
        assert_eq!(v.stored_range(), (Some((-1.5, 2.0)), 2));
        assert_eq!(v.memory_bytes(), 16);
        assert!(v.get(0).is_nan());
        assert!(v.get(9).is_nan(), "outside");
        let v = Voxels::U16(vec![7, 65535, 3]);
        assert_eq!(v.stored_range(), (Some((3.0, 65535.0)), 0));
        assert_eq!((v.memory_bytes(), v.voxel_type(), v.get(1)), (6, VoxelType::U16, 65535.0));
        assert_eq!(Voxels::F64(vec![f64::NAN]).stored_range(), (None, 1));
        // Longer than the lanes, bounds and NaNs in every lane and in the remainder.
        let long: Vec<f32> = (0..100).map(|i| if i % 7 == 3 { f32::NAN } else { (i as f32 - 40.0) * 0.5 }).collect();
        assert_eq!(Voxels::F32(long).stored_range(), (Some((-20.0, 29.5)), 14));
        assert_eq!(1.5f32.swap_bytes().swap_bytes(), 1.5);
        assert_eq!(0x0102u16.swap_bytes(), 0x0201);
        assert!(f64::INFINITY.finite_or_nan().is_nan());
    }

    #[test]
    fn runs_read_as_single_voxels_do() {
        let v = Voxels::I16((0..20).map(|i| i * 3 - 30).collect());
        // Three runs of four: inside, at the end (half outside), wholly outside.
        let mut out = [0.0; 12];
        v.read_runs(&[2, 18, 40], &mut out);
        for (r, &start) in [2usize, 18, 40].iter().enumerate() {
            for i in 0..4 {
                let (got, want) = (out[r * 4 + i], v.get(start + i));
                assert!(got == want || (got.is_nan() && want.is_nan()), "run {r} voxel {i}: {got} vs {want}");
            }
        }
        assert_eq!(out[..4], [-24.0, -21.0, -18.0, -15.0]);
        assert!(out[6].is_nan() && out[8..].iter().all(|x| x.is_nan()));
        // No runs, or runs of no voxels: nothing written.
        v.read_runs(&[], &mut out);
        v.read_runs(&[1, 2, 3], &mut out[..2]);
        assert_eq!(out[0], -24.0);
    }
}
