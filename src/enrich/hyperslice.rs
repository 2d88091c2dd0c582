//! Gridded data over more than two variables, and the axis-aligned 2D slices of a hyperslice
//! matrix.
//!
//! An [`NdGrid`] holds one value at each node of a rectilinear lattice in `d ≥ 2` dimensions. Each
//! axis has a name and strictly increasing coordinates. Values are stored row-major with the
//! **last axis fastest**: for axis lengths `n_0, …, n_{d−1}` the node with indices
//! `(i_0, …, i_{d−1})` sits at `values[((i_0 · n_1 + i_1) · n_2 + i_2) …]`. Non-finite values
//! (NaN, ±inf) are stored as NaN and mean "missing", as in [`Grid`].
//!
//! A hyperslice view shows, for a focus node, the 2D slice through every pair of axes with all
//! other axes held at the focus: [`NdGrid::slice`] builds one, [`slice_matrix`] all of them.
//!
//! Building from long-form rows ([`NdGrid::from_rows`]): the distinct coordinates of each axis
//! (sorted) form the lattice; each row fills one node. A node may appear at most once. Nodes
//! that no row gives are missing (NaN), but at most [`MAX_MISSING_FRACTION`] (half) of all nodes
//! may be missing: beyond that the rows are scattered points, not a grid. Coordinates match
//! exactly (`0.1` and `0.1000001` are different nodes); `-0.0` and `0.0` are the same.

use std::fmt;

use super::grid::{Grid, GridError};

/// Largest number of nodes an [`NdGrid`] may have (2²⁶ ≈ 6.7 × 10⁷, 512 MiB of values).
pub const MAX_NODES: usize = 1 << 26;

/// Largest number of axes (a hyperslice matrix of 16 axes already has 120 panels).
pub const MAX_AXES: usize = 16;

/// Largest fraction of the lattice's nodes that rows may leave missing in [`NdGrid::from_rows`].
pub const MAX_MISSING_FRACTION: f64 = 0.5;

/// Largest total number of nodes over all slices of a [`slice_matrix`].
pub const MAX_MATRIX_NODES: usize = 1 << 26;

/// Why an [`NdGrid`] or a slice of it could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum HypersliceError {
    /// The number of axis names differs from the number of coordinate columns.
    AxisCountMismatch {
        /// Number of axis names.
        names: usize,
        /// Number of coordinate columns.
        columns: usize,
    },
    /// Fewer than two axes.
    TooFewAxes {
        /// Number of axes given.
        dims: usize,
    },
    /// More than [`MAX_AXES`] axes.
    TooManyAxes {
        /// Number of axes given.
        dims: usize,
    },
    /// Two axes have the same name.
    DuplicateAxisName {
        /// The repeated name.
        name: String,
    },
    /// No rows (or, for [`NdGrid::new`], no coordinates on an axis).
    NoRows,
    /// A coordinate column has a different length from the values.
    RowCountMismatch {
        /// The axis.
        axis: String,
        /// Its number of coordinates.
        got: usize,
        /// The number of values.
        expected: usize,
    },
    /// A coordinate is NaN or infinite.
    NonFiniteCoordinate {
        /// The axis.
        axis: String,
        /// The row (or, for [`NdGrid::new`], the position on the axis).
        row: usize,
        /// The offending value.
        value: f64,
    },
    /// An axis of [`NdGrid::new`] has no coordinates.
    EmptyAxis {
        /// The axis.
        axis: String,
    },
    /// An axis of [`NdGrid::new`] is not strictly increasing.
    NotIncreasing {
        /// The axis.
        axis: String,
        /// Position of the offending coordinate.
        index: usize,
        /// The coordinate before it.
        previous: f64,
        /// The offending coordinate.
        value: f64,
    },
    /// [`NdGrid::new`] got a number of values different from the number of nodes.
    ValueCount {
        /// Number of nodes (product of the axis lengths).
        nodes: usize,
        /// Number of values given.
        got: usize,
    },
    /// The lattice has more than [`MAX_NODES`] nodes.
    TooLarge {
        /// Number of coordinates on each axis.
        shape: Vec<usize>,
    },
    /// More than [`MAX_MISSING_FRACTION`] of the lattice's nodes have no row.
    NotAGrid {
        /// Number of distinct coordinates on each axis.
        shape: Vec<usize>,
        /// Number of lattice nodes.
        nodes: usize,
        /// Number of rows.
        rows: usize,
    },
    /// Two rows give the same node.
    DuplicateNode {
        /// The node: each axis name with its coordinate.
        node: Vec<(String, f64)>,
        /// The first row giving it.
        first: usize,
        /// The second row giving it.
        second: usize,
    },
    /// An axis index is not below the number of axes.
    AxisOutOfRange {
        /// The index given.
        axis: usize,
        /// Number of axes.
        dims: usize,
    },
    /// A slice was asked for over the same axis twice.
    SameAxis {
        /// The axis index.
        axis: usize,
    },
    /// The focus has a different number of indices from the number of axes.
    FocusLength {
        /// Number of focus indices.
        got: usize,
        /// Number of axes.
        dims: usize,
    },
    /// A focus index is past the end of its axis.
    FocusOutOfRange {
        /// The axis.
        axis: String,
        /// The index given.
        index: usize,
        /// Number of coordinates on the axis.
        len: usize,
    },
    /// The slices of a matrix would hold more than [`MAX_MATRIX_NODES`] nodes in all.
    MatrixTooLarge {
        /// Total number of slice nodes (saturating).
        nodes: usize,
    },
    /// A slice could not be made into a [`Grid`].
    Grid(GridError),
}

