//! Filled bands, built from contour lines rather than a second marching pass.
//!
//! The region of band `b`, `R = {lower <= f < upper}`, is bounded by three kinds of pieces: lines
//! of the lower level (oriented with `f >= lower`, hence `R`, on their left), lines of the upper
//! level walked backwards (so `f < upper` is on their left), and stretches of the boundary of the
//! non-hole domain. Closed lines are rings as they are. Open lines end on the domain boundary;
//! walking each boundary loop with the domain on the left, the open pieces' ends and starts
//! alternate, and the boundary between an end and the next start lies in `R`, so joining each
//! end to the next start along the loop closes the rings. A boundary loop with no piece ends
//! that lies wholly in the band is a ring by itself.
//!
//! Every ring has `R` on its left, so outer rings come out counter-clockwise and holes
//! clockwise. Each hole is given to its polygon by a ray cast straight down from its lowest
//! crossing with a vertical grid line: the first ring the ray meets bounds the same connected
//! piece of `R`; if that ring is itself a hole, the hole shares its polygon.
//!
//! Adjacent bands use the very same lines (same points, same saddle decisions), so the bands
//! tile the non-hole domain exactly.

use super::lines::{Field, RawLine, dedup_points, trace_levels};
use super::{Band, ContourError, Saddle};
use crate::enrich::grid::Grid;

type Ring = Vec<(f64, f64)>;

/// Bands for cleaned levels (sorted, distinct, finite, at most `MAX_LEVELS`).
pub(super) fn contour_bands(grid: &Grid, levels: &[f64], saddle: Saddle) -> Result<Vec<Band>, ContourError> {
    let mut bands: Vec<Band> = levels
        .windows(2)
        .filter_map(|w| match *w {
            [lower, upper] => Some(Band { lower, upper, polygons: Vec::new() }),
            _ => None,
        })
        .collect();
    if bands.is_empty() || grid.nx() < 2 || grid.ny() < 2 {
        return Ok(bands);
    }
    let field = Field::new(grid, levels, true);
    let traced = trace_levels(&field, levels, true, saddle)?;
    let loops = BoundaryLoops::new(&field);
    for (b, band) in bands.iter_mut().enumerate() {
        let (Some(lower), Some(upper)) = (traced.get(b), traced.get(b + 1)) else {
            break;
        };
        let rings = band_rings(&field, &loops, lower, upper, b);
        band.polygons = nest(grid.xs(), rings);
    }
    Ok(bands)
}

/// A position on a boundary loop: loop, edge position along it, and order within the edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Spot {
    lp: u32,
    pos: u32,
    sub: u8,
}

/// One closed boundary of the non-hole domain, walked with the domain on its left.
struct Loop {
    /// `(cell, local edge)` pairs in walking order.
    edges: Vec<(u32, u8)>,
    /// Smallest and largest node class on the loop.
    lo: u16,
    hi: u16,
}

/// All boundary loops of a field, with a lookup from edge id to loop position.
struct BoundaryLoops {
    loops: Vec<Loop>,
    /// `(edge id, loop, position)`, sorted by edge id.
    index: Vec<(u32, u32, u32)>,
}

impl BoundaryLoops {
    fn new(field: &Field<'_>) -> BoundaryLoops {
        let (nx, ny) = (field.nx, field.ny);
        let mut starts: Vec<(usize, u8)> = Vec::new();
        if field.has_holes {
            for j in 0..ny - 1 {
                for i in 0..nx - 1 {
                    let c = j * nx + i;
                    if !field.cell_valid(c) {
                        continue;
                    }
                    for l in 0..4u8 {
                        if is_boundary(field, c, i, j, l) {
                            starts.push((c, l));
                        }
                    }
                }
            }
        } else {
            starts.push((0, 0));
        }
        let mut seen = vec![0u64; field.n_edges().div_ceil(64)];
        let mut loops = Vec::new();
        let mut index = Vec::new();
        for (c, l) in starts {
            let id = field.edge_id(c, c / nx, l) as usize;
            if seen.get(id / 64).is_some_and(|w| w & (1u64 << (id % 64)) != 0) {
                continue;
            }
            let lp = walk_loop(field, c, l, &mut seen);
            for (pos, &(c, l)) in lp.edges.iter().enumerate() {
                let c = c as usize;
                index.push((field.edge_id(c, c / nx, l), loops.len() as u32, pos as u32));
            }
            loops.push(lp);
        }
        index.sort_unstable();
        BoundaryLoops { loops, index }
    }

