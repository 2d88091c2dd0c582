//! Vector field topology (Helman & Hesselink 1989): critical points, saddle separatrices and
//! boundary switch points of the bilinear interpolant of a [`VectorField`].
//!
//! **Critical points.** In a cell with local coordinates `(s, t) ∈ [0, 1]²` the interpolant is
//! `u = a0 + a1 s + a2 t + a3 s t`, `v = b0 + b1 s + b2 t + b3 s t`. Eliminating `s` from `u = 0`
//! gives the quadratic `(b2 a3 − b3 a2) t² + (b0 a3 + b2 a1 − b1 a2 − b3 a0) t + (b0 a1 − b1 a0) = 0`,
//! solved exactly (cancellation-free form); each root in `[0, 1]` gives `s` back from whichever
//! of `u = 0`, `v = 0` is better conditioned. Points on shared edges or nodes are reported once.
//! Cells with a NaN corner give none; cells where `u` and `v` vanish on a whole curve (not
//! isolated zeros) are skipped. Each point is classified by the eigenvalues of the cell's exact
//! Jacobian there: `det < 0` saddle; real eigenvalues of one sign: node; complex: focus, or centre
//! when `|Re λ| ≤ centre_tolerance × |Im λ|`; `det = 0`: degenerate.
//!
//! **Separatrices.** From each saddle four streamlines start at `± offset` along the unstable
//! eigenvector (traced forward) and the stable one (traced backward).
//!
//! **Boundary switch points.** On each side of the domain the outward normal component
//! `g = v · n` is linear between nodes; where it changes sign the velocity is tangential. With
//! `w` the tangential velocity there and `g'` the derivative of `g` along the side's tangent, the
//! point is an [`SwitchKind::Attachment`] when `w g' > 0` (inflow turns into outflow downstream;
//! the streamline through the point touches the side from outside) and a
//! [`SwitchKind::Detachment`] when `w g' < 0` (outflow turns into inflow; the streamline through
//! the point grazes the side from inside and leaves into the interior, a separatrix of the
//! interior flow).

use rayon::prelude::*;

use super::budget::StepBudget;
use super::field::{VectorField, bilerp, bilerp_gradient};
use super::streamline::{Direction, Streamline, StreamlineOptions, trace_within};

/// Kind of a critical point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CriticalKind {
    /// Real eigenvalues of opposite signs.
    Saddle,
    /// Real negative eigenvalues (a sink).
    AttractingNode,
    /// Real positive eigenvalues (a source).
    RepellingNode,
    /// Complex eigenvalues with negative real part (spiral sink).
    AttractingFocus,
    /// Complex eigenvalues with positive real part (spiral source).
    RepellingFocus,
    /// Purely imaginary eigenvalues (within the tolerance).
    Centre,
    /// A zero eigenvalue (`det J = 0`): not a simple critical point.
    Degenerate,
}

/// An isolated zero of the bilinear interpolant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CriticalPoint {
    /// Position `[x, y]`.
    pub position: [f64; 2],
    /// Cell `(i, j)` it was found in (lower-left node indices).
    pub cell: (usize, usize),
    /// Classification.
    pub kind: CriticalKind,
    /// Eigenvalues as `(re, im)` pairs: real ones in decreasing order, complex ones `(re, +im)`
    /// then `(re, −im)`.
    pub eigenvalues: [(f64, f64); 2],
    /// For saddles, unit eigenvectors `[unstable, stable]` (for eigenvalues `[positive,
    /// negative]`), each with its larger component positive.
    pub eigenvectors: Option<[[f64; 2]; 2]>,
    /// Jacobian `[[∂u/∂x, ∂u/∂y], [∂v/∂x, ∂v/∂y]]` of the cell's interpolant at the point.
    pub jacobian: [[f64; 2]; 2],
}

/// Critical points of `field` (first frame) in row-major cell order; `centre_tolerance` is the
/// largest `|Re λ| / |Im λ|` still called a centre (1e-3 is a good default).
pub fn critical_points(field: &VectorField, centre_tolerance: f64) -> Vec<CriticalPoint> {
    let rows: Vec<Vec<CriticalPoint>> = (0..field.ny().saturating_sub(1))
        .into_par_iter()
        .map(|j| {
            let mut row = Vec::new();
            for i in 0..field.nx() - 1 {
                cell_critical_points(field, i, j, centre_tolerance, &mut row);
            }
            row
        })
        .collect();
    dedupe(field, rows.into_iter().flatten())
}

