//! Marching squares on one grid: node classification, the case tables and the tracker that joins
//! cell segments into polylines. Bands reuse all of it.
//!
//! Layout. A cell is named by the index `c = j * nx + i` of its lower-left node. Its corners, in
//! counter-clockwise order, are 0 = `(i, j)`, 1 = `(i+1, j)`, 2 = `(i+1, j+1)`, 3 = `(i, j+1)`;
//! its local edge `l` runs from corner `l` to corner `l + 1` (0 bottom, 1 right, 2 top, 3 left).
//! Every grid edge also has a global id: horizontal edges `(i, j)–(i+1, j)` are
//! `j * (nx − 1) + i`, vertical edges `(i, j)–(i, j+1)` follow as `nh + j * nx + i` with
//! `nh = (nx − 1) * ny`.
//!
//! Segments are oriented with the above region on their left. Walking a cell's boundary
//! counter-clockwise, an edge going from an above corner to a below corner is where a segment
//! *starts*, an edge going from below to above is where one *ends*; in the neighbouring cell the
//! same edge is walked the other way, so a line leaving one cell through an edge enters the next
//! cell at a segment start. That makes tracking a table lookup per cell.

use super::{ContourError, ContourLine, MAX_CROSSED_CELLS, Saddle};
use crate::enrich::grid::{Grid, fraction};

/// Class of a missing node (NaN): any cell touching it is a hole.
pub(super) const HOLE: u16 = u16::MAX;

/// "No edge" in the tables.
const NONE: u8 = 4;

/// Marching-squares tables, indexed by `case | 16 * centre_above` where bit `b` of `case` says
/// corner `b` is above; `centre_above` only matters for the saddle cases 5 and 10.
struct Tables {
    /// `next[idx][start edge]` = the edge where that segment ends, or [`NONE`].
    next: [[u8; 4]; 32],
    /// `prev[idx][end edge]` = the edge where that segment starts, or [`NONE`].
    prev: [[u8; 4]; 32],
    /// Start edges of the cell's segments (zero, one or two), padded with [`NONE`].
    starts: [[u8; 2]; 32],
}

const fn build_tables() -> Tables {
    let mut next = [[NONE; 4]; 32];
    let mut prev = [[NONE; 4]; 32];
    let mut starts = [[NONE; 2]; 32];
    let mut idx = 0;
    while idx < 32 {
        let case = idx & 15;
        let centre_above = idx >= 16;
        let saddle = case == 5 || case == 10;
        let mut n_starts = 0;
        let mut l = 0;
        while l < 4 {
            let a = (case >> l) & 1;
            let b = (case >> ((l + 1) % 4)) & 1;
            if a == 1 && b == 0 {
                let end = if saddle {
                    // Centre above: the below corners are cut off, so a segment starting on edge
                    // l ends on the next edge; otherwise the above corners are cut off and it
                    // ends on the previous edge.
                    if centre_above { (l + 1) % 4 } else { (l + 3) % 4 }
                } else {
                    // Exactly one end edge: the one going from below to above.
                    let mut e = 0;
                    let mut m = 0;
                    while m < 4 {
                        if (case >> m) & 1 == 0 && (case >> ((m + 1) % 4)) & 1 == 1 {
                            e = m;
                        }
                        m += 1;
                    }
                    e
                };
                next[idx][l] = end as u8;
                prev[idx][end] = l as u8;
                if n_starts < 2 {
                    starts[idx][n_starts] = l as u8;
                    n_starts += 1;
                }
            }
            l += 1;
        }
        idx += 1;
    }
    Tables { next, prev, starts }
}

static TABLES: Tables = build_tables();

/// `a + t (b − a)` for `t` in `[0, 1]`, exact at both ends and finite for finite `a`, `b`.
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    if t <= 0.0 {
        a
    } else if t >= 1.0 {
        b
    } else {
        let d = b - a;
        if d.is_finite() { a + t * d } else { (1.0 - t) * a + t * b }
    }
}

