//! Tests of the isosurface extraction: every cell configuration against a brute-force reference
//! ([`cases`], [`reference`]) and a million random cells against a cheaper one ([`lines`]), whole volumes (watertight, oriented, known shapes; [`shapes`]), the cell
//! list, ties and errors ([`volumes`]), and extraction in slabs on several threads against one
//! pass ([`slabs`]).

mod cases;
mod lines;
mod reference;
mod shapes;
mod slabs;
mod volumes;

use std::collections::HashMap;

use super::*;
use crate::data::volume::Voxels;

/// xorshift64*: deterministic noise for tests.
pub(super) struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x2545_F491_4F6C_DD1D) | 1)
    }

    /// A number in `[0, 1)`.
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A volume of `dims` voxels with `values` (x fastest) and unit spacing.
pub(super) fn volume(dims: [usize; 3], values: Vec<f64>) -> Volume {
    Volume::new(dims, Voxels::F64(values), [1.0; 3]).expect("volume")
}

/// A volume of `dims` voxels placed by `affine`, holding `f` at each voxel's world position.
pub(super) fn sampled(dims: [usize; 3], affine: [[f64; 4]; 3], f: impl Fn([f64; 3]) -> f64) -> Volume {
    let mut values = Vec::with_capacity(dims.iter().product());
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                let w = affine.map(|r| r[0] * i as f64 + r[1] * j as f64 + r[2] * k as f64 + r[3]);
                values.push(f(w));
            }
        }
    }
    volume(dims, values).with_affine(affine).expect("finite affine")
}

/// The affine of spacing `s` with the volume's first voxel at the origin.
pub(super) fn spaced(s: [f64; 3]) -> [[f64; 4]; 3] {
    [[s[0], 0.0, 0.0, 0.0], [0.0, s[1], 0.0, 0.0], [0.0, 0.0, s[2], 0.0]]
}

/// For each undirected edge `(lo, hi)` of the mesh: how often it is used as `lo → hi` and as
/// `hi → lo`.
pub(super) fn edge_uses(mesh: &IsoMesh) -> HashMap<(u32, u32), [u32; 2]> {
    let mut uses: HashMap<(u32, u32), [u32; 2]> = HashMap::new();
    for t in &mesh.triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            let entry = uses.entry((a.min(b), a.max(b))).or_default();
            entry[usize::from(a > b)] += 1;
        }
    }
    uses
}

/// Checks that every edge is used once in each direction, except edges used once whose ends
/// both satisfy the same `open` predicate (they lie on one face of the box where the surface may
/// end). `open` returns a face number for a point on an open face.
pub(super) fn check_closed(mesh: &IsoMesh, open: impl Fn([f64; 3]) -> Vec<usize>) -> Result<(), String> {
    for ((a, b), [f, r]) in edge_uses(mesh) {
        if f == 1 && r == 1 {
            continue;
        }
        let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
        if f + r == 1 && open(pa).iter().any(|face| open(pb).contains(face)) {
            continue;
        }
        return Err(format!("edge {a}–{b} ({pa:?} to {pb:?}) used {f} times forward and {r} backward"));
    }
    Ok(())
}

/// The faces of the index box `[0, n−1]` a point (in index space) lies on.
pub(super) fn box_faces(dims: [usize; 3]) -> impl Fn([f64; 3]) -> Vec<usize> {
    move |p: [f64; 3]| {
        let mut faces = Vec::new();
        for a in 0..3 {
            if p[a].abs() < 1e-9 {
                faces.push(2 * a);
            }
            if (p[a] - (dims[a] - 1) as f64).abs() < 1e-9 {
                faces.push(2 * a + 1);
            }
        }
        faces
    }
}

/// The smallest triangle area of the mesh.
pub(super) fn smallest_area(mesh: &IsoMesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            0.5 * cube::norm(cube::cross(cube::sub(b, a), cube::sub(c, a)))
        })
        .fold(f64::INFINITY, f64::min)
}
