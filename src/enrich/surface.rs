//! Surface view of a 2D grid: the heightfield `z = f(x, y)` drawn in 3D under an orthographic
//! projection, with hidden-surface removal by painter's order and Lambert shading.
//!
//! [`project`] turns a [`Grid`] into a [`SurfaceProjection`]: one [`ProjectedQuad`] per grid cell,
//! sorted back to front, plus the twelve edges of the bounding box and three axis lines for
//! ticks. Drawing the quads in order gives a correct picture of the surface.
//!
//! Rules:
//! - **Camera.** Orthographic (parallel) projection, so parallel lines stay parallel and
//!   [`SurfaceProjection::project_point`] is affine. The camera sits in direction
//!   `(cos el cos az, cos el sin az, sin el)` from the scene: azimuth is measured
//!   counter-clockwise from +x in the x-y plane, elevation up from that plane. The default
//!   [`View`] is azimuth −60°, elevation 30° (the viewer is on the −y side, a little toward +x).
//!   Elevation is clamped to `[MIN_ELEVATION_DEG, 90]`: the surface is always seen from above.
//! - **Box.** x and y are drawn at the same scale (data units), so a terrain keeps its shape;
//!   the larger horizontal extent is 1 model unit. `z_scale` is the vertical exaggeration: one z
//!   unit is drawn `z_scale` times as long as one x or y unit. By default it is chosen so the
//!   z range is drawn [`DEFAULT_HEIGHT_RATIO`] (one half) of the larger horizontal extent; a
//!   constant surface is drawn flat. The box is the full grid extent times the z range of all
//!   non-missing values.
//! - **Screen.** Screen coordinates put the whole projected box in the unit square with the aspect
//!   preserved, y up: the larger screen dimension spans exactly `[0, 1]` and the smaller one is
//!   centred in it ([`SurfaceProjection::size`] gives both).
//! - **Holes.** A cell with a missing (NaN) corner produces no quad.
//! - **Decimation.** A grid with more than [`MAX_CELLS_PER_AXIS`] cells along an axis is drawn
//!   from every `s`-th node along that axis (the smallest stride that fits), always keeping the
//!   last node so the surface covers the whole extent; so at most 400 × 400 quads. Only the kept
//!   nodes are looked at, so a hole narrower than the stride may vanish.
//!   [`SurfaceProjection::stride`] reports the strides.
//! - **Painter's order.** Cells are sorted by the depth of their centre along the horizontal
//!   part of the view direction, farthest first. For a heightfield on a rectilinear grid seen
//!   from above this is exact: a ray's horizontal track crosses cells in order of increasing
//!   horizontal depth, and the surface over a cell lies within that cell's column.
//! - **Shading.** Lambert: the cosine between the quad's normal (the cross product of its
//!   diagonals, taken on the drawn, exaggerated surface, pointing up) and the direction toward the
//!   [`Light`], clamped to `[ambient, 1]`.

use std::fmt;

use super::grid::Grid;

/// Largest number of cells drawn along each grid axis; larger grids are decimated by striding.
pub const MAX_CELLS_PER_AXIS: usize = 400;

/// Smallest view elevation in degrees; lower (and non-positive) elevations are raised to it.
pub const MIN_ELEVATION_DEG: f64 = 1.0;

/// Default drawn height of the z range, as a fraction of the larger horizontal extent.
pub const DEFAULT_HEIGHT_RATIO: f64 = 0.5;

/// Largest drawn height of the z range, as a multiple of the larger horizontal extent.
pub const MAX_HEIGHT_RATIO: f64 = 1000.0;

/// Where the surface is seen from (orthographic camera direction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Degrees counter-clockwise from +x, in the x-y plane, toward the camera.
    pub azimuth_deg: f64,
    /// Degrees above the x-y plane; clamped to `[MIN_ELEVATION_DEG, 90]`.
    pub elevation_deg: f64,
}

impl Default for View {
    /// Azimuth −60°, elevation 30°.
    fn default() -> Self {
        View { azimuth_deg: -60.0, elevation_deg: 30.0 }
    }
}

/// A directional light for Lambert shading, fixed in data space (it does not turn with the view).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Degrees counter-clockwise from +x toward the light.
    pub azimuth_deg: f64,
    /// Degrees above the x-y plane toward the light (90 = straight above).
    pub elevation_deg: f64,
    /// Smallest shade, in `[0, 1]`: faces turned away from the light get this much.
    pub ambient: f64,
}

