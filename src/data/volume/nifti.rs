//! NIfTI-1 volumes: a single `.nii` file (magic `n+1`), plain or gzip/zstd-compressed, or a
//! `.hdr`/`.img` pair (magic `ni1`). The 348-byte header is read in either byte order (told by
//! `sizeof_hdr`); the voxel spacing comes from `pixdim`, its unit from `xyzt_units`, the value
//! scaling from `scl_slope`/`scl_inter` (applied on read; a slope of 0 means none), and the
//! voxel-to-world matrix from the sform (`sform_code > 0`), else the qform quaternion
//! (`qform_code > 0`), else the spacing alone (NIfTI's "method 1": voxel (0, 0, 0) at the origin).
//!
//! Voxel types read: 2 (u8), 4 (i16), 8 (i32), 16 (f32), 64 (f64), 256 (i8), 512 (u16),
//! 768 (u32), 1024 (i64) and 1280 (u64), the last two kept as f64. Refused, with a message naming
//! them: 1 (binary), 32/1792/2048 (complex), 128/2304 (RGB/RGBA), 1536 (float128).

use std::path::Path;

use super::read::{FileType, Input, Layout};
use super::{Scale, SpaceUnit, Volume};
use crate::data::load::LoadError;
use crate::spec::{DataFormat, VoxelType};

/// Bytes of a NIfTI-1 header.
pub const HEADER_BYTES: usize = 348;

/// What the header of a NIfTI-1 file says.
#[derive(Clone, Debug, PartialEq)]
pub struct Header {
    /// Whether the file is little-endian.
    pub little: bool,
    /// `dim[0..8]`.
    pub dim: [i16; 8],
    /// `datatype`.
    pub datatype: i16,
    /// `bitpix`.
    pub bitpix: i16,
    /// `pixdim[0..8]` (`pixdim[0]` is the qform's handedness, `qfac`).
    pub pixdim: [f32; 8],
    /// Where the voxels start (in the `.img` file of a pair).
    pub vox_offset: f32,
    /// `scl_slope`, `scl_inter`.
    pub scl: [f32; 2],
    /// `xyzt_units`.
    pub xyzt_units: u8,
    /// `qform_code`, `sform_code`.
    pub codes: [i16; 2],
    /// `quatern_b, c, d`, `qoffset_x, y, z`.
    pub quatern: [f32; 6],
    /// `srow_x`, `srow_y`, `srow_z`.
    pub srow: [[f32; 4]; 3],
    /// Whether the magic is `ni1` (voxels in a separate `.img` file) rather than `n+1`.
    pub pair: bool,
}

/// Reads numbers at fixed offsets of the header in its byte order.
struct Fields<'a> {
    bytes: &'a [u8; HEADER_BYTES],
    little: bool,
}

impl Fields<'_> {
    fn array<const N: usize>(&self, at: usize) -> [u8; N] {
        let mut out = [0u8; N];
        if let Some(src) = self.bytes.get(at..at + N) {
            out.copy_from_slice(src);
        }
        if !self.little {
            out.reverse();
        }
        out
    }
    fn i16(&self, at: usize) -> i16 {
        i16::from_le_bytes(self.array(at))
    }
    fn f32(&self, at: usize) -> f32 {
        f32::from_le_bytes(self.array(at))
    }
}

