//! A 3-D camera shared by the 3-D kinds: where the scene is seen from ([`View`]: azimuth,
//! elevation, zoom and [`Projection`]), how it is lit ([`Light`]: Lambert diffuse with an ambient
//! floor and optional Blinn–Phong highlights), and the mapping of a data box to the screen
//! ([`Camera`]). Pure numbers: it knows nothing of scenes or renderers.
//!
//! Rules:
//! - **Spaces.** *Data* points lie in a box given by one range per axis. *Model* space centres that
//!   box on the origin with the [extents](Camera::new) the caller chooses (a kind decides how long
//!   each axis is drawn; [`equal_extent`] keeps the data's proportions). *Screen* coordinates put
//!   the whole projected box in the unit square with its aspect kept, y up: the larger screen
//!   dimension spans exactly `[0, 1]` and the smaller one is centred in it (at zoom 1). The box
//!   centre, and every point on the view axis through it, lands in the centre of the square.
//! - **Direction.** The camera sits in direction `(cos el cos az, cos el sin az, sin el)` from the
//!   box centre: azimuth is measured counter-clockwise from +x in the x-y plane, elevation up from
//!   that plane (clamped to `[-90, 90]`). Screen right is `(−sin az, cos az, 0)`, so +z is always
//!   drawn upward (for elevations below 90).
//! - **Projection.** Orthographic keeps parallel lines parallel and ratios along a line, so
//!   [`Camera::project`] is affine. Perspective puts the eye at the distance from which the box's
//!   bounding sphere just fills the field of view `fov_deg`, so every point of the box is in front
//!   of the eye; nearer things are drawn larger. The picture is centred on the view axis, so a
//!   perspective box fills the square in one direction but may not reach both of its edges.
//! - **Zoom** scales the picture about the centre of the unit square (2 = twice as large; parts
//!   then fall outside the square).
//! - **Depth.** [`Camera::distance`] is the distance along the view direction (larger is
//!   farther), for sorting back to front. [`Camera::depth`] is the z-buffer value: larger is
//!   nearer, and it varies linearly across the screen image of any plane (the view coordinate
//!   for orthographic, its reciprocal distance for perspective), so a rasterizer may interpolate
//!   it over a triangle.
//! - **Shading.** [`Light::lambert`] is the cosine between a normal and the direction toward the
//!   light, times the diffuse strength, clamped to `[ambient, 1]`; a zero or non-finite normal
//!   gets the ambient level. [`Light::shade`] lights both sides of a surface (the normal is turned
//!   toward the viewer first) and adds the Blinn–Phong highlight when the light has one.

use std::fmt;

/// Smallest perspective field of view in degrees.
pub const MIN_FOV_DEG: f64 = 1.0;
/// Largest perspective field of view in degrees.
pub const MAX_FOV_DEG: f64 = 170.0;
/// Smallest zoom.
pub const MIN_ZOOM: f64 = 0.01;
/// Largest zoom.
pub const MAX_ZOOM: f64 = 100.0;

/// How 3-D points are flattened onto the screen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Parallel projection: sizes do not change with distance.
    Orthographic,
    /// Central projection from an eye at a finite distance.
    Perspective {
        /// Full field of view in degrees, [`MIN_FOV_DEG`] to [`MAX_FOV_DEG`].
        fov_deg: f64,
    },
}

/// Where the scene is seen from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Degrees counter-clockwise from +x, in the x-y plane, toward the camera.
    pub azimuth_deg: f64,
    /// Degrees above the x-y plane toward the camera; clamped to `[-90, 90]`.
    pub elevation_deg: f64,
    /// Magnification about the centre of the screen square, [`MIN_ZOOM`] to [`MAX_ZOOM`].
    pub zoom: f64,
    /// Orthographic or perspective.
    pub projection: Projection,
}

impl Default for View {
    /// Azimuth −60°, elevation 30°, zoom 1, orthographic.
    fn default() -> Self {
        View { azimuth_deg: -60.0, elevation_deg: 30.0, zoom: 1.0, projection: Projection::Orthographic }
    }
}

impl View {
    /// An orthographic view at zoom 1 from the given direction.
    pub fn new(azimuth_deg: f64, elevation_deg: f64) -> View {
        View { azimuth_deg, elevation_deg, ..View::default() }
    }
}

/// A Blinn–Phong highlight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Specular {
    /// Brightness of the highlight at its peak, in `[0, 1]`.
    pub strength: f64,
    /// Exponent of the half-vector cosine: larger is a smaller, sharper highlight.
    pub shininess: f64,
}

/// A directional light, fixed in data space (it does not turn with the view).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Degrees counter-clockwise from +x toward the light.
    pub azimuth_deg: f64,
    /// Degrees above the x-y plane toward the light (90 = straight above).
    pub elevation_deg: f64,
    /// Smallest shade, in `[0, 1]`: faces turned away from the light get this much.
    pub ambient: f64,
    /// Diffuse strength: the shade of a face squarely facing the light (before the `[ambient, 1]`
    /// clamp).
    pub diffuse: f64,
    /// Optional highlight.
    pub specular: Option<Specular>,
}

