//! Marching cubes with the topology of the trilinear interpolant (MC33's case analysis, derived
//! procedurally): each cell's triangulation is built from its boundary loops ([`surface`]), the
//! interior connectivity of its corners ([`interior`]) and a triangulation of disks and tubes,
//! and memoised per configuration key so that it works as a generated table.
//!
//! [`surface`]: super::surface
//! [`interior`]: super::interior

use std::collections::HashMap;

use super::IsoError;
use super::cube::{
    add, cross, dot, edge_corners, edge_faces, edge_midpoint, norm, scale, sub, trilinear, trilinear_gradient,
};
use super::interior;
use super::mesh::Builder;
use super::surface::{Boundary, boundary, face_decisions, find, inside_mask, union};

/// Local vertex ids of a template: `0..12` the crossing on that cube edge, `CENTRE + n` the
/// `n`-th interior vertex of the cell.
pub(super) const CENTRE: u8 = 12;

/// One cell's triangulation for one configuration.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct Template {
    /// Triangles over local vertex ids, counter-clockwise seen from outside (`g < 0`).
    pub triangles: Vec<[u8; 3]>,
    /// For each interior vertex, the crossed edges (one loop) it is the centre of.
    pub centres: Vec<Vec<u8>>,
    /// Tubes, each as its two loops; stitched per cell by [`stitch`] with the crossings' real
    /// positions, which decide the best band.
    pub tubes: Vec<[Vec<u8>; 2]>,
}

/// How a cell's loops join into surface pieces: for each loop, the first loop of its piece.
/// Loops `l` with `joins[l] == l` and no other loop pointing at them bound disks; two loops in
/// one piece are the ends of a tube.
pub(super) fn joins(b: &Boundary, g: &[f64; 8]) -> Vec<u8> {
    let identity: Vec<u8> = (0..b.loops.len() as u8).collect();
    if b.loops.len() < 2 {
        return identity;
    }
    // Corners joined in the cell: on its surface (patches) or through its interior.
    let through = interior::components(g);
    let mut parent: [u8; 8] = std::array::from_fn(|c| c as u8);
    for (c, (patch, inner)) in b.patches.iter().zip(through).enumerate() {
        union(&mut parent, c, *patch as usize);
        union(&mut parent, c, inner as usize);
    }
    let group: [u8; 8] = std::array::from_fn(|c| find(&mut parent, c) as u8);
    let key = |l: usize| b.sides.get(l).map(|s| (group[s[0] as usize], group[s[1] as usize]));
    let pieces: Vec<u8> = (0..b.loops.len()).map(|l| (0..=l).find(|&m| key(m) == key(l)).unwrap_or(l) as u8).collect();
    // The cell cut by the surface is a tree of regions and pieces: #pieces = #regions − 1.
    let mut regions = group.to_vec();
    regions.sort_unstable();
    regions.dedup();
    let distinct = pieces.iter().enumerate().filter(|&(l, &p)| p as usize == l).count();
    let largest = (0..b.loops.len()).map(|l| pieces.iter().filter(|&&p| p as usize == l).count()).max();
    if distinct + 1 != regions.len() || largest > Some(2) {
        return identity;
    }
    pieces
}

/// The template for a boundary and its joins.
pub(super) fn build(b: &Boundary, joins: &[u8]) -> Template {
    let mut t = Template::default();
    for (l, lp) in b.loops.iter().enumerate() {
        let partners: Vec<usize> = (0..b.loops.len()).filter(|&m| m != l && joins.get(m) == Some(&(l as u8))).collect();
        if joins.get(l) != Some(&(l as u8)) {
            continue; // the far end of a tube, made with its first loop
        }
        match partners.as_slice() {
            [m] => match b.loops.get(*m) {
                Some(other) => t.tubes.push([lp.clone(), other.clone()]),
                None => disk(&mut t, lp),
            },
            _ => disk(&mut t, lp),
        }
        // A loop listed as the far end of a tube that had no first loop cannot happen; the
        // `joins` of [`joins`] always point at the first loop.
    }
    t
}

fn dist(a: u8, b: u8) -> f64 {
    norm(sub(edge_midpoint(a as usize), edge_midpoint(b as usize)))
}

