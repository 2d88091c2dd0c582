//! A regular 2D scalar grid: one value at each node of a rectilinear lattice.
//!
//! The lattice has `nx` columns at the strictly increasing x coordinates `xs` and `ny` rows at the
//! strictly increasing y coordinates `ys` (spacing need not be uniform). Values are stored row
//! by row: the value at node `(i, j)`, that is at `(xs[i], ys[j])`, is `values[j * nx + i]`.
//!
//! Missing data: any non-finite value (NaN, +inf, −inf) is stored as NaN and means "no value
//! here". A cell (the rectangle between four neighbouring nodes) with a missing corner is a hole:
//! interpolation returns NaN there and contouring leaves it empty.

use std::fmt;

/// Largest number of nodes [`Grid::new`] accepts (2³⁰ ≈ 1.07 × 10⁹): node, cell and edge ids
/// then fit in a `u32`.
pub const MAX_NODES: usize = 1 << 30;

/// One of the two grid axes, named in [`GridError`] messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// The column coordinates `xs`.
    X,
    /// The row coordinates `ys`.
    Y,
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Axis::X => "x",
            Axis::Y => "y",
        })
    }
}

/// Why a [`Grid`] could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum GridError {
    /// An axis has no coordinates.
    EmptyAxis {
        /// The empty axis.
        axis: Axis,
    },
    /// An axis coordinate is NaN or infinite.
    NonFiniteCoordinate {
        /// The axis holding it.
        axis: Axis,
        /// Its position on the axis.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// An axis coordinate is not greater than the one before it.
    NotIncreasing {
        /// The axis holding it.
        axis: Axis,
        /// Its position on the axis.
        index: usize,
        /// The coordinate before it.
        previous: f64,
        /// The offending value.
        value: f64,
    },
    /// The number of values is not `nx * ny`.
    ValueCount {
        /// Number of columns (length of `xs`).
        nx: usize,
        /// Number of rows (length of `ys`).
        ny: usize,
        /// Number of values given.
        got: usize,
    },
    /// More than [`MAX_NODES`] nodes.
    TooLarge {
        /// Number of columns.
        nx: usize,
        /// Number of rows.
        ny: usize,
    },
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GridError::EmptyAxis { axis } => {
                write!(f, "the grid's {axis} axis has no coordinates; give at least one")
            }
            GridError::NonFiniteCoordinate { axis, index, value } => {
                write!(f, "grid coordinate {axis}[{index}] is {value}; coordinates must be finite numbers")
            }
            GridError::NotIncreasing { axis, index, previous, value } => write!(
                f,
                "grid coordinate {axis}[{index}] = {value} is not greater than {axis}[{}] = \
                 {previous}; coordinates must be strictly increasing (sort them and drop \
                 duplicates)",
                index.saturating_sub(1)
            ),
            GridError::ValueCount { nx, ny, got } => write!(
                f,
                "the grid has {nx} x {ny} = {} nodes but {got} values were given; give one \
                 value per node, row by row",
                nx.saturating_mul(*ny)
            ),
            GridError::TooLarge { nx, ny } => write!(
                f,
                "a {nx} x {ny} grid has more than {MAX_NODES} nodes; resample it to a coarser \
                 grid"
            ),
        }
    }
}

impl std::error::Error for GridError {}

/// A regular (rectilinear) 2D grid of scalar values; see the module docs for the layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    nx: usize,
    ny: usize,
    xs: Vec<f64>,
    ys: Vec<f64>,
    values: Vec<f64>,
}

