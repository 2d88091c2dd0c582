//! One integration step of `dp/dτ = f(p, τ)` for tracing curves through a vector field.
//!
//! Fixed-step methods: forward Euler (order 1), the explicit midpoint rule RK2 (order 2) and the
//! classical fourth-order Runge–Kutta RK4. The adaptive method is the embedded 5(4) pair of
//! Dormand & Prince (1980): the difference between its fifth- and fourth-order solutions estimates
//! the local error, the step is accepted when that estimate is at most `tolerance`, and the next
//! step is scaled by `0.9 (tolerance / error)^(1/5)` (between ×0.2 and ×5, within
//! `[min_step, max_step]`).
//!
//! The right-hand side is any closure returning `None` where it cannot be evaluated (outside the
//! domain, in a hole); a step touching such a point fails. [`Mode`] turns a velocity sample into
//! the right-hand side: the unit direction (streamlines parametrised by arc length, so equal steps
//! give evenly spaced points) or the true velocity (pathlines parametrised by time). Steps may be
//! negative to integrate backward.

/// Which one-step method to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integrator {
    /// Forward Euler, order 1.
    Euler,
    /// Explicit midpoint rule, order 2.
    Rk2,
    /// Classical Runge–Kutta, order 4.
    Rk4,
    /// Adaptive Dormand–Prince 5(4) with error control.
    Rk45,
}

/// How a velocity sample becomes the right-hand side of the ODE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Unit direction `v / |v|`: the parameter is arc length (streamlines). Zero or non-finite
    /// velocity cannot be normalised and counts as a failed evaluation.
    Normalized,
    /// The velocity itself: the parameter is time (pathlines).
    Velocity,
}

impl Mode {
    /// Applies the mode to a velocity sample.
    #[inline]
    pub fn apply(self, v: [f64; 2]) -> Option<[f64; 2]> {
        match self {
            Mode::Velocity => (v[0].is_finite() && v[1].is_finite()).then_some(v),
            Mode::Normalized => {
                let n = (v[0] * v[0] + v[1] * v[1]).sqrt();
                // `hypot` is slow; use it only when the plain norm over- or underflows.
                let n = if n.is_finite() && n > 1e-150 { n } else { v[0].hypot(v[1]) };
                (n > 0.0 && n.is_finite()).then(|| [v[0] / n, v[1] / n])
            }
        }
    }
}

/// Error control for [`Integrator::Rk45`]; the fixed-step methods ignore it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepControl {
    /// Largest accepted local error estimate (Euclidean norm, in domain units).
    pub tolerance: f64,
    /// Smallest step magnitude; a step this small is accepted whatever its error.
    pub min_step: f64,
    /// Largest step magnitude.
    pub max_step: f64,
}

impl StepControl {
    /// Control with the given tolerance and step bounds (magnitudes; NaN or inverted bounds are
    /// repaired to `min_step ≤ max_step`).
    pub fn new(tolerance: f64, min_step: f64, max_step: f64) -> StepControl {
        let min_step = if min_step.is_finite() && min_step > 0.0 { min_step } else { f64::MIN_POSITIVE };
        let max_step = if max_step.is_finite() && max_step >= min_step { max_step } else { min_step.max(1.0) };
        let tolerance = if tolerance.is_finite() && tolerance > 0.0 { tolerance } else { 1e-6 };
        StepControl { tolerance, min_step, max_step }
    }
}

/// A completed step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The new point.
    pub point: [f64; 2],
    /// The (signed) step actually taken.
    pub taken: f64,
    /// The (signed) step to try next: the same as `taken` for fixed-step methods.
    pub next: f64,
    /// Local error estimate (0 for fixed-step methods).
    pub error: f64,
}

/// Most trials of one adaptive step before it gives up shrinking.
const MAX_TRIALS: usize = 64;

