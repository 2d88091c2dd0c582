//! NumPy `.npy` files: the header (version 1 to 3, dtype, order, shape) and the cells, decoded
//! into numbers for the 2-D grid reader (`matrix`) and the 3-D volume reader (`volume`).

use std::io::Read;
use std::path::Path;

use super::load::LoadError;
use crate::spec::DataFormat;

/// The shapes a reader takes: how many dimensions, and at most how many cells.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    /// The number of dimensions required (0: any).
    pub dims: usize,
    /// The most cells accepted, checked before allocating.
    pub max_cells: usize,
    /// What the array is read as, for the error ("a grid", "a volume").
    pub what: &'static str,
}

/// An array read from a `.npy` file: its shape and its values as numbers, in C order (last axis
/// fastest) whatever the file's order.
#[derive(Clone, Debug, PartialEq)]
pub struct NpyArray {
    /// The shape as numpy gives it.
    pub dims: Vec<usize>,
    /// `dims.iter().product()` values, C order.
    pub values: Vec<f64>,
}

fn npy_error(path: &Path, message: impl Into<String>) -> LoadError {
    LoadError::Parse { origin: format!("`{}`", path.display()), format: DataFormat::Npy, message: message.into() }
}

/// Read a `.npy` array of integers or floats of `shape` (any byte order, C or Fortran order; the
/// file may be gzip- or zstd-compressed). An uncompressed file is decoded as it is read, a few
/// megabytes at a time, into the one vector of values: no copy of the whole file is held.
pub fn read(path: &Path, shape: Shape) -> Result<NpyArray, LoadError> {
    if super::compressed::Compression::of(path).is_some() {
        let bytes = super::compressed::read_bytes(path)?;
        return parse(&bytes, shape).map_err(|m| npy_error(path, m));
    }
    let mut file = super::regular_file::open(path).map_err(|e| LoadError::from_io(path, e))?;
    let file_len = file.metadata().map_err(|e| LoadError::from_io(path, e))?.len();
    let mut head = vec![0u8; HEADER_PREFIX.min(usize::try_from(file_len).unwrap_or(HEADER_PREFIX))];
    file.read_exact(&mut head).map_err(|e| LoadError::from_io(path, e))?;
    let header = Header::parse(&head, shape).map_err(|m| npy_error(path, m))?;
    let wanted = header.data_bytes();
    let available = file_len.saturating_sub(header.data_start as u64);
    if available < wanted as u64 {
        return Err(npy_error(path, header.short_data(available)));
    }
    // The cells read with the header, then the rest of the file, in chunks of whole cells.
    let mut cells = head.get(header.data_start..).unwrap_or(&[]).chain(file).take(wanted as u64);
    let mut values = Vec::with_capacity(header.cells);
    let mut chunk = vec![0u8; (READ_CHUNK / header.size).max(1) * header.size];
    let mut left = wanted;
    while left > 0 {
        let take = chunk.len().min(left);
        cells.read_exact(&mut chunk[..take]).map_err(|e| LoadError::from_io(path, e))?;
        header.decode_into(&chunk[..take], &mut values);
        left -= take;
    }
    Ok(header.finish(values))
}

/// Bytes read for the header before its length is known (the cells after it are kept).
const HEADER_PREFIX: usize = 64 * 1024;
/// Bytes of cells decoded at a time.
const READ_CHUNK: usize = 4 * 1024 * 1024;

/// Bytes at the start of a `.npy` file that say how long its header is.
pub(crate) const PREFIX: usize = 12;

/// The length of the header dict and where it starts, from the magic bytes and version at the
/// start of `bytes` (the first [`PREFIX`] bytes are enough).
pub(crate) fn header_extent(bytes: &[u8]) -> Result<(usize, usize), String> {
    if bytes.get(..6) != Some(b"\x93NUMPY") {
        return Err("not a NumPy .npy file (bad magic bytes)".into());
    }
    let major = *bytes.get(6).ok_or("truncated header")?;
    match major {
        1 => Ok((
            u16::from_le_bytes([*bytes.get(8).ok_or("truncated header")?, *bytes.get(9).ok_or("truncated header")?])
                as usize,
            10,
        )),
        2 | 3 => {
            let b = bytes.get(8..12).ok_or("truncated header")?;
            Ok((u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize, 12))
        }
        v => Err(format!("unsupported .npy version {v}")),
    }
}

