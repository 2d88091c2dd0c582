//! A 2-D vector field sampled on a rectilinear grid, optionally over time.
//!
//! The lattice has `nx` columns at the strictly increasing x coordinates `xs` and `ny` rows at the
//! strictly increasing y coordinates `ys` (spacing need not be uniform). Each component is stored
//! row by row: the velocity at node `(i, j)`, at `(xs[i], ys[j])`, is `(u[j * nx + i], v[j * nx + i])`.
//! An unsteady field holds one such `(u, v)` frame per time of the strictly increasing axis `ts`
//! and interpolates linearly between frames.
//!
//! Inside a cell the field is the bilinear interpolant of its four corners (the same interpolant as
//! `crate::enrich::grid`); the Jacobian is the exact derivative of that interpolant. A non-finite
//! component is stored as NaN: a cell with such a corner is a hole, where sampling gives `None`.

use std::fmt;

/// Largest number of nodes per frame accepted (2³⁰), as for the scalar grid.
pub const MAX_NODES: usize = 1 << 30;

/// One of the field's axes, named in [`FieldError`] messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldAxis {
    /// The column coordinates `xs`.
    X,
    /// The row coordinates `ys`.
    Y,
    /// The time axis `ts` of an unsteady field.
    T,
}

impl fmt::Display for FieldAxis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FieldAxis::X => "x",
            FieldAxis::Y => "y",
            FieldAxis::T => "t",
        })
    }
}

/// Why a [`VectorField`] could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum FieldError {
    /// An axis has fewer coordinates than needed (2 for x and y, 1 for t).
    TooShort {
        /// The short axis.
        axis: FieldAxis,
        /// Number of coordinates given.
        len: usize,
        /// Number required.
        min: usize,
    },
    /// An axis coordinate is NaN or infinite.
    NonFiniteCoordinate {
        /// The axis holding it.
        axis: FieldAxis,
        /// Its position on the axis.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// An axis coordinate is not greater than the one before it.
    NotIncreasing {
        /// The axis holding it.
        axis: FieldAxis,
        /// Its position on the axis.
        index: usize,
        /// The coordinate before it.
        previous: f64,
        /// The offending value.
        value: f64,
    },
    /// A component slice does not have `nx * ny` values.
    ComponentCount {
        /// `"u"` or `"v"`.
        component: &'static str,
        /// The frame (time index) holding it; 0 for a steady field.
        frame: usize,
        /// Number of columns.
        nx: usize,
        /// Number of rows.
        ny: usize,
        /// Number of values given.
        got: usize,
    },
    /// The number of frames differs from the number of times.
    FrameCount {
        /// Number of times in `ts`.
        times: usize,
        /// Number of `(u, v)` frames given.
        frames: usize,
    },
    /// More than [`MAX_NODES`] nodes per frame.
    TooLarge {
        /// Number of columns.
        nx: usize,
        /// Number of rows.
        ny: usize,
    },
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FieldError::TooShort { axis, len, min } => write!(
                f,
                "the vector field's {axis} axis has {len} coordinate(s); give at least {min} so the \
                 field has cells to interpolate in"
            ),
            FieldError::NonFiniteCoordinate { axis, index, value } => {
                write!(f, "field coordinate {axis}[{index}] is {value}; coordinates must be finite numbers")
            }
            FieldError::NotIncreasing { axis, index, previous, value } => write!(
                f,
                "field coordinate {axis}[{index}] = {value} is not greater than {axis}[{}] = {previous}; \
                 coordinates must be strictly increasing (sort them and drop duplicates)",
                index.saturating_sub(1)
            ),
            FieldError::ComponentCount { component, frame, nx, ny, got } => write!(
                f,
                "component {component} of frame {frame} has {got} values but the grid has {nx} x {ny} = {} \
                 nodes; give one value per node, row by row",
                nx.saturating_mul(*ny)
            ),
            FieldError::FrameCount { times, frames } => write!(
                f,
                "the time axis has {times} time(s) but {frames} (u, v) frame(s) were given; give exactly \
                 one frame per time"
            ),
            FieldError::TooLarge { nx, ny } => {
                write!(f, "a {nx} x {ny} field has more than {MAX_NODES} nodes; resample it to a coarser grid")
            }
        }
    }
}