    /// Loop and position of the boundary edge `id`.
    fn locate(&self, id: u32) -> Option<(u32, u32)> {
        let k = self.index.partition_point(|e| e.0 < id);
        self.index.get(k).filter(|e| e.0 == id).map(|e| (e.1, e.2))
    }
}

/// Whether local edge `l` of valid cell `(c, i, j)` borders the grid edge or a hole cell.
fn is_boundary(field: &Field<'_>, c: usize, i: usize, j: usize, l: u8) -> bool {
    match field.across(c, i, j, l) {
        None => true,
        Some((c2, ..)) => !field.cell_valid(c2),
    }
}

/// Walks the boundary loop through edge `(c, l)`, turning left wherever possible (so two valid
/// cells touching only at a corner are kept apart), marking its edges in `seen`.
fn walk_loop(field: &Field<'_>, c0: usize, l0: u8, seen: &mut [u64]) -> Loop {
    let nx = field.nx;
    let mut edges = Vec::new();
    let (mut lo, mut hi) = (u16::MAX, 0u16);
    let (mut c, mut l) = (c0, l0);
    let cap = field.n_edges();
    loop {
        let id = field.edge_id(c, c / nx, l) as usize;
        if let Some(w) = seen.get_mut(id / 64) {
            *w |= 1u64 << (id % 64);
        }
        edges.push((c as u32, l));
        let class = field.cls(field.edge_nodes(c, l).0);
        lo = lo.min(class);
        hi = hi.max(class);
        // The edge ends at a node v; the candidates leaving v, from sharpest left turn on, are
        // edge l+1 of this cell, then (moving across it) the same-numbered edge l of the
        // neighbour, and so on round v.
        let (mut cc, mut ci, mut cj, mut ll) = (c, c % nx, c / nx, (l + 1) % 4);
        let mut next = None;
        for _ in 0..4 {
            match field.across(cc, ci, cj, ll) {
                Some((c2, i2, j2, _)) if field.cell_valid(c2) => {
                    (cc, ci, cj, ll) = (c2, i2, j2, (ll + 3) % 4);
                }
                _ => {
                    next = Some((cc, ll));
                    break;
                }
            }
        }
        let Some((nc, nl)) = next else { break };
        if (nc, nl) == (c0, l0) || edges.len() >= cap {
            break;
        }
        let nid = field.edge_id(nc, nc / nx, nl) as usize;
        if seen.get(nid / 64).is_some_and(|w| w & (1u64 << (nid % 64)) != 0) {
            break; // cannot happen on a consistent walk; stops rather than loops
        }
        (c, l) = (nc, nl);
    }
    Loop { edges, lo, hi }
}

impl Loop {
    /// Whether the loop turns at the end of its edge `q`.
    fn turns_after(&self, q: usize) -> bool {
        let n = self.edges.len();
        match (self.edges.get(q), self.edges.get((q + 1) % n.max(1))) {
            (Some(a), Some(b)) => a.1 != b.1,
            _ => false,
        }
    }

    /// Coordinates of the node where loop edge `q` ends.
    fn end_point(&self, field: &Field<'_>, q: usize) -> (f64, f64) {
        let Some(&(c, l)) = self.edges.get(q) else {
            return (f64::NAN, f64::NAN);
        };
        let v = field.edge_nodes(c as usize, l).1;
        field.node(v % field.nx, v / field.nx)
    }

