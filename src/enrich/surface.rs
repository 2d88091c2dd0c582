//! Surface view of a 2D grid: the heightfield `z = f(x, y)` drawn in 3D through the shared
//! [`Camera`](super::camera), with a painter's order of its cells and Lambert shading.
//!
//! [`project`] turns a [`Grid`] into a [`SurfaceProjection`]: one [`ProjectedQuad`] per grid cell,
//! sorted back to front, each with the z-buffer depth of its corners, plus the twelve edges of the
//! bounding box and three axis lines for ticks. Drawing the quads in order gives a correct picture
//! of the surface (orthographic views); a z-buffer over the corner depths gives one in any view.
//!
//! Rules:
//! - **Camera.** [`super::camera`]'s: by default orthographic (parallel) projection, so parallel
//!   lines stay parallel and [`SurfaceProjection::project_point`] is affine. The camera sits in
//!   direction `(cos el cos az, cos el sin az, sin el)` from the scene: azimuth is measured
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
//!   horizontal depth, and the surface over a cell lies within that cell's column. (Under a
//!   perspective view the order is the same and only approximate; use the corner depths.)
//! - **Shading.** [`Light::lambert`]: the cosine between the quad's normal (the cross product of its
//!   diagonals, taken on the drawn, exaggerated surface, pointing up) and the direction toward the
//!   [`Light`], times its diffuse strength, clamped to `[ambient, 1]`.

use std::fmt;

pub use super::camera::{AxisLine, Light, View};
use super::camera::{Camera, CameraError, axis_lines, cross, span_ratio, sub};
use super::grid::Grid;

/// Largest number of cells drawn along each grid axis; larger grids are decimated by striding.
pub const MAX_CELLS_PER_AXIS: usize = 400;

/// Smallest view elevation in degrees; lower (and non-positive) elevations are raised to it.
pub const MIN_ELEVATION_DEG: f64 = 1.0;

/// Default drawn height of the z range, as a fraction of the larger horizontal extent.
pub const DEFAULT_HEIGHT_RATIO: f64 = 0.5;

/// Largest drawn height of the z range, as a multiple of the larger horizontal extent.
pub const MAX_HEIGHT_RATIO: f64 = 1000.0;

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
    /// Z-buffer depth of each corner ([`Camera::depth`]: larger is nearer, linear on screen), in
    /// the order of `corners`.
    pub depths: [f64; 4],
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
    camera: Camera,
}

impl SurfaceProjection {
    /// Screen position of the data point `(x, y, z)` (same normalisation as the quads). Affine, so
    /// points outside the box are fine; a non-finite input gives a non-finite result.
    pub fn project_point(&self, x: f64, y: f64, z: f64) -> (f64, f64) {
        self.camera.project([x, y, z])
    }

