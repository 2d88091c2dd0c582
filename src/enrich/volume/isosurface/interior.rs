//! Which corners of a cell are joined through the cell's interior, for the trilinear function
//! of the cell — the interior ambiguity of marching cubes (MC33's tunnels).
//!
//! The cell is swept by planes `z = t`. On each plane the trilinear function is bilinear with
//! corner values `s(t) = g(z=0)·(1 − t) + g(z=1)·t`, linear in `t`, and the plane's inside
//! region `{g ≥ 0}` and outside region `{g < 0}` fall into components exactly as the asymptotic
//! decider says (the test `s0·s3 ≥ s1·s2` on the plane's diagonals). That picture changes only at
//! finitely many heights: where a plane corner's value crosses 0 (at most four), and where the
//! plane's saddle crosses the level, i.e. the roots of the quadratic
//! `q(t) = s0(t)·s3(t) − s1(t)·s2(t)` (at most two; the vertex of the parabola is added too, so
//! a tunnel that is only just open is not stepped over). Between two such events the regions are
//! a product of a plane picture with an interval, so their components are those of any plane in
//! between; a component over an interval meets the event plane at either end in the component
//! holding the same plane corners (the closed inside region), or the same corners still strictly
//! outside (the open outside region). A union–find over (plane, plane corner) therefore gives the
//! exact components of both regions in the cell, named by the cube corners they hold — every
//! component holds a corner, as a trilinear function has no interior maximum or minimum.
//!
//! This generalises the plane tests of Chernyaev (1995) and Lopes & Brodlie (2003), which look
//! at the one plane where `q` peaks, to every configuration at once.

use super::surface::{find, union};

/// Most planes looked at: 2 ends, 4 corner roots, 2 saddle roots and the parabola's vertex, and
/// a plane between each two.
const MAX_PLANES: usize = 2 * 9 - 1;

/// A plane of the sweep: its height, plane corners forced to exactly 0 (the plane is that
/// corner's root), and whether the plane's saddle is forced to the level.
#[derive(Clone, Copy, Debug)]
struct Event {
    t: f64,
    zero: u8,
    tie: bool,
}

