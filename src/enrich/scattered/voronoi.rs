//! Voronoi (Dirichlet) cells, clipped to a rectangle.
//!
//! The cell of a point `p` is the set of places at least as close to `p` as to any other point:
//! the intersection of the half-planes `{x : |x − p| <= |x − q|}` over all other points `q`. Only
//! the Delaunay neighbours of `p` contribute a side (every Voronoi edge is dual to a Delaunay
//! edge), so each cell is the clip rectangle cut by one half-plane per neighbour, a convex
//! polygon clipping in `O(degree²)`. Collinear (degenerate) input has no triangles; its points,
//! sorted along the line, have the previous and next point as neighbours.
//!
//! The work happens in a frame scaled by a power of two (exact) so that the points and the
//! rectangle have magnitudes at most 1, and relative to the cell's own point, which keeps
//! bisector arithmetic well inside the `f64` range.

use super::mesh::point_neighbours;
use super::{Frame, ScatteredError, Triangulation};

type Ring = Vec<(f64, f64)>;

/// One cell per point, clipped to `clip = (xmin, ymin, xmax, ymax)`.
pub(super) fn cells(tin: &Triangulation, clip: (f64, f64, f64, f64)) -> Result<Vec<Ring>, ScatteredError> {
    let (xmin, ymin, xmax, ymax) = clip;
    let finite = [xmin, ymin, xmax, ymax].iter().all(|v| v.is_finite());
    if !(finite && xmin < xmax && ymin < ymax) {
        return Err(ScatteredError::InvalidClip { clip });
    }
    let max_abs =
        tin.points.iter().fold([xmin, ymin, xmax, ymax].iter().fold(0.0f64, |m, v| m.max(v.abs())), |m, p| {
            m.max(p.0.abs()).max(p.1.abs())
        });
    let frame = Frame::for_magnitude(max_abs);
    let down = |p: (f64, f64)| (frame.down.apply(p.0), frame.down.apply(p.1));
    let sites: Vec<(f64, f64)> = tin.points.iter().map(|&p| down(p)).collect();
    let rect = [down((xmin, ymin)), down((xmax, ymin)), down((xmax, ymax)), down((xmin, ymax))];

    let mut out: Vec<Ring> = vec![Vec::new(); sites.len()];
    let mut neighbours: Vec<usize> = Vec::new();
    let cell = |i: usize, neighbours: &[usize]| -> Option<Ring> {
        let &p = sites.get(i)?;
        let mut poly: Ring = rect.iter().map(|&(x, y)| (x - p.0, y - p.1)).collect();
        for &j in neighbours {
            let Some(&q) = sites.get(j) else { continue };
            poly = clip_half_plane(&poly, (q.0 - p.0, q.1 - p.1));
            if poly.is_empty() {
                break;
            }
        }
        Some(poly.into_iter().map(|(x, y)| (frame.to_data(x + p.0), frame.to_data(y + p.1))).collect())
    };

    if tin.triangles.is_empty() {
        // Collinear (or fewer than three points): neighbours along the line.
        let mut along: Vec<usize> = (0..sites.len()).collect();
        along.sort_by(|&a, &b| {
            let (pa, pb) = (sites.get(a).copied().unwrap_or_default(), sites.get(b).copied().unwrap_or_default());
            pa.0.total_cmp(&pb.0).then(pa.1.total_cmp(&pb.1))
        });
        for (k, &i) in along.iter().enumerate() {
            neighbours.clear();
            neighbours.extend(k.checked_sub(1).and_then(|k| along.get(k)).copied());
            neighbours.extend(along.get(k + 1).copied());
            if let (Some(ring), Some(slot)) = (cell(i, &neighbours), out.get_mut(i)) {
                *slot = ring;
            }
        }
    } else {
        let (offsets, list) = point_neighbours(&tin.triangles, &tin.neighbors, sites.len());
        for (i, (slot, bounds)) in out.iter_mut().zip(offsets.windows(2)).enumerate() {
            neighbours.clear();
            if let (Some(&from), Some(&to)) = (bounds.first(), bounds.get(1)) {
                neighbours.extend(list.get(from..to).unwrap_or_default().iter().map(|&j| j as usize));
            }
            if let Some(ring) = cell(i, &neighbours) {
                *slot = ring;
            }
        }
    }
    Ok(out)
}

/// The part of the convex polygon `poly` (coordinates relative to the cell's point, which is
/// the origin) on the origin's side of the bisector between the origin and `d`:
/// `{x : x·d <= |d|²/2}`. Points on the bisector are kept.
fn clip_half_plane(poly: &[(f64, f64)], d: (f64, f64)) -> Vec<(f64, f64)> {
    let half = 0.5 * (d.0 * d.0 + d.1 * d.1);
    if half == 0.0 {
        return poly.to_vec();
    }
    let side = |p: (f64, f64)| p.0 * d.0 + p.1 * d.1 - half;
    let mut out = Vec::with_capacity(poly.len() + 1);
    let Some(&last) = poly.last() else {
        return out;
    };
    let (mut prev, mut f_prev) = (last, side(last));
    for &cur in poly {
        let f_cur = side(cur);
        if f_cur <= 0.0 {
            if f_prev > 0.0 {
                out.push(intersect(prev, f_prev, cur, f_cur));
            }
            out.push(cur);
        } else if f_prev <= 0.0 {
            out.push(intersect(prev, f_prev, cur, f_cur));
        }
        prev = cur;
        f_prev = f_cur;
    }
    out.dedup();
    if out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    if out.len() < 3 { Vec::new() } else { out }
}

/// Where the segment from `a` (side value `fa`) to `b` (side value `fb`, of the other sign)
/// meets the bisector.
fn intersect(a: (f64, f64), fa: f64, b: (f64, f64), fb: f64) -> (f64, f64) {
    let t = (fa / (fa - fb)).clamp(0.0, 1.0);
    (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
}
