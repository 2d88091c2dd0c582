//! Chernoff faces: the geometry of one cartoon face whose features are driven by values in [0, 1].
//!
//! A face is laid out in a local frame where the square it must fit in spans −1..1 on both axes
//! (y down), then mapped to canvas units. Every control point of every curve stays inside that
//! square with room for the stroke, and a Bézier curve lies inside the hull of its control points,
//! so the drawn face never leaves its square whatever the parameters.

use std::f64::consts::PI;

use crate::scene::{Color, Item, PathCmd, Point, Rect, Role, Shape, Style};

/// A facial feature a column can drive.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// Width of the head.
    FaceWidth,
    /// Height of the head.
    FaceHeight,
    /// Outline of the lower face, from round to an ovoid face with a pointed chin.
    FaceShape,
    /// Size of the eyes.
    EyeSize,
    /// Distance between the eyes.
    EyeSpacing,
    /// Tilt of the eyes, from drooping outer corners to upturned ones.
    EyeSlant,
    /// Where the pupils sit inside the eyes, from left to right.
    PupilPosition,
    /// Tilt of the eyebrows, from raised inner ends (worried) to lowered ones (stern).
    BrowSlant,
    /// Height of the eyebrows above the eyes.
    BrowHeight,
    /// Length of the nose.
    NoseLength,
    /// Width of the nose.
    NoseWidth,
    /// Curvature of the mouth, from a frown through a straight line to a smile.
    MouthCurvature,
    /// Width of the mouth.
    MouthWidth,
    /// How far the mouth is open.
    MouthOpenness,
    /// Size of the ears.
    EarSize,
    /// Volume and length of the hair, from bald to a full head of hair.
    Hair,
}

impl Feature {
    /// Every feature, in the order columns are assigned when given as a list.
    pub const ALL: [Feature; 16] = [
        Feature::FaceWidth,
        Feature::FaceHeight,
        Feature::FaceShape,
        Feature::EyeSize,
        Feature::EyeSpacing,
        Feature::EyeSlant,
        Feature::PupilPosition,
        Feature::BrowSlant,
        Feature::BrowHeight,
        Feature::NoseLength,
        Feature::NoseWidth,
        Feature::MouthCurvature,
        Feature::MouthWidth,
        Feature::MouthOpenness,
        Feature::EarSize,
        Feature::Hair,
    ];

    /// The spec key, snake_case (e.g. "face_width", "mouth_curvature", "hair").
    pub fn key(self) -> &'static str {
        match self {
            Feature::FaceWidth => "face_width",
            Feature::FaceHeight => "face_height",
            Feature::FaceShape => "face_shape",
            Feature::EyeSize => "eye_size",
            Feature::EyeSpacing => "eye_spacing",
            Feature::EyeSlant => "eye_slant",
            Feature::PupilPosition => "pupil_position",
            Feature::BrowSlant => "brow_slant",
            Feature::BrowHeight => "brow_height",
            Feature::NoseLength => "nose_length",
            Feature::NoseWidth => "nose_width",
            Feature::MouthCurvature => "mouth_curvature",
            Feature::MouthWidth => "mouth_width",
            Feature::MouthOpenness => "mouth_openness",
            Feature::EarSize => "ear_size",
            Feature::Hair => "hair",
        }
    }

    /// Parse a spec key.
    pub fn from_key(key: &str) -> Option<Feature> {
        Feature::ALL.into_iter().find(|f| f.key() == key)
    }

    /// What a low and a high value look like, for the legend.
    pub fn extremes(self) -> (&'static str, &'static str) {
        match self {
            Feature::FaceWidth => ("narrow", "wide"),
            Feature::FaceHeight => ("short", "tall"),
            Feature::FaceShape => ("round", "pointed chin"),
            Feature::EyeSize => ("small", "large"),
            Feature::EyeSpacing => ("close-set", "wide-set"),
            Feature::EyeSlant => ("drooping", "upturned"),
            Feature::PupilPosition => ("looking left", "looking right"),
            Feature::BrowSlant => ("worried", "stern"),
            Feature::BrowHeight => ("low", "high"),
            Feature::NoseLength => ("short", "long"),
            Feature::NoseWidth => ("narrow", "wide"),
            Feature::MouthCurvature => ("frown", "smile"),
            Feature::MouthWidth => ("narrow", "wide"),
            Feature::MouthOpenness => ("closed", "open"),
            Feature::EarSize => ("small", "large"),
            Feature::Hair => ("bald", "full hair"),
        }
    }

    /// Human name, e.g. "face width", "mouth curvature".
    pub fn label(self) -> &'static str {
        match self {
            Feature::FaceWidth => "face width",
            Feature::FaceHeight => "face height",
            Feature::FaceShape => "face shape",
            Feature::EyeSize => "eye size",
            Feature::EyeSpacing => "eye spacing",
            Feature::EyeSlant => "eye slant",
            Feature::PupilPosition => "pupil position",
            Feature::BrowSlant => "brow slant",
            Feature::BrowHeight => "brow height",
            Feature::NoseLength => "nose length",
            Feature::NoseWidth => "nose width",
            Feature::MouthCurvature => "mouth curvature",
            Feature::MouthWidth => "mouth width",
            Feature::MouthOpenness => "mouth openness",
            Feature::EarSize => "ear size",
            Feature::Hair => "hair",
        }
    }
}

