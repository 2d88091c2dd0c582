//! The unit cube of one cell: corner, edge and face numbering shared by every other module.
//!
//! - **Corners** `c = x | y << 1 | z << 2` for the corner at `(x, y, z)`, `x, y, z ∈ {0, 1}`.
//! - **Edges** `e = axis * 4 + m`: the edge along `axis` whose other two coordinates are bit 0
//!   and bit 1 of `m`, taken along the next two axes in cyclic order (`(y, z)` for x, `(z, x)`
//!   for y, `(x, y)` for z). It runs from its lower corner to the corner one step along `axis`.
//! - **Faces** `f = axis * 2 + side`: the face `coordinate[axis] = side`, its outward normal
//!   `−e_axis` for side 0 and `+e_axis` for side 1. Its corners are listed in cyclic order, so
//!   corners 0 and 2 (and 1 and 3) of the list are diagonal; edge `l` of the face joins corners
//!   `l` and `l + 1` of the list.

/// The two axes after `axis`, in cyclic order.
const fn others(axis: usize) -> (usize, usize) {
    ((axis + 1) % 3, (axis + 2) % 3)
}

/// The coordinates of corner `c`.
pub(super) const fn corner_position(c: usize) -> [usize; 3] {
    [c & 1, (c >> 1) & 1, (c >> 2) & 1]
}

/// The lower and upper corner of edge `e` (`e < 12`).
pub(super) const fn edge_corners(e: usize) -> [usize; 2] {
    let axis = e / 4;
    let m = e % 4;
    let (o1, o2) = others(axis);
    let a = (m & 1) << o1 | (m >> 1) << o2;
    [a, a | 1 << axis]
}

/// The axis edge `e` runs along.
pub(super) const fn edge_axis(e: usize) -> usize {
    e / 4
}

/// The edge joining corners `a` and `b`, if they are neighbours.
pub(super) const fn edge_between(a: usize, b: usize) -> Option<usize> {
    let d = a ^ b;
    if a > 7 || b > 7 || d.count_ones() != 1 {
        return None;
    }
    let axis = d.trailing_zeros() as usize;
    let lower = if a < b { a } else { b };
    let (o1, o2) = others(axis);
    let m = ((lower >> o1) & 1) | ((lower >> o2) & 1) << 1;
    Some(axis * 4 + m)
}

/// The four corners of face `f`, in cyclic order.
pub(super) const fn face_corners(f: usize) -> [usize; 4] {
    let axis = f / 2;
    let base = (f % 2) << axis;
    let (o1, o2) = others(axis);
    let (u, v) = (1 << o1, 1 << o2);
    [base, base | u, base | u | v, base | v]
}

/// The outward unit normal of face `f`.
pub(super) const fn face_normal(f: usize) -> [f64; 3] {
    let mut n = [0.0; 3];
    n[f / 2] = if f % 2 == 1 { 1.0 } else { -1.0 };
    n
}

/// The faces edge `e` lies on, as bits `1 << f`.
pub(super) const fn edge_faces(e: usize) -> u8 {
    let [a, _] = edge_corners(e);
    let (o1, o2) = others(edge_axis(e));
    let f1 = o1 * 2 + ((a >> o1) & 1);
    let f2 = o2 * 2 + ((a >> o2) & 1);
    (1 << f1 | 1 << f2) as u8
}

/// The midpoint of edge `e`.
pub(super) fn edge_midpoint(e: usize) -> [f64; 3] {
    let [a, b] = edge_corners(e);
    let (pa, pb) = (corner_position(a), corner_position(b));
    [0, 1, 2].map(|i| (pa[i] + pb[i]) as f64 / 2.0)
}

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(super) fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(super) fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    a.map(|x| x * s)
}

pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub(super) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The trilinear function with corner values `g` at cell-local point `p`.
pub(super) fn trilinear(g: &[f64; 8], p: [f64; 3]) -> f64 {
    let lerp = |a: f64, b: f64, t: f64| a * (1.0 - t) + b * t;
    let x = [0, 2, 4, 6].map(|c| lerp(g[c], g[c | 1], p[0]));
    let y = [lerp(x[0], x[1], p[1]), lerp(x[2], x[3], p[1])];
    lerp(y[0], y[1], p[2])
}

/// The gradient of the trilinear function with corner values `g` at cell-local point `p`.
pub(super) fn trilinear_gradient(g: &[f64; 8], p: [f64; 3]) -> [f64; 3] {
    let mut grad = [0.0; 3];
    for (c, value) in g.iter().enumerate() {
        let q = corner_position(c);
        // The weight of corner c is the product over axes of (p or 1 − p); differentiate one.
        let w = |a: usize| if q[a] == 1 { p[a] } else { 1.0 - p[a] };
        let dw = |a: usize| if q[a] == 1 { 1.0 } else { -1.0 };
        grad[0] += value * dw(0) * w(1) * w(2);
        grad[1] += value * w(0) * dw(1) * w(2);
        grad[2] += value * w(0) * w(1) * dw(2);
    }
    grad
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbering_is_consistent() {
        for e in 0..12 {
            let [a, b] = edge_corners(e);
            assert_eq!(edge_between(a, b), Some(e), "edge {e}");
            assert_eq!(edge_between(b, a), Some(e), "edge {e}");
            assert_eq!(b - a, 1 << edge_axis(e));
            // The edge lies on exactly the two faces holding both its corners.
            for f in 0..6 {
                let on = face_corners(f).contains(&a) && face_corners(f).contains(&b);
                assert_eq!(edge_faces(e) >> f & 1 == 1, on, "edge {e} face {f}");
            }
        }
        for f in 0..6 {
            let cs = face_corners(f);
            for l in 0..4 {
                assert!(edge_between(cs[l], cs[(l + 1) % 4]).is_some(), "face {f}");
            }
            assert!(edge_between(cs[0], cs[2]).is_none());
            for c in cs {
                assert_eq!(corner_position(c)[f / 2], f % 2);
            }
        }
        let g = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
        // g = x + 2y + 4z exactly.
        assert!((trilinear(&g, [0.25, 0.5, 0.75]) - 4.25).abs() < 1e-12);
        let grad = trilinear_gradient(&g, [0.3, 0.6, 0.1]);
        assert!((grad[0] - 1.0).abs() < 1e-12 && (grad[1] - 2.0).abs() < 1e-12 && (grad[2] - 4.0).abs() < 1e-12);
    }
}