/// A disk spanning loop `lp`: one triangle, ears cut off along the shortest diagonals that do
/// not lie on a cube face (up to six crossings), or a fan around an interior vertex.
fn disk(t: &mut Template, lp: &[u8]) {
    let n = lp.len();
    if n < 3 {
        return;
    }
    if n <= 6 {
        let mut poly = lp.to_vec();
        let mut tris = Vec::new();
        while poly.len() > 3 {
            let m = poly.len();
            let ear = (0..m)
                .filter(|&i| edge_faces(poly[(i + m - 1) % m] as usize) & edge_faces(poly[(i + 1) % m] as usize) == 0)
                .min_by(|&i, &j| {
                    let d = |i: usize| dist(poly[(i + m - 1) % m], poly[(i + 1) % m]);
                    d(i).total_cmp(&d(j)).then(i.cmp(&j))
                });
            let Some(i) = ear else { break };
            tris.push([poly[(i + m - 1) % m], poly[i], poly[(i + 1) % m]]);
            poly.remove(i);
        }
        if poly.len() == 3 {
            tris.push([poly[0], poly[1], poly[2]]);
            t.triangles.extend(tris);
            return;
        }
    }
    let c = CENTRE + t.centres.len() as u8;
    t.centres.push(lp.to_vec());
    for i in 0..n {
        t.triangles.push([c, lp[i], lp[(i + 1) % n]]);
    }
}

/// The band of least area between loops `a` and `b` (crossing positions `pos`), as triangles
/// over their vertices: `a` walked forwards and `b` backwards (as boundaries of one annulus they
/// run opposite ways), one triangle per step on either loop. A band is a cyclic sequence of
/// steps with distinct rungs; cut where a step along `b` is followed by one along `a`, it is a
/// walk from rung `(a[i0], c[k0])` that starts along `a`, ends along `b` and never stands on
/// rung `(a[i0], c[k0])` in between (which would pinch the band shut). Every start is tried and
/// a dynamic programme over the walks finds the least total area. No rung joins two crossings
/// on one cube face: the neighbouring cell may join them too, and the edge would have four
/// triangles. Empty when there is no such band, or (with `clean_only`) none that does not cut
/// itself.
pub(super) fn stitch(a: &[u8], b: &[u8], pos: &dyn Fn(u8) -> [f64; 3], clean_only: bool) -> Vec<[u8; 3]> {
    let c: Vec<u8> = b.iter().rev().copied().collect();
    let (m, n) = (a.len(), c.len());
    if m == 0 || n == 0 {
        return Vec::new();
    }
    let area = |p: u8, q: u8, r: u8| 0.5 * norm(cross(sub(pos(q), pos(p)), sub(pos(r), pos(p))));
    let mut bands: Vec<(f64, Vec<[u8; 3]>)> = Vec::new();
    for (i0, k0) in (0..m).flat_map(|i| (0..n).map(move |k| (i, k))) {
        let at = |i: usize| a[(i0 + i) % m];
        let ct = |k: usize| c[(k0 + k) % n];
        if on_face(at(0), ct(0)) {
            continue;
        }
        // cost[i][k]: least area reaching rung (i, k); step[i][k]: whether it came along `a`.
        let width = n + 1;
        let mut cost = vec![f64::INFINITY; (m + 1) * width];
        let mut along_a = vec![false; (m + 1) * width];
        cost[0] = 0.0;
        for i in 0..=m {
            for k in 0..=n {
                let here = i * width + k;
                // The first step goes along `a`, the last along `b`, and rung (m, 0) is the
                // start again.
                // A rung on a cube face would be an edge the neighbouring cell may use too.
                let forbidden = (i == m && k == 0) || (i == 0 && k > 0) || on_face(at(i), ct(k));
                if here == 0 || forbidden {
                    continue;
                }
                if i > 0 && !(i == m && k == n) {
                    let prev = (i - 1) * width + k;
                    let v = cost[prev] + area(at(i - 1), at(i), ct(k));
                    if v < cost[here] {
                        cost[here] = v;
                        along_a[here] = true;
                    }
                }
                if k > 0 {
                    let prev = i * width + k - 1;
                    let v = cost[prev] + area(at(i), ct(k), ct(k - 1));
                    if v < cost[here] {
                        cost[here] = v;
                        along_a[here] = false;
                    }
                }
            }
        }
        let total = cost[m * width + n];
        if !total.is_finite() {
            continue;
        }
        let mut tris = Vec::with_capacity(m + n);
        let (mut i, mut k) = (m, n);
        while i > 0 || k > 0 {
            if along_a[i * width + k] {
                tris.push([at(i - 1), at(i), ct(k)]);
                i -= 1;
            } else {
                tris.push([at(i), ct(k), ct(k - 1)]);
                k -= 1;
            }
        }
        tris.reverse();
        bands.push((total, tris));
    }
    // The least area among the bands that do not cut themselves, else (unless `clean_only`)
    // the least area.
    bands.sort_by(|x, y| x.0.total_cmp(&y.0));
    let clean = bands.iter().position(|(_, tris)| !self_crossing(tris, pos));
    let least = if bands.is_empty() || clean_only { None } else { Some(0) };
    match clean.or(least) {
        Some(n) => bands.swap_remove(n).1,
        None => Vec::new(),
    }
}