impl Default for Light {
    /// Azimuth −120°, elevation 45°, ambient 0.25, diffuse 1, no highlight: from the front left
    /// of the default view.
    fn default() -> Self {
        Light { azimuth_deg: -120.0, elevation_deg: 45.0, ambient: 0.25, diffuse: 1.0, specular: None }
    }
}

/// How brightly a point is lit: a factor for its colour plus a white highlight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shade {
    /// Multiplies the base colour, in `[ambient, 1]`.
    pub diffuse: f64,
    /// Added white, in `[0, 1]` (0 without a highlight).
    pub specular: f64,
}

impl Shade {
    /// A base colour lit by this shade: `c · diffuse + 255 · specular`, rounded and clamped.
    pub fn apply(self, rgb: [u8; 3]) -> [u8; 3] {
        rgb.map(|c| (c as f64 * self.diffuse + 255.0 * self.specular).round().clamp(0.0, 255.0) as u8)
    }
}

impl Light {
    /// Checks every setting: finite angles, ambient in `[0, 1]`, a finite non-negative diffuse
    /// strength, a highlight strength in `[0, 1]` and a positive finite shininess.
    pub fn check(&self) -> Result<(), CameraError> {
        let finite = "a finite angle in degrees";
        let mut checks = vec![
            ("light azimuth", self.azimuth_deg, self.azimuth_deg.is_finite(), finite),
            ("light elevation", self.elevation_deg, self.elevation_deg.is_finite(), finite),
            ("ambient light level", self.ambient, (0.0..=1.0).contains(&self.ambient), "a number between 0 and 1"),
            (
                "diffuse light strength",
                self.diffuse,
                self.diffuse.is_finite() && self.diffuse >= 0.0,
                "a finite number of at least 0",
            ),
        ];
        if let Some(s) = self.specular {
            checks.push((
                "highlight strength",
                s.strength,
                (0.0..=1.0).contains(&s.strength),
                "a number between 0 and 1",
            ));
            checks.push((
                "highlight shininess",
                s.shininess,
                s.shininess.is_finite() && s.shininess > 0.0,
                "a positive finite number",
            ));
        }
        match checks.into_iter().find(|c| !c.2) {
            Some((what, value, _, allowed)) => Err(CameraError::Light { what, value, allowed }),
            None => Ok(()),
        }
    }

    /// Unit vector toward the light.
    pub fn direction(&self) -> [f64; 3] {
        let (la, le) = (self.azimuth_deg.to_radians(), self.elevation_deg.to_radians());
        [le.cos() * la.cos(), le.cos() * la.sin(), le.sin()]
    }

    /// One-sided Lambert shade of a face with (not necessarily unit) `normal`: the cosine toward
    /// the light times [`Light::diffuse`], clamped to `[ambient, 1]`; the ambient level for a
    /// zero or non-finite normal.
    pub fn lambert(&self, normal: [f64; 3]) -> f64 {
        let cos = dot(normal, self.direction()) / dot(normal, normal).sqrt();
        let lit = self.diffuse * cos;
        if lit.is_nan() { self.ambient } else { lit.max(self.ambient).min(1.0) }
    }

    /// Two-sided shade of a point with `normal` seen from direction `toward_eye` (both need not
    /// be unit): the normal is turned toward the viewer, then [`Light::lambert`] plus the
    /// Blinn–Phong highlight `strength · max(0, n·h)^shininess`, `h` halfway between the light
    /// and the eye.
    pub fn shade(&self, normal: [f64; 3], toward_eye: [f64; 3]) -> Shade {
        let n = if dot(normal, toward_eye) < 0.0 { normal.map(|c| -c) } else { normal };
        let diffuse = self.lambert(n);
        let specular = match self.specular {
            Some(Specular { strength, shininess }) => {
                let l = self.direction();
                let e = normalized(toward_eye);
                let h = normalized([l[0] + e[0], l[1] + e[1], l[2] + e[2]]);
                let cos = dot(normalized(n), h);
                let s = strength * cos.max(0.0).powf(shininess);
                if s.is_finite() { s.clamp(0.0, 1.0) } else { 0.0 }
            }
            None => 0.0,
        };
        Shade { diffuse, specular }
    }
}

