//! Assembling the mesh: one vertex per crossed lattice edge (found again by the edge's key when
//! the neighbouring cell asks for it), interior vertices per cell, triangles with no repeated
//! vertex, and at the end the move to world space with the winding kept counter-clockwise from
//! outside.
//!
//! Slabs of cells are assembled apart ([`Builder`], one [`Part`] each) and [`join`]ed: a vertex
//! on the voxel plane two consecutive slabs share is found again by its key in the slab below,
//! so the joined mesh has the same vertices and triangles as one built in a single pass, and
//! [`finish`] numbers the vertices in the order the triangles first use them, so the result does
//! not depend on where the slabs were cut.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use super::cube::corner_position;
use super::normals::{corner_gradients_at, voxel_gradient, world_normals};
use super::{IsoError, IsoMesh, MAX_TRIANGLES, NormalRule};
use crate::data::volume::Volume;

/// A crossing closer than this fraction of its segment to an end is placed on that end and
/// shared with every other crossing there, so no two vertices coincide.
pub(super) const SNAP: f64 = 1e-10;

/// Kind 3 of a vertex key: a lattice point (a crossing snapped onto it).
const CORNER_KIND: u64 = 3;

/// A multiplicative hash for the u64 vertex keys (the standard SipHash is several times slower
/// and the keys are not adversarial).
#[derive(Default)]
pub(super) struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u64(&mut self, x: u64) {
        let h = (self.0 ^ x).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        self.0 = h ^ (h >> 29);
    }
}

/// The key of an interior vertex, which no other cell shares.
const NO_KEY: u64 = u64::MAX;

/// Triangles a builder counts before adding them to the count shared by all slabs.
const BATCH: usize = 1 << 16;

/// The vertices and triangles of a run of cells, in voxel-index space.
#[derive(Default)]
pub(super) struct Part {
    /// Vertex key to vertex.
    map: HashMap<u64, u32, BuildHasherDefault<KeyHasher>>,
    /// Per vertex: its key, [`NO_KEY`] for an interior vertex.
    keys: Vec<u64>,
    positions: Vec<[f64; 3]>,
    /// Per vertex (when normals come from gradients): the field's gradient in index space.
    gradients: Vec<[f64; 3]>,
    /// Per vertex: whether it was snapped onto a lattice point (only there can triangles meet
    /// on the same three vertices).
    snapped: Vec<bool>,
    triangles: Vec<[u32; 3]>,
}

impl Part {
    /// How many triangles the part has.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
}

/// Collects vertices and triangles in voxel-index space.
pub(super) struct Builder<'a> {
    volume: &'a Volume,
    iso: f64,
    /// Voxel-number offset of each cube corner from the cell's lower corner.
    offsets: [usize; 8],
    want_gradients: bool,
    /// Triangles added so far by every builder of one extraction, counted in batches: never
    /// more than were added, so passing [`MAX_TRIANGLES`] means the mesh is too large.
    added: &'a AtomicUsize,
    part: Part,
}