/// For each cube corner, the smallest corner of its component within the cell: inside corners
/// (`g ≥ 0`) grouped by the closed region `{g ≥ 0}`, outside corners by the open region
/// `{g < 0}`.
pub(super) fn components(g: &[f64; 8]) -> [u8; 8] {
    let bottom: [f64; 4] = std::array::from_fn(|s| g[s]);
    let top: [f64; 4] = std::array::from_fn(|s| g[s | 4]);
    let mut events: Vec<Event> = vec![Event { t: 0.0, zero: 0, tie: false }, Event { t: 1.0, zero: 0, tie: false }];
    for s in 0..4 {
        let (a, b) = (bottom[s], top[s]);
        if (a < 0.0 && b > 0.0) || (a > 0.0 && b < 0.0) {
            let t = a / (a - b);
            if t > 0.0 && t < 1.0 {
                events.push(Event { t, zero: 1 << s, tie: false });
            }
        }
    }
    // q(t) = A t² + B t + C with s(t) = a + b t.
    let d: [f64; 4] = std::array::from_fn(|s| top[s] - bottom[s]);
    let qa = d[0] * d[3] - d[1] * d[2];
    let qb = bottom[0] * d[3] + bottom[3] * d[0] - bottom[1] * d[2] - bottom[2] * d[1];
    let qc = bottom[0] * bottom[3] - bottom[1] * bottom[2];
    let mut roots = Vec::with_capacity(2);
    if qa != 0.0 {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let h = -0.5 * (qb + qb.signum() * disc.sqrt());
            if h != 0.0 {
                roots.push(h / qa);
                roots.push(qc / h);
            } else {
                roots.push(0.0);
            }
        }
        let vertex = -qb / (2.0 * qa);
        if vertex > 0.0 && vertex < 1.0 {
            events.push(Event { t: vertex, zero: 0, tie: false });
        }
    } else if qb != 0.0 {
        roots.push(-qc / qb);
    }
    for t in roots {
        if t > 0.0 && t < 1.0 {
            events.push(Event { t, zero: 0, tie: true });
        }
    }
    events.sort_by(|x, y| x.t.total_cmp(&y.t));
    let mut merged: Vec<Event> = Vec::with_capacity(events.len());
    for e in events {
        match merged.last_mut() {
            Some(last) if last.t == e.t => {
                last.zero |= e.zero;
                last.tie |= e.tie;
            }
            _ => merged.push(e),
        }
    }
    // The planes: events, with a plane halfway between each two.
    let mut planes: Vec<Event> = Vec::with_capacity(MAX_PLANES);
    for (n, e) in merged.iter().enumerate() {
        if let Some(prev) = n.checked_sub(1).and_then(|p| merged.get(p)) {
            planes.push(Event { t: 0.5 * (prev.t + e.t), zero: 0, tie: false });
        }
        planes.push(*e);
    }
    let count = planes.len().min(MAX_PLANES);
    // Union–find over (plane, plane corner); node 4p + s.
    let mut parent: Vec<usize> = (0..4 * count).collect();
    let mut class = vec![false; 4 * count];
    for (p, plane) in planes.iter().take(count).enumerate() {
        let t = plane.t;
        let v: [f64; 4] =
            std::array::from_fn(|s| if plane.zero >> s & 1 == 1 { 0.0 } else { bottom[s] * (1.0 - t) + top[s] * t });
        let inside: [bool; 4] = v.map(|x| x >= 0.0);
        for s in 0..4 {
            class[4 * p + s] = inside[s];
        }
        // Plane corners 0 = (0,0), 1 = (1,0), 2 = (0,1), 3 = (1,1); edges 0–1, 0–2, 1–3, 2–3.
        for (a, b) in [(0, 1), (0, 2), (1, 3), (2, 3)] {
            if inside[a] == inside[b] {
                join(&mut parent, 4 * p + a, 4 * p + b);
            }
        }
        if inside[0] == inside[3] && inside[1] == inside[2] && inside[0] != inside[1] {
            let (i, o) = if inside[0] { ((0, 3), (1, 2)) } else { ((1, 2), (0, 3)) };
            let inside_joined = plane.tie || v[i.0] * v[i.1] >= v[o.0] * v[o.1];
            let (a, b) = if inside_joined { i } else { o };
            join(&mut parent, 4 * p + a, 4 * p + b);
        }
        if p > 0 {
            for s in 0..4 {
                if class[4 * (p - 1) + s] == inside[s] {
                    join(&mut parent, 4 * (p - 1) + s, 4 * p + s);
                }
            }
        }
    }
    let last = count.saturating_sub(1);
    let root: [usize; 8] = std::array::from_fn(|c| {
        let node = if c < 4 { c } else { 4 * last + (c - 4) };
        root_of(&mut parent, node)
    });
    let mut groups: [u8; 8] = std::array::from_fn(|c| c as u8);
    for a in 0..8 {
        for b in 0..a {
            if root[a] == root[b] {
                union(&mut groups, a, b);
            }
        }
    }
    std::array::from_fn(|c| find(&mut groups, c) as u8)
}

fn root_of(parent: &mut [usize], n: usize) -> usize {
    let mut n = n;
    while let Some(&up) = parent.get(n) {
        if up == n {
            break;
        }
        let grand = parent.get(up).copied().unwrap_or(up);
        if let Some(slot) = parent.get_mut(n) {
            *slot = grand;
        }
        n = up;
    }
    n
}

fn join(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (root_of(parent, a), root_of(parent, b));
    if ra != rb
        && let Some(slot) = parent.get_mut(ra.max(rb))
    {
        *slot = ra.min(rb);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opposite_corners_join_through_the_middle_only_when_the_centre_is_high() {
        // Corners 0 and 7 inside. Centre value (2 − 6·0.2)/8 > 0 and the body diagonal stays
        // inside: a tunnel.
        let mut g = [-0.2; 8];
        g[0] = 1.0;
        g[7] = 1.0;
        let c = components(&g);
        assert_eq!(c[0], c[7]);
        assert_eq!(c[1], 1, "the outside corners are one component either way");
        g = [-0.5; 8];
        g[0] = 1.0;
        g[7] = 1.0;
        let c = components(&g);
        assert_ne!(c[0], c[7]);
    }
}
