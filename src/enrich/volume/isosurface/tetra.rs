//! Marching tetrahedra: each cell cut into six tetrahedra that all share the cell's main diagonal
//! (corner 0 to corner 7), one for each order of stepping along x, y and z from corner 0 to
//! corner 7. Every cube face is then split along its diagonal through the face's lowest corner,
//! the same diagonal the neighbouring cell uses, so the pieces meet and the mesh stays
//! watertight. In each tetrahedron the field is linear, its level set a triangle or a
//! quadrilateral (two triangles) with vertices on the tetrahedron's edges — lattice edges, face
//! diagonals or the main diagonal, each keyed globally like a lattice edge.

use super::IsoError;
use super::cube::{cross, dot, sub};
use super::mesh::Builder;

/// The six tetrahedra: corners 0, one step, two steps and 7.
const TETS: [[usize; 4]; 6] = {
    let orders = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
    let mut tets = [[0; 4]; 6];
    let mut n = 0;
    while n < 6 {
        let [a, b, _] = orders[n];
        tets[n] = [0, 1 << a, 1 << a | 1 << b, 7];
        n += 1;
    }
    tets
};

/// A triangle as three (inside corner, outside corner) pairs of cube corners.
type Tri = [(u8, u8); 3];

/// The triangles of each tetrahedron for each inside mask over its four corners, oriented
/// counter-clockwise seen from outside.
pub(super) struct Tables {
    tris: Vec<Vec<Tri>>,
}

fn position(c: u8) -> [f64; 3] {
    [f64::from(c & 1), f64::from(c >> 1 & 1), f64::from(c >> 2 & 1)]
}

/// `t` reordered if needed so its normal points from the inside corners to the outside ones
/// (checked with the crossings at the midpoints, where the triangle cannot degenerate).
fn oriented(t: Tri, inside: &[u8], outside: &[u8]) -> Tri {
    let mid = |(a, b): (u8, u8)| {
        let (pa, pb) = (position(a), position(b));
        [0, 1, 2].map(|i| 0.5 * (pa[i] + pb[i]))
    };
    let [p, q, r] = t.map(mid);
    let mean = |cs: &[u8]| {
        let s = cs.iter().fold([0.0; 3], |s, &c| {
            let p = position(c);
            [s[0] + p[0], s[1] + p[1], s[2] + p[2]]
        });
        s.map(|x| x / cs.len() as f64)
    };
    let out = sub(mean(outside), mean(inside));
    if dot(cross(sub(q, p), sub(r, p)), out) < 0.0 { [t[0], t[2], t[1]] } else { t }
}

impl Tables {
    pub fn new() -> Tables {
        let mut tris = Vec::with_capacity(6 * 16);
        for tet in TETS {
            for mask in 0..16usize {
                let inside: Vec<u8> = (0..4).filter(|&v| mask >> v & 1 == 1).map(|v| tet[v] as u8).collect();
                let outside: Vec<u8> = (0..4).filter(|&v| mask >> v & 1 == 0).map(|v| tet[v] as u8).collect();
                let list = match (inside.as_slice(), outside.as_slice()) {
                    ([a], [b, c, d]) | ([b, c, d], [a]) => {
                        let t = if inside.len() == 1 {
                            [(*a, *b), (*a, *c), (*a, *d)]
                        } else {
                            [(*b, *a), (*c, *a), (*d, *a)]
                        };
                        vec![oriented(t, &inside, &outside)]
                    }
                    ([a, b], [c, d]) => {
                        // The quadrilateral a–c, a–d, b–d, b–c, cut along a–c to b–d.
                        let (ac, ad, bd, bc) = ((*a, *c), (*a, *d), (*b, *d), (*b, *c));
                        vec![oriented([ac, ad, bd], &inside, &outside), oriented([ac, bd, bc], &inside, &outside)]
                    }
                    _ => Vec::new(),
                };
                tris.push(list);
            }
        }
        Tables { tris }
    }
}

/// Adds the triangles of the cell with lower corner `cell` (voxel number `base`).
pub(super) fn march(b: &mut Builder, tables: &Tables, cell: [usize; 3], base: usize) -> Result<(), IsoError> {
    let Some(g) = b.corner_values(base) else { return Ok(()) };
    let all = g.iter().filter(|v| **v >= 0.0).count();
    if all == 0 || all == 8 {
        return Ok(());
    }
    let mut ids = [u32::MAX; 64];
    for (n, tet) in TETS.iter().enumerate() {
        let mask = (0..4).fold(0, |m, v| if g[tet[v]] >= 0.0 { m | 1 << v } else { m });
        let Some(list) = tables.tris.get(n * 16 + mask) else { continue };
        for tri in list {
            let mut out = [0u32; 3];
            for (slot, &(i, o)) in out.iter_mut().zip(tri) {
                let (i, o) = (i as usize & 7, o as usize & 7);
                let key = i * 8 + o;
                if ids[key] == u32::MAX {
                    ids[key] = b.crossing(cell, base, i, o, g[i], g[o]).0;
                }
                *slot = ids[key];
            }
            b.triangle(out)?;
        }
    }
    Ok(())
}