    /// Appends the loop's corners met walking from `from` to `to` (exclusive of the edges'
    /// crossing points themselves).
    fn push_path(&self, field: &Field<'_>, from: Spot, to: Spot, out: &mut Ring) {
        let n = self.edges.len();
        if n == 0 {
            return;
        }
        let (a, b) = (from.pos as usize % n, to.pos as usize % n);
        let mut count = (b + n - a) % n;
        if count == 0 && to.sub < from.sub {
            count = n;
        }
        for q in 0..count {
            let e = (a + q) % n;
            if self.turns_after(e) {
                out.push(self.end_point(field, e));
            }
        }
    }
}

/// An open line used as a piece of a band ring (upper-level lines are walked backwards).
struct Piece<'r> {
    line: &'r RawLine,
    reversed: bool,
}

/// Rings of band `b` (between levels `b` and `b + 1`), all with the band on their left.
fn band_rings(field: &Field<'_>, loops: &BoundaryLoops, lower: &[RawLine], upper: &[RawLine], b: usize) -> Vec<Ring> {
    let mut rings: Vec<Ring> = Vec::new();
    let mut pieces: Vec<Piece<'_>> = Vec::new();
    // (spot, piece, is_start)
    let mut ends: Vec<(Spot, u32, bool)> = Vec::new();
    for (lines, is_lower) in [(lower, true), (upper, false)] {
        for line in lines {
            if line.closed {
                let mut ring = line.points.clone();
                if !is_lower {
                    ring.reverse();
                }
                rings.push(ring);
                continue;
            }
            let (first, last) =
                (spot(field, loops, line.first_edge, is_lower), spot(field, loops, line.last_edge, is_lower));
            let (Some(first), Some(last)) = (first, last) else {
                // Not on the boundary: cannot happen for an open line; keep its area anyway.
                rings.push(line.points.clone());
                continue;
            };
            let p = pieces.len() as u32;
            let (start, end) = if is_lower { (first, last) } else { (last, first) };
            ends.push((start, p, true));
            ends.push((end, p, false));
            pieces.push(Piece { line, reversed: !is_lower });
        }
    }

    // Link every piece's end to the next piece start along its loop.
    ends.sort_unstable_by_key(|e| e.0);
    let mut link: Vec<Option<(u32, Spot, Spot)>> = vec![None; pieces.len()];
    let mut g0 = 0;
    while g0 < ends.len() {
        let lp = ends.get(g0).map_or(0, |e| e.0.lp);
        let g1 = g0 + ends[g0..].iter().take_while(|e| e.0.lp == lp).count();
        for q in g0..g1 {
            let (Some(&(end, p, false)), Some(&(start, np, true))) =
                (ends.get(q), ends.get(if q + 1 < g1 { q + 1 } else { g0 }))
            else {
                continue;
            };
            if let Some(slot) = link.get_mut(p as usize) {
                *slot = Some((np, end, start));
            }
        }
        g0 = g1.max(g0 + 1);
    }

    let mut used = vec![false; pieces.len()];
    for p0 in 0..pieces.len() {
        if used.get(p0).copied().unwrap_or(true) {
            continue;
        }
        let mut ring = Ring::new();
        let mut p = p0;
        while let (Some(piece), Some(false)) = (pieces.get(p), used.get(p).copied()) {
            if let Some(u) = used.get_mut(p) {
                *u = true;
            }
            if piece.reversed {
                ring.extend(piece.line.points.iter().rev());
            } else {
                ring.extend_from_slice(&piece.line.points);
            }
            let Some(Some((np, end, start))) = link.get(p).copied() else {
                break;
            };
            if let Some(lp) = loops.loops.get(end.lp as usize) {
                lp.push_path(field, end, start, &mut ring);
            }
            p = np as usize;
        }
        rings.push(ring);
    }

    // Boundary loops lying wholly in the band.
    let class = (b + 1) as u16;
    for lp in &loops.loops {
        if lp.lo == class && lp.hi == class {
            let ring: Ring =
                (0..lp.edges.len()).filter(|&q| lp.turns_after(q)).map(|q| lp.end_point(field, q)).collect();
            rings.push(ring);
        }
    }

    for ring in &mut rings {
        dedup_points(ring, true);
    }
    rings.retain(|r| r.len() >= 3);
    rings
}