impl Default for Light {
    /// Azimuth −120°, elevation 45°, ambient 0.25: from the front left of the default view.
    fn default() -> Self {
        Light { azimuth_deg: -120.0, elevation_deg: 45.0, ambient: 0.25 }
    }
}

/// One of the three data axes of the surface box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceAxis {
    /// The grid's column axis.
    X,
    /// The grid's row axis.
    Y,
    /// The value axis (height).
    Z,
}

/// One grid cell as drawn: a quadrilateral in screen coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct ProjectedQuad {
    /// Screen positions of the corners at nodes `(i, j)`, `(i', j)`, `(i', j')`, `(i, j')`, where
    /// `(i', j')` is the next kept node (`i + 1`, `j + 1` unless decimated).
    pub corners: [(f64, f64); 4],
    /// Horizontal depth of the cell centre in model units; larger is farther. Quads are sorted
    /// by decreasing depth.
    pub depth: f64,
    /// Lambert shade in `[ambient, 1]`.
    pub shade: f64,
    /// Mean of the four corner values (data units), for colouring.
    pub value: f64,
    /// Grid indices `(i, j)` of the cell's first corner node.
    pub cell: (usize, usize),
}

/// One of the twelve edges of the bounding box, in screen coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct BoxEdge {
    /// Screen position of one end.
    pub start: (f64, f64),
    /// Screen position of the other end.
    pub end: (f64, f64),
    /// The data axis the edge runs along.
    pub axis: SurfaceAxis,
    /// True when neither box face meeting at the edge faces the camera: the edge is behind
    /// everything inside the box. Draw hidden edges before the quads (or dashed), the others
    /// after.
    pub hidden: bool,
}

/// A box edge chosen to carry one axis's ticks.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisLine {
    /// The data axis the line runs along.
    pub axis: SurfaceAxis,
    /// Data point `[x, y, z]` at the low end of the axis.
    pub from: [f64; 3],
    /// Data point `[x, y, z]` at the high end of the axis.
    pub to: [f64; 3],
    /// Screen position of `from`.
    pub start: (f64, f64),
    /// Screen position of `to`.
    pub end: (f64, f64),
    /// Unit screen direction pointing away from the box, for tick marks and labels.
    pub outward: (f64, f64),
}

impl AxisLine {
    /// The data point on this line where the axis coordinate is `value` (pass it to
    /// [`SurfaceProjection::project_point`] to place a tick).
    pub fn at(&self, value: f64) -> [f64; 3] {
        let mut p = self.from;
        let k = match self.axis {
            SurfaceAxis::X => 0,
            SurfaceAxis::Y => 1,
            SurfaceAxis::Z => 2,
        };
        if let Some(c) = p.get_mut(k) {
            *c = value;
        }
        p
    }
}

/// The projected surface: quads in painter's order, box edges, axis lines.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceProjection {
    /// One quad per drawn cell, back to front: drawing them in order hides what is behind.
    pub quads: Vec<ProjectedQuad>,
    /// The twelve edges of the bounding box.
    pub box_edges: Vec<BoxEdge>,
    /// Tick lines for x, y and z, in that order. x and y run along the bottom edges nearest the
    /// camera; z along the vertical edge farthest to the left on screen.
    pub axes: [AxisLine; 3],
    /// Width and height of the projected box in screen units; the larger is 1.
    pub size: (f64, f64),
    /// Node strides `(along x, along y)` used to decimate the grid; `(1, 1)` when not decimated.
    pub stride: (usize, usize),
    /// Data range of the box along x.
    pub x_range: (f64, f64),
    /// Data range of the box along y.
    pub y_range: (f64, f64),
    /// Data range of the box along z: smallest and largest non-missing value.
    pub z_range: (f64, f64),
    /// Drawn height of the z range as a fraction of the larger horizontal extent.
    pub height_ratio: f64,
    transform: Transform,
}

impl SurfaceProjection {
    /// Screen position of the data point `(x, y, z)` (same normalisation as the quads). Affine, so
    /// points outside the box are fine; a non-finite input gives a non-finite result.
    pub fn project_point(&self, x: f64, y: f64, z: f64) -> (f64, f64) {
        self.transform.project(x, y, z)
    }
}

