//! Scattered data: a Delaunay triangulation (a TIN) of points carrying values, linear
//! interpolation inside its triangles, contour lines traced on the triangulation itself (no
//! resampling), and the Voronoi (Dirichlet) tessellation of the points.
//!
//! The triangulation comes from [`spade`], whose geometric predicates are exact, so the result is
//! a true Delaunay triangulation whatever the spacing or scale of the points. Internally every
//! coordinate is multiplied by one power of two (an exact operation) so that the largest
//! magnitude lies in `[0.5, 1)`; any finite coordinates work, from `1e-300` to `1e300`.
//!
//! Rules, in the order [`Triangulation::new`] applies them:
//! - **Coordinates** must be finite: a NaN or infinite `x` or `y` is an error naming the first
//!   bad row ([`ScatteredError::NonFiniteCoordinate`]); the caller drops such rows first.
//! - **Duplicates.** Rows at exactly the same position (`==` on both coordinates, so `0.0` and
//!   `-0.0` are the same) are merged: the first row is kept with its value, later ones are dropped
//!   and counted by [`Triangulation::merged_duplicates`]. [`Triangulation::points`] holds the
//!   kept points in input order and [`Triangulation::rows`] names the input row of each. A
//!   coordinate smaller in magnitude than 2⁻¹⁴² times the largest one (far below `f64`
//!   resolution at that scale) counts as zero, as spade's exact predicates require.
//! - **Values.** Non-finite values (NaN, ±inf) are stored as NaN and mean "missing". The point
//!   still takes part in the triangulation and the Voronoi tessellation, but every triangle
//!   touching it is a *hole*: [`Triangulation::interpolate`] is NaN inside it and
//!   [`Triangulation::contour_lines`] leaves it empty.
//! - **Degenerate input.** Fewer than three distinct points, or all points on one line (decided
//!   exactly), is not an error: the result has no triangles, an empty hull and
//!   [`Triangulation::is_degenerate`] is `true`, so a chart can still draw the points and their
//!   Voronoi cells (strips or half-planes), while interpolation is NaN everywhere and there are no
//!   contours.
//! - **Outside the hull** interpolation is NaN.
//! - **Above / below.** For contours a point with `value >= level` is *above* the level; a
//!   contour line is the boundary of the region `{f >= level}` of the linear TIN, with that region
//!   on its left.
//! - **Size.** At most [`MAX_POINTS`] points; contouring is capped by [`MAX_LEVELS`] and
//!   [`MAX_CROSSINGS`], checked before anything large is allocated.
//!
//! Speed: spade's bulk loader (a circle sweep) does the work. From [`SPLIT_MIN`] points on, with
//! two threads available, the points left and right of the median x are triangulated at the same
//! time and only the seam between them is triangulated again (see `split`, which also explains
//! why the result is still the Delaunay triangulation; a stitched mesh that fails its checks is
//! thrown away and the points are triangulated in one piece). Large inputs are handed to spade
//! already in its sweep order, which saves it its own comparison sort. The triangles and their
//! neighbours are copied out of spade's structure into flat arrays; point location walks them
//! from a coarse grid of start triangles with exact orientation tests. The bulk loader's seed
//! (the points nearest the centre, inserted until they are not all on one line) costs time
//! quadratic in its length, so when many points near the centre may be collinear the
//! triangulation is built by insertion instead, starting from an exactly non-collinear
//! triangle; all-collinear input never reaches spade's line code.

mod contour;
mod locate;
mod mesh;
mod split;
#[cfg(test)]
mod tests;
mod voronoi;

use std::fmt;
use std::sync::OnceLock;

use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation as _};

use self::locate::{Hit, Locator};
use self::mesh::Mesh;

use crate::enrich::grid::{Grid, GridError};

/// Most points [`Triangulation::new`] accepts (2²⁴ ≈ 16.8 million): the triangulation needs
/// a few hundred bytes per point, so this bounds it at a few gigabytes.
pub const MAX_POINTS: usize = 1 << 24;

/// Most distinct finite levels one [`Triangulation::contour_lines`] call traces.
pub const MAX_LEVELS: usize = crate::enrich::contour::MAX_LEVELS;

/// Most (triangle, level) crossings one [`Triangulation::contour_lines`] call traces, the same cap
/// as gridded contours ([`crate::enrich::contour::MAX_CROSSED_CELLS`], 2²² ≈ 4.2 million); each
/// yields one output point.
pub const MAX_CROSSINGS: usize = crate::enrich::contour::MAX_CROSSED_CELLS;

/// When more than this many points nearest the centre may lie on one line, spade's bulk loader
/// would spend quadratic time on them (its seed), so the triangulation is built by insertion.
const SEED_LIMIT: usize = 1024;

/// From this many points on, sites reach spade already in its sweep order (sorting integer keys
/// here beats its comparison sort only for large inputs).
const PRESORT_MIN: usize = 1 << 16;

