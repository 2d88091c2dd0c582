//! Where streamlines start: simple seed sets and evenly spaced streamlines.
//!
//! [`rake`], [`grid_seeds`] and [`circle`] place seeds on a segment, a lattice of cell centres and
//! a circle. [`evenly_spaced`] follows Jobard & Lefer (1997), "Creating evenly-spaced
//! streamlines of arbitrary density": a first line is traced from the domain centre; then, line by
//! line in creation order, every sample point proposes two candidate seeds at distance `d_sep`
//! along the normal; a candidate at least `d_sep` from every existing point starts a new line,
//! which is traced both ways until it comes closer than `d_test = 0.5 d_sep` (by default) to
//! another line (or to a far part of itself, except next to its own seed so that closed orbits
//! close), or stops for the usual reasons. Points live in a
//! background grid of cell size `d_sep`, so each distance query looks at 3 × 3 cells. When the
//! queue runs dry, cell centres of a `d_sep` lattice are tried in order to reach regions the
//! first line's family never touched. Everything is sequential and deterministic.

use super::budget::StepBudget;
use super::field::VectorField;
use super::streamline::{Direction, Streamline, StreamlineOptions, dist, trace_with};

/// `n` seeds evenly spaced on the segment from `a` to `b`, both ends included (the midpoint for
/// `n = 1`, none for `n = 0`).
pub fn rake(a: [f64; 2], b: [f64; 2], n: usize) -> Vec<[f64; 2]> {
    if n == 1 {
        return vec![[0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]];
    }
    let last = n.saturating_sub(1).max(1) as f64;
    (0..n).map(|k| k as f64 / last).map(|f| [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]).collect()
}

/// Centres of the `nx × ny` equal cells of the rectangle `[x0, x1, y0, y1]`, row by row from `y0`.
pub fn grid_seeds(bounds: [f64; 4], nx: usize, ny: usize) -> Vec<[f64; 2]> {
    let [x0, x1, y0, y1] = bounds;
    let (dx, dy) = ((x1 - x0) / nx.max(1) as f64, (y1 - y0) / ny.max(1) as f64);
    (0..ny).flat_map(|j| (0..nx).map(move |i| [x0 + (i as f64 + 0.5) * dx, y0 + (j as f64 + 0.5) * dy])).collect()
}

/// `n` seeds evenly spaced on the circle of `radius` about `center`, counter-clockwise from angle 0.
pub fn circle(center: [f64; 2], radius: f64, n: usize) -> Vec<[f64; 2]> {
    let step = std::f64::consts::TAU / n.max(1) as f64;
    (0..n).map(|k| k as f64 * step).map(|a| [center[0] + radius * a.cos(), center[1] + radius * a.sin()]).collect()
}

/// Parameters of [`evenly_spaced`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EvenlySpacedOptions {
    /// Separating distance between lines (domain units).
    pub d_sep: f64,
    /// `d_test / d_sep`: lines stop when closer than `d_test` to another line (Jobard & Lefer: 0.5).
    pub d_test_ratio: f64,
    /// Tracing parameters (direction field, both directions).
    pub streamline: StreamlineOptions,
    /// Largest number of lines.
    pub max_lines: usize,
    /// Lines shorter than this are dropped.
    pub min_length: f64,
}

impl EvenlySpacedOptions {
    /// Jobard & Lefer's defaults for separation `d_sep`: `d_test = 0.5 d_sep`, step at most
    /// `d_sep / 10`, lines of length at least `d_test`, at most 100 000 lines.
    pub fn new(field: &VectorField, d_sep: f64) -> EvenlySpacedOptions {
        let mut streamline = StreamlineOptions::for_field(field);
        streamline.step = streamline.step.min(0.1 * d_sep);
        streamline.closure = 0.25 * streamline.step;
        streamline.direction = Direction::Both;
        EvenlySpacedOptions { d_sep, d_test_ratio: 0.5, streamline, max_lines: 100_000, min_length: 0.5 * d_sep }
    }
}