impl std::error::Error for FieldError {}

/// What sampling the field at a point found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Probe {
    /// The interpolated velocity `[u, v]`.
    Velocity([f64; 2]),
    /// The point is outside the domain (or a coordinate is NaN).
    Outside,
    /// The point is inside the domain, in a cell with a missing corner.
    Hole,
}

/// Fast cell lookup along one axis: uniform axes are found by arithmetic, others by bisection.
#[derive(Debug, Clone, PartialEq)]
struct AxisIndex {
    coords: Vec<f64>,
    /// `(first, 1 / spacing)` when the axis is uniform to 1e-9 relative.
    uniform: Option<(f64, f64)>,
}

impl AxisIndex {
    fn new(coords: Vec<f64>) -> AxisIndex {
        let n = coords.len();
        let (first, last) = (coords.first().copied().unwrap_or(0.0), coords.last().copied().unwrap_or(0.0));
        let h = (last - first) / (n.max(2) - 1) as f64;
        let is_uniform = h.is_finite()
            && h > 0.0
            && coords.iter().enumerate().all(|(i, &c)| (c - (first + i as f64 * h)).abs() <= 1e-9 * h);
        AxisIndex { coords, uniform: is_uniform.then(|| (first, 1.0 / h)) }
    }

    /// Cell index `i` (so that `coords[i] <= x <= coords[i + 1]`) and the fraction across it.
    #[inline]
    fn locate(&self, x: f64) -> Option<(usize, f64)> {
        let c = &self.coords;
        let (&first, &last) = (c.first()?, c.last()?);
        if !(x >= first && x <= last) {
            return None;
        }
        let last_cell = c.len().checked_sub(2)?;
        let mut i = match self.uniform {
            Some((x0, inv_h)) => (((x - x0) * inv_h) as usize).min(last_cell),
            None => c.partition_point(|&a| a <= x).saturating_sub(1).min(last_cell),
        };
        // Correct rounding of the uniform guess by one cell either way.
        if i > 0 && x < c[i] {
            i -= 1;
        } else if i < last_cell && x > c[i + 1] {
            i += 1;
        }
        let s = match self.uniform {
            Some((x0, inv_h)) => (x - x0) * inv_h - i as f64,
            None => (x - c[i]) / (c[i + 1] - c[i]),
        };
        Some((i, s.clamp(0.0, 1.0)))
    }
}

/// Where a point falls: the cell `(i, j)` and the fractions `(s, t)` across it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellPoint {
    /// Column of the cell's lower-left node.
    pub i: usize,
    /// Row of the cell's lower-left node.
    pub j: usize,
    /// Fraction across the cell along x, in `[0, 1]`.
    pub s: f64,
    /// Fraction across the cell along y, in `[0, 1]`.
    pub t: f64,
}

/// A 2-D vector field on a rectilinear grid; see the module docs for the layout.
#[derive(Debug, Clone, PartialEq)]
pub struct VectorField {
    nx: usize,
    ny: usize,
    xs: AxisIndex,
    ys: AxisIndex,
    ts: Vec<f64>,
    us: Vec<Vec<f64>>,
    vs: Vec<Vec<f64>>,
    max_speed: f64,
}

impl VectorField {
    /// Builds a steady field from `xs`, `ys` (at least 2 each, finite, strictly increasing) and the
    /// row-major components `u`, `v` of `xs.len() * ys.len()` values each. Non-finite components
    /// are stored as NaN (holes).
    pub fn new(xs: Vec<f64>, ys: Vec<f64>, u: Vec<f64>, v: Vec<f64>) -> Result<VectorField, FieldError> {
        VectorField::build(xs, ys, Vec::new(), vec![(u, v)])
    }

    /// Builds an unsteady field: one `(u, v)` frame per time of the strictly increasing, finite
    /// axis `ts` (at least one time).
    pub fn unsteady(
        xs: Vec<f64>,
        ys: Vec<f64>,
        ts: Vec<f64>,
        frames: Vec<(Vec<f64>, Vec<f64>)>,
    ) -> Result<VectorField, FieldError> {
        check_axis(FieldAxis::T, &ts, 1)?;
        if frames.len() != ts.len() {
            return Err(FieldError::FrameCount { times: ts.len(), frames: frames.len() });
        }
        VectorField::build(xs, ys, ts, frames)
    }