/// `name = value, …` for a node.
fn fmt_node(node: &[(String, f64)]) -> String {
    node.iter().map(|(n, v)| format!("{n} = {v}")).collect::<Vec<_>>().join(", ")
}

/// `a x b x c` for a shape.
fn fmt_shape(shape: &[usize]) -> String {
    shape.iter().map(usize::to_string).collect::<Vec<_>>().join(" x ")
}

impl fmt::Display for HypersliceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::AxisCountMismatch { names, columns } => {
                write!(f, "{names} axis names but {columns} coordinate columns; give one name per coordinate column")
            }
            Self::TooFewAxes { dims } => write!(
                f,
                "a hyperslice needs at least 2 axes, got {dims}; add coordinate columns (for one variable \
                 use a line chart)"
            ),
            Self::TooManyAxes { dims } => {
                write!(f, "{dims} axes is more than the {MAX_AXES} a hyperslice supports; choose fewer axes")
            }
            Self::DuplicateAxisName { name } => {
                write!(f, "the axis name {name:?} is used twice; give each axis its own column")
            }
            Self::NoRows => write!(f, "the grid has no data; give at least one row"),
            Self::RowCountMismatch { axis, got, expected } => write!(
                f,
                "axis {axis:?} has {got} coordinates but there are {expected} values; give one coordinate \
                 per row on every axis"
            ),
            Self::NonFiniteCoordinate { axis, row, value } => write!(
                f,
                "axis {axis:?} coordinate {row} is {value}; coordinates must be finite numbers (drop or fix \
                 that row)"
            ),
            Self::EmptyAxis { axis } => write!(f, "axis {axis:?} has no coordinates; give at least one"),
            Self::NotIncreasing { axis, index, previous, value } => write!(
                f,
                "axis {axis:?} coordinate {index} = {value} is not greater than the one before it ({previous}); \
                 coordinates must be strictly increasing (sort them and drop duplicates)"
            ),
            Self::ValueCount { nodes, got } => {
                write!(f, "the grid has {nodes} nodes but {got} values were given; give one value per node")
            }
            Self::TooLarge { shape } => write!(
                f,
                "a {} grid has more than {MAX_NODES} nodes; resample it to fewer coordinates per axis",
                fmt_shape(shape)
            ),
            Self::NotAGrid { shape, nodes, rows } => write!(
                f,
                "the rows do not form a grid: the distinct coordinates ({}) make {nodes} nodes but there are \
                 only {rows} rows, so {:.0}% of the nodes would be missing (at most {:.0}% may be); check \
                 that coordinates repeat exactly, or interpolate scattered data onto a grid first",
                fmt_shape(shape),
                100.0 * (nodes.saturating_sub(*rows)) as f64 / (*nodes).max(1) as f64,
                100.0 * MAX_MISSING_FRACTION
            ),
            Self::DuplicateNode { node, first, second } => write!(
                f,
                "rows {first} and {second} both give the node ({}); keep one row per node (aggregate \
                 duplicates first)",
                fmt_node(node)
            ),
            Self::AxisOutOfRange { axis, dims } => {
                write!(f, "axis {axis} does not exist: the grid has {dims} axes, numbered from 0")
            }
            Self::SameAxis { axis } => {
                write!(f, "a slice needs two different axes, got axis {axis} twice; choose another axis")
            }
            Self::FocusLength { got, dims } => {
                write!(f, "the focus has {got} indices but the grid has {dims} axes; give one index per axis")
            }
            Self::FocusOutOfRange { axis, index, len } => write!(
                f,
                "focus index {index} on axis {axis:?} is past its {len} coordinates; give an index below {len}"
            ),
            Self::MatrixTooLarge { nodes } => write!(
                f,
                "the slices of the hyperslice matrix would hold {nodes} nodes (at most {MAX_MATRIX_NODES}); \
                 use fewer axes or coarser ones"
            ),
            Self::Grid(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for HypersliceError {}

/// A rectilinear grid of scalar values over `d ≥ 2` named axes; see the module docs for the layout.
#[derive(Debug, Clone, PartialEq)]
pub struct NdGrid {
    axes: Vec<(String, Vec<f64>)>,
    values: Vec<f64>,
}

/// Checks the number of axes and that names are distinct.
fn check_names<'a>(names: impl Iterator<Item = &'a str> + Clone, dims: usize) -> Result<(), HypersliceError> {
    if dims < 2 {
        return Err(HypersliceError::TooFewAxes { dims });
    }
    if dims > MAX_AXES {
        return Err(HypersliceError::TooManyAxes { dims });
    }
    for (k, name) in names.clone().enumerate() {
        if names.clone().take(k).any(|other| other == name) {
            return Err(HypersliceError::DuplicateAxisName { name: name.to_string() });
        }
    }
    Ok(())
}