/// From this many points on, and with at least two threads, the points are triangulated in two
/// halves at once and stitched (see `split`); below it the split costs more than it saves.
const SPLIT_MIN: usize = 1 << 16;

/// "No triangle" in the neighbour table.
const NONE: u32 = u32::MAX;

/// Why scattered data could not be triangulated, contoured or tessellated.
#[derive(Debug, Clone, PartialEq)]
pub enum ScatteredError {
    /// The number of values differs from the number of points.
    LengthMismatch {
        /// Number of points given.
        points: usize,
        /// Number of values given.
        values: usize,
    },
    /// A point has a NaN or infinite coordinate.
    NonFiniteCoordinate {
        /// Row of the first such point.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// More than [`MAX_POINTS`] points.
    TooManyPoints {
        /// Number of points given.
        count: usize,
        /// The cap, [`MAX_POINTS`].
        max: usize,
    },
    /// More than [`MAX_LEVELS`] distinct finite contour levels.
    TooManyLevels {
        /// Number of distinct finite levels given.
        count: usize,
        /// The cap, [`MAX_LEVELS`].
        max: usize,
    },
    /// The levels cross triangles more than [`MAX_CROSSINGS`] times in total.
    TooManyCrossings {
        /// Number of (triangle, level) crossings the request needs.
        count: usize,
        /// The cap, [`MAX_CROSSINGS`].
        max: usize,
    },
    /// The Voronoi clip rectangle is not finite or has no area.
    InvalidClip {
        /// The rectangle as given, `(xmin, ymin, xmax, ymax)`.
        clip: (f64, f64, f64, f64),
    },
    /// The resampling grid is invalid.
    Grid(GridError),
    /// The triangulator refused points that had passed validation (a bug).
    Triangulator {
        /// spade's description of the problem.
        message: String,
    },
}

impl fmt::Display for ScatteredError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScatteredError::LengthMismatch { points, values } => write!(
                f,
                "{points} points but {values} values were given; give exactly one value per point \
                 (NaN for a missing value)"
            ),
            ScatteredError::NonFiniteCoordinate { index, x, y } => write!(
                f,
                "point {index} is ({x}, {y}); coordinates must be finite numbers, so drop rows with \
                 missing or infinite coordinates first"
            ),
            ScatteredError::TooManyPoints { count, max } => write!(
                f,
                "{count} points were given but at most {max} can be triangulated; thin them first \
                 (sample them, or bin them onto a grid)"
            ),
            ScatteredError::TooManyLevels { count, max } => write!(
                f,
                "{count} distinct contour levels were given but at most {max} are allowed; pass \
                 fewer levels"
            ),
            ScatteredError::TooManyCrossings { count, max } => write!(
                f,
                "these levels cross triangles {count} times but at most {max} crossings are \
                 traced; use fewer levels or fewer points"
            ),
            ScatteredError::InvalidClip { clip: (xmin, ymin, xmax, ymax) } => write!(
                f,
                "the clip rectangle (xmin, ymin, xmax, ymax) = ({xmin}, {ymin}, {xmax}, {ymax}) is \
                 not valid; give finite corners with xmin < xmax and ymin < ymax"
            ),
            ScatteredError::Grid(e) => write!(f, "cannot resample onto this grid: {e}"),
            ScatteredError::Triangulator { message } => write!(
                f,
                "the triangulator refused the points ({message}); this is a bug in dataink, please \
                 report it together with the data"
            ),
        }
    }
}

impl std::error::Error for ScatteredError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ScatteredError::Grid(e) => Some(e),
            _ => None,
        }
    }
}

impl From<GridError> for ScatteredError {
    fn from(e: GridError) -> Self {
        ScatteredError::Grid(e)
    }
}

/// One contour line of a [`Triangulation`] at one level.
#[derive(Debug, Clone, PartialEq)]
pub struct TinLine {
    /// The level this line traces.
    pub level: f64,
    /// Vertices in data coordinates, with the region `{f >= level}` on the left. No two
    /// consecutive points are equal; a closed line does not repeat its first point at the end.
    pub points: Vec<(f64, f64)>,
    /// `true` for a ring (the last point joins back to the first). An open line starts and ends
    /// on the hull or on the edge of a hole.
    pub closed: bool,
}

/// A vertex as spade stores it: the scaled position and the index into [`Triangulation::points`].
#[derive(Debug, Clone, Copy)]
struct Site {
    pos: Point2<f64>,
    pt: u32,
}

impl HasPosition for Site {
    type Scalar = f64;

    fn position(&self) -> Point2<f64> {
        self.pos
    }
}

/// Multiplication by `2^k` for any `k` in about ±2100, in two exact steps when `2^k` itself is
/// not representable.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pow2 {
    a: f64,
    b: f64,
}

impl Pow2 {
    fn new(k: i32) -> Pow2 {
        let half = k / 2;
        Pow2 { a: pow2(half), b: pow2(k - half) }
    }

