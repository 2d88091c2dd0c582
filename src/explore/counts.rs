//! Relighting large mark batches at interactive rates, by counting ink per pixel.
//!
//! Redrawing 100,000 polylines or 30 × 100,000 points with the exact rasterizers takes far
//! longer than a frame on two cores. But a brush drag changes only the rows that enter or leave
//! the brush from one frame to the next. So for a batch of [`FAST_ROWS`] rows or more, each
//! pixel keeps the summed coverage of every layer — the grey context and each lit colour —
//! in integers; a frame subtracts the changed rows from their old layer and adds them to the
//! new one (exactly, integers undo exactly), then turns the sums into colour.
//!
//! The colour of a pixel follows the same blending as the exact renderers for marks of one
//! colour and opacity `a`: `n` marks covering a pixel by `c₁ … cₙ` leave `∏(1 − a·cᵢ)` of what
//! is under them, taken here as `(1 − a)^Σcᵢ`. The grey layer lies under the lit one as in the
//! files; where lit rows of different colours overlap, their colours are mixed by weight rather
//! than stacked in row order. Points are stamped at the nearest pixel with a disc kernel, lines
//! one pixel step along their major axis. With no selection the exact pixels come back.
//! Saving draws the files exactly.

use rayon::prelude::*;

use crate::mark::highlight::CONTEXT;
use crate::render::tiles::Tile;
use crate::scene::{Color, Item, PerPoint, Rect, Shape};

/// Batches with at least this many rows are relit by counting.
pub const FAST_ROWS: usize = 20_000;
/// Batches with more distinct lit colours than this are relit exactly.
const MAX_COLOURS: usize = 12;
/// Coverage units per pixel fully covered.
const UNIT: f64 = 256.0;

/// Geometry of one batch in tile pixels.
#[derive(Debug)]
enum Marks {
    /// Pixel of each point's centre, and the stamp around it (offset x, offset y, coverage).
    Points { at: Vec<(i32, i32)>, kernel: Vec<(i32, i32, u32)> },
    /// Vertices of each polyline, `stride` per row, in tile pixels.
    Lines { points: Vec<(f64, f64)>, stride: usize, width: f64 },
}

/// The count buffers of one large marks tile.
#[derive(Debug)]
pub struct CountedTile {
    marks: Marks,
    /// Table row of each batch entry.
    rows: Vec<u32>,
    /// Lit colour index of each entry.
    colour: Vec<u8>,
    /// The lit colours.
    palette: Vec<Color>,
    /// Whether each entry is lit now.
    lit: Vec<bool>,
    /// Layer sums: `(1 + palette.len()) × width × height`, layer 0 the grey context.
    sums: Vec<u32>,
    width: usize,
    height: usize,
    /// Visible part of the tile (the batch's clip), in tile pixels: x0, y0, x1, y1.
    clip: (i32, i32, i32, i32),
    /// The exact pixels with every row lit.
    exact: Vec<u8>,
}

