//! The triangle mesh a [`Triangulation`](super::Triangulation) keeps: the corners of every
//! triangle, the triangle across each of its edges, the hull ring walked from the edges that have
//! no triangle across them, and each point's neighbours (for the Voronoi cells).

use std::collections::HashMap;

use spade::{DelaunayTriangulation, Point2, Triangulation as _};

use super::{NONE, Site};

/// Triangles, counter-clockwise, with corners named by [`Site::pt`], and for each edge `k` (from
/// corner `k` to corner `k + 1`) the triangle across it, or [`NONE`] on the hull.
#[derive(Debug, Clone, Default)]
pub(super) struct Mesh {
    /// Corners of each triangle.
    pub triangles: Vec<[u32; 3]>,
    /// `neighbors[t][k]`: the triangle across edge `k` of triangle `t`, or [`NONE`].
    pub neighbors: Vec<[u32; 3]>,
    /// How many distinct points the triangles are built on.
    pub vertices: usize,
}

impl Mesh {
    /// Copies spade's inner faces and their adjacency, on up to `threads` threads (the copy is
    /// bound by memory latency, not arithmetic).
    pub fn from_spade(dt: &DelaunayTriangulation<Site>, threads: usize) -> Mesh {
        let count = dt.num_inner_faces();
        let mut triangles = vec![[0u32; 3]; count];
        let mut neighbors = vec![[NONE; 3]; count];
        let fill = |tris: &mut [[u32; 3]], nbs: &mut [[u32; 3]], first: usize| {
            copy_faces(dt, first, tris, nbs, |_, _| {});
        };
        let chunk = count.div_ceil(threads.max(1)).max(1 << 16);
        let mut unstarted = Vec::new();
        std::thread::scope(|scope| {
            let mut parts = triangles.chunks_mut(chunk).zip(neighbors.chunks_mut(chunk)).enumerate();
            let here = parts.next();
            for (c, (tris, nbs)) in parts {
                if std::thread::Builder::new().spawn_scoped(scope, move || fill(tris, nbs, c * chunk)).is_err() {
                    unstarted.push(c);
                }
            }
            if let Some((_, (tris, nbs))) = here {
                fill(tris, nbs, 0);
            }
        });
        // A chunk whose thread could not be started is done here.
        for c in unstarted {
            let end = ((c + 1) * chunk).min(count);
            if let (Some(tris), Some(nbs)) = (triangles.get_mut(c * chunk..end), neighbors.get_mut(c * chunk..end)) {
                fill(tris, nbs, c * chunk);
            }
        }
        Mesh { triangles, neighbors, vertices: dt.num_vertices() }
    }

    /// `true` when the counts obey Euler's relation for a triangulated convex region whose hull
    /// ring has `hull` corners: `T = 2V − 2 − h`.
    pub fn euler_holds(&self, hull: usize) -> bool {
        self.triangles.len() + 2 + hull == 2 * self.vertices
    }
}

/// Copies inner faces `first..` of `dt` (face `t + 1` is triangle `t`; 0 is the outer face)
/// into `triangles` and `neighbors`, as many as they hold, and shows each face's corner positions
/// and names to `visit`, in order.
pub(super) fn copy_faces(
    dt: &DelaunayTriangulation<Site>,
    first: usize,
    triangles: &mut [[u32; 3]],
    neighbors: &mut [[u32; 3]],
    mut visit: impl FnMut([Point2<f64>; 3], [u32; 3]),
) {
    for ((tri, nb), face) in triangles.iter_mut().zip(neighbors.iter_mut()).zip(dt.inner_faces().skip(first)) {
        let edges = face.adjacent_edges();
        let sites = edges.map(|e| *e.from().data());
        *tri = sites.map(|s| s.pt);
        *nb = edges.map(|e| e.rev().face().as_inner().map_or(NONE, |f| f.index().wrapping_sub(1) as u32));
        visit(sites.map(|s| s.pos), *tri);
    }
}

/// The counter-clockwise ring formed by the directed hull edges `(from, to)`, starting at its
/// smallest corner so it does not depend on the edges' order. `None` when the edges do not form
/// one simple cycle (never for a valid triangulation of a convex region).
pub(super) fn hull_ring(edges: &[(usize, usize)]) -> Option<Vec<usize>> {
    let mut next: HashMap<usize, usize> = HashMap::with_capacity(edges.len());
    for &(from, to) in edges {
        if next.insert(from, to).is_some() {
            return None;
        }
    }
    let &start = next.keys().min()?;
    let mut ring = Vec::with_capacity(next.len());
    let mut at = start;
    loop {
        ring.push(at);
        at = *next.get(&at)?;
        if at == start {
            break;
        }
        if ring.len() > next.len() {
            return None;
        }
    }
    (ring.len() == next.len()).then_some(ring)
}

/// Every point's neighbours along triangle edges, in compressed rows: the neighbours of point `i`
/// are `list[offsets[i]..offsets[i + 1]]`. `points` is the number of points the corners index.
pub(super) fn point_neighbours(
    triangles: &[[u32; 3]],
    neighbors: &[[u32; 3]],
    points: usize,
) -> (Vec<usize>, Vec<u32>) {
    // Each interior edge is seen once from each side; a hull edge only from inside, so its
    // reverse direction is added by hand.
    let mut degree = vec![0usize; points + 1];
    let each_edge = |f: &mut dyn FnMut(usize, usize)| {
        for (tri, nb) in triangles.iter().zip(neighbors) {
            for k in 0..3 {
                let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                f(a, b);
                if nb[k] == NONE {
                    f(b, a);
                }
            }
        }
    };
    each_edge(&mut |a, _| {
        if let Some(d) = degree.get_mut(a + 1) {
            *d += 1;
        }
    });
    let mut running = 0;
    for d in &mut degree {
        running += *d;
        *d = running;
    }
    let offsets = degree;
    let mut fill = offsets.clone();
    let mut list = vec![0u32; offsets.last().copied().unwrap_or(0)];
    each_edge(&mut |a, b| {
        if let Some(slot) = fill.get_mut(a)
            && let Some(entry) = list.get_mut(*slot)
        {
            *entry = b as u32;
            *slot += 1;
        }
    });
    (offsets, list)
}