    /// Builds a steady field by evaluating `f(x, y) = [u, v]` at every node.
    pub fn from_fn(
        xs: Vec<f64>,
        ys: Vec<f64>,
        mut f: impl FnMut(f64, f64) -> [f64; 2],
    ) -> Result<VectorField, FieldError> {
        check_axis(FieldAxis::X, &xs, 2)?;
        check_axis(FieldAxis::Y, &ys, 2)?;
        node_count(xs.len(), ys.len())?;
        let (mut u, mut v) = (Vec::with_capacity(xs.len() * ys.len()), Vec::with_capacity(xs.len() * ys.len()));
        for &y in &ys {
            for &x in &xs {
                let [a, b] = f(x, y);
                u.push(a);
                v.push(b);
            }
        }
        VectorField::new(xs, ys, u, v)
    }

    fn build(
        xs: Vec<f64>,
        ys: Vec<f64>,
        ts: Vec<f64>,
        frames: Vec<(Vec<f64>, Vec<f64>)>,
    ) -> Result<VectorField, FieldError> {
        check_axis(FieldAxis::X, &xs, 2)?;
        check_axis(FieldAxis::Y, &ys, 2)?;
        let (nx, ny) = (xs.len(), ys.len());
        let nodes = node_count(nx, ny)?;
        let (mut us, mut vs) = (Vec::with_capacity(frames.len()), Vec::with_capacity(frames.len()));
        let mut max_speed = 0.0f64;
        for (frame, (mut u, mut v)) in frames.into_iter().enumerate() {
            for (component, values) in [("u", &mut u), ("v", &mut v)] {
                if values.len() != nodes {
                    return Err(FieldError::ComponentCount { component, frame, nx, ny, got: values.len() });
                }
                values.iter_mut().filter(|c| !c.is_finite()).for_each(|c| *c = f64::NAN);
            }
            let frame_max = u.iter().zip(&v).map(|(a, b)| a.hypot(*b)).filter(|s| s.is_finite()).fold(0.0, f64::max);
            max_speed = max_speed.max(frame_max);
            us.push(u);
            vs.push(v);
        }
        Ok(VectorField { nx, ny, xs: AxisIndex::new(xs), ys: AxisIndex::new(ys), ts, us, vs, max_speed })
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
        &self.xs.coords
    }

    /// Row coordinates, strictly increasing.
    pub fn ys(&self) -> &[f64] {
        &self.ys.coords
    }

    /// Times of an unsteady field; empty for a steady one.
    pub fn ts(&self) -> &[f64] {
        &self.ts
    }

    /// Number of `(u, v)` frames (1 for a steady field).
    pub fn frames(&self) -> usize {
        self.us.len()
    }

    /// Component `u` of frame `k` (row-major), or `None` when there is no such frame.
    pub fn u(&self, k: usize) -> Option<&[f64]> {
        self.us.get(k).map(Vec::as_slice)
    }

    /// Component `v` of frame `k` (row-major), or `None` when there is no such frame.
    pub fn v(&self, k: usize) -> Option<&[f64]> {
        self.vs.get(k).map(Vec::as_slice)
    }

    /// Domain `[x_min, x_max, y_min, y_max]`.
    pub fn bounds(&self) -> [f64; 4] {
        let (x, y) = (&self.xs.coords, &self.ys.coords);
        [x[0], x[x.len() - 1], y[0], y[y.len() - 1]]
    }

    /// Largest finite node speed over all frames (0 for an all-zero or all-NaN field).
    pub fn max_speed(&self) -> f64 {
        self.max_speed
    }

    /// Smallest cell width or height: a natural length scale for steps and offsets.
    pub fn min_cell(&self) -> f64 {
        let gap = |c: &[f64]| c.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
        gap(&self.xs.coords).min(gap(&self.ys.coords))
    }

