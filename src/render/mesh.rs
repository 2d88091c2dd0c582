//! Triangle meshes rasterized with a z-buffer: at every sample the nearest triangle wins, so
//! intersecting and unsorted triangles come out right.
//!
//! Each triangle is filled by testing the samples of its bounding box against its three edges
//! (barycentric coordinates); depth and colour are interpolated linearly (Gouraud). Edges are
//! evaluated the same way for both triangles that share them, so a shared edge leaves no gap.
//! The mesh's pixels are supersampled ([`SUPERSAMPLE`] per axis when the work allows) and each
//! device pixel takes the mean of its samples, which anti-aliases the outline; the result is
//! composited over the pixmap through the clip. Overlapping triangles of one mesh never blend
//! with each other.
//!
//! Work is bounded: the samples a mesh may visit (its triangles' bounding boxes, clipped to what
//! is visible) are capped at [`MAX_MESH_SAMPLES`]. Supersampling is lowered to stay under it,
//! and past it (a mesh of millions of large overlapping triangles) the remaining triangles are
//! left out. Memory is bounded by drawing in bands of at most [`BAND_SAMPLES`] samples, bands
//! in parallel.

use rayon::prelude::*;
use tiny_skia::Pixmap;

use crate::scene::{Color, Mesh};

use super::png::Clip;

/// Samples per device pixel along each axis when the work allows (9 per pixel).
pub const SUPERSAMPLE: u32 = 3;

/// Most samples one mesh may visit (the sum of its triangles' clipped bounding boxes, in
/// samples); about a second of work.
pub const MAX_MESH_SAMPLES: u64 = 200_000_000;

/// Most samples of one band (depth and colour, 20 bytes each; one band per thread at a time).
pub const BAND_SAMPLES: u64 = 1 << 18;

/// One triangle in device pixels, oriented with positive area.
struct Tri {
    p: [[f64; 2]; 3],
    z: [f64; 3],
    c: [[f64; 4]; 3],
    area: f64,
    /// Bounding box in device pixels, clipped to the drawn region: `x0, y0, x1, y1`.
    bbox: [f64; 4],
}

/// Draws `mesh` at `scale` device pixels per canvas unit inside `clip`: bands of rows in
/// parallel, each with its own depth and colour buffers.
pub(crate) fn draw_mesh(pixmap: &mut Pixmap, mesh: &Mesh, scale: f64, clip: &Clip) {
    let Some((cx0, cy0, cx1, cy1)) = clip.device_bounds(pixmap, scale) else { return };
    let mut tris = Vec::with_capacity(mesh.indices.len());
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for i in 0..mesh.indices.len() {
        let Some((p, colours)) = mesh.triangle(i) else { continue };
        let Some(t) = device_triangle(p, colours, scale, [cx0 as f64, cy0 as f64, cx1 as f64, cy1 as f64]) else {
            continue;
        };
        (lo[0], lo[1]) = (lo[0].min(t.bbox[0]), lo[1].min(t.bbox[1]));
        (hi[0], hi[1]) = (hi[0].max(t.bbox[2]), hi[1].max(t.bbox[3]));
        tris.push(t);
    }
    if tris.is_empty() {
        return;
    }
    // The drawn region: whole pixels covering every visible triangle.
    let (x0, y0) = (lo[0].floor().max(cx0 as f64) as i64, lo[1].floor().max(cy0 as f64) as i64);
    let (x1, y1) = (hi[0].ceil().min(cx1 as f64) as i64, hi[1].ceil().min(cy1 as f64) as i64);
    if x0 >= x1 || y0 >= y1 {
        return;
    }
    let box_samples = |t: &Tri, s: f64| ((t.bbox[2] - t.bbox[0]) * s + 1.0) * ((t.bbox[3] - t.bbox[1]) * s + 1.0);
    let work: f64 = tris.iter().map(|t| box_samples(t, 1.0)).sum();
    let ss = (1..=SUPERSAMPLE).rev().find(|s| work * f64::from(s * s) <= MAX_MESH_SAMPLES as f64).unwrap_or(1);
    let ssf = f64::from(ss);
    // Past the budget, the remaining triangles (in the mesh's order) are left out.
    let mut spent = 0.0;
    let kept = tris
        .iter()
        .position(|t| {
            spent += box_samples(t, ssf);
            spent > MAX_MESH_SAMPLES as f64
        })
        .unwrap_or(tris.len());
    tris.truncate(kept);
    let width = (x1 - x0) as usize * ss as usize;
    // Rows of pixels per band.
    let band_rows = (BAND_SAMPLES / (width as u64 * u64::from(ss)).max(1)).max(1) as usize;
    let mask = clip.device_mask(scale);
    let pixmap_width = i64::from(pixmap.width());
    let row_bytes = pixmap_width as usize * 4;
    let rows = &mut pixmap.data_mut()[y0 as usize * row_bytes..y1 as usize * row_bytes];
    rows.par_chunks_mut(band_rows * row_bytes).enumerate().for_each_init(
        || Band { depth: Vec::new(), colour: Vec::new(), width },
        |band, (b, pixels)| {
            let top = y0 + (b * band_rows) as i64;
            let bottom = (top + band_rows as i64).min(y1);
            let samples = (bottom - top) as usize * ss as usize;
            band.depth.clear();
            band.depth.resize(band.width * samples, f32::NEG_INFINITY);
            band.colour.clear();
            band.colour.resize(band.width * samples, [0.0; 4]);
            for t in &tris {
                if t.bbox[3] < top as f64 || t.bbox[1] > bottom as f64 {
                    continue;
                }
                fill(band, t, (x0 as f64, top as f64), ssf, samples);
            }
            composite(pixels, band, (x0, top), (x1, bottom), ss, (mask, pixmap_width));
        },
    );
}

