//! Volumes: 3-D regular grids of numbers (CT, MRI and simulation fields), read as users have
//! them: 3-D `.npy` arrays ([`npy`]), NIfTI-1 files ([`nifti`]), raw voxel files ([`raw`]), and long
//! tables of `x, y, z, value` on a regular lattice ([`table`]). Which reader a data source takes
//! is decided in [`source`]; [`summary`] describes a volume for `dataink data`.
//!
//! Voxels keep the type of their file ([`Voxels`]); a NIfTI file's `scl_slope`/`scl_inter` are
//! applied as each voxel is read, not to the whole volume. Voxel `(i, j, k)` (along x, y, z) is
//! number `(k * ny + j) * nx + i`, at `affine · (i, j, k, 1)` in world coordinates.

pub mod nifti;
pub mod npy;
pub mod raw;
pub mod read;
pub mod source;
pub mod summary;
pub mod table;
pub mod voxels;

pub use voxels::{Sample, Voxels, type_name, type_size};

use crate::spec::VoxelType;

/// Largest volume accepted, in voxels (2²⁸ = 268,435,456, e.g. 512 × 512 × 1024), checked against
/// the header before anything is allocated.
pub const MAX_VOXELS: usize = 1 << 28;

/// Largest voxel data accepted, in bytes (1 GiB), checked against the header before anything is
/// allocated.
pub const MAX_BYTES: u64 = 1 << 30;

/// A linear map of stored values to real ones: `value = stored × slope + inter` (NIfTI's
/// `scl_slope` and `scl_inter`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    /// The factor (never 0).
    pub slope: f64,
    /// The offset.
    pub inter: f64,
}

/// A unit of length of the world coordinates, from a NIfTI header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpaceUnit {
    /// Metres.
    Metre,
    /// Millimetres.
    Millimetre,
    /// Micrometres.
    Micrometre,
}

impl SpaceUnit {
    /// Its symbol: `m`, `mm`, `µm`.
    pub fn symbol(self) -> &'static str {
        match self {
            SpaceUnit::Metre => "m",
            SpaceUnit::Millimetre => "mm",
            SpaceUnit::Micrometre => "µm",
        }
    }
}

/// A 3-D regular grid of numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    dims: [usize; 3],
    spacing: [f64; 3],
    affine: [[f64; 4]; 3],
    voxels: Voxels,
    scale: Option<Scale>,
    unit: Option<SpaceUnit>,
    /// The stored voxels' range, found on first use.
    stored_range: StoredRange,
}

/// A volume's stored range and missing count, computed once (the voxels never change after
/// the volume is made). Two volumes compare by their voxels, not by whether this was filled.
#[derive(Clone, Debug, Default)]
struct StoredRange(std::sync::OnceLock<(Option<(f64, f64)>, usize)>);

impl PartialEq for StoredRange {
    fn eq(&self, _: &StoredRange) -> bool {
        true
    }
}

/// `Ok` when every spacing is a positive finite number, else a message saying the fix.
pub fn check_spacing(spacing: [f64; 3]) -> Result<(), String> {
    match spacing.iter().position(|s| !(s.is_finite() && *s > 0.0)) {
        Some(axis) => Err(format!(
            "voxel spacing {:?} along {} is not a positive number; give the distance between voxels, e.g. [1.0, 1.0, 2.5]",
            spacing[axis],
            ["x", "y", "z"][axis]
        )),
        None => Ok(()),
    }
}

