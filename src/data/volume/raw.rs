//! Raw volumes: a file of voxels only (`.raw`, `.bin`, `.img` without a header, plain or
//! gzip/zstd-compressed), described in the spec by `dims`, `dtype`, `byte_order`, `spacing` and
//! `header_bytes` (bytes skipped before the first voxel). Voxels run x fastest, then y, then z.

use std::path::Path;

use super::Volume;
use super::read::{FileType, Input, Layout};
use crate::data::load::LoadError;
use crate::spec::{ByteOrder, DataFormat, VoxelType};

/// How a raw file is laid out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RawLayout {
    /// Voxels along x, y and z.
    pub dims: [u64; 3],
    /// The voxel type.
    pub dtype: VoxelType,
    /// The byte order of multi-byte voxels.
    pub byte_order: ByteOrder,
    /// The distance between voxels along x, y and z.
    pub spacing: [f64; 3],
    /// Bytes before the first voxel.
    pub header_bytes: u64,
}

/// Read a raw volume laid out as `layout`. Bytes after the last voxel are ignored.
pub fn read(path: &Path, layout: RawLayout) -> Result<Volume, LoadError> {
    let mut input = Input::open(path, DataFormat::Raw)?;
    let checked = super::check_spacing(layout.spacing).and_then(|()| super::check_size(layout.dims, layout.dtype));
    checked.map_err(|m| input.error(m))?;
    input.check_left(layout.header_bytes, "`header_bytes`")?;
    input.skip_to(layout.header_bytes, "voxel data")?;
    let dims = layout.dims.map(|d| d as usize);
    let little = layout.byte_order == ByteOrder::Little;
    let what = format!("{} × {} × {} {}", dims[0], dims[1], dims[2], super::type_name(layout.dtype));
    let voxels = input.voxels(FileType::Stored(layout.dtype), little, dims, Layout::XFastest, &what)?;
    Volume::new(dims, voxels, layout.spacing).map_err(|m| input.error(m))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(dtype: VoxelType, byte_order: ByteOrder, header_bytes: u64) -> RawLayout {
        RawLayout { dims: [3, 2, 2], dtype, byte_order, spacing: [0.5, 0.5, 1.25], header_bytes }
    }

    #[test]
    fn big_endian_voxels_after_a_header() {
        let dir = tempfile::tempdir().expect("temp dir");
        let values: Vec<i16> = (0..12).map(|n| n * 1000 - 5000).collect();
        let mut bytes = b"HEADER..".to_vec();
        bytes.extend(values.iter().flat_map(|v| v.to_be_bytes()));
        bytes.extend_from_slice(b"trailing bytes are ignored");
        let path = dir.path().join("v.raw");
        std::fs::write(&path, &bytes).expect("write");
        let v = read(&path, layout(VoxelType::I16, ByteOrder::Big, 8)).expect("read");
        assert_eq!(v.values().collect::<Vec<_>>(), values.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
        assert_eq!(v.value(2, 1, 1), 6000.0);
        assert_eq!(v.spacing(), [0.5, 0.5, 1.25]);
        assert_eq!(v.world(2.0, 0.0, 2.0), [1.0, 0.0, 2.5]);
        // The same bytes read little-endian give other numbers: the key matters.
        let le = read(&path, layout(VoxelType::I16, ByteOrder::Little, 8)).expect("read");
        assert_ne!(le.value(1, 0, 0), v.value(1, 0, 0));
    }

    #[test]
    fn short_files_and_bad_layouts_are_clear_errors() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("v.raw");
        std::fs::write(&path, [0u8; 40]).expect("write");
        let err = |l: RawLayout| read(&path, l).expect_err("error").to_string();
        let e = err(layout(VoxelType::U16, ByteOrder::Little, 20));
        assert!(
            e.contains("as a raw volume: the file has 40 bytes, but 3 × 2 × 2 u16 needs 24 bytes from byte 20"),
            "{e}"
        );
        let e = err(layout(VoxelType::U8, ByteOrder::Little, 41));
        assert!(e.contains("the file has 40 bytes, but `header_bytes` needs 41 bytes from byte 0"), "{e}");
        let e = err(RawLayout { dims: [0, 1, 1], ..layout(VoxelType::U8, ByteOrder::Little, 0) });
        assert!(e.contains("no voxels along x"), "{e}");
        let e = err(RawLayout { spacing: [1.0, 1.0, f64::INFINITY], ..layout(VoxelType::U8, ByteOrder::Little, 0) });
        assert!(e.contains("voxel spacing inf along z is not a positive number"), "{e}");
        let e = err(RawLayout { dims: [u64::MAX, 2, 1], ..layout(VoxelType::U8, ByteOrder::Little, 0) });
        assert!(e.contains("more than the limit of 268435456"), "{e}");
    }
}