    /// `x · 2^k`; exact unless the result underflows.
    fn apply(self, x: f64) -> f64 {
        x * self.a * self.b
    }
}

/// `2^k` for `k` in `-1022..=1023` (clamped to that range).
fn pow2(k: i32) -> f64 {
    let k = k.clamp(-1022, 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// The exponent `e` with `m / 2^e` in `[0.5, 1)` for a finite `m > 0`; 0 for `m == 0`.
fn binary_exponent(m: f64) -> i32 {
    let bits = m.abs().to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    if bits == 0 {
        0
    } else if biased == 0 {
        // Subnormal: value = mantissa · 2^-1074.
        let mantissa = bits & ((1u64 << 52) - 1);
        64 - mantissa.leading_zeros() as i32 - 1074
    } else {
        biased - 1022
    }
}

/// Maps data coordinates to the frame spade sees (largest magnitude in `[0.5, 1)`) and back.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Frame {
    down: Pow2,
    up: Pow2,
}

impl Frame {
    /// The frame for data whose largest coordinate magnitude is `max_abs`.
    fn for_magnitude(max_abs: f64) -> Frame {
        let e = binary_exponent(max_abs);
        Frame { down: Pow2::new(-e), up: Pow2::new(e) }
    }

    /// Data → frame, with magnitudes below spade's smallest allowed coordinate flushed to zero
    /// and −0.0 made +0.0 (so equal positions have equal bits).
    fn to_unit(self, x: f64) -> f64 {
        let s = self.down.apply(x);
        if s.abs() < spade::MIN_ALLOWED_VALUE { 0.0 } else { s + 0.0 }
    }

    /// Frame → data.
    fn to_data(self, x: f64) -> f64 {
        self.up.apply(x)
    }
}

/// A Delaunay triangulation of scattered points with one value per point; see the module docs
/// for the rules on duplicates, missing values and degenerate input.
#[derive(Debug, Clone)]
pub struct Triangulation {
    points: Vec<(f64, f64)>,
    values: Vec<f64>,
    /// The input row of each point; empty when there were no duplicates (point `i` is row `i`).
    rows: Vec<usize>,
    triangles: Vec<[u32; 3]>,
    /// `neighbors[t][k]`: the triangle across edge `k` (from corner `k` to corner `k + 1`) of
    /// triangle `t`, or [`NONE`] on the hull.
    neighbors: Vec<[u32; 3]>,
    hull: Vec<usize>,
    merged: usize,
    frame: Frame,
    /// Bounding box of the points in the frame: `(xmin, ymin, xmax, ymax)`.
    bbox: (f64, f64, f64, f64),
    /// Start triangles for point location, built on the first [`Triangulation::interpolate`].
    locator: OnceLock<Locator>,
}

impl Triangulation {
    /// Triangulates `points`, the value of `points[i]` being `values[i]`.
    ///
    /// Errors when the lengths differ, a coordinate is not finite (naming the first such row),
    /// or there are more than [`MAX_POINTS`] points. Duplicates are merged (first row wins);
    /// fewer than three distinct points or collinear points give an `Ok` result with no triangles
    /// ([`Triangulation::is_degenerate`]). Takes about `O(n log n)` time, also for collinear,
    /// cocircular or heavily duplicated input, with one known exception: spade's bulk loader slows
    /// down sharply on a few long concentric arcs (two half-rings of 40,000 points take 1.3 s).
    pub fn new(points: &[(f64, f64)], values: &[f64]) -> Result<Triangulation, ScatteredError> {
        Triangulation::new_split_from(points, values, SPLIT_MIN)
    }

    /// [`Triangulation::new`], splitting the work in two halves from `split_min` points on.
    fn new_split_from(
        points: &[(f64, f64)],
        values: &[f64],
        split_min: usize,
    ) -> Result<Triangulation, ScatteredError> {
        if points.len() != values.len() {
            return Err(ScatteredError::LengthMismatch { points: points.len(), values: values.len() });
        }
        if points.len() > MAX_POINTS {
            return Err(ScatteredError::TooManyPoints { count: points.len(), max: MAX_POINTS });
        }
        // One branch-free pass for the bounding box; a second finds the first bad row if any.
        let mut finite = true;
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for &(x, y) in points {
            finite &= x.is_finite() & y.is_finite();
            x0 = if x < x0 { x } else { x0 };
            y0 = if y < y0 { y } else { y0 };
            x1 = if x > x1 { x } else { x1 };
            y1 = if y > y1 { y } else { y1 };
        }
        if !finite
            && let Some((index, &(x, y))) =
                points.iter().enumerate().find(|(_, p)| !(p.0.is_finite() && p.1.is_finite()))
        {
            return Err(ScatteredError::NonFiniteCoordinate { index, x, y });
        }
        let max_abs = if points.is_empty() { 0.0 } else { x0.abs().max(y0.abs()).max(x1.abs()).max(y1.abs()) };
        let frame = Frame::for_magnitude(max_abs);
        // The frame map is monotone, so this is the bounding box of the points in the frame.
        let bbox = (frame.to_unit(x0), frame.to_unit(y0), frame.to_unit(x1), frame.to_unit(y1));

        // Every row goes to spade (it merges duplicates); the vertex data names the row for now.
        let mesh = triangulate(Sites { points, frame }, split_min)?;
        let clean = |v: f64| if v.is_finite() { v } else { f64::NAN };
        let mut tin = Triangulation {
            points: Vec::new(),
            values: Vec::new(),
            rows: Vec::new(),
            triangles: Vec::new(),
            neighbors: Vec::new(),
            hull: Vec::new(),
            merged: 0,
            frame,
            bbox,
            locator: OnceLock::new(),
        };
        let mesh = match mesh {
            Some(whole) if whole.0.vertices == points.len() => {
                // No duplicates: every row is a point, under its own index.
                tin.points = points.to_vec();
                tin.values = values.iter().map(|&v| clean(v)).collect();
                // `rows` stays empty: every point is its own row.
                Some(whole)
            }
            mesh => {
                // Duplicates were merged (spade keeps an arbitrary one of each), or there is no
                // triangulation to tell: find the first row of every position, keep those rows
                // in input order, and point the corners at them.
                let first = first_rows(points, frame);
                let mut pt_of_row = vec![NONE; points.len()];
                for (row, (((slot, &f), &p), &v)) in
                    pt_of_row.iter_mut().zip(&first).zip(points).zip(values).enumerate()
                {
                    if f as usize == row {
                        *slot = tin.rows.len() as u32;
                        tin.rows.push(row);
                        tin.points.push(p);
                        tin.values.push(clean(v));
                    }
                }
                tin.merged = points.len() - tin.rows.len();
                let point_of = |row: u32| {
                    let f = first.get(row as usize).copied().unwrap_or(NONE);
                    pt_of_row.get(f as usize).copied().unwrap_or(NONE)
                };
                mesh.map(|(mut mesh, mut hull)| {
                    for tri in &mut mesh.triangles {
                        *tri = tri.map(point_of);
                    }
                    for corner in &mut hull {
                        *corner = point_of(*corner as u32) as usize;
                    }
                    // Renamed corners: start the ring at its smallest point again.
                    start_at_smallest(&mut hull);
                    (mesh, hull)
                })
            }
        };
        if let Some((mesh, hull)) = mesh {
            tin.triangles = mesh.triangles;
            tin.neighbors = mesh.neighbors;
            tin.hull = hull;
        }
        Ok(tin)
    }

    /// The position of point `i` in the frame spade and the walk see.
    fn unit(&self, i: u32) -> (f64, f64) {
        self.points
            .get(i as usize)
            .map_or((f64::NAN, f64::NAN), |&(x, y)| (self.frame.to_unit(x), self.frame.to_unit(y)))
    }

    /// The distinct points in input order (duplicates merged, the first row kept).
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    /// The value of each point; missing (non-finite) values are NaN.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The input row of point `i`: `points()[i]` is `points[row(i)]` of the input.
    pub fn row(&self, i: usize) -> usize {
        if self.rows.is_empty() { i } else { self.rows.get(i).copied().unwrap_or(i) }
    }

    /// The input row of each point, increasing (see [`Triangulation::row`]).
    pub fn rows(&self) -> impl ExactSizeIterator<Item = usize> + '_ {
        (0..self.points.len()).map(|i| self.row(i))
    }

    /// Triangles as indices into [`Triangulation::points`] (32 bits suffice: at most
    /// [`MAX_POINTS`] points), each counter-clockwise. Empty when degenerate.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The convex hull as a counter-clockwise ring of point indices starting at the smallest (first
    /// not repeated), including points that lie on a hull edge. Empty when degenerate.
    pub fn hull(&self) -> &[usize] {
        &self.hull
    }

    /// How many input rows were dropped because an earlier row had the same position.
    pub fn merged_duplicates(&self) -> usize {
        self.merged
    }

    /// `true` when there are no triangles: fewer than three distinct points, or all collinear.
    pub fn is_degenerate(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The triangle across edge `k` (from corner `k` to corner `k + 1`) of triangle `t`.
    fn neighbor(&self, t: usize, k: usize) -> Option<usize> {
        let n = *self.neighbors.get(t)?.get(k)?;
        (n != NONE).then_some(n as usize)
    }

    /// Linear interpolation at `(x, y)`: within the triangle containing the point, the plane
    /// through its three corners (barycentric weights). NaN outside the convex hull, for a NaN
    /// coordinate, when degenerate, and inside a hole (a triangle with a missing value; on an edge
    /// both of whose ends have values, the value along that edge is returned). At a data point the
    /// result is its value.
    pub fn interpolate(&self, x: f64, y: f64) -> f64 {
        if self.triangles.is_empty() {
            return f64::NAN;
        }
        let q = (self.frame.to_unit(x), self.frame.to_unit(y));
        let (x0, y0, x1, y1) = self.bbox;
        if !(q.0 >= x0 && q.0 <= x1 && q.1 >= y0 && q.1 <= y1) {
            return f64::NAN;
        }
        let value = |i: u32| self.values.get(i as usize).copied().unwrap_or(f64::NAN);
        match self.locator.get_or_init(|| Locator::new(self)).locate(self, q) {
            Some(Hit::Point(i)) => value(i),
            Some(Hit::Edge(a, b)) => {
                let (pa, pb) = (self.unit(a), self.unit(b));
                let (dx, dy) = (pb.0 - pa.0, pb.1 - pa.1);
                let len2 = dx * dx + dy * dy;
                let t = if len2 > 0.0 { (((q.0 - pa.0) * dx + (q.1 - pa.1) * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
                lerp(value(a), value(b), t)
            }
            Some(Hit::Face(t)) => {
                let Some(&tri) = self.triangles.get(t) else {
                    return f64::NAN;
                };
                let [p0, p1, p2] = tri.map(|i| self.unit(i));
                barycentric(p0, p1, p2, q, tri.map(value))
            }
            None => f64::NAN,
        }
    }

    /// Contour lines of the linear TIN at each of `levels`, ordered by level. Non-finite levels
    /// are dropped and the rest sorted and deduplicated. Each triangle crossed by a level holds
    /// one straight segment between the crossings on its edges (linear interpolation along the
    /// edge); segments are joined through shared edges into polylines. A point with
    /// `value >= level` counts as above; each line has `{f >= level}` on its left. Open lines end
    /// on the hull or on the edge of a hole. A level equal to the minimum gives no line; one equal
    /// to the maximum gives only lines along plateaus of maximal points (a lone maximum gives a
    /// line of zero length, which is dropped). Degenerate triangulations give no lines.
    ///
    /// Errors past [`MAX_LEVELS`] distinct levels or [`MAX_CROSSINGS`] crossings, found before
    /// the output is allocated.
    pub fn contour_lines(&self, levels: &[f64]) -> Result<Vec<TinLine>, ScatteredError> {
        contour::contour_lines(self, levels)
    }

    /// The Voronoi (Dirichlet) cell of every point, in the order of [`Triangulation::points`],
    /// clipped to the rectangle `clip = (xmin, ymin, xmax, ymax)`: the part of the rectangle
    /// closer to that point than to any other. Cells are convex counter-clockwise rings (first
    /// point not repeated); unbounded cells are clipped too, and the cells tile the rectangle. A
    /// cell that misses the rectangle is empty. Degenerate input still has cells: the whole
    /// rectangle for one point, parallel strips for collinear points.
    ///
    /// Errors when the rectangle is not finite or has no area.
    pub fn voronoi_cells(&self, clip: (f64, f64, f64, f64)) -> Result<Vec<Vec<(f64, f64)>>, ScatteredError> {
        voronoi::cells(self, clip)
    }

    /// Linear interpolation onto the regular grid with column coordinates `xs` and row
    /// coordinates `ys` (see [`Triangulation::interpolate`]); nodes outside the hull are NaN
    /// (missing). Errors when the axes are not a valid [`Grid`] (empty, non-finite, not strictly
    /// increasing, too many nodes), checked before any node is evaluated.
    pub fn resample(&self, xs: &[f64], ys: &[f64]) -> Result<Grid, ScatteredError> {
        Ok(Grid::from_fn(xs.to_vec(), ys.to_vec(), |x, y| self.interpolate(x, y))?)
    }
}

/// `a + t (b − a)`, falling back to the convex form when the difference overflows.
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    let v = a + t * (b - a);
    if v.is_finite() || v.is_nan() { v } else { (1.0 - t) * a + t * b }
}

/// The plane through `(p_i, z_i)` evaluated at `q`.
fn barycentric(p0: (f64, f64), p1: (f64, f64), p2: (f64, f64), q: (f64, f64), z: [f64; 3]) -> f64 {
    let (d1x, d1y) = (p1.0 - p0.0, p1.1 - p0.1);
    let (d2x, d2y) = (p2.0 - p0.0, p2.1 - p0.1);
    let (qx, qy) = (q.0 - p0.0, q.1 - p0.1);
    let det = d1x * d2y - d1y * d2x;
    if det == 0.0 {
        return f64::NAN;
    }
    let l1 = (qx * d2y - qy * d2x) / det;
    let l2 = (d1x * qy - d1y * qx) / det;
    let [z0, z1, z2] = z;
    let v = z0 + l1 * (z1 - z0) + l2 * (z2 - z0);
    if v.is_finite() || v.is_nan() { v } else { (1.0 - l1 - l2) * z0 + l1 * z1 + l2 * z2 }
}

/// For every row, the first row at the same position (itself when it is the first).
fn first_rows(points: &[(f64, f64)], frame: Frame) -> Vec<u32> {
    // Positions in the frame have no -0.0, so equal positions have equal bits.
    let mut keyed: Vec<(u64, u64, u32)> = points
        .iter()
        .enumerate()
        .map(|(row, &(x, y))| (frame.to_unit(x).to_bits(), frame.to_unit(y).to_bits(), row as u32))
        .collect();
    keyed.sort_unstable();
    let mut first: Vec<u32> = (0..points.len() as u32).collect();
    let mut group: Option<(u64, u64, u32)> = None;
    for (x, y, row) in keyed {
        match group {
            Some((gx, gy, f)) if gx == x && gy == y => {
                if let Some(slot) = first.get_mut(row as usize) {
                    *slot = f;
                }
            }
            _ => group = Some((x, y, row)),
        }
    }
    first
}

/// The input points as spade sees them: site `i` is row `i` placed in the frame.
#[derive(Debug, Clone, Copy)]
struct Sites<'a> {
    points: &'a [(f64, f64)],
    frame: Frame,
}

impl Sites<'_> {
    /// Number of rows.
    fn len(&self) -> usize {
        self.points.len()
    }

    /// The site of row `row`.
    fn get(&self, row: usize) -> Option<Site> {
        self.points.get(row).map(|&(x, y)| self.site(row, x, y))
    }

    /// Every site, by row.
    fn iter(&self) -> impl Iterator<Item = Site> + '_ {
        self.points.iter().enumerate().map(|(row, &(x, y))| self.site(row, x, y))
    }

    fn site(&self, row: usize, x: f64, y: f64) -> Site {
        Site { pos: Point2::new(self.frame.to_unit(x), self.frame.to_unit(y)), pt: row as u32 }
    }
}

