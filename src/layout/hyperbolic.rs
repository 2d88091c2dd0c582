//! Hyperbolic tree layout in the Poincaré disk, after Lamping, Rao & Pirolli (1995), "A
//! focus+context technique based on hyperbolic geometry for visualizing large hierarchies".
//!
//! **Layout.** The tree is laid out once in the hyperbolic plane, modelled by the open unit disk,
//! with the root at the centre. Every node owns a *wedge* of directions as seen from itself; the
//! root's wedge is the full turn. A node's wedge is split among its children in proportion to
//! their leaf counts (or child counts). Each child sits on the bisector of its share at hyperbolic
//! distance `spacing`, i.e. at Euclidean radius `r = tanh(spacing / 2)` in the parent's own frame.
//! The child's wedge is the set of directions, seen from the child, towards the ideal (rim) points
//! of its share: translating the child to the centre along the bisector turns a half-width `ω`
//! into `ω'` with `cos ω' = ((1 + r²) cos ω − 2r) / (1 + r² − 2r cos ω)` (Lamping & Rao's wedge
//! recursion). Because the parent lies on the bisector of the complementary arc, every subtree
//! stays inside the region bounded by the two geodesic rays from its parent to the ends of its
//! share, so sibling subtrees never overlap. Before the recursion a share is capped at half a turn
//! so a dominant or lone child fans its subtree out ahead of itself instead of wrapping back
//! around its parent. Each node's frame (a Möbius map from its local coordinates to the disk) is its
//! parent's frame after the translation to the child. One pass over the preorder, no recursion,
//! O(n) time.
//!
//! **Viewing.** Changing the focus is an isometry of the disk, a [`Mobius`] map
//! `z ↦ rot·(z + a)/(1 + ā·z)`, applied to the stored positions: O(n), no relayout ([`view`]).
//! Edges are geodesics, arcs of circles orthogonal to the unit circle ([`geodesic`]), and
//! [`scale_at`] gives the local size factor `1 − |z|²` for nodes and labels.
//!
//! **Precision.** A point at hyperbolic distance `d` from the centre has `1 − |z| ≈ 2·e^(−d)`, so
//! beyond `d ≈ 28` the base position is held at radius [`MAX_RADIUS`] = 1 − 1e-12 (it is far below
//! a pixel from the rim there). Focusing on such a node through its base position cannot separate
//! it from its neighbours; [`view_from`] rebuilds positions outward from an anchor node through
//! the stored parent-to-child offsets, so any part of a deep tree can be viewed accurately.
//!
//! Points are `[x, y]` with angles counter-clockwise from +x (y up); a renderer with y down sees
//! the picture mirrored, which is harmless, and must flip `clockwise` of [`Geodesic::Arc`].

use super::hierarchy::Hierarchy;
use std::f64::consts::PI;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Largest radius a returned point may have: points that would round to the rim are pulled in
/// to this radius so every position stays strictly inside the unit disk.
pub const MAX_RADIUS: f64 = 1.0 - 1e-12;

/// Largest accepted `spacing`: beyond it every node but the root sits on the rim.
pub const MAX_SPACING: f64 = 20.0;

/// A complex number, the natural coordinate of the Poincaré disk.
#[derive(Clone, Copy, Debug, PartialEq)]
struct C {
    re: f64,
    im: f64,
}

impl C {
    const ZERO: C = C { re: 0.0, im: 0.0 };
    const ONE: C = C { re: 1.0, im: 0.0 };

    fn of(p: [f64; 2]) -> C {
        C { re: p[0], im: p[1] }
    }

    fn xy(self) -> [f64; 2] {
        [self.re, self.im]
    }

    fn polar(radius: f64, angle: f64) -> C {
        let (sin, cos) = angle.sin_cos();
        C { re: radius * cos, im: radius * sin }
    }

    fn conj(self) -> C {
        C { re: self.re, im: -self.im }
    }

    fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }

    fn scale(self, k: f64) -> C {
        C { re: self.re * k, im: self.im * k }
    }

    fn is_finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
}

impl Add for C {
    type Output = C;
    fn add(self, o: C) -> C {
        C { re: self.re + o.re, im: self.im + o.im }
    }
}

impl Sub for C {
    type Output = C;
    fn sub(self, o: C) -> C {
        C { re: self.re - o.re, im: self.im - o.im }
    }
}

impl Mul for C {
    type Output = C;
    fn mul(self, o: C) -> C {
        C { re: self.re * o.re - self.im * o.im, im: self.re * o.im + self.im * o.re }
    }
}

impl Div for C {
    type Output = C;
    fn div(self, o: C) -> C {
        (self * o.conj()).scale(1.0 / o.norm_sqr())
    }
}

impl Neg for C {
    type Output = C;
    fn neg(self) -> C {
        C { re: -self.re, im: -self.im }
    }
}

