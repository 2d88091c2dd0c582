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
//! one pixel per step along their major axis (the pixel nearest the centre line). With no
//! selection the exact pixels come back. Saving draws the files exactly.

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
    /// Entry of each table row (`u32::MAX` for rows not drawn).
    entry_of: Vec<u32>,
    /// The lit colours.
    palette: Vec<Color>,
    /// Whether each entry is lit now.
    lit: Vec<bool>,
    /// Layer sums, pixel-major: `1 + palette.len()` per pixel, layer 0 the grey context.
    sums: Vec<u32>,
    width: usize,
    height: usize,
    /// Visible part of the tile (the batch's clip), in tile pixels: x0, y0, x1, y1.
    clip: (i32, i32, i32, i32),
    /// The exact pixels with every row lit.
    exact: Vec<u8>,
    /// Pixels whose sums changed since they were last painted.
    dirty: Vec<bool>,
    /// Whether any pixel is dirty.
    any_dirty: bool,
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
                        if x.is_finite() && y.is_finite() { (fast_floor(x), fast_floor(y)) } else { (i32::MIN, 0) }
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
        let (cx0, cy0, cx1, cy1) = clip
            .map(|c| {
                let (x0, y0) = dev(c.x, c.y);
                let (x1, y1) = dev(c.right(), c.bottom());
                (fast_floor(x0), fast_floor(y0), fast_floor(x1) + 1, fast_floor(y1) + 1)
            })
            .unwrap_or((0, 0, width as i32, height as i32));
        let clip = (cx0.max(0), cy0.max(0), cx1.min(width as i32), cy1.min(height as i32));
        let layers = 1 + palette.len();
        let mut entry_of = vec![u32::MAX; item.rows.iter().max().map_or(0, |&r| r as usize + 1)];
        for (e, &r) in item.rows.iter().enumerate() {
            if let Some(slot) = entry_of.get_mut(r as usize) {
                *slot = e as u32;
            }
        }
        let mut counted = CountedTile {
            marks,
            rows: item.rows.clone(),
            colour,
            entry_of,
            palette,
            lit: vec![true; item.rows.len()],
            sums: vec![0; layers * width * height],
            width,
            height,
            clip,
            exact: tile.rgba.clone(),
            dirty: vec![false; width * height],
            any_dirty: false,
        };
        let moves: Vec<(usize, Option<usize>, usize)> =
            (0..counted.rows.len()).map(|i| (i, None, 1 + usize::from(counted.colour[i]))).collect();
        counted.apply(&moves);
        // The tile shows the exact pixels until the first selection; every inked pixel is
        // painted then.
        counted.any_dirty = true;
        Some(counted)
    }

    /// Light the rows of `mask` (`None`: every row) and write the tile's pixels.
    pub fn update(&mut self, mask: Option<&[bool]>, tile: &mut Tile) {
        self.update_rows(mask, None, tile);
    }

    /// [`CountedTile::update`] looking only at table rows `changed` (those whose flag differs
    /// from the previous mask), when the caller knows them; `None` looks at every row.
    pub fn update_rows(&mut self, mask: Option<&[bool]>, changed: Option<&[u32]>, tile: &mut Tile) {
        let entries: Vec<usize> = match changed {
            Some(rows) => rows
                .iter()
                .filter_map(|&r| self.entry_of.get(r as usize).copied().filter(|&e| e != u32::MAX))
                .map(|e| e as usize)
                .collect(),
            None => (0..self.rows.len()).collect(),
        };
        let mut moves = Vec::new();
        for i in entries {
            let Some(&row) = self.rows.get(i) else { continue };
            let now = mask.is_none_or(|m| m.get(row as usize).copied().unwrap_or(false));
            if now == self.lit[i] {
                continue;
            }
            let lit_layer = 1 + usize::from(self.colour[i]);
            let (from, to) = if now { (0, lit_layer) } else { (lit_layer, 0) };
            moves.push((i, Some(from), to));
            self.lit[i] = now;
        }
        self.apply(&moves);
        if mask.is_none() && self.exact.len() == tile.rgba.len() {
            if tile.rgba != self.exact {
                tile.rgba.copy_from_slice(&self.exact);
                tile.version += 1;
            }
            // The sums are back to every row lit, which the exact pixels show; the counted
            // colours go back in at the next selection.
            let layers = 1 + self.palette.len();
            for (d, px) in self.dirty.iter_mut().zip(self.sums.chunks(layers)) {
                *d = px.iter().any(|&v| v > 0);
            }
            self.any_dirty = true;
        } else if self.any_dirty {
            self.paint(tile);
            tile.version += 1;
        }
    }

    /// Move the coverage of each `(entry, from layer, to layer)` (no `from`: only add), in
    /// horizontal bands of the tile in parallel: each band steps through every move but only
    /// writes its own rows, so the sums do not depend on the number of bands.
    fn apply(&mut self, moves: &[(usize, Option<usize>, usize)]) {
        if moves.is_empty() {
            return;
        }
        self.any_dirty = true;
        let layers = 1 + self.palette.len();
        let w = self.width;
        let bands = match self.marks {
            Marks::Lines { .. } if moves.len() >= 64 => (rayon::current_num_threads() * 2).clamp(1, self.height.max(1)),
            _ => 1,
        };
        let rows_per_band = self.height.div_ceil(bands).max(1);
        let marks = &self.marks;
        let clip = self.clip;
        let sum_bands = self.sums.par_chunks_mut(rows_per_band * w * layers);
        let dirty_bands = self.dirty.par_chunks_mut(rows_per_band * w);
        sum_bands.zip(dirty_bands).enumerate().for_each(|(b, (sums, dirty))| {
            let y0 = (b * rows_per_band) as i32;
            let y1 = y0 + (dirty.len() / w.max(1)) as i32;
            let band = Band { y0, y1, clip, w, layers, sums, dirty };
            band.apply(marks, moves);
        });
    }

    /// Turn the layer sums of the dirty pixels into premultiplied pixels.
    fn paint(&mut self, tile: &mut Tile) {
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
        let layers = 1 + self.palette.len();
        let sums = &self.sums;
        let rows = tile.rgba.par_chunks_mut(4 * w.max(1)).zip(self.dirty.par_chunks_mut(w.max(1)));
        rows.enumerate().for_each(|(y, (row, dirty))| {
            for (x, (px, d)) in row.chunks_mut(4).zip(dirty.iter_mut()).enumerate() {
                if !std::mem::take(d) {
                    continue;
                }
                let p = y * w + x;
                let Some(px_sums) = sums.get(p * layers..(p + 1) * layers) else { continue };
                let sg = px_sums.first().copied().unwrap_or(0);
                let (mut keep, mut weight) = (1.0f64, 0.0f64);
                let mut color = [0.0f64; 3];
                for (k, kl) in k_lit.iter().enumerate() {
                    let s = px_sums.get(k + 1).copied().unwrap_or(0);
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
                    // Non-negative: adding a half and truncating rounds (without a libm call).
                    px[c] = (lit * a_lit + grey_rgb[c] * under + 0.5).clamp(0.0, 255.0) as u8;
                }
                px[3] = (alpha * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
            }
        });
        self.any_dirty = false;
    }
}