impl Header {
    /// Parse the 348 header bytes; the error says what is wrong.
    pub fn parse(bytes: &[u8; HEADER_BYTES]) -> Result<Header, String> {
        let size_le = i32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
        let little = match (size_le, size_le.swap_bytes()) {
            (348, _) => true,
            (_, 348) => false,
            (540, _) | (_, 540) => {
                return Err("it is a NIfTI-2 file (sizeof_hdr 540); only NIfTI-1 is read: convert it, e.g. with nibabel's Nifti1Image".into());
            }
            _ => {
                return Err(format!(
                    "not a NIfTI-1 file: sizeof_hdr is {size_le}, not 348 in either byte order (is it another format, or compressed without a .gz extension?)"
                ));
            }
        };
        let f = Fields { bytes, little };
        let pair = match bytes.get(344..348) {
            Some(b"n+1\0") => false,
            Some(b"ni1\0") => true,
            other => {
                return Err(format!(
                    "not a NIfTI-1 file: the magic is {:?}, not \"n+1\" or \"ni1\" (Analyze 7.5 files are not read)",
                    String::from_utf8_lossy(other.unwrap_or(&[]))
                ));
            }
        };
        let header = Header {
            little,
            dim: std::array::from_fn(|n| f.i16(40 + 2 * n)),
            datatype: f.i16(70),
            bitpix: f.i16(72),
            pixdim: std::array::from_fn(|n| f.f32(76 + 4 * n)),
            vox_offset: f.f32(108),
            scl: [f.f32(112), f.f32(116)],
            xyzt_units: bytes[123],
            codes: [f.i16(252), f.i16(254)],
            quatern: std::array::from_fn(|n| f.f32(256 + 4 * n)),
            srow: std::array::from_fn(|r| std::array::from_fn(|c| f.f32(280 + 16 * r + 4 * c))),
            pair,
        };
        Ok(header)
    }

    /// The voxel type of `datatype`, checked against `bitpix`.
    pub fn file_type(&self) -> Result<FileType, String> {
        let ty = match self.datatype {
            2 => FileType::Stored(VoxelType::U8),
            4 => FileType::Stored(VoxelType::I16),
            8 => FileType::Stored(VoxelType::I32),
            16 => FileType::Stored(VoxelType::F32),
            64 => FileType::Stored(VoxelType::F64),
            256 => FileType::Stored(VoxelType::I8),
            512 => FileType::Stored(VoxelType::U16),
            768 => FileType::Stored(VoxelType::U32),
            1024 => FileType::I64,
            1280 => FileType::U64,
            code => {
                let what = match code {
                    1 => "binary (1 bit per voxel)",
                    32 | 1792 | 2048 => "complex",
                    128 | 2304 => "RGB colour",
                    1536 => "128-bit float",
                    _ => "unknown",
                };
                return Err(format!(
                    "datatype {code} ({what}) is not read; volumes of datatype 2 (u8), 4 (i16), 8 (i32), 16 (f32), 64 (f64), 256 (i8), 512 (u16), 768 (u32), 1024 (i64) or 1280 (u64) are"
                ));
            }
        };
        if self.bitpix as usize != ty.size() * 8 {
            return Err(format!(
                "bitpix is {} but datatype {} has {} bits per voxel; the header is inconsistent",
                self.bitpix,
                self.datatype,
                ty.size() * 8
            ));
        }
        Ok(ty)
    }

    /// Voxels along x, y and z, and the number of volumes (the product of `dim[4..]`).
    pub fn dims(&self) -> Result<([u64; 3], u64), String> {
        let rank = self.dim[0];
        if !(1..=7).contains(&rank) {
            return Err(format!("dim[0] is {rank}; it must give the number of dimensions, 1 to 7"));
        }
        let mut sizes = [1u64; 7];
        for (n, size) in sizes.iter_mut().enumerate().take(rank as usize) {
            let d = self.dim[n + 1];
            if d <= 0 {
                return Err(format!("dim[{}] is {d}; every dimension needs at least one voxel", n + 1));
            }
            *size = d as u64;
        }
        Ok(([sizes[0], sizes[1], sizes[2]], sizes[3..].iter().product()))
    }

    /// The distance between voxels along x, y and z (`|pixdim[1..4]|`); an axis of one voxel
    /// with no spacing given gets 1.
    pub fn spacing(&self, dims: [u64; 3]) -> Result<[f64; 3], String> {
        let mut spacing = [1.0; 3];
        for axis in 0..3 {
            let p = f64::from(self.pixdim[axis + 1]).abs();
            if p.is_finite() && p > 0.0 {
                spacing[axis] = p;
            } else if dims[axis] > 1 {
                return Err(format!(
                    "pixdim[{}] is {p}: the header gives no voxel spacing along {}; fix the header (nibabel: img.header.set_zooms)",
                    axis + 1,
                    ["x", "y", "z"][axis]
                ));
            }
        }
        Ok(spacing)
    }

