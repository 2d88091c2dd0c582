//! Point location: which triangle, edge or point of the mesh a place falls on. A coarse grid over
//! the points gives a triangle to start from; a visibility walk with exact orientation tests
//! (Shewchuk's predicates) crosses edges towards the place until no edge faces away from it.

use robust::{Coord, orient2d};

use super::{NONE, Triangulation};

/// Where a place lies in the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Hit {
    /// On a point (its index).
    Point(u32),
    /// On the edge between two points, not at either end.
    Edge(u32, u32),
    /// Strictly inside a triangle (its index).
    Face(usize),
}

/// Start triangles on a coarse grid over the points' bounding box (in the frame).
#[derive(Debug, Clone)]
pub(super) struct Locator {
    cols: usize,
    rows: usize,
    origin: (f64, f64),
    /// Cells per unit length along x and y.
    scale: (f64, f64),
    /// A triangle near each cell, row by row.
    start: Vec<u32>,
}

impl Locator {
    /// A grid of about one cell per four triangles.
    pub fn new(tin: &Triangulation) -> Locator {
        let (x0, y0, x1, y1) = tin.bbox;
        let side = ((tin.triangles.len() / 4) as f64).sqrt().ceil().max(1.0) as usize;
        let (cols, rows) = (side, side);
        let scale = |lo: f64, hi: f64, n: usize| if hi > lo { n as f64 / (hi - lo) } else { 0.0 };
        let mut locator = Locator {
            cols,
            rows,
            origin: (x0, y0),
            scale: (scale(x0, x1, cols), scale(y0, y1, rows)),
            start: vec![NONE; cols * rows],
        };
        for (t, tri) in tin.triangles.iter().enumerate() {
            let cell = locator.cell(tin.unit(tri[0]));
            if let Some(slot) = locator.start.get_mut(cell) {
                *slot = t as u32;
            }
        }
        // Empty cells borrow the nearest filled cell before them (or after, at the start).
        let mut last = locator.start.iter().copied().find(|&t| t != NONE).unwrap_or(0);
        for slot in &mut locator.start {
            if *slot == NONE {
                *slot = last;
            } else {
                last = *slot;
            }
        }
        locator
    }

    /// The grid cell of a place in the frame (clamped to the grid).
    fn cell(&self, (x, y): (f64, f64)) -> usize {
        let index = |v: f64, lo: f64, scale: f64, n: usize| (((v - lo) * scale) as usize).min(n - 1);
        index(y, self.origin.1, self.scale.1, self.rows) * self.cols + index(x, self.origin.0, self.scale.0, self.cols)
    }

    /// Where the place `q` (in the frame) lies; `None` outside the hull or for an empty mesh.
    pub fn locate(&self, tin: &Triangulation, q: (f64, f64)) -> Option<Hit> {
        let mut t = *self.start.get(self.cell(q))? as usize;
        // A visibility walk ends in a Delaunay triangulation; the bound only guards against a bug.
        for step in 0..=tin.triangles.len() {
            let corners = tin.triangles.get(t)?.map(|i| tin.unit(i));
            let mut side = [0.0f64; 3];
            let mut across = None;
            // Trying the edges from a rotating start avoids walking in circles on ties.
            for j in 0..3 {
                let k = (j + step) % 3;
                side[k] = orient(corners[k], corners[(k + 1) % 3], q);
                if side[k] < 0.0 {
                    across = Some(k);
                    break;
                }
            }
            match across {
                None => return Some(hit(tin, t, side)),
                Some(k) => match tin.neighbors.get(t)?[k] {
                    NONE => return None,
                    n => t = n as usize,
                },
            }
        }
        // Not reached for a valid mesh; search every triangle.
        tin.triangles.iter().enumerate().find_map(|(t, tri)| {
            let c = tri.map(|i| tin.unit(i));
            let side = [0, 1, 2].map(|k| orient(c[k], c[(k + 1) % 3], q));
            side.iter().all(|&s| s >= 0.0).then(|| hit(tin, t, side))
        })
    }
}

/// What a place inside (or on) triangle `t` hits, from its side of each edge (zero: on it).
fn hit(tin: &Triangulation, t: usize, side: [f64; 3]) -> Hit {
    let Some(&tri) = tin.triangles.get(t) else {
        return Hit::Face(t);
    };
    let on = side.map(|s| s == 0.0);
    match on {
        [true, true, false] => Hit::Point(tri[1]),
        [false, true, true] => Hit::Point(tri[2]),
        [true, false, true] => Hit::Point(tri[0]),
        [true, false, false] => Hit::Edge(tri[0], tri[1]),
        [false, true, false] => Hit::Edge(tri[1], tri[2]),
        [false, false, true] => Hit::Edge(tri[2], tri[0]),
        _ => Hit::Face(t),
    }
}

/// Positive when `c` is left of the line from `a` to `b`, zero on it (exact).
pub(super) fn orient(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> f64 {
    orient2d(Coord { x: a.0, y: a.1 }, Coord { x: b.0, y: b.1 }, Coord { x: c.0, y: c.1 })
}
