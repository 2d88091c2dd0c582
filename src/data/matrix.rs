//! Grid files: 2-D NumPy arrays (`.npy`) and headerless CSV matrices, read into a long-form
//! [`Table`] with columns `x`, `y` and `value` (one row per grid node), which the grid chart
//! kinds (`contour`, `image`, `section`, `surface`) read like any other long-form table.
//!
//! Column `j` of the matrix lies at x index `j` and row `i` at y index `i` (y grows with the row
//! index); `extent = [x_first, x_last, y_first, y_last]` maps the indices linearly to coordinates.

use std::io::Read;
use std::path::Path;

use super::load::LoadError;
use super::table::{Column, ColumnValues, GridAxis, Table};
use crate::spec::DataFormat;

/// Largest matrix accepted (cells), checked before allocating.
pub const MAX_CELLS: usize = 50_000_000;

/// A dense row-major matrix of numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct Matrix {
    /// Number of rows (along y).
    pub rows: usize,
    /// Number of columns (along x).
    pub cols: usize,
    /// `rows * cols` values, row-major.
    pub values: Vec<f64>,
}

impl Matrix {
    /// The matrix as a long-form table `x, y, value` (its values moved, not copied; `x` and `y` as
    /// [`GridAxis`] columns, spread over the rows only if read row by row), with coordinates from `extent`
    /// (`[x_first, x_last, y_first, y_last]`) or the indices.
    pub fn to_table(self, extent: Option<[f64; 4]>) -> Table {
        let coord = |k: usize, n: usize, first: f64, last: f64| {
            if n <= 1 { first } else { first + (last - first) * k as f64 / (n - 1) as f64 }
        };
        let [x0, x1, y0, y1] =
            extent.unwrap_or([0.0, self.cols.saturating_sub(1) as f64, 0.0, self.rows.saturating_sub(1) as f64]);
        let n = self.rows * self.cols;
        let xs = (0..self.cols).map(|j| coord(j, self.cols, x0, x1)).collect();
        let ys = (0..self.rows).map(|i| coord(i, self.rows, y0, y1)).collect();
        Table {
            columns: vec![
                Column { name: "x".into(), values: ColumnValues::Axis(GridAxis::new(xs, 1, n)) },
                Column { name: "y".into(), values: ColumnValues::Axis(GridAxis::new(ys, self.cols, n)) },
                Column { name: "value".into(), values: ColumnValues::Number(self.values) },
            ],
            rows: n,
        }
    }
}

fn npy_error(path: &Path, message: impl Into<String>) -> LoadError {
    LoadError::Parse { origin: format!("`{}`", path.display()), format: DataFormat::Npy, message: message.into() }
}

