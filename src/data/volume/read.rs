//! Reading voxels from a file, plain or gzip/zstd-compressed, straight into their typed vector:
//! the file's bytes land in the vector's memory (swapped in place when their byte order is not
//! the machine's), so a volume costs its own size and no copy. Only the bytes the header calls
//! for are read, so a compressed file cannot inflate past them.

use std::io::Read;
use std::path::{Path, PathBuf};

use super::voxels::{Sample, Voxels};
use crate::data::compressed::Compression;
use crate::data::load::LoadError;
use crate::spec::{DataFormat, VoxelType};

/// How voxels are laid out in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// x fastest, then y, then z (NIfTI, raw files, C-order `.npy` of shape `(nz, ny, nx)`).
    XFastest,
    /// z fastest, then y, then x (a Fortran-order `.npy` of shape `(nz, ny, nx)`).
    ZFastest,
}

/// The type of a voxel in a file: one that is stored as it is, or a 64-bit integer, stored as
/// `f64`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileType {
    /// Stored in its own type.
    Stored(VoxelType),
    /// Signed 64-bit integers.
    I64,
    /// Unsigned 64-bit integers.
    U64,
}

impl FileType {
    /// Bytes per voxel in the file.
    pub fn size(self) -> usize {
        match self {
            FileType::Stored(ty) => super::type_size(ty),
            FileType::I64 | FileType::U64 => 8,
        }
    }

    /// The type the voxels are kept in.
    pub fn stored(self) -> VoxelType {
        match self {
            FileType::Stored(ty) => ty,
            FileType::I64 | FileType::U64 => VoxelType::F64,
        }
    }
}

/// A volume file opened for reading from its start, decompressed on the fly when its extension
/// names a compression.
pub struct Input {
    reader: Box<dyn Read>,
    path: PathBuf,
    format: DataFormat,
    compression: Option<Compression>,
    /// The file's length, when it is not compressed (so sizes are checked before reading).
    file_len: Option<u64>,
    /// Bytes read (after decompression) so far.
    at: u64,
}

/// Bytes read at a time when voxels must be rearranged or converted.
const CHUNK: usize = 4 * 1024 * 1024;

impl Input {
    /// Open `path`, read as `format` (for the messages).
    pub fn open(path: &Path, format: DataFormat) -> Result<Input, LoadError> {
        let file = crate::data::regular_file::open(path).map_err(|e| LoadError::from_io(path, e))?;
        let compression = Compression::of(path);
        let (reader, file_len): (Box<dyn Read>, _) = match compression {
            None => {
                let len = file.metadata().map_err(|e| LoadError::from_io(path, e))?.len();
                (Box::new(file), Some(len))
            }
            Some(Compression::Gzip) => {
                (Box::new(flate2::read::MultiGzDecoder::new(std::io::BufReader::new(file))), None)
            }
            Some(Compression::Zstd) => {
                let decoder = zstd::stream::read::Decoder::new(file).map_err(|e| LoadError::Decompress {
                    path: path.to_path_buf(),
                    compression: Compression::Zstd,
                    message: e.to_string(),
                })?;
                (Box::new(decoder), None)
            }
        };
        Ok(Input { reader, path: path.to_path_buf(), format, compression, file_len, at: 0 })
    }

    /// The error for a file whose contents are wrong: the file, the format and `message`.
    pub fn error(&self, message: impl Into<String>) -> LoadError {
        LoadError::Parse { origin: format!("`{}`", self.path.display()), format: self.format, message: message.into() }
    }

    /// The file's length, when it is not compressed.
    pub fn file_len(&self) -> Option<u64> {
        self.file_len
    }

