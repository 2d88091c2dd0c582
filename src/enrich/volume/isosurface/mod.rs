//! Isosurfaces of a volume: the triangle mesh of the level set `{f = iso}` of the trilinear
//! interpolant of the voxels, by marching cubes with the topology of the trilinear function
//! ([`Method::MarchingCubes`], as Chernyaev's MC33) or by marching tetrahedra
//! ([`Method::Tetrahedra`]).
//!
//! # Conventions
//!
//! - **Inside / outside.** The surface separates `{f ≥ iso}` (inside) from `{f < iso}`
//!   (outside): a voxel exactly at `iso` is inside, everywhere (corner signs, face and interior
//!   decisions), which is the limit of `iso` lowered by an infinitesimal amount.
//! - **Winding and normals.** Triangles are counter-clockwise seen from outside (the `f < iso`
//!   side) in *world* space, and normals point outward, along `−∇f`. A voxel-to-world affine with
//!   a negative determinant (a flipped axis, common in NIfTI) reverses handedness; the winding is
//!   then reversed so it stays counter-clockwise from outside in the world, and a closed surface
//!   around an inside region has a positive [`IsoMesh::enclosed_volume`].
//! - **Shared vertices.** One vertex per crossed lattice edge (found again by the edge's number
//!   when the neighbouring cell needs it), placed by linear interpolation of the two voxel values
//!   along the edge, so the mesh is indexed and watertight. Marching cubes adds interior vertices
//!   inside a cell where a configuration needs one (a boundary loop of more than six crossings,
//!   or one that cannot be cut into ears without a triangle lying on a cube face); marching
//!   tetrahedra also puts vertices on face diagonals and main diagonals, keyed the same way.
//! - **Voxels at the level.** A crossing that falls on a voxel (the voxel's value is `iso`
//!   exactly, or within a `1e-10` fraction of its edge) is placed on the voxel and shared by all
//!   crossings there, so no two vertices coincide; triangles whose vertices collapse onto one
//!   another are dropped, and so are pairs of triangles on the same three vertices wound
//!   opposite ways (a sheet folded flat). Dropping them keeps every edge used equally often in both directions
//!   (the surface stays closed and oriented), but where the level set really pinches at such a
//!   voxel (two sheets touching at a point or along a lattice edge, as the true `{f ≥ iso}` does)
//!   an edge may be used by four triangles instead of two. A level equal to the data's minimum
//!   gives no surface; one equal to a lone maximum gives nothing either (a point).
//! - **Holes.** A cell with a missing corner (NaN) gets no triangles, so the surface has a hole
//!   there, bounded by the missing cells' edges. Cells on the volume's outer faces are open there
//!   too: the surface ends where the data ends.
//! - **Cells.** A cell is the cube of voxels `(i..i+1, j..j+1, k..k+1)`, numbered
//!   `(k·(ny−1) + j)·(nx−1) + i`. [`active_cells`] lists the cells whose corner range holds
//!   `iso`; [`extract`] works through those or through a list it is given (a span-space index
//!   built elsewhere), sorted and without repeats first.
//! - **Threads.** [`active_cells`] scans the z layers of cells on rayon's threads. [`extract`]
//!   cuts its sorted cells into slabs of whole z layers (about four a thread, none under 4096
//!   cells; one on one thread), marches each slab on its own and joins them: a vertex on the
//!   voxel plane two slabs share is found again by its key in the slab below, triangles keep the
//!   order of their cells, and vertices are numbered in the order the triangles first use them.
//!   The mesh is therefore the same, bit for bit, as one pass over the cells gives, whatever the
//!   number of threads.
//!
//! # Marching cubes: the case analysis
//!
//! The triangulation of each cell is derived procedurally from the topology of the trilinear
//! function on the cell, following the case analysis of E. V. Chernyaev, *Marching Cubes 33:
//! construction of topologically correct isosurfaces* (CERN CN/95-17, 1995), with its interior
//! test as corrected and discussed by A. Lopes and K. Brodlie, *Improving the robustness and
//! accuracy of the marching cubes algorithm for isosurfacing* (IEEE TVCG 9(1), 2003),
//! L. Custodio, T. Etiene, S. Pesco and C. Silva, *Practical considerations on Marching Cubes 33
//! topological correctness* (Computers & Graphics 37(7), 2013) and D. Vega, J. Abache and
//! D. Coll, *A fast and memory-saving marching cubes 33 implementation with the correct interior
//! test* (JCGT 8(3), 2019): the surface in each cell has the topology of the trilinear
//! interpolant. No table or code from those works or any implementation was used; instead of
//! per-case tables and per-case interior tests, the steps below derive each configuration, and
//! the tests check every one against a brute-force reference (the 33 configurations of MC33 are
//! what they find):
//!
//! 1. **Faces** (module `surface`): on each face whose corners alternate in sign, the asymptotic
//!    decider (Nielson and Hamann, 1991) — the bilinear saddle value
//!    `(f00·f11 − f10·f01)/(f00 + f11 − f10 − f01)` against `iso` — says whether the inside
//!    corners are joined across the face. Neighbouring cells decide a shared face identically.
//! 2. **Loops**: the face segments are chained into closed, oriented loops on the cube's
//!    surface, cutting it into patches.
//! 3. **Interior** (module `interior`): when a cell has two or more loops, the components of
//!    `{f ≥ iso}` and `{f < iso}` inside the cell are found exactly by sweeping planes across it
//!    (a generalisation of Chernyaev's and Lopes–Brodlie's plane test to every configuration:
//!    MC33's tunnels of cases 4, 6, 7, 10, 12 and 13). Loops whose two sides belong to the same
//!    pair of components are the two ends of one tube; the others bound disks.
//! 4. **Triangles** (module `cell`): a disk of three crossings is a triangle, of four to six
//!    it is cut into ears along the shortest diagonals not lying on a cube face, larger ones
//!    are fanned around an interior vertex (the loop's centroid moved onto the trilinear level
//!    set by a few Newton steps when that stays close); a tube is a band between its two loops,
//!    one triangle per crossing, chosen per cell from the real crossing positions: the band of
//!    least area that does not cut itself and has no rung (edge between the loops) lying on a
//!    cube face, where the neighbouring cell could use the same edge. When no such band exists,
//!    the tube goes through a waist of interior vertices (one loop shrunk towards the tube's
//!    middle and moved onto the level set) and is two bands.
//!
//! The result per configuration key (sign pattern, face decisions, which loops are joined) is
//! memoised during an extraction (per slab), so it acts as a generated table (tubes keep their two loops
//! in it and are stitched per cell). The tests check every one of the 256 sign patterns, with
//! random corner values covering the face decisions and interior outcomes, against a
//! brute-force count of components, boundary loops and Euler characteristic on a fine lattice,
//! and a million random cells against a second, line-based reference (the topology
//! verification of Etiene et al., 2012: no cell differs).

