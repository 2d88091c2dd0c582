//! Contour lines and filled contour bands on a regular 2D grid.
//!
//! Method: each grid cell is the bilinear patch through its four corner values; marching squares
//! classifies the corners against a level, places a crossing on every edge whose ends lie on
//! different sides (linear interpolation along the edge, i.e. the bilinear patch restricted to
//! it), and joins the crossings with straight segments. The two ambiguous ("saddle") corner
//! patterns are resolved by [`Saddle`]. Segments are tracked from cell to cell through shared
//! edge crossings into polylines ([`contour_lines`]); bands between consecutive levels are built
//! from the same lines plus pieces of the grid boundary ([`contour_bands`]).
//!
//! Conventions, shared by lines and bands:
//! - **Above / below.** A node with `value >= level` is *above* the level, otherwise *below*.
//!   A contour line is the boundary, inside the grid, of the (linearised) region `{f >= level}`,
//!   oriented with that region on its **left**.
//! - **Level equal to the grid minimum** gives no line (every node is above, so the region has no
//!   boundary inside the grid). **Level equal to the maximum** gives closed rings around plateaus
//!   of maximal nodes; a lone maximal node gives a ring of zero length, which is dropped.
//! - **Bands** hold `lower <= f < upper`, the topmost band also `f == upper`; values outside
//!   the first and last level are not filled.
//! - **Holes.** A cell with a missing corner (NaN or ±inf, see [`crate::enrich::grid`]) is a
//!   hole: it gets no segments, so lines stop on the hole's edge (as open lines) and bands leave
//!   it unfilled.
//! - **Levels** are cleaned first: non-finite levels are dropped, the rest sorted and
//!   deduplicated. More than [`MAX_LEVELS`] distinct levels is an error
//!   ([`ContourError::TooManyLevels`]), never a silent cut.
//! - **Size.** Work and output grow with the number of (cell, level) crossings; nothing is
//!   allocated per segment. More than [`MAX_CROSSED_CELLS`] crossings is an error
//!   ([`ContourError::TooManyCrossings`]), found by counting before anything large is allocated.

mod bands;
mod lines;
#[cfg(test)]
mod tests;

use std::fmt;

use crate::enrich::grid::Grid;

/// Most distinct levels one call accepts.
pub const MAX_LEVELS: usize = 1000;

/// Most (cell, level) crossings one call traces (2²² ≈ 4.2 million). Each crossing yields about
/// one output point per line (two for bands, whose rings share lines), and a chart draws both, so
/// this bounds a chart's contour geometry near a gigabyte at worst (a 500 × 500 grid of uniform
/// noise with ten levels, about 1.6 million crossings, peaks at 650 MB as a whole process). Fields
/// that cross more cells are noise at the grid's scale: an image shows them better.
pub const MAX_CROSSED_CELLS: usize = 1 << 22;

/// How a saddle cell (corners alternating above/below around the cell, marching-squares cases 5
/// and 10) connects its four crossings.
///
/// Either way the two segments separate the corners; the choice is whether the two *above*
/// corners are joined through the cell centre (the centre counts as above) or the two *below*
/// corners are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Saddle {
    /// The asymptotic decider: the centre is above when the bilinear patch's saddle value
    /// `(f00·f11 − f01·f10) / (f00 + f11 − f01 − f10)` is `>= level` (see
    /// [`asymptotic_saddle_value`]). This matches the true topology of the bilinear patch.
    #[default]
    Asymptotic,
    /// The centre is above when the mean of the four corners is `>= level`.
    Center,
}

/// One contour line at one level.
#[derive(Debug, Clone, PartialEq)]
pub struct ContourLine {
    /// The level this line traces.
    pub level: f64,
    /// Vertices in data coordinates, with the region `{f >= level}` on the left. No two
    /// consecutive points are equal; a closed line does not repeat its first point at the end.
    pub points: Vec<(f64, f64)>,
    /// `true` for a ring (the last point joins back to the first). An open line starts and ends
    /// on the grid boundary or on the edge of a hole.
    pub closed: bool,
}

/// The filled region between two consecutive levels.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Lower level; points with `value >= lower` are in the band (if also below `upper`).
    pub lower: f64,
    /// Upper level; points with `value < upper` are in the band, and for the topmost band also
    /// points with `value == upper`.
    pub upper: f64,
    /// Polygons in data coordinates: each is its outer ring followed by its holes. Rings are
    /// closed implicitly (the first point is not repeated); outer rings run counter-clockwise
    /// (positive signed area), holes clockwise.
    pub polygons: Vec<Vec<Vec<(f64, f64)>>>,
}