    /// The unit of `pixdim` and of world coordinates, if `xyzt_units` names one.
    pub fn unit(&self) -> Option<SpaceUnit> {
        match self.xyzt_units & 0x07 {
            1 => Some(SpaceUnit::Metre),
            2 => Some(SpaceUnit::Millimetre),
            3 => Some(SpaceUnit::Micrometre),
            _ => None,
        }
    }

    /// The value scaling, when `scl_slope` is a finite number other than 0 (and not 1 with an
    /// `scl_inter` of 0).
    pub fn scale(&self) -> Option<Scale> {
        let (slope, inter) = (f64::from(self.scl[0]), f64::from(self.scl[1]));
        let inter = if inter.is_finite() { inter } else { 0.0 };
        (slope.is_finite() && slope != 0.0 && !(slope == 1.0 && inter == 0.0)).then_some(Scale { slope, inter })
    }

    /// The voxel-to-world matrix: the sform if `sform_code > 0`, else the qform if
    /// `qform_code > 0`, else a scaling by `spacing`.
    pub fn affine(&self, spacing: [f64; 3]) -> [[f64; 4]; 3] {
        let [qform_code, sform_code] = self.codes;
        if sform_code > 0 {
            return self.srow.map(|row| row.map(f64::from));
        }
        if qform_code > 0 {
            return self.qform(spacing);
        }
        let [sx, sy, sz] = spacing;
        [[sx, 0.0, 0.0, 0.0], [0.0, sy, 0.0, 0.0], [0.0, 0.0, sz, 0.0]]
    }

    /// The qform: rotation from the quaternion `(b, c, d)` (with `a` from unit length), scaled by
    /// the spacing, z flipped when `qfac = pixdim[0]` is negative, then offset.
    fn qform(&self, spacing: [f64; 3]) -> [[f64; 4]; 3] {
        let [b, c, d, qx, qy, qz] = self.quatern.map(f64::from);
        let sum = b * b + c * c + d * d;
        // As nifti1_io: a slightly-over-unit (b, c, d) is renormalised with a = 0.
        let (a, b, c, d) = if 1.0 - sum < 1e-7 {
            let n = sum.sqrt();
            (0.0, b / n, c / n, d / n)
        } else {
            ((1.0 - sum).sqrt(), b, c, d)
        };
        let qfac = if self.pixdim[0] < 0.0 { -1.0 } else { 1.0 };
        let [sx, sy, sz] = [spacing[0], spacing[1], spacing[2] * qfac];
        let r = [
            [a * a + b * b - c * c - d * d, 2.0 * (b * c - a * d), 2.0 * (b * d + a * c)],
            [2.0 * (b * c + a * d), a * a + c * c - b * b - d * d, 2.0 * (c * d - a * b)],
            [2.0 * (b * d - a * c), 2.0 * (c * d + a * b), a * a + d * d - c * c - b * b],
        ];
        let offset = [qx, qy, qz];
        std::array::from_fn(|row| [r[row][0] * sx, r[row][1] * sy, r[row][2] * sz, offset[row]])
    }
}

/// A NIfTI volume and what the reader noted about it.
#[derive(Debug)]
pub struct Read {
    /// The volume.
    pub volume: Volume,
    /// Notes for the user (a 4-D file read at one of its volumes).
    pub warnings: Vec<String>,
}

