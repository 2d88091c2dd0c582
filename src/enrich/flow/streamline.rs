//! Streamlines and pathlines: curves tangent to a [`VectorField`], traced from a seed.
//!
//! A streamline solves `dp/ds = v(p) / |v(p)|` (arc length `s`, [`Mode::Normalized`]) or
//! `dp/dt = v(p)` ([`Mode::Velocity`]) with one of the one-step methods of
//! [`super::integrate`], forward and/or backward from the seed. Each half stops at the first of:
//!
//! - the domain boundary: a step (or one of its stages) leaving the domain is retried with halved
//!   steps, and the last one is clipped to the boundary rectangle ([`StopReason::Boundary`]);
//! - a hole (cell with a NaN corner) that halved steps cannot avoid ([`StopReason::Hole`]);
//! - stagnation: speed at most `stagnation × max_speed` of the field ([`StopReason::Stagnation`]);
//! - `max_length` of arc length or `max_steps` steps (caps, so tracing never hangs);
//! - closing on itself: after moving farther than `2 × closure` from the seed, the curve passes
//!   within `closure` of it; the seed is appended to close the loop ([`StopReason::Closed`]);
//! - a caller's veto ([`trace_with`], used by evenly spaced seeding; [`StopReason::TooClose`]).
//!
//! Pathlines ([`pathline`]) integrate the unsteady velocity in time and also stop at the end of
//! the field's time axis ([`StopReason::TimeRange`]).

use super::budget::StepBudget;
use super::field::VectorField;
use super::integrate::{Integrator, Mode, StepControl, step};

/// Why one half of a streamline stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// The seed is outside the domain (the streamline is empty).
    OutsideDomain,
    /// The curve reached the domain boundary (its last point is on it).
    Boundary,
    /// The curve ran into a hole (cell with a missing corner), or the seed is in one.
    Hole,
    /// The speed fell to the stagnation threshold.
    Stagnation,
    /// The arc length (or time, in velocity mode) reached `max_length`.
    MaxLength,
    /// `max_steps` steps were taken.
    MaxSteps,
    /// The curve returned to its seed: a closed orbit.
    Closed,
    /// The caller's acceptance test refused the next point.
    TooClose,
    /// A pathline reached the end of the field's time axis.
    TimeRange,
    /// This half was not traced (direction not requested, or the other half closed the loop).
    NotTraced,
}

/// Which way(s) to trace from the seed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Along the flow only.
    Forward,
    /// Against the flow only.
    Backward,
    /// Both, joined at the seed.
    Both,
}

/// Tracing parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StreamlineOptions {
    /// One-step method.
    pub integrator: Integrator,
    /// Direction field (arc length) or true velocity (time).
    pub mode: Mode,
    /// Step magnitude (initial step for [`Integrator::Rk45`]); a non-positive or NaN step means
    /// half the smallest cell.
    pub step: f64,
    /// Error control for [`Integrator::Rk45`].
    pub control: StepControl,
    /// Largest arc length (normalized mode) or duration (velocity mode) per half.
    pub max_length: f64,
    /// Largest number of steps per half.
    pub max_steps: usize,
    /// Stagnation threshold as a fraction of the field's maximum speed.
    pub stagnation: f64,
    /// Closing distance for closed orbits (0 disables closure detection).
    pub closure: f64,
    /// Which way(s) to trace.
    pub direction: Direction,
}

impl StreamlineOptions {
    /// Defaults scaled to the field: RK4 on the direction field, step 0.5 × smallest cell,
    /// length up to 4 × the domain's perimeter, 100 000 steps, stagnation 1e-6, closure 0.25 step.
    pub fn for_field(field: &VectorField) -> StreamlineOptions {
        let [x0, x1, y0, y1] = field.bounds();
        let h = 0.5 * field.min_cell();
        StreamlineOptions {
            integrator: Integrator::Rk4,
            mode: Mode::Normalized,
            step: h,
            control: StepControl::new(1e-3 * h, 1e-3 * h, 4.0 * h),
            max_length: 8.0 * ((x1 - x0) + (y1 - y0)),
            max_steps: 100_000,
            stagnation: 1e-6,
            closure: 0.25 * h,
            direction: Direction::Both,
        }
    }
}

