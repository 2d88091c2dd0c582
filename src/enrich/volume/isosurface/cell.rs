//! Marching cubes with the topology of the trilinear interpolant (MC33's case analysis, derived
//! procedurally): each cell's triangulation is built from its boundary loops ([`surface`]), the
//! interior connectivity of its corners ([`interior`]) and a triangulation of disks and tubes,
//! and memoised per configuration key so that it works as a generated table.
//!
//! [`surface`]: super::surface
//! [`interior`]: super::interior

use std::collections::HashMap;

use super::IsoError;
use super::cube::{add, dot, edge_faces, edge_midpoint, norm, scale, sub, trilinear, trilinear_gradient};
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
                Some(other) => tube(&mut t, lp, other),
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

/// A tube between loops `a` and `b`: a band stitched between them, `a` walked forwards and `b`
/// backwards (as boundaries of one annulus they run opposite ways), starting at their closest
/// pair of crossings and always taking the shorter rung.
fn tube(t: &mut Template, a: &[u8], b: &[u8]) {
    let c: Vec<u8> = b.iter().rev().copied().collect();
    let (m, n) = (a.len(), c.len());
    if m == 0 || n == 0 {
        return;
    }
    let (mut i0, mut k0) = (0, 0);
    for i in 0..m {
        for k in 0..n {
            if dist(a[i], c[k]) < dist(a[i0], c[k0]) {
                (i0, k0) = (i, k);
            }
        }
    }
    let at = |i: usize| a[(i0 + i) % m];
    let ct = |k: usize| c[(k0 + k) % n];
    let (mut i, mut k) = (0, 0);
    while i < m || k < n {
        // Never close one loop while the other has not moved: the closing rung would be the
        // starting one and the band would pinch.
        let can_a = i < m && !(i + 1 == m && k == 0);
        let can_c = k < n && !(k + 1 == n && i == 0);
        let forward_a = match (can_a, can_c) {
            (true, true) => dist(at(i + 1), ct(k)) <= dist(at(i), ct(k + 1)),
            (a, _) => a,
        };
        if forward_a {
            t.triangles.push([at(i), at(i + 1), ct(k)]);
            i += 1;
        } else {
            t.triangles.push([at(i), ct(k + 1), ct(k)]);
            k += 1;
        }
    }
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

/// Adds the triangles of the cell with lower corner `cell` (voxel number `base`).
pub(super) fn march(b: &mut Builder, cache: &mut Cache, cell: [usize; 3], base: usize) -> Result<(), IsoError> {
    let Some(g) = b.corner_values(base) else { return Ok(()) };
    let Some(template) = cache.template(&g) else { return Ok(()) };
    let mut ids = [u32::MAX; 12];
    let mut local = [[0.0; 3]; 12];
    let mut vertex = |b: &mut Builder, e: u8| -> (u32, [f64; 3]) {
        let e = e as usize;
        if let (Some(&id), Some(&p)) = (ids.get(e), local.get(e))
            && id != u32::MAX
        {
            return (id, p);
        }
        let [lo, hi] = super::cube::edge_corners(e % 12);
        let (inside, outside) = if g[lo] >= 0.0 { (lo, hi) } else { (hi, lo) };
        let (id, p) = b.crossing(cell, base, inside, outside, g[inside], g[outside]);
        if let (Some(slot), Some(pos)) = (ids.get_mut(e), local.get_mut(e)) {
            *slot = id;
            *pos = p;
        }
        (id, p)
    };
    let mut centre_ids = Vec::with_capacity(template.centres.len());
    for edges in &template.centres {
        let points: Vec<[f64; 3]> = edges.iter().map(|&e| vertex(b, e).1).collect();
        let mean = scale(points.iter().fold([0.0; 3], |s, p| add(s, *p)), 1.0 / points.len().max(1) as f64);
        let spread = points.iter().map(|p| norm(sub(*p, mean))).sum::<f64>() / points.len().max(1) as f64;
        let p = project(&g, mean, 0.5 * spread);
        centre_ids.push(b.centre(cell, base, p));
    }
    for tri in &template.triangles {
        let mut out = [0u32; 3];
        for (slot, &v) in out.iter_mut().zip(tri) {
            *slot = if v >= CENTRE {
                match centre_ids.get((v - CENTRE) as usize) {
                    Some(&id) => id,
                    None => return Ok(()),
                }
            } else {
                vertex(b, v).0
            };
        }
        b.triangle(out)?;
    }
    Ok(())
}