mod cell;
mod cube;
mod interior;
mod measure;
mod mesh;
mod normals;
mod surface;
#[cfg(test)]
mod tests;
mod tetra;

use std::fmt;
use std::ops::Range;
use std::sync::atomic::AtomicUsize;

use rayon::prelude::*;

use crate::data::volume::{Volume, Voxels};
use crate::enrich::volume::sample::invert;

/// Most triangles one extraction makes (2²⁶ ≈ 67 million, about 2.4 GB of mesh).
pub const MAX_TRIANGLES: usize = 1 << 26;

/// How cells are cut into triangles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// Marching cubes with the topology of the trilinear interpolant (MC33): faces decided by
    /// the asymptotic decider, tunnels through cells by the interior test.
    #[default]
    MarchingCubes,
    /// Marching tetrahedra, six per cell around the main diagonal.
    Tetrahedra,
}

/// How vertex normals are found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NormalRule {
    /// `−∇f` from central differences at the voxels, interpolated to the vertex and taken to
    /// world space by the inverse transpose of the affine; the face rule where it vanishes.
    #[default]
    Gradient,
    /// The area-weighted mean of the normals of the triangles around the vertex.
    Faces,
}

/// A triangle mesh of an isosurface, in world coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IsoMesh {
    /// Vertex positions in world coordinates.
    pub positions: Vec<[f64; 3]>,
    /// Unit outward normals in world space, one per position.
    pub normals: Vec<[f64; 3]>,
    /// Triangles as indices into `positions`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// Why an isosurface cannot be extracted.