/// Feature values, each in [0, 1]; 0.5 is neutral. Values outside are clamped; NaN means neutral.
///
/// Indexed by `Feature as usize`, i.e. in the order of [`Feature::ALL`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceParams(pub [f64; 16]);

impl FaceParams {
    /// Every feature at 0.5.
    pub fn neutral() -> FaceParams {
        FaceParams([0.5; 16])
    }

    /// The value of one feature, clamped to [0, 1] (NaN reads as 0.5).
    pub fn get(&self, f: Feature) -> f64 {
        unit(self.0[f as usize])
    }

    /// Set one feature, clamping to [0, 1] (NaN stores 0.5).
    pub fn set(&mut self, f: Feature, v: f64) {
        self.0[f as usize] = unit(v);
    }
}

impl Default for FaceParams {
    fn default() -> FaceParams {
        FaceParams::neutral()
    }
}

/// Colours of one face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacePaint {
    /// Fill of the head and ears.
    pub skin: Color,
    /// Outlines, brows, pupils, nose and mouth.
    pub ink: Color,
    /// Fill of the hair.
    pub hair: Color,
}

/// The items drawing one face centred at `center`, fitting inside a square of side `size`.
///
/// Items come back to front — hair, ears, head, brows, eyes, pupils, nose, mouth — all with
/// [`Role::DataMark`] and labelled with the part they draw. Strokes are `size / 60` wide, at least
/// 0.75; from size 45 up they stay inside the square too. A non-finite centre or a size that is
/// not a positive finite number draws nothing.
pub fn face_items(params: &FaceParams, center: Point, size: f64, paint: FacePaint) -> Vec<Item> {
    let Some(frame) = Frame::new(center, size) else { return Vec::new() };
    let head = Head::new(params);
    let eyes = eyes(params, &head);
    let sw = (size / 60.0).max(0.75);
    let ink = |w: f64| Style::stroke(paint.ink, w);
    let filled = |fill: Color, w: f64| Style { fill: Some(fill), ..ink(w) };

    let mut items = Vec::with_capacity(12);
    if let Some(hair) = hair_path(params.get(Feature::Hair), &head) {
        let style = Style { fill: Some(paint.hair), ..Style::stroke(paint.ink.with_opacity(0.8), sw * 0.8) };
        items.push(frame.path("hair", hair, style));
    }
    for ear in ear_paths(params.get(Feature::EarSize), &head) {
        items.push(frame.path("ear", ear, filled(paint.skin, sw)));
    }
    items.push(frame.path("head", head_path(&head), filled(paint.skin, sw)));
    for brow in brow_paths(params, &head, &eyes) {
        items.push(frame.path("brow", brow, ink(sw * 1.5)));
    }
    for eye in &eyes {
        items.push(frame.path("eye", ellipse(eye.center, eye.rx, eye.ry, eye.angle), filled(Color::WHITE, sw * 0.8)));
    }
    for eye in &eyes {
        let (c, r) = pupil(params.get(Feature::PupilPosition), eye);
        items.push(frame.circle("pupil", c, r, Style::fill(paint.ink)));
    }
    items.push(frame.path("nose", nose_path(params, &head, &eyes), ink(sw)));
    let (mouth, open) = mouth_path(params, &head);
    let style = if open { filled(paint.ink.with_opacity(0.3), sw * 1.1) } else { ink(sw * 1.1) };
    items.push(frame.path("mouth", mouth, style));
    items
}

/// The face outline's bounding box for given params (for tests and layout).
///
/// This is the head alone, without ears and hair. A non-finite centre or a size that is not a
/// positive finite number gives an empty rectangle at the centre.
pub fn face_bounds(params: &FaceParams, center: Point, size: f64) -> Rect {
    let Some(frame) = Frame::new(center, size) else { return Rect::new(center.x, center.y, 0.0, 0.0) };
    let outline = frame.map(head_path(&Head::new(params)));
    let pts: Vec<Point> = outline.iter().flat_map(|c| cmd_points(*c)).collect();
    let (x0, x1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.x), b.max(p.x)));
    let (y0, y1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.y), b.max(p.y)));
    Rect::new(x0, y0, x1 - x0, y1 - y0)
}

/// 4/3·(√2 − 1): the control-point distance of a cubic quarter circle of radius 1.
const KAPPA: f64 = 0.552_284_749_830_793_4;

/// A value as a feature level: clamped to [0, 1], NaN as neutral.
fn unit(v: f64) -> f64 {
    if v.is_nan() { 0.5 } else { v.clamp(0.0, 1.0) }
}

/// The value a fraction `t` of the way from `a` to `b`.
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

