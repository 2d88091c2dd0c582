//! Tests for contour lines and bands: known answers on analytic fields, the saddle example,
//! invariants on random fields with holes, and bad input.

use super::*;
use crate::enrich::grid::Grid;

type Pt = (f64, f64);

/// `n` coordinates from `a` to `b`, evenly spaced.
fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect()
}

/// `n` strictly increasing, unevenly spaced coordinates starting at `a`.
fn uneven(a: f64, n: usize, seed: u64) -> Vec<f64> {
    let mut rng = Rng(seed);
    let mut x = a;
    (0..n)
        .map(|_| {
            let v = x;
            x += 0.05 + 0.1 * rng.next();
            v
        })
        .collect()
}

/// xorshift64*: deterministic noise for tests.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn lines(grid: &Grid, levels: &[f64], saddle: Saddle) -> Vec<ContourLine> {
    contour_lines(grid, levels, saddle).unwrap()
}

fn bands(grid: &Grid, levels: &[f64], saddle: Saddle) -> Vec<Band> {
    contour_bands(grid, levels, saddle).unwrap()
}

fn signed_area(ring: &[Pt]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|k| {
            let (a, b) = (ring[k], ring[(k + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        / 2.0
}

/// Area of a band: outer rings minus holes.
fn band_area(band: &Band) -> f64 {
    band.polygons.iter().flat_map(|p| p.iter()).map(|r| signed_area(r)).sum()
}

fn ring_contains(ring: &[Pt], (px, py): Pt) -> bool {
    let n = ring.len();
    let mut inside = false;
    for k in 0..n {
        let ((ax, ay), (bx, by)) = (ring[k], ring[(k + 1) % n]);
        if (ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay) {
            inside = !inside;
        }
    }
    inside
}

/// Inside the outer ring and outside every hole.
fn polygon_contains(poly: &[Vec<Pt>], p: Pt) -> bool {
    match poly.split_first() {
        Some((outer, holes)) => ring_contains(outer, p) && !holes.iter().any(|h| ring_contains(h, p)),
        None => false,
    }
}

/// Whether cell `(i, j)` exists and has no missing corner.
fn cell_ok(g: &Grid, i: isize, j: isize) -> bool {
    if i < 0 || j < 0 || i as usize + 1 >= g.nx() || j as usize + 1 >= g.ny() {
        return false;
    }
    let (i, j) = (i as usize, j as usize);
    [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)].iter().all(|&(a, b)| !g.value(a, b).is_nan())
}

/// The two cells beside the grid edge holding `p` (a point strictly inside an edge).
fn cells_beside(g: &Grid, (x, y): Pt) -> [(isize, isize); 2] {
    let (xs, ys) = (g.xs(), g.ys());
    if let Some(j) = ys.iter().position(|&v| v == y) {
        let i = xs.partition_point(|&v| v < x) - 1;
        assert!(xs[i] < x && x < xs[i + 1], "point {x},{y} is not inside a horizontal edge");
        [(i as isize, j as isize - 1), (i as isize, j as isize)]
    } else {
        let i = xs.iter().position(|&v| v == x).expect("point on a grid edge");
        let j = ys.partition_point(|&v| v < y) - 1;
        assert!(ys[j] < y && y < ys[j + 1]);
        [(i as isize - 1, j as isize), (i as isize, j as isize)]
    }
}

/// A cell holding both points, each on one of its edges.
fn share_a_cell(g: &Grid, p: Pt, q: Pt) -> bool {
    let a = cells_beside(g, p);
    let b = cells_beside(g, q);
    a.iter().any(|c| b.contains(c) && cell_ok(g, c.0, c.1))
}

// ---------------------------------------------------------------- the saddle example

/// Corner values of the example: f00 = −3, f10 = 1, f01 = 10, f11 = −5.
const EX: (f64, f64, f64, f64) = (-3.0, 1.0, 10.0, -5.0);

fn example_cell() -> Grid {
    let (f00, f10, f01, f11) = EX;
    Grid::new(vec![0.0, 1.0], vec![0.0, 1.0], vec![f00, f10, f01, f11]).unwrap()
}

#[test]
fn saddle_example_value_and_point() {
    let (f00, f10, f01, f11) = EX;
    // D = f00 + f11 − f01 − f10 = −3 − 5 − 10 − 1 = −19; value = (15 − 10) / −19.
    let v = asymptotic_saddle_value(f00, f10, f01, f11).unwrap();
    assert!((v - (-5.0 / 19.0)).abs() < 1e-15, "{v}");
    // s* = (f00 − f01) / D = −13 / −19, t* = (f00 − f10) / D = −4 / −19.
    let (s, t) = saddle_point(f00, f10, f01, f11).unwrap();
    assert!((s - 13.0 / 19.0).abs() < 1e-15 && (t - 4.0 / 19.0).abs() < 1e-15);
    // The gradient of the patch vanishes there and the patch takes the saddle value.
    let ds = (f10 - f00) * (1.0 - t) + (f11 - f01) * t;
    let dt = (f01 - f00) * (1.0 - s) + (f11 - f10) * s;
    assert!(ds.abs() < 1e-14 && dt.abs() < 1e-14, "{ds} {dt}");
    let at = example_cell().bilinear(s, t);
    assert!((at - v).abs() < 1e-14, "{at}");
    // The centre average is 0.75, well above the saddle value.
    assert_eq!(0.25 * (f00 + f10 + f01 + f11), 0.75);
    // A bilinear patch without a saddle (D = 0).
    assert_eq!(asymptotic_saddle_value(1.0, 2.0, 3.0, 4.0), None);
    assert_eq!(saddle_point(1.0, 2.0, 3.0, 4.0), None);
}

/// Whether `{f >= level}` joins corner (1, 0) to corner (0, 1) inside the example cell, by a
/// flood fill over a fine sampling of the true bilinear patch.
fn above_corners_joined(level: f64) -> bool {
    let g = example_cell();
    let n = 601;
    let at = |a: usize, b: usize| g.bilinear(a as f64 / (n - 1) as f64, b as f64 / (n - 1) as f64);
    let mut seen = vec![false; n * n];
    let mut stack = vec![(n - 1, 0)];
    seen[n - 1] = true;
    while let Some((a, b)) = stack.pop() {
        if (a, b) == (0, n - 1) {
            return true;
        }
        let nbrs = [(a.wrapping_sub(1), b), (a + 1, b), (a, b.wrapping_sub(1)), (a, b + 1)];
        for (p, q) in nbrs {
            if p < n && q < n && !seen[q * n + p] && at(p, q) >= level {
                seen[q * n + p] = true;
                stack.push((p, q));
            }
        }
    }
    false
}

#[test]
fn saddle_deciders_connect_the_example_differently() {
    let g = example_cell();
    // 0.25 lies between the saddle value (−0.263) and the centre average (0.75).
    let level = 0.25;
    // Crossings: bottom (0.8125, 0), right (1, 0.125), top (0.65, 1), left (0, 0.25).
    let (bottom, right, top, left) = ((0.8125, 0.0), (1.0, 0.125), (0.65, 1.0), (0.0, 0.25));
    let segs = |s: Saddle| {
        let mut v: Vec<Vec<Pt>> = lines(&g, &[level], s).into_iter().map(|l| l.points).collect();
        v.sort_by(|a, b| a[0].partial_cmp(&b[0]).unwrap());
        v
    };
    // Asymptotic: saddle value < level, so the centre is below and each above corner ((1, 0)
    // with value 1 and (0, 1) with value 10) is cut off on its own.
    assert_eq!(segs(Saddle::Asymptotic), vec![vec![left, top], vec![right, bottom]]);
    // Centre average: 0.75 >= level, so the centre is above and the below corners are cut off.
    assert_eq!(segs(Saddle::Center), vec![vec![left, bottom], vec![right, top]]);
    // The true bilinear patch agrees with the asymptotic decider.
    assert!(!above_corners_joined(level));
    // Below the saddle value or above the centre average the deciders agree, and so does the
    // patch.
    for (level, joined) in [(-1.0, true), (0.9, false)] {
        let a = lines(&g, &[level], Saddle::Asymptotic);
        let c = lines(&g, &[level], Saddle::Center);
        assert_eq!(a, c, "level {level}");
        assert_eq!(above_corners_joined(level), joined, "level {level}");
    }
}

#[test]
fn saddle_deciders_split_bands_differently() {
    let g = example_cell();
    for (saddle, lower_parts, upper_parts) in [(Saddle::Asymptotic, 1, 2), (Saddle::Center, 2, 1)] {
        let b = bands(&g, &[-5.0, 0.25, 10.0], saddle);
        assert_eq!(b.len(), 2);
        assert_eq!(b[0].polygons.len(), lower_parts, "{saddle:?}");
        assert_eq!(b[1].polygons.len(), upper_parts, "{saddle:?}");
        let total = band_area(&b[0]) + band_area(&b[1]);
        assert!((total - 1.0).abs() < 1e-12, "{total}");
    }
}

// ---------------------------------------------------------------- analytic fields

#[test]
fn plane_contours_are_vertical_lines_at_the_level() {
    let xs = uneven(0.0, 30, 7);
    let ys = uneven(-1.0, 20, 8);
    let g = Grid::from_fn(xs.clone(), ys.clone(), |x, _| x).unwrap();
    let levels = [0.35, 0.7, 1.234];
    let out = lines(&g, &levels, Saddle::Asymptotic);
    assert_eq!(out.len(), 3);
    for (line, &level) in out.iter().zip(&levels) {
        assert_eq!(line.level, level);
        assert!(!line.closed);
        assert_eq!(line.points.len(), ys.len());
        for (k, &(x, y)) in line.points.iter().enumerate() {
            assert!((x - level).abs() < 1e-12, "{x} vs {level}");
            // Larger x on the left means walking down.
            assert_eq!(y, ys[ys.len() - 1 - k]);
        }
    }
    // A level exactly on a grid column: nodes there are above, so the line runs through them.
    let on = lines(&g, &[xs[5]], Saddle::Asymptotic);
    assert_eq!(on.len(), 1);
    assert!(on[0].points.iter().all(|p| p.0 == xs[5]));
}

#[test]
fn paraboloid_level_is_one_ring_inside_the_circle() {
    let n = 201;
    let h = 4.0 / (n - 1) as f64;
    let g = Grid::from_fn(linspace(-2.0, 2.0, n), linspace(-2.0, 2.0, n), |x, y| x * x + y * y).unwrap();
    for r in [1.0, 1.3, 0.55] {
        let out = lines(&g, &[r * r], Saddle::Asymptotic);
        assert_eq!(out.len(), 1, "r = {r}");
        let ring = &out[0];
        assert!(ring.closed);
        // Along an edge the linear interpolant of x² + y² overshoots by at most h²/4, so at a
        // crossing r² − h²/4 <= ‖p‖² <= r².
        for &(x, y) in &ring.points {
            let d2 = x * x + y * y;
            assert!(d2 <= r * r + 1e-12 && d2 >= r * r - h * h / 4.0 - 1e-12, "{d2} r={r}");
        }
        // The region {f >= r²} (outside) is on the left: the ring runs clockwise.
        let area = signed_area(&ring.points);
        let circle = std::f64::consts::PI * r * r;
        assert!(area < 0.0);
        assert!(-area < circle && -area > circle * (1.0 - 1e-3), "{area} vs {circle}");
    }
    // A peak instead of a pit: the ring runs counter-clockwise.
    let peak = Grid::from_fn(linspace(-2.0, 2.0, 41), linspace(-2.0, 2.0, 41), |x, y| -(x * x + y * y)).unwrap();
    let out = lines(&peak, &[-1.0], Saddle::Asymptotic);
    assert_eq!(out.len(), 1);
    assert!(signed_area(&out[0].points) > 3.0);
}

#[test]
fn xy_saddle_zero_level_gives_the_axes() {
    // Nodes at ±0.05, ±0.15, …, ±0.95: the origin is the centre of a saddle cell.
    let c: Vec<f64> = (-10..10).map(|i| (i as f64 + 0.5) * 0.1).collect();
    let g = Grid::from_fn(c.clone(), c.clone(), |x, y| x * y).unwrap();
    for saddle in [Saddle::Asymptotic, Saddle::Center] {
        let out = lines(&g, &[0.0], saddle);
        assert_eq!(out.len(), 2, "{saddle:?}");
        for line in &out {
            assert!(!line.closed);
            for &(x, y) in &line.points {
                assert!(x.abs() < 1e-15 || y.abs() < 1e-15, "({x}, {y}) off the axes");
            }
            assert_eq!(line.points.len(), 20);
        }
        // The saddle value is exactly 0, so the centre counts as above: quadrants I and III
        // (f > 0) join and the lines cut off quadrants II and IV.
        let mut ends: Vec<(Pt, Pt)> = out.iter().map(|l| (l.points[0], *l.points.last().unwrap())).collect();
        ends.sort_by(|a, b| a.partial_cmp(b).unwrap());
        // With f >= 0 on the left, one line runs up the y axis from the bottom and turns right
        // along the x axis; the other runs down from the top and turns left.
        let e = 0.95;
        let close = |p: Pt, q: Pt| (p.0 - q.0).abs() < 1e-12 && (p.1 - q.1).abs() < 1e-12;
        assert!(close(ends[0].0, (0.0, -e)) && close(ends[0].1, (e, 0.0)), "{ends:?}");
        assert!(close(ends[1].0, (0.0, e)) && close(ends[1].1, (-e, 0.0)), "{ends:?}");
    }
}

#[test]
fn paraboloid_band_is_an_annulus() {
    let n = 201;
    let g = Grid::from_fn(linspace(-2.0, 2.0, n), linspace(-2.0, 2.0, n), |x, y| x * x + y * y).unwrap();
    let out = bands(&g, &[0.25, 1.0], Saddle::Asymptotic);
    assert_eq!(out.len(), 1);
    let polys = &out[0].polygons;
    assert_eq!(polys.len(), 1);
    assert_eq!(polys[0].len(), 2, "outer ring and one hole");
    assert!(signed_area(&polys[0][0]) > 0.0 && signed_area(&polys[0][1]) < 0.0);
    let expected = std::f64::consts::PI * (1.0 - 0.25);
    let area = band_area(&out[0]);
    assert!((area - expected).abs() < 2e-3 * expected, "{area} vs {expected}");
    // Outer ring on the unit circle, hole on the circle of radius 0.5 (within h²/4 in f).
    let h = 0.02;
    for (ring, r2) in [(&polys[0][0], 1.0), (&polys[0][1], 0.25)] {
        for &(x, y) in ring.iter() {
            let d2 = x * x + y * y;
            assert!(d2 <= r2 + 1e-12 && d2 >= r2 - h * h / 4.0 - 1e-12);
        }
    }
}

#[test]
fn plane_bands_have_exact_areas() {
    let xs = uneven(0.0, 30, 3);
    let ys = uneven(2.0, 25, 4);
    let height = ys[ys.len() - 1] - ys[0];
    let g = Grid::from_fn(xs.clone(), ys, |x, _| x).unwrap();
    let levels = [0.3, 0.7, 1.5, xs[20]];
    let out = bands(&g, &levels, Saddle::Asymptotic);
    assert_eq!(out.len(), 3);
    for (band, w) in out.iter().zip(levels.windows(2)) {
        assert_eq!(band.polygons.len(), 1);
        assert_eq!(band.polygons[0].len(), 1);
        let expected = (w[1] - w[0]) * height;
        assert!((band_area(band) - expected).abs() < 1e-12, "{w:?}");
    }
}

// ---------------------------------------------------------------- random fields with holes

/// A random field on an uneven grid with about `hole_share` of its nodes missing (NaN, +inf or
/// −inf).
fn random_grid(nx: usize, ny: usize, seed: u64, hole_share: f64) -> Grid {
    let mut rng = Rng(seed);
    let values = (0..nx * ny)
        .map(|k| {
            let v = rng.next();
            if rng.next() < hole_share { [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][k % 3] } else { v }
        })
        .collect();
    Grid::new(uneven(0.0, nx, seed + 1), uneven(0.0, ny, seed + 2), values).unwrap()
}

/// Number of edges next to at least one valid cell whose ends lie on different sides of `level`.
fn crossing_edges(g: &Grid, level: f64) -> (usize, usize) {
    let (nx, ny) = (g.nx() as isize, g.ny() as isize);
    let (mut all, mut boundary) = (0, 0);
    let mut count = |a: f64, b: f64, c1: (isize, isize), c2: (isize, isize)| {
        let (v1, v2) = (cell_ok(g, c1.0, c1.1), cell_ok(g, c2.0, c2.1));
        if (v1 || v2) && (a >= level) != (b >= level) {
            all += 1;
            if v1 != v2 {
                boundary += 1;
            }
        }
    };
    for j in 0..ny {
        for i in 0..nx - 1 {
            let (a, b) = (g.value(i as usize, j as usize), g.value(i as usize + 1, j as usize));
            count(a, b, (i, j - 1), (i, j));
        }
    }
    for j in 0..ny - 1 {
        for i in 0..nx {
            let (a, b) = (g.value(i as usize, j as usize), g.value(i as usize, j as usize + 1));
            count(a, b, (i - 1, j), (i, j));
        }
    }
    (all, boundary)
}

#[test]
fn random_lines_are_closed_or_end_on_a_boundary() {
    for seed in 1..=12u64 {
        let g = random_grid(37, 29, seed, 0.08);
        let levels = [0.2, 0.5, 0.8];
        for saddle in [Saddle::Asymptotic, Saddle::Center] {
            let out = lines(&g, &levels, saddle);
            for &level in &levels {
                let mut points = 0;
                let mut open_ends = 0;
                for line in out.iter().filter(|l| l.level == level) {
                    points += line.points.len();
                    let n = line.points.len();
                    let pairs = if line.closed { n } else { n - 1 };
                    for k in 0..pairs {
                        let (p, q) = (line.points[k], line.points[(k + 1) % n]);
                        assert!(share_a_cell(&g, p, q), "seed {seed}: {p:?} {q:?}");
                    }
                    // Points on a boundary edge are exactly the open lines' two ends.
                    for (k, &p) in line.points.iter().enumerate() {
                        let [c1, c2] = cells_beside(&g, p);
                        let on_boundary = cell_ok(&g, c1.0, c1.1) != cell_ok(&g, c2.0, c2.1);
                        let is_end = !line.closed && (k == 0 || k == n - 1);
                        assert_eq!(on_boundary, is_end, "seed {seed} level {level} point {k}");
                    }
                    if !line.closed {
                        open_ends += 2;
                    }
                }
                // Every crossing is used exactly once: nothing lost, nothing traced twice.
                let (all, boundary) = crossing_edges(&g, level);
                assert_eq!(points, all, "seed {seed} level {level}");
                assert_eq!(open_ends, boundary, "seed {seed} level {level}");
            }
        }
    }
}

/// Checks that `bands` tile the valid cells, rings are oriented, and every interior node lies
/// in exactly the band holding its value.
fn check_bands(g: &Grid, levels: &[f64], out: &[Band], what: &str) {
    let (xs, ys) = (g.xs(), g.ys());
    let mut valid_area = 0.0;
    for j in 0..g.ny() - 1 {
        for i in 0..g.nx() - 1 {
            if cell_ok(g, i as isize, j as isize) {
                valid_area += (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
            }
        }
    }
    let total: f64 = out.iter().map(band_area).sum();
    assert!((total - valid_area).abs() <= 1e-9 * valid_area, "{what}: bands cover {total}, valid cells {valid_area}");
    for band in out {
        for poly in &band.polygons {
            assert!(signed_area(&poly[0]) > 0.0, "{what}: outer ring not counter-clockwise");
            for hole in &poly[1..] {
                assert!(signed_area(hole) < 0.0, "{what}: hole not clockwise");
                assert!(ring_contains(&poly[0], hole[0]), "{what}: hole outside its polygon");
            }
        }
    }
    for (j, &y) in ys.iter().enumerate().take(g.ny() - 1).skip(1) {
        for (i, &x) in xs.iter().enumerate().take(g.nx() - 1).skip(1) {
            let (ii, jj) = (i as isize, j as isize);
            let around = [(ii - 1, jj - 1), (ii, jj - 1), (ii - 1, jj), (ii, jj)];
            if !around.iter().all(|&(a, b)| cell_ok(g, a, b)) {
                continue;
            }
            let v = g.value(i, j);
            if levels.contains(&v) {
                continue;
            }
            let p = (x, y);
            let holders: Vec<usize> = out
                .iter()
                .enumerate()
                .filter(|(_, b)| b.polygons.iter().any(|poly| polygon_contains(poly, p)))
                .map(|(k, _)| k)
                .collect();
            let want: Vec<usize> =
                out.iter().enumerate().filter(|(_, b)| b.lower <= v && v < b.upper).map(|(k, _)| k).collect();
            assert_eq!(holders, want, "{what}: node ({i}, {j}) with value {v}");
        }
    }
}

#[test]
fn random_bands_tile_the_valid_cells() {
    for seed in 1..=10u64 {
        let g = random_grid(33, 27, seed, 0.06);
        let (lo, hi) = g.range().unwrap();
        let levels = [lo, 0.2, 0.45, 0.5, 0.8, hi];
        for saddle in [Saddle::Asymptotic, Saddle::Center] {
            let out = bands(&g, &levels, saddle);
            assert_eq!(out.len(), 5);
            check_bands(&g, &levels, &out, &format!("seed {seed} {saddle:?}"));
        }
    }
}

#[test]
fn smooth_bands_with_nested_holes_tile_the_domain() {
    // Many peaks and pits (bands with holes, islands inside holes), plus a block of NaN.
    let xs = linspace(-3.0, 3.0, 121);
    let ys = linspace(-2.0, 2.5, 97);
    let g = Grid::from_fn(xs, ys, |x, y| {
        if (0.4..0.9).contains(&x) && (-0.3..0.2).contains(&y) {
            f64::NAN
        } else {
            (2.0 * x).sin() * (3.0 * y).cos() + 0.3 * x
        }
    })
    .unwrap();
    let (lo, hi) = g.range().unwrap();
    let mut levels = vec![lo];
    levels.extend(nice_levels(lo, hi, 10));
    levels.push(hi);
    for saddle in [Saddle::Asymptotic, Saddle::Center] {
        let out = bands(&g, &levels, saddle);
        let holes: usize = out.iter().flat_map(|b| &b.polygons).map(|p| p.len() - 1).sum();
        assert!(holes > 5, "the field should give holes, got {holes}");
        check_bands(&g, &levels, &out, &format!("{saddle:?}"));
    }
}

#[test]
fn nan_hole_inside_a_band_is_a_hole_of_its_polygon() {
    let mut values = Vec::new();
    for _j in 0..7 {
        for i in 0..9 {
            values.push(i as f64);
        }
    }
    values[3 * 9 + 4] = f64::NAN; // node (4, 3): the four cells around it are holes
    let g = Grid::new(linspace(0.0, 8.0, 9), linspace(0.0, 6.0, 7), values).unwrap();
    let out = bands(&g, &[1.5, 6.5], Saddle::Asymptotic);
    let polys = &out[0].polygons;
    assert_eq!(polys.len(), 1);
    assert_eq!(polys[0].len(), 2);
    assert_eq!(signed_area(&polys[0][1]), -4.0);
    assert!((band_area(&out[0]) - (5.0 * 6.0 - 4.0)).abs() < 1e-12);
    // Lines stop at the hole: the level-4 line (through node column 4) is cut in two.
    let l = lines(&g, &[4.5], Saddle::Asymptotic);
    assert_eq!(l.len(), 2);
    assert!(l.iter().all(|l| !l.closed));
}

// ---------------------------------------------------------------- levels at the extremes

#[test]
fn level_equal_to_min_gives_nothing_and_to_max_rings_the_plateau() {
    // 6 × 6 nodes of 0 with a 2 × 2 plateau of 1 at nodes (2..=3, 2..=3), and a lone 1 at (0, 5).
    let mut values = vec![0.0; 36];
    for (i, j) in [(2, 2), (3, 2), (2, 3), (3, 3)] {
        values[j * 6 + i] = 1.0;
    }
    let g = Grid::new(linspace(0.0, 5.0, 6), linspace(0.0, 5.0, 6), values.clone()).unwrap();
    assert!(lines(&g, &[0.0], Saddle::Asymptotic).is_empty(), "level == min");
    let at_max = lines(&g, &[1.0], Saddle::Asymptotic);
    assert_eq!(at_max.len(), 1);
    assert!(at_max[0].closed);
    let mut pts = at_max[0].points.clone();
    assert_eq!(signed_area(&pts), 1.0, "counter-clockwise round the plateau");
    pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(pts, vec![(2.0, 2.0), (2.0, 3.0), (3.0, 2.0), (3.0, 3.0)]);
    // A lone maximal node gives a zero-length ring, which is dropped.
    let mut lone = vec![0.0; 36];
    lone[14] = 1.0;
    let g2 = Grid::new(linspace(0.0, 5.0, 6), linspace(0.0, 5.0, 6), lone).unwrap();
    assert!(lines(&g2, &[1.0], Saddle::Asymptotic).is_empty());
    // Bands from min to max: the top band includes the maximum, so everything is filled.
    for g in [&g, &g2] {
        let out = bands(g, &[0.0, 1.0], Saddle::Asymptotic);
        assert_eq!(band_area(&out[0]), 25.0);
        let out = bands(g, &[0.0, 0.5, 1.0], Saddle::Asymptotic);
        assert!((band_area(&out[0]) + band_area(&out[1]) - 25.0).abs() < 1e-12);
    }
}

// ---------------------------------------------------------------- bad input

#[test]
fn grids_without_cells_give_nothing() {
    for (nx, ny) in [(1, 1), (1, 7), (7, 1)] {
        let g = Grid::new(
            linspace(0.0, 1.0, nx.max(2))[..nx].to_vec(),
            linspace(0.0, 1.0, ny.max(2))[..ny].to_vec(),
            (0..nx * ny).map(|k| k as f64).collect(),
        )
        .unwrap();
        assert!(lines(&g, &[0.5, 2.5], Saddle::Asymptotic).is_empty());
        let b = bands(&g, &[0.0, 0.5, 2.5, 10.0], Saddle::Asymptotic);
        assert_eq!(b.len(), 3);
        assert!(b.iter().all(|b| b.polygons.is_empty()));
    }
}

#[test]
fn constant_grid_has_no_lines_and_lies_in_one_band() {
    let g = Grid::from_fn(linspace(0.0, 4.0, 5), linspace(0.0, 2.0, 3), |_, _| 3.0).unwrap();
    assert!(lines(&g, &[2.0, 3.0, 4.0], Saddle::Asymptotic).is_empty());
    // 3 is in [3, 4): the second band holds the whole domain as one rectangle.
    let out = bands(&g, &[2.0, 3.0, 4.0], Saddle::Asymptotic);
    assert!(out[0].polygons.is_empty());
    assert_eq!(out[1].polygons.len(), 1);
    let mut ring = out[1].polygons[0][0].clone();
    assert_eq!(signed_area(&ring), 8.0);
    ring.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(ring, vec![(0.0, 0.0), (0.0, 2.0), (4.0, 0.0), (4.0, 2.0)]);
    // The topmost band includes its upper level.
    let out = bands(&g, &[2.0, 3.0], Saddle::Asymptotic);
    assert_eq!(band_area(&out[0]), 8.0);
    // A single level (for example min == max) makes no band.
    assert!(bands(&g, &[3.0], Saddle::Asymptotic).is_empty());
}

#[test]
fn all_missing_grid_gives_nothing() {
    let g = Grid::new(linspace(0.0, 1.0, 4), linspace(0.0, 1.0, 3), vec![f64::NAN; 12]).unwrap();
    assert_eq!(g.range(), None);
    assert!(lines(&g, &[0.0, 1.0], Saddle::Asymptotic).is_empty());
    let b = bands(&g, &[0.0, 1.0], Saddle::Asymptotic);
    assert!(b[0].polygons.is_empty());
}

#[test]
fn infinite_values_are_holes_like_nan() {
    let nan = random_grid(20, 15, 99, 0.0);
    let mut with_inf = nan.values().to_vec();
    let mut with_nan = with_inf.clone();
    for k in [3usize, 50, 51, 120, 200, 201, 221] {
        with_inf[k] = if k % 2 == 0 { f64::INFINITY } else { f64::NEG_INFINITY };
        with_nan[k] = f64::NAN;
    }
    let a = Grid::new(nan.xs().to_vec(), nan.ys().to_vec(), with_inf).unwrap();
    let b = Grid::new(nan.xs().to_vec(), nan.ys().to_vec(), with_nan).unwrap();
    let levels = [0.0, 0.3, 0.6, 1.0];
    assert_eq!(lines(&a, &levels, Saddle::Asymptotic), lines(&b, &levels, Saddle::Asymptotic));
    assert_eq!(bands(&a, &levels, Saddle::Asymptotic), bands(&b, &levels, Saddle::Asymptotic));
    check_bands(&a, &levels, &bands(&a, &levels, Saddle::Asymptotic), "inf holes");
    // The holes changed the answer: lines end on them.
    assert_ne!(lines(&a, &levels, Saddle::Asymptotic), lines(&nan, &levels, Saddle::Asymptotic));
}

#[test]
fn levels_are_sorted_deduplicated_and_cleaned() {
    let g = random_grid(15, 12, 5, 0.0);
    let clean = [0.2, 0.5, 0.8];
    let messy = [0.8, f64::NAN, 0.2, 0.5, 0.2, f64::INFINITY, 0.8, f64::NEG_INFINITY];
    assert_eq!(clean_levels(&messy).unwrap(), clean.to_vec());
    assert_eq!(lines(&g, &messy, Saddle::Asymptotic), lines(&g, &clean, Saddle::Asymptotic));
    assert_eq!(bands(&g, &messy, Saddle::Center), bands(&g, &clean, Saddle::Center));
    assert!(!lines(&g, &clean, Saddle::Asymptotic).is_empty());
    assert!(lines(&g, &[f64::NAN], Saddle::Asymptotic).is_empty());
}

#[test]
fn too_many_levels_is_an_error_with_the_count() {
    let g = random_grid(10, 10, 3, 0.0);
    let many: Vec<f64> = (0..1001).map(|k| k as f64 / 1000.0).collect();
    let err = contour_lines(&g, &many, Saddle::Asymptotic).unwrap_err();
    assert_eq!(err, ContourError::TooManyLevels { count: 1001, max: 1000 });
    let msg = err.to_string();
    assert!(msg.contains("1001") && msg.contains("at most 1000"), "{msg}");
    assert!(contour_bands(&g, &many, Saddle::Asymptotic).is_err());
    // Exactly the cap is fine, and repeated values count once.
    let out = contour_lines(&g, &many[..1000], Saddle::Asymptotic).unwrap();
    assert!(out.len() > 100);
    let repeated = vec![0.5; 5000];
    assert_eq!(contour_lines(&g, &repeated, Saddle::Asymptotic).unwrap().len(), {
        lines(&g, &[0.5], Saddle::Asymptotic).len()
    });
    // 1000 levels spanning [0, 1] (the field's values lie in [0, 1)) still tile the grid.
    let spanning: Vec<f64> = (0..1000).map(|k| k as f64 / 999.0).collect();
    let b = contour_bands(&g, &spanning, Saddle::Asymptotic).unwrap();
    assert_eq!(b.len(), 999);
    check_bands(&g, &spanning, &b, "1000 levels");
}

#[test]
fn too_many_crossings_is_an_error_before_tracing() {
    // Noise on 400 × 400 nodes crosses about 160 000 cells × 600 levels ≈ 10⁸ times.
    let g = random_grid(400, 400, 11, 0.0);
    let many: Vec<f64> = (0..1000).map(|k| k as f64 / 999.0).collect();
    let err = contour_lines(&g, &many, Saddle::Asymptotic).unwrap_err();
    let ContourError::TooManyCrossings { count, max } = err else { panic!("{err:?}") };
    assert_eq!(max, MAX_CROSSED_CELLS);
    assert!(count > max && count < 160_000 * 1000, "{count}");
    assert!(err.to_string().contains(&count.to_string()) && err.to_string().contains("fewer levels"));
    assert!(matches!(contour_bands(&g, &many, Saddle::Asymptotic), Err(ContourError::TooManyCrossings { .. })));
    // The same grid with ten levels is fine.
    assert!(!lines(&g, &many[..10], Saddle::Asymptotic).is_empty());
}

#[test]
fn extreme_magnitudes_stay_finite() {
    let xs = vec![-1e308, 0.0, 1e308];
    let ys = vec![-1e300, 1e300];
    let g = Grid::new(xs, ys, vec![-1e308, 1e308, -1e308, 1e308, -1e308, 1e308]).unwrap();
    for saddle in [Saddle::Asymptotic, Saddle::Center] {
        let out = lines(&g, &[0.0, 1e307, -f64::MAX], saddle);
        assert!(!out.is_empty());
        for l in &out {
            assert!(l.points.iter().all(|p| p.0.is_finite() && p.1.is_finite()), "{l:?}");
        }
        let b = bands(&g, &[-1e308, 0.0, 1e308], saddle);
        for band in &b {
            for ring in band.polygons.iter().flatten() {
                assert!(ring.iter().all(|p| p.0.is_finite() && p.1.is_finite()));
            }
        }
    }
}

// ---------------------------------------------------------------- nice levels

#[test]
fn nice_levels_known_answers() {
    assert_eq!(nice_levels(0.0, 1.0, 10), vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9]);
    assert_eq!(nice_levels(0.0, 100.0, 4), vec![20.0, 40.0, 60.0, 80.0]);
    assert_eq!(nice_levels(-1.0, 1.0, 5), vec![-0.5, 0.0, 0.5]);
    assert_eq!(nice_levels(0.13, 0.87, 3), vec![0.25, 0.5, 0.75]);
    assert_eq!(nice_levels(3.0, 7.0, 1), vec![5.0]);
    assert_eq!(nice_levels(0.0, 1.0, 1), vec![0.5]);
    assert_eq!(nice_levels(-37.0, 1234.0, 5), vec![0.0, 250.0, 500.0, 750.0, 1000.0]);
    assert_eq!(nice_levels(0.0, 10.0, 4), vec![2.0, 4.0, 6.0, 8.0]);
    assert_eq!(nice_levels(0.0, 10.0, 3), vec![2.5, 5.0, 7.5]);
    // Strictly inside: the ends are never levels.
    assert_eq!(nice_levels(0.0, 1.0, 2), vec![0.5]);
}

#[test]
fn nice_levels_survive_bad_input() {
    assert!(nice_levels(f64::NAN, 1.0, 5).is_empty());
    assert!(nice_levels(0.0, f64::INFINITY, 5).is_empty());
    assert!(nice_levels(1.0, 0.0, 5).is_empty());
    assert!(nice_levels(1.0, 1.0, 5).is_empty());
    assert!(nice_levels(0.0, 1.0, 0).is_empty());
    let wide = nice_levels(-f64::MAX, f64::MAX, 10);
    assert!(!wide.is_empty() && wide.len() <= 10);
    assert!(wide.iter().all(|l| l.is_finite()));
    let capped = nice_levels(0.0, 1.0, usize::MAX);
    assert!(capped.len() <= MAX_LEVELS && capped.len() >= MAX_LEVELS / 3, "{}", capped.len());
    assert!(capped.windows(2).all(|w| w[0] < w[1]));
    // A tiny span far from zero still gives a few distinct levels inside it.
    let tiny = nice_levels(1e6, 1e6 + 1e-6, 5);
    assert!(!tiny.is_empty() && tiny.len() <= 5);
    assert!(tiny.iter().all(|&l| l > 1e6 && l < 1e6 + 1e-6));
    let far = nice_levels(1e300, 1.000000000000001e300, 5);
    assert!(far.len() <= 5 && far.windows(2).all(|w| w[0] < w[1]));
}

// ---------------------------------------------------------------- timing (run by hand)

/// The benchmark field: smooth, with several peaks, pits and saddles.
fn bench_grid(n: usize) -> Grid {
    Grid::from_fn(linspace(-3.0, 3.0, n), linspace(-3.0, 3.0, n), |x, y| {
        (1.7 * x).sin() * (1.3 * y).cos() + 0.2 * (x * x - y * y) + 0.1 * x * y + 0.2
    })
    .unwrap()
}

fn time<T>(label: &str, runs: usize, mut f: impl FnMut() -> T) -> T {
    let mut best = f64::INFINITY;
    let mut out = f();
    for _ in 0..runs {
        let t = std::time::Instant::now();
        out = f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!("{label}: best of {runs}: {:.1} ms", best * 1e3);
    out
}

#[test]
#[ignore = "timing; run with --release -- --ignored --nocapture"]
fn timing_lines_2000() {
    let g = bench_grid(2000);
    let (lo, hi) = g.range().unwrap();
    let levels = nice_levels(lo, hi, 10);
    println!("levels {levels:?}");
    let out = time("lines 2000x2000", 5, || lines(&g, &levels, Saddle::Asymptotic));
    let pts: usize = out.iter().map(|l| l.points.len()).sum();
    println!("{} lines, {pts} points", out.len());
}

#[test]
#[ignore = "timing; run with --release -- --ignored --nocapture"]
fn timing_bands_2000() {
    let g = bench_grid(2000);
    let (lo, hi) = g.range().unwrap();
    let mut levels = vec![lo];
    levels.extend(nice_levels(lo, hi, 10));
    levels.push(hi);
    let out = time("bands 2000x2000", 5, || bands(&g, &levels, Saddle::Asymptotic));
    let polys: usize = out.iter().map(|b| b.polygons.len()).sum();
    let pts: usize = out.iter().flat_map(|b| &b.polygons).flatten().map(Vec::len).sum();
    println!("{} bands, {polys} polygons, {pts} points", out.len());
}