/// Depth and straight-alpha colour of every sample of one band of rows.
struct Band {
    depth: Vec<f32>,
    colour: Vec<[f32; 4]>,
    width: usize,
}

/// A scene triangle in device pixels, oriented with positive area and its box clipped to
/// `region`; `None` when it has no area there or its numbers are not finite.
fn device_triangle(p: [[f32; 3]; 3], colours: [Color; 3], scale: f64, region: [f64; 4]) -> Option<Tri> {
    let mut d = p.map(|q| [f64::from(q[0]) * scale, f64::from(q[1]) * scale]);
    let mut z = p.map(|q| f64::from(q[2]));
    let mut c = colours.map(|c| [f64::from(c.r), f64::from(c.g), f64::from(c.b), f64::from(c.a)]);
    let mut area = Edge::new(d[0], d[1]).at(d[2]);
    if area < 0.0 {
        d.swap(1, 2);
        z.swap(1, 2);
        c.swap(1, 2);
        area = -area;
    }
    if !(area > 0.0 && area.is_finite()) || d.iter().flatten().chain(&z).any(|v| !v.is_finite()) {
        return None;
    }
    let min = |k: usize| d[0][k].min(d[1][k]).min(d[2][k]);
    let max = |k: usize| d[0][k].max(d[1][k]).max(d[2][k]);
    let bbox = [min(0).max(region[0]), min(1).max(region[1]), max(0).min(region[2]), max(1).min(region[3])];
    (bbox[0] <= bbox[2] && bbox[1] <= bbox[3]).then_some(Tri { p: d, z, c, area, bbox })
}

/// The edge from `a` to `b` as its endpoints in a fixed order, so that the two triangles sharing
/// an edge get exactly opposite values at every sample (no sample falls between them).
#[derive(Clone, Copy)]
struct Edge {
    from: [f64; 2],
    to: [f64; 2],
    /// Whether the endpoints were swapped (the value is negated).
    flipped: bool,
}

impl Edge {
    fn new(a: [f64; 2], b: [f64; 2]) -> Edge {
        if (a[0], a[1]) <= (b[0], b[1]) {
            Edge { from: a, to: b, flipped: false }
        } else {
            Edge { from: b, to: a, flipped: true }
        }
    }

    /// Twice the signed area of `(a, b, p)`.
    #[inline]
    fn at(&self, p: [f64; 2]) -> f64 {
        let (u, v) = (self.from, self.to);
        let raw = (v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]);
        if self.flipped { -raw } else { raw }
    }
}