/// Whether local vertices `a` and `b` are crossings on a common cube face.
fn on_face(a: u8, b: u8) -> bool {
    a < CENTRE && b < CENTRE && edge_faces(a as usize) & edge_faces(b as usize) != 0
}

/// Whether two of `tris` that share no vertex meet (separating axis test over the triangles'
/// normals and the cross products of their edges; a gap of 1e-12 separates).
fn self_crossing(tris: &[[u8; 3]], pos: &dyn Fn(u8) -> [f64; 3]) -> bool {
    tris.iter().enumerate().any(|(n, t)| {
        tris.iter().skip(n + 1).any(|u| !t.iter().any(|v| u.contains(v)) && triangles_meet(t.map(pos), u.map(pos)))
    })
}

/// Whether triangles `a` and `b` share a point, by the separating axis theorem.
pub(super) fn triangles_meet(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> bool {
    let edges = |t: &[[f64; 3]; 3]| [sub(t[1], t[0]), sub(t[2], t[1]), sub(t[0], t[2])];
    let (ea, eb) = (edges(&a), edges(&b));
    let span = |t: &[[f64; 3]; 3], axis: [f64; 3]| {
        let d = t.map(|p| dot(p, axis));
        (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]))
    };
    let separates = |axis: [f64; 3]| {
        let len = norm(axis);
        if len.is_nan() || len <= 1e-12 {
            return false;
        }
        let axis = scale(axis, 1.0 / len);
        let ((a0, a1), (b0, b1)) = (span(&a, axis), span(&b, axis));
        a1 < b0 - 1e-12 || b1 < a0 - 1e-12
    };
    let normals = [cross(ea[0], ea[1]), cross(eb[0], eb[1])];
    !(normals.into_iter().any(separates) || ea.iter().any(|x| eb.iter().any(|y| separates(cross(*x, *y)))))
}

/// Boundaries and templates met so far in one extraction.
#[derive(Default)]
pub(super) struct Cache {
    boundaries: HashMap<u16, Option<Boundary>>,
    templates: HashMap<u64, Template>,
}

impl Cache {
    /// The template for corner values `g` (`f − iso`), or `None` when the cell is not crossed.
    pub fn template(&mut self, g: &[f64; 8]) -> Option<&Template> {
        let signs = inside_mask(g);
        if signs == 0 || signs == 255 {
            return None;
        }
        let joined = face_decisions(g, signs);
        let key = u16::from(signs) | u16::from(joined) << 8;
        let b = self.boundaries.entry(key).or_insert_with(|| boundary(signs, joined)).as_ref()?;
        let j = joins(b, g);
        let code = j.iter().enumerate().fold(0u64, |code, (l, &p)| code | u64::from(p) << (3 * l));
        Some(self.templates.entry(u64::from(key) | code << 16).or_insert_with(|| build(b, &j)))
    }
}

/// Moves `p` onto the level set of the trilinear function by Newton steps along its gradient,
/// keeping the result only when it lands closer to the level, inside the cell and within
/// `reach` of `p`.
fn project(g: &[f64; 8], p: [f64; 3], reach: f64) -> [f64; 3] {
    let mut q = p;
    for _ in 0..8 {
        let v = trilinear(g, q);
        let d = trilinear_gradient(g, q);
        let n2 = dot(d, d);
        if !(n2 > 0.0 && v.is_finite()) {
            break;
        }
        q = sub(q, scale(d, v / n2)).map(|x| x.clamp(0.0, 1.0));
    }
    let better = trilinear(g, q).abs() < trilinear(g, p).abs();
    let inside = q.iter().all(|&x| x > 1e-6 && x < 1.0 - 1e-6);
    if better && inside && norm(sub(q, p)) <= reach { q } else { p }
}

