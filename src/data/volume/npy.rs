//! 3-D `.npy` arrays as volumes: shape `(nz, ny, nx)`, so a C-order array has x varying fastest
//! (voxel `(i, j, k)` is `array[k, j, i]`), in any integer or float dtype numpy writes, either
//! byte order and either memory order (Fortran order is rearranged a slab at a time as it is
//! read), plain or gzip/zstd-compressed. The header is parsed by [`crate::data::npy`].

use std::path::Path;

use super::read::{FileType, Input, Layout};
use super::{MAX_VOXELS, Volume};
use crate::data::load::LoadError;
use crate::data::npy::{self, Header, Shape};
use crate::spec::{DataFormat, VoxelType};

/// How a volume is read from a `.npy` file.
const VOLUME: Shape = Shape { dims: 3, max_cells: MAX_VOXELS, what: "a volume" };

/// The `.npy` header at the start of `input`, whatever its number of dimensions.
fn header(input: &mut Input, shape: Shape) -> Result<Header, LoadError> {
    let mut bytes = vec![0u8; npy::PREFIX];
    input.read_exact(&mut bytes, "header")?;
    let (len, start) = npy::header_extent(&bytes).map_err(|m| input.error(m))?;
    bytes.resize(start + len, 0);
    if let Some(rest) = bytes.get_mut(npy::PREFIX..) {
        input.read_exact(rest, "header")?;
    }
    Header::parse(&bytes, shape).map_err(|m| input.error(m))
}

/// The number of dimensions of the `.npy` array in `path`, read from its header only.
pub fn ndim(path: &Path) -> Result<usize, LoadError> {
    let mut input = Input::open(path, DataFormat::Npy)?;
    let any = Shape { dims: 0, max_cells: usize::MAX, what: "an array" };
    header(&mut input, any).map(|h| h.dims.len())
}

/// The voxel type of a `.npy` dtype.
fn file_type(h: &Header) -> Option<FileType> {
    Some(match (h.dtype.kind, h.dtype.size) {
        ('u', 1) => FileType::Stored(VoxelType::U8),
        ('i', 1) => FileType::Stored(VoxelType::I8),
        ('u', 2) => FileType::Stored(VoxelType::U16),
        ('i', 2) => FileType::Stored(VoxelType::I16),
        ('u', 4) => FileType::Stored(VoxelType::U32),
        ('i', 4) => FileType::Stored(VoxelType::I32),
        ('f', 4) => FileType::Stored(VoxelType::F32),
        ('f', 8) => FileType::Stored(VoxelType::F64),
        ('i', 8) => FileType::I64,
        ('u', 8) => FileType::U64,
        _ => return None,
    })
}