/// Why a camera could not be set up.
#[derive(Debug, Clone, PartialEq)]
pub enum CameraError {
    /// A view angle is NaN or infinite.
    NonFiniteAngle {
        /// Which angle, e.g. `"view azimuth"`.
        what: &'static str,
        /// The offending value.
        value: f64,
    },
    /// The zoom is outside `[MIN_ZOOM, MAX_ZOOM]` or not a number.
    Zoom {
        /// The offending value.
        value: f64,
    },
    /// The perspective field of view is outside `[MIN_FOV_DEG, MAX_FOV_DEG]` or not a number.
    FieldOfView {
        /// The offending value.
        value: f64,
    },
    /// A light setting is out of range.
    Light {
        /// Which setting, e.g. `"diffuse light strength"`.
        what: &'static str,
        /// The offending value.
        value: f64,
        /// The allowed values.
        allowed: &'static str,
    },
    /// A model extent is negative or not finite.
    Extent {
        /// The extents given.
        extent: [f64; 3],
    },
}

impl fmt::Display for CameraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFiniteAngle { what, value } => write!(f, "the {what} is {value}; give a finite angle in degrees"),
            Self::Zoom { value } => write!(f, "the zoom is {value}; give a number from {MIN_ZOOM} to {MAX_ZOOM}"),
            Self::FieldOfView { value } => {
                write!(f, "the field of view is {value} degrees; give a number from {MIN_FOV_DEG} to {MAX_FOV_DEG}")
            }
            Self::Light { what, value, allowed } => write!(f, "the {what} is {value}; give {allowed}"),
            Self::Extent { extent } => {
                write!(f, "the model extents {extent:?} must be finite and not negative")
            }
        }
    }
}

impl std::error::Error for CameraError {}

/// Data → model → screen mapping of one data box seen from one [`View`]; see the module docs.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    ranges: [(f64, f64); 3],
    extent: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    eye: [f64; 3],
    /// Perspective only: distance of the eye from the box centre, in model units.
    eye_distance: Option<f64>,
    /// Raw screen minimum, scale, and offsets centring the smaller dimension (zoom included).
    min: (f64, f64),
    scale: f64,
    offset: (f64, f64),
    size: (f64, f64),
}

impl Camera {
    /// A camera on the data box `ranges` (low and high end per axis; equal ends are fine) drawn
    /// with model `extent`s (the box's side lengths in model space), seen from `view`.
    pub fn new(ranges: [(f64, f64); 3], extent: [f64; 3], view: View) -> Result<Camera, CameraError> {
        for (what, value) in [("view azimuth", view.azimuth_deg), ("view elevation", view.elevation_deg)] {
            if !value.is_finite() {
                return Err(CameraError::NonFiniteAngle { what, value });
            }
        }
        if !(MIN_ZOOM..=MAX_ZOOM).contains(&view.zoom) {
            return Err(CameraError::Zoom { value: view.zoom });
        }
        if extent.iter().any(|e| !(e.is_finite() && *e >= 0.0)) {
            return Err(CameraError::Extent { extent });
        }
        let eye_distance = match view.projection {
            Projection::Orthographic => None,
            Projection::Perspective { fov_deg } => {
                if !(MIN_FOV_DEG..=MAX_FOV_DEG).contains(&fov_deg) {
                    return Err(CameraError::FieldOfView { value: fov_deg });
                }
                let radius = 0.5 * dot(extent, extent).sqrt();
                let d = radius / (0.5 * fov_deg.to_radians()).sin();
                Some(if d > 0.0 && d.is_finite() { d } else { 1.0 })
            }
        };
        let az = view.azimuth_deg.to_radians();
        let el = view.elevation_deg.clamp(-90.0, 90.0).to_radians();
        let (sa, ca, se, ce) = (az.sin(), az.cos(), el.sin(), el.cos());
        let mut camera = Camera {
            ranges,
            extent,
            right: [-sa, ca, 0.0],
            up: [-se * ca, -se * sa, ce],
            eye: [ce * ca, ce * sa, se],
            eye_distance,
            min: (0.0, 0.0),
            scale: 1.0,
            offset: (0.0, 0.0),
            size: (0.0, 0.0),
        };
        // Fit the projected box into the unit square, then zoom about its centre.
        let (mut lo, mut hi) = ((f64::INFINITY, f64::INFINITY), (f64::NEG_INFINITY, f64::NEG_INFINITY));
        for p in camera.corners() {
            let (sx, sy) = camera.raw(p);
            lo = (lo.0.min(sx), lo.1.min(sy));
            hi = (hi.0.max(sx), hi.1.max(sy));
        }
        if camera.eye_distance.is_some() {
            // Perspective images are not symmetric: keep the view axis in the centre.
            let (mx, my) = (lo.0.abs().max(hi.0.abs()), lo.1.abs().max(hi.1.abs()));
            (lo, hi) = ((-mx, -my), (mx, my));
        }
        let (w, h) = (hi.0 - lo.0, hi.1 - lo.1);
        let big = w.max(h);
        let scale = if big > 0.0 && big.is_finite() { 1.0 / big } else { 1.0 };
        let offset = (0.5 * (1.0 - w * scale), 0.5 * (1.0 - h * scale));
        let z = view.zoom;
        camera.min = lo;
        camera.scale = scale * z;
        camera.offset = (offset.0 * z + 0.5 * (1.0 - z), offset.1 * z + 0.5 * (1.0 - z));
        camera.size = (w * camera.scale, h * camera.scale);
        Ok(camera)
    }

