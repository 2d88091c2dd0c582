//! The isosurface where it meets the cell's boundary: which faces join their inside corners
//! (the asymptotic decider), the oriented boundary loops on the cube's surface, and the patches
//! of the cube's surface the loops cut it into.
//!
//! A cube face is the bilinear patch through its four corner values `g = f − iso`. A face is
//! *ambiguous* when its corners alternate inside/outside around it; then its bilinear patch has
//! a saddle with value `s = (g0·g2 − g1·g3) / (g0 + g2 − g1 − g3)` (corners in cyclic order), and
//! the two inside corners are joined across the face exactly when `s ≥ 0` (Nielson and Hamann's
//! asymptotic decider). With `g0, g2 ≥ 0 > g1, g3` the denominator is positive, so the test is
//! `g0·g2 ≥ g1·g3`: two products, which neighbouring cells compute identically, so both cells
//! sharing a face decide it the same way. `s = 0` joins the inside corners, as `f == iso` counts as
//! inside everywhere.

use super::cube::{
    corner_position, cross, dot, edge_between, edge_corners, edge_midpoint, face_corners, face_normal, sub,
};

/// Bit `c` set when corner `c` is inside (`g ≥ 0`).
pub(super) fn inside_mask(g: &[f64; 8]) -> u8 {
    g.iter().enumerate().fold(0, |m, (c, v)| if *v >= 0.0 { m | 1 << c } else { m })
}

/// Whether face `f` is ambiguous under the inside mask `signs`.
pub(super) fn ambiguous(signs: u8, f: usize) -> bool {
    let s = face_corners(f).map(|c| signs >> c & 1);
    s[0] == s[2] && s[1] == s[3] && s[0] != s[1]
}

/// Bit `f` set when face `f` is ambiguous and its inside corners are joined across it; bits of
/// faces that are not ambiguous are 0.
pub(super) fn face_decisions(g: &[f64; 8], signs: u8) -> u8 {
    let mut joined = 0;
    for f in 0..6 {
        if !ambiguous(signs, f) {
            continue;
        }
        let [a, b, c, d] = face_corners(f);
        let (inside, outside) = if signs >> a & 1 == 1 { ((a, c), (b, d)) } else { ((b, d), (a, c)) };
        if g[inside.0] * g[inside.1] >= g[outside.0] * g[outside.1] {
            joined |= 1 << f;
        }
    }
    joined
}

/// The isosurface's trace on the cube's surface for one sign pattern and face decisions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Boundary {
    /// Closed loops of crossed edges, each oriented so that, seen from outside the cube, the
    /// inside corners lie on its right: the orientation a loop gets as the boundary of a surface
    /// whose triangles are counter-clockwise seen from the outside (`g < 0`) side.
    pub loops: Vec<Vec<u8>>,
    /// For each loop, an inside and an outside corner next to it (the ends of its first edge).
    pub sides: Vec<[u8; 2]>,
    /// For each corner, its patch: corners joined on the cube's surface without crossing a loop
    /// (along uncrossed edges and across faces whose decision joins them) share a number, the
    /// smallest corner of the patch.
    pub patches: [u8; 8],
}

/// A union–find over at most 8 corners.
pub(super) fn find(parent: &mut [u8; 8], c: usize) -> usize {
    let mut c = c;
    while parent[c] as usize != c {
        let up = parent[c] as usize;
        parent[c] = parent[up];
        c = up;
    }
    c
}

/// Joins the sets of `a` and `b`; the smaller corner becomes the root.
pub(super) fn union(parent: &mut [u8; 8], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
        parent[hi] = lo as u8;
    }
}