/// Triangulates the sites (duplicates allowed) into a mesh and its hull
/// ring: in two halves at once from `split_min` points on when two threads are available,
/// otherwise (or when the split does not apply) in one piece. `None` when there are no
/// triangles (fewer than three distinct points, or all collinear).
fn triangulate(sites: Sites<'_>, split_min: usize) -> Result<Option<(Mesh, Vec<usize>)>, ScatteredError> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, 8);
    if sites.len() >= split_min
        && threads >= 2
        && let Some(done) = split::triangulate(sites)?
    {
        return Ok(Some(done));
    }
    let Some(dt) = build(sites.iter().collect(), threads)? else {
        return Ok(None);
    };
    let mesh = Mesh::from_spade(&dt, threads);
    if mesh.triangles.is_empty() {
        return Ok(None);
    }
    // Hull edges run clockwise around spade's triangulation; reverse for counter-clockwise and
    // start at the smallest point, as the split does.
    let mut hull: Vec<usize> = dt.convex_hull().map(|e| e.from().data().pt as usize).collect();
    hull.reverse();
    start_at_smallest(&mut hull);
    Ok(Some((mesh, hull)))
}

/// Rotates a ring so that it starts at its smallest element (the hull's order, whichever way it
/// was found).
fn start_at_smallest(ring: &mut [usize]) {
    if let Some(start) = ring.iter().enumerate().min_by_key(|&(_, &p)| p).map(|(k, _)| k) {
        ring.rotate_left(start);
    }
}

