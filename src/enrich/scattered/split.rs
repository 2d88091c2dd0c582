//! Divide and conquer for large inputs, on two threads: the points left and right of the median
//! x are triangulated at the same time, and only the seam between the halves is triangulated
//! again.
//!
//! Why the result is the Delaunay triangulation `DT` of all points. Let the halves be `L`
//! (`x < m`) and `R` (`x >= m`).
//! - A triangle of `DT(L)` whose circumcircle lies wholly left of `m` is empty of `R` too, so it
//!   is in `DT`: it is *settled*. Likewise on the right.
//! - Let the *seam* `B` be the corners of the unsettled triangles of both halves and the hull
//!   points of both halves. Every triangle of `DT` that is not settled has its corners in `B`: a
//!   point of `L` outside `B` has a bounded cell in the Voronoi diagram of `L`, and the discs
//!   centred on that cell through the point stay left of `m` (their right edge is a convex
//!   function of the centre, largest at a cell vertex, which is the circumcentre of a settled
//!   triangle), so the cell is unchanged by `R` and all its triangles are settled.
//! - A triangle of `DT(B)` whose circumcircle reaches both sides of `m` is empty of all points:
//!   if it held a point of `L`, the smallest disc inside the circle, tangent to it at its
//!   rightmost point and through a point of `L`, would be empty of `L` and reach `m`, so that
//!   point would be in `B`, which the circle of a triangle of `DT(B)` cannot hold.
//!
//! So `DT` is the settled triangles of both halves plus the triangles of `DT(B)` whose circle
//! crosses `m` (with [`SLACK`] on each side, which the argument allows). The circle tests are
//! done in floating point; for cocircular points near the seam they could disagree between two
//! equally valid triangulations, so the stitched mesh is checked (every shared edge matched once,
//! one hull ring, Euler's relation) and the caller triangulates in one piece when it fails.
//!
//! Cost: the seam is small for ordinary data (about 3,200 of 1,000,000 uniform random points).
//! Data with many points on its hull is left to the caller: where more than [`HULL_SHARE_MAX`]
//! of a pseudo-random sample lies on the sample's own convex hull (about 2% for uniform points in
//! a square, 100% for points on one circle, `1/k` for `k` concentric rings). For points on one
//! circle the seam is every point and the halves' work is wasted (200,000 points took 0.50 s
//! that way against 0.1 s in one piece); the halves of a few concentric rings are arcs, on which
//! spade's bulk loader slows down sharply (two rings of 100,000 points took 9.1 s split against
//! 1.0 s in one piece; ten rings 1.13 s against 0.42 s; a hundred rings 0.07 s against 0.14 s).

use std::collections::HashMap;

use spade::{Point2, Triangulation as _};

use super::mesh::{Mesh, copy_faces, hull_ring};
use super::{NONE, ScatteredError, Site, Sites, build, certainly_off_line};

/// Slack around the split line in frame coordinates (magnitudes below 1): a circle within it of
/// the line counts as reaching the other side, which only grows the seam.
const SLACK: f64 = 1e-9;

/// Above this share of a sample on its convex hull, the split is not tried (see the module docs).
const HULL_SHARE_MAX: f64 = 0.05;

/// Which half of the points.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Side {
    Left,
    Right,
}

/// What is left of one triangulated half once its settled triangles sit, compacted, at the
/// front of its part of the shared buffers (neighbour indices local to the half, [`NONE`] where
/// the triangle across is unsettled or missing).
struct Half {
    /// How many triangles are settled.
    settled: usize,
    /// The settled triangles' edges with [`NONE`] across: `(triangle, edge)`.
    open: Vec<(u32, u8)>,
    /// The seam points of the half.
    seam: Vec<u32>,
    /// Distinct points in the half.
    vertices: usize,
}

