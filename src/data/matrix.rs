//! Grid files: 2-D NumPy arrays (`.npy`) and headerless CSV matrices, read into a long-form
//! [`Table`] with columns `x`, `y` and `value` (one row per grid node), which the grid chart
//! kinds (`contour`, `image`, `section`, `surface`) read like any other long-form table.
//!
//! Column `j` of the matrix lies at x index `j` and row `i` at y index `i` (y grows with the row
//! index); `extent = [x_first, x_last, y_first, y_last]` maps the indices linearly to coordinates.

use std::path::Path;

use super::load::LoadError;
use super::table::{Column, ColumnValues, GridAxis, Table};

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

/// How a grid is read from a `.npy` file.
const GRID: super::npy::Shape = super::npy::Shape { dims: 2, max_cells: MAX_CELLS, what: "a grid" };

/// Read a 2-D `.npy` array of integers or floats as a matrix (any byte order, C or Fortran
/// order; the file may be gzip- or zstd-compressed).
pub fn read_npy(path: &Path) -> Result<Matrix, LoadError> {
    super::npy::read(path, GRID).map(matrix_of)
}

/// Parse `.npy` bytes into a matrix; the error is a message for the user.
pub fn parse_npy(bytes: &[u8]) -> Result<Matrix, String> {
    super::npy::parse(bytes, GRID).map(matrix_of)
}

fn matrix_of(array: super::npy::NpyArray) -> Matrix {
    let (rows, cols) = (array.dims.first().copied().unwrap_or(0), array.dims.get(1).copied().unwrap_or(0));
    Matrix { rows, cols, values: array.values }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A version-1 .npy file of little-endian f8 values.
    fn npy(shape: &str, fortran: bool, values: &[f64]) -> Vec<u8> {
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        crate::data::npy::test_file("<f8", fortran, shape, &data)
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