/// Largest number of background-grid cells; a smaller `d_sep` is raised to respect it.
const MAX_CELLS: usize = 1 << 22;

/// A stored sample point: its line, its parameter along the line, its position.
#[derive(Debug, Clone, Copy)]
struct Entry {
    line: u32,
    param: f64,
    point: [f64; 2],
}

/// Uniform background grid of square cells for near-constant-time distance queries.
struct Background {
    x0: f64,
    y0: f64,
    cell: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<Entry>>,
}

impl Background {
    fn new(bounds: [f64; 4], cell: f64) -> Background {
        let [x0, x1, y0, y1] = bounds;
        let nx = (((x1 - x0) / cell).ceil() as usize).max(1);
        let ny = (((y1 - y0) / cell).ceil() as usize).max(1);
        Background { x0, y0, cell, nx, ny, cells: vec![Vec::new(); nx * ny] }
    }

    fn cell_of(&self, p: [f64; 2]) -> (usize, usize) {
        let i = (((p[0] - self.x0) / self.cell).max(0.0) as usize).min(self.nx - 1);
        let j = (((p[1] - self.y0) / self.cell).max(0.0) as usize).min(self.ny - 1);
        (i, j)
    }

    fn insert(&mut self, e: Entry) {
        let (i, j) = self.cell_of(e.point);
        if let Some(c) = self.cells.get_mut(j * self.nx + i) {
            c.push(e);
        }
    }

    /// Whether any entry within `radius` (≤ cell size) of `p` satisfies `conflict`; the entries
    /// looked at are taken from `budget`, and a spent budget counts as a conflict (tracing stops).
    fn any_near(&self, p: [f64; 2], radius: f64, budget: &StepBudget, conflict: impl Fn(&Entry) -> bool) -> bool {
        let (i, j) = self.cell_of(p);
        let r2 = radius * radius;
        let near = |q: [f64; 2]| (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) < r2;
        for cj in j.saturating_sub(1)..=(j + 1).min(self.ny - 1) {
            for ci in i.saturating_sub(1)..=(i + 1).min(self.nx - 1) {
                let Some(cell) = self.cells.get(cj * self.nx + ci) else {
                    continue;
                };
                if !budget.examine(cell.len() as u64) {
                    return true;
                }
                if cell.iter().any(|e| near(e.point) && conflict(e)) {
                    return true;
                }
            }
        }
        false
    }

    /// Removes every entry of `line` stored near the given points.
    fn remove_line(&mut self, line: u32, points: &[[f64; 2]]) {
        for &p in points {
            let (i, j) = self.cell_of(p);
            if let Some(c) = self.cells.get_mut(j * self.nx + i) {
                c.retain(|e| e.line != line);
            }
        }
    }
}