impl CountedTile {
    /// Count buffers for `tile`, whose single item is `item` clipped to `clip`, at `scale`
    /// device pixels per canvas unit; `None` when the batch is small, has per-point radii or
    /// outlines, or too many colours (those are relit exactly).
    pub fn new(item: &Item, clip: Option<Rect>, tile: &Tile, scale: f64) -> Option<CountedTile> {
        if item.rows.len() < FAST_ROWS || tile.width == 0 || tile.height == 0 {
            return None;
        }
        let (width, height) = (tile.width as usize, tile.height as usize);
        let (ox, oy) = (tile.rect.x, tile.rect.y);
        let dev = |x: f64, y: f64| ((x - ox) * scale, (y - oy) * scale);
        let (marks, colors) = match &item.shape {
            Shape::Points(b) => {
                let PerPoint::Uniform(r) = b.radius else { return None };
                if b.stroke.is_some() || b.centers.len() != item.rows.len() {
                    return None;
                }
                let at = b
                    .centers
                    .iter()
                    .map(|c| {
                        let (x, y) = dev(c.x, c.y);
                        if x.is_finite() && y.is_finite() { (x.floor() as i32, y.floor() as i32) } else { (i32::MIN, 0) }
                    })
                    .collect();
                (Marks::Points { at, kernel: disc_kernel(r * scale) }, &b.fill)
            }
            Shape::Lines(b) => {
                if b.len() != item.rows.len() {
                    return None;
                }
                let points = b.points.iter().map(|p| dev(p.x, p.y)).collect();
                (Marks::Lines { points, stride: b.stride, width: b.width * scale }, &b.color)
            }
            _ => return None,
        };
        let (palette, colour) = palette_of(colors, item.rows.len())?;
        let clip = clip
            .map(|c| {
                let (x0, y0) = dev(c.x, c.y);
                let (x1, y1) = dev(c.right(), c.bottom());
                (x0.floor() as i32, y0.floor() as i32, x1.ceil() as i32, y1.ceil() as i32)
            })
            .unwrap_or((0, 0, width as i32, height as i32));
        let layers = 1 + palette.len();
        let mut counted = CountedTile {
            marks,
            rows: item.rows.clone(),
            colour,
            palette,
            lit: vec![true; item.rows.len()],
            sums: vec![0; layers * width * height],
            width,
            height,
            clip,
            exact: tile.rgba.clone(),
        };
        for i in 0..counted.rows.len() {
            let layer = 1 + usize::from(counted.colour[i]);
            counted.deposit(i, layer, true);
        }
        Some(counted)
    }

    /// Light the rows of `mask` (`None`: every row) and write the tile's pixels.
    pub fn update(&mut self, mask: Option<&[bool]>, tile: &mut Tile) {
        for i in 0..self.rows.len() {
            let now = mask.is_none_or(|m| m.get(self.rows[i] as usize).copied().unwrap_or(false));
            if now == self.lit[i] {
                continue;
            }
            let lit_layer = 1 + usize::from(self.colour[i]);
            let (from, to) = if now { (0, lit_layer) } else { (lit_layer, 0) };
            self.deposit(i, from, false);
            self.deposit(i, to, true);
            self.lit[i] = now;
        }
        if mask.is_none() && self.exact.len() == tile.rgba.len() {
            tile.rgba.copy_from_slice(&self.exact);
        } else {
            self.paint(tile);
        }
        tile.version += 1;
    }

    /// Add (or remove) entry `i`'s coverage to layer `layer`.
    fn deposit(&mut self, i: usize, layer: usize, add: bool) {
        let (w, h) = (self.width, self.height);
        let (cx0, cy0, cx1, cy1) = self.clip;
        let base = layer * w * h;
        let sums = &mut self.sums;
        let mut put = |x: i32, y: i32, amount: u32| {
            if x < cx0.max(0) || y < cy0.max(0) || x >= cx1.min(w as i32) || y >= cy1.min(h as i32) || amount == 0 {
                return;
            }
            let Some(s) = sums.get_mut(base + y as usize * w + x as usize) else { return };
            *s = if add { s.wrapping_add(amount) } else { s.wrapping_sub(amount) };
        };
        match &self.marks {
            Marks::Points { at, kernel } => {
                let Some(&(px, py)) = at.get(i) else { return };
                if px == i32::MIN {
                    return;
                }
                for &(dx, dy, c) in kernel {
                    put(px + dx, py + dy, c);
                }
            }
            Marks::Lines { points, stride, width } => {
                let Some(line) = points.get(i * stride..(i + 1) * stride) else { return };
                for seg in line.windows(2) {
                    let ((x0, y0), (x1, y1)) = (seg[0], seg[1]);
                    if !(x0.is_finite() && y0.is_finite() && x1.is_finite() && y1.is_finite()) {
                        continue;
                    }
                    let steep = (y1 - y0).abs() > (x1 - x0).abs();
                    // Step along the major axis one pixel centre at a time; `a` major, `b` minor.
                    let (a0, b0, a1, b1) = if steep { (y0, x0, y1, x1) } else { (x0, y0, x1, y1) };
                    let (a0, b0, a1, b1) = if a0 <= a1 { (a0, b0, a1, b1) } else { (a1, b1, a0, b0) };
                    let slope = if a1 > a0 { (b1 - b0) / (a1 - a0) } else { 0.0 };
                    let per_step = (width.max(1.0) * (1.0 + slope * slope).sqrt()).min(1.5) * UNIT;
                    let start = (a0 - 0.5).ceil() as i32;
                    let end = (a1 - 0.5).ceil() as i32; // half-open: the next segment takes its first centre
                    for a in start..end {
                        let b = b0 + (f64::from(a) + 0.5 - a0) * slope - 0.5;
                        let lo = b.floor();
                        let f = b - lo;
                        let (low, high) = (((1.0 - f) * per_step) as u32, (f * per_step) as u32);
                        let lo = lo as i32;
                        if steep {
                            put(lo, a, low);
                            put(lo + 1, a, high);
                        } else {
                            put(a, lo, low);
                            put(a, lo + 1, high);
                        }
                    }
                }
            }
        }
    }