/// Depth-tests and fills the samples of `t` in the band whose top-left pixel corner is
/// `origin`.
fn fill(band: &mut Band, t: &Tri, origin: (f64, f64), ss: f64, rows: usize) {
    // Sample (i, j) sits at device (origin.0 + (i + 0.5) / ss, origin.1 + (j + 0.5) / ss).
    let index = |v: f64, o: f64, n: usize, up: bool| {
        let s = (v - o) * ss - 0.5;
        let s = if up { s.floor() + 1.0 } else { s.ceil() };
        s.clamp(0.0, n as f64) as usize
    };
    let (i0, i1) = (index(t.bbox[0], origin.0, band.width, false), index(t.bbox[2], origin.0, band.width, true));
    let (j0, j1) = (index(t.bbox[1], origin.1, rows, false), index(t.bbox[3], origin.1, rows, true));
    if i0 >= i1 || j0 >= j1 {
        return;
    }
    let [a, b, c] = t.p;
    let edges = [Edge::new(b, c), Edge::new(c, a), Edge::new(a, b)];
    for j in j0..j1 {
        let y = origin.1 + (j as f64 + 0.5) / ss;
        for i in i0..i1 {
            let x = origin.0 + (i as f64 + 0.5) / ss;
            let q = [x, y];
            let (w0, w1, w2) = (edges[0].at(q), edges[1].at(q), edges[2].at(q));
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            let (w0, w1, w2) = (w0 / t.area, w1 / t.area, w2 / t.area);
            let z = (w0 * t.z[0] + w1 * t.z[1] + w2 * t.z[2]) as f32;
            let k = j * band.width + i;
            let Some(stored) = band.depth.get_mut(k) else { continue };
            if z <= *stored {
                continue;
            }
            *stored = z;
            if let Some(out) = band.colour.get_mut(k) {
                *out = [0, 1, 2, 3].map(|m| (w0 * t.c[0][m] + w1 * t.c[1][m] + w2 * t.c[2][m]) as f32);
            }
        }
    }
}