/// Why a surface could not be projected.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceError {
    /// The grid has fewer than two nodes along an axis, so it has no cells.
    NoCells {
        /// Number of columns.
        nx: usize,
        /// Number of rows.
        ny: usize,
    },
    /// Every cell has a missing corner, so nothing can be drawn.
    NoCompleteCells {
        /// Number of columns.
        nx: usize,
        /// Number of rows.
        ny: usize,
    },
    /// A view or light angle is NaN or infinite.
    NonFiniteAngle {
        /// Which angle, e.g. `"view azimuth"`.
        what: &'static str,
        /// The offending value.
        value: f64,
    },
    /// The ambient light level is outside `[0, 1]` or NaN.
    Ambient {
        /// The offending value.
        value: f64,
    },
    /// The vertical exaggeration is not a positive finite number.
    ZScale {
        /// The offending value.
        value: f64,
    },
    /// The vertical exaggeration draws the z range more than [`MAX_HEIGHT_RATIO`] times the larger
    /// horizontal extent.
    ZScaleTooLarge {
        /// The z scale given.
        value: f64,
        /// The resulting height ratio.
        ratio: f64,
    },
}

impl fmt::Display for SurfaceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoCells { nx, ny } => write!(
                f,
                "a surface needs at least 2 x 2 grid nodes, the grid has {nx} x {ny}; give at least two \
                 distinct coordinates along each axis"
            ),
            Self::NoCompleteCells { nx, ny } => write!(
                f,
                "every cell of the {nx} x {ny} grid has a missing (NaN) corner, so there is no surface to \
                 draw; fill the missing values or choose another value column"
            ),
            Self::NonFiniteAngle { what, value } => {
                write!(f, "the {what} is {value}; give a finite angle in degrees")
            }
            Self::Ambient { value } => {
                write!(f, "the ambient light level is {value}; give a number between 0 and 1")
            }
            Self::ZScale { value } => write!(
                f,
                "the z scale (vertical exaggeration) is {value}; give a positive number, or leave it \
                 unset to draw the z range at {DEFAULT_HEIGHT_RATIO} of the larger horizontal extent"
            ),
            Self::ZScaleTooLarge { value, ratio } => write!(
                f,
                "a z scale of {value} draws the z range {ratio:e} times as tall as the grid is wide \
                 (at most {MAX_HEIGHT_RATIO}); give a smaller z scale or leave it unset"
            ),
        }
    }
}

impl std::error::Error for SurfaceError {}

/// Data → model → screen mapping.
#[derive(Debug, Clone, PartialEq)]
struct Transform {
    x: (f64, f64),
    y: (f64, f64),
    z: (f64, f64),
    /// Model extents of x, y and z (the larger of the first two is 1; z is the height ratio).
    extent: [f64; 3],
    /// Screen right, screen up and toward-camera unit vectors in model space.
    right: [f64; 3],
    up: [f64; 3],
    eye: [f64; 3],
    /// Raw screen minimum, scale, and offsets centring the smaller dimension.
    min: (f64, f64),
    scale: f64,
    offset: (f64, f64),
}

impl Transform {
    /// Model coordinates of a data point: the box is centred on the origin.
    fn model(&self, x: f64, y: f64, z: f64) -> [f64; 3] {
        let [ex, ey, ez] = self.extent;
        [
            (unit(self.x.0, self.x.1, x) - 0.5) * ex,
            (unit(self.y.0, self.y.1, y) - 0.5) * ey,
            (unit(self.z.0, self.z.1, z) - 0.5) * ez,
        ]
    }

    /// Raw (unnormalised) screen coordinates of a model point.
    fn raw(&self, p: [f64; 3]) -> (f64, f64) {
        (dot(self.right, p), dot(self.up, p))
    }

    /// Unit-square screen coordinates of a model point.
    fn screen(&self, p: [f64; 3]) -> (f64, f64) {
        let (sx, sy) = self.raw(p);
        ((sx - self.min.0) * self.scale + self.offset.0, (sy - self.min.1) * self.scale + self.offset.1)
    }

    fn project(&self, x: f64, y: f64, z: f64) -> (f64, f64) {
        self.screen(self.model(x, y, z))
    }