/// Shorthand for a point of the local frame.
fn pt(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// The points a command mentions, control points included.
fn cmd_points(cmd: PathCmd) -> Vec<Point> {
    match cmd {
        PathCmd::MoveTo(p) | PathCmd::LineTo(p) => vec![p],
        PathCmd::QuadTo(a, p) => vec![a, p],
        PathCmd::CubicTo(a, b, p) => vec![a, b, p],
        PathCmd::Close => Vec::new(),
    }
}

/// The face's local frame: the square of side `size` around `center` spans −1..1 on both axes.
struct Frame {
    center: Point,
    half: f64,
}

impl Frame {
    /// The frame of a valid face square, or `None` for a non-finite centre or a bad size.
    fn new(center: Point, size: f64) -> Option<Frame> {
        let ok = size.is_finite() && size > 0.0 && center.x.is_finite() && center.y.is_finite();
        ok.then_some(Frame { center, half: size / 2.0 })
    }

    /// A local point in canvas units.
    fn point(&self, p: Point) -> Point {
        Point::new(self.center.x + p.x * self.half, self.center.y + p.y * self.half)
    }

    /// A local path in canvas units.
    fn map(&self, cmds: Vec<PathCmd>) -> Vec<PathCmd> {
        let m = |p| self.point(p);
        cmds.into_iter()
            .map(|c| match c {
                PathCmd::MoveTo(p) => PathCmd::MoveTo(m(p)),
                PathCmd::LineTo(p) => PathCmd::LineTo(m(p)),
                PathCmd::QuadTo(a, p) => PathCmd::QuadTo(m(a), m(p)),
                PathCmd::CubicTo(a, b, p) => PathCmd::CubicTo(m(a), m(b), m(p)),
                PathCmd::Close => PathCmd::Close,
            })
            .collect()
    }

    /// A labelled path item from a local path.
    fn path(&self, label: &str, cmds: Vec<PathCmd>, style: Style) -> Item {
        Item::new(Role::DataMark, Shape::Path(self.map(cmds)), style).labelled(label)
    }

    /// A labelled circle item from a local centre and radius.
    fn circle(&self, label: &str, center: Point, radius: f64, style: Style) -> Item {
        let shape = Shape::Circle { center: self.point(center), radius: radius * self.half };
        Item::new(Role::DataMark, shape, style).labelled(label)
    }
}

/// An ellipse centred at `c` with semi-axes `rx`, `ry`, rotated by `angle` radians (clockwise on
/// screen), as four cubic Béziers.
fn ellipse(c: Point, rx: f64, ry: f64, angle: f64) -> Vec<PathCmd> {
    let (s, co) = angle.sin_cos();
    let at = |x: f64, y: f64| pt(c.x + x * co - y * s, c.y + x * s + y * co);
    let (kx, ky) = (KAPPA * rx, KAPPA * ry);
    vec![
        PathCmd::MoveTo(at(rx, 0.0)),
        PathCmd::CubicTo(at(rx, ky), at(kx, ry), at(0.0, ry)),
        PathCmd::CubicTo(at(-kx, ry), at(-rx, ky), at(-rx, 0.0)),
        PathCmd::CubicTo(at(-rx, -ky), at(-kx, -ry), at(0.0, -ry)),
        PathCmd::CubicTo(at(kx, -ry), at(rx, -ky), at(rx, 0.0)),
        PathCmd::Close,
    ]
}

/// The head in the local frame: centred on x = 0.
struct Head {
    /// Vertical centre (where the head is widest).
    cy: f64,
    /// Half width.
    hw: f64,
    /// Half height.
    hh: f64,
    /// 0 round … 1 ovoid with a pointed chin.
    shape: f64,
}

impl Head {
    /// The head drawn for `p`.
    fn new(p: &FaceParams) -> Head {
        Head {
            cy: 0.08,
            hw: lerp(0.5, 0.76, p.get(Feature::FaceWidth)),
            hh: lerp(0.6, 0.82, p.get(Feature::FaceHeight)),
            shape: p.get(Feature::FaceShape),
        }
    }

    /// Half width of the (always elliptical) upper half of the head at height `y`.
    fn upper_half_width(&self, y: f64) -> f64 {
        let t = ((self.cy - y) / self.hh).clamp(0.0, 1.0);
        self.hw * (1.0 - t * t).sqrt()
    }
}

/// The head outline: an ellipse on top; below, the jaw tapers towards a pointed chin with `shape`.
fn head_path(h: &Head) -> Vec<PathCmd> {
    let (cy, w, hh, s) = (h.cy, h.hw, h.hh, h.shape);
    let cheek = lerp(KAPPA, 0.45, s) * hh;
    let (jaw_x, jaw_y) = (lerp(KAPPA, 0.26, s) * w, lerp(1.0, 0.8, s) * hh);
    let chin = cy + hh;
    vec![
        PathCmd::MoveTo(pt(w, cy)),
        PathCmd::CubicTo(pt(w, cy + cheek), pt(jaw_x, cy + jaw_y), pt(0.0, chin)),
        PathCmd::CubicTo(pt(-jaw_x, cy + jaw_y), pt(-w, cy + cheek), pt(-w, cy)),
        PathCmd::CubicTo(pt(-w, cy - KAPPA * hh), pt(-KAPPA * w, cy - hh), pt(0.0, cy - hh)),
        PathCmd::CubicTo(pt(KAPPA * w, cy - hh), pt(w, cy - KAPPA * hh), pt(w, cy)),
        PathCmd::Close,
    ]
}

/// Hair behind the head: a scalloped cap whose thickness and reach down the sides grow with `v`.
fn hair_path(v: f64, h: &Head) -> Option<Vec<PathCmd>> {
    if v <= 0.0 {
        return None;
    }
    let t = lerp(0.03, 0.12, v);
    let (a, b) = (h.hw + t, h.hh + t);
    let end_y = h.cy + lerp(-0.6, 0.3, v) * h.hh;
    let start = ((h.cy - end_y) / b).asin();
    let at = |th: f64| pt(a * th.cos(), h.cy - b * th.sin());
    let normal = |th: f64| {
        let (nx, ny) = (th.cos() / a, -th.sin() / b);
        let len = nx.hypot(ny);
        pt(nx / len, ny / len)
    };
    let bump = 0.45 * t;
    let n = 9;
    let step = (PI - 2.0 * start) / n as f64;
    let mut cmds = vec![PathCmd::MoveTo(at(start))];
    for i in 0..n {
        let (t0, t1) = (start + step * i as f64, start + step * (i + 1) as f64);
        let (p0, p1, n0, n1) = (at(t0), at(t1), normal(t0), normal(t1));
        let c0 = pt(p0.x + n0.x * bump, p0.y + n0.y * bump);
        let c1 = pt(p1.x + n1.x * bump, p1.y + n1.y * bump);
        cmds.push(PathCmd::CubicTo(c0, c1, p1));
    }
    // The straight edge back across runs behind the head, where only its ends show.
    cmds.push(PathCmd::Close);
    Some(cmds)
}

/// Two ears, left then right, half hidden behind the head.
fn ear_paths(v: f64, h: &Head) -> [Vec<PathCmd>; 2] {
    let rx = lerp(0.06, 0.13, v);
    let ry = 1.5 * rx;
    let (x, y) = (h.hw + 0.45 * rx, h.cy - 0.04 * h.hh);
    [ellipse(pt(-x, y), rx, ry, 0.0), ellipse(pt(x, y), rx, ry, 0.0)]
}

/// One eye: an ellipse and the side of the face it is on (−1 left, +1 right).
struct Eye {
    center: Point,
    rx: f64,
    ry: f64,
    angle: f64,
    side: f64,
}

/// The two eyes, left then right.
fn eyes(p: &FaceParams, h: &Head) -> [Eye; 2] {
    let rx = lerp(0.07, 0.15, p.get(Feature::EyeSize));
    let ry = 0.66 * rx;
    let dx = (lerp(0.28, 0.6, p.get(Feature::EyeSpacing)) * h.hw).max(rx + 0.02);
    let y = h.cy - 0.12 * h.hh;
    // Positive tilt raises the outer corners.
    let tilt = lerp(-0.7, 0.7, p.get(Feature::EyeSlant));
    [-1.0, 1.0].map(|side| Eye { center: pt(side * dx, y), rx, ry, angle: -side * tilt, side })
}

/// The pupil of `eye`: centre and radius, slid along the eye's long axis from left to right.
fn pupil(v: f64, eye: &Eye) -> (Point, f64) {
    let r = 0.58 * eye.ry;
    let d = lerp(-1.0, 1.0, v) * 0.6 * (eye.rx - r);
    let (s, c) = eye.angle.sin_cos();
    (pt(eye.center.x + d * c, eye.center.y + d * s), r)
}

/// Two eyebrows, left then right: straight segments above the eyes, kept inside the head.
fn brow_paths(p: &FaceParams, h: &Head, eyes: &[Eye; 2]) -> [Vec<PathCmd>; 2] {
    let lift = lerp(0.04, 0.17, p.get(Feature::BrowHeight));
    // Positive angle lowers the inner ends.
    let angle = lerp(-0.4, 0.4, p.get(Feature::BrowSlant));
    let (s, c) = angle.sin_cos();
    eyes.each_ref().map(|eye| {
        let (x, y) = (eye.center.x, eye.center.y - eye.ry - lift);
        let room = h.upper_half_width(y + 0.05) - 0.04 - x.abs();
        let half = (1.15 * eye.rx).min(room / c).max(0.3 * eye.rx);
        let inner = pt(x - eye.side * half * c, y + half * s);
        let outer = pt(x + eye.side * half * c, y - half * s);
        vec![PathCmd::MoveTo(inner), PathCmd::LineTo(outer)]
    })
}

/// The nose: down the left side from between the eyes, round the nostrils, up a little on the right.
fn nose_path(p: &FaceParams, h: &Head, eyes: &[Eye; 2]) -> Vec<PathCmd> {
    let len = lerp(0.08, 0.32, p.get(Feature::NoseLength)) * h.hh;
    let w = lerp(0.08, 0.25, p.get(Feature::NoseWidth)) * h.hw;
    let top = eyes[0].center.y;
    let bottom = top + len;
    vec![
        PathCmd::MoveTo(pt(-0.2 * w, top)),
        PathCmd::CubicTo(pt(-0.2 * w, top + 0.6 * len), pt(-w, bottom - 0.45 * w), pt(-w, bottom - 0.1 * w)),
        PathCmd::CubicTo(pt(-w, bottom + 0.35 * w), pt(w, bottom + 0.35 * w), pt(w, bottom - 0.1 * w)),
        PathCmd::QuadTo(pt(w, bottom - 0.35 * w), pt(0.6 * w, bottom - 0.5 * w)),
    ]
}

/// The mouth and whether it is open: a quadratic curve bent by the curvature (corners fixed, middle
/// down for a smile), or, when open, a closed lens between two such curves on either side of it.
fn mouth_path(p: &FaceParams, h: &Head) -> (Vec<PathCmd>, bool) {
    let half = lerp(0.2, 0.5, p.get(Feature::MouthWidth)) * h.hw;
    let y = h.cy + 0.5 * h.hh;
    let bend = (p.get(Feature::MouthCurvature) - 0.5) * 2.0 * (0.4 * half).min(0.14 * h.hh);
    let gap = p.get(Feature::MouthOpenness) * 0.22 * h.hh;
    let (left, right) = (pt(-half, y), pt(half, y));
    // Both lips part evenly from the centre line, so opening the mouth does not change its mood.
    let mut cmds = vec![PathCmd::MoveTo(left), PathCmd::QuadTo(pt(0.0, y + 2.0 * bend - gap), right)];
    let open = gap > 0.0;
    if open {
        cmds.push(PathCmd::QuadTo(pt(0.0, y + 2.0 * bend + gap), left));
        cmds.push(PathCmd::Close);
    }
    (cmds, open)
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAINT: FacePaint =
        FacePaint { skin: Color::rgb(250, 220, 190), ink: Color::rgb(40, 40, 40), hair: Color::rgb(90, 60, 40) };
    const C: Point = Point::new(200.0, 150.0);

    fn with(f: Feature, v: f64) -> FaceParams {
        let mut p = FaceParams::neutral();
        p.set(f, v);
        p
    }

    fn draw(p: &FaceParams) -> Vec<Item> {
        face_items(p, C, 100.0, PAINT)
    }

    fn parts<'a>(items: &'a [Item], label: &str) -> Vec<&'a Item> {
        items.iter().filter(|i| i.label.as_deref() == Some(label)).collect()
    }

    fn cmds(item: &Item) -> &[PathCmd] {
        match &item.shape {
            Shape::Path(c) => c,
            other => panic!("expected a path, got {other:?}"),
        }
    }

    /// Every point an item reaches, control points included, each with the distance the paint
    /// extends around it (half the stroke, or a circle's radius plus half its stroke).
    fn reach(item: &Item) -> Vec<(Point, f64)> {
        let half = item.style.stroke.as_ref().map_or(0.0, |s| s.width / 2.0);
        match &item.shape {
            Shape::Path(c) => c.iter().flat_map(|c| cmd_points(*c)).map(|p| (p, half)).collect(),
            Shape::Circle { center, radius } => vec![(*center, radius + half)],
            other => panic!("unexpected shape {other:?}"),
        }
    }

    /// The centre of an ellipse path: the mean of its four on-curve extreme points.
    fn ellipse_center(item: &Item) -> Point {
        let ends: Vec<Point> =
            cmds(item).iter().filter_map(|c| if let PathCmd::CubicTo(_, _, p) = c { Some(*p) } else { None }).collect();
        assert_eq!(ends.len(), 4);
        Point::new(ends.iter().map(|p| p.x).sum::<f64>() / 4.0, ends.iter().map(|p| p.y).sum::<f64>() / 4.0)
    }

    fn pupil_centers(items: &[Item]) -> Vec<Point> {
        parts(items, "pupil")
            .iter()
            .map(|i| match i.shape {
                Shape::Circle { center, .. } => center,
                _ => panic!("pupil is not a circle"),
            })
            .collect()
    }

    /// A small deterministic generator of values in [lo, hi).
    fn sampler(mut state: u64) -> impl FnMut(f64, f64) -> f64 {
        move |lo, hi| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            lo + (hi - lo) * ((state >> 11) as f64 / (1u64 << 53) as f64)
        }
    }

    #[test]
    fn keys_round_trip_and_are_distinct() {
        let mut keys: Vec<&str> = Feature::ALL.iter().map(|f| f.key()).collect();
        for f in Feature::ALL {
            assert_eq!(Feature::from_key(f.key()), Some(f));
            assert_eq!(f.label(), f.key().replace('_', " "));
            assert_eq!(Feature::ALL[f as usize], f, "ALL is in declaration order");
        }
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), 16);
        assert_eq!(Feature::from_key("Face_Width"), None);
        assert_eq!(Feature::from_key(""), None);
    }

    #[test]
    fn extremes_name_two_different_looks() {
        for f in Feature::ALL {
            let (lo, hi) = f.extremes();
            assert!(!lo.is_empty() && !hi.is_empty() && lo != hi, "{f:?}");
        }
        assert_eq!(Feature::MouthCurvature.extremes(), ("frown", "smile"));
        assert_eq!(Feature::Hair.extremes(), ("bald", "full hair"));
    }

    #[test]
    fn params_are_clamped_and_nan_is_neutral() {
        let mut p = FaceParams([
            f64::NAN,
            -3.0,
            7.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.25,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ]);
        assert_eq!(p.get(Feature::FaceWidth), 0.5);
        assert_eq!(p.get(Feature::FaceHeight), 0.0);
        assert_eq!(p.get(Feature::FaceShape), 1.0);
        assert_eq!(p.get(Feature::EyeSize), 1.0);
        assert_eq!(p.get(Feature::EyeSpacing), 0.0);
        assert_eq!(p.get(Feature::EyeSlant), 0.25);
        p.set(Feature::Hair, f64::NAN);
        assert_eq!(p.0[Feature::Hair as usize], 0.5);
        p.set(Feature::Hair, 1.5);
        assert_eq!(p.get(Feature::Hair), 1.0);
        assert_eq!(FaceParams::default(), FaceParams::neutral());
        assert_eq!(draw(&FaceParams([f64::NAN; 16])), draw(&FaceParams::neutral()));
        assert_eq!(draw(&FaceParams([9.0; 16])), draw(&FaceParams([1.0; 16])));
    }

    #[test]
    fn every_point_is_finite_and_inside_the_square() {
        let mut next = sampler(0x9e37_79b9_7f4a_7c15);
        let mut cases = vec![
            FaceParams([0.0; 16]),
            FaceParams([1.0; 16]),
            FaceParams([0.5; 16]),
            FaceParams([f64::NAN; 16]),
            FaceParams([-1e300; 16]),
            FaceParams([f64::INFINITY; 16]),
        ];
        // Every corner of a few feature subsets, and random vectors in and around [0, 1].
        for mask in 0u32..(1 << 16) {
            if mask.count_ones() <= 1 || mask.count_ones() >= 15 || mask % 97 == 0 {
                cases.push(FaceParams(std::array::from_fn(|i| f64::from((mask >> i) & 1))));
            }
        }
        for _ in 0..500 {
            cases.push(FaceParams(std::array::from_fn(|_| next(0.0, 1.0))));
            cases.push(FaceParams(std::array::from_fn(|_| next(-0.5, 1.5))));
        }
        for (k, p) in cases.iter().enumerate() {
            let size = [60.0, 120.0, 7.0, 1000.0, 45.0][k % 5];
            let center = Point::new(next(-500.0, 500.0), next(-500.0, 500.0));
            let half = size / 2.0;
            let items = face_items(p, center, size, PAINT);
            assert!(items.len() >= 11, "{p:?}");
            for item in &items {
                let stroke = item.style.stroke.as_ref().map_or(0.0, |s| s.width / 2.0);
                for (q, pad) in reach(item) {
                    assert!(q.x.is_finite() && q.y.is_finite() && pad.is_finite(), "{item:?}");
                    // Below 45 the 0.75 minimum stroke outgrows the face; the geometry still fits.
                    let pad = if size >= 45.0 { pad } else { pad - stroke };
                    let inside =
                        (q.x - center.x).abs() + pad <= half + 1e-9 && (q.y - center.y).abs() + pad <= half + 1e-9;
                    assert!(inside, "{:?} of {p:?} at size {size}: {q:?} ± {pad} leaves the square", item.label);
                }
            }
            let b = face_bounds(p, center, size);
            assert!([b.x, b.y, b.w, b.h].iter().all(|v| v.is_finite()) && b.w > 0.0 && b.h > 0.0);
        }
    }

    #[test]
    fn face_width_and_height_scale_the_outline() {
        let levels = [0.0, 0.25, 0.5, 0.75, 1.0];
        let widths: Vec<f64> = levels.iter().map(|&v| face_bounds(&with(Feature::FaceWidth, v), C, 100.0).w).collect();
        let heights: Vec<f64> =
            levels.iter().map(|&v| face_bounds(&with(Feature::FaceHeight, v), C, 100.0).h).collect();
        assert!(widths.windows(2).all(|w| w[1] > w[0]), "{widths:?}");
        assert!(heights.windows(2).all(|h| h[1] > h[0]), "{heights:?}");
        // Width does not change height and vice versa.
        let h0 = face_bounds(&with(Feature::FaceWidth, 0.0), C, 100.0).h;
        assert!((h0 - face_bounds(&with(Feature::FaceWidth, 1.0), C, 100.0).h).abs() < 1e-9);
    }

    #[test]
    fn face_bounds_is_the_head_outline() {
        let mut next = sampler(7);
        for _ in 0..50 {
            let p = FaceParams(std::array::from_fn(|_| next(0.0, 1.0)));
            let items = draw(&p);
            let pts: Vec<Point> = reach(parts(&items, "head")[0]).into_iter().map(|(q, _)| q).collect();
            let b = face_bounds(&p, C, 100.0);
            let min_x = pts.iter().map(|q| q.x).fold(f64::INFINITY, f64::min);
            let max_y = pts.iter().map(|q| q.y).fold(f64::NEG_INFINITY, f64::max);
            assert!((b.x - min_x).abs() < 1e-9 && (b.bottom() - max_y).abs() < 1e-9);
            assert!((b.x + b.w / 2.0 - C.x).abs() < 1e-9, "the head is centred horizontally");
        }
    }

    #[test]
    fn pointed_chin_narrows_the_jaw() {
        // The on-curve midpoint of the lower right quarter moves inwards as the shape gets pointed.
        let jaw_x = |v: f64| {
            let items = draw(&with(Feature::FaceShape, v));
            match cmds(parts(&items, "head")[0])[1] {
                PathCmd::CubicTo(a, b, _) => {
                    let PathCmd::MoveTo(s) = cmds(parts(&items, "head")[0])[0] else { panic!() };
                    (s.x + 3.0 * a.x + 3.0 * b.x) / 8.0
                }
                other => panic!("{other:?}"),
            }
        };
        let xs: Vec<f64> = [0.0, 0.5, 1.0].into_iter().map(jaw_x).collect();
        assert!(xs[0] > xs[1] && xs[1] > xs[2], "{xs:?}");
    }

    #[test]
    fn mouth_curvature_bends_the_centre_line() {
        for openness in [0.0, 0.5, 1.0] {
            for width in [0.0, 1.0] {
                // Middle control point of the mouth's centre line minus the corners' y (y grows down).
                let sag = |curvature: f64| {
                    let mut p = with(Feature::MouthCurvature, curvature);
                    p.set(Feature::MouthOpenness, openness);
                    p.set(Feature::MouthWidth, width);
                    let items = draw(&p);
                    let path = cmds(parts(&items, "mouth")[0]);
                    let PathCmd::MoveTo(corner) = path[0] else { panic!("{path:?}") };
                    let ctrls: Vec<f64> = path
                        .iter()
                        .filter_map(|c| if let PathCmd::QuadTo(a, _) = c { Some(a.y) } else { None })
                        .collect();
                    ctrls.iter().sum::<f64>() / ctrls.len() as f64 - corner.y
                };
                assert!(sag(1.0) > 1.0, "smile: middle below the corners");
                assert!(sag(0.0) < -1.0, "frown: middle above the corners");
                assert!(sag(0.5).abs() < 1e-9, "straight");
                assert!(sag(0.75) > 0.0 && sag(0.75) < sag(1.0));
            }
        }
    }

    #[test]
    fn mouth_opens_into_a_filled_lens() {
        let shut = draw(&with(Feature::MouthOpenness, 0.0));
        let mouth = parts(&shut, "mouth")[0];
        assert!(!cmds(mouth).contains(&PathCmd::Close) && mouth.style.fill.is_none());
        assert_eq!(cmds(mouth).len(), 2);
        for v in [0.1, 1.0] {
            let open = draw(&with(Feature::MouthOpenness, v));
            let mouth = parts(&open, "mouth")[0];
            assert_eq!(cmds(mouth).last(), Some(&PathCmd::Close));
            let fill = mouth.style.fill.expect("open mouth is filled");
            assert_eq!((fill.r, fill.g, fill.b), (PAINT.ink.r, PAINT.ink.g, PAINT.ink.b));
            assert!(fill.a > 0 && fill.a < 128);
        }
        // Wider open, further apart lips.
        let gap = |v: f64| {
            let items = draw(&with(Feature::MouthOpenness, v));
            let ys: Vec<f64> = cmds(parts(&items, "mouth")[0])
                .iter()
                .filter_map(|c| if let PathCmd::QuadTo(a, _) = c { Some(a.y) } else { None })
                .collect();
            ys[1] - ys[0]
        };
        assert!(gap(1.0) > gap(0.5) && gap(0.5) > 0.0);
    }

    #[test]
    fn eye_spacing_separates_the_eyes() {
        let distance = |v: f64| {
            let items = draw(&with(Feature::EyeSpacing, v));
            let eyes = parts(&items, "eye");
            let (l, r) = (ellipse_center(eyes[0]), ellipse_center(eyes[1]));
            assert!((l.y - r.y).abs() < 1e-9 && l.x < r.x);
            r.x - l.x
        };
        let d: Vec<f64> = [0.0, 0.25, 0.5, 0.75, 1.0].into_iter().map(distance).collect();
        assert!(d.windows(2).all(|w| w[1] > w[0]), "{d:?}");
    }

    #[test]
    fn eye_slant_raises_the_outer_corners() {
        // Outer corner height relative to the eye centre: up (smaller y) for upturned eyes.
        let outer_rise = |v: f64| {
            let items = draw(&with(Feature::EyeSlant, v));
            let right = parts(&items, "eye")[1];
            let PathCmd::MoveTo(start) = cmds(right)[0] else { panic!() };
            ellipse_center(right).y - start.y
        };
        assert!(outer_rise(1.0) > 1.0 && outer_rise(0.0) < -1.0 && outer_rise(0.5).abs() < 1e-9);
    }

    #[test]
    fn pupils_move_right_and_stay_in_their_eyes() {
        let mut last: Option<Vec<Point>> = None;
        for v in [0.0, 0.25, 0.5, 0.75, 1.0] {
            for slant in [0.0, 0.5, 1.0] {
                let mut p = with(Feature::PupilPosition, v);
                p.set(Feature::EyeSlant, slant);
                let items = draw(&p);
                for (eye, pupil) in parts(&items, "eye").iter().zip(parts(&items, "pupil")) {
                    let Shape::Circle { center, radius } = pupil.shape else { panic!() };
                    let e = ellipse_center(eye);
                    let rx = match cmds(eye)[0] {
                        PathCmd::MoveTo(s) => (s.x - e.x).hypot(s.y - e.y),
                        _ => panic!(),
                    };
                    assert!((center.x - e.x).hypot(center.y - e.y) + radius < rx);
                }
            }
            let now = pupil_centers(&draw(&with(Feature::PupilPosition, v)));
            if let Some(before) = last {
                assert!(now.iter().zip(&before).all(|(a, b)| a.x > b.x), "{before:?} → {now:?}");
            }
            last = Some(now);
        }
    }

    #[test]
    fn brows_rise_with_brow_height() {
        let top = |v: f64| {
            let items = draw(&with(Feature::BrowHeight, v));
            parts(&items, "brow").iter().flat_map(|b| reach(b)).map(|(q, _)| q.y).fold(f64::INFINITY, f64::min)
        };
        assert!(top(1.0) < top(0.5) && top(0.5) < top(0.0));
    }

    #[test]
    fn hair_appears_only_with_hair() {
        assert!(parts(&draw(&with(Feature::Hair, 0.0)), "hair").is_empty());
        assert_eq!(parts(&draw(&with(Feature::Hair, 0.01)), "hair").len(), 1);
        assert_eq!(parts(&draw(&with(Feature::Hair, 1.0)), "hair").len(), 1);
        // More hair reaches higher above the head.
        let top = |v: f64| {
            let items = draw(&with(Feature::Hair, v));
            reach(parts(&items, "hair")[0]).iter().map(|(q, _)| q.y).fold(f64::INFINITY, f64::min)
        };
        assert!(top(1.0) < top(0.5) && top(0.5) < top(0.1));
    }

    #[test]
    fn small_ears_still_show_beside_the_head() {
        for v in [0.0, 1.0] {
            let p = with(Feature::EarSize, v);
            let b = face_bounds(&p, C, 100.0);
            let items = draw(&p);
            let ears = parts(&items, "ear");
            assert_eq!(ears.len(), 2);
            let xs: Vec<f64> = ears.iter().flat_map(|e| reach(e)).map(|(q, _)| q.x).collect();
            let (lo, hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, c), &x| (a.min(x), c.max(x)));
            assert!(lo < b.x - 2.0 && hi > b.right() + 2.0, "ears at {v} do not show");
        }
    }

    #[test]
    fn items_come_in_drawing_order_as_data_marks() {
        let items = draw(&FaceParams::neutral());
        let labels: Vec<&str> = items.iter().map(|i| i.label.as_deref().unwrap()).collect();
        let order = ["hair", "ear", "ear", "head", "brow", "brow", "eye", "eye", "pupil", "pupil", "nose", "mouth"];
        assert_eq!(labels, order);
        assert!(items.iter().all(|i| i.role == Role::DataMark && i.rows.is_empty()));
        assert_eq!(parts(&items, "head")[0].style.fill, Some(PAINT.skin));
        assert_eq!(parts(&items, "hair")[0].style.fill, Some(PAINT.hair));
    }

    #[test]
    fn stroke_width_follows_size_with_a_floor() {
        let width = |size: f64| {
            let items = face_items(&FaceParams::neutral(), C, size, PAINT);
            parts(&items, "head")[0].style.stroke.as_ref().unwrap().width
        };
        assert!((width(120.0) - 2.0).abs() < 1e-12);
        assert_eq!(width(30.0), 0.75);
    }

    #[test]
    fn same_params_draw_the_same_face() {
        let mut next = sampler(42);
        for _ in 0..20 {
            let p = FaceParams(std::array::from_fn(|_| next(0.0, 1.0)));
            assert_eq!(draw(&p), draw(&p));
            assert_eq!(face_bounds(&p, C, 80.0), face_bounds(&p, C, 80.0));
        }
    }

    #[test]
    fn invalid_size_or_centre_draws_nothing() {
        let p = FaceParams::neutral();
        for size in [0.0, -10.0, f64::NAN, f64::INFINITY] {
            assert!(face_items(&p, C, size, PAINT).is_empty());
            assert_eq!(face_bounds(&p, C, size), Rect::new(C.x, C.y, 0.0, 0.0));
        }
        assert!(face_items(&p, Point::new(f64::NAN, 0.0), 100.0, PAINT).is_empty());
    }

    #[test]
    fn ellipse_curves_pass_through_the_ellipse() {
        let (c, rx, ry, angle) = (Point::new(3.0, -2.0), 5.0, 2.0, 0.7_f64);
        let (s, co) = angle.sin_cos();
        let path = ellipse(c, rx, ry, angle);
        let mut start = match path[0] {
            PathCmd::MoveTo(p) => p,
            _ => panic!(),
        };
        for cmd in &path[1..5] {
            let PathCmd::CubicTo(a, b, e) = *cmd else { panic!("{cmd:?}") };
            // The curve's midpoint, rotated back into the ellipse's own axes, is on the ellipse.
            let m = Point::new(
                (start.x + 3.0 * a.x + 3.0 * b.x + e.x) / 8.0 - c.x,
                (start.y + 3.0 * a.y + 3.0 * b.y + e.y) / 8.0 - c.y,
            );
            let (u, v) = (m.x * co + m.y * s, -m.x * s + m.y * co);
            assert!(((u / rx).powi(2) + (v / ry).powi(2) - 1.0).abs() < 1e-3);
            start = e;
        }
        assert_eq!(path[5], PathCmd::Close);
    }
}