    /// Model coordinates of a data point: the box is centred on the origin.
    pub fn model(&self, p: [f64; 3]) -> [f64; 3] {
        let [(x0, x1), (y0, y1), (z0, z1)] = self.ranges;
        let [ex, ey, ez] = self.extent;
        [(unit(x0, x1, p[0]) - 0.5) * ex, (unit(y0, y1, p[1]) - 0.5) * ey, (unit(z0, z1, p[2]) - 0.5) * ez]
    }

    /// Raw (unnormalised) screen coordinates of a model point.
    fn raw(&self, m: [f64; 3]) -> (f64, f64) {
        let (u, v) = (dot(self.right, m), dot(self.up, m));
        match self.eye_distance {
            None => (u, v),
            Some(d) => {
                let k = d / (d - dot(self.eye, m));
                if k > 0.0 { (k * u, k * v) } else { (f64::NAN, f64::NAN) }
            }
        }
    }

    /// Unit-square screen coordinates of a model point (y up). Non-finite for a non-finite point
    /// or, in perspective, a point at or behind the eye.
    pub fn screen(&self, m: [f64; 3]) -> (f64, f64) {
        let (sx, sy) = self.raw(m);
        ((sx - self.min.0) * self.scale + self.offset.0, (sy - self.min.1) * self.scale + self.offset.1)
    }

    /// The ray through unit-square screen point `(sx, sy)`: a model point on it in front of the
    /// whole box and its unit direction away from the viewer (from the eye, in perspective).
    /// [`Camera::screen`] takes every point of the ray back to `(sx, sy)`.
    pub fn ray(&self, sx: f64, sy: f64) -> ([f64; 3], [f64; 3]) {
        let u = (sx - self.offset.0) / self.scale + self.min.0;
        let v = (sy - self.offset.1) / self.scale + self.min.1;
        let (r, up, e) = (self.right, self.up, self.eye);
        let across = [u * r[0] + v * up[0], u * r[1] + v * up[1], u * r[2] + v * up[2]];
        match self.eye_distance {
            None => {
                let back = dot(self.extent, self.extent).sqrt() + 1.0;
                ([across[0] + back * e[0], across[1] + back * e[1], across[2] + back * e[2]], e.map(|c| -c))
            }
            Some(d) => {
                let dir = normalized([across[0] - d * e[0], across[1] - d * e[1], across[2] - d * e[2]]);
                (e.map(|c| d * c), dir)
            }
        }
    }

    /// The data point of a model point ([`Camera::model`] undone; a flat axis gives its low end).
    pub fn data(&self, m: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|a| {
            let (lo, hi) = self.ranges[a];
            let e = self.extent[a];
            if e > 0.0 { lo + (m[a] / e + 0.5) * (hi - lo) } else { lo }
        })
    }

    /// Unit-square screen coordinates of a data point.
    pub fn project(&self, p: [f64; 3]) -> (f64, f64) {
        self.screen(self.model(p))
    }

    /// Z-buffer depth of a model point: larger is nearer, linear across the screen image of a
    /// plane (see the module docs).
    pub fn depth(&self, m: [f64; 3]) -> f64 {
        let w = dot(self.eye, m);
        match self.eye_distance {
            None => w,
            Some(d) => 1.0 / (d - w),
        }
    }

    /// Distance of a model point along the view direction, relative to the box centre (larger is
    /// farther).
    pub fn distance(&self, m: [f64; 3]) -> f64 {
        -dot(self.eye, m)
    }

    /// Unit vector from the box centre toward the camera (model space).
    pub fn toward_camera(&self) -> [f64; 3] {
        self.eye
    }

    /// Direction toward the eye from model point `m`: [`Camera::toward_camera`] for
    /// orthographic, toward the eye position for perspective.
    pub fn toward_eye_from(&self, m: [f64; 3]) -> [f64; 3] {
        match self.eye_distance {
            None => self.eye,
            Some(d) => normalized([d * self.eye[0] - m[0], d * self.eye[1] - m[1], d * self.eye[2] - m[2]]),
        }
    }

    /// Unit vectors of screen right and screen up in model space.
    pub fn screen_axes(&self) -> ([f64; 3], [f64; 3]) {
        (self.right, self.up)
    }

    /// Width and height of the projected box in screen units (the larger is the zoom).
    pub fn size(&self) -> (f64, f64) {
        self.size
    }

    /// Model extents of x, y and z.
    pub fn extent(&self) -> [f64; 3] {
        self.extent
    }

    /// The data ranges of the box.
    pub fn ranges(&self) -> [(f64, f64); 3] {
        self.ranges
    }

    /// The eight corners of the model box; bit 0 of the index picks the x side, bit 1 y, bit 2 z.
    pub fn corners(&self) -> [[f64; 3]; 8] {
        let mut corners = [[0.0; 3]; 8];
        for (c, corner) in corners.iter_mut().enumerate() {
            for (k, coord) in corner.iter_mut().enumerate() {
                let side = if c >> k & 1 == 1 { 0.5 } else { -0.5 };
                *coord = side * self.extent.get(k).copied().unwrap_or(0.0);
            }
        }
        corners
    }
}