/// Pulls a point onto the closed disk of radius [`MAX_RADIUS`] (non-finite points pass through).
fn clamp_disk(z: C) -> C {
    let n2 = z.norm_sqr();
    if n2 > MAX_RADIUS * MAX_RADIUS { z.scale(MAX_RADIUS / n2.sqrt()) } else { z }
}

/// An orientation-preserving isometry of the Poincaré disk, `z ↦ rot·(z + a)/(1 + ā·z)` with
/// `|a| < 1` and `|rot| = 1`. Constructors keep both invariants (`|a| ≤` [`MAX_RADIUS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mobius {
    rot: C,
    a: C,
}

impl Mobius {
    /// Builds a map from raw parts, normalising `rot` to unit length and clamping `a` into the disk.
    fn from_parts(rot: C, a: C) -> Mobius {
        let len = rot.abs();
        let rot = if len.is_finite() && len > 0.0 { rot.scale(1.0 / len) } else { C::ONE };
        let a = if a.is_finite() { clamp_disk(a) } else { C::ZERO };
        Mobius { rot, a }
    }

    /// The map that leaves every point where it is.
    pub fn identity() -> Mobius {
        Mobius { rot: C::ONE, a: C::ZERO }
    }

    /// Rotation about the centre by `angle` radians (counter-clockwise); non-finite → identity.
    pub fn rotation(angle: f64) -> Mobius {
        if !angle.is_finite() {
            return Mobius::identity();
        }
        Mobius { rot: C::polar(1.0, angle), a: C::ZERO }
    }

    /// The hyperbolic translation along the diameter through `to` that moves the centre to `to`.
    fn translation(to: C) -> Mobius {
        Mobius::from_parts(C::ONE, to)
    }

    /// The hyperbolic translation that moves `point` to the centre, `z ↦ (z − p)/(1 − p̄·z)`.
    /// It slides the plane along the geodesic through `point` and the centre without any spin
    /// (Lamping–Rao's click-to-focus): directions along that geodesic are kept, others turn a
    /// little, as translations in the hyperbolic plane do. To keep, say, the parent direction
    /// fixed on screen, follow it with a [`Mobius::rotation`]. A point on or outside the rim is
    /// first pulled in to [`MAX_RADIUS`]; a non-finite point gives the identity.
    pub fn focus_on(point: [f64; 2]) -> Mobius {
        let p = C::of(point);
        if !p.is_finite() {
            return Mobius::identity();
        }
        Mobius::from_parts(C::ONE, -p)
    }

    /// The hyperbolic translation along the geodesic through `from` and `to` that maps `from`
    /// to `to` (for dragging the view with the pointer). Built as: move `from` to the centre,
    /// translate along the diameter to the image of `to`, move back. Non-finite points give the
    /// identity; points outside the disk are pulled in to [`MAX_RADIUS`].
    pub fn drag(from: [f64; 2], to: [f64; 2]) -> Mobius {
        let (f, t) = (C::of(from), C::of(to));
        if !f.is_finite() || !t.is_finite() {
            return Mobius::identity();
        }
        let to_centre = Mobius::focus_on(from);
        let along = Mobius::translation(to_centre.map(clamp_disk(t)));
        to_centre.then(&along).then(&to_centre.inverse())
    }

    /// The composition "first `self`, then `next`" (`z ↦ next(self(z))`), in closed form.
    pub fn then(&self, next: &Mobius) -> Mobius {
        let (r1, a1, r2, a2) = (self.rot, self.a, next.rot, next.a);
        let lead = r1 + a2 * a1.conj();
        let a = (r1 * a1 + a2) / lead;
        let rot = r2 * lead / (C::ONE + a2.conj() * r1 * a1);
        Mobius::from_parts(rot, a)
    }

    /// The map applied to one point, in complex arithmetic, without clamping.
    fn map(&self, z: C) -> C {
        self.rot * (z + self.a) / (C::ONE + self.a.conj() * z)
    }

    /// Maps a point. The point is first pulled in to [`MAX_RADIUS`] and so is the result;
    /// non-finite coordinates are returned unchanged.
    pub fn apply(&self, z: [f64; 2]) -> [f64; 2] {
        let z = C::of(z);
        if !z.is_finite() {
            return z.xy();
        }
        clamp_disk(self.map(clamp_disk(z))).xy()
    }

    /// The inverse map, `(rot, a) ↦ (conj(rot), −rot·a)`.
    pub fn inverse(&self) -> Mobius {
        Mobius::from_parts(self.rot.conj(), -(self.rot * self.a))
    }

    /// The unit factor `rot` of `z ↦ rot·(z + a)/(1 + ā·z)`, as `[re, im]`.
    pub fn rot(&self) -> [f64; 2] {
        self.rot.xy()
    }

    /// The offset `a` of `z ↦ rot·(z + a)/(1 + ā·z)`, as `[re, im]` (`|a| < 1`).
    pub fn offset(&self) -> [f64; 2] {
        self.a.xy()
    }