/// A traced curve: points from the backward end to the forward end.
#[derive(Debug, Clone, PartialEq)]
pub struct Streamline {
    /// The polyline; empty when the seed is outside the domain or in a hole.
    pub points: Vec<[f64; 2]>,
    /// Integration parameter at each point: signed arc length (normalized mode) or time
    /// (velocity mode), 0 (or the start time) at the seed.
    pub params: Vec<f64>,
    /// Index of the seed in `points` (0 when empty).
    pub seed_index: usize,
    /// Why the backward half stopped.
    pub backward: StopReason,
    /// Why the forward half stopped.
    pub forward: StopReason,
}

impl Streamline {
    /// Total polyline length.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| dist(w[0], w[1])).sum()
    }

    /// Whether the curve closed on itself.
    pub fn is_closed(&self) -> bool {
        self.forward == StopReason::Closed || self.backward == StopReason::Closed
    }
}

/// Traces the streamline through `seed`.
pub fn trace(field: &VectorField, seed: [f64; 2], options: &StreamlineOptions) -> Streamline {
    trace_with(field, seed, options, &mut |_, _| true)
}

/// Traces the streamline through `seed`, taking every step from `budget` (a spent budget stops
/// the curve with [`StopReason::TooClose`]; check [`StepBudget::exhausted`]).
pub fn trace_within(
    field: &VectorField,
    seed: [f64; 2],
    options: &StreamlineOptions,
    budget: &StepBudget,
) -> Streamline {
    trace_with(field, seed, options, &mut |_, _| budget.step())
}

/// Traces the streamline through `seed`, asking `accept(point, param)` before adding each new
/// point; a refusal stops that half with [`StopReason::TooClose`]. The backward half is traced first.
pub fn trace_with(
    field: &VectorField,
    seed: [f64; 2],
    options: &StreamlineOptions,
    accept: &mut dyn FnMut([f64; 2], f64) -> bool,
) -> Streamline {
    let tracer = Tracer { field, options, time_dependent: false, closure: options.closure };
    tracer.run(seed, 0.0, accept)
}

/// Traces the pathline of a particle released at `seed` at time `t0` through an unsteady field
/// (velocity mode; `options.mode` is ignored, `step` and `max_length` are durations).
/// A steady field gives its streamline parametrised by time. Closure is not detected. Every step
/// is taken from `budget`; a spent budget ends the trace early.
pub fn pathline(
    field: &VectorField,
    seed: [f64; 2],
    t0: f64,
    options: &StreamlineOptions,
    budget: &StepBudget,
) -> Streamline {
    let options = StreamlineOptions { mode: Mode::Velocity, ..*options };
    let tracer = Tracer { field, options: &options, time_dependent: !field.ts().is_empty(), closure: 0.0 };
    tracer.run(seed, t0, &mut |_, _| budget.step())
}

/// One half of a curve: points after the seed, their parameters, and why it stopped.
struct Half {
    points: Vec<[f64; 2]>,
    params: Vec<f64>,
    reason: StopReason,
}

/// Most halvings of a failed step before clipping to the boundary or giving up.
const MAX_HALVINGS: usize = 10;

/// Shared state of one tracing call.
struct Tracer<'a> {
    field: &'a VectorField,
    options: &'a StreamlineOptions,
    time_dependent: bool,
    closure: f64,
}