/// Averages each pixel's samples of the band's rows `y0..y1` and paints them over `pixels` (those
/// rows of the pixmap, `pw` pixels wide), source over, through `mask` (of the whole pixmap).
fn composite(
    pixels: &mut [u8],
    band: &Band,
    (x0, y0): (i64, i64),
    (x1, y1): (i64, i64),
    ss: u32,
    (mask, pw): (Option<&[u8]>, i64),
) {
    let n = (ss * ss) as f32;
    let ss = ss as usize;
    for py in y0..y1 {
        for px in x0..x1 {
            let (mut r, mut g, mut b, mut a) = (0f32, 0f32, 0f32, 0f32);
            for sj in 0..ss {
                let row = (py - y0) as usize * ss + sj;
                for si in 0..ss {
                    let k = row * band.width + (px - x0) as usize * ss + si;
                    let Some(c) = band.colour.get(k) else { continue };
                    let alpha = c[3] / 255.0;
                    (r, g, b, a) = (r + c[0] * alpha, g + c[1] * alpha, b + c[2] * alpha, a + c[3]);
                }
            }
            if a <= 0.0 {
                continue;
            }
            let m = mask.map_or(1.0, |m| f32::from(m.get((py * pw + px) as usize).copied().unwrap_or(0)) / 255.0);
            let (r, g, b, a) = (r / n * m, g / n * m, b / n * m, a / n * m);
            let at = ((py - y0) * pw + px) as usize;
            let Some(dst) = pixels.get_mut(at * 4..at * 4 + 4) else { continue };
            let keep = 1.0 - a / 255.0;
            for (d, s) in dst.iter_mut().zip([r, g, b, a]) {
                *d = (s + f32::from(*d) * keep).round().clamp(0.0, 255.0) as u8;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use crate::render::to_pixmap;
    use crate::scene::{Color, Item, Mesh, Rect, Role, Scene, Shape, Style};

    const RED: Color = Color::rgb(220, 20, 30);
    const BLUE: Color = Color::rgb(20, 40, 200);

    /// A mesh of flat-coloured triangles, each `([x, y, depth] × 3, colour)`.
    fn mesh(tris: &[([[f32; 3]; 3], Color)]) -> Mesh {
        let positions = tris.iter().flat_map(|(p, _)| *p).collect::<Vec<_>>();
        let colors = tris.iter().flat_map(|(_, c)| [*c; 3]).collect::<Vec<_>>();
        let indices = (0..tris.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect::<Vec<_>>();
        Mesh { positions: Arc::new(positions), indices: Arc::new(indices), colors: Arc::new(colors), normals: None }
    }

    fn draw(mesh: Mesh, background: Color) -> tiny_skia::Pixmap {
        let item = Item::new(Role::DataMark, Shape::Mesh(mesh), Style::default());
        let scene = Scene { width: 100.0, height: 80.0, background, title: None, items: vec![item] };
        to_pixmap(&scene, 1.0).unwrap()
    }

    fn px(p: &tiny_skia::Pixmap, x: u32, y: u32) -> [u8; 4] {
        p.pixel(x, y).map_or([0; 4], |c| [c.red(), c.green(), c.blue(), c.alpha()])
    }

    fn rgb(c: Color) -> [u8; 4] {
        [c.r, c.g, c.b, 255]
    }

    #[test]
    fn the_nearer_triangle_wins_whatever_the_order() {
        let near = ([[10.0, 10.0, 1.0], [70.0, 10.0, 1.0], [10.0, 70.0, 1.0]], RED);
        let far = ([[30.0, 20.0, 0.0], [90.0, 20.0, 0.0], [30.0, 75.0, 0.0]], BLUE);
        for order in [[far, near], [near, far]] {
            let p = draw(mesh(&order), Color::WHITE);
            assert_eq!(px(&p, 35, 25), rgb(RED), "the overlap shows the nearer triangle");
            assert_eq!(px(&p, 80, 25), rgb(BLUE), "the farther one shows where it is alone");
            assert_eq!(px(&p, 15, 15), rgb(RED));
            assert_eq!(px(&p, 95, 5), rgb(Color::WHITE));
        }
    }

    #[test]
    fn intersecting_triangles_swap_where_their_depths_cross() {
        // Red rises toward the viewer from left to right, blue falls: they cross at x = 50.
        let red = ([[10.0, 10.0, 0.0], [90.0, 10.0, 1.0], [50.0, 70.0, 0.5]], RED);
        let blue = ([[10.0, 12.0, 1.0], [90.0, 12.0, 0.0], [50.0, 72.0, 0.5]], BLUE);
        let p = draw(mesh(&[red, blue]), Color::WHITE);
        assert_eq!(px(&p, 30, 20), rgb(BLUE));
        assert_eq!(px(&p, 70, 20), rgb(RED));
    }

    #[test]
    fn rasterized_area_matches_the_analytic_area() {
        let tris = [
            [[10.3, 12.7, 0.0], [83.1, 20.2, 0.0], [35.6, 71.9, 0.0]],
            [[50.5, 5.5, 0.0], [52.25, 60.0, 0.0], [48.0, 30.0, 0.0]],
            [[5.0, 5.0, 0.0], [95.0, 6.0, 0.0], [6.0, 75.0, 0.0]],
        ];
        for t in tris {
            let p = draw(mesh(&[(t, Color::BLACK)]), Color::TRANSPARENT);
            let covered: f64 = p.pixels().iter().map(|c| f64::from(c.alpha()) / 255.0).sum();
            let [a, b, c] = t.map(|v| [f64::from(v[0]), f64::from(v[1])]);
            let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs();
            assert!((covered - area).abs() <= 1.0, "{t:?}: {covered} pixels for an area of {area}");
        }
    }

    #[test]
    fn shared_edges_leave_no_seam() {
        // A square of two triangles with a skewed diagonal: every pixel inside is fully covered.
        let a = ([[10.0, 10.0, 0.0], [90.0, 10.0, 0.0], [90.0, 70.0, 0.0]], Color::BLACK);
        let b = ([[10.0, 10.0, 0.0], [90.0, 70.0, 0.0], [10.0, 70.0, 0.0]], Color::BLACK);
        let p = draw(mesh(&[a, b]), Color::WHITE);
        for y in 10..70 {
            for x in 10..90 {
                assert_eq!(px(&p, x, y), [0, 0, 0, 255], "({x}, {y})");
            }
        }
        assert_eq!(px(&p, 9, 40), [255; 4]);
    }

    #[test]
    fn colours_are_interpolated_between_vertices() {
        let m = Mesh {
            positions: Arc::new(vec![[10.0, 70.0, 0.0], [90.0, 70.0, 0.0], [50.0, 10.0, 0.0]]),
            indices: Arc::new(vec![[0, 1, 2]]),
            colors: Arc::new(vec![Color::rgb(255, 0, 0), Color::rgb(0, 255, 0), Color::rgb(0, 0, 255)]),
            normals: None,
        };
        let p = draw(m, Color::WHITE);
        let centre = px(&p, 50, 50);
        for c in &centre[..3] {
            assert!(c.abs_diff(85) <= 6, "{centre:?}");
        }
        let near_red = px(&p, 15, 68);
        assert!(near_red[0] > 200 && near_red[1] < 40 && near_red[2] < 40, "{near_red:?}");
    }

    #[test]
    fn broken_triangles_are_skipped_without_panic() {
        let (nan, inf) = (f32::NAN, f32::INFINITY);
        let good = ([[10.0, 10.0, 0.0], [40.0, 10.0, 0.0], [10.0, 40.0, 0.0]], RED);
        let tris = [
            ([[50.0, 10.0, 0.0], [nan, 10.0, 0.0], [50.0, 40.0, 0.0]], BLUE),
            ([[50.0, 10.0, nan], [90.0, 10.0, 0.0], [50.0, 40.0, 0.0]], BLUE),
            ([[50.0, 10.0, 0.0], [inf, 10.0, 0.0], [50.0, 40.0, 0.0]], BLUE),
            ([[50.0, 10.0, 0.0], [70.0, 30.0, 0.0], [90.0, 50.0, 0.0]], BLUE), // collinear
            ([[50.0, 10.0, 0.0], [50.0, 10.0, 0.0], [50.0, 10.0, 0.0]], BLUE), // a point
            ([[-1e30, -1e30, -1.0], [1e30, -1e30, -1.0], [0.0, 3e38, -1.0]], BLUE), // huge, behind
            good,
        ];
        let mut m = mesh(&tris);
        // And indices past the vertices, and fewer colours than vertices.
        Arc::make_mut(&mut m.indices).push([0, 1, 99]);
        Arc::make_mut(&mut m.indices).push([u32::MAX, 2, 3]);
        for scale in [1.0, 0.3, 2.5] {
            let item = Item::new(Role::DataMark, Shape::Mesh(m.clone()), Style::default());
            let scene = Scene { width: 100.0, height: 80.0, background: Color::WHITE, title: None, items: vec![item] };
            assert!(to_pixmap(&scene, scale).is_ok());
        }
        let p = draw(m.clone(), Color::WHITE);
        assert_eq!(px(&p, 15, 15), rgb(RED), "the good triangle is drawn over the huge one");
        assert_eq!(px(&p, 75, 15), rgb(BLUE), "the huge finite triangle is drawn");
        // Without the huge one, nothing of the broken ones shows.
        let mut tris = tris.to_vec();
        tris.remove(5);
        let p = draw(mesh(&tris), Color::WHITE);
        assert_eq!(px(&p, 55, 15), [255; 4]);
        assert_eq!(px(&p, 70, 29), [255; 4]);
        let short = Mesh { colors: Arc::new(vec![RED]), ..mesh(&[good]) };
        let p = draw(short, Color::WHITE);
        let faded = px(&p, 37, 11);
        assert!(faded[1] > 220, "vertices without a colour are transparent: {faded:?}");
    }

    #[test]
    fn the_clip_cuts_the_mesh() {
        let big = ([[0.0, 0.0, 0.0], [200.0, 0.0, 0.0], [0.0, 200.0, 0.0]], RED);
        let item = Item::new(Role::DataMark, Shape::Mesh(mesh(&[big])), Style::default());
        let group = Item::group(Role::DataMark, vec![item], Some(Rect::new(20.0, 20.0, 30.5, 30.0)));
        let scene = Scene { width: 100.0, height: 80.0, background: Color::WHITE, title: None, items: vec![group] };
        let p = to_pixmap(&scene, 1.0).unwrap();
        assert_eq!(px(&p, 25, 25), rgb(RED));
        assert_eq!(px(&p, 15, 25), [255; 4]);
        assert_eq!(px(&p, 25, 55), [255; 4]);
        let edge = px(&p, 50, 30);
        assert!(edge[1] > 100 && edge[1] < 160, "half-covered clip edge pixel: {edge:?}");
    }

    #[test]
    fn band_drawing_matches_one_pass() {
        // A mesh taller than one band is drawn in several; the seams between bands are invisible.
        let tall = ([[0.0, 0.0, 0.0], [900.0, 40.0, 0.0], [30.0, 2000.0, 1.0]], RED);
        let cross = ([[0.0, 1000.0, 2.0], [900.0, 900.0, 2.0], [900.0, 1100.0, 2.0]], BLUE);
        let item = Item::new(Role::DataMark, Shape::Mesh(mesh(&[tall, cross])), Style::default());
        let scene = Scene { width: 900.0, height: 2000.0, background: Color::WHITE, title: None, items: vec![item] };
        let p = to_pixmap(&scene, 1.0).unwrap();
        assert!(900 * 2000 * 9 > super::BAND_SAMPLES, "the test must need more than one band");
        let row = |y: u32| (0..900).filter(|&x| px(&p, x, y) != [255; 4]).count();
        // Row widths change smoothly down the triangle: no missing or doubled rows at band edges.
        for rows in [100..850, 1150..1900] {
            let widths: Vec<usize> = rows.map(row).collect();
            let jump = widths.windows(2).position(|w| w[0].abs_diff(w[1]) > 2);
            assert_eq!(jump, None, "a jump in row widths: {widths:?}");
        }
        // The nearer blue triangle covers the red one where they overlap.
        assert_eq!(px(&p, 450, 1000), rgb(BLUE));
        assert_eq!(px(&p, 300, 500), rgb(RED));
    }
}
