//! Navigating a hyperbolic tree: dragging moves the focus with the pointer (a hyperbolic
//! translation taking the point under the pointer to its new place), and focusing on a node
//! slides it to the centre along the geodesic through it, eased over a short animation.

use crate::layout::hyperbolic::Mobius;

/// Seconds a click-to-focus takes.
pub const FOCUS_SECONDS: f64 = 0.35;

/// Where a disk point may lie at most (points further out are pulled in).
const RIM: f64 = 0.999_999;

/// The view of a hyperbolic tree after its spec focus, and an animation in progress.
#[derive(Clone, Debug, PartialEq)]
pub struct FocusView {
    /// The map applied after the spec focus is centred.
    pub transform: Mobius,
    animation: Option<Animation>,
}

/// A click-to-focus on its way.
#[derive(Clone, Debug, PartialEq)]
struct Animation {
    /// The view when it started.
    start: Mobius,
    /// Where the node was in that view.
    from: [f64; 2],
    /// Seconds run so far.
    elapsed: f64,
    /// Seconds it takes.
    duration: f64,
}

impl Default for FocusView {
    fn default() -> Self {
        FocusView { transform: Mobius::identity(), animation: None }
    }
}

impl FocusView {
    /// Move the view so that the disk point `from` goes to `to` (stops any animation).
    pub fn drag(&mut self, from: [f64; 2], to: [f64; 2]) {
        self.animation = None;
        self.transform = self.transform.then(&Mobius::drag(pull_in(from), pull_in(to)));
    }

    /// Start sliding the node now at disk point `at` to the centre over `duration` seconds
    /// (at once when `duration` is not positive).
    pub fn focus(&mut self, at: [f64; 2], duration: f64) {
        let at = pull_in(at);
        let start = self.transform;
        self.animation = Some(Animation { start, from: at, elapsed: 0.0, duration });
        if !(duration.is_finite() && duration > 0.0) {
            self.advance(0.0);
        }
    }

    /// Advance the animation by `dt` seconds; returns whether it is still running.
    pub fn advance(&mut self, dt: f64) -> bool {
        let Some(a) = &mut self.animation else { return false };
        a.elapsed += if dt.is_finite() { dt.max(0.0) } else { 0.0 };
        let t = if a.duration > 0.0 { (a.elapsed / a.duration).min(1.0) } else { 1.0 };
        let (start, from) = (a.start, a.from);
        self.transform = start.then(&Mobius::drag(from, along(from, smoothstep(t))));
        if t >= 1.0 {
            self.animation = None;
        }
        self.animation.is_some()
    }

    /// Whether a focus animation is running.
    pub fn is_animating(&self) -> bool {
        self.animation.is_some()
    }

    /// Back to the spec's focus.
    pub fn reset(&mut self) {
        *self = FocusView::default();
    }
}

/// The point a fraction `t` of the hyperbolic way from `p` to the centre, on the diameter
/// through `p`.
pub fn along(p: [f64; 2], t: f64) -> [f64; 2] {
    let r = p[0].hypot(p[1]);
    if r <= 0.0 || !r.is_finite() {
        return [0.0, 0.0];
    }
    let d = r.min(RIM).atanh() * (1.0 - t.clamp(0.0, 1.0));
    let k = d.tanh() / r;
    [p[0] * k, p[1] * k]
}

/// Ease in and out.
fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// A finite disk point (non-finite becomes the centre, the rim is pulled in).
fn pull_in(z: [f64; 2]) -> [f64; 2] {
    if !(z[0].is_finite() && z[1].is_finite()) {
        return [0.0, 0.0];
    }
    let r = z[0].hypot(z[1]);
    if r > RIM { [z[0] * RIM / r, z[1] * RIM / r] } else { z }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::hyperbolic::distance;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
    }

    #[test]
    fn focusing_slides_the_node_to_the_centre_along_its_diameter() {
        let mut view = FocusView::default();
        let node = [0.6, -0.3];
        let other = [-0.2, 0.5];
        view.focus(node, 1.0);
        let mut last = distance(node, [0.0, 0.0]);
        for _ in 0..9 {
            assert!(view.advance(0.1));
            let now = view.transform.apply(node);
            let d = distance(now, [0.0, 0.0]);
            assert!(d < last, "the node moves towards the centre: {d} then {last}");
            // It stays on the diameter through where it started.
            assert!((now[0] * node[1] - now[1] * node[0]).abs() < 1e-9);
            last = d;
        }
        assert!(!view.advance(0.5), "the animation ends");
        assert!(close(view.transform.apply(node), [0.0, 0.0]));
        // Other nodes move by the same isometry: distances between nodes are kept.
        let moved = view.transform.apply(other);
        assert!((distance(moved, [0.0, 0.0]) - distance(other, node)).abs() < 1e-9);
    }

    #[test]
    fn dragging_moves_the_point_under_the_pointer_with_it() {
        let mut view = FocusView::default();
        view.drag([0.1, 0.1], [0.4, -0.2]);
        assert!(close(view.transform.apply([0.1, 0.1]), [0.4, -0.2]));
        view.drag([0.4, -0.2], [0.0, 0.0]);
        assert!(close(view.transform.apply([0.1, 0.1]), [0.0, 0.0]));
        view.focus([0.5, 0.0], 0.0);
        assert!(!view.is_animating());
        view.reset();
        assert_eq!(view, FocusView::default());
        assert_eq!(along([0.0, 0.0], 0.5), [0.0, 0.0]);
    }
}