impl Tracer<'_> {
    fn sample(&self, p: [f64; 2], t: f64) -> Option<[f64; 2]> {
        if self.time_dependent { self.field.velocity_at(p[0], p[1], t) } else { self.field.velocity(p[0], p[1]) }
    }

    /// Why sampling failed at `(p, t)`.
    fn failure(&self, p: [f64; 2], t: f64) -> StopReason {
        let ts = self.field.ts();
        if !self.field.contains(p[0], p[1]) {
            StopReason::Boundary
        } else if self.time_dependent && (ts.first().is_some_and(|&a| t < a) || ts.last().is_some_and(|&b| t > b)) {
            StopReason::TimeRange
        } else {
            StopReason::Hole
        }
    }

    fn run(&self, seed: [f64; 2], t0: f64, accept: &mut dyn FnMut([f64; 2], f64) -> bool) -> Streamline {
        let empty = |reason| Streamline {
            points: Vec::new(),
            params: Vec::new(),
            seed_index: 0,
            backward: reason,
            forward: reason,
        };
        if !self.field.contains(seed[0], seed[1]) {
            return empty(StopReason::OutsideDomain);
        }
        if self.sample(seed, t0).is_none() {
            return empty(self.failure(seed, t0));
        }
        let dir = self.options.direction;
        let not_traced = || Half { points: Vec::new(), params: Vec::new(), reason: StopReason::NotTraced };
        let mut forward =
            if dir == Direction::Backward { not_traced() } else { self.half(seed, t0, 1.0, &mut *accept) };
        let mut backward = if dir == Direction::Forward || forward.reason == StopReason::Closed {
            not_traced()
        } else {
            self.half(seed, t0, -1.0, &mut *accept)
        };
        if backward.reason == StopReason::Closed && dir == Direction::Both {
            forward = not_traced();
        }
        let seed_index = backward.points.len();
        backward.points.reverse();
        backward.params.reverse();
        let mut points = backward.points;
        let mut params = backward.params;
        points.push(seed);
        params.push(t0);
        points.extend(forward.points);
        params.extend(forward.params);
        Streamline { points, params, seed_index, backward: backward.reason, forward: forward.reason }
    }

    /// Traces one half in direction `sign` (+1 forward, −1 backward).
    fn half(&self, seed: [f64; 2], t0: f64, sign: f64, accept: &mut dyn FnMut([f64; 2], f64) -> bool) -> Half {
        let o = self.options;
        let threshold = o.stagnation.max(0.0) * self.field.max_speed();
        let rhs = |p: [f64; 2], t: f64| self.sample(p, t).and_then(|v| o.mode.apply(v));
        let mut out = Half { points: Vec::new(), params: Vec::new(), reason: StopReason::MaxSteps };
        let (mut p, mut tau, mut length) = (seed, t0, 0.0);
        let nominal = if o.step.is_finite() && o.step > 0.0 { o.step } else { 0.5 * self.field.min_cell() };
        let mut h = sign * nominal;
        let mut left_seed = false;
        for _ in 0..o.max_steps {
            let Some(v) = self.sample(p, tau) else {
                out.reason = self.failure(p, tau);
                return out;
            };
            if v[0].hypot(v[1]) <= threshold {
                out.reason = StopReason::Stagnation;
                return out;
            }
            if length >= o.max_length {
                out.reason = StopReason::MaxLength;
                return out;
            }
            if let Some(remaining) = self.time_left(tau, sign) {
                if remaining * sign <= 0.0 {
                    out.reason = StopReason::TimeRange;
                    return out;
                }
                if h.abs() > remaining.abs() {
                    h = remaining;
                }
            }
            let (q, taken, next, clipped) = match self.step_or_clip(&rhs, p, tau, h) {
                Ok(s) => s,
                Err(reason) => {
                    out.reason = reason;
                    return out;
                }
            };
            if !accept(q, if o.mode == Mode::Normalized { sign * (length + dist(p, q)) } else { tau + taken }) {
                out.reason = StopReason::TooClose;
                return out;
            }
            length += dist(p, q);
            let closes = left_seed && self.closure > 0.0 && segment_distance(seed, p, q) < self.closure;
            left_seed |= dist(q, seed) > 2.0 * self.closure;
            tau += taken;
            p = if closes { seed } else { q };
            out.points.push(p);
            out.params.push(if o.mode == Mode::Normalized { sign * length } else { tau });
            if closes {
                out.reason = StopReason::Closed;
                return out;
            }
            if clipped {
                out.reason = StopReason::Boundary;
                return out;
            }
            h = if o.integrator == Integrator::Rk45 { next } else { sign * nominal };
        }
        out
    }

    /// The signed time left before the end of the time axis in direction `sign`, for pathlines.
    fn time_left(&self, tau: f64, sign: f64) -> Option<f64> {
        if !self.time_dependent {
            return None;
        }
        let ts = self.field.ts();
        let end = if sign > 0.0 { ts.last()? } else { ts.first()? };
        Some(end - tau)
    }

    /// One step from `p`; on failure retries with halved steps, then clips an Euler step to the
    /// boundary. Returns the new point, the parameter advance, the next step and whether the
    /// point was clipped to the boundary.
    #[allow(clippy::type_complexity)]
    fn step_or_clip<F>(&self, rhs: &F, p: [f64; 2], tau: f64, h: f64) -> Result<([f64; 2], f64, f64, bool), StopReason>
    where
        F: Fn([f64; 2], f64) -> Option<[f64; 2]>,
    {
        let o = self.options;
        let mut trial = h;
        for _ in 0..=MAX_HALVINGS {
            if let Some(s) = step(rhs, o.integrator, p, tau, trial, &o.control) {
                if self.field.contains(s.point[0], s.point[1]) {
                    let next = if trial == h { s.next } else { h };
                    return Ok((s.point, s.taken, next, false));
                }
                let q = clip_to_box(self.field.bounds(), p, s.point);
                let full = dist(p, s.point);
                let fraction = if full > 0.0 { dist(p, q) / full } else { 0.0 };
                return Ok((q, s.taken * fraction, s.next, true));
            }
            trial *= 0.5;
        }
        // Every halving failed: if the boundary is within one step along the current
        // direction, end exactly on it; otherwise something inside (a hole) blocks the way.
        let d = rhs(p, tau).ok_or(StopReason::Hole)?;
        let far = [p[0] + h * d[0], p[1] + h * d[1]];
        if self.field.contains(far[0], far[1]) {
            return Err(self.failure(far, tau + h));
        }
        let q = clip_to_box(self.field.bounds(), p, far);
        Ok((q, h, h, true))
    }
}