/// Triangulates `sites` in two halves on two threads and returns the mesh and its hull ring.
/// `Ok(None)` when the split does not apply (a half with under three points, or on one line) or
/// the stitched mesh fails its checks; the caller then triangulates in one piece.
pub(super) fn triangulate(sites: Sites<'_>) -> Result<Option<(Mesh, Vec<usize>)>, ScatteredError> {
    if sites.len() < 8 {
        return Ok(None);
    }
    let m = split_line(sites);
    let left_count = sites.iter().filter(|s| s.pos.x < m).count();
    if left_count < 3 || sites.len() - left_count < 3 {
        return Ok(None);
    }
    if hull_share(sites) > HULL_SHARE_MAX {
        return Ok(None);
    }
    // A half on one line would make the other half's work wasted: leave such input to the caller.
    if !spans_a_plane(sites, |s| s.pos.x < m) || !spans_a_plane(sites, |s| s.pos.x >= m) {
        return Ok(None);
    }
    // One pair of buffers for the whole mesh, each half triangulating into its own part: `k`
    // points have at most `2k − 5` triangles, and the final mesh has fewer than `2n`. The zeroed
    // memory is only touched (paged in) by the thread that fills it.
    let left_room = 2 * left_count;
    let mut triangles = vec![[0u32; 3]; 2 * sites.len()];
    let mut neighbors = vec![[0u32; 3]; 2 * sites.len()];
    let (tris_left, tris_right) = triangles.split_at_mut(left_room);
    let (nbs_left, nbs_right) = neighbors.split_at_mut(left_room);
    let (l, r) = std::thread::scope(|scope| {
        let other = std::thread::Builder::new()
            .spawn_scoped(scope, move || half(sites, Side::Left, m, left_count, tris_left, nbs_left));
        let r = half(sites, Side::Right, m, sites.len() - left_count, tris_right, nbs_right);
        let l = match other {
            Ok(handle) => handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
            // No second thread: let the caller work in one piece.
            Err(_) => Ok(None),
        };
        (l, r)
    });
    let (Some(l), Some(r)) = (l?, r?) else {
        return Ok(None);
    };
    stitch(sites, m, Mesh { triangles, neighbors, vertices: l.vertices + r.vertices }, left_room, l, r)
}

/// The median x of a sample of the sites: the halves need not be equal, only close.
fn split_line(sites: Sites<'_>) -> f64 {
    let step = (sites.len() / 4096).max(1);
    let mut xs: Vec<f64> = (0..sites.len()).step_by(step).filter_map(|row| sites.get(row)).map(|s| s.pos.x).collect();
    let mid = xs.len() / 2;
    xs.select_nth_unstable_by(mid, f64::total_cmp).1.to_owned()
}

/// The share of a sample of 1,024 sites (rows picked by Fibonacci hashing, so that no period in
/// the row order aliases with the sample) that lies on the sample's convex hull (Andrew's
/// monotone chain in floating point; an estimate is all that is needed).
pub(super) fn hull_share(sites: Sites<'_>) -> f64 {
    let n = sites.len().max(1) as u64;
    let mut sample: Vec<(f64, f64)> = (0..1024u64)
        .filter_map(|j| sites.get((j.wrapping_mul(0x9e37_79b9_7f4a_7c15) % n) as usize))
        .map(|s| (s.pos.x, s.pos.y))
        .collect();
    sample.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    sample.dedup();
    if sample.len() < 3 {
        return 1.0;
    }
    let turns_left =
        |o: (f64, f64), a: (f64, f64), b: (f64, f64)| (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0) > 0.0;
    let chain = |points: &mut dyn Iterator<Item = (f64, f64)>| {
        let mut chain: Vec<(f64, f64)> = Vec::new();
        for p in points {
            while let [.., o, a] = chain[..] {
                if turns_left(o, a, p) {
                    break;
                }
                chain.pop();
            }
            chain.push(p);
        }
        chain.len().saturating_sub(1)
    };
    let hull = chain(&mut sample.iter().copied()) + chain(&mut sample.iter().rev().copied());
    hull as f64 / sample.len() as f64
}

/// `true` when some site `keep` selects is certainly off the line through the first two distinct
/// ones (floating point with a safe error bound, so a half with almost all points on one line
/// counts as a line). For almost any data the first few sites settle it; for points on one line
/// it costs one pass without exact arithmetic.
fn spans_a_plane(sites: Sites<'_>, keep: impl Fn(&Site) -> bool) -> bool {
    let mut chosen = sites.iter().filter(|s| keep(s));
    let Some(a) = chosen.next() else {
        return false;
    };
    let Some(b) = chosen.by_ref().find(|s| s.pos != a.pos) else {
        return false;
    };
    chosen.any(|c| certainly_off_line(a.pos, b.pos, c.pos))
}