    /// Depth of a model point along the horizontal part of the view direction (larger = farther).
    fn horizontal_depth(&self, p: [f64; 3]) -> f64 {
        -(self.eye[0] * p[0] + self.eye[1] * p[1])
    }

    /// Full 3D depth of a data point along the view direction (larger = farther).
    #[cfg(test)]
    fn view_depth(&self, x: f64, y: f64, z: f64) -> f64 {
        -dot(self.eye, self.model(x, y, z))
    }
}

/// Projects the heightfield of `grid` as seen from `view`, shaded by `light`; see the module docs
/// for the camera, box, decimation, hole and ordering rules. `z_scale` is the vertical
/// exaggeration (drawn length of one z unit over that of one x or y unit); `None` draws the z range
/// at half the larger horizontal extent.
pub fn project(grid: &Grid, view: View, light: Light, z_scale: Option<f64>) -> Result<SurfaceProjection, SurfaceError> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (Some(&x0), Some(&x1), Some(&y0), Some(&y1)) = (grid.xs().first(), grid.xs().last(), grid.ys().first(), grid.ys().last())
    else {
        return Err(SurfaceError::NoCells { nx, ny });
    };
    if nx < 2 || ny < 2 {
        return Err(SurfaceError::NoCells { nx, ny });
    }
    for (what, value) in [
        ("view azimuth", view.azimuth_deg),
        ("view elevation", view.elevation_deg),
        ("light azimuth", light.azimuth_deg),
        ("light elevation", light.elevation_deg),
    ] {
        if !value.is_finite() {
            return Err(SurfaceError::NonFiniteAngle { what, value });
        }
    }
    let ambient = light.ambient;
    if !(0.0..=1.0).contains(&ambient) {
        return Err(SurfaceError::Ambient { value: ambient });
    }
    let Some(z_range) = grid.range() else {
        return Err(SurfaceError::NoCompleteCells { nx, ny });
    };

    // Model extents: the larger horizontal extent is 1.
    let q = span_ratio((x0, x1), (y0, y1));
    let (ex, ey) = if q >= 1.0 { (1.0, 1.0 / q) } else { (q, 1.0) };
    let wide = if q >= 1.0 { (x0, x1) } else { (y0, y1) };
    let height_ratio = match z_scale {
        None => {
            if z_range.1 > z_range.0 {
                DEFAULT_HEIGHT_RATIO
            } else {
                0.0
            }
        }
        Some(k) => {
            if !(k > 0.0 && k.is_finite()) {
                return Err(SurfaceError::ZScale { value: k });
            }
            let ratio = k * span_ratio(z_range, wide);
            if !(ratio <= MAX_HEIGHT_RATIO) {
                return Err(SurfaceError::ZScaleTooLarge { value: k, ratio });
            }
            ratio
        }
    };

    let az = view.azimuth_deg.to_radians();
    let el = view.elevation_deg.clamp(MIN_ELEVATION_DEG, 90.0).to_radians();
    let (sa, ca, se, ce) = (az.sin(), az.cos(), el.sin(), el.cos());
    let mut t = Transform {
        x: (x0, x1),
        y: (y0, y1),
        z: z_range,
        extent: [ex, ey, height_ratio],
        right: [-sa, ca, 0.0],
        up: [-se * ca, -se * sa, ce],
        eye: [ce * ca, ce * sa, se],
        min: (0.0, 0.0),
        scale: 1.0,
        offset: (0.0, 0.0),
    };

    // Fit the projected box into the unit square.
    let corners = box_corners(&t);
    let (mut lo, mut hi) = ((f64::INFINITY, f64::INFINITY), (f64::NEG_INFINITY, f64::NEG_INFINITY));
    for &p in &corners {
        let (sx, sy) = t.raw(p);
        lo = (lo.0.min(sx), lo.1.min(sy));
        hi = (hi.0.max(sx), hi.1.max(sy));
    }
    let (w, h) = (hi.0 - lo.0, hi.1 - lo.1);
    let big = w.max(h);
    t.min = lo;
    t.scale = if big > 0.0 && big.is_finite() { 1.0 / big } else { 1.0 };
    t.offset = (0.5 * (1.0 - w * t.scale), 0.5 * (1.0 - h * t.scale));
    let size = (w * t.scale, h * t.scale);

    // Decimate, then build one quad per complete cell.
    let (ii, sx) = strided(nx);
    let (jj, sy) = strided(ny);
    let light_dir = {
        let (la, le) = (light.azimuth_deg.to_radians(), light.elevation_deg.to_radians());
        [le.cos() * la.cos(), le.cos() * la.sin(), le.sin()]
    };
    let mut quads = Vec::with_capacity(ii.len().saturating_sub(1).saturating_mul(jj.len().saturating_sub(1)));
    for jw in jj.windows(2) {
        let &[j0, j1] = jw else { continue };
        for iw in ii.windows(2) {
            let &[i0, i1] = iw else { continue };
            if let Some(quad) = make_quad(grid, &t, light_dir, ambient, (i0, i1), (j0, j1)) {
                quads.push(quad);
            }
        }
    }
    if quads.is_empty() {
        return Err(SurfaceError::NoCompleteCells { nx, ny });
    }
    quads.sort_by(|a, b| b.depth.total_cmp(&a.depth).then(a.cell.1.cmp(&b.cell.1)).then(a.cell.0.cmp(&b.cell.0)));

    let box_edges = box_edges(&t, &corners);
    let axes = axis_lines(&t);
    Ok(SurfaceProjection {
        quads,
        box_edges,
        axes,
        size,
        stride: (sx, sy),
        x_range: (x0, x1),
        y_range: (y0, y1),
        z_range,
        height_ratio,
        transform: t,
    })
}