/// Drops repeats of a point found in two neighbouring cells (on their shared edge or node).
fn dedupe(field: &VectorField, points: impl Iterator<Item = CriticalPoint>) -> Vec<CriticalPoint> {
    let tol = 1e-7 * field.min_cell();
    let mut kept: Vec<CriticalPoint> = Vec::new();
    for p in points {
        let repeat = kept
            .iter()
            .rev()
            .take_while(|k| k.cell.1 + 1 >= p.cell.1)
            .any(|k| (k.position[0] - p.position[0]).abs() <= tol && (k.position[1] - p.position[1]).abs() <= tol);
        if !repeat {
            kept.push(p);
        }
    }
    kept
}

/// Bilinear coefficients `[c0, c1, c2, c3]` of `c0 + c1 s + c2 t + c3 s t` from corners.
fn coefficients(f: [f64; 4]) -> [f64; 4] {
    [f[0], f[1] - f[0], f[2] - f[0], f[3] - f[2] - f[1] + f[0]]
}

/// Appends the critical points of cell `(i, j)` to `out`.
fn cell_critical_points(field: &VectorField, i: usize, j: usize, centre_tol: f64, out: &mut Vec<CriticalPoint>) {
    let Some((uc, vc)) = field.cell_corners(i, j) else {
        return;
    };
    if uc.iter().chain(&vc).any(|c| !c.is_finite()) {
        return;
    }
    let scale = uc.iter().chain(&vc).fold(0.0f64, |m, c| m.max(c.abs()));
    if scale == 0.0 {
        return; // identically zero: no isolated points
    }
    // Quick reject: a component of one strict sign on all corners has no zero in the cell
    // (values within rounding noise of 0 count as zero, so zeros on cell edges are kept).
    let noise = 1e-12 * scale;
    let one_sign = |c: &[f64; 4]| c.iter().all(|&x| x > noise) || c.iter().all(|&x| x < -noise);
    if one_sign(&uc) || one_sign(&vc) {
        return;
    }
    let (Some((hx, hy)), Some(&x0), Some(&y0)) = (field.cell_size(i, j), field.xs().get(i), field.ys().get(j)) else {
        return;
    };
    let [a0, a1, a2, a3] = coefficients(uc);
    let [b0, b1, b2, b3] = coefficients(vc);
    let roots = quadratic_roots(b2 * a3 - b3 * a2, b0 * a3 + b2 * a1 - b1 * a2 - b3 * a0, b0 * a1 - b1 * a0);
    let eps = 1e-9;
    let mut found: Vec<(f64, f64)> = Vec::new();
    for t in roots.into_iter().flatten() {
        if !(t >= -eps && t <= 1.0 + eps) {
            continue;
        }
        let t = t.clamp(0.0, 1.0);
        let (du, dv) = (a1 + a3 * t, b1 + b3 * t);
        let s = if du.abs() >= dv.abs() { -(a0 + a2 * t) / du } else { -(b0 + b2 * t) / dv };
        if !(s >= -eps && s <= 1.0 + eps) {
            continue;
        }
        let s = s.clamp(0.0, 1.0);
        let residual = bilerp(uc, s, t).abs().max(bilerp(vc, s, t).abs());
        if residual > 1e-9 * scale || found.iter().any(|&(fs, ft)| (fs - s).abs() < eps && (ft - t).abs() < eps) {
            continue;
        }
        found.push((s, t));
        let [dus, dut] = bilerp_gradient(uc, s, t);
        let [dvs, dvt] = bilerp_gradient(vc, s, t);
        let jacobian = [[dus / hx, dut / hy], [dvs / hx, dvt / hy]];
        let Classification { kind, eigenvalues, eigenvectors } = classify(jacobian, centre_tol);
        out.push(CriticalPoint {
            position: [x0 + s * hx, y0 + t * hy],
            cell: (i, j),
            kind,
            eigenvalues,
            eigenvectors,
            jacobian,
        });
    }
}