    /// Where the map sends the centre, `rot·a`, pulled in to [`MAX_RADIUS`].
    fn image_of_centre(&self) -> C {
        clamp_disk(self.rot * self.a)
    }
}

/// Settings of [`HyperbolicLayout::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HyperbolicOptions {
    /// Hyperbolic distance from a parent to each child; finite, in (0, [`MAX_SPACING`]].
    /// Default 1.0 (children of the centre at Euclidean radius tanh(0.5) ≈ 0.46).
    pub spacing: f64,
    /// Share of the parent's wedge proportional to each child's leaf count (true, the default)
    /// or to its child count, a leaf counting as one (false).
    pub weight_by_leaves: bool,
}

impl Default for HyperbolicOptions {
    fn default() -> Self {
        HyperbolicOptions { spacing: 1.0, weight_by_leaves: true }
    }
}

/// Why a hyperbolic layout or view could not be made.
#[derive(Clone, Debug, PartialEq)]
pub enum HyperbolicError {
    /// `spacing` is not finite or not in (0, [`MAX_SPACING`]].
    BadSpacing(f64),
    /// The anchor of [`view_from`] is not a node of the layout.
    AnchorOutOfRange {
        /// The anchor given.
        anchor: usize,
        /// Number of nodes in the layout.
        len: usize,
    },
}

impl fmt::Display for HyperbolicError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadSpacing(s) => write!(
                f,
                "hyperbolic spacing {s} is not usable: give a finite distance greater than 0 and at most \
                 {MAX_SPACING} (1.0 is a good start)"
            ),
            Self::AnchorOutOfRange { anchor, len } => {
                write!(f, "anchor node {anchor} does not exist: the layout has {len} nodes (use 0..{len})")
            }
        }
    }
}

impl std::error::Error for HyperbolicError {}

/// A tree laid out in the Poincaré disk with the root at the centre.
#[derive(Clone, Debug, PartialEq)]
pub struct HyperbolicLayout {
    /// Position of every node, root at 0.
    base: Vec<[f64; 2]>,
    /// Position of every node in its parent's frame (0 for the root).
    local: Vec<[f64; 2]>,
    /// Parent of every node ([`super::hierarchy::NO_PARENT`] for the root).
    parent: Vec<u32>,
    /// Preorder from the root.
    order: Vec<u32>,
}

impl HyperbolicLayout {
    /// Lays `tree` out (see the module documentation). Errors only on a bad `spacing`.
    pub fn new(tree: &Hierarchy, options: &HyperbolicOptions) -> Result<Self, HyperbolicError> {
        let spacing = options.spacing;
        if !(spacing.is_finite() && spacing > 0.0 && spacing <= MAX_SPACING) {
            return Err(HyperbolicError::BadSpacing(spacing));
        }
        let radius = (spacing / 2.0).tanh();
        let weight = share_weights(tree, options.weight_by_leaves);
        let (pass, _) = wedge_pass(tree, radius, &weight);
        Ok(HyperbolicLayout {
            base: pass.base,
            local: pass.local,
            parent: tree.parent_raw().to_vec(),
            order: pass.order,
        })
    }

    /// Base position of every node (root at the centre), indexed by node.
    pub fn base(&self) -> &[[f64; 2]] {
        &self.base
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.base.len()
    }

    /// Always false: a layout has at least its root.
    pub fn is_empty(&self) -> bool {
        self.base.is_empty()
    }

    /// The parent of `node`, if it has one.
    fn parent_of(&self, node: usize) -> Option<usize> {
        self.parent.get(node).filter(|&&p| p != super::hierarchy::NO_PARENT).map(|&p| p as usize)
    }

    /// Frame of `node`: the map from its local coordinates (node at 0) to the base disk,
    /// recomposed from the root exactly as the layout pass does.
    fn frame_of(&self, node: usize) -> Mobius {
        let mut path = vec![node];
        while let Some(p) = path.last().and_then(|&v| self.parent_of(v)) {
            path.push(p);
        }
        path.iter()
            .rev()
            .skip(1)
            .fold(Mobius::identity(), |frame, &v| Mobius::translation(C::of(self.local[v])).then(&frame))
    }
}

/// What one layout pass produces, per node.
struct Pass {
    /// Position in the parent's frame.
    local: Vec<[f64; 2]>,
    /// Position in the disk.
    base: Vec<[f64; 2]>,
    /// Preorder.
    order: Vec<u32>,
}