/// Product of the axis lengths, or `TooLarge` past [`MAX_NODES`].
fn node_count(shape: &[usize]) -> Result<usize, HypersliceError> {
    shape
        .iter()
        .try_fold(1usize, |acc, &n| acc.checked_mul(n))
        .filter(|&n| n <= MAX_NODES)
        .ok_or_else(|| HypersliceError::TooLarge { shape: shape.to_vec() })
}

impl NdGrid {
    /// Builds a grid from its axes (name and strictly increasing finite coordinates) and one value
    /// per node, last axis fastest. Non-finite values are stored as NaN (missing).
    pub fn new(axes: Vec<(String, Vec<f64>)>, mut values: Vec<f64>) -> Result<NdGrid, HypersliceError> {
        check_names(axes.iter().map(|(n, _)| n.as_str()), axes.len())?;
        for (name, coords) in &axes {
            if coords.is_empty() {
                return Err(HypersliceError::EmptyAxis { axis: name.clone() });
            }
            let mut previous = f64::NEG_INFINITY;
            for (index, &value) in coords.iter().enumerate() {
                if !value.is_finite() {
                    return Err(HypersliceError::NonFiniteCoordinate { axis: name.clone(), row: index, value });
                }
                if index > 0 && value <= previous {
                    return Err(HypersliceError::NotIncreasing { axis: name.clone(), index, previous, value });
                }
                previous = value;
            }
        }
        let shape: Vec<usize> = axes.iter().map(|(_, c)| c.len()).collect();
        let nodes = node_count(&shape)?;
        if values.len() != nodes {
            return Err(HypersliceError::ValueCount { nodes, got: values.len() });
        }
        for v in &mut values {
            if !v.is_finite() {
                *v = f64::NAN;
            }
        }
        Ok(NdGrid { axes, values })
    }

