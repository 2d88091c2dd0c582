//! Volumes: 3-D regular grids of numbers (CT, MRI and simulation fields), read from 3-D `.npy`
//! arrays in any numeric dtype and either memory order, with the voxel spacing the caller gives.
//!
//! A numpy array of shape `(nz, ny, nx)` in C order has x varying fastest, as a 2-D grid's
//! `(ny, nx)` does: voxel `(i, j, k)` (along x, y, z) is `values[(k * ny + j) * nx + i]`, at
//! `origin + (i, j, k) * spacing`.

use std::path::Path;

use super::load::LoadError;
use super::npy::{self, NpyArray, Shape};

/// Largest volume accepted (voxels), checked against the header before anything is allocated:
/// 512³ with room to spare.
pub const MAX_VOXELS: usize = 1 << 28;

/// How a volume is read from a `.npy` file.
const VOLUME: Shape = Shape { dims: 3, max_cells: MAX_VOXELS, what: "a volume" };

/// A 3-D regular grid of numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    /// Voxels along x, y and z.
    pub dims: [usize; 3],
    /// The distance between neighbouring voxels along x, y and z (all positive).
    pub spacing: [f64; 3],
    /// `nx * ny * nz` values, x fastest, then y, then z; NaN where missing.
    pub values: Vec<f64>,
}

impl Volume {
    /// The value of voxel `(i, j, k)`, if it is inside.
    pub fn value(&self, i: usize, j: usize, k: usize) -> Option<f64> {
        let [nx, ny, nz] = self.dims;
        (i < nx && j < ny && k < nz).then(|| self.values.get((k * ny + j) * nx + i).copied()).flatten()
    }

    /// The extent of the volume along x, y and z from voxel 0 (`(n - 1) * spacing`).
    pub fn extent(&self) -> [f64; 3] {
        [0, 1, 2].map(|a| self.dims[a].saturating_sub(1) as f64 * self.spacing[a])
    }
}

/// `Ok` when every spacing is a positive finite number, else a message saying the fix.
fn check_spacing(spacing: [f64; 3]) -> Result<(), String> {
    match spacing.iter().position(|s| !(s.is_finite() && *s > 0.0)) {
        Some(axis) => Err(format!(
            "voxel spacing {:?} along {} is not a positive number; give the distance between voxels, e.g. [1.0, 1.0, 2.5]",
            spacing[axis],
            ["x", "y", "z"][axis]
        )),
        None => Ok(()),
    }
}

/// Read a 3-D `.npy` array (shape `(nz, ny, nx)`, any numeric dtype, C or Fortran order, plain or
/// gzip/zstd-compressed) as a volume with voxel `spacing` along x, y and z.
pub fn read_npy_volume(path: &Path, spacing: [f64; 3]) -> Result<Volume, LoadError> {
    check_spacing(spacing).map_err(|message| LoadError::Parse {
        origin: format!("`{}`", path.display()),
        format: crate::spec::DataFormat::Npy,
        message,
    })?;
    npy::read(path, VOLUME).map(|a| volume_of(a, spacing))
}

/// Parse `.npy` bytes into a volume; the error is a message for the user.
pub fn parse_npy_volume(bytes: &[u8], spacing: [f64; 3]) -> Result<Volume, String> {
    check_spacing(spacing)?;
    npy::parse(bytes, VOLUME).map(|a| volume_of(a, spacing))
}