/// Lamping–Rao's wedge recursion over the preorder: splits each node's wedge among its children
/// by `weight`, places each child on the bisector of its share at Euclidean radius `radius` in
/// the parent's frame, and gives it the wedge it sees towards the ends of its (capped) share.
/// Also returns every node's wedge `(start, width)` in radians, in its own frame.
fn wedge_pass(tree: &Hierarchy, radius: f64, weight: &[f64]) -> (Pass, Vec<(f64, f64)>) {
    let n = tree.len();
    let order = tree.preorder();
    let mut frame = vec![Mobius::identity(); n];
    let mut wedge = vec![(0.0, 0.0); n];
    let mut local = vec![[0.0; 2]; n];
    let mut base = vec![[0.0; 2]; n];
    wedge[tree.root()] = (0.0, 2.0 * PI);
    for &p in &order {
        let p = p as usize;
        let kids = tree.children(p);
        let total: f64 = kids.iter().map(|&c| weight[c as usize]).sum();
        let (start, width) = wedge[p];
        let mut used = 0.0;
        for &c in kids {
            let c = c as usize;
            let share = width * weight[c] / total;
            let direction = start + used + share / 2.0;
            used += share;
            let offset = C::polar(radius, direction);
            let half = child_half_width(share.min(PI) / 2.0, radius);
            wedge[c] = (direction - half, 2.0 * half);
            frame[c] = Mobius::translation(offset).then(&frame[p]);
            local[c] = offset.xy();
            base[c] = frame[c].image_of_centre().xy();
        }
    }
    (Pass { local, base, order }, wedge)
}

/// Weight of each node in its parent's split: leaf count, or child count with a leaf as one.
fn share_weights(tree: &Hierarchy, by_leaves: bool) -> Vec<f64> {
    if by_leaves {
        tree.sum_leaves(&vec![1.0; tree.len()])
    } else {
        (0..tree.len()).map(|v| tree.children(v).len().max(1) as f64).collect()
    }
}

/// Half-width of a child's wedge seen from the child, for a share of half-width `half` seen from
/// the parent and the child at Euclidean radius `radius` in the parent's frame.
fn child_half_width(half: f64, radius: f64) -> f64 {
    let (cos, r2) = (half.cos(), radius * radius);
    let c = ((1.0 + r2) * cos - 2.0 * radius) / (1.0 + r2 - 2.0 * radius * cos);
    c.clamp(-1.0, 1.0).acos()
}

/// Every node's position after `transform`, from the stored base positions: O(n), no relayout.
/// Accurate wherever the base positions are (see the module note on precision).
pub fn view(layout: &HyperbolicLayout, transform: &Mobius) -> Vec<[f64; 2]> {
    layout.base.iter().map(|&z| transform.apply(z)).collect()
}

/// Every node's position in the view centred on `anchor` and then moved by `transform`. In exact
/// arithmetic this equals `view(layout, &Mobius::focus_on(layout.base()[anchor]).then(transform))`,
/// but positions are rebuilt outward from the anchor through the parent-to-child offsets, so nodes
/// near the anchor are placed accurately however deep the anchor is. O(n) time, 32 bytes a node
/// of scratch memory. An app that lets the user drag far can re-anchor on the node nearest the
/// centre and keep `transform` small.
pub fn view_from(
    layout: &HyperbolicLayout,
    anchor: usize,
    transform: &Mobius,
) -> Result<Vec<[f64; 2]>, HyperbolicError> {
    let n = layout.len();
    if anchor >= n {
        return Err(HyperbolicError::AnchorOutOfRange { anchor, len: n });
    }
    // The anchor's frame followed by focusing on its base position is the rotation by the
    // frame's `rot`; starting there makes the result agree with `view`.
    let start = Mobius { rot: layout.frame_of(anchor).rot, a: C::ZERO }.then(transform);
    let mut to_screen = vec![Mobius::identity(); n];
    let mut done = vec![false; n];
    to_screen[anchor] = start;
    done[anchor] = true;
    let mut node = anchor;
    while let Some(p) = layout.parent_of(node) {
        to_screen[p] = Mobius::translation(-C::of(layout.local[node])).then(&to_screen[node]);
        done[p] = true;
        node = p;
    }
    for &v in &layout.order {
        let v = v as usize;
        if done[v] {
            continue;
        }
        if let Some(p) = layout.parent_of(v) {
            to_screen[v] = Mobius::translation(C::of(layout.local[v])).then(&to_screen[p]);
        }
    }
    Ok(to_screen.iter().map(|m| m.image_of_centre().xy()).collect())
}

/// Hyperbolic distance between two disk points, `2·artanh(|p − q| / |1 − p̄·q|)`. Points are
/// first pulled in to [`MAX_RADIUS`]; non-finite input gives NaN.
pub fn distance(p: [f64; 2], q: [f64; 2]) -> f64 {
    let (p, q) = (clamp_disk(C::of(p)), clamp_disk(C::of(q)));
    if !p.is_finite() || !q.is_finite() {
        return f64::NAN;
    }
    let ratio = (p - q).abs() / (C::ONE - p.conj() * q).abs();
    2.0 * ratio.min(MAX_RADIUS).atanh()
}