/// Real roots of `a t² + b t + c = 0` in cancellation-free form; `None` entries for missing
/// roots. Identically zero coefficients (every `t` a root) give no roots.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    let finite = |x: f64| x.is_finite().then_some(x);
    if a == 0.0 {
        return if b == 0.0 { [None, None] } else { [finite(-c / b), None] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return [Some(0.0), None];
    }
    [finite(q / a), finite(c / q)]
}

/// The classification of a Jacobian: kind, eigenvalues and (saddles only) eigenvectors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Classification {
    /// Kind of critical point.
    pub kind: CriticalKind,
    /// Eigenvalues as `(re, im)` pairs; see [`CriticalPoint::eigenvalues`].
    pub eigenvalues: [(f64, f64); 2],
    /// Unit eigenvectors `[unstable, stable]` of a saddle.
    pub eigenvectors: Option<[[f64; 2]; 2]>,
}

/// Classifies a critical point by the eigenvalues of its Jacobian `j`; `centre_tolerance` is the
/// largest `|Re λ| / |Im λ|` still called a centre.
pub fn classify(j: [[f64; 2]; 2], centre_tolerance: f64) -> Classification {
    let [[a, b], [c, d]] = j;
    let half_trace = 0.5 * (a + d);
    let det = a * d - b * c;
    let disc = half_trace * half_trace - det;
    let norm2 = a * a + b * b + c * c + d * d;
    if disc < 0.0 {
        let im = (-disc).sqrt();
        let kind = if half_trace.abs() <= centre_tolerance * im {
            CriticalKind::Centre
        } else if half_trace < 0.0 {
            CriticalKind::AttractingFocus
        } else {
            CriticalKind::RepellingFocus
        };
        return Classification { kind, eigenvalues: [(half_trace, im), (half_trace, -im)], eigenvectors: None };
    }
    let root = disc.sqrt();
    // Larger-magnitude eigenvalue first from the sum, the other from the product (no cancellation).
    let big = if half_trace >= 0.0 { half_trace + root } else { half_trace - root };
    let small = if big != 0.0 { det / big } else { 0.0 };
    let (l1, l2) = if big >= small { (big, small) } else { (small, big) };
    let values = [(l1, 0.0), (l2, 0.0)];
    if det.abs() <= 1e-12 * norm2 || norm2 == 0.0 {
        return Classification { kind: CriticalKind::Degenerate, eigenvalues: values, eigenvectors: None };
    }
    if det < 0.0 {
        let vectors = [eigenvector(j, l1), eigenvector(j, l2)];
        return Classification { kind: CriticalKind::Saddle, eigenvalues: values, eigenvectors: Some(vectors) };
    }
    let kind = if l1 < 0.0 { CriticalKind::AttractingNode } else { CriticalKind::RepellingNode };
    Classification { kind, eigenvalues: values, eigenvectors: None }
}

/// Unit eigenvector of `j` for the real eigenvalue `l`, its larger component made positive.
fn eigenvector(j: [[f64; 2]; 2], l: f64) -> [f64; 2] {
    let [[a, b], [c, d]] = j;
    let (p, q) = ([b, l - a], [l - d, c]);
    let v = if p[0].hypot(p[1]) >= q[0].hypot(q[1]) { p } else { q };
    let n = v[0].hypot(v[1]);
    if n == 0.0 {
        return [1.0, 0.0];
    }
    let sign = if v[0].abs() >= v[1].abs() { v[0].signum() } else { v[1].signum() };
    [sign * v[0] / n, sign * v[1] / n]
}

/// Which eigen-direction of a saddle a separatrix follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SeparatrixKind {
    /// Along the unstable eigenvector, traced forward (flow leaving the saddle).
    Unstable,
    /// Along the stable eigenvector, traced backward (flow arriving at the saddle).
    Stable,
}

/// A separatrix of a saddle.
#[derive(Debug, Clone, PartialEq)]
pub struct Separatrix {
    /// Index of the saddle in the critical-point list given to [`separatrices`].
    pub saddle: usize,
    /// Unstable or stable.
    pub kind: SeparatrixKind,
    /// `+1` or `−1`: which way along the eigenvector it starts.
    pub side: f64,
    /// The traced curve, starting next to the saddle (with the saddle itself prepended).
    pub line: Streamline,
}

