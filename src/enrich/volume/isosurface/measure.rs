//! Measures of a mesh: area, enclosed volume, Euler characteristic and connected components.

use super::IsoMesh;
use super::cube::{cross, dot, norm, sub};

impl IsoMesh {
    /// The corners of triangle `t` (a vertex index out of range reads as the origin).
    fn corners(&self, t: &[u32; 3]) -> [[f64; 3]; 3] {
        t.map(|v| self.positions.get(v as usize).copied().unwrap_or([0.0; 3]))
    }

    /// The total area of the triangles, in world units squared.
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = self.corners(t);
                0.5 * norm(cross(sub(b, a), sub(c, a)))
            })
            .sum()
    }

    /// The signed volume enclosed, by the divergence theorem: the sum over triangles of
    /// `a · (b × c) / 6`. Positive for a closed surface wound counter-clockwise from outside
    /// (the mesh's convention). For a surface cut open by the volume's edge or a hole the
    /// result depends on the origin.
    pub fn enclosed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = self.corners(t);
                dot(a, cross(b, c)) / 6.0
            })
            .sum()
    }

    /// `V − E + F` over the vertices used by triangles, the distinct edges and the triangles:
    /// 2 for a sphere, 0 for a torus; each boundary loop of an open surface lowers it by one.
    pub fn euler_characteristic(&self) -> i64 {
        // Each edge listed under its smaller end (a counting sort), then the few edges of each
        // vertex deduplicated on their own.
        let n = self.triangles.iter().flatten().max().map_or(0, |&v| v as usize + 1);
        let mut used = vec![false; n];
        let mut starts = vec![0u32; n + 1];
        for t in &self.triangles {
            for i in 0..3 {
                used[t[i] as usize] = true;
                starts[t[i].min(t[(i + 1) % 3]) as usize + 1] += 1;
            }
        }
        for v in 0..n {
            starts[v + 1] += starts[v];
        }
        let mut cursor = starts.clone();
        let mut far = vec![0u32; 3 * self.triangles.len()];
        for t in &self.triangles {
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                let at = &mut cursor[a.min(b) as usize];
                far[*at as usize] = a.max(b);
                *at += 1;
            }
        }
        let mut edges = 0usize;
        for v in 0..n {
            let list = &mut far[starts[v] as usize..starts[v + 1] as usize];
            list.sort_unstable();
            edges += list.chunk_by(|a, b| a == b).count();
        }
        let vertices = used.iter().filter(|&&u| u).count();
        vertices as i64 - edges as i64 + self.triangles.len() as i64
    }

    /// The number of connected pieces of the triangles (sharing a vertex joins two triangles).
    pub fn components(&self) -> usize {
        let mut parent: Vec<u32> = (0..self.positions.len() as u32).collect();
        fn root(parent: &mut [u32], v: u32) -> u32 {
            let mut v = v;
            while let Some(&up) = parent.get(v as usize) {
                if up == v {
                    break;
                }
                let grand = parent.get(up as usize).copied().unwrap_or(up);
                if let Some(slot) = parent.get_mut(v as usize) {
                    *slot = grand;
                }
                v = up;
            }
            v
        }
        let mut used = vec![false; parent.len()];
        for t in &self.triangles {
            for &v in t {
                if let Some(u) = used.get_mut(v as usize) {
                    *u = true;
                }
            }
            for &v in &t[1..] {
                let (r0, r) = (root(&mut parent, t[0]), root(&mut parent, v));
                if r != r0
                    && let Some(slot) = parent.get_mut(r.max(r0) as usize)
                {
                    *slot = r.min(r0);
                }
            }
        }
        (0..parent.len() as u32).filter(|&v| used[v as usize] && root(&mut parent, v) == v).count()
    }
}