    /// Fill `buf` from the file; `what` names the part read, for a file that ends too early.
    pub fn read_exact(&mut self, buf: &mut [u8], what: &str) -> Result<(), LoadError> {
        match self.reader.read_exact(buf) {
            Ok(()) => {
                self.at += buf.len() as u64;
                Ok(())
            }
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => Err(self.error(format!(
                "the file ends inside the {what} (it has fewer than {} bytes{}); is it cut short?",
                self.at + buf.len() as u64,
                if self.compression.is_some() { " once decompressed" } else { "" }
            ))),
            Err(e) => Err(self.io_error(e)),
        }
    }

    fn io_error(&self, e: std::io::Error) -> LoadError {
        match self.compression {
            Some(compression) => LoadError::Decompress { path: self.path.clone(), compression, message: e.to_string() },
            None => LoadError::from_io(&self.path, e),
        }
    }

    /// Read and drop bytes up to `offset` (an offset before the current one is an error).
    pub fn skip_to(&mut self, offset: u64, what: &str) -> Result<(), LoadError> {
        let Some(gap) = offset.checked_sub(self.at) else {
            return Err(self.error(format!("the {what} starts at byte {offset}, inside the header")));
        };
        let copied =
            std::io::copy(&mut (&mut self.reader).take(gap), &mut std::io::sink()).map_err(|e| self.io_error(e))?;
        self.at += copied;
        if copied < gap {
            return Err(self.error(format!("the file ends before the {what}, which starts at byte {offset}")));
        }
        Ok(())
    }

    /// Refuse a plain file too short to hold `bytes` more bytes from here, before allocating them.
    pub fn check_left(&self, bytes: u64, what: &str) -> Result<(), LoadError> {
        match self.file_len {
            Some(len) if len.saturating_sub(self.at) < bytes => Err(self.error(format!(
                "the file has {len} bytes, but {what} needs {bytes} bytes from byte {}; is it cut short, or are the dimensions wrong?",
                self.at
            ))),
            _ => Ok(()),
        }
    }

    /// Read `count` voxels of `ty` in `little`-endian (else big-endian) byte order, laid out as
    /// `layout` in a volume of `dims` (x, y, z). `what` names them in messages.
    pub fn voxels(
        &mut self,
        ty: FileType,
        little: bool,
        dims: [usize; 3],
        layout: Layout,
        what: &str,
    ) -> Result<Voxels, LoadError> {
        let count = dims[0] * dims[1] * dims[2];
        self.check_left((count * ty.size()) as u64, what)?;
        let swap = little != cfg!(target_endian = "little");
        Ok(match ty {
            FileType::Stored(VoxelType::U8) => Voxels::U8(self.typed(dims, layout, swap, what)?),
            FileType::Stored(VoxelType::I8) => Voxels::I8(self.typed(dims, layout, swap, what)?),
            FileType::Stored(VoxelType::U16) => Voxels::U16(self.typed(dims, layout, swap, what)?),
            FileType::Stored(VoxelType::I16) => Voxels::I16(self.typed(dims, layout, swap, what)?),
            FileType::Stored(VoxelType::U32) => Voxels::U32(self.typed(dims, layout, swap, what)?),
            FileType::Stored(VoxelType::I32) => Voxels::I32(self.typed(dims, layout, swap, what)?),
            FileType::Stored(VoxelType::F32) => Voxels::F32(self.typed(dims, layout, swap, what)?),
            FileType::Stored(VoxelType::F64) => Voxels::F64(self.typed(dims, layout, swap, what)?),
            FileType::I64 => Voxels::F64(self.wide(dims, layout, swap, what, |b| i64::from_ne_bytes(b) as f64)?),
            FileType::U64 => Voxels::F64(self.wide(dims, layout, swap, what, |b| u64::from_ne_bytes(b) as f64)?),
        })
    }