#[derive(Clone, Debug, PartialEq)]
pub enum IsoError {
    /// The level is NaN or infinite.
    IsoNotFinite(f64),
    /// The surface would have more than `limit` triangles.
    TooManyTriangles {
        /// The limit, [`MAX_TRIANGLES`].
        limit: usize,
    },
    /// The voxel-to-world matrix flattens the volume (its 3 × 3 part has no inverse).
    FlatAffine([[f64; 4]; 3]),
    /// A cell number in the given list is not a cell of the volume.
    CellOutOfRange {
        /// The cell number.
        cell: u32,
        /// The number of cells.
        cells: usize,
    },
}

impl fmt::Display for IsoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IsoError::IsoNotFinite(iso) => {
                write!(f, "the isosurface level {iso} is not a finite number; give a number")
            }
            IsoError::TooManyTriangles { limit } => write!(
                f,
                "the isosurface has more than {limit} triangles (2^26); the field is noise at the scale of its voxels — smooth or downsample the volume, or choose another level"
            ),
            IsoError::FlatAffine(m) => {
                write!(f, "the voxel-to-world matrix {m:?} flattens the volume (its 3 × 3 part has no inverse)")
            }
            IsoError::CellOutOfRange { cell, cells } => {
                write!(f, "cell {cell} is not in the volume, which has {cells} cells")
            }
        }
    }
}

impl std::error::Error for IsoError {}

/// The number of cells along each axis (`n − 1`, 0 for an axis of one voxel).
fn cell_dims(volume: &Volume) -> [usize; 3] {
    volume.dims().map(|n| n.saturating_sub(1))
}

/// The cells whose corners are all present and whose corner minimum `≤ iso ≤` maximum, in
/// increasing order: a brute-force scan of the volume, its z layers of cells shared among
/// rayon's threads. Cells where the surface can pass; a cell whose corners are all `≥ iso` with
/// one exactly at `iso` is listed but gets no triangles. Empty when `iso` is not finite or the
/// volume is one voxel thick.
///
/// Each voxel plane is read as runs and each voxel becomes three bits (`≤ iso`, `≥ iso`,
/// missing), packed 64 to a word along each row; a cell's bits are those of its eight corners,
/// two planes and two rows ORed and each bit ORed with its right neighbour, so 64 cells are
/// decided in a few word operations:
/// minimum `≤ iso` is some corner `≤ iso`, maximum `≥ iso` some corner `≥ iso`, the rule of
/// `corner_range` without its eight reads a cell.
pub fn active_cells(volume: &Volume, iso: f64) -> Vec<u32> {
    let [cx, cy, cz] = cell_dims(volume);
    if !iso.is_finite() || cx == 0 || cy == 0 || cz == 0 {
        return Vec::new();
    }
    let [nx, ny, _] = volume.dims();
    let plane = nx * ny;
    let words = nx.div_ceil(64);
    let layers: Vec<Vec<u32>> = (0..cz)
        .into_par_iter()
        .map_init(
            || (vec![0.0; plane], PlanePair::<Vec<[u64; 3]>>::default()),
            |(values, planes), k| {
                planes.hold(k, |p, masks| plane_masks(volume, p, iso, values, masks));
                let (near, far) = (&planes.near, &planes.far);
                let mut out = Vec::new();
                for j in 0..cy {
                    let id_row = ((k * cy + j) * cx) as u32;
                    for w in 0..words {
                        // Columns of rows j and j + 1 of both planes, then each cell i with its
                        // column i + 1.
                        let col = |w: usize, b: usize| {
                            let at = |r: usize| {
                                near.get(r * words + w).map_or(0, |m| m[b]) | far.get(r * words + w).map_or(0, |m| m[b])
                            };
                            at(j) | at(j + 1)
                        };
                        let cell = |b: usize| {
                            let here = col(w, b);
                            let next = if w + 1 < words { col(w + 1, b) << 63 } else { 0 };
                            here | (here >> 1) | next
                        };
                        let mut active = cell(0) & cell(1) & !cell(2);
                        // Only cells 0..cx of the row.
                        let first = 64 * w;
                        if first + 64 > cx {
                            active &= if cx > first { (1u64 << (cx - first)) - 1 } else { 0 };
                        }
                        while active != 0 {
                            let i = first + active.trailing_zeros() as usize;
                            out.push(id_row + i as u32);
                            active &= active - 1;
                        }
                    }
                }
                out
            },
        )
        .collect();
    layers.concat()
}