impl Grid {
    /// Builds a grid from column coordinates `xs`, row coordinates `ys` and `xs.len() *
    /// ys.len()` values in row-major order (`values[j * nx + i]` sits at `(xs[i], ys[j])`).
    ///
    /// Coordinates must be finite and strictly increasing. Non-finite values (NaN, ±inf) are
    /// accepted and stored as NaN, meaning "missing". A 1 × 1 or 1 × N grid is valid; it just
    /// has no cells.
    pub fn new(xs: Vec<f64>, ys: Vec<f64>, mut values: Vec<f64>) -> Result<Grid, GridError> {
        check_axis(Axis::X, &xs)?;
        check_axis(Axis::Y, &ys)?;
        let (nx, ny) = (xs.len(), ys.len());
        let nodes = match nx.checked_mul(ny) {
            Some(n) if n <= MAX_NODES => n,
            _ => return Err(GridError::TooLarge { nx, ny }),
        };
        if values.len() != nodes {
            return Err(GridError::ValueCount { nx, ny, got: values.len() });
        }
        for v in &mut values {
            if !v.is_finite() {
                *v = f64::NAN;
            }
        }
        Ok(Grid { nx, ny, xs, ys, values })
    }

    /// Builds a grid by evaluating `f(x, y)` at every node.
    pub fn from_fn(xs: Vec<f64>, ys: Vec<f64>, mut f: impl FnMut(f64, f64) -> f64) -> Result<Grid, GridError> {
        check_axis(Axis::X, &xs)?;
        check_axis(Axis::Y, &ys)?;
        match xs.len().checked_mul(ys.len()) {
            Some(n) if n <= MAX_NODES => {}
            _ => {
                return Err(GridError::TooLarge { nx: xs.len(), ny: ys.len() });
            }
        }
        let values = ys.iter().flat_map(|&y| xs.iter().map(move |&x| (x, y))).map(|(x, y)| f(x, y)).collect();
        Grid::new(xs, ys, values)
    }

    /// Number of columns (nodes along x).
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Number of rows (nodes along y).
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Column coordinates, strictly increasing.
    pub fn xs(&self) -> &[f64] {
        &self.xs
    }

    /// Row coordinates, strictly increasing.
    pub fn ys(&self) -> &[f64] {
        &self.ys
    }

    /// All values, row by row; missing values are NaN, never ±inf.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The value at node `(i, j)`, i.e. at `(xs[i], ys[j])`; NaN when the value is missing or
    /// the node is outside the grid.
    pub fn value(&self, i: usize, j: usize) -> f64 {
        if i >= self.nx || j >= self.ny {
            return f64::NAN;
        }
        self.values.get(j * self.nx + i).copied().unwrap_or(f64::NAN)
    }

    /// Smallest and largest non-missing value, or `None` when every value is missing.
    pub fn range(&self) -> Option<(f64, f64)> {
        let mut it = self.values.iter().copied().filter(|v| !v.is_nan());
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v))))
    }

    /// Bilinear interpolation at `(x, y)`: within the cell `[x_i, x_{i+1}] × [y_j, y_{j+1}]`,
    /// with `s = (x − x_i) / (x_{i+1} − x_i)` and `t = (y − y_j) / (y_{j+1} − y_j)`,
    /// `f = f00 (1−s)(1−t) + f10 s (1−t) + f01 (1−s) t + f11 s t` where `f10` is the value at
    /// `(x_{i+1}, y_j)` and `f01` the one at `(x_i, y_{j+1})`.
    ///
    /// NaN outside the grid, for a NaN coordinate, and in a cell with a missing corner. Along an
    /// axis with a single coordinate, only that coordinate is inside (linear along the other).
    pub fn bilinear(&self, x: f64, y: f64) -> f64 {
        let (Some((i0, i1, s)), Some((j0, j1, t))) = (locate(&self.xs, x), locate(&self.ys, y)) else {
            return f64::NAN;
        };
        let f00 = self.value(i0, j0);
        let f10 = self.value(i1, j0);
        let f01 = self.value(i0, j1);
        let f11 = self.value(i1, j1);
        let bottom = f00 + s * (f10 - f00);
        let top = f01 + s * (f11 - f01);
        let v = bottom + t * (top - bottom);
        if v.is_finite() || v.is_nan() {
            return v;
        }
        // Differences overflowed: use the convex form, which stays finite for finite corners.
        let bottom = (1.0 - s) * f00 + s * f10;
        let top = (1.0 - s) * f01 + s * f11;
        (1.0 - t) * bottom + t * top
    }
}