/// The boundary loops and patches for the inside mask `signs` and face decisions `joined`, or
/// `None` if the segments do not close into loops (never for valid input; checked by the tests).
pub(super) fn boundary(signs: u8, joined: u8) -> Option<Boundary> {
    let inside = |c: usize| signs >> c & 1 == 1;
    let crossed = |e: usize| {
        let [a, b] = edge_corners(e);
        inside(a) != inside(b)
    };
    // next[e] = the crossed edge a face segment leads to from crossed edge e.
    let mut next = [u8::MAX; 12];
    let mut incoming = [0u8; 12];
    for f in 0..6 {
        let cs = face_corners(f);
        let face_edges: [usize; 4] = std::array::from_fn(|l| edge_between(cs[l], cs[(l + 1) % 4]).unwrap_or(0));
        let cut: Vec<usize> = (0..4).filter(|&l| crossed(face_edges[l])).collect();
        let pairs: Vec<(usize, usize)> = match cut.len() {
            0 => Vec::new(),
            2 => vec![(face_edges[cut[0]], face_edges[cut[1]])],
            4 => {
                // Cut off the corners that are not joined: the outside ones when the inside
                // corners are joined across the face, else the inside ones. Corner l of the face
                // lies between face edges l − 1 and l.
                let cut_inside = joined >> f & 1 == 0;
                (0..4)
                    .filter(|&l| inside(cs[l]) == cut_inside)
                    .map(|l| (face_edges[(l + 3) % 4], face_edges[l]))
                    .collect()
            }
            _ => return None,
        };
        for (e1, e2) in pairs {
            // Orient so that, seen from outside, the inside end of e1 lies on the right.
            let (p, q) = (edge_midpoint(e1), edge_midpoint(e2));
            let [a, b] = edge_corners(e1);
            let x = if inside(a) { a } else { b };
            let xp = corner_position(x).map(|v| v as f64);
            let left = dot(cross(sub(q, p), sub(xp, p)), face_normal(f)) > 0.0;
            let (from, to) = if left { (e2, e1) } else { (e1, e2) };
            if next[from] != u8::MAX {
                return None;
            }
            next[from] = to as u8;
            incoming[to] += 1;
        }
    }
    let mut loops = Vec::new();
    let mut sides = Vec::new();
    let mut seen = [false; 12];
    for start in 0..12 {
        if !crossed(start) || seen[start] {
            continue;
        }
        if next[start] == u8::MAX || incoming[start] != 1 {
            return None;
        }
        let mut lp = Vec::new();
        let mut e = start;
        while !seen[e] {
            seen[e] = true;
            lp.push(e as u8);
            e = next[e] as usize;
            if e >= 12 {
                return None;
            }
        }
        if e != start {
            return None;
        }
        let [a, b] = edge_corners(start);
        sides.push(if inside(a) { [a as u8, b as u8] } else { [b as u8, a as u8] });
        loops.push(lp);
    }
    let mut parent: [u8; 8] = std::array::from_fn(|c| c as u8);
    for e in 0..12 {
        let [a, b] = edge_corners(e);
        if inside(a) == inside(b) {
            union(&mut parent, a, b);
        }
    }
    for f in 0..6 {
        if super::surface::ambiguous(signs, f) {
            let [a, b, c, d] = face_corners(f);
            let a_joined = inside(a) == (joined >> f & 1 == 1);
            if a_joined {
                union(&mut parent, a, c);
            } else {
                union(&mut parent, b, d);
            }
        }
    }
    let patches = std::array::from_fn(|c| find(&mut parent, c) as u8);
    Some(Boundary { loops, sides, patches })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_corner_gives_one_triangle_loop_around_it() {
        let b = boundary(1, 0).expect("loops");
        assert_eq!(b.loops.len(), 1);
        assert_eq!(b.loops[0].len(), 3);
        // x-edge 0, then y-edge (corner 0 → 2) 4 + 0... whatever the numbers, the order must be
        // x, y, z around the corner (counter-clockwise seen from outside, i.e. from (1, 1, 1)).
        let axes: Vec<usize> = b.loops[0].iter().map(|&e| e as usize / 4).collect();
        let start = axes.iter().position(|&a| a == 0).expect("an x edge");
        let rotated: Vec<usize> = (0..3).map(|i| axes[(start + i) % 3]).collect();
        assert_eq!(rotated, vec![0, 1, 2]);
        assert_eq!(b.patches, [0, 1, 1, 1, 1, 1, 1, 1]);
    }

    #[test]
    fn every_pattern_and_decision_closes_into_loops_that_cut_the_surface_into_patches() {
        for signs in 0..=255u8 {
            let amb: Vec<usize> = (0..6).filter(|&f| ambiguous(signs, f)).collect();
            for choice in 0..1u32 << amb.len() {
                let joined = amb.iter().enumerate().fold(0u8, |m, (i, &f)| m | ((choice >> i & 1) as u8) << f);
                let b = boundary(signs, joined).expect("closed loops");
                let mut patches = b.patches.to_vec();
                patches.sort_unstable();
                patches.dedup();
                // n disjoint loops on a sphere cut it into n + 1 pieces.
                assert_eq!(patches.len(), b.loops.len() + 1, "signs {signs:08b} joined {joined:06b}");
                let crossed = (0..12)
                    .filter(|&e| {
                        let [a, c] = edge_corners(e);
                        (signs >> a & 1) != (signs >> c & 1)
                    })
                    .count();
                assert_eq!(b.loops.iter().map(Vec::len).sum::<usize>(), crossed);
            }
        }
    }
}