fn volume_of(array: NpyArray, spacing: [f64; 3]) -> Volume {
    let dim = |k: usize| array.dims.get(k).copied().unwrap_or(0);
    let mut values = array.values;
    for v in &mut values {
        if !v.is_finite() {
            *v = f64::NAN;
        }
    }
    Volume { dims: [dim(2), dim(1), dim(0)], spacing, values }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::data::npy::test_file as npy;

    /// f(i, j, k) = i + 10 j + 100 k on a 4 × 3 × 2 (x, y, z) volume.
    fn f(i: usize, j: usize, k: usize) -> f64 {
        (i + 10 * j + 100 * k) as f64
    }

    #[test]
    fn c_and_fortran_order_give_the_same_voxels() {
        let (nx, ny, nz) = (4, 3, 2);
        let mut c = Vec::new();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    c.extend_from_slice(&(f(i, j, k) as u16).to_le_bytes());
                }
            }
        }
        // Fortran order of the (nz, ny, nx) array: its first axis (z) fastest.
        let mut fo = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                for k in 0..nz {
                    fo.extend_from_slice(&(f(i, j, k) as u16).to_le_bytes());
                }
            }
        }
        let spacing = [0.5, 0.5, 2.0];
        let a = parse_npy_volume(&npy("<u2", false, "(2, 3, 4)", &c), spacing).expect("C order");
        let b = parse_npy_volume(&npy("<u2", true, "(2, 3, 4)", &fo), spacing).expect("Fortran order");
        assert_eq!(a, b);
        assert_eq!(a.dims, [4, 3, 2]);
        for (i, j, k) in [(0, 0, 0), (3, 0, 0), (1, 2, 0), (2, 1, 1), (3, 2, 1)] {
            assert_eq!(a.value(i, j, k), Some(f(i, j, k)), "({i}, {j}, {k})");
        }
        assert_eq!(a.value(4, 0, 0), None);
        assert_eq!(a.extent(), [1.5, 1.0, 2.0]);
    }

    #[test]
    fn big_endian_floats_and_missing_voxels() {
        let values = [1.5f32, f32::NAN, f32::INFINITY, -2.0, 0.0, 8.0, 9.0, 10.0];
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
        let v = parse_npy_volume(&npy(">f4", false, "(2, 2, 2)", &data), [1.0; 3]).expect("volume");
        assert_eq!(v.value(0, 0, 0), Some(1.5));
        assert!(v.value(1, 0, 0).is_some_and(f64::is_nan));
        assert!(v.value(0, 1, 0).is_some_and(f64::is_nan), "an infinite voxel is missing");
        assert_eq!(v.value(1, 1, 1), Some(10.0));
    }

    #[test]
    fn wrong_shapes_short_files_and_bad_spacing_are_clear_errors() {
        let grid = npy("<f8", false, "(2, 2)", &[0u8; 32]);
        assert_eq!(
            parse_npy_volume(&grid, [1.0; 3]),
            Err("the array has shape (2, 2); a volume needs a 3-D array".into())
        );
        let short = npy("<f8", false, "(2, 2, 2)", &[0u8; 40]);
        assert_eq!(
            parse_npy_volume(&short, [1.0; 3]),
            Err("the data has 40 bytes, 64 expected for 2 × 2 × 2 <f8".into())
        );
        let huge = npy("<u1", false, "(1024, 1024, 1024)", &[]);
        assert!(parse_npy_volume(&huge, [1.0; 3]).is_err_and(|e| e.contains("more than 268435456")));
        let ok = npy("<f8", false, "(1, 1, 1)", &[0u8; 8]);
        let err = parse_npy_volume(&ok, [1.0, 0.0, 1.0]).expect_err("zero spacing");
        assert!(err.contains("voxel spacing 0.0 along y is not a positive number"), "{err}");
        // A 2-D reader refuses a volume the same way.
        let volume = npy("<f8", false, "(1, 1, 1)", &[0u8; 8]);
        assert_eq!(
            crate::data::matrix::parse_npy(&volume),
            Err("the array has shape (1, 1, 1); a grid needs a 2-D array".into())
        );
    }

    #[test]
    fn a_file_is_read_in_chunks_to_the_same_volume_as_its_bytes() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (nx, ny, nz) = (64, 64, 160); // 655,360 f8 voxels: 5 MB, over one 4 MB read chunk
        let data: Vec<u8> = (0..nx * ny * nz).flat_map(|n| ((n % 1009) as f64).to_le_bytes()).collect();
        let bytes = npy("<f8", false, &format!("({nz}, {ny}, {nx})"), &data);
        let path = dir.path().join("v.npy");
        std::fs::write(&path, &bytes).expect("write");
        let read = read_npy_volume(&path, [1.0, 1.0, 3.0]).expect("read");
        assert_eq!(read, parse_npy_volume(&bytes, [1.0, 1.0, 3.0]).expect("parse"));
        assert_eq!(read.value(5, 0, 0), Some(5.0));
        assert_eq!(read.value(0, 1, 0), Some(64.0));
    }
}