/// What a thread going up the layers of cells keeps of the two voxel planes of each layer:
/// the far plane of layer `k` is the near plane of layer `k + 1`, so each plane is made once.
#[derive(Default)]
struct PlanePair<T> {
    /// What was made of plane `k`.
    near: T,
    /// What was made of plane `k + 1`.
    far: T,
    /// The plane `far` holds.
    far_plane: Option<usize>,
}

impl<T> PlanePair<T> {
    /// Hold planes `k` (near) and `k + 1` (far), `make` filling a plane's slot when it is not
    /// already held.
    fn hold(&mut self, k: usize, mut make: impl FnMut(usize, &mut T)) {
        if self.far_plane == Some(k) {
            std::mem::swap(&mut self.near, &mut self.far);
        } else {
            make(k, &mut self.near);
        }
        make(k + 1, &mut self.far);
        self.far_plane = Some(k + 1);
    }
}

/// The bits of [`active_cells`] for voxel plane `k`: per row, 64 voxels to a word,
/// `[≤ iso, ≥ iso, missing]`; `values` is a plane's worth of room. Voxels stored as `f32`
/// without a scale are compared as they are ([`LevelTest::stored_f32`]); others are read as
/// numbers first.
fn plane_masks(volume: &Volume, k: usize, iso: f64, values: &mut [f64], masks: &mut Vec<[u64; 3]>) {
    let nx = volume.dims()[0];
    let plane = values.len();
    masks.clear();
    match (volume.voxels(), volume.scale()) {
        (Voxels::F32(stored), None) => {
            let stored = stored.get(k * plane..(k + 1) * plane).unwrap_or_default();
            LevelTest::stored_f32(iso).rows(stored, nx, masks);
        }
        _ => {
            volume.read_run(k * plane, values);
            LevelTest::numbers(iso).rows(values, nx, masks);
        }
    }
}

/// The tests a cell's corners are put to against a level — `≤ iso`, `≥ iso`, missing — on
/// values of type `T`: numbers against `iso` itself, or stored `f32` voxels against the `f32`
/// bounds that give the same answers as their `f64` values (no conversion a voxel). Shared by
/// [`active_cells`] and the span-space index's bricks.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LevelTest<T> {
    /// A value is `≤ iso` when `≤ below`.
    below: T,
    /// A value is `≥ iso` when `≥ above`.
    above: T,
}

impl LevelTest<f64> {
    /// The tests on values as numbers.
    pub fn numbers(iso: f64) -> LevelTest<f64> {
        LevelTest { below: iso, above: iso }
    }
}

impl LevelTest<f32> {
    /// The tests on stored `f32` voxels: `below` the largest `f32` at most `iso` and `above` the
    /// smallest at least `iso`, so `v ≤ below` exactly when `f64::from(v) ≤ iso` and `v ≥ above`
    /// exactly when `f64::from(v) ≥ iso` (for finite `iso`).
    pub fn stored_f32(iso: f64) -> LevelTest<f32> {
        let near = iso as f32;
        let below = if f64::from(near) > iso { near.next_down() } else { near };
        let above = if f64::from(near) < iso { near.next_up() } else { near };
        LevelTest { below, above }
    }
}