impl<'a> Builder<'a> {
    pub fn new(volume: &'a Volume, iso: f64, want_gradients: bool, added: &'a AtomicUsize) -> Builder<'a> {
        let [nx, ny, _] = volume.dims();
        let offsets = std::array::from_fn(|c| {
            let [x, y, z] = corner_position(c);
            x + y * nx + z * nx * ny
        });
        Builder { volume, iso, offsets, want_gradients, added, part: Part::default() }
    }

    /// `f − iso` at the cell's eight corners, or `None` when one is missing (or the difference
    /// is not finite): the cell is a hole.
    pub fn corner_values(&self, base: usize) -> Option<[f64; 8]> {
        let mut g = [0.0; 8];
        for (slot, off) in g.iter_mut().zip(self.offsets) {
            *slot = self.volume.get(base + off) - self.iso;
            if !slot.is_finite() {
                return None;
            }
        }
        Some(g)
    }

    /// The vertex where the segment from cube corner `inside` (`g_in ≥ 0`) to cube corner
    /// `outside` (`g_out < 0`) of the cell at `cell` (voxel number `base`) crosses the level,
    /// and its cell-local position. The two corners differ in a set of bits (an edge, a face
    /// diagonal or the main diagonal, always from a lower corner to one whose bits include it).
    pub fn crossing(
        &mut self,
        cell: [usize; 3],
        base: usize,
        inside: usize,
        outside: usize,
        g_in: f64,
        g_out: f64,
    ) -> (u32, [f64; 3]) {
        let t = g_in / (g_in - g_out);
        let (pa, pb) = (corner_position(inside).map(|v| v as f64), corner_position(outside).map(|v| v as f64));
        let snapped = if t <= SNAP {
            Some(inside)
        } else if t >= 1.0 - SNAP {
            Some(outside)
        } else {
            None
        };
        let key = match snapped {
            Some(c) => (base + self.offsets[c & 7]) as u64 * 8 + CORNER_KIND,
            None => {
                let lower = inside & outside;
                let kind = match inside ^ outside {
                    1 => 0,
                    2 => 1,
                    4 => 2,
                    3 => 4,
                    5 => 5,
                    6 => 6,
                    _ => 7,
                };
                (base + self.offsets[lower & 7]) as u64 * 8 + kind
            }
        };
        let local = match snapped {
            Some(c) => corner_position(c).map(|v| v as f64),
            None => [0, 1, 2].map(|a| pa[a] + t * (pb[a] - pa[a])),
        };
        let part = &mut self.part;
        if let Some(&id) = part.map.get(&key) {
            return (id, local);
        }
        let id = part.positions.len() as u32;
        part.keys.push(key);
        part.positions.push([0, 1, 2].map(|a| cell[a] as f64 + local[a]));
        part.snapped.push(snapped.is_some());
        if self.want_gradients {
            let at = |c: usize| {
                let [x, y, z] = corner_position(c);
                voxel_gradient(self.volume, [cell[0] + x, cell[1] + y, cell[2] + z])
            };
            let grad = match snapped {
                Some(c) => at(c),
                None => {
                    let (ga, gb) = (at(inside), at(outside));
                    [0, 1, 2].map(|a| ga[a] * (1.0 - t) + gb[a] * t)
                }
            };
            part.gradients.push(grad);
        }
        part.map.insert(key, id);
        (id, local)
    }

    /// A new interior vertex of the cell at `cell`, at cell-local position `p`.
    pub fn centre(&mut self, cell: [usize; 3], p: [f64; 3]) -> u32 {
        let part = &mut self.part;
        let id = part.positions.len() as u32;
        part.keys.push(NO_KEY);
        part.positions.push([0, 1, 2].map(|a| cell[a] as f64 + p[a]));
        part.snapped.push(false);
        if self.want_gradients {
            part.gradients.push(corner_gradients_at(self.volume, cell, p));
        }
        id
    }

    /// Adds a triangle unless two of its vertices are the same (a crossing snapped onto a
    /// lattice point collapses it), or says the mesh is too large: more than [`MAX_TRIANGLES`]
    /// added by this builder or, as far as counted yet, by all builders of the extraction.
    pub fn triangle(&mut self, t: [u32; 3]) -> Result<(), IsoError> {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return Ok(());
        }
        let triangles = &mut self.part.triangles;
        if triangles.len() >= MAX_TRIANGLES {
            return Err(IsoError::TooManyTriangles { limit: MAX_TRIANGLES });
        }
        triangles.push(t);
        if triangles.len().is_multiple_of(BATCH)
            && self.added.fetch_add(BATCH, Ordering::Relaxed) + BATCH > MAX_TRIANGLES
        {
            return Err(IsoError::TooManyTriangles { limit: MAX_TRIANGLES });
        }
        Ok(())
    }

    /// The vertices and triangles collected.
    pub fn into_part(self) -> Part {
        self.part
    }
}

/// One mesh from the parts of consecutive slabs of cells, in order: `bottoms[s]` is the lowest
/// voxel plane (z) of slab `s`'s cells, increasing, and `plane` the number of voxels in a plane.
/// A vertex of slab `s` on that plane is the vertex of slab `s − 1` with the same key, if it has
/// one; vertices are otherwise numbered slab after slab. The triangles keep their order.
pub(super) fn join(mut parts: Vec<Part>, bottoms: &[usize], plane: usize) -> Part {
    if parts.len() < 2 {
        return parts.pop().unwrap_or_default();
    }
    let fresh = u32::MAX;
    // For each vertex of each slab: the vertex of the slab below with its key, or `fresh`.
    let below: Vec<Vec<u32>> = parts
        .par_iter()
        .enumerate()
        .map(|(s, part)| {
            let (Some(prev), Some(&bottom)) = (s.checked_sub(1).and_then(|p| parts.get(p)), bottoms.get(s)) else {
                return vec![fresh; part.keys.len()];
            };
            let on_bottom = |key: u64| key != NO_KEY && (key >> 3) as usize / plane.max(1) == bottom;
            part.keys
                .iter()
                .map(|&key| if on_bottom(key) { prev.map.get(&key).copied().unwrap_or(fresh) } else { fresh })
                .collect()
        })
        .collect();
    let mut starts = Vec::with_capacity(parts.len());
    let mut count = 0u32;
    for links in &below {
        starts.push(count);
        count += links.iter().filter(|&&l| l == fresh).count() as u32;
    }
    // Each slab's fresh vertices numbered in order; a vertex found below is never itself on the
    // slab below's bottom plane (the planes differ), so it is fresh there.
    let numbered: Vec<Vec<u32>> = below
        .par_iter()
        .zip(&starts)
        .map(|(links, &start)| {
            let mut next = start;
            links
                .iter()
                .map(|&l| {
                    if l != fresh {
                        return fresh;
                    }
                    next += 1;
                    next - 1
                })
                .collect()
        })
        .collect();
    let ids: Vec<Vec<u32>> = numbered
        .par_iter()
        .zip(&below)
        .enumerate()
        .map(|(s, (own, links))| {
            let prev = s.checked_sub(1).and_then(|p| numbered.get(p));
            own.iter()
                .zip(links)
                .map(
                    |(&id, &l)| {
                        if l == fresh { id } else { prev.and_then(|p| p.get(l as usize)).copied().unwrap_or(id) }
                    },
                )
                .collect()
        })
        .collect();
    let pieces: Vec<Part> = parts
        .par_iter()
        .zip(&below)
        .zip(&ids)
        .map(|((part, links), ids)| {
            let own: Vec<usize> = links.iter().enumerate().filter(|&(_, &l)| l == fresh).map(|(v, _)| v).collect();
            Part {
                positions: own.iter().filter_map(|&v| part.positions.get(v).copied()).collect(),
                gradients: own.iter().filter_map(|&v| part.gradients.get(v).copied()).collect(),
                snapped: own.iter().filter_map(|&v| part.snapped.get(v).copied()).collect(),
                triangles: part
                    .triangles
                    .iter()
                    .map(|t| t.map(|v| ids.get(v as usize).copied().unwrap_or(fresh)))
                    .collect(),
                ..Part::default()
            }
        })
        .collect();
    let mut joined = Part::default();
    for piece in pieces {
        joined.positions.extend(piece.positions);
        joined.gradients.extend(piece.gradients);
        joined.snapped.extend(piece.snapped);
        joined.triangles.extend(piece.triangles);
    }
    joined
}