/// One horizontal band of a tile's count buffers.
struct Band<'a> {
    /// First row of the band (tile pixels).
    y0: i32,
    /// Row after the band.
    y1: i32,
    /// Visible part of the tile: x0, y0, x1, y1.
    clip: (i32, i32, i32, i32),
    /// Tile width in pixels.
    w: usize,
    /// Layers per pixel.
    layers: usize,
    /// The band's sums, pixel-major.
    sums: &'a mut [u32],
    /// The band's dirty flags.
    dirty: &'a mut [bool],
}

impl Band<'_> {
    fn apply(self, marks: &Marks, moves: &[(usize, Option<usize>, usize)]) {
        let (lo_y, hi_y) = (self.y0.max(self.clip.1), self.y1.min(self.clip.3));
        let (lo_x, hi_x) = (self.clip.0, self.clip.2);
        // A point stamp wholly inside the band and the clip is written without per-pixel
        // checks, at offsets from its centre pixel.
        let (reach, offsets): (i32, Vec<(isize, u32)>) = match marks {
            Marks::Points { kernel, .. } => (
                kernel.iter().map(|&(dx, dy, _)| dx.abs().max(dy.abs())).max().unwrap_or(0),
                kernel.iter().map(|&(dx, dy, c)| (dy as isize * self.w as isize + dx as isize, c)).collect(),
            ),
            Marks::Lines { .. } => (0, Vec::new()),
        };
        for &(i, from, to) in moves {
            if let Marks::Points { at, .. } = marks
                && let Some(&(px, py)) = at.get(i)
                && px != i32::MIN
                && px - reach >= lo_x
                && px + reach < hi_x
                && py - reach >= lo_y
                && py + reach < hi_y
            {
                let centre = (py - self.y0) as isize * self.w as isize + px as isize;
                for &(o, c) in &offsets {
                    let p = (centre + o) as usize;
                    let base = p * self.layers;
                    if let Some(s) = from.and_then(|f| self.sums.get_mut(base + f)) {
                        *s = s.wrapping_sub(c);
                    }
                    if let Some(s) = self.sums.get_mut(base + to) {
                        *s = s.wrapping_add(c);
                    }
                    if let Some(d) = self.dirty.get_mut(p) {
                        *d = true;
                    }
                }
                continue;
            }
            let mut put = |x: i32, y: i32, amount: u32| {
                if x < lo_x || x >= hi_x || y < lo_y || y >= hi_y || amount == 0 {
                    return;
                }
                let p = (y - self.y0) as usize * self.w + x as usize;
                if let Some(px) = self.sums.get_mut(p * self.layers..(p + 1) * self.layers) {
                    if let Some(s) = from.and_then(|f| px.get_mut(f)) {
                        *s = s.wrapping_sub(amount);
                    }
                    if let Some(s) = px.get_mut(to) {
                        *s = s.wrapping_add(amount);
                    }
                }
                if let Some(d) = self.dirty.get_mut(p) {
                    *d = true;
                }
            };
            match marks {
                Marks::Points { at, kernel } => {
                    let Some(&(px, py)) = at.get(i) else { continue };
                    if px == i32::MIN {
                        continue;
                    }
                    for &(dx, dy, c) in kernel {
                        put(px + dx, py + dy, c);
                    }
                }
                Marks::Lines { points, stride, width } => {
                    let Some(line) = points.get(i * stride..(i + 1) * stride) else { continue };
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
                        let mut start = fast_floor(a0 - 0.5) + 1;
                        // Half-open: the next segment takes its first pixel centre.
                        let mut end = fast_floor(a1 - 0.5) + 1;
                        if steep {
                            // Only the band's rows.
                            start = start.max(lo_y);
                            end = end.min(hi_y);
                        } else if slope.abs() > 1e-12 {
                            // Only the columns whose line passes through the band's rows.
                            let at_b = |b: f64| a0 + (b + 0.5 - b0) / slope - 0.5;
                            let (e0, e1) = (at_b(f64::from(lo_y) - 1.0), at_b(f64::from(hi_y)));
                            start = start.max(fast_floor(e0.min(e1)));
                            end = end.min(fast_floor(e0.max(e1)) + 2);
                        } else if fast_floor(b0 - 0.5) + 1 < lo_y || fast_floor(b0 - 0.5) > hi_y {
                            continue;
                        }
                        // Each step's ink goes to the pixel nearest the centre line: with
                        // thousands of lines summed, splitting it between two pixels would
                        // change nothing visible and cost twice the writes.
                        let amount = per_step as u32;
                        for a in start..end {
                            let b = fast_floor(b0 + (f64::from(a) + 0.5 - a0) * slope);
                            if steep { put(b, a, amount) } else { put(a, b, amount) }
                        }
                    }
                }
            }
        }
    }
}