/// The number of voxels of `dims` stored as `ty`, or why such a volume is refused (an axis of no
/// voxels, more than [`MAX_VOXELS`], more than [`MAX_BYTES`]). Checked before allocating.
pub fn check_size(dims: [u64; 3], ty: VoxelType) -> Result<usize, String> {
    let shown = format!("{} × {} × {}", dims[0], dims[1], dims[2]);
    if let Some(axis) = dims.iter().position(|&d| d == 0) {
        return Err(format!("the volume is {shown} voxels: no voxels along {}", ["x", "y", "z"][axis]));
    }
    let count = dims
        .iter()
        .try_fold(1u64, |n, &d| n.checked_mul(d))
        .and_then(|n| usize::try_from(n).ok())
        .filter(|&n| n <= MAX_VOXELS)
        .ok_or_else(|| {
            format!(
                "the volume is {shown} voxels, more than the limit of {MAX_VOXELS} (2^28, e.g. 512 × 512 × 1024); crop or downsample it"
            )
        })?;
    let bytes = count as u64 * type_size(ty) as u64;
    if bytes > MAX_BYTES {
        return Err(format!(
            "the volume's {shown} {} voxels take {bytes} bytes, more than the limit of {MAX_BYTES} (1 GiB); store it in a smaller type or crop it",
            type_name(ty)
        ));
    }
    Ok(count)
}

impl Volume {
    /// A volume of `voxels` (x fastest) with `dims` voxels along x, y and z and voxel `spacing`,
    /// placed with voxel `(0, 0, 0)` at the origin and its axes along x, y and z.
    pub fn new(dims: [usize; 3], voxels: Voxels, spacing: [f64; 3]) -> Result<Volume, String> {
        check_spacing(spacing)?;
        let count = dims.iter().try_fold(1usize, |n, &d| n.checked_mul(d));
        if count != Some(voxels.len()) {
            return Err(format!(
                "{} voxels do not fill a volume of {} × {} × {}",
                voxels.len(),
                dims[0],
                dims[1],
                dims[2]
            ));
        }
        let [sx, sy, sz] = spacing;
        let affine = [[sx, 0.0, 0.0, 0.0], [0.0, sy, 0.0, 0.0], [0.0, 0.0, sz, 0.0]];
        Ok(Volume { dims, spacing, affine, voxels, scale: None, unit: None, stored_range: StoredRange::default() })
    }

    /// The same volume placed in the world by `affine` (rows x, y, z of a 4 × 4 matrix whose last
    /// row is `0 0 0 1`), or why it cannot be (a non-finite entry).
    pub fn with_affine(mut self, affine: [[f64; 4]; 3]) -> Result<Volume, String> {
        if affine.iter().flatten().any(|a| !a.is_finite()) {
            return Err(format!("the voxel-to-world matrix {affine:?} has a value that is not a finite number"));
        }
        self.affine = affine;
        Ok(self)
    }

    /// The same volume moved so that voxel `(0, 0, 0)` lies at `origin`, or why it cannot be
    /// (a coordinate that is not a finite number).
    pub fn with_origin(mut self, origin: [f64; 3]) -> Result<Volume, String> {
        if let Some(bad) = origin.iter().find(|c| !c.is_finite()) {
            return Err(format!(
                "origin {origin:?} has {bad}, which is not a finite number; give the position of the first voxel"
            ));
        }
        for (row, o) in self.affine.iter_mut().zip(origin) {
            row[3] = o;
        }
        Ok(self)
    }

    /// The same volume with its stored values mapped by `scale` on read (`None`: as stored).
    pub fn with_scale(mut self, scale: Option<Scale>) -> Volume {
        self.scale = scale.filter(|s| s.slope != 0.0 && s.slope.is_finite() && s.inter.is_finite());
        self
    }

    /// The same volume with its world coordinates in `unit`.
    pub fn with_unit(mut self, unit: Option<SpaceUnit>) -> Volume {
        self.unit = unit;
        self
    }

    /// Voxels along x, y and z.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The distance between neighbouring voxels along x, y and z (all positive and finite).
    pub fn spacing(&self) -> [f64; 3] {
        self.spacing
    }

    /// The voxel-to-world matrix: rows x, y and z of `world = affine · (i, j, k, 1)`.
    pub fn affine(&self) -> [[f64; 4]; 3] {
        self.affine
    }

    /// The stored voxels.
    pub fn voxels(&self) -> &Voxels {
        &self.voxels
    }

    /// The map from stored to real values, if the file gives one.
    pub fn scale(&self) -> Option<Scale> {
        self.scale
    }