/// Evenly spaced streamlines after Jobard & Lefer (1997); see the module docs. A non-positive or
/// NaN `d_sep` gives no lines; a `d_sep` so small that the background grid would exceed 2²²
/// cells is raised to fit. Every step and seeding attempt is taken from `budget`; once it is spent
/// the lines finished so far are returned (see [`StepBudget::exhausted`]). Lines are returned in
/// creation order.
pub fn evenly_spaced(field: &VectorField, options: &EvenlySpacedOptions, budget: &StepBudget) -> Vec<Streamline> {
    let bounds = field.bounds();
    let area = (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]);
    if !(options.d_sep.is_finite() && options.d_sep > 0.0) {
        return Vec::new();
    }
    let d_sep = options.d_sep.max((area / MAX_CELLS as f64).sqrt());
    let d_test = d_sep * options.d_test_ratio.clamp(0.0, 1.0);
    let self_gap = 4.0 * d_sep;
    let threshold = options.streamline.stagnation.max(0.0) * field.max_speed();
    let mut grid = Background::new(bounds, d_sep);
    let mut lines: Vec<Streamline> = Vec::new();
    let is_seed = |grid: &Background, p: [f64; 2]| {
        field.speed(p[0], p[1]).is_some_and(|s| s > threshold)
            && !grid.any_near(p, d_sep * (1.0 - 1e-3), budget, |_| true)
    };
    let mut fallback = grid_seeds(bounds, grid.nx, grid.ny).into_iter();
    let centre = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])];
    let mut pending = Some(centre);
    let mut next_line = 0usize; // the next line whose points propose candidates
    let mut attempts = 0usize;
    let max_attempts = options.max_lines.saturating_mul(64).max(1 << 16);
    while lines.len() < options.max_lines && attempts < max_attempts {
        let seed = match pending.take() {
            Some(s) => s,
            None => match next_candidate(&lines, &mut next_line, &grid, d_sep, &is_seed) {
                Some(s) => s,
                None => match fallback.by_ref().find(|&p| is_seed(&grid, p)) {
                    Some(s) => s,
                    None => break,
                },
            },
        };
        attempts += 1;
        if !budget.attempt() {
            break;
        }
        if !is_seed(&grid, seed) {
            continue;
        }
        let id = lines.len() as u32;
        grid.insert(Entry { line: id, param: 0.0, point: seed });
        let mut accept = |q: [f64; 2], param: f64| {
            if !budget.step() {
                return false;
            }
            // A far part of the line itself also counts, except its start seen from next to the
            // seed, so that closed orbits can close instead of stopping short.
            let near_seed = dist(q, seed) < d_test;
            let close = grid.any_near(q, d_test, budget, |e| {
                e.line != id || ((e.param - param).abs() > self_gap && !(near_seed && e.param.abs() < 2.0 * d_test))
            });
            if !close {
                grid.insert(Entry { line: id, param, point: q });
            }
            !close
        };
        let line = trace_with(field, seed, &options.streamline, &mut accept);
        if budget.exhausted() {
            // A line cut short by the budget is kept only if it is long enough, as any other.
            if line.points.len() >= 2 && line.length() >= options.min_length {
                lines.push(line);
            }
            break;
        }
        if line.points.len() < 2 || line.length() < options.min_length {
            grid.remove_line(id, &line.points);
            grid.remove_line(id, &[seed]);
            continue;
        }
        lines.push(line);
    }
    lines
}