/// `x.floor()` as an integer without a libm call (the baseline x86-64 target has no rounding
/// instruction); saturates far outside the `i32` range, where nothing is drawn anyway.
#[inline]
fn fast_floor(x: f64) -> i32 {
    let i = x as i32;
    if f64::from(i) > x { i - 1 } else { i }
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
        assert!(c.sums.chunks(3).take(n).any(|px| px[0] > 0));
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
    fn line_sums_do_not_depend_on_the_bands() {
        use crate::scene::LineBatch;
        let n = FAST_ROWS;
        let points: Vec<Point> = (0..n)
            .flat_map(|i| {
                let y = |k: usize| 2.0 + ((i * (7 + k * 5) + k * 13) % 56) as f64;
                [Point::new(1.0, y(0)), Point::new(20.0, y(1)), Point::new(39.0, y(2))]
            })
            .collect();
        let batch =
            LineBatch { points, stride: 3, color: PerPoint::Uniform(Color::BLACK.with_opacity(0.1)), width: 1.0 };
        let item = Item::new(Role::DataMark, Shape::Lines(batch), Style::default()).with_rows((0..n as u32).collect());
        let scene =
            Scene { width: 40.0, height: 60.0, background: Color::WHITE, title: None, items: vec![item.clone()] };
        let mut t = Tiles::new(&scene, 1.0, |i| i.role == Role::DataMark);
        let k = t.tiles.iter().position(|x| x.dynamic).unwrap();
        let mut banded = CountedTile::new(&item, None, &t.tiles[k], 1.0).unwrap();
        let mut one_by_one = CountedTile::new(&item, None, &t.tiles[k], 1.0).unwrap();
        assert_eq!(banded.sums, one_by_one.sums);
        let mask: Vec<bool> = (0..n).map(|i| i % 5 == 0).collect();
        banded.update(Some(&mask), &mut t.tiles[k]);
        // The same moves applied one at a time (one band each).
        for (i, _) in mask.iter().enumerate().filter(|(_, lit)| !**lit) {
            one_by_one.apply(&[(i, Some(1), 0)]);
        }
        assert_eq!(banded.sums, one_by_one.sums);
        assert!(banded.sums.chunks(2).any(|px| px[0] > 0 && px[1] > 0));
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