/// Triangulates the sites (duplicates allowed: spade merges them), presorting large inputs on up
/// to `threads` threads. `None` when fewer than three sites or when all are collinear and the
/// insertion path found that out.
fn build(sites: Vec<Site>, threads: usize) -> Result<Option<DelaunayTriangulation<Site>>, ScatteredError> {
    let spade_err = |e: spade::InsertionError| ScatteredError::Triangulator { message: format!("{e:?}") };
    if sites.len() < 3 {
        return Ok(None);
    }
    let centre = centroid(&sites);
    let bulk_load = |sites: Vec<Site>| Ok(Some(DelaunayTriangulation::<Site>::bulk_load(sites).map_err(spade_err)?));
    // The bulk loader's seed (see `seed_length`) costs time quadratic in its length. Small inputs
    // are usually cleared by a cheap bound and sorted by spade itself.
    if sites.len() < PRESORT_MIN {
        match seed_prefix(&sites, centre) {
            None => return Ok(None),
            Some((_, _, prefix)) if prefix <= SEED_LIMIT => return bulk_load(sites),
            // The bound is loose when many points share the smallest rounded distance (a ring
            // around the centre): count the seed exactly below.
            Some(_) => {}
        }
    }
    // Sorted in the loader's sweep order (large inputs always: it saves spade its own sort), the
    // seed can be counted exactly.
    let sorted = sweep_sorted(&sites, centre, threads);
    if seed_length(&sorted) <= SEED_LIMIT {
        return bulk_load(sorted);
    }
    drop(sorted);
    let Some((ia, ib, _)) = seed_prefix(&sites, centre) else {
        // At most two distinct positions: nothing to triangulate.
        return Ok(None);
    };
    // Many points nearest the centre (the bulk loader's seed) may be collinear: find, exactly,
    // a point off the line through the two nearest, or learn that all points are collinear.
    let (Some(&a), Some(&b)) = (sites.get(ia), sites.get(ib)) else {
        return Ok(None);
    };
    let mut probe = DelaunayTriangulation::<Site>::new();
    probe.insert(a).map_err(spade_err)?;
    probe.insert(b).map_err(spade_err)?;
    let Some(edge) = probe.directed_edges().next() else {
        return Ok(None);
    };
    let Some(ic) = sites.iter().position(|s| !edge.side_query(s.pos).is_on_line()) else {
        return Ok(None);
    };
    let Some(&c) = sites.get(ic) else {
        return Ok(None);
    };
    // Insert that triangle first, then the rest in Morton (Z-curve) order so each walk from
    // the previous vertex is short.
    let mut dt = DelaunayTriangulation::<Site>::new();
    dt.insert(a).map_err(spade_err)?;
    dt.insert(b).map_err(spade_err)?;
    let mut last = dt.insert(c).map_err(spade_err)?;
    let rest: Vec<Site> =
        sites.iter().enumerate().filter(|&(i, _)| i != ia && i != ib && i != ic).map(|(_, &s)| s).collect();
    for s in morton_order(rest) {
        last = dt.insert_with_hint(s, last).map_err(spade_err)?;
    }
    Ok(Some(dt))
}