    /// Builds a grid from long-form rows: `coords[k][r]` is row `r`'s coordinate on the axis named
    /// `axis_names[k]`, and `values[r]` its value. See the module docs for how rows become nodes;
    /// the errors name the bad row or node.
    pub fn from_rows(axis_names: &[String], coords: &[&[f64]], values: &[f64]) -> Result<NdGrid, HypersliceError> {
        let dims = axis_names.len();
        if coords.len() != dims {
            return Err(HypersliceError::AxisCountMismatch { names: dims, columns: coords.len() });
        }
        check_names(axis_names.iter().map(String::as_str), dims)?;
        let rows = values.len();
        if rows == 0 {
            return Err(HypersliceError::NoRows);
        }
        for (name, column) in axis_names.iter().zip(coords) {
            if column.len() != rows {
                return Err(HypersliceError::RowCountMismatch {
                    axis: name.clone(),
                    got: column.len(),
                    expected: rows,
                });
            }
            if let Some((row, &value)) = column.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(HypersliceError::NonFiniteCoordinate { axis: name.clone(), row, value });
            }
        }
        // Distinct sorted coordinates per axis; `+ 0.0` turns −0 into +0.
        let axes: Vec<(String, Vec<f64>)> = axis_names
            .iter()
            .zip(coords)
            .map(|(name, column)| {
                let mut c: Vec<f64> = column.iter().map(|&v| v + 0.0).collect();
                c.sort_by(f64::total_cmp);
                c.dedup();
                (name.clone(), c)
            })
            .collect();
        let shape: Vec<usize> = axes.iter().map(|(_, c)| c.len()).collect();
        let nodes = node_count(&shape)?;
        // Without duplicates every row fills its own node, so this bounds the missing nodes exactly.
        let missing = nodes.saturating_sub(rows);
        if missing as f64 > MAX_MISSING_FRACTION * nodes as f64 {
            return Err(HypersliceError::NotAGrid { shape, nodes, rows });
        }
        let locate = |r: usize| -> Option<usize> {
            axes.iter().zip(coords).try_fold(0usize, |flat, ((_, axis), column)| {
                let v = *column.get(r)?;
                let i = axis.partition_point(|&c| c < v);
                (axis.get(i) == Some(&v)).then_some(flat * axis.len() + i)
            })
        };
        let mut grid = vec![f64::NAN; nodes];
        let mut filled = vec![0u64; nodes.div_ceil(64)];
        for (r, &value) in values.iter().enumerate() {
            let Some(flat) = locate(r) else { continue };
            let (Some(word), bit) = (filled.get_mut(flat / 64), 1u64 << (flat % 64)) else { continue };
            if *word & bit != 0 {
                let first = (0..r).find(|&q| locate(q) == Some(flat)).unwrap_or(0);
                let node =
                    axis_names.iter().zip(coords).map(|(n, c)| (n.clone(), c.get(r).copied().unwrap_or(f64::NAN)));
                return Err(HypersliceError::DuplicateNode { node: node.collect(), first, second: r });
            }
            *word |= bit;
            if let Some(slot) = grid.get_mut(flat) {
                *slot = if value.is_finite() { value } else { f64::NAN };
            }
        }
        Ok(NdGrid { axes, values: grid })
    }

    /// Number of axes (at least 2).
    pub fn dims(&self) -> usize {
        self.axes.len()
    }

    /// Name and coordinates of axis `k`, or `None` past the last axis.
    pub fn axis(&self, k: usize) -> Option<(&str, &[f64])> {
        self.axes.get(k).map(|(n, c)| (n.as_str(), c.as_slice()))
    }

    /// Number of coordinates on each axis.
    pub fn shape(&self) -> Vec<usize> {
        self.axes.iter().map(|(_, c)| c.len()).collect()
    }

    /// All values, last axis fastest; missing values are NaN.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Position in [`values`](Self::values) of the node with these indices, if it exists.
    fn flat(&self, index: &[usize]) -> Option<usize> {
        if index.len() != self.axes.len() {
            return None;
        }
        self.axes.iter().zip(index).try_fold(0usize, |flat, ((_, c), &i)| (i < c.len()).then_some(flat * c.len() + i))
    }

    /// The value at the node with one index per axis; NaN when it is missing, or when the index
    /// has the wrong length or is past the end of an axis.
    pub fn value_at(&self, index: &[usize]) -> f64 {
        self.flat(index).and_then(|f| self.values.get(f).copied()).unwrap_or(f64::NAN)
    }

    /// For each axis, the index of the node nearest to the focus coordinate. Coordinates outside
    /// the axis clamp to its first or last node; halfway between two nodes picks the lower one; a
    /// NaN or absent coordinate (focus shorter than [`dims`](Self::dims)) picks the middle node
    /// (the lower middle for an even count). Extra focus entries are ignored.
    pub fn nearest_index(&self, focus: &[f64]) -> Vec<usize> {
        self.axes
            .iter()
            .enumerate()
            .map(|(k, (_, c))| {
                let last = c.len().saturating_sub(1);
                match focus.get(k) {
                    Some(&v) if !v.is_nan() => {
                        let i = c.partition_point(|&x| x < v);
                        if i == 0 {
                            return 0;
                        }
                        if i > last {
                            return last;
                        }
                        match (c.get(i - 1), c.get(i)) {
                            (Some(&lo), Some(&hi)) if hi - v < v - lo => i,
                            _ => i - 1,
                        }
                    }
                    _ => last / 2,
                }
            })
            .collect()
    }

    /// The 2D slice over axis `a` (as x) and axis `b` (as y), with every other axis held at its
    /// `focus` index (`focus` has one index per axis; the entries for `a` and `b` are ignored).
    pub fn slice(&self, a: usize, b: usize, focus: &[usize]) -> Result<Grid, HypersliceError> {
        let dims = self.axes.len();
        for axis in [a, b] {
            if axis >= dims {
                return Err(HypersliceError::AxisOutOfRange { axis, dims });
            }
        }
        if a == b {
            return Err(HypersliceError::SameAxis { axis: a });
        }
        if focus.len() != dims {
            return Err(HypersliceError::FocusLength { got: focus.len(), dims });
        }
        // Strides (last axis fastest) and the flat offset of the focus on the fixed axes.
        let mut strides = vec![1usize; dims];
        let mut base = 0usize;
        let mut stride = 1usize;
        for k in (0..dims).rev() {
            let (Some((name, coords)), Some(&i), Some(s)) = (self.axes.get(k), focus.get(k), strides.get_mut(k)) else {
                continue;
            };
            *s = stride;
            if k != a && k != b {
                if i >= coords.len() {
                    return Err(HypersliceError::FocusOutOfRange { axis: name.clone(), index: i, len: coords.len() });
                }
                base += i * stride;
            }
            stride *= coords.len();
        }
        let (Some((_, xs)), Some((_, ys)), Some(&sa), Some(&sb)) =
            (self.axes.get(a), self.axes.get(b), strides.get(a), strides.get(b))
        else {
            return Err(HypersliceError::AxisOutOfRange { axis: a.max(b), dims });
        };
        let mut values = Vec::with_capacity(xs.len() * ys.len());
        for j in 0..ys.len() {
            for i in 0..xs.len() {
                values.push(self.values.get(base + i * sa + j * sb).copied().unwrap_or(f64::NAN));
            }
        }
        Grid::new(xs.clone(), ys.clone(), values).map_err(HypersliceError::Grid)
    }

    /// Smallest and largest non-missing value, or `None` when every value is missing.
    pub fn range(&self) -> Option<(f64, f64)> {
        let mut it = self.values.iter().copied().filter(|v| !v.is_nan());
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v))))
    }
}