/// The hyperbolic line segment between two disk points, as drawn in the Poincaré disk.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geodesic {
    /// A straight segment: the two points are (nearly) on a diameter.
    Segment {
        /// Start point.
        from: [f64; 2],
        /// End point.
        to: [f64; 2],
    },
    /// An arc, less than a half circle, of a circle orthogonal to the unit circle
    /// (`|center|² = radius² + 1`).
    Arc {
        /// Centre of the circle (outside the unit disk).
        center: [f64; 2],
        /// Radius of the circle.
        radius: f64,
        /// Start point.
        from: [f64; 2],
        /// End point.
        to: [f64; 2],
        /// True when going from `from` to `to` turns clockwise about `center` (y up).
        clockwise: bool,
    },
}

/// Below this `|a × b|` the geodesic is drawn straight: its circle has radius above ~1e9 and
/// the arc bows less than 1e-9 from the chord.
const STRAIGHT_CROSS: f64 = 1e-9;

/// The geodesic between `a` and `b`. Points are pulled in to [`MAX_RADIUS`]. The circle's centre
/// `c` solves `c·a = (1 + |a|²)/2` and `c·b = (1 + |b|²)/2` (it passes through both points and
/// meets the unit circle at right angles); when `a`, `b` and the centre are (nearly) collinear,
/// or a point is not finite, the result is a [`Geodesic::Segment`].
pub fn geodesic(a: [f64; 2], b: [f64; 2]) -> Geodesic {
    let (p, q) = (clamp_disk(C::of(a)), clamp_disk(C::of(b)));
    let cross = p.re * q.im - p.im * q.re;
    if cross.is_nan() || cross.abs() <= STRAIGHT_CROSS {
        return Geodesic::Segment { from: p.xy(), to: q.xy() };
    }
    let (ka, kb) = ((1.0 + p.norm_sqr()) / 2.0, (1.0 + q.norm_sqr()) / 2.0);
    let center = C { re: (ka * q.im - kb * p.im) / cross, im: (p.re * kb - q.re * ka) / cross };
    let radius = (center.norm_sqr() - 1.0).max(0.0).sqrt();
    let (u, v) = (p - center, q - center);
    let turn = u.re * v.im - u.im * v.re;
    Geodesic::Arc { center: center.xy(), radius, from: p.xy(), to: q.xy(), clockwise: turn < 0.0 }
}

/// Smallest angle step [`Geodesic::points`] accepts (radians).
const MIN_ANGLE_STEP: f64 = 1e-3;

impl Geodesic {
    /// A polyline through the geodesic: the two ends of a segment, or points on the arc at most
    /// `max_angle_step` radians apart (about the arc's centre), both ends exact. A step below
    /// 0.001 rad, or not finite, is raised to 0.001, so an arc has at most ~3,143 points.
    pub fn points(&self, max_angle_step: f64) -> Vec<[f64; 2]> {
        match *self {
            Geodesic::Segment { from, to } => vec![from, to],
            Geodesic::Arc { center, radius, from, to, .. } => {
                let c = C::of(center);
                let (u, v) = (C::of(from) - c, C::of(to) - c);
                let start = u.im.atan2(u.re);
                let sweep = (u.conj() * v).im.atan2((u.conj() * v).re);
                let step = if max_angle_step.is_finite() { max_angle_step.max(MIN_ANGLE_STEP) } else { MIN_ANGLE_STEP };
                let pieces = (sweep.abs() / step).ceil().max(1.0) as usize;
                let mut out = Vec::with_capacity(pieces + 1);
                out.push(from);
                for k in 1..pieces {
                    let angle = start + sweep * k as f64 / pieces as f64;
                    out.push((c + C::polar(radius, angle)).xy());
                }
                out.push(to);
                out
            }
        }
    }
}