/// The mean position of the sites, computed the way spade's bulk loader does (one pass, shared
/// by [`seed_prefix`] and [`sweep_sorted`]).
fn centroid(sites: &[Site]) -> (f64, f64) {
    let (mut sx, mut sy) = (0.0f64, 0.0f64);
    for s in sites {
        sx += s.pos.x;
        sy += s.pos.y;
    }
    let inv = 1.0 / sites.len().max(1) as f64;
    (sx * inv, sy * inv)
}

/// The sites in the order spade's bulk loader sorts them into (decreasing distance from their
/// mean, ties by increasing x, then y). spade sorts again, but finds a sorted input in one linear
/// pass; sorting plain integer keys here (on two threads when `threads` allows) is faster than
/// its comparison sort.
/// spade recomputes the mean in this order, which can differ in the last bits from the mean
/// used here; a pair that swaps because of that only costs spade a full sort.
fn sweep_sorted(sites: &[Site], (cx, cy): (f64, f64), threads: usize) -> Vec<Site> {
    // Same arithmetic as spade's `distance_2`; the complement of the (non-negative) distance's
    // bits sorts by decreasing distance.
    let key = |p: Point2<f64>| !((cx - p.x) * (cx - p.x) + (cy - p.y) * (cy - p.y)).to_bits();
    let mut keyed: Vec<(u64, u32)> = sites.iter().enumerate().map(|(i, s)| (key(s.pos), i as u32)).collect();
    let mut merged = if threads < 2 {
        keyed.sort_unstable();
        keyed
    } else {
        sort_on_two_threads(keyed)
    };
    let pos = |i: u32| sites.get(i as usize).map_or(Point2::new(0.0, 0.0), |s| s.pos);
    // Equal distances (rare): by x, then y.
    let mut start = 0;
    while let Some(&(k, _)) = merged.get(start) {
        let len = merged.get(start..).map_or(1, |rest| rest.iter().take_while(|e| e.0 == k).count()).max(1);
        if len > 1
            && let Some(run) = merged.get_mut(start..start + len)
        {
            run.sort_by(|a, b| {
                let (p, q) = (pos(a.1), pos(b.1));
                p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y))
            });
        }
        start += len;
    }
    // Gather (random reads, so two threads help).
    if threads < 2 {
        let mut out = Vec::with_capacity(merged.len());
        out.extend(merged.iter().filter_map(|&(_, i)| sites.get(i as usize).copied()));
        return out;
    }
    let mut out = vec![Site { pos: Point2::new(0.0, 0.0), pt: 0 }; merged.len()];
    let gather = |part: &mut [Site], order: &[(u64, u32)]| {
        for (slot, &(_, i)) in part.iter_mut().zip(order) {
            if let Some(&s) = sites.get(i as usize) {
                *slot = s;
            }
        }
    };
    let half = merged.len().div_ceil(2).max(1);
    let started = std::thread::scope(|scope| {
        let mut parts = out.chunks_mut(half).zip(merged.chunks(half));
        let here = parts.next();
        let started = parts
            .all(|(part, order)| std::thread::Builder::new().spawn_scoped(scope, move || gather(part, order)).is_ok());
        if let Some((part, order)) = here {
            gather(part, order);
        }
        started
    });
    if !started && let (Some(part), Some(order)) = (out.get_mut(half..), merged.get(half..)) {
        gather(part, order);
    }
    out
}