/// A box edge chosen to carry one axis's ticks.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisLine {
    /// The data axis the line runs along: 0 for x, 1 for y, 2 for z.
    pub axis: usize,
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
    /// [`Camera::project`] to place a tick).
    pub fn at(&self, value: f64) -> [f64; 3] {
        let mut p = self.from;
        let k = self.axis;
        if let Some(c) = p.get_mut(k) {
            *c = value;
        }
        p
    }
}

/// Screen direction of the model direction `d`, normalised; `fallback` when it is edge-on.
fn screen_direction(t: &Camera, d: [f64; 3], fallback: (f64, f64)) -> (f64, f64) {
    let (right, up) = t.screen_axes();
    let (sx, sy) = (dot(right, d), dot(up, d));
    let len = sx.hypot(sy);
    if len > 1e-9 { (sx / len, sy / len) } else { fallback }
}

/// The box edges carrying each axis's ticks: x and y along the edges of the bottom face lowest
/// on screen (nearest the camera when seen from above), z along the leftmost vertical edge.
pub fn axis_lines(t: &Camera) -> [AxisLine; 3] {
    let [(x0, x1), (y0, y1), (z0, z1)] = t.ranges();
    let eye = t.toward_camera();
    let line = |axis, from: [f64; 3], to: [f64; 3], outward| AxisLine {
        axis,
        from,
        to,
        start: t.project(from),
        end: t.project(to),
        outward,
    };
    // The camera is on the high side of an axis when the eye vector points that way. Seen from
    // below, the bottom face shows and its far edges are the lowest on screen.
    let below = eye[2] < 0.0;
    let near_y_high = (eye[1] > 0.0) != below;
    let near_x_high = (eye[0] > 0.0) != below;
    let y_near = if near_y_high { y1 } else { y0 };
    let x_near = if near_x_high { x1 } else { x0 };
    let x_out = screen_direction(t, [0.0, if near_y_high { 1.0 } else { -1.0 }, 0.0], (0.0, -1.0));
    let y_out = screen_direction(t, [if near_x_high { 1.0 } else { -1.0 }, 0.0, 0.0], (0.0, -1.0));
    // Leftmost vertical edge: the bottom corner with the smallest screen x.
    let mut best = (x0, y0);
    let mut best_sx = f64::INFINITY;
    for (x, y) in [(x0, y0), (x1, y0), (x0, y1), (x1, y1)] {
        let (sx, _) = t.project([x, y, z0]);
        if sx < best_sx {
            best_sx = sx;
            best = (x, y);
        }
    }
    [
        line(0, [x0, y_near, z0], [x1, y_near, z0], x_out),
        line(1, [x_near, y0, z0], [x_near, y1, z0], y_out),
        line(2, [best.0, best.1, z0], [best.0, best.1, z1], (-1.0, 0.0)),
    ]
}

/// Model extents that keep the data box's proportions, the longest side 1 (a flat axis gets 0;
/// all-flat gives zeros).
pub fn equal_extent(ranges: [(f64, f64); 3]) -> [f64; 3] {
    let spans = ranges.map(|(a, b)| {
        let s = (b - a).abs();
        if s.is_finite() { s } else { (0.5 * b - 0.5 * a).abs() * 2.0 }
    });
    let big = spans.iter().copied().fold(0.0, f64::max);
    if big > 0.0 && big.is_finite() { spans.map(|s| s / big) } else { [0.0; 3] }
}

/// Position of `v` on the range `[a, b]` as a fraction (0 at `a`, 1 at `b`, unclamped) without
/// overflow for huge spans; 0.5 when `a == b`.
pub fn unit(a: f64, b: f64, v: f64) -> f64 {
    if a == b {
        return 0.5;
    }
    let (num, den) = (v - a, b - a);
    if num.is_finite() && den.is_finite() { num / den } else { (0.5 * v - 0.5 * a) / (0.5 * b - 0.5 * a) }
}

/// Length of the range `a` over that of `b`, without overflow for huge spans.
pub fn span_ratio(a: (f64, f64), b: (f64, f64)) -> f64 {
    let (num, den) = (a.1 - a.0, b.1 - b.0);
    if num.is_finite() && den.is_finite() { num / den } else { (0.5 * a.1 - 0.5 * a.0) / (0.5 * b.1 - 0.5 * b.0) }
}