    /// Whether `(x, y)` lies in the closed domain rectangle.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let [x0, x1, y0, y1] = self.bounds();
        x >= x0 && x <= x1 && y >= y0 && y <= y1
    }

    /// The cell holding `(x, y)` and the fractions across it; `None` outside the domain.
    pub fn locate(&self, x: f64, y: f64) -> Option<CellPoint> {
        let (i, s) = self.xs.locate(x)?;
        let (j, t) = self.ys.locate(y)?;
        Some(CellPoint { i, j, s, t })
    }

    /// Corner values `[f00, f10, f01, f11]` of cell `(i, j)` in component slice `c`.
    #[inline]
    fn corners(&self, c: &[f64], i: usize, j: usize) -> [f64; 4] {
        let k = j * self.nx + i;
        let at = |k: usize| c.get(k).copied().unwrap_or(f64::NAN);
        [at(k), at(k + 1), at(k + self.nx), at(k + self.nx + 1)]
    }

    /// Bilinear velocity of frame `k` at a located point; `None` in a hole.
    #[inline]
    fn frame_velocity(&self, k: usize, p: &CellPoint) -> Option<[f64; 2]> {
        let (u, v) = (self.us.get(k)?, self.vs.get(k)?);
        let a = bilerp(self.corners(u, p.i, p.j), p.s, p.t);
        let b = bilerp(self.corners(v, p.i, p.j), p.s, p.t);
        (a.is_finite() && b.is_finite()).then_some([a, b])
    }

    /// Samples frame 0 at `(x, y)`, telling a point outside the domain from one in a hole.
    #[inline]
    pub fn probe(&self, x: f64, y: f64) -> Probe {
        match self.locate(x, y) {
            None => Probe::Outside,
            Some(p) => self.frame_velocity(0, &p).map_or(Probe::Hole, Probe::Velocity),
        }
    }

    /// Bilinear velocity `[u, v]` at `(x, y)` (the first frame of an unsteady field); `None`
    /// outside the domain or in a hole.
    #[inline]
    pub fn velocity(&self, x: f64, y: f64) -> Option<[f64; 2]> {
        let p = self.locate(x, y)?;
        self.frame_velocity(0, &p)
    }

    /// Velocity at `(x, y)` and time `t`, linear in time between frames. A steady field ignores
    /// `t`; an unsteady one gives `None` for `t` outside `[ts[0], ts[last]]` or NaN.
    pub fn velocity_at(&self, x: f64, y: f64, t: f64) -> Option<[f64; 2]> {
        let p = self.locate(x, y)?;
        if self.ts.len() < 2 {
            return match self.ts.first() {
                Some(&t0) if t != t0 => None,
                _ => self.frame_velocity(0, &p),
            };
        }
        let (first, last) = (self.ts[0], self.ts[self.ts.len() - 1]);
        if !(t >= first && t <= last) {
            return None;
        }
        let k = self.ts.partition_point(|&a| a <= t).saturating_sub(1).min(self.ts.len() - 2);
        let w = ((t - self.ts[k]) / (self.ts[k + 1] - self.ts[k])).clamp(0.0, 1.0);
        let a = self.frame_velocity(k, &p)?;
        let b = self.frame_velocity(k + 1, &p)?;
        Some([a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])])
    }

    /// Speed `|(u, v)|` at `(x, y)`; `None` outside the domain or in a hole.
    pub fn speed(&self, x: f64, y: f64) -> Option<f64> {
        self.velocity(x, y).map(|[a, b]| a.hypot(b))
    }

    /// Speed at `(x, y)` and time `t`; see [`VectorField::velocity_at`].
    pub fn speed_at(&self, x: f64, y: f64, t: f64) -> Option<f64> {
        self.velocity_at(x, y, t).map(|[a, b]| a.hypot(b))
    }

    /// Jacobian `[[∂u/∂x, ∂u/∂y], [∂v/∂x, ∂v/∂y]]` of the bilinear interpolant (first frame) at
    /// `(x, y)`; `None` outside the domain or in a hole.
    pub fn jacobian(&self, x: f64, y: f64) -> Option<[[f64; 2]; 2]> {
        let p = self.locate(x, y)?;
        let (hx, hy) = self.cell_size(p.i, p.j)?;
        let u = self.corners(self.us.first()?, p.i, p.j);
        let v = self.corners(self.vs.first()?, p.i, p.j);
        let [du_ds, du_dt] = bilerp_gradient(u, p.s, p.t);
        let [dv_ds, dv_dt] = bilerp_gradient(v, p.s, p.t);
        let j = [[du_ds / hx, du_dt / hy], [dv_ds / hx, dv_dt / hy]];
        j.iter().flatten().all(|d| d.is_finite()).then_some(j)
    }

    /// Width and height of cell `(i, j)`.
    pub fn cell_size(&self, i: usize, j: usize) -> Option<(f64, f64)> {
        let (x, y) = (&self.xs.coords, &self.ys.coords);
        Some((x.get(i + 1)? - x.get(i)?, y.get(j + 1)? - y.get(j)?))
    }

    /// Corner velocities of cell `(i, j)` of the first frame: `([u00, u10, u01, u11], [v00, …])`
    /// where `u10` sits at `(xs[i + 1], ys[j])`.
    pub fn cell_corners(&self, i: usize, j: usize) -> Option<([f64; 4], [f64; 4])> {
        if i + 1 >= self.nx || j + 1 >= self.ny {
            return None;
        }
        Some((self.corners(self.us.first()?, i, j), self.corners(self.vs.first()?, i, j)))
    }
}