/// A grid with every node classified against a sorted list of levels.
pub(super) struct Field<'a> {
    /// Nodes along x.
    pub nx: usize,
    /// Nodes along y.
    pub ny: usize,
    xs: &'a [f64],
    ys: &'a [f64],
    f: &'a [f64],
    /// Per node: how many levels are `<=` its value ([`HOLE`] for NaN). A node is above level
    /// `k` exactly when its class is `> k`.
    cls: Vec<u16>,
    /// Whether any node is missing.
    pub has_holes: bool,
}

impl<'a> Field<'a> {
    /// Classifies `grid` against `levels` (sorted, distinct, finite, at most `u16::MAX − 1`).
    ///
    /// With `top_inclusive`, a node exactly equal to the last level is counted below it (class
    /// `n − 1`): that level then uses `value > level` as "above", which puts such nodes in the
    /// topmost band.
    pub fn new(grid: &'a Grid, levels: &[f64], top_inclusive: bool) -> Field<'a> {
        let values = grid.values();
        let mut cls = vec![0u16; values.len()];
        if levels.len() <= 16 {
            classify_few(values, levels, &mut cls);
        } else {
            classify_many(values, levels, &mut cls);
        }
        let mut has_holes = false;
        let last = levels.last().copied().unwrap_or(f64::NAN);
        for (c, &v) in cls.iter_mut().zip(values) {
            if v.is_nan() {
                *c = HOLE;
                has_holes = true;
            } else if top_inclusive && v == last {
                *c = c.saturating_sub(1);
            }
        }
        Field { nx: grid.nx(), ny: grid.ny(), xs: grid.xs(), ys: grid.ys(), f: values, cls, has_holes }
    }

    /// Class of node `v` ([`HOLE`] outside the grid).
    #[inline]
    pub fn cls(&self, v: usize) -> u16 {
        self.cls.get(v).copied().unwrap_or(HOLE)
    }

    /// Value of node `v` (NaN outside the grid).
    #[inline]
    fn f(&self, v: usize) -> f64 {
        self.f.get(v).copied().unwrap_or(f64::NAN)
    }

    /// Coordinates of node `(i, j)`.
    #[inline]
    pub fn node(&self, i: usize, j: usize) -> (f64, f64) {
        (self.xs.get(i).copied().unwrap_or(f64::NAN), self.ys.get(j).copied().unwrap_or(f64::NAN))
    }

    /// Number of horizontal edges.
    fn n_horizontal(&self) -> usize {
        (self.nx - 1) * self.ny
    }

    /// Number of edges, horizontal and vertical.
    pub fn n_edges(&self) -> usize {
        self.n_horizontal() + self.nx * (self.ny - 1)
    }

    /// Whether the grid has at least one cell.
    pub fn has_cells(&self) -> bool {
        self.nx >= 2 && self.ny >= 2
    }

    /// Whether cell `c` (lower-left node index) has no missing corner.
    #[inline]
    pub fn cell_valid(&self, c: usize) -> bool {
        let nx = self.nx;
        self.cls(c).max(self.cls(c + 1)).max(self.cls(c + nx)).max(self.cls(c + nx + 1)) != HOLE
    }

    /// Global id of local edge `l` of cell `c` in row `j`.
    #[inline]
    pub fn edge_id(&self, c: usize, j: usize, l: u8) -> u32 {
        let id = match l {
            0 => c - j,
            1 => self.n_horizontal() + c + 1,
            2 => c + self.nx - j - 1,
            _ => self.n_horizontal() + c,
        };
        id as u32
    }

    /// The cell across local edge `l` of cell `(c, i, j)` and that edge's local index there;
    /// `None` at the grid border (holes are not checked).
    #[inline]
    pub fn across(&self, c: usize, i: usize, j: usize, l: u8) -> Option<(usize, usize, usize, u8)> {
        match l {
            0 => (j > 0).then(|| (c - self.nx, i, j - 1, 2)),
            1 => (i + 2 < self.nx).then(|| (c + 1, i + 1, j, 3)),
            2 => (j + 2 < self.ny).then(|| (c + self.nx, i, j + 1, 0)),
            _ => (i > 0).then(|| (c - 1, i - 1, j, 1)),
        }
    }

    /// Node indices at the ends of local edge `l` of cell `c`, in counter-clockwise order.
    #[inline]
    pub fn edge_nodes(&self, c: usize, l: u8) -> (usize, usize) {
        let nx = self.nx;
        match l {
            0 => (c, c + 1),
            1 => (c + 1, c + 1 + nx),
            2 => (c + 1 + nx, c + nx),
            _ => (c + nx, c),
        }
    }

    /// Where level `level` crosses local edge `l` of cell `(c, i, j)`. Always interpolated from
    /// the lower-left end, so both cells sharing the edge would get the same bits.
    #[inline]
    fn crossing(&self, c: usize, i: usize, j: usize, l: u8, level: f64) -> (f64, f64) {
        let nx = self.nx;
        let (a, b, horizontal, i, j) = match l {
            0 => (c, c + 1, true, i, j),
            1 => (c + 1, c + 1 + nx, false, i + 1, j),
            2 => (c + nx, c + nx + 1, true, i, j + 1),
            _ => (c, c + nx, false, i, j),
        };
        let t = fraction(self.f(a), self.f(b), level);
        let (x0, y0) = self.node(i, j);
        if horizontal {
            let (x1, _) = self.node(i + 1, j);
            (lerp(x0, x1, t), y0)
        } else {
            let (_, y1) = self.node(i, j + 1);
            (x0, lerp(y0, y1, t))
        }
    }

    /// Cells crossed by at least one level, grouped by level (a cell appears once per level
    /// that crosses it). Hole cells are left out.
    /// Errors when more than [`MAX_CROSSED_CELLS`] (cell, level) pairs would be traced.
    fn candidates(&self, n_levels: usize) -> Result<Candidates, ContourError> {
        let (nx, ny) = (self.nx, self.ny);
        let mut found: Vec<(u32, u16, u16)> = Vec::new();
        for j in 0..ny - 1 {
            let (Some(row0), Some(row1)) =
                (self.cls.get(j * nx..(j + 1) * nx), self.cls.get((j + 1) * nx..(j + 2) * nx))
            else {
                break;
            };
            let quads = row0.iter().zip(&row0[1..]).zip(row1.iter().zip(&row1[1..]));
            for (i, ((&a, &b), (&d, &e))) in quads.enumerate() {
                if a == b && a == d && a == e {
                    continue;
                }
                let hi = a.max(b).max(d).max(e);
                if hi == HOLE {
                    continue;
                }
                let lo = a.min(b).min(d).min(e);
                found.push(((j * nx + i) as u32, lo, hi));
            }
        }
        let total: usize =
            found.iter().map(|&(_, lo, hi)| usize::from(hi).min(n_levels).saturating_sub(usize::from(lo))).sum();
        if total > MAX_CROSSED_CELLS {
            return Err(ContourError::TooManyCrossings { count: total, max: MAX_CROSSED_CELLS });
        }
        let mut start = vec![0usize; n_levels + 1];
        for &(_, lo, hi) in &found {
            for k in usize::from(lo)..usize::from(hi).min(n_levels) {
                if let Some(s) = start.get_mut(k + 1) {
                    *s += 1;
                }
            }
        }
        let mut running = 0;
        for s in &mut start {
            running += *s;
            *s = running;
        }
        let mut fill = start.clone();
        let mut cells = vec![0u32; start.last().copied().unwrap_or(0)];
        for &(c, lo, hi) in &found {
            for k in usize::from(lo)..usize::from(hi).min(n_levels) {
                if let Some(pos) = fill.get_mut(k) {
                    if let Some(cell) = cells.get_mut(*pos) {
                        *cell = c;
                    }
                    *pos += 1;
                }
            }
        }
        Ok(Candidates { start, cells })
    }
}

/// Counts, for each value, the levels `<=` it (NaN counts 0): a few levels, so compare each
/// block of values against every level in turn, which the compiler vectorises.
fn classify_few(values: &[f64], levels: &[f64], cls: &mut [u16]) {
    const BLOCK: usize = 256;
    let mut acc = [0u64; BLOCK];
    for (vals, out) in values.chunks(BLOCK).zip(cls.chunks_mut(BLOCK)) {
        let acc = &mut acc[..vals.len()];
        acc.fill(0);
        for &l in levels {
            for (a, &v) in acc.iter_mut().zip(vals) {
                *a += u64::from(l <= v);
            }
        }
        for (o, &a) in out.iter_mut().zip(acc.iter()) {
            *o = a as u16;
        }
    }
}

/// Like [`classify_few`] for many levels: neighbouring nodes usually share a class, so try the
/// previous node's class before a binary search.
fn classify_many(values: &[f64], levels: &[f64], cls: &mut [u16]) {
    let n = levels.len();
    let mut prev = 0usize;
    for (o, &v) in cls.iter_mut().zip(values) {
        let lower_ok = prev == 0 || levels.get(prev - 1).is_some_and(|&l| l <= v);
        let upper_ok = prev == n || levels.get(prev).is_some_and(|&l| v < l);
        if !(lower_ok && upper_ok) {
            prev = levels.partition_point(|&l| l <= v);
        }
        *o = prev as u16;
    }
}

/// Cells to visit per level, in compressed rows: level `k`'s cells are
/// `cells[start[k]..start[k + 1]]`.
struct Candidates {
    start: Vec<usize>,
    cells: Vec<u32>,
}

impl Candidates {
    fn level(&self, k: usize) -> &[u32] {
        match (self.start.get(k), self.start.get(k + 1)) {
            (Some(&a), Some(&b)) => self.cells.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }
}

/// One traced polyline before cleaning, with the global ids of the edges it starts and ends on
/// (for a closed line both are the id of its first point's edge).
pub(super) struct RawLine {
    /// Crossing points in order, the above side on the left.
    pub points: Vec<(f64, f64)>,
    /// Whether the line joins back to its start.
    pub closed: bool,
    /// Edge holding the first point.
    pub first_edge: u32,
    /// Edge holding the last point.
    pub last_edge: u32,
}

/// Traces the lines of one level.
struct Tracer<'f, 'a> {
    field: &'f Field<'a>,
    /// Level index: a node is above when its class is `> k`.
    k: u16,
    level: f64,
    /// Use `>` rather than `>=` for the saddle centre (the top level of bands).
    strict: bool,
    saddle: Saddle,
    visited: &'f mut [u64],
    fwd: Vec<(f64, f64)>,
    back: Vec<(f64, f64)>,
}

impl Tracer<'_, '_> {
    #[inline]
    fn is_visited(&self, e: u32) -> bool {
        let e = e as usize;
        self.visited.get(e / 64).is_some_and(|w| w & (1u64 << (e % 64)) != 0)
    }