/// What a `.npy` header says: the shape, the dtype and where the cells start.
pub(crate) struct Header {
    /// The shape as numpy gives it.
    pub(crate) dims: Vec<usize>,
    /// The number of cells.
    pub(crate) cells: usize,
    /// Bytes per cell.
    pub(crate) size: usize,
    /// Whether the first axis varies fastest in the file.
    pub(crate) fortran: bool,
    /// The dtype as written (`<u2`).
    pub(crate) descr: String,
    /// Where the cells start in the file.
    pub(crate) data_start: usize,
    /// The cell type.
    pub(crate) dtype: Dtype,
}

impl Header {
    /// Parse the magic bytes, version and header dict at the start of `bytes`.
    pub(crate) fn parse(bytes: &[u8], want: Shape) -> Result<Header, String> {
        let (len, start) = header_extent(bytes)?;
        let header = std::str::from_utf8(bytes.get(start..start + len).ok_or("truncated header")?)
            .map_err(|_| "header is not text".to_string())?;
        let descr = dict_value(header, "descr").ok_or("header has no 'descr'")?;
        let descr = descr.trim_matches(|c| c == '\'' || c == '"');
        let fortran = dict_value(header, "fortran_order").map(|v| v.starts_with("True")).unwrap_or(false);
        let shape = dict_value(header, "shape").ok_or("header has no 'shape'")?;
        let dims: Vec<usize> = shape
            .trim_matches(|c| c == '(' || c == ')')
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(|s| s.parse::<usize>().map_err(|_| format!("bad shape {shape}")))
            .collect::<Result<_, _>>()?;
        if want.dims != 0 && dims.len() != want.dims {
            return Err(format!("the array has shape {shape}; {} needs a {}-D array", want.what, want.dims));
        }
        let sizes: Vec<String> = dims.iter().map(usize::to_string).collect();
        let cells = dims
            .iter()
            .try_fold(1usize, |n, &d| n.checked_mul(d))
            .filter(|&n| n <= want.max_cells)
            .ok_or(format!("the array has {} cells, more than {}", sizes.join(" × "), want.max_cells))?;
        let (little, kind, size) = {
            let mut chars = descr.chars();
            let order = chars.next().ok_or("empty dtype")?;
            let kind = chars.next().ok_or("bad dtype")?;
            let size: usize = chars
                .as_str()
                .parse()
                .ok()
                .filter(|s| [1, 2, 4, 8].contains(s))
                .ok_or(format!("unsupported dtype {descr}; use float or integer arrays"))?;
            (order != '>', kind, size)
        };
        let dtype = Dtype { kind, size, little };
        if !dtype.is_known() {
            return Err(format!("unsupported dtype {descr}; use float or integer arrays"));
        }
        Ok(Header { dims, cells, size, fortran, descr: descr.to_string(), data_start: start + len, dtype })
    }

    /// Bytes of cell data the shape and dtype call for.
    pub(crate) fn data_bytes(&self) -> usize {
        self.cells * self.size
    }

    /// The error for a file with only `available` bytes of cells.
    pub(crate) fn short_data(&self, available: u64) -> String {
        let sizes: Vec<String> = self.dims.iter().map(usize::to_string).collect();
        format!(
            "the data has {available} bytes, {} expected for {} {}",
            self.data_bytes(),
            sizes.join(" × "),
            self.descr
        )
    }

    /// Decode whole cells of `data` onto `values`.
    fn decode_into(&self, data: &[u8], values: &mut Vec<f64>) {
        self.dtype.decode(data, values);
    }