    /// The unit of the world coordinates and spacing, if the file names one.
    pub fn unit(&self) -> Option<SpaceUnit> {
        self.unit
    }

    /// The number of voxels.
    pub fn len(&self) -> usize {
        self.voxels.len()
    }

    /// Whether the volume has no voxels (never, for a volume that was read).
    pub fn is_empty(&self) -> bool {
        self.voxels.is_empty()
    }

    /// The number of voxel `(i, j, k)`, if it is inside.
    pub fn index(&self, i: usize, j: usize, k: usize) -> Option<usize> {
        let [nx, ny, nz] = self.dims;
        (i < nx && j < ny && k < nz).then(|| (k * ny + j) * nx + i)
    }

    /// The value of voxel number `index` (scaled; NaN when missing or outside).
    pub fn get(&self, index: usize) -> f64 {
        let stored = self.voxels.get(index);
        match self.scale {
            Some(Scale { slope, inter }) => stored * slope + inter,
            None => stored,
        }
    }

    /// The values of voxels `start..start + out.len()` into `out` (scaled; NaN when missing or
    /// outside): [`Volume::get`] for a run, without its per-voxel dispatch on the stored type.
    pub fn read_run(&self, start: usize, out: &mut [f64]) {
        self.voxels.read_run(start, out);
        if let Some(Scale { slope, inter }) = self.scale {
            out.iter_mut().for_each(|v| *v = *v * slope + inter);
        }
    }

    /// The values of runs of voxels into `out`, run after run, each `out.len() / starts.len()`
    /// long (scaled; NaN when missing or outside): [`Volume::read_run`] for many short runs,
    /// with one dispatch on the stored type.
    pub fn read_runs(&self, starts: &[usize], out: &mut [f64]) {
        self.voxels.read_runs(starts, out);
        if let Some(Scale { slope, inter }) = self.scale {
            out.iter_mut().for_each(|v| *v = *v * slope + inter);
        }
    }

    /// The value of voxel `(i, j, k)` (scaled; NaN when missing or outside).
    pub fn value(&self, i: usize, j: usize, k: usize) -> f64 {
        self.index(i, j, k).map_or(f64::NAN, |n| self.get(n))
    }