/// Checks that an axis is non-empty, finite and strictly increasing.
fn check_axis(axis: Axis, coords: &[f64]) -> Result<(), GridError> {
    if coords.is_empty() {
        return Err(GridError::EmptyAxis { axis });
    }
    let mut previous = f64::NEG_INFINITY;
    for (index, &value) in coords.iter().enumerate() {
        if !value.is_finite() {
            return Err(GridError::NonFiniteCoordinate { axis, index, value });
        }
        if index > 0 && value <= previous {
            return Err(GridError::NotIncreasing { axis, index, previous, value });
        }
        previous = value;
    }
    Ok(())
}

/// Finds the interval `[a[i0], a[i1]]` holding `x` and the fraction `s` of the way across it.
/// `None` outside `[a[0], a[n-1]]` or for NaN; on a single-coordinate axis `i0 == i1`.
fn locate(axis: &[f64], x: f64) -> Option<(usize, usize, f64)> {
    let (&first, &last) = (axis.first()?, axis.last()?);
    if !(x >= first && x <= last) {
        return None;
    }
    if axis.len() == 1 {
        return Some((0, 0, 0.0));
    }
    let i0 = axis.partition_point(|&a| a <= x).saturating_sub(1).min(axis.len() - 2);
    let (a, b) = (*axis.get(i0)?, *axis.get(i0 + 1)?);
    Some((i0, i0 + 1, fraction(a, b, x)))
}