/// Takes one step of size `h` (negative for backward) from `p` at parameter `tau`.
/// `None` when the right-hand side fails at any stage.
pub fn step<F>(f: &F, integrator: Integrator, p: [f64; 2], tau: f64, h: f64, control: &StepControl) -> Option<Step>
where
    F: Fn([f64; 2], f64) -> Option<[f64; 2]>,
{
    let fixed = |point: [f64; 2]| Some(Step { point, taken: h, next: h, error: 0.0 });
    match integrator {
        Integrator::Euler => fixed(euler(f, p, tau, h)?),
        Integrator::Rk2 => fixed(rk2(f, p, tau, h)?),
        Integrator::Rk4 => fixed(rk4(f, p, tau, h)?),
        Integrator::Rk45 => adaptive(f, p, tau, h, control),
    }
}

/// `p + h k`.
#[inline]
fn axpy(p: [f64; 2], h: f64, k: [f64; 2]) -> [f64; 2] {
    [p[0] + h * k[0], p[1] + h * k[1]]
}

/// Forward Euler step.
#[inline]
pub fn euler<F>(f: &F, p: [f64; 2], tau: f64, h: f64) -> Option<[f64; 2]>
where
    F: Fn([f64; 2], f64) -> Option<[f64; 2]>,
{
    Some(axpy(p, h, f(p, tau)?))
}

/// Explicit midpoint step.
#[inline]
pub fn rk2<F>(f: &F, p: [f64; 2], tau: f64, h: f64) -> Option<[f64; 2]>
where
    F: Fn([f64; 2], f64) -> Option<[f64; 2]>,
{
    let k1 = f(p, tau)?;
    let k2 = f(axpy(p, 0.5 * h, k1), tau + 0.5 * h)?;
    Some(axpy(p, h, k2))
}

/// Classical fourth-order Runge–Kutta step.
#[inline]
pub fn rk4<F>(f: &F, p: [f64; 2], tau: f64, h: f64) -> Option<[f64; 2]>
where
    F: Fn([f64; 2], f64) -> Option<[f64; 2]>,
{
    let k1 = f(p, tau)?;
    let k2 = f(axpy(p, 0.5 * h, k1), tau + 0.5 * h)?;
    let k3 = f(axpy(p, 0.5 * h, k2), tau + 0.5 * h)?;
    let k4 = f(axpy(p, h, k3), tau + h)?;
    let d = |c: usize| (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]) / 6.0;
    Some(axpy(p, h, [d(0), d(1)]))
}