/// Read a 2-D `.npy` array of integers or floats (any byte order, C or Fortran order; the file
/// may be gzip- or zstd-compressed). An uncompressed file is decoded as it is read, a few
/// megabytes at a time, into the one vector of values: no copy of the whole file is held.
pub fn read_npy(path: &Path) -> Result<Matrix, LoadError> {
    if super::compressed::Compression::of(path).is_some() {
        let bytes = super::compressed::read_bytes(path)?;
        return parse_npy(&bytes).map_err(|m| npy_error(path, m));
    }
    let mut file = super::regular_file::open(path).map_err(|e| LoadError::from_io(path, e))?;
    let file_len = file.metadata().map_err(|e| LoadError::from_io(path, e))?.len();
    let mut head = vec![0u8; HEADER_PREFIX.min(usize::try_from(file_len).unwrap_or(HEADER_PREFIX))];
    file.read_exact(&mut head).map_err(|e| LoadError::from_io(path, e))?;
    let header = Header::parse(&head).map_err(|m| npy_error(path, m))?;
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

/// What a `.npy` header says: the shape, the dtype and where the cells start.
struct Header {
    rows: usize,
    cols: usize,
    cells: usize,
    size: usize,
    fortran: bool,
    descr: String,
    data_start: usize,
    dtype: Dtype,
}

impl Header {
    /// Parse the magic bytes, version and header dict at the start of `bytes`.
    fn parse(bytes: &[u8]) -> Result<Header, String> {
        if bytes.get(..6) != Some(b"\x93NUMPY") {
            return Err("not a NumPy .npy file (bad magic bytes)".into());
        }
        let major = *bytes.get(6).ok_or("truncated header")?;
        let (len, start) = match major {
            1 => (
                u16::from_le_bytes([*bytes.get(8).ok_or("truncated header")?, *bytes.get(9).ok_or("truncated header")?])
                    as usize,
                10,
            ),
            2 | 3 => {
                let b = bytes.get(8..12).ok_or("truncated header")?;
                (u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize, 12)
            }
            v => return Err(format!("unsupported .npy version {v}")),
        };
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
        let [rows, cols] = dims[..] else {
            return Err(format!("the array has shape {shape}; a grid needs a 2-D array"));
        };
        let cells = rows
            .checked_mul(cols)
            .filter(|&n| n <= MAX_CELLS)
            .ok_or(format!("the array has {rows} × {cols} cells, more than {MAX_CELLS}"))?;
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
        Ok(Header { rows, cols, cells, size, fortran, descr: descr.to_string(), data_start: start + len, dtype })
    }

    /// Bytes of cell data the shape and dtype call for.
    fn data_bytes(&self) -> usize {
        self.cells * self.size
    }

    /// The error for a file with only `available` bytes of cells.
    fn short_data(&self, available: u64) -> String {
        format!(
            "the data has {available} bytes, {} expected for {} × {} {}",
            self.data_bytes(),
            self.rows,
            self.cols,
            self.descr
        )
    }

    /// Decode whole cells of `data` onto `values`.
    fn decode_into(&self, data: &[u8], values: &mut Vec<f64>) {
        self.dtype.decode(data, values);
    }

    /// The matrix of the decoded cells, transposed to row-major if the file is column-major.
    fn finish(&self, mut values: Vec<f64>) -> Matrix {
        let (rows, cols) = (self.rows, self.cols);
        if self.fortran {
            let mut t = vec![0.0; self.cells];
            for j in 0..cols {
                for i in 0..rows {
                    if let (Some(dst), Some(&src)) = (t.get_mut(i * cols + j), values.get(j * rows + i)) {
                        *dst = src;
                    }
                }
            }
            values = t;
        }
        Matrix { rows, cols, values }
    }
}

/// Parse `.npy` bytes into a matrix; the error is a message for the user.
pub fn parse_npy(bytes: &[u8]) -> Result<Matrix, String> {
    let header = Header::parse(bytes)?;
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
struct Dtype {
    kind: char,
    size: usize,
    little: bool,
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A version-1 .npy file of little-endian f8 values.
    fn npy(shape: &str, fortran: bool, values: &[f64]) -> Vec<u8> {
        let mut header = format!(
            "{{'descr': '<f8', 'fortran_order': {}, 'shape': {shape}, }}",
            if fortran { "True" } else { "False" }
        );
        while (10 + header.len() + 1) % 64 != 0 {
            header.push(' ');
        }
        header.push('\n');
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        for v in values {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out
    }

    #[test]
    fn zero_or_huge_item_sizes_are_refused_not_panics() {
        let good = npy("(2, 2)", false, &[1.0, 2.0, 3.0, 4.0]);
        // Same-length edits of the descr keep the header length valid; only 1, 2, 4, 8 are sizes.
        for bad in ["<f0", "<f9", "<u3"] {
            let mut bytes = good.clone();
            let at = bytes.windows(3).position(|w| w == b"<f8").expect("descr");
            bytes[at..at + 3].copy_from_slice(bad.as_bytes());
            let err = parse_npy(&bytes).expect_err(bad);
            assert!(err.contains("unsupported dtype"), "{bad}: {err}");
        }
    }

    /// A version-1 .npy file of `descr` with the given raw cell bytes.
    fn npy_raw(descr: &str, shape: &str, data: &[u8]) -> Vec<u8> {
        let good = npy(shape, false, &[]);
        let mut out = String::from_utf8_lossy(&good[10..]).replace("<f8", descr).into_bytes();
        let mut bytes = good[..10].to_vec();
        bytes.append(&mut out);
        bytes.extend_from_slice(data);
        bytes
    }

    #[test]
    fn every_dtype_in_both_byte_orders_reads_its_values() {
        let values = [-7.0f64, 0.0, 1.0, 100.0];
        let unsigned = [0.0f64, 1.0, 7.0, 200.0];
        macro_rules! check {
            ($t:ty, $code:literal, $vals:expr) => {
                for (order, big) in [("<", false), (">", true)] {
                    let data: Vec<u8> = $vals
                        .iter()
                        .flat_map(|&v| {
                            let v = v as $t;
                            if big { v.to_be_bytes().to_vec() } else { v.to_le_bytes().to_vec() }
                        })
                        .collect();
                    let descr = format!("{order}{}", $code);
                    let m = parse_npy(&npy_raw(&descr, "(2, 2)", &data)).unwrap_or_else(|e| panic!("{descr}: {e}"));
                    assert_eq!(m.values, $vals.to_vec(), "{descr}");
                }
            };
        }
        check!(f64, "f8", values);
        check!(f32, "f4", values);
        check!(i64, "i8", values);
        check!(i32, "i4", values);
        check!(i16, "i2", values);
        check!(i8, "i1", values);
        check!(u64, "u8", unsigned);
        check!(u32, "u4", unsigned);
        check!(u16, "u2", unsigned);
        check!(u8, "u1", unsigned);
    }

    #[test]
    fn c_and_fortran_order_read_the_same_matrix() {
        let c = parse_npy(&npy("(2, 3)", false, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0])).expect("C order");
        let f = parse_npy(&npy("(2, 3)", true, &[1.0, 4.0, 2.0, 5.0, 3.0, 6.0])).expect("Fortran order");
        assert_eq!(c, Matrix { rows: 2, cols: 3, values: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0] });
        assert_eq!(c, f);
    }

    #[test]
    fn bad_files_give_clear_messages() {
        assert_eq!(parse_npy(b"PK\x03\x04"), Err("not a NumPy .npy file (bad magic bytes)".into()));
        assert_eq!(
            parse_npy(&npy("(2, 2, 2)", false, &[0.0; 8])),
            Err("the array has shape (2, 2, 2); a grid needs a 2-D array".into())
        );
        let short = npy("(3, 3)", false, &[0.0; 4]);
        assert_eq!(parse_npy(&short), Err("the data has 32 bytes, 72 expected for 3 × 3 <f8".into()));
    }

    #[test]
    fn extent_maps_indices_to_coordinates() {
        let m = Matrix { rows: 2, cols: 3, values: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0] };
        let t = m.clone().to_table(Some([10.0, 20.0, -1.0, 1.0]));
        assert_eq!(t.column("x").and_then(|c| c.numbers()), Some(&[10.0, 15.0, 20.0, 10.0, 15.0, 20.0][..]));
        assert_eq!(t.column("y").and_then(|c| c.numbers()), Some(&[-1.0, -1.0, -1.0, 1.0, 1.0, 1.0][..]));
        assert_eq!(t.column("value").and_then(|c| c.numbers()), Some(&m.values[..]));
    }

    #[test]
    fn files_are_read_in_chunks_to_the_same_matrix_as_their_bytes() {
        let dir = tempfile::tempdir().expect("temp dir");
        // Over two read chunks of f4 cells, C and Fortran order; a small file; a file cut short.
        let (rows, cols) = (1100, 1000);
        let data: Vec<u8> = (0..rows * cols).flat_map(|k| ((k % 977) as f32 - 300.5).to_le_bytes()).collect();
        let shape = format!("({rows}, {cols})");
        for (name, bytes) in [
            ("big.npy", npy_raw("<f4", &shape, &data)),
            ("fortran.npy", as_fortran(npy_raw("<f4", &shape, &data))),
            ("small.npy", npy("(2, 3)", false, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0])),
        ] {
            let path = dir.path().join(name);
            std::fs::write(&path, &bytes).expect("write");
            assert_eq!(read_npy(&path).expect(name), parse_npy(&bytes).expect(name), "{name}");
        }
        let path = dir.path().join("short.npy");
        let bytes = npy_raw("<f4", &shape, &data);
        std::fs::write(&path, &bytes[..bytes.len() - 5]).expect("write");
        let err = read_npy(&path).expect_err("short file").to_string();
        assert!(err.contains("the data has 4399995 bytes, 4400000 expected for 1100 × 1000 <f4"), "{err}");
    }

    /// The same file marked column-major (the header keeps its length).
    fn as_fortran(mut bytes: Vec<u8>) -> Vec<u8> {
        let (from, to) = (b"'fortran_order': False", b"'fortran_order': True ");
        let at = bytes.windows(from.len()).position(|w| w == from).expect("a C-order header");
        bytes[at..at + to.len()].copy_from_slice(to);
        bytes
    }
}