/// The next valid candidate seed proposed by the lines from `next_line` on: for each sample
/// point, the points at `d_sep` on either side along the normal.
fn next_candidate(
    lines: &[Streamline],
    next_line: &mut usize,
    grid: &Background,
    d_sep: f64,
    is_seed: &impl Fn(&Background, [f64; 2]) -> bool,
) -> Option<[f64; 2]> {
    while let Some(line) = lines.get(*next_line) {
        let pts = &line.points;
        for k in 0..pts.len() {
            let (a, b) = (pts[k.saturating_sub(1)], pts[(k + 1).min(pts.len() - 1)]);
            let len = dist(a, b);
            if len <= 0.0 {
                continue;
            }
            let n = [-(b[1] - a[1]) / len, (b[0] - a[0]) / len];
            for side in [1.0, -1.0] {
                let c = [pts[k][0] + side * d_sep * n[0], pts[k][1] + side * d_sep * n[1]];
                if is_seed(grid, c) {
                    return Some(c);
                }
            }
        }
        *next_line += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(n: usize, a: f64, b: f64) -> Vec<f64> {
        (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect()
    }

    #[test]
    fn simple_seed_sets() {
        assert_eq!(rake([0.0, 0.0], [1.0, 2.0], 3), vec![[0.0, 0.0], [0.5, 1.0], [1.0, 2.0]]);
        assert_eq!(rake([0.0, 0.0], [1.0, 2.0], 1), vec![[0.5, 1.0]]);
        assert!(rake([0.0, 0.0], [1.0, 2.0], 0).is_empty());
        assert_eq!(grid_seeds([0.0, 2.0, 0.0, 1.0], 2, 1), vec![[0.5, 0.5], [1.5, 0.5]]);
        let c = circle([1.0, 1.0], 2.0, 4);
        assert!((c[1][0] - 1.0).abs() < 1e-12 && (c[1][1] - 3.0).abs() < 1e-12);
        assert!(c.iter().all(|p| ((p[0] - 1.0).hypot(p[1] - 1.0) - 2.0).abs() < 1e-12));
    }

    #[test]
    fn uniform_flow_gives_horizontal_lines_d_sep_apart() {
        let field = VectorField::from_fn(axis(21, 0.0, 1.0), axis(21, 0.0, 1.0), |_, _| [1.0, 0.0]).unwrap();
        let d_sep = 0.05;
        let options = EvenlySpacedOptions::new(&field, d_sep);
        let lines = evenly_spaced(&field, &options, &StepBudget::default());
        let mut heights = Vec::new();
        for line in &lines {
            let y = line.points[0][1];
            assert!(line.points.iter().all(|p| (p[1] - y).abs() < 1e-9), "line at y = {y} is not horizontal");
            assert!(line.length() > 0.99, "line at y = {y} does not cross the domain");
            heights.push(y);
        }
        heights.sort_by(f64::total_cmp);
        assert!(heights.len() >= 19, "{} lines", heights.len());
        for w in heights.windows(2) {
            let gap = w[1] - w[0];
            assert!((gap - d_sep).abs() <= 0.1 * d_sep, "gap {gap} between {} and {}", w[0], w[1]);
        }
    }

    #[test]
    fn lines_keep_d_test_apart_and_are_deterministic() {
        // A centre with a shear: curved lines that must stop near each other.
        let f = |x: f64, y: f64| [-(y - 0.5) + 0.3, x - 0.5];
        let field = VectorField::from_fn(axis(41, 0.0, 1.0), axis(41, 0.0, 1.0), f).unwrap();
        let options = EvenlySpacedOptions::new(&field, 0.06);
        let lines = evenly_spaced(&field, &options, &StepBudget::default());
        assert!(lines.len() > 5);
        // Orbits around the centre at (0.5, 0.8) that fit in the domain close on themselves.
        assert!(lines.iter().any(Streamline::is_closed));
        // No line winds on the spot: the point count stays near area / (d_sep × step).
        let points: usize = lines.iter().map(|l| l.points.len()).sum();
        assert!(points < 6000, "{points} points");
        let d_test = 0.5 * 0.06;
        for (a, la) in lines.iter().enumerate() {
            for lb in &lines[a + 1..] {
                for p in &la.points {
                    for q in &lb.points {
                        assert!(dist(*p, *q) >= d_test * (1.0 - 1e-6), "points {p:?} {q:?} too close");
                    }
                }
            }
        }
        assert_eq!(lines, evenly_spaced(&field, &options, &StepBudget::default()));
    }

    #[test]
    fn bad_separation_gives_nothing_and_caps_hold() {
        let field = VectorField::from_fn(axis(5, 0.0, 1.0), axis(5, 0.0, 1.0), |_, _| [1.0, 0.0]).unwrap();
        for d in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(evenly_spaced(&field, &EvenlySpacedOptions::new(&field, d), &StepBudget::default()).is_empty());
        }
        let mut options = EvenlySpacedOptions::new(&field, 0.01);
        options.max_lines = 7;
        assert_eq!(evenly_spaced(&field, &options, &StepBudget::default()).len(), 7);
    }

    #[test]
    fn budget_stops_seeding_cleanly() {
        let field = VectorField::from_fn(axis(21, 0.0, 1.0), axis(21, 0.0, 1.0), |_, _| [1.0, 0.0]).unwrap();
        let options = EvenlySpacedOptions::new(&field, 0.05);
        let full = evenly_spaced(&field, &options, &StepBudget::default());
        let budget = StepBudget::new(300, 1_000);
        let cut = evenly_spaced(&field, &options, &budget);
        assert!(budget.exhausted());
        assert!(!cut.is_empty() && cut.len() < full.len(), "{} of {} lines", cut.len(), full.len());
        // Every line before the one the budget cut short is as in a full run.
        assert_eq!(cut[..cut.len() - 1], full[..cut.len() - 1]);
    }
}
