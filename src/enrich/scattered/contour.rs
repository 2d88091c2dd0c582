//! Marching triangles on the linear TIN.
//!
//! A triangle's corners are `0, 1, 2` counter-clockwise; its edge `k` runs from corner `k` to
//! corner `k + 1`. For one level, a triangle whose corners are neither all above nor all below is
//! crossed by exactly one segment (no ambiguous cases, unlike squares). Walking its boundary
//! counter-clockwise, the edge going from an above corner to a below corner is where the segment
//! *starts* and the edge going from below to above is where it *ends*; that puts the above region
//! on the segment's left. The neighbour across the end edge walks that edge the other way, so
//! there it is the start edge: a line is followed from triangle to triangle through the
//! neighbour table alone (edges are identified by the triangles sharing them, never by
//! comparing coordinates).

use super::{MAX_CROSSINGS, ScatteredError, TinLine, Triangulation};
use crate::enrich::contour::ContourError;
use crate::enrich::grid::fraction;

/// Cleans the levels, counts crossings, and traces every level.
pub(super) fn contour_lines(tin: &Triangulation, levels: &[f64]) -> Result<Vec<TinLine>, ScatteredError> {
    // The same level cleaning as grid contours: finite, sorted, distinct, at most MAX_LEVELS.
    let levels = crate::enrich::contour::clean_levels(levels).map_err(|e| match e {
        ContourError::TooManyLevels { count, max } => ScatteredError::TooManyLevels { count, max },
        ContourError::TooManyCrossings { count, max } => ScatteredError::TooManyCrossings { count, max },
    })?;
    if levels.is_empty() || tin.triangles.is_empty() {
        return Ok(Vec::new());
    }

    // Level range of each non-hole triangle: levels in (zmin, zmax] cross it.
    let ranges: Vec<(u32, u32)> = tin
        .triangles
        .iter()
        .map(|tri| match corner_values(tin, tri) {
            Some(z) => {
                let zmin = z[0].min(z[1]).min(z[2]);
                let zmax = z[0].max(z[1]).max(z[2]);
                let lo = levels.partition_point(|&l| l <= zmin);
                let hi = levels.partition_point(|&l| l <= zmax);
                (lo as u32, hi.max(lo) as u32)
            }
            None => (0, 0),
        })
        .collect();
    let total = ranges.iter().fold(0usize, |acc, &(lo, hi)| acc.saturating_add((hi - lo) as usize));
    if total > MAX_CROSSINGS {
        return Err(ScatteredError::TooManyCrossings { count: total, max: MAX_CROSSINGS });
    }

    // Crossed triangles grouped by level (compressed rows).
    let mut starts = vec![0usize; levels.len() + 1];
    for &(lo, hi) in &ranges {
        for l in lo..hi {
            if let Some(s) = starts.get_mut(l as usize + 1) {
                *s += 1;
            }
        }
    }
    for l in 1..starts.len() {
        let before = starts.get(l - 1).copied().unwrap_or(0);
        if let Some(s) = starts.get_mut(l) {
            *s += before;
        }
    }
    let mut fill = starts.clone();
    let mut crossed = vec![0u32; total];
    for (t, &(lo, hi)) in ranges.iter().enumerate() {
        for l in lo..hi {
            if let Some(f) = fill.get_mut(l as usize) {
                if let Some(slot) = crossed.get_mut(*f) {
                    *slot = t as u32;
                }
                *f += 1;
            }
        }
    }
    drop(ranges);

    let mut seen = vec![u32::MAX; tin.triangles.len()];
    let mut out = Vec::new();
    for (li, &level) in levels.iter().enumerate() {
        let (Some(&a), Some(&b)) = (starts.get(li), starts.get(li + 1)) else {
            continue;
        };
        let Some(list) = crossed.get(a..b) else {
            continue;
        };
        let tracer = Tracer { tin, level, stamp: li as u32 };
        // Open lines first: those whose start edge is on the hull or a hole's edge.
        for &t in list {
            let t = t as usize;
            if seen.get(t) == Some(&tracer.stamp) {
                continue;
            }
            let Some((start, _)) = tracer.edges(t) else {
                continue;
            };
            if tracer.across(t, start).is_none() {
                push_line(&mut out, level, tracer.follow(t, true, &mut seen));
            }
        }
        // Whatever is left forms rings.
        for &t in list {
            let t = t as usize;
            if seen.get(t) != Some(&tracer.stamp) && tracer.edges(t).is_some() {
                push_line(&mut out, level, tracer.follow(t, false, &mut seen));
            }
        }
    }
    Ok(out)
}