impl<T: Copy + PartialOrd> LevelTest<T> {
    /// The three tests on up to 64 values, bit `i` of each word for `run[i]`. Each test is first
    /// one byte a value, then eight bytes become eight bits at a time: loops the compiler turns
    /// into vector compares (a bit shifted in per value stayed scalar).
    #[inline]
    pub fn bits(&self, run: &[T]) -> [u64; 3] {
        let mut bytes = [[0u8; 64]; 3];
        for (b, &v) in bytes[0].iter_mut().zip(run) {
            *b = u8::from(v <= self.below);
        }
        for (b, &v) in bytes[1].iter_mut().zip(run) {
            *b = u8::from(v >= self.above);
        }
        // Only NaN is not equal to itself.
        #[allow(clippy::eq_op)]
        for (b, &v) in bytes[2].iter_mut().zip(run) {
            *b = u8::from(v != v);
        }
        let valid = if run.len() >= 64 { u64::MAX } else { (1u64 << run.len()) - 1 };
        bytes.map(|b| pack_bits(&b) & valid)
    }

    /// The three tests on a plane of rows `nx` long, 64 values to a word along each row.
    fn rows(&self, plane: &[T], nx: usize, masks: &mut Vec<[u64; 3]>) {
        for row in plane.chunks_exact(nx) {
            masks.extend(row.chunks(64).map(|run| self.bits(run)));
        }
    }
}

/// Bit `i` of the result is byte `i` of `bytes` (each 0 or 1): eight bytes at a time, by the
/// multiplication that gathers the low bits of a word's bytes into its top byte.
#[inline]
fn pack_bits(bytes: &[u8; 64]) -> u64 {
    let mut bits = 0u64;
    for (k, chunk) in bytes.chunks_exact(8).enumerate() {
        let word = u64::from_le_bytes(std::array::from_fn(|i| chunk[i]));
        bits |= (word.wrapping_mul(0x0102_0408_1020_4080) >> 56) << (8 * k);
    }
    bits
}

/// The corner offsets (voxel numbers relative to a cell's first corner) of a cell, bit 0 of the
/// corner number picking +x, bit 1 +y, bit 2 +z.
#[cfg(test)]
pub(crate) fn corner_offsets(volume: &Volume) -> [usize; 8] {
    let [nx, ny, _] = volume.dims();
    std::array::from_fn(|c| (c & 1) + (c >> 1 & 1) * nx + (c >> 2 & 1) * nx * ny)
}

/// The corner minimum and maximum of the cell whose first corner is voxel `base`, or `None` if
/// a corner is missing: the rule of [`active_cells`] (a cell is active when `lo ≤ iso ≤ hi`),
/// written plainly, for the tests to check [`active_cells`] against.
#[cfg(test)]
pub(crate) fn corner_range(volume: &Volume, base: usize, offsets: &[usize; 8]) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut missing = false;
    for off in offsets {
        let v = volume.get(base + off);
        missing |= v.is_nan();
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (!missing).then_some((lo, hi))
}

/// The isosurface `f = iso` of `volume` by `method`, with normals by `normals`, from the cells
/// listed in `cells` (cell numbers as in the module docs; any order, repeats ignored) or, when
/// `None`, from [`active_cells`]. Cells the surface does not cross add nothing.
///
/// The sorted cells are cut into slabs of whole z layers, marched on rayon's threads and joined
/// into one mesh (see the module docs): the same mesh, bit for bit, whatever the number of
/// threads.
pub fn extract(
    volume: &Volume,
    iso: f64,
    method: Method,
    normals: NormalRule,
    cells: Option<&[u32]>,
) -> Result<IsoMesh, IsoError> {
    extract_split(volume, iso, method, normals, cells, Split::for_threads(rayon::current_num_threads()))
}