/// Read a 3-D `.npy` array as a volume with voxel `spacing` along x, y and z.
pub fn read(path: &Path, spacing: [f64; 3]) -> Result<Volume, LoadError> {
    let mut input = Input::open(path, DataFormat::Npy)?;
    super::check_spacing(spacing).map_err(|m| input.error(m))?;
    let h = header(&mut input, VOLUME)?;
    let ty = file_type(&h)
        .ok_or_else(|| input.error(format!("unsupported dtype {}; use float or integer arrays", h.descr)))?;
    let [nz, ny, nx] = [0, 1, 2].map(|a| h.dims.get(a).copied().unwrap_or(0));
    super::check_size([nx, ny, nz].map(|d| d as u64), ty.stored()).map_err(|m| input.error(m))?;
    if let Some(len) = input.file_len() {
        let available = len.saturating_sub(h.data_start as u64);
        if available < h.data_bytes() as u64 {
            return Err(input.error(h.short_data(available)));
        }
    }
    let layout = if h.fortran { Layout::ZFastest } else { Layout::XFastest };
    let voxels = input.voxels(ty, h.dtype.little, [nx, ny, nz], layout, "array data")?;
    Volume::new([nx, ny, nz], voxels, spacing).map_err(|m| input.error(m))
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::data::npy::test_file as npy;

    /// f(i, j, k) = i + 10 j + 100 k on a 4 × 3 × 2 (x, y, z) volume.
    fn f(i: usize, j: usize, k: usize) -> f64 {
        (i + 10 * j + 100 * k) as f64
    }

    fn write(dir: &Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let path = dir.join(name);
        std::fs::write(&path, bytes).expect("write");
        path
    }

    #[test]
    fn c_and_fortran_order_give_the_same_voxels() {
        let dir = tempfile::tempdir().expect("temp dir");
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
        let a = read(&write(dir.path(), "c.npy", &npy("<u2", false, "(2, 3, 4)", &c)), spacing).expect("C order");
        let b = read(&write(dir.path(), "f.npy", &npy("<u2", true, "(2, 3, 4)", &fo)), spacing).expect("Fortran");
        assert_eq!(a, b);
        assert_eq!(a.dims(), [4, 3, 2]);
        assert!(matches!(a.voxels(), super::super::Voxels::U16(_)), "kept as u16");
        for (i, j, k) in [(0, 0, 0), (3, 0, 0), (1, 2, 0), (2, 1, 1), (3, 2, 1)] {
            assert_eq!(a.value(i, j, k), f(i, j, k), "({i}, {j}, {k})");
        }
        assert!(a.value(4, 0, 0).is_nan());
        assert_eq!(a.extent(), [1.5, 1.0, 2.0]);
        assert_eq!(ndim(&dir.path().join("c.npy")).ok(), Some(3));
    }

    #[test]
    fn every_dtype_round_trips_in_both_byte_orders() {
        let dir = tempfile::tempdir().expect("temp dir");
        let values = [0.0f64, 1.0, 7.0, 100.0, 3.0, 2.0, 5.0, 9.0];
        macro_rules! check {
            ($t:ty, $code:literal, $stored:ident) => {
                for (order, big) in [("<", false), (">", true)] {
                    let data: Vec<u8> = values
                        .iter()
                        .flat_map(|&v| {
                            let v = v as $t;
                            if big { v.to_be_bytes().to_vec() } else { v.to_le_bytes().to_vec() }
                        })
                        .collect();
                    let descr = format!("{order}{}", $code);
                    let path = write(dir.path(), "v.npy", &npy(&descr, false, "(2, 2, 2)", &data));
                    let v = read(&path, [1.0; 3]).unwrap_or_else(|e| panic!("{descr}: {e}"));
                    assert!(matches!(v.voxels(), super::super::Voxels::$stored(_)), "{descr}");
                    assert_eq!(v.values().collect::<Vec<_>>(), values.to_vec(), "{descr}");
                }
            };
        }
        check!(u8, "u1", U8);
        check!(i8, "i1", I8);
        check!(u16, "u2", U16);
        check!(i16, "i2", I16);
        check!(u32, "u4", U32);
        check!(i32, "i4", I32);
        check!(f32, "f4", F32);
        check!(f64, "f8", F64);
        check!(i64, "i8", F64);
        check!(u64, "u8", F64);
    }

    #[test]
    fn big_endian_floats_and_missing_voxels() {
        let dir = tempfile::tempdir().expect("temp dir");
        let values = [1.5f32, f32::NAN, f32::INFINITY, -2.0, 0.0, 8.0, 9.0, 10.0];
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
        let path = write(dir.path(), "v.npy", &npy(">f4", false, "(2, 2, 2)", &data));
        let v = read(&path, [1.0; 3]).expect("volume");
        assert_eq!(v.value(0, 0, 0), 1.5);
        assert!(v.value(1, 0, 0).is_nan());
        assert!(v.value(0, 1, 0).is_nan(), "an infinite voxel is missing");
        assert_eq!(v.value(1, 1, 1), 10.0);
        assert_eq!(v.range(), (Some((-2.0, 10.0)), 2));
    }

    #[test]
    fn wrong_shapes_short_files_and_bad_spacing_are_clear_errors() {
        let dir = tempfile::tempdir().expect("temp dir");
        let err = |name: &str, bytes: &[u8], spacing: [f64; 3]| {
            read(&write(dir.path(), name, bytes), spacing).expect_err(name).to_string()
        };
        let e = err("grid.npy", &npy("<f8", false, "(2, 2)", &[0u8; 32]), [1.0; 3]);
        assert!(e.ends_with("grid.npy` as NumPy .npy: the array has shape (2, 2); a volume needs a 3-D array"), "{e}");
        let e = err("short.npy", &npy("<f8", false, "(2, 2, 2)", &[0u8; 40]), [1.0; 3]);
        assert!(e.ends_with("the data has 40 bytes, 64 expected for 2 × 2 × 2 <f8"), "{e}");
        let e = err("huge.npy", &npy("<u1", false, "(1024, 1024, 1024)", &[]), [1.0; 3]);
        assert!(e.contains("more than 268435456"), "{e}");
        let e = err("f8.npy", &npy("<f8", false, "(1024, 512, 512)", &[]), [1.0; 3]);
        assert!(e.contains("more than the limit of 1073741824 (1 GiB)"), "{e}");
        let e = err("zero.npy", &npy("<f8", false, "(1, 0, 1)", &[]), [1.0; 3]);
        assert!(e.contains("no voxels along y"), "{e}");
        let e = err("ok.npy", &npy("<f8", false, "(1, 1, 1)", &[0u8; 8]), [1.0, 0.0, 1.0]);
        assert!(e.contains("voxel spacing 0.0 along y is not a positive number"), "{e}");
        let e = err("c.npy", &npy("<c8", false, "(1, 1, 1)", &[0u8; 8]), [1.0; 3]);
        assert!(e.contains("unsupported dtype <c8"), "{e}");
        let e = err("magic.npy", b"PK\x03\x04 not numpy at all", [1.0; 3]);
        assert!(e.contains("not a NumPy .npy file (bad magic bytes)"), "{e}");
        assert_eq!(ndim(&dir.path().join("grid.npy")).ok(), Some(2));
    }

    #[test]
    fn large_fortran_files_read_in_slabs_and_compressed_files_alike() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (nx, ny, nz) = (70, 64, 160); // 1.4 MB of f8 per x plane pair: several slabs
        let g = |i: usize, j: usize, k: usize| ((i * 7 + j * 13 + k * 31) % 1009) as f64;
        let mut fo = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                for k in 0..nz {
                    fo.extend_from_slice(&g(i, j, k).to_le_bytes());
                }
            }
        }
        let bytes = npy("<f8", true, &format!("({nz}, {ny}, {nx})"), &fo);
        let v = read(&write(dir.path(), "f.npy", &bytes), [1.0, 1.0, 3.0]).expect("read");
        for (i, j, k) in [(0, 0, 0), (69, 63, 159), (35, 1, 80), (13, 62, 2)] {
            assert_eq!(v.value(i, j, k), g(i, j, k), "({i}, {j}, {k})");
        }
        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        std::io::Write::write_all(&mut gz, &bytes).expect("gzip");
        let path = write(dir.path(), "f.npy.gz", &gz.finish().expect("gzip"));
        assert_eq!(read(&path, [1.0, 1.0, 3.0]).expect("gzip read"), v);
        assert_eq!(ndim(&path).ok(), Some(3));
    }
}