/// The slices of a hyperslice matrix: `((a, b), slice)` with axis `a` as x and axis `b` as y.
pub type SliceMatrix = Vec<((usize, usize), Grid)>;

/// Every slice of the hyperslice matrix through the focus node: for each pair of axes `a < b`,
/// `((a, b), grid.slice(a, b, focus))` with axis `a` as x and `b` as y, ordered by `a` then `b`
/// (the panels of the lower triangle, column `a`, row `b`). With two axes there is one slice.
/// Fails on a bad focus, or when the slices would hold more than [`MAX_MATRIX_NODES`] nodes.
pub fn slice_matrix(grid: &NdGrid, focus: &[usize]) -> Result<SliceMatrix, HypersliceError> {
    let shape = grid.shape();
    let mut total = 0usize;
    for (a, &na) in shape.iter().enumerate() {
        for &nb in shape.iter().skip(a + 1) {
            total = total.saturating_add(na.saturating_mul(nb));
        }
    }
    if total > MAX_MATRIX_NODES {
        return Err(HypersliceError::MatrixTooLarge { nodes: total });
    }
    let dims = grid.dims();
    let mut out = Vec::with_capacity(dims * dims.saturating_sub(1) / 2);
    for a in 0..dims {
        for b in a + 1..dims {
            out.push(((a, b), grid.slice(a, b, focus)?));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(n: &[&str]) -> Vec<String> {
        n.iter().map(|s| s.to_string()).collect()
    }

    const XS: [f64; 4] = [0.0, 1.0, 2.5, 3.0];
    const YS: [f64; 3] = [-1.0, 0.5, 2.0];
    const ZS: [f64; 2] = [10.0, 20.0];

    fn f(x: f64, y: f64, z: f64) -> f64 {
        x + 10.0 * y + 100.0 * z
    }

    /// Long-form rows of f over XS × YS × ZS, in a shuffled order, with `skip` nodes left out.
    fn rows(skip: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
        let mut nodes = Vec::new();
        for &x in &XS {
            for &y in &YS {
                for &z in &ZS {
                    nodes.push((x, y, z));
                }
            }
        }
        // Deterministic shuffle: 7 is coprime with 24, so r -> 7r mod 24 is a permutation.
        let n = nodes.len();
        let order: Vec<(f64, f64, f64)> = (0..n).map(|r| nodes[(7 * r + 5) % n]).skip(skip).collect();
        (
            order.iter().map(|p| p.0).collect(),
            order.iter().map(|p| p.1).collect(),
            order.iter().map(|p| p.2).collect(),
            order.iter().map(|p| f(p.0, p.1, p.2)).collect(),
        )
    }

    fn built() -> NdGrid {
        let (x, y, z, v) = rows(0);
        NdGrid::from_rows(&names(&["x", "y", "z"]), &[&x, &y, &z], &v).unwrap()
    }

    #[test]
    fn rows_become_a_grid_with_the_last_axis_fastest() {
        let g = built();
        assert_eq!(g.dims(), 3);
        assert_eq!(g.shape(), vec![4, 3, 2]);
        assert_eq!(g.axis(0), Some(("x", &XS[..])));
        assert_eq!(g.axis(1), Some(("y", &YS[..])));
        assert_eq!(g.axis(2), Some(("z", &ZS[..])));
        assert_eq!(g.axis(3), None);
        for (i, &x) in XS.iter().enumerate() {
            for (j, &y) in YS.iter().enumerate() {
                for (k, &z) in ZS.iter().enumerate() {
                    assert_eq!(g.value_at(&[i, j, k]), f(x, y, z));
                    assert_eq!(g.values()[(i * 3 + j) * 2 + k], f(x, y, z));
                }
            }
        }
        assert!(g.value_at(&[4, 0, 0]).is_nan());
        assert!(g.value_at(&[0, 0]).is_nan());
        assert_eq!(g.range(), Some((f(0.0, -1.0, 10.0), f(3.0, 2.0, 20.0))));
        // The same grid built directly.
        let direct = NdGrid::new(
            vec![("x".into(), XS.to_vec()), ("y".into(), YS.to_vec()), ("z".into(), ZS.to_vec())],
            g.values().to_vec(),
        )
        .unwrap();
        assert_eq!(direct, g);
    }

    #[test]
    fn slices_reproduce_the_function_at_every_node() {
        let g = built();
        let axes = [&XS[..], &YS[..], &ZS[..]];
        let mut checked = 0;
        for (i, &xf) in XS.iter().enumerate() {
            for (j, &yf) in YS.iter().enumerate() {
                for (k, &zf) in ZS.iter().enumerate() {
                    let focus = [i, j, k];
                    for (a, b) in [(0, 1), (0, 2), (1, 2), (2, 0)] {
                        let s = g.slice(a, b, &focus).unwrap();
                        assert_eq!(s.xs(), axes[a]);
                        assert_eq!(s.ys(), axes[b]);
                        for (ia, &ca) in axes[a].iter().enumerate() {
                            for (ib, &cb) in axes[b].iter().enumerate() {
                                let mut p = [xf, yf, zf];
                                p[a] = ca;
                                p[b] = cb;
                                assert_eq!(s.value(ia, ib), f(p[0], p[1], p[2]), "slice ({a}, {b}) at {focus:?}");
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
        assert_eq!(checked, 24 * (12 + 8 + 6 + 8));
    }

    #[test]
    fn the_matrix_has_one_slice_per_pair() {
        let g = built();
        let m = slice_matrix(&g, &[1, 2, 0]).unwrap();
        let keys: Vec<(usize, usize)> = m.iter().map(|(k, _)| *k).collect();
        assert_eq!(keys, vec![(0, 1), (0, 2), (1, 2)]);
        let (_, xz) = &m[1];
        assert_eq!((xz.nx(), xz.ny()), (4, 2));
        assert_eq!(xz.value(3, 1), f(3.0, 2.0, 20.0)); // y held at index 2
        let (_, yz) = &m[2];
        assert_eq!(yz.value(0, 0), f(1.0, -1.0, 10.0)); // x held at index 1

        let two = NdGrid::from_rows(
            &names(&["a", "b"]),
            &[&[0.0, 1.0, 0.0, 1.0], &[0.0, 0.0, 5.0, 5.0]],
            &[1.0, 2.0, 3.0, 4.0],
        )
        .unwrap();
        let m = slice_matrix(&two, &[0, 0]).unwrap();
        assert_eq!(m.len(), 1);
        assert_eq!(m[0].0, (0, 1));
        assert_eq!(m[0].1.values(), &[1.0, 2.0, 3.0, 4.0]);
        assert!(matches!(slice_matrix(&g, &[0, 0]), Err(HypersliceError::FocusLength { got: 2, dims: 3 })));
    }

    #[test]
    fn nearest_index_picks_the_closest_node_and_clamps() {
        let g = built();
        assert_eq!(g.nearest_index(&[-100.0, 100.0, 15.1]), vec![0, 2, 1]);
        assert_eq!(g.nearest_index(&[1.8, 0.0, 14.9]), vec![2, 1, 0]);
        assert_eq!(g.nearest_index(&[f64::INFINITY, f64::NEG_INFINITY, 15.0]), vec![3, 0, 0], "tie picks lower");
        assert_eq!(g.nearest_index(&[2.75, 1.25, 20.0]), vec![2, 1, 1]);
        assert_eq!(g.nearest_index(&[f64::NAN]), vec![1, 1, 0], "NaN and absent pick the middle");
        assert_eq!(g.nearest_index(&[3.0, 2.0, 20.0, 99.0]), vec![3, 2, 1]);
    }

    #[test]
    fn a_duplicate_node_is_named() {
        let (mut x, mut y, mut z, mut v) = rows(0);
        x.push(2.5);
        y.push(0.5);
        z.push(20.0);
        v.push(0.0);
        let e = NdGrid::from_rows(&names(&["x", "y", "z"]), &[&x, &y, &z], &v).unwrap_err();
        let first = (0..24).find(|&r| (x[r], y[r], z[r]) == (2.5, 0.5, 20.0)).unwrap();
        assert_eq!(
            e,
            HypersliceError::DuplicateNode {
                node: vec![("x".into(), 2.5), ("y".into(), 0.5), ("z".into(), 20.0)],
                first,
                second: 24
            }
        );
        let msg = e.to_string();
        assert!(msg.contains("x = 2.5, y = 0.5, z = 20") && msg.contains(&format!("rows {first} and 24")), "{msg}");
        assert!(msg.contains("one row per node"), "{msg}");
    }

    #[test]
    fn missing_nodes_are_nan_up_to_half() {
        // 12 of 24 nodes missing: exactly half, still a grid.
        let (x, y, z, v) = rows(12);
        let g = NdGrid::from_rows(&names(&["x", "y", "z"]), &[&x, &y, &z], &v).unwrap();
        assert_eq!(g.shape(), vec![4, 3, 2]);
        assert_eq!(g.values().iter().filter(|v| v.is_nan()).count(), 12);
        for r in 0..x.len() {
            let idx = g.nearest_index(&[x[r], y[r], z[r]]);
            assert_eq!(g.value_at(&idx), v[r]);
        }
        // 13 missing: not a grid.
        let (x, y, z, v) = rows(13);
        let e = NdGrid::from_rows(&names(&["x", "y", "z"]), &[&x, &y, &z], &v).unwrap_err();
        assert_eq!(e, HypersliceError::NotAGrid { shape: vec![4, 3, 2], nodes: 24, rows: 11 });
        let msg = e.to_string();
        assert!(msg.contains("4 x 3 x 2") && msg.contains("24 nodes") && msg.contains("11 rows"), "{msg}");
        assert!(msg.contains("54%") && msg.contains("interpolate scattered data"), "{msg}");
        // Scattered points (all coordinates distinct) are refused, not gridded.
        let a: Vec<f64> = (0..50).map(|i| i as f64 * 0.37).collect();
        let b: Vec<f64> = (0..50).map(|i| (i as f64 * 1.3).sin()).collect();
        let e = NdGrid::from_rows(&names(&["a", "b"]), &[&a, &b], &a).unwrap_err();
        assert!(matches!(e, HypersliceError::NotAGrid { nodes: 2500, rows: 50, .. }));
    }

    #[test]
    fn nan_values_stay_missing() {
        let (x, y, z, mut v) = rows(0);
        v[3] = f64::NAN;
        v[4] = f64::INFINITY;
        let g = NdGrid::from_rows(&names(&["x", "y", "z"]), &[&x, &y, &z], &v).unwrap();
        for r in [3, 4] {
            assert!(g.value_at(&g.nearest_index(&[x[r], y[r], z[r]])).is_nan());
        }
        assert_eq!(g.values().iter().filter(|v| v.is_nan()).count(), 2);
        let s = g.slice(0, 1, &g.nearest_index(&[x[3], y[3], z[3]])).unwrap();
        assert_eq!(s.values().iter().filter(|v| v.is_nan()).count(), 1);
        let all = NdGrid::new(vec![("a".into(), vec![0.0]), ("b".into(), vec![0.0])], vec![f64::NAN]).unwrap();
        assert_eq!(all.range(), None);
    }

    #[test]
    fn negative_zero_is_the_same_coordinate() {
        let g = NdGrid::from_rows(
            &names(&["a", "b"]),
            &[&[-0.0, 1.0, 0.0, 1.0], &[0.0, 0.0, 1.0, 1.0]],
            &[1.0, 2.0, 3.0, 4.0],
        )
        .unwrap();
        assert_eq!(g.shape(), vec![2, 2]);
        let e = NdGrid::from_rows(&names(&["a", "b"]), &[&[-0.0, 0.0], &[1.0, 1.0]], &[1.0, 2.0]).unwrap_err();
        assert!(matches!(e, HypersliceError::DuplicateNode { first: 0, second: 1, .. }));
    }

    #[test]
    fn fewer_than_two_axes_is_an_error() {
        let e = NdGrid::from_rows(&names(&["x"]), &[&[0.0, 1.0]], &[1.0, 2.0]).unwrap_err();
        assert_eq!(e, HypersliceError::TooFewAxes { dims: 1 });
        assert!(e.to_string().contains("at least 2 axes, got 1"), "{e}");
        let e = NdGrid::new(vec![("x".into(), vec![0.0])], vec![1.0]).unwrap_err();
        assert_eq!(e, HypersliceError::TooFewAxes { dims: 1 });
        let many: Vec<String> = (0..17).map(|k| format!("v{k}")).collect();
        let col = [0.0];
        let cols: Vec<&[f64]> = (0..17).map(|_| &col[..]).collect();
        let e = NdGrid::from_rows(&many, &cols, &[1.0]).unwrap_err();
        assert_eq!(e, HypersliceError::TooManyAxes { dims: 17 });
    }

    #[test]
    fn bad_rows_are_reported_with_their_values() {
        let n = names(&["x", "y"]);
        let e = NdGrid::from_rows(&n, &[&[0.0, 1.0]], &[1.0, 2.0]).unwrap_err();
        assert_eq!(e, HypersliceError::AxisCountMismatch { names: 2, columns: 1 });
        let e = NdGrid::from_rows(&n, &[&[0.0, 1.0], &[0.0]], &[1.0, 2.0]).unwrap_err();
        assert_eq!(e, HypersliceError::RowCountMismatch { axis: "y".into(), got: 1, expected: 2 });
        assert!(e.to_string().contains("\"y\" has 1 coordinates but there are 2 values"), "{e}");
        let e = NdGrid::from_rows(&n, &[&[0.0, 1.0], &[0.0, f64::NAN]], &[1.0, 2.0]).unwrap_err();
        assert!(matches!(e, HypersliceError::NonFiniteCoordinate { row: 1, .. }));
        assert!(e.to_string().contains("coordinate 1 is NaN") && e.to_string().contains("finite"), "{e}");
        let e = NdGrid::from_rows(&n, &[&[], &[]], &[]).unwrap_err();
        assert_eq!(e, HypersliceError::NoRows);
        let e = NdGrid::from_rows(&names(&["x", "x"]), &[&[0.0], &[0.0]], &[1.0]).unwrap_err();
        assert_eq!(e, HypersliceError::DuplicateAxisName { name: "x".into() });

        let e = NdGrid::new(vec![("x".into(), vec![0.0, 0.0]), ("y".into(), vec![1.0])], vec![0.0; 2]).unwrap_err();
        assert_eq!(e, HypersliceError::NotIncreasing { axis: "x".into(), index: 1, previous: 0.0, value: 0.0 });
        let e = NdGrid::new(vec![("x".into(), vec![]), ("y".into(), vec![1.0])], vec![]).unwrap_err();
        assert_eq!(e, HypersliceError::EmptyAxis { axis: "x".into() });
        let e = NdGrid::new(vec![("x".into(), vec![0.0, 1.0]), ("y".into(), vec![1.0])], vec![0.0; 3]).unwrap_err();
        assert_eq!(e, HypersliceError::ValueCount { nodes: 2, got: 3 });
    }

    #[test]
    fn too_large_is_refused_before_allocating() {
        // 10 000 rows with distinct coordinates on three axes: 10¹² nodes.
        let c: Vec<f64> = (0..10_000).map(f64::from).collect();
        let e = NdGrid::from_rows(&names(&["a", "b", "c"]), &[&c, &c, &c], &c).unwrap_err();
        assert_eq!(e, HypersliceError::TooLarge { shape: vec![10_000; 3] });
        assert!(e.to_string().contains("10000 x 10000 x 10000"), "{e}");
        // The product overflows usize without panicking.
        let axes: Vec<(String, Vec<f64>)> = (0..8).map(|k| (format!("v{k}"), c.clone())).collect();
        let e = NdGrid::new(axes, vec![]).unwrap_err();
        assert!(matches!(e, HypersliceError::TooLarge { .. }));
    }

    #[test]
    fn a_matrix_of_huge_slices_is_refused() {
        // One axis of 2²³ and eight single-node axes: each of the eight slices with the long axis
        // has 2²³ nodes, 2²⁶ + 28 in all.
        let long: Vec<f64> = (0..1u32 << 23).map(f64::from).collect();
        let mut axes = vec![("t".to_string(), long)];
        axes.extend((0..8).map(|k| (format!("p{k}"), vec![0.0])));
        let g = NdGrid::new(axes, vec![0.0; 1 << 23]).unwrap();
        let e = slice_matrix(&g, &[0; 9]).unwrap_err();
        assert_eq!(e, HypersliceError::MatrixTooLarge { nodes: (1 << 26) + 28 });
        // A single slice is still fine.
        assert_eq!(g.slice(0, 1, &[0; 9]).unwrap().nx(), 1 << 23);
    }

    #[test]
    fn bad_slices_are_errors() {
        let g = built();
        assert_eq!(g.slice(0, 3, &[0, 0, 0]), Err(HypersliceError::AxisOutOfRange { axis: 3, dims: 3 }));
        assert_eq!(g.slice(1, 1, &[0, 0, 0]), Err(HypersliceError::SameAxis { axis: 1 }));
        assert_eq!(g.slice(0, 1, &[0, 0]), Err(HypersliceError::FocusLength { got: 2, dims: 3 }));
        let e = g.slice(0, 1, &[0, 0, 2]).unwrap_err();
        assert_eq!(e, HypersliceError::FocusOutOfRange { axis: "z".into(), index: 2, len: 2 });
        assert!(e.to_string().contains("below 2"), "{e}");
        // Focus entries on the slice's own axes are ignored, even out of range.
        assert!(g.slice(0, 1, &[99, 99, 1]).is_ok());
    }
}