/// A tube between loops `a` and `c` through a waist: loop `a` (one waist vertex per distinct
/// vertex of it, numbered from `first`) shrunk towards the middle of the tube and moved onto
/// the level set, and the bands from `a` to the waist and from the waist to `c`. Used when every
/// direct band would put a rung on a cube face or cut itself; of a few waists, the first whose
/// bands do not cut themselves, else the first. Returns the waist's positions and the triangles.
fn through_waist(
    g: &[f64; 8],
    a: &[u8],
    c: &[u8],
    first: u8,
    point: &dyn Fn(u8) -> [f64; 3],
) -> (Vec<[f64; 3]>, Vec<[u8; 3]>) {
    let ends: Vec<[f64; 3]> = a.iter().chain(c).map(|&v| point(v)).collect();
    let (middle, _) = spread(&ends);
    let mut distinct: Vec<u8> = Vec::with_capacity(a.len());
    let waist: Vec<u8> = a
        .iter()
        .map(|&v| {
            let k = distinct.iter().position(|&d| d == v).unwrap_or_else(|| {
                distinct.push(v);
                distinct.len() - 1
            });
            first + k as u8
        })
        .collect();
    let backwards: Vec<u8> = waist.iter().rev().copied().collect();
    let mut fallback = None;
    for shrink in [0.5, 0.35, 0.65, 0.2, 0.8] {
        for onto_level in [true, false] {
            let positions: Vec<[f64; 3]> = distinct
                .iter()
                .map(|&v| {
                    let q = point(v);
                    let p = add(q, scale(sub(middle, q), shrink));
                    if onto_level { project(g, p, 0.5 * shrink * norm(sub(middle, q))) } else { p }
                })
                .collect();
            let pos = |v: u8| match v.checked_sub(first) {
                Some(k) => positions.get(k as usize).copied().unwrap_or([0.5; 3]),
                None => point(v),
            };
            let mut band = stitch(a, &backwards, &pos, false);
            band.extend(stitch(&waist, c, &pos, false));
            band.retain(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
            if !self_crossing(&band, &pos) {
                return (positions, band);
            }
            fallback.get_or_insert((positions, band));
        }
    }
    fallback.unwrap_or_default()
}

/// The mean of `points` and their mean distance from it.
fn spread(points: &[[f64; 3]]) -> ([f64; 3], f64) {
    let n = points.len().max(1) as f64;
    let mean = scale(points.iter().fold([0.0; 3], |s, p| add(s, *p)), 1.0 / n);
    (mean, points.iter().map(|p| norm(sub(*p, mean))).sum::<f64>() / n)
}

/// Adds the triangles of the cell with lower corner `cell` (voxel number `base`).
pub(super) fn march(b: &mut Builder, cache: &mut Cache, cell: [usize; 3], base: usize) -> Result<(), IsoError> {
    let Some(g) = b.corner_values(base) else { return Ok(()) };
    let Some(template) = cache.template(&g) else { return Ok(()) };
    // Every crossed edge is on a loop, so every one gets a vertex.
    let mut ids = [u32::MAX; 12];
    let mut local = [[0.5; 3]; 12];
    for e in 0..12 {
        let [lo, hi] = edge_corners(e);
        if (g[lo] >= 0.0) == (g[hi] >= 0.0) {
            continue;
        }
        let (inside, outside) = if g[lo] >= 0.0 { (lo, hi) } else { (hi, lo) };
        (ids[e], local[e]) = b.crossing(cell, base, inside, outside, g[inside], g[outside]);
    }
    // Local vertices 0..12 are the crossings; from CENTRE on come the centres, then the waists
    // of tubes (`more`: their positions and mesh vertices; no allocation for most cells).
    let mut more: (Vec<[f64; 3]>, Vec<u32>) = (Vec::new(), Vec::new());
    for edges in &template.centres {
        let loop_points: Vec<[f64; 3]> = edges.iter().map(|&e| local[e as usize % 12]).collect();
        let (mean, radius) = spread(&loop_points);
        let p = project(&g, mean, 0.5 * radius);
        more.0.push(p);
        more.1.push(b.centre(cell, p));
    }
    let point = |more: &[[f64; 3]], v: u8| {
        let v = v as usize;
        local.get(v).or_else(|| more.get(v - CENTRE as usize)).copied().unwrap_or([0.5; 3])
    };
    // Crossings snapped onto one lattice point are one vertex: name each by its first edge
    // (looked up only in the few cells with a tube).
    let canonical = |lp: &[u8]| -> Vec<u8> {
        let same = |e: usize| (0..e).find(|&d| ids[d] == ids[e] && ids[e] != u32::MAX).unwrap_or(e) as u8;
        lp.iter().map(|&v| if (v as usize) < ids.len() { same(v as usize) } else { v }).collect()
    };
    let mut stitched: Vec<[u8; 3]> = Vec::new();
    for [a, c] in &template.tubes {
        let (a, c) = (canonical(a), canonical(c));
        let band = stitch(&a, &c, &|v| point(&more.0, v), true);
        if !band.is_empty() {
            stitched.extend(band);
            continue;
        }
        let first = CENTRE + more.0.len() as u8;
        let (positions, band) = through_waist(&g, &a, &c, first, &|v| point(&more.0, v));
        for p in positions {
            more.0.push(p);
            more.1.push(b.centre(cell, p));
        }
        stitched.extend(band);
    }
    for tri in template.triangles.iter().chain(&stitched) {
        let mut out = [0u32; 3];
        for (slot, &v) in out.iter_mut().zip(tri) {
            let id = if v >= CENTRE { more.1.get((v - CENTRE) as usize) } else { ids.get(v as usize) };
            match id {
                Some(&id) if id != u32::MAX => *slot = id,
                _ => return Ok(()),
            }
        }
        b.triangle(out)?;
    }
    Ok(())
}