/// `keyed` sorted: each half on its own thread, then merged.
fn sort_on_two_threads(mut keyed: Vec<(u64, u32)>) -> Vec<(u64, u32)> {
    let mid = keyed.len() / 2;
    let (lo, hi) = keyed.split_at_mut(mid);
    let started = std::thread::scope(|scope| {
        let started = std::thread::Builder::new().spawn_scoped(scope, || lo.sort_unstable()).is_ok();
        hi.sort_unstable();
        started
    });
    if !started && let Some(lo) = keyed.get_mut(..mid) {
        lo.sort_unstable();
    }
    let (lo, hi) = keyed.split_at(mid);
    let mut merged: Vec<(u64, u32)> = Vec::with_capacity(keyed.len());
    let (mut i, mut j) = (0, 0);
    while let (Some(&a), Some(&b)) = (lo.get(i), hi.get(j)) {
        if a <= b {
            merged.push(a);
            i += 1;
        } else {
            merged.push(b);
            j += 1;
        }
    }
    merged.extend_from_slice(lo.get(i..).unwrap_or_default());
    merged.extend_from_slice(hi.get(j..).unwrap_or_default());
    merged
}

/// The bulk loader's seed: it inserts points by increasing distance from their mean until they
/// are not all on one line, at a cost quadratic in their number. Returns the indices of the two
/// nearest distinct points and a bound on the seed's length: the number of points no farther
/// than the nearest one that is certainly off the line through those two (float orientation
/// with a conservative error bound). `None` when there are not two distinct positions.
fn seed_prefix(sites: &[Site], (cx, cy): (f64, f64)) -> Option<(usize, usize, usize)> {
    let dist = |p: Point2<f64>| (cx - p.x) * (cx - p.x) + (cy - p.y) * (cy - p.y);
    let nearest = |skip: Option<Point2<f64>>| {
        sites
            .iter()
            .enumerate()
            .filter(|(_, s)| skip != Some(s.pos))
            .min_by(|(_, s), (_, t)| dist(s.pos).total_cmp(&dist(t.pos)))
            .map(|(i, _)| i)
    };
    let ia = nearest(None)?;
    let a = sites.get(ia)?.pos;
    let ib = nearest(Some(a))?;
    let b = sites.get(ib)?.pos;
    let reach =
        sites.iter().filter(|s| certainly_off_line(a, b, s.pos)).map(|s| dist(s.pos)).fold(f64::INFINITY, f64::min);
    let prefix = sites.iter().filter(|s| dist(s.pos) <= reach).count();
    Some((ia, ib, prefix))
}