    /// The array of the decoded cells, reordered to C order if the file is in Fortran order.
    fn finish(self, values: Vec<f64>) -> NpyArray {
        if !self.fortran || self.dims.len() < 2 {
            return NpyArray { dims: self.dims, values };
        }
        // Fortran order: the first axis fastest. Walk the C-order index and read the Fortran one.
        let mut out = vec![0.0; self.cells];
        let mut strides = vec![1usize; self.dims.len()];
        for k in 1..self.dims.len() {
            strides[k] = strides[k - 1] * self.dims[k - 1];
        }
        let mut at = vec![0usize; self.dims.len()];
        for dst in out.iter_mut() {
            let src: usize = at.iter().zip(&strides).map(|(i, s)| i * s).sum();
            *dst = values.get(src).copied().unwrap_or(f64::NAN);
            for k in (0..self.dims.len()).rev() {
                at[k] += 1;
                if at[k] < self.dims[k] {
                    break;
                }
                at[k] = 0;
            }
        }
        NpyArray { dims: self.dims, values: out }
    }
}

/// Parse `.npy` bytes into an array of `shape`; the error is a message for the user.
pub fn parse(bytes: &[u8], shape: Shape) -> Result<NpyArray, String> {
    let header = Header::parse(bytes, shape)?;
    let data = bytes.get(header.data_start..).ok_or("truncated data")?;
    if data.len() < header.data_bytes() {
        return Err(header.short_data(data.len() as u64));
    }
    let mut values = Vec::with_capacity(header.cells);
    header.decode_into(&data[..header.data_bytes()], &mut values);
    Ok(header.finish(values))
}

/// A cell type numpy writes: kind `f`, `i` or `u`, `size` bytes, little- or big-endian.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dtype {
    /// `f`, `i` or `u`.
    pub(crate) kind: char,
    /// Bytes per cell.
    pub(crate) size: usize,
    /// Whether the bytes are little-endian.
    pub(crate) little: bool,
}

/// Expands to one monomorphic decoding loop per dtype, so the loop over the cells neither
/// branches on the dtype nor calls through a pointer.
macro_rules! decode_as {
    ($dtype:expr, $data:expr, $values:expr, $(($kind:literal, $t:ty, $n:literal)),* $(,)?) => {
        match ($dtype.kind, $dtype.size, $dtype.little) {
            $(
                ($kind, $n, true) => $values.extend(
                    $data.chunks_exact($n).map(|c| <[u8; $n]>::try_from(c).map_or(f64::NAN, |b| <$t>::from_le_bytes(b) as f64)),
                ),
                ($kind, $n, false) => $values.extend(
                    $data.chunks_exact($n).map(|c| <[u8; $n]>::try_from(c).map_or(f64::NAN, |b| <$t>::from_be_bytes(b) as f64)),
                ),
            )*
            _ => return false,
        }
    };
}

impl Dtype {
    /// Whether dataink reads this dtype.
    fn is_known(self) -> bool {
        self.decode(&[], &mut Vec::new())
    }

    /// Decode whole cells of `data` onto `values`; `false` for a dtype not read.
    fn decode(self, data: &[u8], values: &mut Vec<f64>) -> bool {
        decode_as!(
            self,
            data,
            values,
            ('f', f64, 8),
            ('f', f32, 4),
            ('i', i64, 8),
            ('i', i32, 4),
            ('i', i16, 2),
            ('i', i8, 1),
            ('u', u64, 8),
            ('u', u32, 4),
            ('u', u16, 2),
            ('u', u8, 1),
        );
        true
    }
}

/// The text after `'key':` in a Python dict literal, up to the next top-level comma.
fn dict_value<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let at = header.find(&format!("'{key}'"))? + key.len() + 2;
    let rest = header.get(at..)?.trim_start().strip_prefix(':')?.trim_start();
    let mut depth = 0i32;
    for (i, c) in rest.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    Some(rest.trim())
}

/// A version-1 `.npy` file of `descr` cells (`<f8`, `>u2`, ...) with the given raw cell bytes, for
/// tests.
#[cfg(test)]
pub(crate) fn test_file(descr: &str, fortran: bool, shape: &str, data: &[u8]) -> Vec<u8> {
    let mut header = format!(
        "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
        if fortran { "True" } else { "False" }
    );
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}