/// Bilinear interpolation of corners `[f00, f10, f01, f11]` at fractions `(s, t)`.
#[inline]
pub(crate) fn bilerp(f: [f64; 4], s: f64, t: f64) -> f64 {
    let bottom = f[0] + s * (f[1] - f[0]);
    let top = f[2] + s * (f[3] - f[2]);
    bottom + t * (top - bottom)
}

/// Gradient `[∂f/∂s, ∂f/∂t]` of the bilinear interpolant of corners `[f00, f10, f01, f11]`.
#[inline]
pub(crate) fn bilerp_gradient(f: [f64; 4], s: f64, t: f64) -> [f64; 2] {
    [(1.0 - t) * (f[1] - f[0]) + t * (f[3] - f[2]), (1.0 - s) * (f[2] - f[0]) + s * (f[3] - f[1])]
}

/// Checks that an axis has at least `min` finite, strictly increasing coordinates.
fn check_axis(axis: FieldAxis, coords: &[f64], min: usize) -> Result<(), FieldError> {
    if coords.len() < min {
        return Err(FieldError::TooShort { axis, len: coords.len(), min });
    }
    let mut previous = f64::NEG_INFINITY;
    for (index, &value) in coords.iter().enumerate() {
        if !value.is_finite() {
            return Err(FieldError::NonFiniteCoordinate { axis, index, value });
        }
        if index > 0 && value <= previous {
            return Err(FieldError::NotIncreasing { axis, index, previous, value });
        }
        previous = value;
    }
    Ok(())
}