/// Triangulates one half into `triangles` and `neighbors`, and keeps its settled triangles at
/// their front, in order.
fn half(
    sites: Sites<'_>,
    side: Side,
    m: f64,
    count: usize,
    triangles: &mut [[u32; 3]],
    neighbors: &mut [[u32; 3]],
) -> Result<Option<Half>, ScatteredError> {
    let mut part = Vec::with_capacity(count);
    part.extend(sites.iter().filter(|s| (s.pos.x < m) == (side == Side::Left)));
    let Some(dt) = build(part, 1)? else {
        return Ok(None);
    };
    let faces = dt.num_inner_faces();
    let vertices = dt.num_vertices();
    let (Some(triangles), Some(neighbors)) = (triangles.get_mut(..faces), neighbors.get_mut(..faces)) else {
        return Ok(None);
    };
    // The new index of each settled triangle, in order; [`NONE`] for the others.
    let mut index = Vec::with_capacity(faces);
    let mut kept = 0u32;
    copy_faces(&dt, 0, triangles, neighbors, |corners, names| {
        let settled = match side {
            Side::Left => circle_reach(corners, names, m - SLACK) == Reach::Left,
            Side::Right => circle_reach(corners, names, m + SLACK) == Reach::Right,
        };
        index.push(if settled { kept } else { NONE });
        kept += u32::from(settled);
    });
    drop(dt);
    let mut seam = Vec::new();
    let mut open = Vec::new();
    // Compact in place: a settled triangle only moves towards the front.
    let mut write = 0usize;
    for (read, &new_index) in index.iter().enumerate() {
        let (Some(&tri), Some(&nb)) = (triangles.get(read), neighbors.get(read)) else {
            break;
        };
        if new_index == NONE {
            seam.extend_from_slice(&tri);
            continue;
        }
        let mut mapped = [NONE; 3];
        for k in 0..3 {
            if nb[k] == NONE {
                // A hull edge of the half: its ends are seam points.
                seam.push(tri[k]);
                seam.push(tri[(k + 1) % 3]);
            } else {
                mapped[k] = index.get(nb[k] as usize).copied().unwrap_or(NONE);
            }
            if mapped[k] == NONE {
                open.push((write as u32, k as u8));
            }
        }
        if let (Some(t), Some(n)) = (triangles.get_mut(write), neighbors.get_mut(write)) {
            *t = tri;
            *n = mapped;
        }
        write += 1;
    }
    seam.sort_unstable();
    seam.dedup();
    Ok(Some(Half { settled: write, open, seam, vertices }))
}