/// The quad of the cell with corner nodes `i0, i1` × `j0, j1`, or `None` when a corner is missing.
fn make_quad(
    grid: &Grid,
    t: &Transform,
    light: [f64; 3],
    ambient: f64,
    (i0, i1): (usize, usize),
    (j0, j1): (usize, usize),
) -> Option<ProjectedQuad> {
    let (xs, ys) = (grid.xs(), grid.ys());
    let (&xa, &xb, &ya, &yb) = (xs.get(i0)?, xs.get(i1)?, ys.get(j0)?, ys.get(j1)?);
    let z = [grid.value(i0, j0), grid.value(i1, j0), grid.value(i1, j1), grid.value(i0, j1)];
    if z.iter().any(|v| v.is_nan()) {
        return None;
    }
    let p = [t.model(xa, ya, z[0]), t.model(xb, ya, z[1]), t.model(xb, yb, z[2]), t.model(xa, yb, z[3])];
    let d1 = sub(p[2], p[0]);
    let d2 = sub(p[3], p[1]);
    let n = cross(d1, d2);
    let len = dot(n, n).sqrt();
    let lambert = dot(n, light) / len;
    let shade = if lambert.is_nan() { ambient } else { lambert.max(ambient).min(1.0) };
    let centre = [0.25 * (p[0][0] + p[1][0] + p[2][0] + p[3][0]), 0.25 * (p[0][1] + p[1][1] + p[2][1] + p[3][1]), 0.0];
    Some(ProjectedQuad {
        corners: [t.screen(p[0]), t.screen(p[1]), t.screen(p[2]), t.screen(p[3])],
        depth: t.horizontal_depth(centre),
        shade,
        value: 0.25 * z[0] + 0.25 * z[1] + 0.25 * z[2] + 0.25 * z[3],
        cell: (i0, j0),
    })
}

/// The eight corners of the model box; bit 0 of the index picks the x side, bit 1 y, bit 2 z.
fn box_corners(t: &Transform) -> [[f64; 3]; 8] {
    let mut corners = [[0.0; 3]; 8];
    for (c, corner) in corners.iter_mut().enumerate() {
        for (k, coord) in corner.iter_mut().enumerate() {
            let side = if c >> k & 1 == 1 { 0.5 } else { -0.5 };
            *coord = side * t.extent.get(k).copied().unwrap_or(0.0);
        }
    }
    corners
}

/// Whether the box face on `side` (0 = low, 1 = high) of model axis `k` faces the camera.
fn faces_camera(t: &Transform, k: usize, side: usize) -> bool {
    let e = t.eye.get(k).copied().unwrap_or(0.0);
    let outward = if side == 1 { e } else { -e };
    outward > 1e-12
}