/// Read a NIfTI-1 volume: a `.nii` file, or the `.hdr` of a pair whose voxels are in `img` (the
/// `.img` file beside it). `frame` picks one volume of a 4-D file (default 0, with a warning).
pub fn read(path: &Path, img: Option<&Path>, frame: Option<u64>) -> Result<Read, LoadError> {
    let mut input = Input::open(path, DataFormat::Nifti)?;
    let mut bytes = [0u8; HEADER_BYTES];
    input.read_exact(&mut bytes, "348-byte header")?;
    let header = Header::parse(&bytes).map_err(|m| input.error(m))?;
    let ty = header.file_type().map_err(|m| input.error(m))?;
    let (dims, frames) = header.dims().map_err(|m| input.error(m))?;
    let count = super::check_size(dims, ty.stored()).map_err(|m| input.error(m))?;
    let spacing = header.spacing(dims).map_err(|m| input.error(m))?;
    let mut warnings = Vec::new();
    let frame = match frame {
        Some(n) if n >= frames => {
            return Err(input.error(format!(
                "`frame = {n}` asks for volume {n}, but the file holds {frames} (0 to {})",
                frames - 1
            )));
        }
        Some(n) => n,
        None => {
            if frames > 1 {
                warnings.push(format!(
                    "the file holds {frames} volumes (dim[4..] = {:?}); volume 0 is read, `frame = N` picks another",
                    &header.dim[4..=(header.dim[0] as usize).clamp(4, 7)]
                ));
            }
            0
        }
    };
    let vox_offset = f64::from(header.vox_offset);
    if !(vox_offset.is_finite() && vox_offset >= 0.0 && vox_offset < 1e15) {
        return Err(input.error(format!("vox_offset is {vox_offset}, not a byte offset")));
    }
    let start = vox_offset as u64 + frame * (count * ty.size()) as u64;
    let mut input = match (header.pair, img) {
        (false, None) => {
            if vox_offset < HEADER_BYTES as f64 {
                return Err(input.error(format!(
                    "vox_offset is {vox_offset}, inside the 348-byte header; a single-file NIfTI has its voxels at 352 or later"
                )));
            }
            input
        }
        (true, Some(img)) => Input::open(img, DataFormat::Nifti)?,
        (true, None) => {
            return Err(input.error(
                "the magic \"ni1\" says the voxels are in a separate .img file; name the .hdr file in `path`, with the .img beside it",
            ));
        }
        (false, Some(_)) => {
            return Err(input.error(
                "the magic \"n+1\" says the voxels follow the header in this file, but it is named .hdr; rename it to .nii",
            ));
        }
    };
    input.skip_to(start, "voxel data")?;
    let voxels = input.voxels(ty, header.little, dims.map(|d| d as usize), Layout::XFastest, "voxel data")?;
    let volume = Volume::new(dims.map(|d| d as usize), voxels, spacing)
        .and_then(|v| v.with_affine(header.affine(spacing)))
        .map_err(|m| input.error(m))?
        .with_scale(header.scale())
        .with_unit(header.unit());
    Ok(Read { volume, warnings })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::data::volume::Voxels;

    fn fixture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/volume").join(name)
    }

    /// What nibabel read from each fixture (`make_fixtures.py`).
    fn expected() -> serde_json::Value {
        let text = std::fs::read_to_string(fixture("expected.json")).expect("expected.json");
        serde_json::from_str(&text).expect("JSON")
    }

    fn numbers(value: &serde_json::Value) -> Vec<f64> {
        value.as_array().expect("array").iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect()
    }

    #[test]
    fn fixtures_read_voxel_for_voxel_as_nibabel_reads_them() {
        let expected = expected();
        let files = expected.as_object().expect("object");
        assert_eq!(files.len(), 7);
        for (name, want) in files {
            let img = name.strip_suffix(".hdr").map(|stem| fixture(&format!("{stem}.img")));
            let read = read(&fixture(name), img.as_deref(), None).unwrap_or_else(|e| panic!("{name}: {e}"));
            let v = &read.volume;
            let dims: Vec<usize> = numbers(&want["dims"]).iter().map(|&d| d as usize).collect();
            assert_eq!(v.dims().to_vec(), dims, "{name}");
            let values: Vec<f64> = v.values().collect();
            let want_values = numbers(&want["values"]);
            assert_eq!(values.len(), want_values.len(), "{name}");
            for (n, (a, b)) in values.iter().zip(&want_values).enumerate() {
                assert!(a == b || (a.is_nan() && b.is_nan()), "{name}: voxel {n} is {a}, nibabel reads {b}");
            }
            let dtype = want["dtype"].as_str().expect("dtype");
            let stored = super::super::type_name(v.voxels().voxel_type());
            let as_numpy = match stored {
                "u8" => "uint8",
                "u16" => "uint16",
                "i16" => "int16",
                "f32" => "float32",
                other => other,
            };
            assert_eq!(as_numpy, dtype, "{name}: kept in the file's type");
            let zooms = numbers(&want["zooms"]);
            assert_eq!(v.spacing().to_vec(), zooms, "{name}");
            // nibabel's affine when both codes are 0 centres the volume and flips x; NIfTI's
            // method 1 (read here) is the spacing alone.
            if name != "u16_noform.nii" {
                let affine: Vec<f64> = want["affine"].as_array().expect("rows").iter().flat_map(numbers).collect();
                for (a, b) in v.affine().iter().flatten().zip(&affine) {
                    assert!((a - b).abs() < 1e-6, "{name}: affine {:?}, nibabel {affine:?}", v.affine());
                }
            }
            let unit = v.unit().map_or("unknown", |u| match u {
                SpaceUnit::Millimetre => "mm",
                SpaceUnit::Micrometre => "micron",
                SpaceUnit::Metre => "meter",
            });
            assert_eq!(unit, want["unit"].as_str().unwrap_or(""), "{name}");
        }
    }

    #[test]
    fn scaling_stays_a_view_and_forms_take_their_precedence() {
        let read = read(&fixture("le_sform_i16.nii"), None, None).expect("read");
        assert!(matches!(read.volume.voxels(), Voxels::I16(_)));
        assert_eq!(read.volume.scale(), Some(Scale { slope: 0.5, inter: -3.0 }));
        assert_eq!(read.volume.voxels().get(1), 1.0, "stored as written");
        assert_eq!(read.volume.get(1), -2.5, "read scaled");
        assert_eq!(read.volume.voxels().memory_bytes(), 48);
        let noform = super::read(&fixture("u16_noform.nii"), None, None).expect("read").volume;
        assert_eq!(noform.affine(), [[0.25, 0.0, 0.0, 0.0], [0.0, 0.5, 0.0, 0.0], [0.0, 0.0, 4.0, 0.0]]);
        let qform = super::read(&fixture("be_qform_f32.nii"), None, None).expect("read").volume;
        assert_eq!(qform.orientation(), "PRI");
        assert_eq!(qform.range(), (Some((0.0, 123.0)), 1));
    }

    #[test]
    fn frames_of_a_4d_file() {
        let path = fixture("u8_4d.nii");
        let first = read(&path, None, None).expect("read");
        assert_eq!(first.warnings.len(), 1);
        assert!(
            first.warnings[0].starts_with("the file holds 3 volumes (dim[4..] = [3]); volume 0 is read"),
            "{:?}",
            first.warnings
        );
        let third = read(&path, None, Some(2)).expect("frame 2");
        assert!(third.warnings.is_empty());
        assert_eq!(third.volume.value(3, 2, 1), first.volume.value(3, 2, 1) + 2.0);
        let err = read(&path, None, Some(3)).expect_err("no frame 3").to_string();
        assert!(err.ends_with("`frame = 3` asks for volume 3, but the file holds 3 (0 to 2)"), "{err}");
    }

    /// The bytes of a fixture with `edit` applied, written to a temporary file.
    fn edited(dir: &Path, name: &str, edit: impl FnOnce(&mut Vec<u8>)) -> std::path::PathBuf {
        let mut bytes = std::fs::read(fixture(name)).expect("fixture");
        edit(&mut bytes);
        let path = dir.join(name);
        std::fs::write(&path, bytes).expect("write");
        path
    }

    #[test]
    fn bad_headers_and_short_files_are_clear_errors() {
        let dir = tempfile::tempdir().expect("temp dir");
        let le = "le_sform_i16.nii";
        let err = |path: std::path::PathBuf| read(&path, None, None).expect_err("an error").to_string();
        let cases: Vec<(Box<dyn FnOnce(&mut Vec<u8>)>, &str)> = vec![
            (Box::new(|b: &mut Vec<u8>| b.truncate(200)), "the file ends inside the 348-byte header"),
            (
                Box::new(|b: &mut Vec<u8>| b.truncate(380)),
                "the file has 380 bytes, but voxel data needs 48 bytes from byte 352",
            ),
            (Box::new(|b: &mut Vec<u8>| b[344..348].copy_from_slice(b"xyz\0")), "the magic is \"xyz\\0\""),
            (Box::new(|b: &mut Vec<u8>| b[0..4].copy_from_slice(&540i32.to_le_bytes())), "it is a NIfTI-2 file"),
            (Box::new(|b: &mut Vec<u8>| b[0..4].copy_from_slice(&1234i32.to_le_bytes())), "sizeof_hdr is 1234"),
            (
                Box::new(|b: &mut Vec<u8>| b[70..72].copy_from_slice(&32i16.to_le_bytes())),
                "datatype 32 (complex) is not read",
            ),
            (
                Box::new(|b: &mut Vec<u8>| b[72..74].copy_from_slice(&8i16.to_le_bytes())),
                "bitpix is 8 but datatype 4 has 16 bits",
            ),
            (
                Box::new(|b: &mut Vec<u8>| b[44..46].copy_from_slice(&0i16.to_le_bytes())),
                "dim[2] is 0; every dimension needs",
            ),
            (Box::new(|b: &mut Vec<u8>| b[44..46].copy_from_slice(&(-3i16).to_le_bytes())), "dim[2] is -3"),
            (Box::new(|b: &mut Vec<u8>| b[40..42].copy_from_slice(&9i16.to_le_bytes())), "dim[0] is 9"),
            (
                Box::new(|b: &mut Vec<u8>| {
                    for n in 1..4 {
                        b[40 + 2 * n..42 + 2 * n].copy_from_slice(&32767i16.to_le_bytes());
                    }
                }),
                "the volume is 32767 × 32767 × 32767 voxels, more than the limit of 268435456",
            ),
            (Box::new(|b: &mut Vec<u8>| b[84..88].copy_from_slice(&f32::NAN.to_le_bytes())), "pixdim[2] is NaN"),
            (
                Box::new(|b: &mut Vec<u8>| b[108..112].copy_from_slice(&100f32.to_le_bytes())),
                "vox_offset is 100, inside the 348-byte header",
            ),
            (
                Box::new(|b: &mut Vec<u8>| b[344..348].copy_from_slice(b"ni1\0")),
                "the voxels are in a separate .img file",
            ),
        ];
        for (edit, message) in cases {
            let e = err(edited(dir.path(), le, edit));
            assert!(e.starts_with("cannot read `") && e.contains("as NIfTI-1: "), "{e}");
            assert!(e.contains(message), "{message}: {e}");
        }
    }

    #[test]
    fn compressed_files_stop_at_the_header_size() {
        let dir = tempfile::tempdir().expect("temp dir");
        // A header of 4 × 3 × 2 i16 voxels followed by 50 MB of zeros: only 48 bytes are inflated.
        let mut bytes = std::fs::read(fixture("le_sform_i16.nii")).expect("fixture");
        bytes.resize(50_000_000, 0);
        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        std::io::Write::write_all(&mut gz, &bytes).expect("gzip");
        let path = dir.path().join("bomb.nii.gz");
        std::fs::write(&path, gz.finish().expect("gzip")).expect("write");
        let read = read(&path, None, None).expect("the voxels the header calls for");
        assert_eq!(read.volume.len(), 24);
        // Cut short inside the voxels, and corrupt.
        let full = std::fs::read(fixture("le_sform_i16.nii.gz")).expect("fixture");
        let path = dir.path().join("short.nii.gz");
        std::fs::write(&path, &full[..full.len() - 30]).expect("write");
        let e = super::read(&path, None, None).expect_err("short").to_string();
        assert!(e.contains("short.nii.gz"), "{e}");
        std::fs::write(&path, b"\x1f\x8b\x08\x00 this is not deflate data at all, not at all").expect("write");
        let e = super::read(&path, None, None).expect_err("corrupt").to_string();
        assert!(e.starts_with("cannot decompress `") && e.contains("as gzip"), "{e}");
    }
}