/// How [`extract`] cuts its cells into slabs.
#[derive(Clone, Copy, Debug)]
struct Split {
    /// About how many slabs.
    slabs: usize,
    /// Fewest cells in a slab (fewer cells stay in one slab).
    min_cells: usize,
}

impl Split {
    /// Four slabs a thread (so threads that finish early take over the rest), none under 4096
    /// cells; one slab on one thread.
    fn for_threads(threads: usize) -> Split {
        Split { slabs: if threads > 1 { 4 * threads } else { 1 }, min_cells: 4096 }
    }

    /// The slabs of the sorted cell list `list` with `layer` cells in each z layer, as ranges of
    /// the list: about equal numbers of cells, each cut between two z layers.
    fn ranges(self, list: &[u32], layer: usize) -> Vec<Range<usize>> {
        let slabs = self.slabs.min(list.len() / self.min_cells.max(1)).max(1);
        let z = |n: usize| list.get(n).map(|&c| c as usize / layer.max(1));
        let mut ranges = Vec::with_capacity(slabs);
        let mut start = 0;
        for s in 1..slabs {
            let mut cut = (s * list.len() / slabs).max(start + 1);
            while cut < list.len() && z(cut) == z(cut - 1) {
                cut += 1;
            }
            if cut >= list.len() {
                break;
            }
            ranges.push(start..cut);
            start = cut;
        }
        ranges.push(start..list.len());
        ranges
    }
}

/// [`extract`] with the cells cut into slabs by `split`.
fn extract_split(
    volume: &Volume,
    iso: f64,
    method: Method,
    normals: NormalRule,
    cells: Option<&[u32]>,
    split: Split,
) -> Result<IsoMesh, IsoError> {
    if !iso.is_finite() {
        return Err(IsoError::IsoNotFinite(iso));
    }
    let inverse = invert(volume.affine()).ok_or(IsoError::FlatAffine(volume.affine()))?;
    let owned: Vec<u32>;
    let list: &[u32] = match cells {
        Some(given) if given.windows(2).all(|w| w[0] < w[1]) => given,
        Some(given) => {
            let mut sorted = given.to_vec();
            sorted.sort_unstable();
            sorted.dedup();
            owned = sorted;
            &owned
        }
        None => {
            owned = active_cells(volume, iso);
            &owned
        }
    };
    let [cx, cy, cz] = cell_dims(volume);
    let count = cx * cy * cz;
    let inside = list.partition_point(|&c| (c as usize) < count);
    if let Some(&cell) = list.get(inside) {
        return Err(IsoError::CellOutOfRange { cell, cells: count });
    }
    let [nx, ny, _] = volume.dims();
    let tables = (method == Method::Tetrahedra).then(tetra::Tables::new);
    let added = AtomicUsize::new(0);
    let ranges = split.ranges(list, cx * cy);
    let parts: Vec<mesh::Part> = ranges
        .par_iter()
        .map(|range| {
            let mut builder = mesh::Builder::new(volume, iso, normals == NormalRule::Gradient, &added);
            let mut cache = cell::Cache::default();
            for &id in list.get(range.clone()).unwrap_or_default() {
                let n = id as usize;
                let cell = [n % cx, n / cx % cy, n / (cx * cy)];
                let base = (cell[2] * ny + cell[1]) * nx + cell[0];
                match &tables {
                    Some(t) => tetra::march(&mut builder, t, cell, base)?,
                    None => cell::march(&mut builder, &mut cache, cell, base)?,
                }
            }
            Ok(builder.into_part())
        })
        .collect::<Result<_, IsoError>>()?;
    if parts.iter().map(mesh::Part::triangle_count).sum::<usize>() > MAX_TRIANGLES {
        return Err(IsoError::TooManyTriangles { limit: MAX_TRIANGLES });
    }
    let bottoms: Vec<usize> =
        ranges.iter().map(|r| list.get(r.start).map_or(0, |&c| c as usize / (cx * cy).max(1))).collect();
    let joined = mesh::join(parts, &bottoms, nx * ny);
    Ok(mesh::finish(volume, joined, normals, inverse))
}