/// The point where the segment from `p` (inside) to `q` leaves the rectangle `[x0, x1, y0, y1]`.
pub(crate) fn clip_to_box(b: [f64; 4], p: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    let mut lambda = 1.0f64;
    for (axis, lo, hi) in [(0, b[0], b[1]), (1, b[2], b[3])] {
        let d = q[axis] - p[axis];
        if q[axis] > hi && d > 0.0 {
            lambda = lambda.min((hi - p[axis]) / d);
        } else if q[axis] < lo && d < 0.0 {
            lambda = lambda.min((lo - p[axis]) / d);
        }
    }
    let lambda = lambda.clamp(0.0, 1.0);
    let x = (p[0] + lambda * (q[0] - p[0])).clamp(b[0], b[1]);
    let y = (p[1] + lambda * (q[1] - p[1])).clamp(b[2], b[3]);
    [x, y]
}

/// Euclidean distance.
#[inline]
pub(crate) fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    let d = (dx * dx + dy * dy).sqrt();
    // `hypot` is slow; it is only needed when the plain form over- or underflows.
    if d.is_finite() && d > 1e-150 { d } else { dx.hypot(dy) }
}

/// Distance from `c` to the segment `[a, b]`.
fn segment_distance(c: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 { (((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
    dist(c, [a[0] + t * dx, a[1] + t * dy])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(n: usize, a: f64, b: f64) -> Vec<f64> {
        (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect()
    }

    fn rotation() -> VectorField {
        VectorField::from_fn(axis(41, -2.0, 2.0), axis(41, -2.0, 2.0), |x, y| [-y, x]).unwrap()
    }

    #[test]
    fn rotation_closes_into_the_unit_circle() {
        let field = rotation();
        let mut o = StreamlineOptions::for_field(&field);
        o.step = 0.01;
        o.closure = 0.005;
        let line = trace(&field, [1.0, 0.0], &o);
        assert_eq!(line.forward, StopReason::Closed);
        assert_eq!(line.backward, StopReason::NotTraced);
        let radial = line.points.iter().map(|p| (p[0].hypot(p[1]) - 1.0).abs()).fold(0.0, f64::max);
        assert!(radial < 1e-3, "max radial error {radial}");
        assert!((line.length() - 2.0 * std::f64::consts::PI).abs() < 0.02, "length {}", line.length());
        // Counter-clockwise: the first step goes up.
        assert!(line.points[1][1] > 0.0);
    }

    #[test]
    fn lines_stay_inside_and_end_on_the_boundary() {
        // A saddle u = x, v = −y: every streamline leaves through the left or right side.
        let field = VectorField::from_fn(axis(21, -1.0, 1.0), axis(21, -1.0, 1.0), |x, y| [x, -y]).unwrap();
        for integrator in [Integrator::Euler, Integrator::Rk2, Integrator::Rk4, Integrator::Rk45] {
            let mut o = StreamlineOptions::for_field(&field);
            o.integrator = integrator;
            for seed in [[0.3, 0.2], [-0.5, 0.9], [0.99, -0.99]] {
                let line = trace(&field, seed, &o);
                assert!(line.points.iter().all(|p| field.contains(p[0], p[1]) && p[0].is_finite()));
                assert_eq!(line.forward, StopReason::Boundary, "{integrator:?} from {seed:?}");
                assert_eq!(line.backward, StopReason::Boundary, "{integrator:?} from {seed:?}");
                let end = line.points[line.points.len() - 1];
                assert!((end[0].abs() - 1.0).abs() < 1e-12, "forward end {end:?} not on x = ±1");
                let start = line.points[0];
                assert!((start[1].abs() - 1.0).abs() < 1e-12, "backward end {start:?} not on y = ±1");
                // The invariant x·y is conserved along the hyperbola.
                let c = seed[0] * seed[1];
                let drift = line.points.iter().map(|p| (p[0] * p[1] - c).abs()).fold(0.0, f64::max);
                assert!(drift < 2e-2, "{integrator:?}: x·y drifts by {drift}");
            }
        }
    }

    #[test]
    fn degenerate_seeds_and_fields() {
        let zero = VectorField::from_fn(axis(5, 0.0, 1.0), axis(5, 0.0, 1.0), |_, _| [0.0, 0.0]).unwrap();
        let o = StreamlineOptions::for_field(&zero);
        let line = trace(&zero, [0.5, 0.5], &o);
        assert_eq!(
            (line.points.clone(), line.forward, line.backward),
            (vec![[0.5, 0.5]], StopReason::Stagnation, StopReason::Stagnation)
        );
        let line = trace(&zero, [1.5, 0.5], &o);
        assert!(line.points.is_empty());
        assert_eq!(line.forward, StopReason::OutsideDomain);
        let line = trace(&zero, [f64::NAN, 0.5], &o);
        assert_eq!(line.backward, StopReason::OutsideDomain);
    }

    #[test]
    fn holes_and_caps_stop_the_line() {
        // Uniform flow to +x with a hole in the column of cells 6..7.
        let xs = axis(11, 0.0, 1.0);
        let mut u = vec![1.0; 121];
        for j in 0..11 {
            u[j * 11 + 7] = f64::NAN;
        }
        let field = VectorField::new(xs.clone(), xs, u, vec![0.0; 121]).unwrap();
        let mut o = StreamlineOptions::for_field(&field);
        o.direction = Direction::Forward;
        let line = trace(&field, [0.05, 0.5], &o);
        assert_eq!(line.forward, StopReason::Hole);
        let end = line.points[line.points.len() - 1];
        assert!(end[0] <= 0.6 + 1e-9 && end[0] > 0.55, "stopped at {end:?}");
        o.max_steps = 3;
        assert_eq!(trace(&field, [0.05, 0.5], &o).forward, StopReason::MaxSteps);
        o.max_steps = 1000;
        o.max_length = 0.2;
        let capped = trace(&field, [0.05, 0.5], &o);
        assert_eq!(capped.forward, StopReason::MaxLength);
        assert!((capped.length() - 0.2).abs() < o.step + 1e-12);
        // A huge cap on a closed orbit with closure detection off still ends.
        let rot = rotation();
        let mut o = StreamlineOptions::for_field(&rot);
        o.closure = 0.0;
        o.max_steps = 5000;
        o.max_length = f64::INFINITY;
        assert_eq!(trace(&rot, [1.0, 0.0], &o).forward, StopReason::MaxSteps);
    }

    #[test]
    fn pathlines_follow_time_and_stop_at_its_end() {
        let xs = axis(11, 0.0, 10.0);
        let frames = vec![(vec![1.0; 121], vec![0.0; 121]), (vec![1.0; 121], vec![2.0; 121])];
        let field = VectorField::unsteady(xs.clone(), xs, vec![0.0, 2.0], frames).unwrap();
        let mut o = StreamlineOptions::for_field(&field);
        o.step = 0.1;
        o.direction = Direction::Forward;
        let line = pathline(&field, [1.0, 1.0], 0.0, &o, &StepBudget::default());
        assert_eq!(line.forward, StopReason::TimeRange);
        // x = 1 + t, y = 1 + t²/2 at t = 2.
        let end = line.points[line.points.len() - 1];
        assert!((end[0] - 3.0).abs() < 1e-9 && (end[1] - 3.0).abs() < 1e-9, "{end:?}");
        assert!((line.params[line.params.len() - 1] - 2.0).abs() < 1e-9);
    }
}