/// Why contours could not be computed.
#[derive(Debug, Clone, PartialEq)]
pub enum ContourError {
    /// More than [`MAX_LEVELS`] distinct finite levels.
    TooManyLevels {
        /// Number of distinct finite levels given.
        count: usize,
        /// The cap, [`MAX_LEVELS`].
        max: usize,
    },
    /// The levels cross more than [`MAX_CROSSED_CELLS`] cells in total (counted once per level),
    /// typically many levels over a large noisy grid.
    TooManyCrossings {
        /// Number of (cell, level) crossings the request needs.
        count: usize,
        /// The cap, [`MAX_CROSSED_CELLS`].
        max: usize,
    },
}

impl fmt::Display for ContourError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ContourError::TooManyLevels { count, max } => write!(
                f,
                "{count} distinct contour levels were given but at most {max} are allowed; pass \
                 fewer levels (for example a level count, which picks nice round levels)"
            ),
            ContourError::TooManyCrossings { count, max } => write!(
                f,
                "these levels cross grid cells {count} times but at most {max} crossings are \
                 traced; use fewer levels, smooth or resample the grid to fewer cells, or draw it as \
                 `kind = \"image\"`"
            ),
        }
    }
}

impl std::error::Error for ContourError {}

/// Contour lines of `grid` at each of `levels` (cleaned as described in the module docs),
/// ordered by level. For example on the plane `f = x` the level 0.5 gives the single open line
/// `[(0.5, y_max), (0.5, y_min)]` (larger x on its left).
pub fn contour_lines(grid: &Grid, levels: &[f64], saddle: Saddle) -> Result<Vec<ContourLine>, ContourError> {
    let levels = clean_levels(levels)?;
    lines::contour_lines(grid, &levels, saddle)
}

/// Filled bands between consecutive levels: band `k` covers `levels[k] <= f < levels[k + 1]`,
/// the topmost band also `f == levels[last]`. One [`Band`] per consecutive pair, in order, even
/// when its polygons are empty.
///
/// Levels are cleaned first (module docs); fewer than two levels give no bands. Values below the
/// first level or above the last are not filled: pass the grid's minimum and maximum (see
/// [`Grid::range`]) as the outer levels to fill every non-hole cell. Adjacent bands share their
/// boundary lines exactly, so together they tile the non-hole cells without gaps or overlaps.
pub fn contour_bands(grid: &Grid, levels: &[f64], saddle: Saddle) -> Result<Vec<Band>, ContourError> {
    let levels = clean_levels(levels)?;
    bands::contour_bands(grid, &levels, saddle)
}

/// Drops non-finite levels, sorts and deduplicates the rest; errors past [`MAX_LEVELS`].
pub fn clean_levels(levels: &[f64]) -> Result<Vec<f64>, ContourError> {
    let mut out: Vec<f64> = levels.iter().copied().filter(|l| l.is_finite()).collect();
    out.sort_by(f64::total_cmp);
    out.dedup_by(|a, b| a == b);
    if out.len() > MAX_LEVELS {
        return Err(ContourError::TooManyLevels { count: out.len(), max: MAX_LEVELS });
    }
    Ok(out)
}

/// About `count` nice round levels strictly inside `(min, max)`: the multiples of a step
/// `m × 10^k` with `m` in {1, 2, 2.5, 5}. Of the steps near `(max − min) / count`, the one giving
/// the most levels without exceeding `count` wins (the larger step on a tie), so at most `count`
/// levels come back, e.g. `(0, 1, 10)` gives 0.1, 0.2, …, 0.9 and `(0, 100, 4)` gives 20, 40, 60,
/// 80.
///
/// Empty when `min` or `max` is not finite, `min >= max`, or `count == 0`; `count` is capped at
/// [`MAX_LEVELS`]. Levels are computed as integer multiples divided by a power of ten, so they
/// are the doubles nearest the short decimals (0.3, not 0.30000000000000004).
pub fn nice_levels(min: f64, max: f64, count: usize) -> Vec<f64> {
    let count = count.min(MAX_LEVELS);
    if !(min.is_finite() && max.is_finite()) || min >= max || count == 0 {
        return Vec::new();
    }
    // Halves first, so the span of ±f64::MAX does not overflow.
    let raw = (0.5 * max - 0.5 * min) / count as f64 * 2.0;
    let Some(mut step) = nice_step(raw) else {
        return Vec::new();
    };
    let mut best: Vec<f64> = Vec::new();
    // The step at or above `raw` and the next three smaller nice steps.
    for _ in 0..4 {
        if let Some(levels) = multiples(min, max, step, count)
            && levels.len() > best.len()
        {
            best = levels;
        }
        step = smaller_step(step);
    }
    best
}