/// Up to four separatrices per saddle in `points`, started at `offset` from it along `±` each
/// eigenvector and traced with `options` (its `direction` is overridden). Starts outside the
/// domain or in holes (a saddle on the boundary) give no separatrix. Steps come from `budget`.
pub fn separatrices(
    field: &VectorField,
    points: &[CriticalPoint],
    offset: f64,
    options: &StreamlineOptions,
    budget: &StepBudget,
) -> Vec<Separatrix> {
    let mut out = Vec::new();
    for (index, p) in points.iter().enumerate() {
        let (CriticalKind::Saddle, Some([unstable, stable])) = (p.kind, p.eigenvectors) else {
            continue;
        };
        for (kind, e, direction) in [
            (SeparatrixKind::Unstable, unstable, Direction::Forward),
            (SeparatrixKind::Stable, stable, Direction::Backward),
        ] {
            for side in [1.0, -1.0] {
                let seed = [p.position[0] + side * offset * e[0], p.position[1] + side * offset * e[1]];
                let mut line = trace_within(field, seed, &StreamlineOptions { direction, ..*options }, budget);
                if line.points.len() < 2 {
                    continue;
                }
                // Start the polyline at the saddle itself.
                if direction == Direction::Forward {
                    line.points.insert(0, p.position);
                    line.params.insert(0, -offset);
                    line.seed_index += 1;
                } else {
                    line.points.push(p.position);
                    line.params.push(offset);
                }
                out.push(Separatrix { saddle: index, kind, side, line });
            }
        }
    }
    out
}

/// A side of the domain rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// `y = y_min`, outward normal `(0, −1)`, tangent `+x`.
    Bottom,
    /// `x = x_max`, outward normal `(1, 0)`, tangent `+y`.
    Right,
    /// `y = y_max`, outward normal `(0, 1)`, tangent `+x`.
    Top,
    /// `x = x_min`, outward normal `(−1, 0)`, tangent `+y`.
    Left,
}

/// Kind of a boundary switch point; see the module docs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SwitchKind {
    /// `w g' > 0`: inflow turns into outflow along the tangential flow.
    Attachment,
    /// `w g' < 0`: outflow turns into inflow; the streamline through it enters the interior.
    Detachment,
}

/// A point of a domain side where the normal velocity changes sign.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryPoint {
    /// Position `[x, y]` on the side.
    pub position: [f64; 2],
    /// The side.
    pub side: Side,
    /// Attachment or detachment.
    pub kind: SwitchKind,
    /// Tangential velocity `w` (along the side's tangent).
    pub tangential_velocity: f64,
    /// Derivative `g'` of the outward normal component along the side's tangent.
    pub normal_derivative: f64,
}