/// Local size factor `1 − |z|²` of the Poincaré disk at `z` (1 at the centre, → 0 at the rim);
/// scale node marks and labels by it. Clamped to [0, 1]; non-finite input gives 0.
pub fn scale_at(z: [f64; 2]) -> f64 {
    let s = 1.0 - C::of(z).norm_sqr();
    if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (SplitMix64) for test points.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }

        /// A point uniform in angle, radius up to `max`.
        fn point(&mut self, max: f64) -> [f64; 2] {
            C::polar(max * self.next(), 2.0 * PI * self.next()).xy()
        }

        fn mobius(&mut self) -> Mobius {
            Mobius::focus_on(self.point(0.9)).then(&Mobius::rotation(2.0 * PI * self.next()))
        }
    }

    /// A complete tree with the given branching per level.
    fn balanced(branching: &[usize]) -> Hierarchy {
        let mut parents = vec![None];
        let mut level = vec![0usize];
        for &b in branching {
            let mut next = Vec::new();
            for &p in &level {
                for _ in 0..b {
                    next.push(parents.len());
                    parents.push(Some(p));
                }
            }
            level = next;
        }
        Hierarchy::from_parents(&parents).unwrap()
    }

    fn chain(n: usize) -> Hierarchy {
        let parents: Vec<_> = (0..n).map(|i| i.checked_sub(1)).collect();
        Hierarchy::from_parents(&parents).unwrap()
    }

    fn star(n: usize) -> Hierarchy {
        let parents: Vec<_> = (0..n).map(|i| if i == 0 { None } else { Some(0) }).collect();
        Hierarchy::from_parents(&parents).unwrap()
    }

    fn layout(tree: &Hierarchy) -> HyperbolicLayout {
        HyperbolicLayout::new(tree, &HyperbolicOptions::default()).unwrap()
    }

    fn close(p: [f64; 2], q: [f64; 2], tol: f64) -> bool {
        (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol
    }

    fn inside(p: [f64; 2]) -> bool {
        p[0].is_finite() && p[1].is_finite() && p[0].hypot(p[1]) < 1.0
    }

    #[test]
    fn every_position_is_finite_inside_the_disk_with_the_root_at_the_centre() {
        let trees = [chain(1), chain(100_000), star(10_000), balanced(&[3, 4, 5, 2])];
        for tree in &trees {
            let lay = layout(tree);
            assert_eq!(lay.base().len(), tree.len());
            assert_eq!(lay.base()[tree.root()], [0.0, 0.0]);
            assert!(lay.base().iter().all(|&p| inside(p)));
        }
        // A star's children all sit at radius tanh(1/2), at distinct angles.
        let lay = layout(&star(10_000));
        let r = 0.5f64.tanh();
        assert!(lay.base()[1..].iter().all(|p| (p[0].hypot(p[1]) - r).abs() < 1e-12));
        let mut angles: Vec<f64> = lay.base()[1..].iter().map(|p| p[1].atan2(p[0])).collect();
        angles.sort_by(f64::total_cmp);
        assert!(angles.windows(2).all(|w| w[1] - w[0] > 0.5 * 2.0 * PI / 10_000.0));
    }

    #[test]
    fn parent_to_child_distance_is_the_spacing() {
        let tree = balanced(&[3, 2, 4, 2]);
        for spacing in [0.3, 1.0, 2.5] {
            let options = HyperbolicOptions { spacing, weight_by_leaves: false };
            let lay = HyperbolicLayout::new(&tree, &options).unwrap();
            for v in 0..tree.len() {
                if let Some(p) = tree.parent(v) {
                    let d = distance(lay.base()[p], lay.base()[v]);
                    assert!((d - spacing).abs() < 1e-9 * spacing, "{v}: {d} vs {spacing}");
                }
            }
        }
    }

    /// Checks that in every node's own frame, each child's whole subtree lies within the
    /// angular share of the node's wedge given to that child (share ∝ leaf count).
    fn assert_subtrees_in_their_shares(tree: &Hierarchy) {
        let lay = layout(tree);
        let leaves = tree.sum_leaves(&vec![1.0; tree.len()]);
        let (_, wedge) = wedge_pass(tree, 0.5f64.tanh(), &leaves);
        for (p, &(start, width)) in wedge.iter().enumerate() {
            let total: f64 = tree.children(p).iter().map(|&k| leaves[k as usize]).sum();
            let to_local = lay.frame_of(p).inverse();
            let mut low = start;
            for &c in tree.children(p) {
                let high = low + width * leaves[c as usize] / total;
                let mut stack = vec![c as usize];
                while let Some(v) = stack.pop() {
                    stack.extend(tree.children(v).iter().map(|&k| k as usize));
                    let z = to_local.apply(lay.base()[v]);
                    let angle = low + (z[1].atan2(z[0]) - low).rem_euclid(2.0 * PI);
                    assert!(angle <= high + 1e-9, "node {v} under child {c} of {p}: {angle} not in [{low}, {high}]");
                }
                low = high;
            }
        }
    }

    #[test]
    fn sibling_subtrees_stay_in_their_own_share_of_every_wedge() {
        assert_subtrees_in_their_shares(&balanced(&[3, 3, 3, 3]));
        // Lopsided: child 1 holds one leaf, child 2 holds 27 below it, and a lone chain hangs off it.
        let mut parents = vec![None, Some(0), Some(0)];
        for level in 0..3 {
            let first = parents.len();
            let above: Vec<usize> = if level == 0 { vec![2] } else { (first - 3usize.pow(level)..first).collect() };
            for p in above {
                parents.extend([Some(p); 3]);
            }
        }
        let last = parents.len() - 1;
        parents.extend((last..last + 5).map(Some));
        assert_subtrees_in_their_shares(&Hierarchy::from_parents(&parents).unwrap());
        // A leaf and a star of 10 stars of 10: the big share (> half a turn) is capped so the
        // subtree cannot fan out behind its centre into the leaf's share.
        let mut parents = vec![None, Some(0), Some(0)];
        parents.extend([Some(2); 10]);
        for hub in 3..13 {
            parents.extend([Some(hub); 10]);
        }
        assert_subtrees_in_their_shares(&Hierarchy::from_parents(&parents).unwrap());
    }

    #[test]
    fn a_lone_child_fans_out_ahead_instead_of_around_its_parent() {
        // Root, lone child 1, ten leaves under it. The capped share (half a turn) gives child 1 a
        // wedge of half-width π − acos(tanh 1) ≈ 140°, so the outermost leaves are 126° off the
        // forward direction: by the hyperbolic law of cosines they are ≈ 1.02 from the root (an
        // uncapped full-turn share would put them at 162°, only ≈ 0.37 away).
        let mut parents = vec![None, Some(0)];
        parents.extend([Some(1); 10]);
        let lay = layout(&Hierarchy::from_parents(&parents).unwrap());
        let nearest = (2..12).map(|v| distance(lay.base()[0], lay.base()[v])).fold(f64::INFINITY, f64::min);
        let half = PI - 1f64.tanh().acos();
        let at_child = PI - 0.9 * half; // angle at child 1 between the root and an outermost leaf
        let expected = (1f64.cosh().powi(2) - 1f64.sinh().powi(2) * at_child.cos()).acosh();
        assert!((nearest - expected).abs() < 1e-9 && expected > 1.0, "{nearest} vs {expected}");
    }

    #[test]
    fn focusing_on_a_node_puts_it_at_the_centre() {
        let tree = balanced(&[4, 3, 3, 2]);
        let lay = layout(&tree);
        for node in [0, 1, 7, 30, tree.len() - 1] {
            let shown = view(&lay, &Mobius::focus_on(lay.base()[node]));
            assert!(close(shown[node], [0.0, 0.0], 1e-12), "{node}: {:?}", shown[node]);
            assert!(shown.iter().all(|&p| inside(p)));
        }
    }

    #[test]
    fn mobius_maps_keep_points_inside_and_preserve_hyperbolic_distance() {
        let mut rng = Rng(7);
        for _ in 0..200 {
            let m = rng.mobius();
            let (p, q) = (rng.point(0.95), rng.point(0.95));
            let (mp, mq) = (m.apply(p), m.apply(q));
            assert!(inside(mp) && inside(mq));
            let (before, after) = (distance(p, q), distance(mp, mq));
            assert!((before - after).abs() <= 1e-9 * before.max(1e-3), "{before} vs {after}");
        }
    }

    #[test]
    fn composition_and_inverse_agree_with_pointwise_application() {
        let mut rng = Rng(11);
        for _ in 0..200 {
            let (f, g) = (rng.mobius(), rng.mobius());
            let z = rng.point(0.9);
            assert!(close(f.then(&g).apply(z), g.apply(f.apply(z)), 1e-12));
            assert!(close(f.inverse().apply(f.apply(z)), z, 1e-12));
            assert!(close(f.then(&f.inverse()).apply(z), z, 1e-12));
            let r = f.then(&g).rot();
            assert!((r[0].hypot(r[1]) - 1.0).abs() < 1e-15);
        }
        assert_eq!(Mobius::identity().apply([0.3, -0.2]), [0.3, -0.2]);
    }

    #[test]
    fn drag_maps_from_to_to_and_slides_along_their_geodesic() {
        let mut rng = Rng(3);
        for _ in 0..100 {
            let (from, to) = (rng.point(0.9), rng.point(0.9));
            let m = Mobius::drag(from, to);
            assert!(close(m.apply(from), to, 1e-10));
            // A third point on the geodesic through from and to stays on that geodesic.
            let line = geodesic(from, to);
            let beyond = Mobius::drag(to, from).apply(from); // one more step along the line
            let moved = m.apply(beyond);
            if let Geodesic::Arc { center, radius, .. } = line {
                let off = (moved[0] - center[0]).hypot(moved[1] - center[1]) - radius;
                assert!(off.abs() < 1e-8 * radius.max(1.0), "{off}");
            }
        }
        assert_eq!(Mobius::drag([f64::NAN, 0.0], [0.1, 0.2]), Mobius::identity());
    }

    #[test]
    fn geodesics_are_orthogonal_arcs_through_both_ends_or_diameter_segments() {
        let mut rng = Rng(5);
        let mut arcs = 0;
        for _ in 0..200 {
            let (a, b) = (rng.point(0.98), rng.point(0.98));
            let line = geodesic(a, b);
            let Geodesic::Arc { center, radius, clockwise, .. } = line else {
                continue;
            };
            arcs += 1;
            let c = C::of(center);
            // The circle passes through both ends and meets the unit circle at right angles.
            for end in [a, b] {
                assert!(((C::of(end) - c).abs() - radius).abs() < 1e-9 * radius.max(1.0));
            }
            assert!((c.norm_sqr() - radius * radius - 1.0).abs() < 1e-9 * c.norm_sqr());
            // Every polyline point lies on the hyperbolic segment: d(a, m) + d(m, b) = d(a, b).
            let pts = line.points(0.05);
            assert_eq!((pts[0], pts[pts.len() - 1]), (a, b));
            let whole = distance(a, b);
            for &m in &pts {
                assert!(inside(m));
                assert!((distance(a, m) + distance(m, b) - whole).abs() < 1e-7 * whole.max(1.0));
            }
            let (u, v) = (C::of(a) - c, C::of(b) - c);
            assert_eq!(clockwise, (u.conj() * v).im < 0.0);
        }
        assert!(arcs > 190);
        assert_eq!(geodesic([0.5, 0.5], [-0.2, -0.2]), Geodesic::Segment { from: [0.5, 0.5], to: [-0.2, -0.2] });
        assert!(matches!(geodesic([0.0, 0.0], [0.3, 0.7]), Geodesic::Segment { .. }));
        // By hand: from (0.5, 0) to (0, 0.5), c·a = 0.625 gives the centre (1.25, 1.25), r² = 2.125,
        // and the short way round that centre (from angle ≈ 239° down to ≈ 211°) is clockwise.
        let Geodesic::Arc { center, radius, clockwise, .. } = geodesic([0.5, 0.0], [0.0, 0.5]) else { panic!() };
        assert!(close(center, [1.25, 1.25], 1e-12) && (radius - 2.125f64.sqrt()).abs() < 1e-12);
        assert!(clockwise);
    }

    #[test]
    fn scale_shrinks_from_one_at_the_centre_to_zero_at_the_rim() {
        assert_eq!(scale_at([0.0, 0.0]), 1.0);
        assert!((scale_at([0.6, 0.0]) - 0.64).abs() < 1e-15);
        assert!(scale_at([0.0, 0.999_999]) < 2.1e-6);
        assert_eq!(scale_at([3.0, 0.0]), 0.0);
        assert_eq!(scale_at([f64::NAN, 0.0]), 0.0);
        assert!(distance([f64::NAN, 0.0], [0.0, 0.0]).is_nan());
        // By hand: from the centre to radius tanh(1/2) is 2·artanh(tanh(1/2)) = 1.
        assert!((distance([0.0, 0.0], [0.0, 0.5f64.tanh()]) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn view_from_matches_view_and_stays_accurate_deep_in_a_chain() {
        let tree = balanced(&[3, 3, 2, 2]);
        let lay = layout(&tree);
        let t = Mobius::drag([0.1, 0.0], [0.0, 0.3]);
        for anchor in [0, 2, 9, tree.len() - 1] {
            let direct = view(&lay, &Mobius::focus_on(lay.base()[anchor]).then(&t));
            let rebuilt = view_from(&lay, anchor, &t).unwrap();
            assert!(direct.iter().zip(&rebuilt).all(|(&p, &q)| close(p, q, 1e-9)));
        }
        // 5,000 levels down, base positions are pinned to the rim but a view from there is exact.
        let lay = layout(&chain(10_000));
        assert!((lay.base()[5_000][0].hypot(lay.base()[5_000][1]) - MAX_RADIUS).abs() < 1e-15);
        let shown = view_from(&lay, 5_000, &Mobius::identity()).unwrap();
        assert_eq!(shown[5_000], [0.0, 0.0]);
        for v in 4_995..5_005 {
            let d = distance(shown[v], shown[v + 1]);
            assert!((d - 1.0).abs() < 1e-9, "{v}: {d}");
        }
        assert_eq!(view_from(&lay, 10_000, &t), Err(HyperbolicError::AnchorOutOfRange { anchor: 10_000, len: 10_000 }));
    }

    #[test]
    fn bad_spacing_is_refused_with_the_value() {
        let tree = chain(3);
        for spacing in [0.0, -1.0, f64::NAN, f64::INFINITY, 25.0] {
            let err = HyperbolicLayout::new(&tree, &HyperbolicOptions { spacing, weight_by_leaves: true }).unwrap_err();
            assert!(err.to_string().contains(&spacing.to_string()), "{err}");
            assert!(matches!(err, HyperbolicError::BadSpacing(_)));
        }
    }

    #[test]
    fn layout_is_deterministic_and_leaf_weighting_widens_big_subtrees() {
        // Root with a leaf child (1) and a child (2) holding 9 leaves.
        let mut parents = vec![None, Some(0), Some(0)];
        parents.extend(std::iter::repeat_n(Some(2), 9));
        let tree = Hierarchy::from_parents(&parents).unwrap();
        let by_leaves = layout(&tree);
        assert_eq!(by_leaves, layout(&tree));
        // Leaf shares 1:9 of the full turn: child 1 on the bisector of [0, 0.2π], child 2 of [0.2π, 2π].
        let angle = |p: [f64; 2]| p[1].atan2(p[0]).rem_euclid(2.0 * PI);
        assert!((angle(by_leaves.base()[1]) - 0.1 * PI).abs() < 1e-12);
        assert!((angle(by_leaves.base()[2]) - 1.1 * PI).abs() < 1e-12);
        // Child counts 1:9 give the same split here.
        let by_kids =
            HyperbolicLayout::new(&tree, &HyperbolicOptions { spacing: 1.0, weight_by_leaves: false }).unwrap();
        assert!((angle(by_kids.base()[1]) - 0.1 * PI).abs() < 1e-12);
    }
}