/// Where a line of the lower (`is_lower`) or upper level meets the boundary on edge `id`.
fn spot(field: &Field<'_>, loops: &BoundaryLoops, id: u32, is_lower: bool) -> Option<Spot> {
    let (lp, pos) = loops.locate(id)?;
    let &(c, l) = loops.loops.get(lp as usize)?.edges.get(pos as usize)?;
    let (a, b) = field.edge_nodes(c as usize, l);
    // Along the loop direction, the lower crossing comes first where the value increases.
    let increasing = field.cls(a) < field.cls(b);
    Some(Spot { lp, pos, sub: u8::from(is_lower != increasing) })
}

/// Twice the signed area of a ring (positive when counter-clockwise), relative to its first
/// point to limit cancellation.
fn signed_area2(ring: &[(f64, f64)]) -> f64 {
    let Some(&(x0, y0)) = ring.first() else {
        return 0.0;
    };
    let n = ring.len();
    let mut sum = 0.0;
    for k in 0..n {
        let (Some(&(ax, ay)), Some(&(bx, by))) = (ring.get(k), ring.get((k + 1) % n)) else {
            continue;
        };
        sum += (ax - x0) * (by - y0) - (bx - x0) * (ay - y0);
    }
    sum
}

/// Even-odd point-in-ring test.
fn contains(ring: &[(f64, f64)], (px, py): (f64, f64)) -> bool {
    let n = ring.len();
    let mut inside = false;
    for k in 0..n {
        let (Some(&(ax, ay)), Some(&(bx, by))) = (ring.get(k), ring.get((k + 1) % n)) else {
            continue;
        };
        if (ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay) {
            inside = !inside;
        }
    }
    inside
}

/// Where a ring crosses the vertical grid lines: calls `visit(m, y)` for every segment crossing
/// `x = xs[m]`, counting a point exactly on the line as being to its right.
fn for_each_crossing(ring: &[(f64, f64)], xs: &[f64], mut visit: impl FnMut(usize, f64)) {
    let n = ring.len();
    for k in 0..n {
        let (Some(&(ax, ay)), Some(&(bx, by))) = (ring.get(k), ring.get((k + 1) % n)) else {
            continue;
        };
        if ax == bx {
            continue;
        }
        let (lo, hi) = if ax < bx { (ax, bx) } else { (bx, ax) };
        let mut m = xs.partition_point(|&x| x <= lo);
        while let Some(&x) = xs.get(m) {
            if x > hi {
                break;
            }
            let y = if x == ax {
                ay
            } else if x == bx {
                by
            } else {
                ay + (x - ax) * (by - ay) / (bx - ax)
            };
            visit(m, y);
            m += 1;
        }
    }
}