/// Joins the settled triangles of both halves (the right ones moved down behind the left ones)
/// with the seam triangles whose circles cross the split line, matches the open edges, and checks
/// the result.
fn stitch(
    sites: Sites<'_>,
    m: f64,
    mut mesh: Mesh,
    left_room: usize,
    l: Half,
    r: Half,
) -> Result<Option<(Mesh, Vec<usize>)>, ScatteredError> {
    let seam_sites: Vec<Site> = l.seam.iter().chain(&r.seam).filter_map(|&i| sites.get(i as usize)).collect();
    let Some(dt) = build(seam_sites, 1)? else {
        return Ok(None);
    };
    // Seam triangles whose circle crosses the line are kept, numbered after the settled ones.
    let total = l.settled + r.settled;
    let faces = dt.num_inner_faces();
    let (mut seam_triangles, mut seam_neighbors) = (vec![[0; 3]; faces], vec![[NONE; 3]; faces]);
    let mut index = Vec::with_capacity(faces);
    let mut kept = total as u32;
    copy_faces(&dt, 0, &mut seam_triangles, &mut seam_neighbors, |corners, names| {
        let crossing = circle_reach(corners, names, m - SLACK) != Reach::Left
            && circle_reach(corners, names, m + SLACK) != Reach::Right;
        index.push(if crossing { kept } else { NONE });
        kept += u32::from(crossing);
    });
    drop(dt);

    // Right settled triangles go straight after the left ones, their neighbours shifted.
    let shift = l.settled as u32;
    let right = left_room..left_room + r.settled;
    if right.end > mesh.triangles.len() {
        return Ok(None);
    }
    mesh.triangles.copy_within(right.clone(), l.settled);
    mesh.neighbors.copy_within(right, l.settled);
    for nb in mesh.neighbors.get_mut(l.settled..total).unwrap_or_default() {
        *nb = nb.map(|n| if n == NONE { NONE } else { n + shift });
    }
    mesh.triangles.truncate(total);
    mesh.neighbors.truncate(total);
    let mut open = l.open;
    open.extend(r.open.iter().map(|&(t, k)| (t + shift, k)));

    for ((tri, nb), &new_index) in seam_triangles.iter().zip(&seam_neighbors).zip(&index) {
        if new_index == NONE {
            continue;
        }
        let t = mesh.triangles.len() as u32;
        let mapped = nb.map(|n| if n == NONE { NONE } else { index.get(n as usize).copied().unwrap_or(NONE) });
        for (k, &n) in mapped.iter().enumerate() {
            if n == NONE {
                open.push((t, k as u8));
            }
        }
        mesh.triangles.push(*tri);
        mesh.neighbors.push(mapped);
    }

    // Match each open edge with its reverse; what stays unmatched is the hull.
    let mut by_edge: HashMap<(u32, u32), u32> = HashMap::with_capacity(open.len());
    let mut ends = Vec::with_capacity(open.len());
    for &(t, k) in &open {
        let Some(tri) = mesh.triangles.get(t as usize) else {
            return Ok(None);
        };
        let key = (tri[k as usize % 3], tri[(k as usize + 1) % 3]);
        if by_edge.insert(key, t).is_some() {
            // The same directed edge twice: two triangles overlap.
            return Ok(None);
        }
        ends.push(key);
    }
    let mut hull_edges = Vec::new();
    for (&(t, k), &(a, b)) in open.iter().zip(&ends) {
        match (by_edge.get(&(b, a)), mesh.neighbors.get_mut(t as usize)) {
            (Some(&across), Some(nb)) => nb[k as usize % 3] = across,
            _ => hull_edges.push((a as usize, b as usize)),
        }
    }
    let Some(hull) = hull_ring(&hull_edges) else {
        return Ok(None);
    };
    Ok(mesh.euler_holds(hull.len()).then_some((mesh, hull)))
}

/// Where the circle through a triangle's corners lies against the line `x = line`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Reach {
    /// Wholly left of it.
    Left,
    /// Wholly right of it.
    Right,
    /// Touching or crossing it, or too thin a triangle for floating point to tell.
    Across,
}

/// Where the circle through the corners lies against `x = line`, decided without division from
/// the corners in increasing order of their names, so the same triangle gets the same answer in
/// whichever triangulation it is found. With the circle's centre `a + n/d` and radius `|n|/|d|`
/// relative to the first corner `a`, and `e = (line − a.x)·d − n.x`, it is wholly left when
/// `e·d > 0` and `e² > |n|²`, wholly right when `e·d < 0` and `e² > |n|²`.
fn circle_reach(corners: [Point2<f64>; 3], names: [u32; 3], line: f64) -> Reach {
    let mut order = [0usize, 1, 2];
    order.sort_unstable_by_key(|&k| names[k]);
    let [a, b, c] = order.map(|k| corners[k]);
    let (bx, by) = (b.x - a.x, b.y - a.y);
    let (cx, cy) = (c.x - a.x, c.y - a.y);
    let d = 2.0 * (bx * cy - by * cx);
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    let nx = cy * b2 - by * c2;
    let ny = bx * c2 - cx * b2;
    let e = (line - a.x) * d - nx;
    if e * e > nx * nx + ny * ny {
        if e * d > 0.0 {
            return Reach::Left;
        }
        if e * d < 0.0 {
            return Reach::Right;
        }
    }
    Reach::Across
}