    /// Turn the layer sums into premultiplied pixels.
    fn paint(&self, tile: &mut Tile) {
        let (w, h) = (self.width, self.height);
        let n = w * h;
        if tile.rgba.len() != n * 4 {
            return;
        }
        let alpha_of = |c: Color| c.alpha().clamp(0.0, 0.999);
        let grey = CONTEXT.with_opacity(self.palette.first().map_or(1.0, |c| c.alpha()));
        let k_grey = (1.0 - alpha_of(grey)).ln() / UNIT;
        let k_lit: Vec<f64> = self.palette.iter().map(|c| (1.0 - alpha_of(*c)).ln() / UNIT).collect();
        let rgb = |c: Color| [f64::from(c.r), f64::from(c.g), f64::from(c.b)];
        let grey_rgb = rgb(grey);
        let lit_rgb: Vec<[f64; 3]> = self.palette.iter().map(|c| rgb(*c)).collect();
        let sums = &self.sums;
        tile.rgba.par_chunks_mut(4 * w.max(1)).enumerate().for_each(|(y, row)| {
            for (x, px) in row.chunks_mut(4).enumerate() {
                let p = y * w + x;
                let sg = sums.get(p).copied().unwrap_or(0);
                let (mut keep, mut weight) = (1.0f64, 0.0f64);
                let mut color = [0.0f64; 3];
                for (k, kl) in k_lit.iter().enumerate() {
                    let s = sums.get((k + 1) * n + p).copied().unwrap_or(0);
                    if s == 0 {
                        continue;
                    }
                    let t = (f64::from(s) * kl).exp();
                    keep *= t;
                    let wk = 1.0 - t;
                    weight += wk;
                    for (c, l) in color.iter_mut().zip(lit_rgb[k]) {
                        *c += wk * l;
                    }
                }
                let a_lit = 1.0 - keep;
                let a_grey = if sg == 0 { 0.0 } else { 1.0 - (f64::from(sg) * k_grey).exp() };
                let under = a_grey * (1.0 - a_lit);
                let alpha = a_lit + under;
                for c in 0..3 {
                    let lit = if weight > 0.0 { color[c] / weight } else { 0.0 };
                    px[c] = (lit * a_lit + grey_rgb[c] * under).round().clamp(0.0, 255.0) as u8;
                }
                px[3] = (alpha * 255.0).round().clamp(0.0, 255.0) as u8;
            }
        });
    }
}

/// Distinct colours of a batch and each entry's index into them; `None` for too many.
fn palette_of(colors: &PerPoint<Color>, n: usize) -> Option<(Vec<Color>, Vec<u8>)> {
    match colors {
        PerPoint::Uniform(c) => Some((vec![*c], vec![0; n])),
        PerPoint::Each(cs) => {
            let mut palette: Vec<Color> = Vec::new();
            let mut index = Vec::with_capacity(n);
            for i in 0..n {
                let c = cs.get(i).or(cs.first()).copied().unwrap_or(Color::BLACK);
                let k = match palette.iter().position(|p| *p == c) {
                    Some(k) => k,
                    None if palette.len() < MAX_COLOURS => {
                        palette.push(c);
                        palette.len() - 1
                    }
                    None => return None,
                };
                index.push(k as u8);
            }
            Some((palette, index))
        }
    }
}