/// Groups rings into polygons: each counter-clockwise ring is an outer ring, each clockwise ring
/// a hole of the polygon found by a downward ray (module docs). Rings of zero area are dropped.
fn nest(xs: &[f64], rings: Vec<Ring>) -> Vec<Vec<Ring>> {
    let areas: Vec<f64> = rings.iter().map(|r| signed_area2(r)).collect();
    let is_hole = |r: usize| areas.get(r).is_some_and(|&a| a < 0.0);
    let holes: Vec<usize> = (0..rings.len()).filter(|&r| is_hole(r)).collect();
    let mut parent: Vec<Option<usize>> = vec![None; rings.len()];

    if !holes.is_empty() {
        // Lowest crossing of each hole with a vertical grid line.
        let mut lowest: Vec<Option<(usize, f64)>> = vec![None; rings.len()];
        let mut needed = vec![false; xs.len()];
        for &h in &holes {
            let mut best: Option<(usize, f64)> = None;
            if let Some(ring) = rings.get(h) {
                for_each_crossing(ring, xs, |m, y| {
                    if best.is_none_or(|(_, by)| y < by) {
                        best = Some((m, y));
                    }
                });
            }
            if let Some((m, _)) = best
                && let Some(n) = needed.get_mut(m)
            {
                *n = true;
            }
            if let Some(slot) = lowest.get_mut(h) {
                *slot = best;
            }
        }
        // Every ring's crossings with those lines, sorted along each line.
        let mut hits: Vec<(usize, f64, usize)> = Vec::new();
        for (r, ring) in rings.iter().enumerate() {
            if areas.get(r).is_some_and(|&a| a != 0.0) {
                for_each_crossing(ring, xs, |m, y| {
                    if needed.get(m).copied().unwrap_or(false) {
                        hits.push((m, y, r));
                    }
                });
            }
        }
        hits.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        // The ring just below each hole's lowest crossing.
        let mut below: Vec<Option<usize>> = vec![None; rings.len()];
        for &h in &holes {
            let Some(Some((m, y))) = lowest.get(h).copied() else {
                continue;
            };
            let mut q = hits.partition_point(|e| e.0 < m || (e.0 == m && e.1 < y));
            while hits.get(q).is_some_and(|e| e.0 == m && e.1 == y && e.2 != h) {
                q += 1;
            }
            let found =
                hits.get(..q).unwrap_or(&[]).iter().rev().take_while(|e| e.0 == m).find(|e| e.2 != h).map(|e| e.2);
            if let Some(slot) = below.get_mut(h) {
                *slot = found;
            }
        }
        // Follow holes down to an outer ring.
        for &h in &holes {
            let mut r = h;
            let mut steps = 0;
            while is_hole(r) && steps <= rings.len() {
                match below.get(r).copied().flatten() {
                    Some(next) => r = next,
                    None => break,
                }
                steps += 1;
            }
            let found = if is_hole(r) {
                // Fallback for degenerate input: the smallest outer ring holding the hole.
                rings.get(h).and_then(|ring| ring.first()).and_then(|&p| {
                    (0..rings.len())
                        .filter(|&o| areas.get(o).is_some_and(|&a| a > 0.0))
                        .filter(|&o| rings.get(o).is_some_and(|ring| contains(ring, p)))
                        .min_by(|&a, &b| {
                            let area = |r: usize| areas.get(r).copied().unwrap_or(f64::INFINITY);
                            area(a).total_cmp(&area(b))
                        })
                })
            } else {
                Some(r)
            };
            if let Some(slot) = parent.get_mut(h) {
                *slot = found;
            }
        }
    }

    let mut slot_of: Vec<Option<usize>> = vec![None; rings.len()];
    let mut polygons: Vec<Vec<Ring>> = Vec::new();
    let mut rings: Vec<Option<Ring>> = rings.into_iter().map(Some).collect();
    for (r, ring) in rings.iter_mut().enumerate() {
        if areas.get(r).is_some_and(|&a| a > 0.0)
            && let Some(ring) = ring.take()
        {
            if let Some(s) = slot_of.get_mut(r) {
                *s = Some(polygons.len());
            }
            polygons.push(vec![ring]);
        }
    }
    for h in holes {
        let target = parent.get(h).copied().flatten().and_then(|o| slot_of.get(o).copied().flatten());
        if let (Some(t), Some(ring)) = (target, rings.get_mut(h).and_then(Option::take))
            && let Some(poly) = polygons.get_mut(t)
        {
            poly.push(ring);
        }
    }
    polygons
}