    /// The camera the surface was projected with.
    pub fn camera(&self) -> &Camera {
        &self.camera
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
    /// The view (zoom, field of view) or the light (diffuse, highlight) is out of range.
    Camera(CameraError),
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
            Self::Camera(e) => e.fmt(f),
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

/// Depth of a model point along the horizontal part of the view direction (larger = farther).
fn horizontal_depth(camera: &Camera, p: [f64; 3]) -> f64 {
    let eye = camera.toward_camera();
    -(eye[0] * p[0] + eye[1] * p[1])
}

/// Projects the heightfield of `grid` as seen from `view`, shaded by `light`; see the module docs
/// for the camera, box, decimation, hole and ordering rules. `z_scale` is the vertical
/// exaggeration (drawn length of one z unit over that of one x or y unit); `None` draws the z range
/// at half the larger horizontal extent.
pub fn project(grid: &Grid, view: View, light: Light, z_scale: Option<f64>) -> Result<SurfaceProjection, SurfaceError> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (Some(&x0), Some(&x1), Some(&y0), Some(&y1)) =
        (grid.xs().first(), grid.xs().last(), grid.ys().first(), grid.ys().last())
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
            if ratio.is_nan() || ratio > MAX_HEIGHT_RATIO {
                return Err(SurfaceError::ZScaleTooLarge { value: k, ratio });
            }
            ratio
        }
    };

    let view = View { elevation_deg: view.elevation_deg.clamp(MIN_ELEVATION_DEG, 90.0), ..view };
    light.check().map_err(SurfaceError::Camera)?;
    let camera =
        Camera::new([(x0, x1), (y0, y1), z_range], [ex, ey, height_ratio], view).map_err(SurfaceError::Camera)?;
    let corners = camera.corners();
    let size = camera.size();

    // Decimate, then build one quad per complete cell.
    let (ii, sx) = strided(nx);
    let (jj, sy) = strided(ny);
    let mut quads = Vec::with_capacity(ii.len().saturating_sub(1).saturating_mul(jj.len().saturating_sub(1)));
    for jw in jj.windows(2) {
        let &[j0, j1] = jw else { continue };
        for iw in ii.windows(2) {
            let &[i0, i1] = iw else { continue };
            if let Some(quad) = make_quad(grid, &camera, &light, (i0, i1), (j0, j1)) {
                quads.push(quad);
            }
        }
    }
    if quads.is_empty() {
        return Err(SurfaceError::NoCompleteCells { nx, ny });
    }
    quads.sort_by(|a, b| b.depth.total_cmp(&a.depth).then(a.cell.1.cmp(&b.cell.1)).then(a.cell.0.cmp(&b.cell.0)));

    let box_edges = box_edges(&camera, &corners);
    let axes = axis_lines(&camera);
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
        camera,
    })
}

/// The quad of the cell with corner nodes `i0, i1` × `j0, j1`, or `None` when a corner is missing.
fn make_quad(
    grid: &Grid,
    camera: &Camera,
    light: &Light,
    (i0, i1): (usize, usize),
    (j0, j1): (usize, usize),
) -> Option<ProjectedQuad> {
    let (xs, ys) = (grid.xs(), grid.ys());
    let (&xa, &xb, &ya, &yb) = (xs.get(i0)?, xs.get(i1)?, ys.get(j0)?, ys.get(j1)?);
    let z = [grid.value(i0, j0), grid.value(i1, j0), grid.value(i1, j1), grid.value(i0, j1)];
    if z.iter().any(|v| v.is_nan()) {
        return None;
    }
    let p = [
        camera.model([xa, ya, z[0]]),
        camera.model([xb, ya, z[1]]),
        camera.model([xb, yb, z[2]]),
        camera.model([xa, yb, z[3]]),
    ];
    let n = cross(sub(p[2], p[0]), sub(p[3], p[1]));
    let centre = [0.25 * (p[0][0] + p[1][0] + p[2][0] + p[3][0]), 0.25 * (p[0][1] + p[1][1] + p[2][1] + p[3][1]), 0.0];
    Some(ProjectedQuad {
        corners: p.map(|m| camera.screen(m)),
        depths: p.map(|m| camera.depth(m)),
        depth: horizontal_depth(camera, centre),
        shade: light.lambert(n),
        value: 0.25 * z[0] + 0.25 * z[1] + 0.25 * z[2] + 0.25 * z[3],
        cell: (i0, j0),
    })
}

/// Whether the box face on `side` (0 = low, 1 = high) of model axis `k` faces the camera.
fn faces_camera(camera: &Camera, k: usize, side: usize) -> bool {
    let e = camera.toward_camera().get(k).copied().unwrap_or(0.0);
    let outward = if side == 1 { e } else { -e };
    outward > 1e-12
}