/// Coverage of a disc of radius `r` (device pixels) centred in a pixel, over that pixel and
/// its neighbours, in [`UNIT`]s (4 × 4 samples per pixel).
fn disc_kernel(r: f64) -> Vec<(i32, i32, u32)> {
    let r = if r.is_finite() { r.clamp(0.5, 16.0) } else { 1.0 };
    let reach = (r + 0.5).ceil() as i32;
    let mut out = Vec::new();
    for dy in -reach..=reach {
        for dx in -reach..=reach {
            let mut inside = 0;
            for sy in 0..4 {
                for sx in 0..4 {
                    let x = f64::from(dx) + (f64::from(sx) + 0.5) / 4.0 - 0.5;
                    let y = f64::from(dy) + (f64::from(sy) + 0.5) / 4.0 - 0.5;
                    if x * x + y * y <= r * r {
                        inside += 1;
                    }
                }
            }
            if inside > 0 {
                out.push((dx, dy, (f64::from(inside) / 16.0 * UNIT).round() as u32));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::tiles::Tiles;
    use crate::scene::{Point, PointBatch, Role, Scene, Style};

    /// A batch of `n` points on a 60 × 40 canvas, two colours, clipped to the canvas.
    fn tiles(n: usize) -> (Tiles, Item) {
        let red = Color::rgb(200, 30, 30).with_opacity(0.3);
        let blue = Color::rgb(30, 30, 200).with_opacity(0.3);
        let centers = (0..n).map(|i| Point::new(5.0 + (i * 7 % 50) as f64, 5.0 + (i * 13 % 30) as f64)).collect();
        let fill = PerPoint::Each((0..n).map(|i| if i % 2 == 0 { red } else { blue }).collect());
        let batch = PointBatch { centers, radius: PerPoint::Uniform(1.2), fill, stroke: None };
        let item = Item::new(Role::DataMark, Shape::Points(batch), Style::default()).with_rows((0..n as u32).collect());
        let scene = Scene {
            width: 60.0,
            height: 40.0,
            background: Color::WHITE,
            title: None,
            items: vec![Item::group(Role::DataMark, vec![item.clone()], Some(Rect::new(0.0, 0.0, 60.0, 40.0)))],
        };
        (Tiles::new(&scene, 1.0, |i| i.role == Role::DataMark && !i.rows.is_empty()), item)
    }

    #[test]
    fn counts_undo_exactly_and_no_selection_restores_the_exact_pixels() {
        let (mut t, item) = tiles(FAST_ROWS);
        let k = t.tiles.iter().position(|x| x.dynamic).unwrap();
        let (it, clip) = t.single_item(k).map(|(i, c)| (i.clone(), c)).unwrap();
        assert_eq!(it, item);
        let mut c = CountedTile::new(&it, clip, &t.tiles[k], 1.0).expect("large enough to count");
        let start = c.sums.clone();
        let mask: Vec<bool> = (0..FAST_ROWS).map(|i| i % 3 == 0).collect();
        c.update(Some(&mask), &mut t.tiles[k]);
        assert_ne!(c.sums, start);
        // Grey ink went to layer 0, and the layer totals still hold every row's stamp once.
        let n = c.width * c.height;
        let total = |s: &[u32]| s.iter().map(|&v| u64::from(v)).sum::<u64>();
        assert!(c.sums[..n].iter().any(|&v| v > 0));
        assert_eq!(total(&c.sums), total(&start));
        let lit_pixels = t.tiles[k].rgba.clone();
        c.update(None, &mut t.tiles[k]);
        assert_eq!(c.sums, start, "back to every row lit");
        assert_eq!(t.tiles[k].rgba, c.exact, "the exact pixels come back");
        assert_ne!(lit_pixels, c.exact);
        // Few rows, or many colours, are relit exactly instead.
        let (small, item) = tiles(100);
        assert!(CountedTile::new(&item, None, &small.tiles[0], 1.0).is_none());
    }

    #[test]
    fn the_kernel_covers_the_disc_area() {
        for r in [1.0, 1.5, 3.0] {
            let area: f64 = disc_kernel(r).iter().map(|&(_, _, c)| f64::from(c) / UNIT).sum();
            let want = std::f64::consts::PI * r * r;
            assert!((area - want).abs() / want < 0.12, "r = {r}: {area} vs {want}");
        }
    }
}