/// Boundary switch points of `field` (first frame), side by side in the order bottom, right, top,
/// left, each along its tangent. Normal components within 1e-12 × the maximum speed of zero count as
/// zero (a side along which the flow is tangential has no switch points); segments with a NaN end,
/// and points where `w g' = 0`, are skipped.
pub fn boundary_points(field: &VectorField) -> Vec<BoundaryPoint> {
    let (nx, ny) = (field.nx(), field.ny());
    let (Some(u), Some(v)) = (field.u(0), field.v(0)) else {
        return Vec::new();
    };
    let node = |i: usize, j: usize| -> [f64; 2] {
        let k = j * nx + i;
        [u.get(k).copied().unwrap_or(f64::NAN), v.get(k).copied().unwrap_or(f64::NAN)]
    };
    let (xs, ys) = (field.xs(), field.ys());
    let mut out = Vec::new();
    for side in [Side::Bottom, Side::Right, Side::Top, Side::Left] {
        // Nodes along the side: (coordinate along the tangent, fixed position, velocity).
        let nodes: Vec<(f64, [f64; 2], [f64; 2])> = match side {
            Side::Bottom => xs.iter().enumerate().map(|(i, &x)| (x, [x, ys[0]], node(i, 0))).collect(),
            Side::Top => xs.iter().enumerate().map(|(i, &x)| (x, [x, ys[ny - 1]], node(i, ny - 1))).collect(),
            Side::Left => ys.iter().enumerate().map(|(j, &y)| (y, [xs[0], y], node(0, j))).collect(),
            Side::Right => ys.iter().enumerate().map(|(j, &y)| (y, [xs[nx - 1], y], node(nx - 1, j))).collect(),
        };
        let (normal, tangent) = match side {
            Side::Bottom => ([0.0, -1.0], [1.0, 0.0]),
            Side::Top => ([0.0, 1.0], [1.0, 0.0]),
            Side::Left => ([-1.0, 0.0], [0.0, 1.0]),
            Side::Right => ([1.0, 0.0], [0.0, 1.0]),
        };
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        // Normal components within rounding noise of zero count as zero.
        let noise = 1e-12 * field.max_speed();
        let normal_of = |v: [f64; 2]| {
            let g = dot(v, normal);
            if g.abs() <= noise { 0.0 } else { g }
        };
        let mut last_sign = 0.0; // sign of the last non-zero normal component before this segment
        for w in nodes.windows(2) {
            let ((sa, pa, va), (sb, pb, vb)) = (w[0], w[1]);
            let (ga, gb) = (normal_of(va), normal_of(vb));
            if !ga.is_finite() || !gb.is_finite() {
                last_sign = 0.0;
                continue;
            }
            if ga != 0.0 {
                last_sign = ga.signum();
            }
            // A sign change strictly inside the segment, or a zero stretch ending at `a` between
            // values of opposite signs.
            let crosses = ga * gb < 0.0 || (ga == 0.0 && gb != 0.0 && last_sign == -gb.signum());
            if !crosses {
                continue;
            }
            let f = ga / (ga - gb);
            let g_prime = (gb - ga) / (sb - sa);
            let velocity = [va[0] + f * (vb[0] - va[0]), va[1] + f * (vb[1] - va[1])];
            let tangential = dot(velocity, tangent);
            let product = tangential * g_prime;
            if product == 0.0 || !product.is_finite() {
                continue;
            }
            let kind = if product > 0.0 { SwitchKind::Attachment } else { SwitchKind::Detachment };
            let position = [pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1])];
            out.push(BoundaryPoint {
                position,
                side,
                kind,
                tangential_velocity: tangential,
                normal_derivative: g_prime,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(n: usize, a: f64, b: f64) -> Vec<f64> {
        (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect()
    }

    fn field(f: impl FnMut(f64, f64) -> [f64; 2]) -> VectorField {
        VectorField::from_fn(axis(21, -1.0, 1.0), axis(21, -1.0, 1.0), f).unwrap()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn saddle_at_a_node_is_found_once_with_axis_eigenvectors() {
        let points = critical_points(&field(|x, y| [x, -y]), 1e-3);
        assert_eq!(points.len(), 1, "{points:?}");
        let p = points[0];
        assert_eq!(p.kind, CriticalKind::Saddle);
        assert!(close(p.position[0], 0.0) && close(p.position[1], 0.0));
        assert_eq!(p.eigenvalues, [(1.0, 0.0), (-1.0, 0.0)]);
        let [unstable, stable] = p.eigenvectors.unwrap();
        assert!(close(unstable[0], 1.0) && close(unstable[1], 0.0), "{unstable:?}");
        assert!(close(stable[0], 0.0) && close(stable[1], 1.0), "{stable:?}");
    }

    #[test]
    fn centre_focus_and_node_are_classified() {
        type Case = (fn(f64, f64) -> [f64; 2], CriticalKind, [(f64, f64); 2]);
        let cases: [Case; 3] = [
            (|x, y| [-y, x], CriticalKind::Centre, [(0.0, 1.0), (0.0, -1.0)]),
            (|x, y| [-x - y, x - y], CriticalKind::AttractingFocus, [(-1.0, 1.0), (-1.0, -1.0)]),
            (|x, y| [x, y], CriticalKind::RepellingNode, [(1.0, 0.0), (1.0, 0.0)]),
        ];
        for (f, kind, eigenvalues) in cases {
            // Shift the lattice so the zero lies inside a cell, not on a node.
            let g = VectorField::from_fn(axis(20, -1.0, 0.95), axis(17, -0.8, 1.0), f).unwrap();
            let points = critical_points(&g, 1e-3);
            assert_eq!(points.len(), 1, "{kind:?}: {points:?}");
            let p = points[0];
            assert_eq!(p.kind, kind);
            assert!(close(p.position[0], 0.0) && close(p.position[1], 0.0), "{:?}", p.position);
            for (got, want) in p.eigenvalues.iter().zip(&eigenvalues) {
                assert!(close(got.0, want.0) && close(got.1, want.1), "{kind:?}: {:?}", p.eigenvalues);
            }
        }
        let c = classify([[-1.0, 0.0], [0.0, -2.0]], 1e-3);
        assert_eq!((c.kind, c.eigenvalues), (CriticalKind::AttractingNode, [(-1.0, 0.0), (-2.0, 0.0)]));
        assert_eq!(classify([[1.0, 0.0], [0.0, 0.0]], 1e-3).kind, CriticalKind::Degenerate);
        // Nearly pure rotation: a centre within the tolerance, a focus outside it.
        assert_eq!(classify([[1e-4, -1.0], [1.0, 1e-4]], 1e-3).kind, CriticalKind::Centre);
        assert_eq!(classify([[1e-2, -1.0], [1.0, 1e-2]], 1e-3).kind, CriticalKind::RepellingFocus);
    }

    #[test]
    fn two_zeros_in_one_cell_are_both_found() {
        // A bilinear field with two zeros in one cell: u = x y − 0.1, v = x + y − 0.7 on the unit
        // square, zero at (0.2, 0.5) and (0.5, 0.2).
        let g =
            VectorField::new(vec![0.0, 1.0], vec![0.0, 1.0], vec![-0.1, -0.1, -0.1, 0.9], vec![-0.7, 0.3, 0.3, 1.3])
                .unwrap();
        let points = critical_points(&g, 1e-3);
        assert_eq!(points.len(), 2);
        for p in &points {
            let [x, y] = p.position;
            assert!((x * y - 0.1).abs() < 1e-12 && (x + y - 0.7).abs() < 1e-12, "{:?}", p.position);
        }
        // det J = x − y changes sign between them: one saddle, one non-saddle.
        assert_eq!(points.iter().filter(|p| p.kind == CriticalKind::Saddle).count(), 1);
    }

    #[test]
    fn no_zeros_and_holes_give_no_points() {
        assert!(critical_points(&field(|x, y| [1.0 + 0.1 * x * y, y]), 1e-3).is_empty());
        assert!(critical_points(&field(|_, _| [0.0, 0.0]), 1e-3).is_empty());
        let g = VectorField::from_fn(axis(20, -1.0, 0.95), axis(20, -1.0, 0.95), |x, y| {
            if x.abs() < 0.1 && y.abs() < 0.1 { [f64::NAN, 0.0] } else { [x, -y] }
        })
        .unwrap();
        assert!(critical_points(&g, 1e-3).is_empty());
    }

    #[test]
    fn separatrices_of_a_saddle_follow_the_axes() {
        let g = field(|x, y| [x, -y]);
        let points = critical_points(&g, 1e-3);
        let o = StreamlineOptions::for_field(&g);
        let seps = separatrices(&g, &points, 1e-3, &o, &StepBudget::default());
        assert_eq!(seps.len(), 4);
        for s in &seps {
            let end = s.line.points[if s.kind == SeparatrixKind::Unstable { s.line.points.len() - 1 } else { 0 }];
            match s.kind {
                // Unstable: out along the x axis to x = ±1; stable: in from y = ±1.
                SeparatrixKind::Unstable => assert!(close(end[0], s.side) && end[1].abs() < 1e-9, "{end:?}"),
                SeparatrixKind::Stable => assert!(close(end[1], s.side) && end[0].abs() < 1e-9, "{end:?}"),
            }
        }
    }

    #[test]
    fn boundary_switch_points_are_found_and_classified() {
        // u = 1, v = x − 0.5 on the unit square: switch points at (0.5, 0) and (0.5, 1).
        let g = VectorField::from_fn(axis(11, 0.0, 1.0), axis(11, 0.0, 1.0), |x, _| [1.0, x - 0.5]).unwrap();
        let points = boundary_points(&g);
        assert_eq!(points.len(), 2, "{points:?}");
        let (bottom, top) = (points[0], points[1]);
        assert_eq!((bottom.side, bottom.kind), (Side::Bottom, SwitchKind::Detachment));
        assert_eq!((top.side, top.kind), (Side::Top, SwitchKind::Attachment));
        assert!(close(bottom.position[0], 0.5) && close(top.position[0], 0.5));
        assert!(close(bottom.normal_derivative, -1.0) && close(top.tangential_velocity, 1.0));
    }
}