    /// Every value in voxel order (scaled; NaN where missing).
    pub fn values(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.len()).map(|n| self.get(n))
    }

    /// The world position of voxel `(i, j, k)` (fractional indices allowed).
    pub fn world(&self, i: f64, j: f64, k: f64) -> [f64; 3] {
        self.affine.map(|row| row[0] * i + row[1] * j + row[2] * k + row[3])
    }

    /// The smallest and largest values that are not missing (scaled), and how many are missing;
    /// `None` for the range when every voxel is missing. One pass over the stored voxels, the
    /// first time.
    pub fn range(&self) -> (Option<(f64, f64)>, usize) {
        let (stored, missing) = *self.stored_range.0.get_or_init(|| self.voxels.stored_range());
        let range = stored.map(|(lo, hi)| match self.scale {
            Some(Scale { slope, inter }) => {
                let (a, b) = (lo * slope + inter, hi * slope + inter);
                (a.min(b), a.max(b))
            }
            None => (lo, hi),
        });
        (range, missing)
    }

    /// The extent of the volume along x, y and z from voxel 0 (`(n - 1) * spacing`).
    pub fn extent(&self) -> [f64; 3] {
        [0, 1, 2].map(|a| self.dims[a].saturating_sub(1) as f64 * self.spacing[a])
    }

    /// The direction each voxel axis mostly runs in the world, as a NIfTI/RAS+ code: `R`/`L`
    /// (+x/−x), `A`/`P` (+y/−y), `S`/`I` (+z/−z) for i, j and k, e.g. `"RAS"` or `"LPS"`.
    pub fn orientation(&self) -> String {
        (0..3)
            .map(|axis| {
                let column = [self.affine[0][axis], self.affine[1][axis], self.affine[2][axis]];
                let world = (0..3).max_by(|&a, &b| column[a].abs().total_cmp(&column[b].abs())).unwrap_or(axis);
                let plus = column[world] >= 0.0;
                match (world, plus) {
                    (0, true) => 'R',
                    (0, false) => 'L',
                    (1, true) => 'A',
                    (1, false) => 'P',
                    (_, true) => 'S',
                    (_, false) => 'I',
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_scaled_on_read_and_indexed_x_fastest() {
        let v = Volume::new([2, 2, 2], Voxels::I16((0..8).collect()), [1.0, 2.0, 3.0]).expect("volume");
        assert_eq!(v.value(1, 0, 0), 1.0);
        assert_eq!(v.value(0, 1, 0), 2.0);
        assert_eq!(v.value(0, 0, 1), 4.0);
        assert!(v.value(2, 0, 0).is_nan());
        assert_eq!(v.extent(), [1.0, 2.0, 3.0]);
        assert_eq!(v.world(1.0, 1.0, 1.0), [1.0, 2.0, 3.0]);
        assert_eq!(v.orientation(), "RAS");
        let scaled = v.with_scale(Some(Scale { slope: -0.5, inter: 10.0 }));
        assert_eq!(scaled.value(1, 1, 1), 7.0 * -0.5 + 10.0);
        assert_eq!(scaled.range(), (Some((6.5, 10.0)), 0));
        assert_eq!(scaled.values().take(2).collect::<Vec<_>>(), vec![10.0, 9.5]);
        assert_eq!(scaled.voxels().memory_bytes(), 16, "stored as i16, not converted");
        // A run reads what `get` reads, NaN past the end.
        let mut run = [0.0; 4];
        scaled.read_run(6, &mut run);
        assert_eq!(run[..2], [scaled.get(6), scaled.get(7)]);
        assert!(run[2].is_nan() && run[3].is_nan());
        scaled.read_run(100, &mut run);
        assert!(run.iter().all(|v| v.is_nan()));
        let flipped =
            scaled.with_affine([[-1.0, 0.0, 0.0, 5.0], [0.0, 0.0, 2.0, 0.0], [0.0, -3.0, 0.0, 0.0]]).expect("finite");
        assert_eq!(flipped.orientation(), "LIA");
        assert!(Volume::new([2, 2, 2], Voxels::U8(vec![0; 7]), [1.0; 3]).is_err());
    }

    #[test]
    fn sizes_are_checked_before_allocating() {
        assert_eq!(check_size([4, 3, 2], VoxelType::U16), Ok(24));
        let err = check_size([4, 0, 2], VoxelType::U8).expect_err("empty");
        assert_eq!(err, "the volume is 4 × 0 × 2 voxels: no voxels along y");
        let err = check_size([1 << 40, 1 << 40, 1 << 40], VoxelType::U8).expect_err("overflow");
        assert!(err.contains("more than the limit of 268435456"), "{err}");
        let err = check_size([512, 512, 1024], VoxelType::F64).expect_err("2 GiB");
        assert!(err.contains("take 2147483648 bytes, more than the limit of 1073741824"), "{err}");
        assert_eq!(check_size([512, 512, 1024], VoxelType::F32), Ok(1 << 28));
        assert!(check_spacing([1.0, f64::NAN, 1.0]).is_err_and(|e| e.contains("along y")));
    }

    #[test]
    fn an_origin_moves_voxel_zero_and_must_be_finite() {
        let v = Volume::new([2, 2, 2], Voxels::U8(vec![0; 8]), [1.0, 2.0, 3.0]).expect("volume");
        let moved = v.clone().with_origin([-1.0, 5.0, 0.5]).expect("finite");
        assert_eq!(moved.world(0.0, 0.0, 0.0), [-1.0, 5.0, 0.5]);
        assert_eq!(moved.world(1.0, 1.0, 1.0), [0.0, 7.0, 3.5]);
        let err = v.with_origin([0.0, f64::INFINITY, 0.0]).expect_err("infinite");
        assert!(err.contains("not a finite number"), "{err}");
    }
}