/// Dot product.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a − b`.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Cross product.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `a` scaled to unit length (unchanged when its length is zero or not finite).
fn normalized(a: [f64; 3]) -> [f64; 3] {
    let len = dot(a, a).sqrt();
    if len > 0.0 && len.is_finite() { a.map(|c| c / len) } else { a }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BOX: [(f64, f64); 3] = [(0.0, 4.0), (0.0, 2.0), (-1.0, 1.0)];

    fn camera(view: View) -> Camera {
        Camera::new(BOX, equal_extent(BOX), view).unwrap()
    }

    fn close(a: (f64, f64), b: (f64, f64)) -> bool {
        (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12
    }

    fn perspective(az: f64, el: f64, fov_deg: f64) -> View {
        View { projection: Projection::Perspective { fov_deg }, ..View::new(az, el) }
    }

    #[test]
    fn rays_project_back_to_their_screen_point() {
        let ranges = [(0.0, 4.0), (-1.0, 1.0), (10.0, 13.0)];
        for projection in [Projection::Orthographic, Projection::Perspective { fov_deg: 30.0 }] {
            let view = View { azimuth_deg: -50.0, elevation_deg: 35.0, zoom: 1.3, projection };
            let cam = Camera::new(ranges, equal_extent(ranges), view).unwrap();
            for (sx, sy) in [(0.5, 0.5), (0.2, 0.7), (0.9, 0.1)] {
                let (o, d) = cam.ray(sx, sy);
                assert!((dot(d, d) - 1.0).abs() < 1e-12);
                // In perspective the ray starts at the eye, which has no screen point.
                for t in [0.3, 0.7, 1.9] {
                    let m = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
                    let (x, y) = cam.screen(m);
                    assert!((x - sx).abs() < 1e-9 && (y - sy).abs() < 1e-9, "{projection:?} {t}: {x} {y}");
                    let back = cam.model(cam.data(m));
                    assert!((0..3).all(|a| (back[a] - m[a]).abs() < 1e-9));
                }
                // The origin lies in front of the box: nearer the viewer than every corner.
                assert!(cam.corners().iter().all(|c| cam.distance(*c) > cam.distance(o)));
            }
        }
    }

    #[test]
    fn the_box_centre_projects_to_the_centre_of_the_square() {
        // The box centre is on the view axis in every view and projection.
        for view in [View::new(-60.0, 30.0), View::new(17.0, -40.0), perspective(100.0, 20.0, 60.0)] {
            for zoom in [1.0, 0.5, 3.0] {
                let c = camera(View { zoom, ..view });
                assert!(close(c.project([2.0, 1.0, 0.0]), (0.5, 0.5)), "{view:?} zoom {zoom}");
                // And so does any other point on the view axis.
                let e = c.toward_camera();
                let m = [0.3 * e[0], 0.3 * e[1], 0.3 * e[2]];
                assert!(close(c.screen(m), (0.5, 0.5)), "{view:?} zoom {zoom}: {:?}", c.screen(m));
            }
        }
    }

    #[test]
    fn known_directions() {
        // Azimuth 0: the camera is on +x, screen right is +y, screen up is +z.
        let c = camera(View::new(0.0, 0.0));
        let (r, u) = c.screen_axes();
        assert!(close((r[0], r[1]), (0.0, 1.0)) && r[2] == 0.0);
        assert!(close((u[0], u[1]), (0.0, 0.0)) && (u[2] - 1.0).abs() < 1e-12);
        assert!((c.toward_camera()[0] - 1.0).abs() < 1e-12);
        let a = c.project([2.0, 0.0, 0.0]);
        let b = c.project([2.0, 2.0, 0.0]);
        assert!(b.0 > a.0 && (b.1 - a.1).abs() < 1e-12, "+y goes right");
        // Moving along x (toward the camera) does not move the point on screen.
        assert!(close(c.project([0.0, 1.0, 0.5]), c.project([4.0, 1.0, 0.5])));
        // Azimuth 90: the camera is on +y, screen right is −x.
        let c = camera(View::new(90.0, 0.0));
        let (r, _) = c.screen_axes();
        assert!(close((r[0], r[1]), (-1.0, 0.0)));
        assert!(c.project([0.0, 1.0, 0.0]).0 > c.project([4.0, 1.0, 0.0]).0);
        // Elevation 90: looking straight down; z does not move a point, x and y span the screen
        // (azimuth 0: +y right, +x down) with the 4 × 2 box filling the width.
        let c = camera(View::new(0.0, 90.0));
        assert!(close(c.project([1.0, 1.0, -1.0]), c.project([1.0, 1.0, 1.0])));
        assert!(close(c.project([0.0, 0.0, 0.0]), (0.25, 1.0)));
        assert!(close(c.project([4.0, 2.0, 0.0]), (0.75, 0.0)));
        assert!(close(c.size(), (0.5, 1.0)));
    }

    #[test]
    fn orthographic_keeps_parallels_and_ratios() {
        let c = camera(View::new(33.0, 41.0));
        let (a, b) = ([0.5, 0.2, -0.7], [3.1, 1.9, 0.6]);
        let lerp = |t: f64| [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
        let (pa, pb) = (c.project(a), c.project(b));
        for t in [0.25, 0.5, 0.9] {
            let p = c.project(lerp(t));
            assert!(close(p, (pa.0 + t * (pb.0 - pa.0), pa.1 + t * (pb.1 - pa.1))), "ratio at {t}");
        }
        // A translated copy of the segment is parallel and equally long on screen.
        let shift = [0.7, -0.4, 0.3];
        let (qa, qb) = (c.project([0, 1, 2].map(|k| a[k] + shift[k])), c.project([0, 1, 2].map(|k| b[k] + shift[k])));
        assert!(close((pb.0 - pa.0, pb.1 - pa.1), (qb.0 - qa.0, qb.1 - qa.1)));
    }

    #[test]
    fn perspective_draws_the_nearer_of_two_equal_segments_longer() {
        let c = camera(perspective(0.0, 20.0, 50.0));
        // The camera is on +x: the segment at x = 4 is nearer than the one at x = 0.
        let len = |x: f64| {
            let (p, q) = (c.project([x, 0.5, 0.0]), c.project([x, 1.5, 0.0]));
            (q.0 - p.0).hypot(q.1 - p.1)
        };
        assert!(len(4.0) > 1.2 * len(0.0), "{} vs {}", len(4.0), len(0.0));
        // Orthographic draws them the same.
        let o = camera(View::new(0.0, 20.0));
        let olen = |x: f64| (o.project([x, 1.5, 0.0]).0 - o.project([x, 0.5, 0.0]).0).abs();
        assert!((olen(4.0) - olen(0.0)).abs() < 1e-12);
        // The whole box still fits the unit square.
        for m in c.corners() {
            let (x, y) = c.screen(m);
            assert!((-1e-12..=1.0 + 1e-12).contains(&x) && (-1e-12..=1.0 + 1e-12).contains(&y));
        }
    }

    #[test]
    fn depth_order_follows_the_distance_along_the_view_direction() {
        let mut seed = 11u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for view in [View::new(-60.0, 30.0), View::new(200.0, -10.0), perspective(45.0, 60.0, 40.0)] {
            let c = camera(view);
            let e = c.toward_camera();
            for _ in 0..200 {
                let a = [4.0 * rnd(), 2.0 * rnd(), 2.0 * rnd() - 1.0];
                let b = [4.0 * rnd(), 2.0 * rnd(), 2.0 * rnd() - 1.0];
                let (ma, mb) = (c.model(a), c.model(b));
                // Distance along the view direction, computed independently.
                let along = |m: [f64; 3]| -(m[0] * e[0] + m[1] * e[1] + m[2] * e[2]);
                let farther = along(ma) > along(mb);
                assert_eq!(c.distance(ma) > c.distance(mb), farther);
                assert_eq!(c.depth(ma) < c.depth(mb), farther, "{view:?}: depth is larger for the nearer");
            }
        }
    }

    #[test]
    fn perspective_depth_is_linear_on_screen() {
        // Along a segment, the z-buffer depth at the screen midpoint is the mean of the ends'.
        let c = camera(perspective(-30.0, 25.0, 60.0));
        let (a, b) = (c.model([0.2, 0.1, -0.9]), c.model([3.8, 1.7, 0.8]));
        let (sa, sb) = (c.screen(a), c.screen(b));
        // Find the model point whose screen image is the screen midpoint, by bisection.
        let mid = (0.5 * (sa.0 + sb.0), 0.5 * (sa.1 + sb.1));
        let at = |t: f64| [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
        let (mut lo, mut hi) = (0.0, 1.0);
        let dir = (sb.0 - sa.0, sb.1 - sa.1);
        for _ in 0..100 {
            let t = 0.5 * (lo + hi);
            let s = c.screen(at(t));
            if (s.0 - mid.0) * dir.0 + (s.1 - mid.1) * dir.1 < 0.0 { lo = t } else { hi = t }
        }
        let t = 0.5 * (lo + hi);
        assert!((t - 0.5).abs() > 0.01, "perspective moves the midpoint");
        let want = 0.5 * (c.depth(a) + c.depth(b));
        assert!((c.depth(at(t)) - want).abs() < 1e-9 * want.abs().max(1.0));
    }

    #[test]
    fn lambert_facing_gives_one_and_perpendicular_gives_ambient() {
        let light = Light { azimuth_deg: 30.0, elevation_deg: 40.0, ambient: 0.2, ..Light::default() };
        let l = light.direction();
        assert!((light.lambert(l) - 1.0).abs() < 1e-12);
        assert!((light.lambert(l.map(|c| 7.0 * c)) - 1.0).abs() < 1e-12, "the normal's length does not matter");
        // Perpendicular to the light: a horizontal vector at right angles to its azimuth, and the
        // cross product of that with the light.
        let side = [-(30f64.to_radians().sin()), 30f64.to_radians().cos(), 0.0];
        assert!((light.lambert(side) - 0.2).abs() < 1e-12);
        assert!((light.lambert(cross(side, l)) - 0.2).abs() < 1e-12);
        // Turned away: ambient; at 60°: one half; zero normal: ambient.
        assert_eq!(light.lambert(l.map(|c| -c)), 0.2);
        let overhead = Light { elevation_deg: 90.0, ..light };
        assert!((overhead.lambert([60f64.to_radians().sin(), 0.0, 0.5]) - 0.5).abs() < 1e-12);
        assert_eq!(light.lambert([0.0; 3]), 0.2);
        assert_eq!(light.lambert([f64::NAN, 0.0, 1.0]), 0.2);
        // Weaker diffuse light.
        let dim = Light { diffuse: 0.6, ..light };
        assert!((dim.lambert(l) - 0.6).abs() < 1e-12);
    }

    #[test]
    fn shade_is_two_sided_with_a_blinn_phong_highlight() {
        let light = Light { azimuth_deg: 0.0, elevation_deg: 90.0, ambient: 0.1, ..Light::default() };
        let eye = [0.0, 0.0, 1.0];
        // A face seen from its back is lit as its front.
        assert_eq!(light.shade([0.0, 0.0, -1.0], eye), Shade { diffuse: 1.0, specular: 0.0 });
        let shiny = Light { specular: Some(Specular { strength: 0.5, shininess: 20.0 }), ..light };
        let s = shiny.shade([0.0, 0.0, 1.0], eye);
        assert!((s.specular - 0.5).abs() < 1e-12, "peak where the half vector is the normal");
        let tilted = shiny.shade([0.5, 0.0, 1.0], eye);
        assert!(tilted.specular < 0.5 * s.specular && tilted.specular > 0.0);
        assert_eq!(Shade { diffuse: 0.5, specular: 0.0 }.apply([200, 100, 3]), [100, 50, 2]);
        assert_eq!(Shade { diffuse: 1.0, specular: 0.5 }.apply([200, 100, 0]), [255, 228, 128]);
    }

    #[test]
    fn bad_views_are_errors_that_say_the_fix() {
        let e = Camera::new(BOX, [1.0; 3], View::new(f64::NAN, 0.0)).unwrap_err();
        assert!(e.to_string().contains("view azimuth is NaN"), "{e}");
        let e = Camera::new(BOX, [1.0; 3], View { zoom: 0.0, ..View::default() }).unwrap_err();
        assert_eq!(e, CameraError::Zoom { value: 0.0 });
        assert!(e.to_string().contains("from 0.01 to 100"), "{e}");
        let e = Camera::new(BOX, [1.0; 3], View { zoom: f64::NAN, ..View::default() }).unwrap_err();
        assert!(matches!(e, CameraError::Zoom { .. }));
        let e = Camera::new(BOX, [1.0; 3], perspective(0.0, 0.0, 180.0)).unwrap_err();
        assert!(e.to_string().contains("field of view is 180"), "{e}");
        let e = Light { diffuse: -1.0, ..Light::default() }.check().unwrap_err();
        assert!(e.to_string().contains("diffuse light strength is -1"), "{e}");
        let shiny = Light { specular: Some(Specular { strength: 0.5, shininess: 0.0 }), ..Light::default() };
        assert!(shiny.check().unwrap_err().to_string().contains("shininess is 0; give a positive"));
        assert_eq!(Light::default().check(), Ok(()));
        let e = Camera::new(BOX, [1.0, -1.0, 0.0], View::default()).unwrap_err();
        assert!(matches!(e, CameraError::Extent { .. }));
        // A degenerate box is fine: everything lands in the centre.
        let c = Camera::new([(1.0, 1.0); 3], [0.0; 3], perspective(0.0, 0.0, 30.0)).unwrap();
        assert!(close(c.project([1.0, 1.0, 1.0]), (0.5, 0.5)));
    }

    #[test]
    fn zoom_scales_about_the_centre() {
        let one = camera(View::new(-60.0, 30.0));
        let two = camera(View { zoom: 2.0, ..View::new(-60.0, 30.0) });
        let p = [0.3, 1.7, 0.4];
        let (a, b) = (one.project(p), two.project(p));
        assert!(close((b.0 - 0.5, b.1 - 0.5), (2.0 * (a.0 - 0.5), 2.0 * (a.1 - 0.5))));
        assert!(close(two.size(), (2.0 * one.size().0, 2.0 * one.size().1)));
    }
}