/// `nx * ny`, refused above [`MAX_NODES`].
fn node_count(nx: usize, ny: usize) -> Result<usize, FieldError> {
    match nx.checked_mul(ny) {
        Some(n) if n <= MAX_NODES => Ok(n),
        _ => Err(FieldError::TooLarge { nx, ny }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(n: usize, a: f64, b: f64) -> Vec<f64> {
        (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect()
    }

    #[test]
    fn bilinear_fields_are_reproduced_exactly_with_their_jacobian() {
        // u = 1 + 2x − 3y + 0.5xy, v = x·y − y: bilinear, so exact on any (non-uniform) lattice.
        let f = |x: f64, y: f64| [1.0 + 2.0 * x - 3.0 * y + 0.5 * x * y, x * y - y];
        let field = VectorField::from_fn(vec![0.0, 0.5, 2.0, 3.0], vec![-1.0, 0.0, 4.0], f).unwrap();
        for &(x, y) in &[(0.0, -1.0), (0.3, 2.0), (1.7, -0.2), (3.0, 4.0), (2.0, 0.0)] {
            let [a, b] = field.velocity(x, y).unwrap();
            let [ea, eb] = f(x, y);
            assert!((a - ea).abs() < 1e-12 && (b - eb).abs() < 1e-12, "at ({x}, {y})");
            let j = field.jacobian(x, y).unwrap();
            let exact = [[2.0 + 0.5 * y, -3.0 + 0.5 * x], [y, x - 1.0]];
            for r in 0..2 {
                for c in 0..2 {
                    assert!((j[r][c] - exact[r][c]).abs() < 1e-12, "J[{r}][{c}] at ({x}, {y})");
                }
            }
        }
        assert_eq!(field.velocity(-0.1, 0.0), None);
        assert_eq!(field.velocity(f64::NAN, 0.0), None);
        assert_eq!(field.probe(3.5, 0.0), Probe::Outside);
    }

    #[test]
    fn nan_corner_makes_a_hole_only_in_its_cells() {
        let mut u = vec![1.0; 9];
        u[0] = f64::INFINITY;
        let field = VectorField::new(axis(3, 0.0, 2.0), axis(3, 0.0, 2.0), u, vec![0.0; 9]).unwrap();
        assert_eq!(field.probe(0.5, 0.5), Probe::Hole);
        assert_eq!(field.velocity(1.5, 0.5), Some([1.0, 0.0]));
        assert_eq!(field.jacobian(0.5, 0.5), None);
        assert_eq!(field.max_speed(), 1.0);
        assert!(field.u(0).unwrap()[0].is_nan());
    }

    #[test]
    fn unsteady_fields_are_linear_in_time() {
        let xs = axis(2, 0.0, 1.0);
        let frames = vec![(vec![0.0; 4], vec![1.0; 4]), (vec![2.0; 4], vec![1.0; 4])];
        let field = VectorField::unsteady(xs.clone(), xs, vec![0.0, 4.0], frames).unwrap();
        assert_eq!(field.velocity_at(0.5, 0.5, 1.0), Some([0.5, 1.0]));
        assert_eq!(field.velocity_at(0.5, 0.5, 4.0), Some([2.0, 1.0]));
        assert_eq!(field.velocity_at(0.5, 0.5, 4.1), None);
        assert_eq!(field.speed_at(0.5, 0.5, 0.0), Some(1.0));
    }

    #[test]
    fn errors_keep_the_bad_value_and_say_the_fix() {
        let e = VectorField::new(vec![0.0], vec![0.0, 1.0], vec![0.0; 2], vec![0.0; 2]).unwrap_err();
        assert_eq!(e, FieldError::TooShort { axis: FieldAxis::X, len: 1, min: 2 });
        assert!(e.to_string().contains("at least 2"), "{e}");
        let e = VectorField::new(vec![0.0, 1.0], vec![0.0, f64::NAN], vec![0.0; 4], vec![0.0; 4]).unwrap_err();
        assert!(e.to_string().contains("y[1] is NaN"), "{e}");
        let e = VectorField::new(vec![0.0, 1.0, 1.0], vec![0.0, 1.0], vec![0.0; 6], vec![0.0; 6]).unwrap_err();
        assert_eq!(e, FieldError::NotIncreasing { axis: FieldAxis::X, index: 2, previous: 1.0, value: 1.0 });
        assert!(e.to_string().contains("strictly increasing"), "{e}");
        let e = VectorField::new(vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0; 4], vec![0.0; 3]).unwrap_err();
        assert!(e.to_string().contains("component v of frame 0 has 3 values"), "{e}");
        let xs = vec![0.0, 1.0];
        let e = VectorField::unsteady(xs.clone(), xs, vec![0.0, 1.0], vec![(vec![0.0; 4], vec![0.0; 4])]).unwrap_err();
        assert_eq!(e, FieldError::FrameCount { times: 2, frames: 1 });
    }

    #[test]
    fn uniform_and_bisection_lookup_agree() {
        let uniform = AxisIndex::new(axis(11, -1.0, 1.0));
        let mut bumped = axis(11, -1.0, 1.0);
        bumped[5] += 1e-3;
        let general = AxisIndex::new(bumped.clone());
        assert!(uniform.uniform.is_some() && general.uniform.is_none());
        for k in 0..=200 {
            let x = -1.0 + k as f64 * 0.01;
            let (i, s) = uniform.locate(x).unwrap();
            assert!(uniform.coords[i] <= x + 1e-15 && x <= uniform.coords[i + 1] + 1e-15 && (0.0..=1.0).contains(&s));
            let (i, _) = general.locate(x).unwrap();
            assert!(bumped[i] <= x && x <= bumped[i + 1]);
        }
        assert_eq!(uniform.locate(1.0).map(|(i, _)| i), Some(9));
    }
}