/// The corner values of a triangle, or `None` for a hole (a missing value).
fn corner_values(tin: &Triangulation, tri: &[u32; 3]) -> Option<[f64; 3]> {
    let mut z = [0.0; 3];
    for (zk, &v) in z.iter_mut().zip(tri) {
        *zk = *tin.values.get(v as usize)?;
        if zk.is_nan() {
            return None;
        }
    }
    Some(z)
}

/// Drops repeated points and stores the line if anything is left.
fn push_line(out: &mut Vec<TinLine>, level: f64, (mut points, closed): (Vec<(f64, f64)>, bool)) {
    points.dedup();
    if closed && points.len() > 1 && points.first() == points.last() {
        points.pop();
    }
    if points.len() >= 2 {
        out.push(TinLine { level, points, closed });
    }
}

/// Follows lines of one level.
struct Tracer<'a> {
    tin: &'a Triangulation,
    level: f64,
    /// Marks triangles visited at this level in the shared `seen` table.
    stamp: u32,
}

impl Tracer<'_> {
    /// The start and end edge of triangle `t`'s segment, or `None` if the level does not cross
    /// it (or it is a hole).
    fn edges(&self, t: usize) -> Option<(usize, usize)> {
        let z = corner_values(self.tin, self.tin.triangles.get(t)?)?;
        let above = z.map(|v| v >= self.level);
        let (mut start, mut end) = (None, None);
        for k in 0..3 {
            match (above[k], above[(k + 1) % 3]) {
                (true, false) => start = Some(k),
                (false, true) => end = Some(k),
                _ => {}
            }
        }
        Some((start?, end?))
    }

    /// The crossed, non-hole triangle across edge `k` of `t`, if any.
    fn across(&self, t: usize, k: usize) -> Option<usize> {
        let n = self.tin.neighbor(t, k)?;
        self.edges(n).map(|_| n)
    }

    /// Where the level crosses edge `k` of triangle `t`, computed from the edge's ends in a
    /// fixed order so both triangles sharing the edge would get the same bits.
    fn crossing(&self, t: usize, k: usize) -> (f64, f64) {
        let Some(tri) = self.tin.triangles.get(t) else {
            return (f64::NAN, f64::NAN);
        };
        let (u, w) = (tri[k % 3] as usize, tri[(k + 1) % 3] as usize);
        let (lo, hi) = (u.min(w), u.max(w));
        let (Some(&p), Some(&q), Some(&zp), Some(&zq)) =
            (self.tin.points.get(lo), self.tin.points.get(hi), self.tin.values.get(lo), self.tin.values.get(hi))
        else {
            return (f64::NAN, f64::NAN);
        };
        let s = fraction(zp, zq, self.level);
        (super::lerp(p.0, q.0, s), super::lerp(p.1, q.1, s))
    }

    /// Follows the line through `t0` forwards, marking triangles in `seen`. An open line starts
    /// on `t0`'s start edge and runs until it leaves the non-hole TIN; a ring runs until it gets
    /// back to `t0`. Returns the points and whether the line is closed.
    fn follow(&self, t0: usize, open: bool, seen: &mut [u32]) -> (Vec<(f64, f64)>, bool) {
        let mut points = Vec::new();
        let Some((start, _)) = self.edges(t0) else {
            return (points, false);
        };
        if open {
            points.push(self.crossing(t0, start));
        }
        let mut t = t0;
        // Each step marks a new triangle, so this ends within `seen.len()` steps.
        loop {
            let Some(mark) = seen.get_mut(t) else {
                return (points, false);
            };
            *mark = self.stamp;
            let Some((_, end)) = self.edges(t) else {
                return (points, false);
            };
            points.push(self.crossing(t, end));
            let Some(next) = self.across(t, end) else {
                return (points, false);
            };
            if seen.get(next) == Some(&self.stamp) {
                return (points, !open && next == t0);
            }
            t = next;
        }
    }
}