/// The twelve box edges, each flagged hidden when neither adjacent face faces the camera.
fn box_edges(t: &Camera, corners: &[[f64; 3]; 8]) -> Vec<BoxEdge> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn view(azimuth_deg: f64, elevation_deg: f64) -> View {
        View::new(azimuth_deg, elevation_deg)
    }

    fn overhead(ambient: f64) -> Light {
        Light { azimuth_deg: 0.0, elevation_deg: 90.0, ambient, ..Light::default() }
    }

    fn lin(n: usize, h: f64) -> Vec<f64> {
        (0..n).map(|i| i as f64 * h).collect()
    }

    /// Deterministic pseudo-random numbers in [0, 1).
    fn rng(state: &mut u64) -> f64 {
        *state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    fn order_of(p: &SurfaceProjection) -> Vec<(usize, usize)> {
        p.quads.iter().map(|q| q.cell).collect()
    }

    #[test]
    fn painter_order_puts_far_cells_first() {
        let g = Grid::from_fn(lin(6, 1.0), lin(5, 1.0), |x, y| 0.1 * x * y).unwrap();
        // Camera at −y looking along +y: larger y is farther, so rows come in decreasing j.
        let p = project(&g, view(-90.0, 30.0), Light::default(), None).unwrap();
        let order = order_of(&p);
        assert_eq!(order.len(), 20);
        assert!(order.windows(2).all(|w| w[0].1 >= w[1].1), "{order:?}");
        assert_eq!(order.first().map(|c| c.1), Some(3));
        // Camera at +x looking along −x: smaller x is farther.
        let order = order_of(&project(&g, view(0.0, 30.0), Light::default(), None).unwrap());
        assert!(order.windows(2).all(|w| w[0].0 <= w[1].0), "{order:?}");
        // Camera at +y: smaller y is farther.
        let order = order_of(&project(&g, view(90.0, 30.0), Light::default(), None).unwrap());
        assert!(order.windows(2).all(|w| w[0].1 <= w[1].1), "{order:?}");
        // Camera at −x −y (azimuth −135°): the cell at the largest x and y is the farthest.
        let order = order_of(&project(&g, view(-135.0, 30.0), Light::default(), None).unwrap());
        assert_eq!(order.first(), Some(&(4, 3)));
        assert_eq!(order.last(), Some(&(0, 0)));
    }

    /// Where the screen point `q` falls in the parallelogram `s0 + s (s1 − s0) + t (s3 − s0)`.
    fn barycentric(q: (f64, f64), c: &[(f64, f64); 4]) -> Option<(f64, f64)> {
        let (ax, ay) = (c[1].0 - c[0].0, c[1].1 - c[0].1);
        let (bx, by) = (c[3].0 - c[0].0, c[3].1 - c[0].1);
        let det = ax * by - ay * bx;
        if det.abs() < 1e-12 {
            return None;
        }
        let (dx, dy) = (q.0 - c[0].0, q.1 - c[0].1);
        Some(((dx * by - dy * bx) / det, (ax * dy - ay * dx) / det))
    }

    #[test]
    fn painter_order_agrees_with_ray_casting() {
        // z = g(x) + h(y) makes every cell planar, so each quad is exactly the projection of the
        // surface over its cell and the true depth at a screen point is linear within it. At any
        // screen point covered by several quads, the one drawn last must be the nearest.
        let mut seed = 7u64;
        let mut xs = vec![0.0];
        let mut ys = vec![0.0];
        for _ in 0..8 {
            let last = *xs.last().unwrap();
            xs.push(last + 0.5 + rng(&mut seed));
        }
        for _ in 0..6 {
            let last = *ys.last().unwrap();
            ys.push(last + 0.5 + rng(&mut seed));
        }
        let mut gx: Vec<f64> = xs.iter().map(|_| 3.0 * rng(&mut seed)).collect();
        let gy: Vec<f64> = ys.iter().map(|_| 3.0 * rng(&mut seed)).collect();
        gx[4] += 8.0; // a ridge
        let mut values = Vec::new();
        for hy in &gy {
            for gxv in &gx {
                values.push(gxv + hy);
            }
        }
        let g = Grid::new(xs.clone(), ys.clone(), values).unwrap();
        let mut overlaps = 0usize;
        for az in [-60.0, 0.0, 37.0, 90.0, 135.0, 180.0, 250.0, -10.0] {
            for el in [10.0, 35.0, 70.0] {
                let p = project(&g, view(az, el), Light::default(), None).unwrap();
                let depth = |i: usize, j: usize| p.camera.distance(p.camera.model([xs[i], ys[j], g.value(i, j)]));
                for _ in 0..300 {
                    let q = (rng(&mut seed), rng(&mut seed));
                    let mut hits = Vec::new();
                    for (k, quad) in p.quads.iter().enumerate() {
                        let Some((s, t)) = barycentric(q, &quad.corners) else { continue };
                        let margin = 1e-6;
                        if s > margin && s < 1.0 - margin && t > margin && t < 1.0 - margin {
                            let (i, j) = quad.cell;
                            let (d00, d10, d01) = (depth(i, j), depth(i + 1, j), depth(i, j + 1));
                            hits.push((k, d00 + s * (d10 - d00) + t * (d01 - d00)));
                        }
                    }
                    overlaps += hits.len().saturating_sub(1);
                    for w in hits.windows(2) {
                        assert!(
                            w[0].1 >= w[1].1 - 1e-9,
                            "view ({az}, {el}) at {q:?}: quad {:?} (depth {}) drawn before nearer-or-equal {:?} \
                             (depth {}) is wrong",
                            p.quads[w[0].0].cell,
                            w[0].1,
                            p.quads[w[1].0].cell,
                            w[1].1
                        );
                    }
                }
            }
        }
        assert!(overlaps > 500, "too few overlapping quads to test the order: {overlaps}");
    }

    #[test]
    fn a_spike_in_front_is_drawn_after_the_cells_it_hides() {
        let mut v = vec![0.0; 25];
        v[5 + 2] = 10.0; // node (2, 1), near the front when looking along +y
        let g = Grid::new(lin(5, 1.0), lin(5, 1.0), v).unwrap();
        let p = project(&g, view(-90.0, 60.0), Light::default(), None).unwrap();
        let pos = |cell: (usize, usize)| p.quads.iter().position(|q| q.cell == cell).unwrap();
        let spike_cells = [(1, 0), (2, 0), (1, 1), (2, 1)];
        let behind: Vec<(usize, usize)> = (0..4).flat_map(|i| (2..4).map(move |j| (i, j))).collect();
        for &s in &spike_cells {
            for &b in &behind {
                assert!(pos(s) > pos(b), "spike cell {s:?} must be drawn after {b:?}");
            }
        }
        // The spike top really covers some cell behind it on screen.
        let top = p.project_point(2.0, 1.0, 10.0);
        let covered = p
            .quads
            .iter()
            .filter(|q| q.cell.1 >= 2)
            .any(|q| barycentric(top, &q.corners).is_some_and(|(s, t)| s.min(t) > -1e-9 && s.max(t) < 1.0 + 1e-9));
        assert!(covered, "the spike top {top:?} should overlap a cell behind it");
    }

    #[test]
    fn shading_is_lambert_with_an_ambient_floor() {
        let flat = Grid::new(lin(3, 1.0), lin(3, 1.0), vec![2.0; 9]).unwrap();
        let p = project(&flat, View::default(), overhead(0.2), None).unwrap();
        assert!(p.quads.iter().all(|q| (q.shade - 1.0).abs() < 1e-12));
        let low = Light { azimuth_deg: 10.0, elevation_deg: 30.0, ambient: 0.2, ..Light::default() };
        let p = project(&flat, View::default(), low, None).unwrap();
        assert!(p.quads.iter().all(|q| (q.shade - 0.5).abs() < 1e-12), "{:?}", p.quads[0].shade);

        // z = tan 60° · x at true scale: the normal is tilted 60° from vertical, toward −x.
        let tilt = 60f64.to_radians().tan();
        let slope = Grid::from_fn(lin(4, 1.0), lin(3, 1.0), |x, _| tilt * x).unwrap();
        let shade = |light: Light| {
            let p = project(&slope, View::default(), light, Some(1.0)).unwrap();
            assert!(p.quads.windows(2).all(|w| (w[0].shade - w[1].shade).abs() < 1e-12));
            p.quads[0].shade
        };
        assert!((shade(overhead(0.2)) - 0.5).abs() < 1e-12);
        assert!((shade(overhead(0.7)) - 0.7).abs() < 1e-12, "ambient floor");
        let facing = Light { azimuth_deg: 180.0, elevation_deg: 30.0, ambient: 0.1, ..Light::default() };
        assert!((shade(facing) - 1.0).abs() < 1e-12);
        let behind = Light { azimuth_deg: 0.0, elevation_deg: 30.0, ambient: 0.1, ..Light::default() };
        assert!((shade(behind) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn the_box_fills_the_unit_square_with_its_aspect() {
        let g = Grid::from_fn(lin(7, 2.0), lin(4, 1.0), |x, y| (x - y).sin()).unwrap();
        for (az, el) in [(-60.0, 30.0), (0.0, 10.0), (45.0, 90.0), (200.0, 60.0), (-90.0, 5.0)] {
            let p = project(&g, view(az, el), Light::default(), None).unwrap();
            let (z0, z1) = p.z_range;
            let mut pts = Vec::new();
            for x in [0.0, 12.0] {
                for y in [0.0, 3.0] {
                    for z in [z0, z1] {
                        pts.push(p.project_point(x, y, z));
                    }
                }
            }
            let min_x = pts.iter().map(|q| q.0).fold(f64::INFINITY, f64::min);
            let max_x = pts.iter().map(|q| q.0).fold(f64::NEG_INFINITY, f64::max);
            let min_y = pts.iter().map(|q| q.1).fold(f64::INFINITY, f64::min);
            let max_y = pts.iter().map(|q| q.1).fold(f64::NEG_INFINITY, f64::max);
            let (w, h) = (max_x - min_x, max_y - min_y);
            assert!((w.max(h) - 1.0).abs() < 1e-12, "view ({az}, {el}): {w} x {h}");
            assert!((min_x + max_x - 1.0).abs() < 1e-12 && (min_y + max_y - 1.0).abs() < 1e-12, "centred");
            assert!((p.size.0 - w).abs() < 1e-12 && (p.size.1 - h).abs() < 1e-12);
            // Every quad corner lies in the box.
            for q in &p.quads {
                for c in q.corners {
                    assert!(
                        c.0 >= min_x - 1e-12 && c.0 <= max_x + 1e-12 && c.1 >= min_y - 1e-12 && c.1 <= max_y + 1e-12
                    );
                }
            }
        }
    }

    #[test]
    fn projection_is_affine() {
        let g = Grid::from_fn(lin(5, 1.0), lin(9, 0.25), |x, y| x * x - y).unwrap();
        let p = project(&g, view(33.0, 41.0), Light::default(), Some(0.3)).unwrap();
        let mut seed = 3u64;
        for _ in 0..100 {
            let a: [f64; 3] = [0; 3].map(|_| 20.0 * rng(&mut seed) - 10.0);
            let b: [f64; 3] = [0; 3].map(|_| 20.0 * rng(&mut seed) - 10.0);
            let pa = p.project_point(a[0], a[1], a[2]);
            let pb = p.project_point(b[0], b[1], b[2]);
            let pm = p.project_point(0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]));
            assert!((0.5 * (pa.0 + pb.0) - pm.0).abs() < 1e-12 && (0.5 * (pa.1 + pb.1) - pm.1).abs() < 1e-12);
        }
        // Screen y is up: raising a point raises it on screen.
        assert!(p.project_point(1.0, 1.0, 5.0).1 > p.project_point(1.0, 1.0, 0.0).1);
        assert!(p.project_point(f64::NAN, 1.0, 1.0).0.is_nan());
    }

    #[test]
    fn cells_with_a_missing_corner_are_holes() {
        let mut v: Vec<f64> = (0..20).map(f64::from).collect();
        v[5 + 2] = f64::NAN; // interior node (2, 1) of a 5 x 4 grid: four cells touch it
        let g = Grid::new(lin(5, 1.0), lin(4, 1.0), v).unwrap();
        let p = project(&g, View::default(), Light::default(), None).unwrap();
        assert_eq!(p.quads.len(), 12 - 4);
        for gone in [(1, 0), (2, 0), (1, 1), (2, 1)] {
            assert!(p.quads.iter().all(|q| q.cell != gone), "{gone:?} should be a hole");
        }
        // value is the mean of the four corners: cell (0, 0) has corners 0, 1, 6, 5.
        let q = p.quads.iter().find(|q| q.cell == (0, 0)).unwrap();
        assert_eq!(q.value, 3.0);
        assert!(p.quads.iter().all(|q| q.value.is_finite() && q.shade.is_finite()));
    }

    #[test]
    fn large_grids_are_decimated_by_striding() {
        let g = Grid::from_fn(lin(1001, 0.01), lin(11, 1.0), |x, y| x + 100.0 * y).unwrap();
        let p = project(&g, View::default(), Light::default(), None).unwrap();
        assert_eq!(p.stride, (3, 1));
        assert_eq!(p.quads.len(), 334 * 10);
        let mut is: Vec<usize> = p.quads.iter().map(|q| q.cell.0).collect();
        is.sort_unstable();
        is.dedup();
        assert_eq!(is, (0..1000).step_by(3).collect::<Vec<_>>());
        // The last kept cell runs from node 999 to node 1000: its value is the mean over those.
        let q = p.quads.iter().find(|q| q.cell == (999, 0)).unwrap();
        assert!((q.value - (0.5 * (9.99 + 10.0) + 50.0)).abs() < 1e-9, "{}", q.value);
        // Its far corner is the grid's last node.
        assert_eq!(q.corners[2], p.project_point(10.0, 1.0, g.value(1000, 1)));

        let big = Grid::from_fn(lin(802, 1.0), lin(802, 1.0), |x, y| x - y).unwrap();
        let p = project(&big, View::default(), Light::default(), None).unwrap();
        assert_eq!(p.stride, (3, 3));
        assert!(p.quads.len() <= MAX_CELLS_PER_AXIS * MAX_CELLS_PER_AXIS);
        assert_eq!(p.quads.len(), 267 * 267);
    }

    #[test]
    fn default_height_is_half_the_wider_extent() {
        // Looking along +y, screen x is model x, and a vertical edge of height H appears as H cos(el).
        let g = Grid::from_fn(lin(5, 1.0), lin(3, 1.0), |x, y| 2.5 * x * y / 4.0).unwrap();
        assert_eq!(g.range(), Some((0.0, 5.0)));
        let ratio = |p: &SurfaceProjection| {
            let wx = p.project_point(4.0, 0.0, 0.0).0 - p.project_point(0.0, 0.0, 0.0).0;
            let hz = p.project_point(0.0, 0.0, 5.0).1 - p.project_point(0.0, 0.0, 0.0).1;
            hz / wx / 30f64.to_radians().cos()
        };
        let p = project(&g, view(-90.0, 30.0), Light::default(), None).unwrap();
        assert_eq!(p.height_ratio, 0.5);
        assert!((ratio(&p) - 0.5).abs() < 1e-12);
        // z scale 0.4: 5 z units drawn as 2 x units, half of the 4-unit width.
        let p = project(&g, view(-90.0, 30.0), Light::default(), Some(0.4)).unwrap();
        assert!((p.height_ratio - 0.5).abs() < 1e-12 && (ratio(&p) - 0.5).abs() < 1e-12);
        let p = project(&g, view(-90.0, 30.0), Light::default(), Some(1.0)).unwrap();
        assert!((ratio(&p) - 1.25).abs() < 1e-12);
        // A constant surface is flat.
        let flat = Grid::new(lin(3, 1.0), lin(3, 1.0), vec![4.0; 9]).unwrap();
        let p = project(&flat, view(-90.0, 30.0), Light::default(), None).unwrap();
        assert_eq!(p.height_ratio, 0.0);
        assert_eq!(p.z_range, (4.0, 4.0));
    }

    #[test]
    fn elevation_is_clamped_to_above_the_plane() {
        let g = Grid::from_fn(lin(4, 1.0), lin(4, 1.0), |x, y| x * y).unwrap();
        let at = |el: f64| project(&g, view(-60.0, el), Light::default(), None).unwrap();
        assert_eq!(at(-20.0).quads, at(MIN_ELEVATION_DEG).quads);
        assert_eq!(at(0.0).quads, at(MIN_ELEVATION_DEG).quads);
        assert_eq!(at(135.0).quads, at(90.0).quads);
        assert_ne!(at(45.0).quads, at(90.0).quads);
    }

    #[test]
    fn hidden_box_edges_are_the_ones_behind_the_surface() {
        let g = Grid::from_fn(lin(4, 1.0), lin(3, 1.0), |x, y| x + y).unwrap();
        let p = project(&g, View::default(), Light::default(), None).unwrap();
        assert_eq!(p.box_edges.len(), 12);
        // Camera on the −y, +x side above: the far bottom corner is (x0, y1, z0).
        let far = p.project_point(0.0, 2.0, 0.0);
        let hidden: Vec<&BoxEdge> = p.box_edges.iter().filter(|e| e.hidden).collect();
        assert_eq!(hidden.len(), 3);
        for e in &hidden {
            let touches = |a: (f64, f64)| (a.0 - far.0).abs() < 1e-12 && (a.1 - far.1).abs() < 1e-12;
            assert!(touches(e.start) || touches(e.end), "{e:?}");
        }
        let axes: Vec<SurfaceAxis> = hidden.iter().map(|e| e.axis).collect();
        assert!(axes.contains(&SurfaceAxis::X) && axes.contains(&SurfaceAxis::Y) && axes.contains(&SurfaceAxis::Z));
        // Straight from above only the four top edges show.
        let top = project(&g, view(-60.0, 90.0), Light::default(), None).unwrap();
        let visible: Vec<&BoxEdge> = top.box_edges.iter().filter(|e| !e.hidden).collect();
        assert_eq!(visible.len(), 4);
        assert!(visible.iter().all(|e| e.axis != SurfaceAxis::Z));
    }

    #[test]
    fn axis_lines_run_along_the_near_bottom_edges() {
        let g = Grid::from_fn(lin(4, 1.0), lin(3, 1.0), |x, y| x + y).unwrap();
        let p = project(&g, View::default(), Light::default(), None).unwrap();
        let [x, y, z] = &p.axes;
        assert_eq!((x.axis, x.from, x.to), (0, [0.0, 0.0, 0.0], [3.0, 0.0, 0.0]));
        assert_eq!((y.axis, y.from, y.to), (1, [3.0, 0.0, 0.0], [3.0, 2.0, 0.0]));
        // Leftmost vertical edge in the default view: the near-left corner (x0, y0).
        assert_eq!((z.axis, z.from, z.to), (2, [0.0, 0.0, 0.0], [0.0, 0.0, 5.0]));
        assert_eq!(x.start, p.project_point(0.0, 0.0, 0.0));
        assert_eq!(x.at(1.5), [1.5, 0.0, 0.0]);
        assert_eq!(z.at(2.0), [0.0, 0.0, 2.0]);
        // Tick labels go outward: below the front x edge, to the right of the right y edge.
        assert!(x.outward.1 < 0.0 && y.outward.0 > 0.0);
        assert!((x.outward.0.hypot(x.outward.1) - 1.0).abs() < 1e-12);
        for line in &p.axes {
            assert!(p.box_edges.iter().any(|e| !e.hidden
                && ((e.start == line.start && e.end == line.end) || (e.start == line.end && e.end == line.start))));
        }
    }

    #[test]
    fn huge_and_tiny_coordinates_stay_finite() {
        let g = Grid::new(vec![-1e308, 1e308], vec![0.0, 1e308], vec![-1e308, 1e308, 0.0, 1.0]).unwrap();
        let p = project(&g, View::default(), Light::default(), None).unwrap();
        assert_eq!(p.quads.len(), 1);
        let q = &p.quads[0];
        assert!(q.corners.iter().all(|c| c.0.is_finite() && c.1.is_finite()));
        assert!(q.shade.is_finite() && q.value.is_finite() && q.depth.is_finite());
        assert!((p.size.0.max(p.size.1) - 1.0).abs() < 1e-12);

        let g = Grid::new(vec![0.0, 5e-324], vec![0.0, 1e-300], vec![0.0, 1.0, 2.0, 3.0]).unwrap();
        let p = project(&g, View::default(), Light::default(), None).unwrap();
        assert!(p.quads[0].corners.iter().all(|c| c.0.is_finite() && c.1.is_finite()));
        assert!((p.size.0.max(p.size.1) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn errors_keep_the_value_and_say_the_fix() {
        let good = Grid::from_fn(lin(3, 1.0), lin(3, 1.0), |x, y| x + y).unwrap();
        let row = Grid::new(lin(5, 1.0), vec![0.0], vec![1.0; 5]).unwrap();
        let e = project(&row, View::default(), Light::default(), None).unwrap_err();
        assert_eq!(e, SurfaceError::NoCells { nx: 5, ny: 1 });
        assert!(e.to_string().contains("5 x 1") && e.to_string().contains("at least two"), "{e}");

        let mut v = vec![1.0; 9];
        for k in [1, 3, 5, 7] {
            v[k] = f64::NAN;
        }
        let holes = Grid::new(lin(3, 1.0), lin(3, 1.0), v).unwrap();
        let e = project(&holes, View::default(), Light::default(), None).unwrap_err();
        assert_eq!(e, SurfaceError::NoCompleteCells { nx: 3, ny: 3 });
        let empty = Grid::new(lin(3, 1.0), lin(3, 1.0), vec![f64::NAN; 9]).unwrap();
        let e = project(&empty, View::default(), Light::default(), None).unwrap_err();
        assert!(e.to_string().contains("missing (NaN) corner"), "{e}");

        let e = project(&good, view(f64::NAN, 30.0), Light::default(), None).unwrap_err();
        assert!(matches!(e, SurfaceError::NonFiniteAngle { what: "view azimuth", .. }));
        assert!(e.to_string().contains("view azimuth is NaN"), "{e}");
        let light = Light { elevation_deg: f64::INFINITY, ..Light::default() };
        let e = project(&good, View::default(), light, None).unwrap_err();
        assert!(e.to_string().contains("light elevation is inf"), "{e}");

        let e = project(&good, View::default(), Light { ambient: 1.5, ..Light::default() }, None).unwrap_err();
        assert_eq!(e, SurfaceError::Ambient { value: 1.5 });
        assert!(e.to_string().contains("1.5") && e.to_string().contains("between 0 and 1"), "{e}");
        let e = project(&good, View::default(), Light { ambient: f64::NAN, ..Light::default() }, None).unwrap_err();
        assert!(matches!(e, SurfaceError::Ambient { .. }));

        for bad in [0.0, -2.0, f64::NAN, f64::INFINITY] {
            let e = project(&good, View::default(), Light::default(), Some(bad)).unwrap_err();
            assert!(matches!(e, SurfaceError::ZScale { .. }), "{bad}: {e}");
        }
        let e = project(&good, View::default(), Light::default(), Some(-2.0)).unwrap_err();
        assert!(e.to_string().contains("is -2") && e.to_string().contains("positive"), "{e}");
        let e = project(&good, View::default(), Light::default(), Some(1e9)).unwrap_err();
        assert!(matches!(e, SurfaceError::ZScaleTooLarge { value, .. } if value == 1e9));
        assert!(e.to_string().contains("smaller z scale"), "{e}");
        let e = project(&good, View::default(), Light::default(), Some(f64::MAX)).unwrap_err();
        assert!(matches!(e, SurfaceError::ZScaleTooLarge { .. }));
    }

    #[test]
    fn strides_keep_the_last_node() {
        assert_eq!(strided(2), (vec![0, 1], 1));
        assert_eq!(strided(401), ((0..=400).collect(), 1));
        let (kept, s) = strided(402);
        assert_eq!(s, 2);
        assert_eq!(kept.last(), Some(&401));
        assert_eq!(kept.len() - 1, 201);
        assert!(kept.windows(2).all(|w| w[1] > w[0] && w[1] - w[0] <= s));
    }
}