/// The twelve box edges, each flagged hidden when neither adjacent face faces the camera.
fn box_edges(t: &Transform, corners: &[[f64; 3]; 8]) -> Vec<BoxEdge> {
    const AXES: [SurfaceAxis; 3] = [SurfaceAxis::X, SurfaceAxis::Y, SurfaceAxis::Z];
    let mut edges = Vec::with_capacity(12);
    for (c, &a) in corners.iter().enumerate() {
        for (k, &axis) in AXES.iter().enumerate() {
            if c >> k & 1 == 1 {
                continue;
            }
            let Some(&b) = corners.get(c | 1 << k) else { continue };
            let visible = (0..3).filter(|&m| m != k).any(|m| faces_camera(t, m, c >> m & 1));
            edges.push(BoxEdge { start: t.screen(a), end: t.screen(b), axis, hidden: !visible });
        }
    }
    edges
}

/// Screen direction of the model direction `d`, normalised; `fallback` when it is edge-on.
fn screen_direction(t: &Transform, d: [f64; 3], fallback: (f64, f64)) -> (f64, f64) {
    let (sx, sy) = (dot(t.right, d), dot(t.up, d));
    let len = sx.hypot(sy);
    if len > 1e-9 { (sx / len, sy / len) } else { fallback }
}

/// Tick lines: x and y along the bottom edges nearest the camera, z along the leftmost vertical
/// edge.
fn axis_lines(t: &Transform) -> [AxisLine; 3] {
    let (x0, x1) = t.x;
    let (y0, y1) = t.y;
    let (z0, z1) = t.z;
    let line = |axis, from: [f64; 3], to: [f64; 3], outward| AxisLine {
        axis,
        from,
        to,
        start: t.project(from[0], from[1], from[2]),
        end: t.project(to[0], to[1], to[2]),
        outward,
    };
    // The camera is on the high side of an axis when the eye vector points that way.
    let near_y_high = t.eye[1] > 0.0;
    let near_x_high = t.eye[0] > 0.0;
    let y_near = if near_y_high { y1 } else { y0 };
    let x_near = if near_x_high { x1 } else { x0 };
    let x_out = screen_direction(t, [0.0, if near_y_high { 1.0 } else { -1.0 }, 0.0], (0.0, -1.0));
    let y_out = screen_direction(t, [if near_x_high { 1.0 } else { -1.0 }, 0.0, 0.0], (0.0, -1.0));
    // Leftmost vertical edge: the bottom corner with the smallest screen x.
    let mut best = (x0, y0);
    let mut best_sx = f64::INFINITY;
    for (x, y) in [(x0, y0), (x1, y0), (x0, y1), (x1, y1)] {
        let (sx, _) = t.project(x, y, z0);
        if sx < best_sx {
            best_sx = sx;
            best = (x, y);
        }
    }
    [
        line(SurfaceAxis::X, [x0, y_near, z0], [x1, y_near, z0], x_out),
        line(SurfaceAxis::Y, [x_near, y0, z0], [x_near, y1, z0], y_out),
        line(SurfaceAxis::Z, [best.0, best.1, z0], [best.0, best.1, z1], (-1.0, 0.0)),
    ]
}

/// Node indices kept along an axis of `n` nodes and the stride: every `s`-th node plus the last,
/// with `s` the smallest stride leaving at most [`MAX_CELLS_PER_AXIS`] cells.
fn strided(n: usize) -> (Vec<usize>, usize) {
    let cells = n.saturating_sub(1);
    let stride = cells.div_ceil(MAX_CELLS_PER_AXIS).max(1);
    let mut kept: Vec<usize> = (0..cells).step_by(stride).collect();
    if n > 0 {
        kept.push(cells);
    }
    (kept, stride)
}

/// Position of `v` on the range `[a, b]` as a fraction (0 at `a`, 1 at `b`, unclamped) without
/// overflow for huge spans; 0.5 when `a == b`.
fn unit(a: f64, b: f64, v: f64) -> f64 {
    if a == b {
        return 0.5;
    }
    let (num, den) = (v - a, b - a);
    if num.is_finite() && den.is_finite() { num / den } else { (0.5 * v - 0.5 * a) / (0.5 * b - 0.5 * a) }
}

/// Length of the range `a` over that of `b`, without overflow for huge spans.
fn span_ratio(a: (f64, f64), b: (f64, f64)) -> f64 {
    let (num, den) = (a.1 - a.0, b.1 - b.0);
    if num.is_finite() && den.is_finite() { num / den } else { (0.5 * a.1 - 0.5 * a.0) / (0.5 * b.1 - 0.5 * b.0) }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