    #[inline]
    fn visit(&mut self, e: u32) {
        let e = e as usize;
        if let Some(w) = self.visited.get_mut(e / 64) {
            *w |= 1u64 << (e % 64);
        }
    }

    /// Table index of cell `c`, or `None` for a hole.
    #[inline]
    fn case(&self, c: usize) -> Option<usize> {
        let fd = self.field;
        let nx = fd.nx;
        let (a, b, d, e) = (fd.cls(c), fd.cls(c + 1), fd.cls(c + nx + 1), fd.cls(c + nx));
        if a.max(b).max(d).max(e) == HOLE {
            return None;
        }
        let k = self.k;
        let case = usize::from(a > k) | usize::from(b > k) << 1 | usize::from(d > k) << 2 | usize::from(e > k) << 3;
        if (case == 5 || case == 10) && self.centre_above(c, case) { Some(case | 16) } else { Some(case) }
    }

    /// Saddle decision for cell `c` with case 5 (corners 0 and 2 above) or 10 (1 and 3 above).
    fn centre_above(&self, c: usize, case: usize) -> bool {
        let fd = self.field;
        let nx = fd.nx;
        let (f00, f10, f11, f01) = (fd.f(c), fd.f(c + 1), fd.f(c + nx + 1), fd.f(c + nx));
        let level = self.level;
        match self.saddle {
            Saddle::Center => {
                let mean = 0.25 * f00 + 0.25 * f10 + 0.25 * f01 + 0.25 * f11;
                if self.strict { mean > level } else { mean >= level }
            }
            Saddle::Asymptotic => {
                // With g = f − level the saddle value of g is (g00 g11 − g01 g10) / D, and D has
                // the sign of the above diagonal (positive for case 5, negative for case 10), so
                // "saddle value >= level" is "product of the above diagonal >= product of the
                // below diagonal". No division, so no trouble when D rounds to zero.
                let (g00, g10, g11, g01) = (f00 - level, f10 - level, f11 - level, f01 - level);
                let (above, below) = if case == 5 { (g00 * g11, g01 * g10) } else { (g10 * g01, g00 * g11) };
                if self.strict { above > below } else { above >= below }
            }
        }
    }