/// The mesh in world space: unused vertices dropped and the rest numbered in the order the
/// triangles first use them, the winding reversed when the affine flips handedness, and normals
/// by `rule`. `inverse` is the world-to-index affine.
pub(super) fn finish(volume: &Volume, part: Part, rule: NormalRule, inverse: [[f64; 4]; 3]) -> IsoMesh {
    let Part { positions, gradients, snapped, mut triangles, .. } = part;
    cancel_fins(&mut triangles, &snapped);
    let mut remap = vec![u32::MAX; positions.len()];
    let mut kept = Vec::new();
    for t in &mut triangles {
        for v in t.iter_mut() {
            if let Some(slot) = remap.get_mut(*v as usize) {
                if *slot == u32::MAX {
                    *slot = kept.len() as u32;
                    kept.push(*v as usize);
                }
                *v = *slot;
            }
        }
    }
    let affine = volume.affine();
    let det = affine[0][0] * (affine[1][1] * affine[2][2] - affine[1][2] * affine[2][1])
        - affine[0][1] * (affine[1][0] * affine[2][2] - affine[1][2] * affine[2][0])
        + affine[0][2] * (affine[1][0] * affine[2][1] - affine[1][1] * affine[2][0]);
    if det < 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    let world: Vec<[f64; 3]> =
        kept.par_iter().filter_map(|&v| positions.get(v)).map(|p| volume.world(p[0], p[1], p[2])).collect();
    let grads: Vec<[f64; 3]> = match rule {
        NormalRule::Gradient => kept.par_iter().map(|&v| gradients.get(v).copied().unwrap_or([0.0; 3])).collect(),
        NormalRule::Faces => Vec::new(),
    };
    let normals = world_normals(&world, &triangles, &grads, inverse);
    IsoMesh { positions: world, normals, triangles }
}

/// Removes pairs of triangles on the same three vertices wound opposite ways: a sheet folded
/// flat onto itself, left where crossings were snapped onto lattice points. Each pair cancels as
/// a chain, so every edge stays used equally often each way.
fn cancel_fins(triangles: &mut Vec<[u32; 3]>, snapped: &[bool]) {
    let is_snapped = |v: u32| snapped.get(v as usize).copied().unwrap_or(false);
    let mut groups: HashMap<[u32; 3], Vec<usize>, BuildHasherDefault<KeyHasher>> = HashMap::default();
    for (n, t) in triangles.iter().enumerate() {
        if t.iter().any(|&v| is_snapped(v)) {
            let mut key = *t;
            key.sort_unstable();
            groups.entry(key).or_default().push(n);
        }
    }
    let mut drop = vec![false; triangles.len()];
    for (key, members) in groups {
        if members.len() < 2 {
            continue;
        }
        // A triangle's winding relative to its sorted vertices: a rotation of the sorted order
        // is one way, anything else the other.
        let (mut forward, mut backward) = (Vec::new(), Vec::new());
        for n in members {
            let Some(t) = triangles.get(n) else { continue };
            let rotations = [key, [key[1], key[2], key[0]], [key[2], key[0], key[1]]];
            if rotations.contains(t) {
                forward.push(n);
            } else {
                backward.push(n);
            }
        }
        for (a, b) in forward.into_iter().zip(backward) {
            for n in [a, b] {
                if let Some(d) = drop.get_mut(n) {
                    *d = true;
                }
            }
        }
    }
    if drop.iter().any(|d| *d) {
        let mut n = 0;
        triangles.retain(|_| {
            let keep = !drop.get(n).copied().unwrap_or(false);
            n += 1;
            keep
        });
    }
}