/// The multiples of `m × 10^e` strictly inside `(min, max)`, or `None` if more than `cap`.
fn multiples(min: f64, max: f64, (m, e): (f64, i32), cap: usize) -> Option<Vec<f64>> {
    let at = |k: f64| {
        if e >= 0 { k * m * 10f64.powi(e) } else { k * m / 10f64.powi(-e) }
    };
    let step = at(1.0);
    if !(step.is_finite() && step > 0.0) {
        return Some(Vec::new());
    }
    let first = (min / step).floor();
    let mut out: Vec<f64> = Vec::new();
    // About span / step <= count + 1 multiples fit; a few extra rounds absorb rounding.
    for n in 0..cap + 4 {
        let level = at(first + n as f64);
        if level >= max {
            return Some(out);
        }
        if level > min && out.last().is_none_or(|&last| level > last) {
            if out.len() == cap {
                return None;
            }
            out.push(level);
        }
    }
    Some(out)
}

/// The next smaller nice step: 5 → 2.5 → 2 → 1 → 0.5 (each times the same power of ten).
fn smaller_step((m, e): (f64, i32)) -> (f64, i32) {
    if m == 5.0 {
        (25.0, e - 1)
    } else if m == 25.0 {
        (2.0, e + 1)
    } else if m == 2.0 {
        (1.0, e)
    } else {
        (5.0, e - 1)
    }
}

/// The smallest step `m × 10^e >= raw` with `m` in {1, 2, 2.5, 5}, returned as `(m', e')` with
/// an integer-valued `m'` (2.5 becomes 25 × 10^(e−1)); `None` for non-positive or non-finite
/// `raw`.
fn nice_step(raw: f64) -> Option<(f64, i32)> {
    if !(raw.is_finite() && raw > 0.0) {
        return None;
    }
    let mut exp = raw.log10().floor() as i32;
    // Guard against log10 rounding: make 10^exp <= raw < 10^(exp+1).
    if pow10(exp) > raw {
        exp -= 1;
    }
    if pow10(exp + 1) <= raw {
        exp += 1;
    }
    for (m, shift) in [(1.0, 0), (2.0, 0), (25.0, -1), (5.0, 0)] {
        if m * pow10(exp + shift) >= raw {
            return Some((m, exp + shift));
        }
    }
    Some((1.0, exp + 1))
}

/// `10^e` as an `f64`, exact for the integer powers that are representable.
fn pow10(e: i32) -> f64 {
    if e >= 0 { 10f64.powi(e) } else { 1.0 / 10f64.powi(-e) }
}

/// The value of the bilinear patch at its saddle point, `(f00·f11 − f01·f10) / D` with
/// `D = f00 + f11 − f01 − f10`; `None` when `D == 0` (no saddle: the patch is then linear along
/// one direction) or the result is not finite.
///
/// Corner naming: `f00` at `(x0, y0)`, `f10` at `(x1, y0)`, `f01` at `(x0, y1)`, `f11` at
/// `(x1, y1)`. Example: `f00 = −3, f10 = 1, f01 = 10, f11 = −5` gives `D = −19` and the saddle
/// value `(15 − 10) / −19 = −5/19 ≈ −0.263`.
pub fn asymptotic_saddle_value(f00: f64, f10: f64, f01: f64, f11: f64) -> Option<f64> {
    let d = f00 + f11 - f01 - f10;
    if d == 0.0 {
        return None;
    }
    let v = (f00 * f11 - f01 * f10) / d;
    v.is_finite().then_some(v)
}

/// Where the bilinear patch has its saddle, in cell-local coordinates `(s, t)` (`s = 0` at `x0`,
/// `s = 1` at `x1`, likewise `t` along y; the point may lie outside the unit square).
///
/// Writing the patch as `f = f00 + (f10 − f00) s + (f01 − f00) t + D s t` with
/// `D = f00 + f11 − f01 − f10`, the gradient vanishes at `s* = (f00 − f01) / D`,
/// `t* = (f00 − f10) / D`; in data coordinates `x* = x0 + s* (x1 − x0)`,
/// `y* = y0 + t* (y1 − y0)`. `None` when `D == 0` or the result is not finite. Example:
/// `f00 = −3, f10 = 1, f01 = 10, f11 = −5` gives `(13/19, 4/19) ≈ (0.684, 0.211)`.
pub fn saddle_point(f00: f64, f10: f64, f01: f64, f11: f64) -> Option<(f64, f64)> {
    let d = f00 + f11 - f01 - f10;
    if d == 0.0 {
        return None;
    }
    let (s, t) = ((f00 - f01) / d, (f00 - f10) / d);
    (s.is_finite() && t.is_finite()).then_some((s, t))
}