/// How many sites spade's bulk loader inserts for its seed, given them in its sweep order: it pops
/// the nearest first until the last three distinct positions are not on one line (exact test;
/// spade also wants their mean inside a face, which can only add a few more).
fn seed_length(sorted: &[Site]) -> usize {
    let mut last: [Option<Point2<f64>>; 3] = [None; 3];
    for (popped, site) in sorted.iter().rev().enumerate() {
        if last[2] == Some(site.pos) {
            // A repeated position (equal positions are adjacent in this order) adds no vertex.
            continue;
        }
        last = [last[1], last[2], Some(site.pos)];
        if let [Some(a), Some(b), Some(c)] = last
            && locate::orient((a.x, a.y), (b.x, b.y), (c.x, c.y)) != 0.0
        {
            return popped + 1;
        }
    }
    sorted.len()
}

/// `true` when `p` is certainly off the line through `a` and `b`: the floating-point orientation
/// clears a conservative error bound (frame coordinates, magnitudes below 1). `false` may still
/// be off the line, by a hair.
fn certainly_off_line(a: Point2<f64>, b: Point2<f64>, p: Point2<f64>) -> bool {
    let left = (b.x - a.x) * (p.y - a.y);
    let right = (b.y - a.y) * (p.x - a.x);
    let detsum = left.abs() + right.abs();
    detsum > 1e-280 && (left - right).abs() > 1e-14 * detsum
}

/// `sites` sorted along a Z-order curve over their bounding box.
fn morton_order(sites: Vec<Site>) -> Vec<Site> {
    let (x0, y0, x1, y1) =
        sites.iter().fold((f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY), |b, s| {
            (b.0.min(s.pos.x), b.1.min(s.pos.y), b.2.max(s.pos.x), b.3.max(s.pos.y))
        });
    let quantize = |v: f64, lo: f64, hi: f64| -> u32 {
        let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
        (t.clamp(0.0, 1.0) * 65535.0) as u32
    };
    let spread = |mut v: u32| -> u32 {
        v &= 0xffff;
        v = (v | (v << 8)) & 0x00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333;
        (v | (v << 1)) & 0x5555_5555
    };
    let mut keyed: Vec<(u32, Site)> = sites
        .into_iter()
        .map(|s| (spread(quantize(s.pos.x, x0, x1)) | (spread(quantize(s.pos.y, y0, y1)) << 1), s))
        .collect();
    keyed.sort_by_key(|e| e.0);
    keyed.into_iter().map(|e| e.1).collect()
}