    /// Traces every line through the given candidate cells.
    fn run(&mut self, cells: &[u32], out: &mut Vec<RawLine>) {
        let nx = self.field.nx;
        for &c in cells {
            let c = c as usize;
            let Some(idx) = self.case(c) else { continue };
            let Some(starts) = TABLES.starts.get(idx) else { continue };
            for &s in starts {
                if s == NONE {
                    break;
                }
                let (i, j) = (c % nx, c / nx);
                if self.is_visited(self.field.edge_id(c, j, s)) {
                    continue;
                }
                out.push(self.trace(c, i, j, s, idx));
            }
        }
    }

    /// Follows the line through the segment starting on local edge `s` of cell `(c, i, j)`:
    /// forwards until it leaves the grid, meets a hole or returns to its start, then (if open)
    /// backwards from the start.
    fn trace(&mut self, c0: usize, i0: usize, j0: usize, s0: u8, idx0: usize) -> RawLine {
        let fd = self.field;
        let level = self.level;
        let start_edge = fd.edge_id(c0, j0, s0);
        self.visit(start_edge);
        self.fwd.clear();
        self.back.clear();
        self.fwd.push(fd.crossing(c0, i0, j0, s0, level));

        let (mut c, mut i, mut j) = (c0, i0, j0);
        let mut e = TABLES.next.get(idx0).map_or(NONE, |t| t[usize::from(s0 & 3)]);
        let mut closed = false;
        let mut last_edge = start_edge;
        while e != NONE {
            let id = fd.edge_id(c, j, e);
            if id == start_edge {
                closed = true;
                break;
            }
            if self.is_visited(id) {
                break; // cannot happen with consistent tables; stops rather than loops
            }
            self.visit(id);
            self.fwd.push(fd.crossing(c, i, j, e, level));
            last_edge = id;
            let Some((c2, i2, j2, entry)) = fd.across(c, i, j, e) else { break };
            let Some(idx) = self.case(c2) else { break };
            (c, i, j) = (c2, i2, j2);
            e = TABLES.next.get(idx).map_or(NONE, |t| t[usize::from(entry)]);
        }

        let mut first_edge = start_edge;
        if !closed {
            let (mut c, mut i, mut j, mut e) = (c0, i0, j0, s0);
            while let Some((c2, i2, j2, exit)) = fd.across(c, i, j, e) {
                let Some(idx) = self.case(c2) else { break };
                let s = TABLES.prev.get(idx).map_or(NONE, |t| t[usize::from(exit)]);
                if s == NONE {
                    break;
                }
                let id = fd.edge_id(c2, j2, s);
                if self.is_visited(id) {
                    break;
                }
                self.visit(id);
                self.back.push(fd.crossing(c2, i2, j2, s, level));
                first_edge = id;
                (c, i, j, e) = (c2, i2, j2, s);
            }
        }

        let mut points = Vec::with_capacity(self.back.len() + self.fwd.len());
        points.extend(self.back.iter().rev());
        points.extend_from_slice(&self.fwd);
        RawLine {
            points,
            closed,
            first_edge: if closed { start_edge } else { first_edge },
            last_edge: if closed { start_edge } else { last_edge },
        }
    }
}

/// Traces all lines of every level; `strict_top` makes the last level use `value > level` for
/// the saddle centre (pair it with a `top_inclusive` field). Returns one list per level.
pub(super) fn trace_levels(
    field: &Field<'_>,
    levels: &[f64],
    strict_top: bool,
    saddle: Saddle,
) -> Result<Vec<Vec<RawLine>>, ContourError> {
    if !field.has_cells() || levels.is_empty() {
        return Ok(levels.iter().map(|_| Vec::new()).collect());
    }
    let cands = field.candidates(levels.len())?;
    let mut visited = vec![0u64; field.n_edges().div_ceil(64)];
    let mut result = Vec::with_capacity(levels.len());
    for (k, &level) in levels.iter().enumerate() {
        let cells = cands.level(k);
        let mut out = Vec::new();
        let mut tracer = Tracer {
            field,
            k: k as u16,
            level,
            strict: strict_top && k + 1 == levels.len(),
            saddle,
            visited: &mut visited,
            fwd: Vec::new(),
            back: Vec::new(),
        };
        tracer.run(cells, &mut out);
        // Clear only the bits this level can have set: edges of its candidate cells.
        for &c in cells {
            let c = c as usize;
            let j = c / field.nx;
            for l in 0..4 {
                let e = field.edge_id(c, j, l) as usize;
                if let Some(w) = visited.get_mut(e / 64) {
                    *w = 0;
                }
            }
        }
        result.push(out);
    }
    Ok(result)
}

/// Removes consecutive repeated points (and, for a ring, a last point equal to the first).
pub(super) fn dedup_points(points: &mut Vec<(f64, f64)>, closed: bool) {
    points.dedup();
    if closed && points.len() > 1 && points.first() == points.last() {
        points.pop();
    }
}

/// Contour lines for cleaned levels (sorted, distinct, finite, at most `MAX_LEVELS`).
pub(super) fn contour_lines(grid: &Grid, levels: &[f64], saddle: Saddle) -> Result<Vec<ContourLine>, ContourError> {
    if levels.is_empty() || grid.nx() < 2 || grid.ny() < 2 {
        return Ok(Vec::new());
    }
    let field = Field::new(grid, levels, false);
    let traced = trace_levels(&field, levels, false, saddle)?;
    let mut out = Vec::new();
    for (raw, &level) in traced.into_iter().zip(levels) {
        for line in raw {
            let mut points = line.points;
            dedup_points(&mut points, line.closed);
            if points.len() >= 2 {
                out.push(ContourLine { level, points, closed: line.closed });
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tables agree with geometry: every segment (drawn between edge midpoints of a unit
    /// cell) has the above corners on its left and the below corners on its right; in saddle
    /// cells, the corner it cuts off is on the correct side and the centre is on the side the
    /// decision says.
    #[test]
    fn segments_keep_above_on_the_left() {
        let corner = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let mid = |l: usize| {
            let (a, b) = (corner[l], corner[(l + 1) % 4]);
            ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0)
        };
        let side = |p: (f64, f64), q: (f64, f64), r: (f64, f64)| (q.0 - p.0) * (r.1 - p.1) - (q.1 - p.1) * (r.0 - p.0);
        for idx in 0..32usize {
            let case = idx & 15;
            let saddle = case == 5 || case == 10;
            let mut n = 0;
            for s in 0..4usize {
                let e = TABLES.next[idx][s];
                if e == NONE {
                    continue;
                }
                let e = e as usize;
                n += 1;
                assert_eq!(TABLES.prev[idx][e] as usize, s);
                let (p, q) = (mid(s), mid(e));
                for (b, &c) in corner.iter().enumerate() {
                    let above = (case >> b) & 1 == 1;
                    let cut_off = (e == (s + 3) % 4 && b == s) || (e == (s + 1) % 4 && b == e);
                    if !saddle || cut_off {
                        assert_eq!(side(p, q, c) > 0.0, above, "idx {idx}, {s}->{e}, corner {b}");
                    }
                }
                if saddle {
                    assert_eq!(side(p, q, (0.5, 0.5)) > 0.0, idx >= 16, "idx {idx} centre");
                }
            }
            let expected = match case {
                0 | 15 => 0,
                5 | 10 => 2,
                _ => 1,
            };
            assert_eq!(n, expected, "case {case}");
            let starts = TABLES.starts[idx].iter().filter(|&&s| s != NONE).count();
            assert_eq!(starts, expected);
        }
    }
}