/// Dormand–Prince tableau: nodes `c`, stage weights `a` (lower triangle, row `i` has `i` entries).
const DP_C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const DP_A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
    [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
    [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
];
/// Fifth-order weights (equal to the last row of `DP_A`).
const DP_B5: [f64; 7] = [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0];
/// Embedded fourth-order weights.
const DP_B4: [f64; 7] =
    [5179.0 / 57600.0, 0.0, 7571.0 / 16695.0, 393.0 / 640.0, -92097.0 / 339200.0, 187.0 / 2100.0, 1.0 / 40.0];

/// One Dormand–Prince trial: the fifth-order point and the local error estimate.
fn dopri_trial<F>(f: &F, p: [f64; 2], tau: f64, h: f64) -> Option<([f64; 2], f64)>
where
    F: Fn([f64; 2], f64) -> Option<[f64; 2]>,
{
    let mut k = [[0.0; 2]; 7];
    for stage in 0..7 {
        let mut q = p;
        for (a, kk) in DP_A[stage].iter().zip(&k).take(stage) {
            q = axpy(q, h * a, *kk);
        }
        k[stage] = f(q, tau + DP_C[stage] * h)?;
    }
    let (mut hi, mut err) = (p, [0.0; 2]);
    for (s, kk) in k.iter().enumerate() {
        hi = axpy(hi, h * DP_B5[s], *kk);
        err = axpy(err, h * (DP_B5[s] - DP_B4[s]), *kk);
    }
    Some((hi, err[0].hypot(err[1])))
}

/// Adaptive Dormand–Prince step: shrinks until the error is within tolerance (or the step reaches
/// `min_step`), then proposes the next step.
fn adaptive<F>(f: &F, p: [f64; 2], tau: f64, h: f64, control: &StepControl) -> Option<Step>
where
    F: Fn([f64; 2], f64) -> Option<[f64; 2]>,
{
    let sign = if h < 0.0 { -1.0 } else { 1.0 };
    let clamp = |m: f64| sign * m.clamp(control.min_step, control.max_step);
    let mut h = clamp(h.abs());
    for _ in 0..MAX_TRIALS {
        let (point, error) = dopri_trial(f, p, tau, h)?;
        let at_min = h.abs() <= control.min_step;
        let factor = if !error.is_finite() {
            0.2
        } else if error > 0.0 {
            (0.9 * (control.tolerance / error).powf(0.2)).clamp(0.2, 5.0)
        } else {
            5.0
        };
        if error <= control.tolerance || at_min {
            return Some(Step { point, taken: h, next: clamp(h.abs() * factor), error });
        }
        h = clamp(h.abs() * factor.min(0.9));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rotation u = −y, v = x: the exact solution from (1, 0) is (cos τ, sin τ).
    fn rotation(p: [f64; 2], _: f64) -> Option<[f64; 2]> {
        Some([-p[1], p[0]])
    }

    /// Global error at τ = 1 after `n` fixed steps from (1, 0).
    fn global_error(integrator: Integrator, n: usize) -> f64 {
        let control = StepControl::new(1e-6, 1e-9, 1.0);
        let h = 1.0 / n as f64;
        let mut p = [1.0, 0.0];
        for k in 0..n {
            p = step(&rotation, integrator, p, k as f64 * h, h, &control).unwrap().point;
        }
        (p[0] - 1f64.cos()).hypot(p[1] - 1f64.sin())
    }

    #[test]
    fn fixed_step_methods_show_their_orders() {
        for (integrator, n, order) in
            [(Integrator::Euler, 200, 1.0), (Integrator::Rk2, 100, 2.0), (Integrator::Rk4, 20, 4.0)]
        {
            let observed = (global_error(integrator, n) / global_error(integrator, 2 * n)).log2();
            assert!((observed - order).abs() < 0.3, "{integrator:?}: observed order {observed}");
        }
    }

    #[test]
    fn rk45_meets_its_tolerance_and_adapts() {
        let tolerance = 1e-7;
        let control = StepControl::new(tolerance, 1e-6, 0.5);
        let (mut p, mut tau, mut h) = ([1.0, 0.0], 0.0, 0.01f64);
        let mut steps = 0;
        let mut grew = false;
        while tau < 2.0 * std::f64::consts::PI - 1e-12 && steps < 10_000 {
            let rest = 2.0 * std::f64::consts::PI - tau;
            let s = step(&rotation, Integrator::Rk45, p, tau, h.min(rest), &control).unwrap();
            assert!(s.error <= tolerance, "step error {} above tolerance", s.error);
            // Local error against the exact rotation by `taken` from p.
            let (c, sn) = (s.taken.cos(), s.taken.sin());
            let exact = [c * p[0] - sn * p[1], sn * p[0] + c * p[1]];
            assert!((s.point[0] - exact[0]).hypot(s.point[1] - exact[1]) <= tolerance);
            grew |= s.next > s.taken;
            p = s.point;
            tau += s.taken;
            h = s.next;
            steps += 1;
        }
        assert!(grew, "the step never grew from its small start");
        assert!(steps < 200, "{steps} steps for one turn");
        assert!((p[0] - 1.0).hypot(p[1]) <= steps as f64 * tolerance);
    }

    #[test]
    fn failures_and_modes() {
        let wall = |p: [f64; 2], _: f64| (p[0] < 1.0).then_some([1.0, 0.0]);
        let control = StepControl::new(1e-6, 1e-6, 1.0);
        for integrator in [Integrator::Euler, Integrator::Rk2, Integrator::Rk4, Integrator::Rk45] {
            assert!(step(&wall, integrator, [1.5, 0.0], 0.0, 0.1, &control).is_none());
            let back = step(&wall, integrator, [0.5, 0.0], 0.0, -0.25, &control).unwrap();
            assert!((back.point[0] - 0.25).abs() < 1e-12, "{integrator:?} backward");
        }
        assert_eq!(Mode::Normalized.apply([3.0, 4.0]), Some([0.6, 0.8]));
        assert_eq!(Mode::Normalized.apply([0.0, 0.0]), None);
        assert_eq!(Mode::Velocity.apply([3.0, 4.0]), Some([3.0, 4.0]));
        assert_eq!(Mode::Velocity.apply([f64::NAN, 4.0]), None);
    }
}