    /// Voxels of a stored type, read into their vector's memory.
    fn typed<T: Sample>(
        &mut self,
        dims: [usize; 3],
        layout: Layout,
        swap: bool,
        what: &str,
    ) -> Result<Vec<T>, LoadError> {
        let fix = |v: &mut [T]| {
            if swap {
                v.iter_mut().for_each(|x| *x = x.swap_bytes());
            }
            if T::FLOAT {
                v.iter_mut().for_each(|x| *x = x.finite_or_nan());
            }
        };
        let mut out = vec![T::zeroed(); dims[0] * dims[1] * dims[2]];
        match layout {
            Layout::XFastest => {
                self.read_exact(bytemuck::cast_slice_mut(&mut out), what)?;
                fix(&mut out);
            }
            Layout::ZFastest => {
                // Slabs of whole x planes in the file (z fastest), each scattered as rows of x.
                let [nx, ny, nz] = dims;
                let plane = ny * nz;
                let slab = (CHUNK / (plane * size_of::<T>()).max(1)).clamp(1, nx);
                let mut buf = vec![T::zeroed(); slab * plane];
                let mut i0 = 0;
                while i0 < nx {
                    let b = slab.min(nx - i0);
                    let part = &mut buf[..b * plane];
                    self.read_exact(bytemuck::cast_slice_mut(part), what)?;
                    fix(part);
                    scatter_z_fastest(part, &mut out, [nx, ny, nz], i0, b);
                    i0 += b;
                }
            }
        }
        Ok(out)
    }

    /// 64-bit integer voxels, converted to `f64` a chunk at a time.
    fn wide(
        &mut self,
        dims: [usize; 3],
        layout: Layout,
        swap: bool,
        what: &str,
        convert: fn([u8; 8]) -> f64,
    ) -> Result<Vec<f64>, LoadError> {
        let count = dims[0] * dims[1] * dims[2];
        let mut file_order = Vec::with_capacity(count);
        let mut chunk = vec![0u8; CHUNK];
        while file_order.len() < count {
            let take = ((count - file_order.len()) * 8).min(CHUNK);
            self.read_exact(&mut chunk[..take], what)?;
            file_order.extend(chunk[..take].chunks_exact(8).map(|c| {
                let mut b = <[u8; 8]>::try_from(c).unwrap_or_default();
                if swap {
                    b.reverse();
                }
                convert(b)
            }));
        }
        if layout == Layout::XFastest {
            return Ok(file_order);
        }
        let mut out = vec![0.0; count];
        scatter_z_fastest(&file_order, &mut out, dims, 0, dims[0]);
        Ok(out)
    }
}

/// Put `b` x planes starting at x = `i0`, read z fastest (`slab[(bi * ny + j) * nz + k]`), into
/// `out` (x fastest): for each (j, k), a run of `b` neighbouring voxels along x.
fn scatter_z_fastest<T: Copy>(slab: &[T], out: &mut [T], [nx, ny, nz]: [usize; 3], i0: usize, b: usize) {
    for j in 0..ny {
        for k in 0..nz {
            let row = (k * ny + j) * nx + i0;
            if let Some(dst) = out.get_mut(row..row + b) {
                for (bi, d) in dst.iter_mut().enumerate() {
                    if let Some(&s) = slab.get((bi * ny + j) * nz + k) {
                        *d = s;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_fastest_slabs_land_x_fastest() {
        let [nx, ny, nz] = [5, 3, 4];
        let f = |i: usize, j: usize, k: usize| (i + 10 * j + 100 * k) as u16;
        let mut file = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                for k in 0..nz {
                    file.push(f(i, j, k));
                }
            }
        }
        let mut out = vec![0u16; nx * ny * nz];
        // Two slabs of unequal width, as the reader makes them.
        let plane = ny * nz;
        scatter_z_fastest(&file[..3 * plane], &mut out, [nx, ny, nz], 0, 3);
        scatter_z_fastest(&file[3 * plane..], &mut out, [nx, ny, nz], 3, 2);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    assert_eq!(out[(k * ny + j) * nx + i], f(i, j, k), "({i}, {j}, {k})");
                }
            }
        }
    }
}