/// `(x − a) / (b − a)` clamped to `[0, 1]`, without overflow when `b − a` exceeds `f64::MAX`.
pub(crate) fn fraction(a: f64, b: f64, x: f64) -> f64 {
    let (num, den) = (x - a, b - a);
    let s = if num.is_finite() && den.is_finite() { num / den } else { (0.5 * x - 0.5 * a) / (0.5 * b - 0.5 * a) };
    if s.is_nan() { 0.5 } else { s.clamp(0.0, 1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(n: usize, h: f64) -> Vec<f64> {
        (0..n).map(|i| i as f64 * h).collect()
    }

    #[test]
    fn layout_is_row_major() {
        let g = Grid::new(vec![0.0, 1.0, 2.0], vec![10.0, 20.0], vec![1., 2., 3., 4., 5., 6.]).unwrap();
        assert_eq!((g.nx(), g.ny()), (3, 2));
        assert_eq!(g.value(0, 0), 1.0);
        assert_eq!(g.value(2, 0), 3.0);
        assert_eq!(g.value(0, 1), 4.0);
        assert_eq!(g.value(2, 1), 6.0);
        assert!(g.value(3, 0).is_nan());
        assert!(g.value(0, 2).is_nan());
    }

    #[test]
    fn non_finite_values_are_missing() {
        let g =
            Grid::new(vec![0.0, 1.0], vec![0.0, 1.0], vec![f64::INFINITY, 1.0, f64::NEG_INFINITY, f64::NAN]).unwrap();
        assert!(g.value(0, 0).is_nan());
        assert!(g.value(0, 1).is_nan());
        assert_eq!(g.range(), Some((1.0, 1.0)));
        assert!(g.bilinear(0.5, 0.5).is_nan());
        let all_nan = Grid::new(vec![0.0], vec![0.0], vec![f64::NAN]).unwrap();
        assert_eq!(all_nan.range(), None);
    }

    #[test]
    fn errors_name_the_bad_value_and_the_fix() {
        let e = Grid::new(vec![], vec![0.0], vec![]).unwrap_err();
        assert_eq!(e, GridError::EmptyAxis { axis: Axis::X });
        assert!(e.to_string().contains("at least one"));

        let e = Grid::new(vec![0.0, f64::NAN], vec![0.0], vec![0.0; 2]).unwrap_err();
        assert!(matches!(e, GridError::NonFiniteCoordinate { axis: Axis::X, index: 1, .. }));
        assert!(e.to_string().contains("x[1] is NaN"), "{e}");

        let e = Grid::new(vec![0.0], vec![0.0, 2.0, 2.0], vec![0.0; 3]).unwrap_err();
        assert_eq!(e, GridError::NotIncreasing { axis: Axis::Y, index: 2, previous: 2.0, value: 2.0 });
        let msg = e.to_string();
        assert!(msg.contains("y[2] = 2") && msg.contains("strictly increasing"), "{msg}");

        let e = Grid::new(vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0; 3]).unwrap_err();
        assert_eq!(e, GridError::ValueCount { nx: 2, ny: 2, got: 3 });
        assert!(e.to_string().contains("4 nodes but 3 values"), "{e}");
    }

    #[test]
    fn too_large_is_refused_before_allocating() {
        // Both axes are small vectors, but their product overflows the node cap.
        let xs = axis(40_000, 1.0);
        let ys = axis(40_000, 1.0);
        let e = Grid::new(xs.clone(), ys.clone(), vec![]).unwrap_err();
        assert_eq!(e, GridError::TooLarge { nx: 40_000, ny: 40_000 });
        let mut calls = 0usize;
        let e = Grid::from_fn(xs, ys, |_, _| {
            calls += 1;
            0.0
        })
        .unwrap_err();
        assert!(matches!(e, GridError::TooLarge { .. }));
        assert_eq!(calls, 0);
    }

    #[test]
    fn bilinear_reproduces_bilinear_functions() {
        // f = 1 + 2x − 3y + 0.5xy is bilinear, so interpolation is exact on any lattice.
        let f = |x: f64, y: f64| 1.0 + 2.0 * x - 3.0 * y + 0.5 * x * y;
        let g = Grid::from_fn(vec![0.0, 0.5, 2.0, 3.0], vec![-1.0, 0.0, 4.0], f).unwrap();
        for &(x, y) in &[(0.0, -1.0), (0.3, 2.0), (1.7, -0.2), (3.0, 4.0), (2.0, 0.0)] {
            assert!((g.bilinear(x, y) - f(x, y)).abs() < 1e-12, "at ({x}, {y})");
        }
        assert!(g.bilinear(-0.1, 0.0).is_nan());
        assert!(g.bilinear(1.0, 4.5).is_nan());
        assert!(g.bilinear(f64::NAN, 0.0).is_nan());
    }

    #[test]
    fn bilinear_is_nan_only_in_cells_touching_a_hole() {
        let mut v = vec![1.0; 9];
        v[0] = f64::NAN; // node (0, 0): only cell (0, 0) touches it
        let g = Grid::new(vec![0.0, 1.0, 2.0], vec![0.0, 1.0, 2.0], v).unwrap();
        assert!(g.bilinear(0.5, 0.5).is_nan());
        assert_eq!(g.bilinear(1.5, 0.5), 1.0);
        assert_eq!(g.bilinear(1.5, 1.5), 1.0);
    }

    #[test]
    fn degenerate_axes_interpolate_along_the_other() {
        let g = Grid::new(vec![5.0], vec![0.0, 1.0, 2.0], vec![0.0, 10.0, 30.0]).unwrap();
        assert_eq!(g.bilinear(5.0, 1.5), 20.0);
        assert!(g.bilinear(5.1, 1.5).is_nan());
        let one = Grid::new(vec![1.0], vec![1.0], vec![7.0]).unwrap();
        assert_eq!(one.bilinear(1.0, 1.0), 7.0);
        assert_eq!(one.range(), Some((7.0, 7.0)));
    }

    #[test]
    fn fraction_survives_overflowing_spans() {
        assert_eq!(fraction(-f64::MAX, f64::MAX, 0.0), 0.5);
        assert_eq!(fraction(0.0, 4.0, 1.0), 0.25);
        assert_eq!(fraction(0.0, 4.0, 9.0), 1.0);
    }
}
