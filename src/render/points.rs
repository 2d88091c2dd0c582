//! Fast rasterization of point batches (scatter plots of millions of points).
//!
//! Instead of building and filling a path per circle, each point blends a precomputed
//! anti-aliased coverage stamp straight into the pixmap's premultiplied RGBA buffer. Stamps are
//! computed once per (quantized) device radius at `SUB × SUB` subpixel offsets by tiny-skia's
//! own anti-aliased rasterizer (into small masks), so they match its generic path; only the
//! snapping of centres to 1/`SUB` pixel differs. Outlines use ring stamps; strokes thinner
//! than one device pixel are drawn one pixel wide with proportionally less alpha, as tiny-skia
//! draws hairlines. Points larger than `MAX_STAMP_RADIUS` device pixels go through tiny-skia.
//! Drawing order is preserved point by point (fill, then outline), as in SVG.

use tiny_skia::{FillRule, Mask, PathBuilder, Pixmap, Transform};

use crate::scene::{Color, PerPoint, PointBatch};

use super::png::{Clip, paint};
use super::visible_stroke;

/// Subpixel positions per axis (centres are snapped to 1/SUB of a device pixel).
const SUB: usize = 8;
/// Radius quantization steps per device pixel.
const RADIUS_STEPS: f64 = 16.0;
/// Largest outer radius, in device pixels, drawn with stamps.
const MAX_STAMP_RADIUS: f64 = 32.0;

/// Coverage of one disc or ring at one subpixel offset.
struct Stamp {
    /// Side length of the square coverage grid.
    size: usize,
    /// First and one-past-last row with non-zero coverage.
    y0: usize,
    y1: usize,
    /// Per row, the half-open column range of non-zero coverage.
    spans: Vec<(usize, usize)>,
    /// Coverage 0..=255, row-major, `size * size`.
    cov: Vec<u8>,
    /// The stamp pre-multiplied by the batch's uniform colour, if it has one.
    painted: Option<Painted>,
}

/// Pixels per block of a painted stamp.
const BLOCK: usize = 8;

/// Eight pixels of a stamp in one colour: per channel, the coverage-scaled colour and the
/// inverse alpha that multiplies the destination (255 where the stamp does not cover, which
/// leaves those pixels exactly unchanged).
#[derive(Clone)]
struct Block {
    scaled: [u8; 4 * BLOCK],
    inverse: [u16; 4 * BLOCK],
}

/// A stamp painted in one colour as rows of whole blocks, so blending runs on fixed-size
/// arrays the compiler turns into SIMD: rows `y0..y1`, each `blocks` blocks from column `x0`.
struct Painted {
    x0: usize,
    blocks: usize,
    rows: Vec<Block>,
}

/// Paints `stamp` with a coverage table.
fn paint_stamp(stamp: &Stamp, table: &[u32; 256]) -> Painted {
    let rows = stamp.y0..stamp.y1;
    let spans = stamp.spans.get(rows.clone()).unwrap_or(&[]);
    let x0 = spans.iter().filter(|(a, b)| b > a).map(|(a, _)| *a).min().unwrap_or(0);
    let x1 = spans.iter().map(|(_, b)| *b).max().unwrap_or(0).max(x0);
    let blocks = (x1 - x0).div_ceil(BLOCK);
    let empty = Block { scaled: [0; 4 * BLOCK], inverse: [255; 4 * BLOCK] };
    let mut out = vec![empty; rows.len() * blocks];
    for (row, y) in out.chunks_exact_mut(blocks.max(1)).zip(rows) {
        for (k, block) in row.iter_mut().enumerate() {
            for p in 0..BLOCK {
                let x = x0 + k * BLOCK + p;
                let c = if x < stamp.size { stamp.cov.get(y * stamp.size + x).copied().unwrap_or(0) } else { 0 };
                let v = table[usize::from(c)];
                let inv = (255 - (v >> 24)) as u16;
                for (ch, byte) in v.to_le_bytes().into_iter().enumerate() {
                    block.scaled[p * 4 + ch] = byte;
                    block.inverse[p * 4 + ch] = inv;
                }
            }
        }
    }
    Painted { x0, blocks, rows: out }
}

/// Blends one block onto 8 destination pixels: `dst * inverse / 255 + scaled` per channel.
#[inline(always)]
fn blend_block(dst: &mut [u8; 4 * BLOCK], block: &Block) {
    for ((d, &s), &inv) in dst.iter_mut().zip(&block.scaled).zip(&block.inverse) {
        *d = s.wrapping_add(((u16::from(*d) * inv + 255) >> 8) as u8);
    }
}

/// Stamps for every subpixel offset of one shape; stamp pixel (0, 0) lies at device pixel
/// (floor(centre) − half) on each axis.
struct StampSet {
    half: i64,
    /// `SUB * SUB` stamps, index `sub_y * SUB + sub_x`.
    stamps: Vec<Stamp>,
}

/// Stamps of a filled disc of radius `r` (`ring` = `None`) or of its outline of width `ring`,
/// rasterized by tiny-skia itself into small masks so they match its generic path exactly.
fn build_set(r: f64, ring: Option<f64>) -> StampSet {
    let outer = r + ring.map_or(0.0, |w| w / 2.0);
    let half = outer.ceil() as i64 + 1;
    let size = (2 * half + 1) as usize;
    let mut stamps = Vec::with_capacity(SUB * SUB);
    for sy in 0..SUB {
        for sx in 0..SUB {
            let cx = half as f64 + sx as f64 / SUB as f64;
            let cy = half as f64 + sy as f64 / SUB as f64;
            let cov = stamp_coverage(size, cx, cy, r, ring).unwrap_or_else(|| vec![0; size * size]);
            let spans: Vec<(usize, usize)> = cov
                .chunks_exact(size)
                .map(|row| match (row.iter().position(|&v| v > 0), row.iter().rposition(|&v| v > 0)) {
                    (Some(a), Some(b)) => (a, b + 1),
                    _ => (0, 0),
                })
                .collect();
            let y0 = spans.iter().position(|(a, b)| b > a).unwrap_or(0);
            let y1 = spans.iter().rposition(|(a, b)| b > a).map_or(0, |j| j + 1);
            stamps.push(Stamp { size, y0, y1, spans, cov, painted: None });
        }
    }
    StampSet { half, stamps }
}

/// `set` with every stamp painted by `table` (unchanged without one).
fn painted_set(mut set: StampSet, table: Option<&[u32; 256]>) -> StampSet {
    if let Some(table) = table {
        for stamp in &mut set.stamps {
            stamp.painted = Some(paint_stamp(stamp, table));
        }
    }
    set
}

/// Anti-aliased coverage of one disc or ring in a `size` × `size` grid.
fn stamp_coverage(size: usize, cx: f64, cy: f64, r: f64, ring: Option<f64>) -> Option<Vec<u8>> {
    let side = u32::try_from(size).ok()?;
    let mut mask = Mask::new(side, side)?;
    let circle = PathBuilder::from_circle(cx as f32, cy as f32, r as f32)?;
    let path = match ring {
        None => circle,
        Some(w) => circle
            .stroke(&tiny_skia::Stroke { width: super::png::stroke_width(w), ..tiny_skia::Stroke::default() }, 1.0)?,
    };
    mask.fill_path(&path, FillRule::Winding, true, Transform::identity());
    Some(mask.take())
}

/// `x * c / 255` on all four 8-bit lanes of `x`, with tiny-skia's rounding (`(v + 255) >> 8`),
/// which is exact for `c` = 0 and `c` = 255.
#[inline(always)]
pub(super) fn mul_lanes(x: u32, c: u32) -> u32 {
    let rb = (((x & 0x00FF_00FF) * c + 0x00FF_00FF) >> 8) & 0x00FF_00FF;
    let ga = (((x >> 8) & 0x00FF_00FF) * c + 0x00FF_00FF) & 0xFF00_FF00;
    rb | ga
}

/// Source-over of an already coverage-scaled premultiplied `s` onto premultiplied `dst`.
#[inline(always)]
pub(super) fn over(dst: u32, s: u32) -> u32 {
    s + mul_lanes(dst, 255 - (s >> 24))
}

/// A straight-alpha colour as packed premultiplied RGBA (little-endian byte order R, G, B, A).
pub(super) fn premultiplied(c: Color) -> u32 {
    let a = u32::from(c.a);
    let pm = |v: u8| (u32::from(v) * a + 127) / 255;
    pm(c.r) | (pm(c.g) << 8) | (pm(c.b) << 16) | (a << 24)
}

/// The source colour of a stamp: one colour with its 256 coverage-scaled values precomputed,
/// or a colour scaled per pixel.
#[derive(Clone, Copy)]
enum Source<'a> {
    Table(&'a [u32; 256]),
    Color(u32),
}

/// Coverage-scaled values of a premultiplied colour for every coverage 0..=255.
pub(super) fn coverage_table(src: u32) -> Box<[u32; 256]> {
    let mut t = Box::new([0u32; 256]);
    for (c, v) in (0u32..).zip(t.iter_mut()) {
        *v = mul_lanes(src, c);
    }
    t
}

/// Where blits may write: a horizontal band of the pixmap (its bytes start at row `row0`),
/// limited to the half-open device rectangle `x0..x1 × y0..y1`, plus the clip mask (whole
/// pixmap, row-major) if any. Shared with the line rasterizer.
pub(super) struct Target<'a> {
    /// Pixmap width in pixels.
    pub(super) width: usize,
    /// First pixmap row of the band's bytes.
    pub(super) row0: i64,
    /// Writable columns `x0..x1` and rows `y0..y1`.
    pub(super) x0: i64,
    pub(super) y0: i64,
    pub(super) x1: i64,
    pub(super) y1: i64,
    /// Clip coverage of the whole pixmap, if the clip is not pixel-aligned.
    pub(super) mask: Option<&'a [u8]>,
}

/// Blends one stamp with its pixel (0, 0) at device pixel (`ox`, `oy`).
///
/// Rows of a painted stamp that lie wholly inside the target (and unmasked) are blended a
/// block at a time; other rows go pixel by pixel.
fn blit(data: &mut [u8], t: &Target<'_>, stamp: &Stamp, ox: i64, oy: i64, src: Source<'_>) {
    let ys = (oy + stamp.y0 as i64).max(t.y0);
    let ye = (oy + stamp.y1 as i64).min(t.y1);
    if let (Some(painted), Source::Table(_), None) = (&stamp.painted, src, t.mask) {
        let bx = ox + painted.x0 as i64;
        let width = painted.blocks * BLOCK;
        if bx >= t.x0 && bx + width as i64 <= t.x1 {
            if ys >= ye {
                return;
            }
            // ys lies inside the target and the stamp rows: all offsets are non-negative.
            let nb = painted.blocks;
            let r0 = (ys - oy) as usize - stamp.y0;
            let rows = (ye - ys) as usize;
            let first = (ys - t.row0) as usize * t.width + bx as usize;
            let Some(blocks) = painted.rows.get(r0 * nb..(r0 + rows) * nb) else { return };
            if nb == 1 {
                for (k, block) in blocks.iter().enumerate() {
                    let p = (first + k * t.width) * 4;
                    let Some(dst) =
                        data.get_mut(p..p + 4 * BLOCK).and_then(|d| <&mut [u8; 4 * BLOCK]>::try_from(d).ok())
                    else {
                        break;
                    };
                    blend_block(dst, block);
                }
            } else {
                for (k, row_blocks) in blocks.chunks_exact(nb.max(1)).enumerate() {
                    let p = (first + k * t.width) * 4;
                    let Some(dst) = data.get_mut(p..p + width * 4) else { break };
                    let (dst, _) = dst.as_chunks_mut::<{ 4 * BLOCK }>();
                    for (d, block) in dst.iter_mut().zip(row_blocks) {
                        blend_block(d, block);
                    }
                }
            }
            return;
        }
    }
    for y in ys..ye {
        blit_row(data, t, stamp, ox, oy, y, src);
    }
}

/// Blends row `y` of a stamp placed at (`ox`, `oy`), pixel by pixel.
fn blit_row(data: &mut [u8], t: &Target<'_>, stamp: &Stamp, ox: i64, oy: i64, y: i64, src: Source<'_>) {
    // y lies inside the target and the stamp, so both offsets are non-negative.
    let sy = (y - oy) as usize;
    let Some(&(a, b)) = stamp.spans.get(sy) else { return };
    let xs = (ox + a as i64).max(t.x0);
    let xe = (ox + b as i64).min(t.x1);
    if xs >= xe {
        return;
    }
    let n = (xe - xs) as usize;
    let start = sy * stamp.size + (xs - ox) as usize;
    let Some(cov_row) = stamp.cov.get(start..start + n) else { return };
    let p = (y - t.row0) as usize * t.width + xs as usize;
    let Some(dst_row) = data.get_mut(p * 4..(p + n) * 4) else { return };
    let (dst_px, _) = dst_row.as_chunks_mut::<4>();
    match t.mask {
        None => blend_row(dst_px, cov_row, src),
        Some(mask) => {
            let q = y as usize * t.width + xs as usize;
            let mut buf = [0u8; 128];
            let (Some(mask_row), Some(buf)) = (mask.get(q..q + n), buf.get_mut(..n)) else { return };
            for ((b, &c), &m) in buf.iter_mut().zip(cov_row).zip(mask_row) {
                *b = ((u32::from(c) * u32::from(m) + 255) >> 8) as u8;
            }
            blend_row(dst_px, buf, src);
        }
    }
}

/// Source-over of `src` at per-pixel coverage `cov` onto a row of premultiplied pixels.
#[inline(always)]
fn blend_row(dst: &mut [[u8; 4]], cov: &[u8], src: Source<'_>) {
    match src {
        Source::Table(table) => {
            for (d, &c) in dst.iter_mut().zip(cov) {
                *d = over(u32::from_le_bytes(*d), table[usize::from(c)]).to_le_bytes();
            }
        }
        Source::Color(color) => {
            for (d, &c) in dst.iter_mut().zip(cov) {
                *d = over(u32::from_le_bytes(*d), mul_lanes(color, u32::from(c))).to_le_bytes();
            }
        }
    }
}

/// Stamp sets indexed by quantized radius, built before drawing.
struct Cache {
    sets: Vec<Option<StampSet>>,
}

impl Cache {
    fn new() -> Cache {
        Cache { sets: (0..KEYS).map(|_| None).collect() }
    }

    fn get(&self, key: usize) -> Option<&StampSet> {
        self.sets.get(key)?.as_ref()
    }
}

/// Number of radius keys (quantized radii up to `MAX_STAMP_RADIUS`).
const KEYS: usize = (MAX_STAMP_RADIUS * RADIUS_STEPS) as usize + 2;
/// Rows per band when a batch is binned into horizontal bands (keeps the pixels being blended
/// in cache and lets bands be drawn in parallel).
const BAND_ROWS: usize = 32;
/// Batches smaller than this are drawn in one pass on the calling thread.
const PARALLEL_MIN_POINTS: usize = 20_000;
/// Points binned and drawn per round (their records stay in cache).
const POINT_CHUNK: usize = 1 << 16;
/// Offset (device pixels) that keeps snapped coordinates positive: points are culled to within
/// `MAX_STAMP_RADIUS + 2` pixels of the canvas before snapping.
const SNAP_OFFSET: f64 = 4096.0;

/// A point ready to stamp, compact so binned points are read sequentially: the pixel holding
/// its snapped centre, the subpixel stamp index, how many rows it reaches up and down, its
/// radius key and (for per-point colours) its premultiplied fill.
#[derive(Clone, Copy)]
struct Spot {
    fx: i32,
    fy: i32,
    sub: u8,
    ext: u8,
    key: u16,
    fill: u32,
}

/// Everything a point needs to be drawn, shared read-only by all threads.
struct Plan<'a> {
    batch: &'a PointBatch,
    scale: f64,
    fills: Cache,
    rings: Cache,
    /// Uniform fill as a coverage table.
    fill_table: Option<Box<[u32; 256]>>,
    /// Stroke: device width and coverage table.
    stroke: Option<(f64, Box<[u32; 256]>)>,
    /// Device clip bounds (half-open).
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Plan<'_> {
    fn stroke_half(&self) -> f64 {
        self.stroke.as_ref().map_or(0.0, |(w, _)| w / 2.0)
    }

    /// Calls `out(i, Some(spot))` for each visible stamp point of `range` in order, and
    /// `out(i, None)` for a point too large for stamps; stops when `out` returns false.
    fn visit(&self, range: std::ops::Range<usize>, out: &mut impl FnMut(usize, Option<Spot>) -> bool) {
        let batch = self.batch;
        let fill_each = |i: usize| batch.fill.at(i).map_or(0, premultiplied);
        match (&batch.radius, self.fill_table.is_some()) {
            (PerPoint::Uniform(r), true) => self.scan(range, |_| Some(*r), |_| 0, out),
            (PerPoint::Uniform(r), false) => self.scan(range, |_| Some(*r), fill_each, out),
            (PerPoint::Each(_), true) => self.scan(range, |i| batch.radius.at(i), |_| 0, out),
            (PerPoint::Each(_), false) => self.scan(range, |i| batch.radius.at(i), fill_each, out),
        }
    }

    /// [`Plan::visit`] with radius and fill lookups inlined.
    #[inline(always)]
    fn scan(
        &self,
        range: std::ops::Range<usize>,
        radius: impl Fn(usize) -> Option<f64>,
        fill: impl Fn(usize) -> u32,
        out: &mut impl FnMut(usize, Option<Spot>) -> bool,
    ) {
        let Some(centers) = self.batch.centers.get(range.clone()) else { return };
        let stroke_half = self.stroke_half();
        let snap = |v: f64| ((v + SNAP_OFFSET) * SUB as f64 + 0.5) as i64 - SNAP_OFFSET as i64 * SUB as i64;
        for (i, c) in range.zip(centers) {
            let Some(r) = radius(i) else { continue };
            let (x, y, rd) = (c.x * self.scale, c.y * self.scale, r * self.scale);
            let outer = rd + stroke_half;
            let reach = outer + 1.0;
            // Written so that NaN and infinite values fail every comparison and are skipped.
            let visible = rd > 0.0
                && reach < f64::MAX
                && x >= self.x0 - reach
                && x <= self.x1 + reach
                && y >= self.y0 - reach
                && y <= self.y1 + reach;
            if !visible {
                continue;
            }
            let keep_going = if outer > MAX_STAMP_RADIUS {
                out(i, None)
            } else {
                // Positive after the offset, so shifts and masks are floor and remainder.
                let (qx, qy) = (snap(x), snap(y));
                let spot = Spot {
                    fx: (qx >> SUB.trailing_zeros()) as i32,
                    fy: (qy >> SUB.trailing_zeros()) as i32,
                    sub: (((qy & (SUB as i64 - 1)) << SUB.trailing_zeros()) | (qx & (SUB as i64 - 1))) as u8,
                    ext: (outer as u8).saturating_add(2),
                    key: (rd * RADIUS_STEPS + 0.5) as u16,
                    fill: fill(i),
                };
                out(i, Some(spot))
            };
            if !keep_going {
                return;
            }
        }
    }

    /// Builds the stamp sets for every radius key marked in `keys`.
    fn prepare(&mut self, keys: &[bool]) {
        let stroke = self.stroke.as_ref().map(|(w, _)| *w);
        for (key, _) in keys.iter().enumerate().filter(|(_, used)| **used) {
            let rq = key as f64 / RADIUS_STEPS;
            if key > 0
                && let Some(slot @ None) = self.fills.sets.get_mut(key)
            {
                *slot = Some(painted_set(build_set(rq, None), self.fill_table.as_deref()));
            }
            if let Some(w) = stroke
                && let Some(slot @ None) = self.rings.sets.get_mut(key)
            {
                let table = self.stroke.as_ref().map(|(_, t)| &**t);
                *slot = Some(painted_set(build_set(rq, Some(w)), table));
            }
        }
    }

    /// Radius keys used by the points of `range`, and whether any point is too large for
    /// stamps.
    fn keys(&self, range: std::ops::Range<usize>) -> (Vec<bool>, bool) {
        let mut keys = vec![false; KEYS];
        if let PerPoint::Uniform(r) = self.batch.radius {
            let rd = r * self.scale;
            if !rd.is_finite() || rd <= 0.0 {
                return (keys, false);
            }
            if rd + self.stroke_half() > MAX_STAMP_RADIUS {
                return (keys, true);
            }
            if let Some(k) = keys.get_mut((rd * RADIUS_STEPS + 0.5) as usize) {
                *k = true;
            }
            return (keys, false);
        }
        let mut large = false;
        self.visit(range, &mut |_, spot| {
            match spot {
                Some(s) => {
                    if let Some(k) = keys.get_mut(usize::from(s.key)) {
                        *k = true;
                    }
                }
                None => large = true,
            }
            true
        });
        (keys, large)
    }

    /// Draws one stamp point (fill, then outline) into `data` within `t`.
    #[inline(always)]
    fn draw(&self, spot: &Spot, data: &mut [u8], t: &Target<'_>) {
        let key = usize::from(spot.key);
        let sub = usize::from(spot.sub);
        let (fx, fy) = (i64::from(spot.fx), i64::from(spot.fy));
        if let Some(set) = self.fills.get(key) {
            let src = match &self.fill_table {
                Some(table) => Some(Source::Table(table)),
                None => (spot.fill >> 24 != 0).then_some(Source::Color(spot.fill)),
            };
            if let (Some(src), Some(stamp)) = (src, set.stamps.get(sub)) {
                blit(data, t, stamp, fx - set.half, fy - set.half, src);
            }
        }
        if let (Some((_, table)), Some(set)) = (&self.stroke, self.rings.get(key))
            && let Some(stamp) = set.stamps.get(sub)
        {
            blit(data, t, stamp, fx - set.half, fy - set.half, Source::Table(table));
        }
    }

    /// Bins the stamp points of `range` into `bands` (cleared first) of `BAND_ROWS` rows each,
    /// keeping batch order within every band.
    fn bin(&self, range: std::ops::Range<usize>, bands: &mut [Vec<Spot>]) {
        for band in bands.iter_mut() {
            band.clear();
        }
        let (top, bottom) = (self.y0 as i64, self.y1 as i64 - 1);
        self.visit(range, &mut |_, spot| {
            let Some(spot) = spot else { return true };
            let (fy, ext) = (i64::from(spot.fy), i64::from(spot.ext));
            let lo = ((fy - ext).max(top) as usize) / BAND_ROWS;
            let hi = ((fy + ext).min(bottom).max(0) as usize) / BAND_ROWS;
            if lo == hi {
                if let Some(band) = bands.get_mut(lo) {
                    band.push(spot);
                }
            } else {
                for band in bands.iter_mut().take(hi + 1).skip(lo) {
                    band.push(spot);
                }
            }
            true
        });
    }
}

/// Draws every point of `batch` (canvas units, `scale` device pixels per unit) inside `clip`.
///
/// Points with a non-finite centre or a non-finite or non-positive radius are skipped. Large
/// batches are binned into horizontal bands, in parallel, and the bands drawn in parallel; each
/// band draws its points in batch order, so overlapping points stack exactly as when drawn one
/// by one.
pub(crate) fn draw_batch(pixmap: &mut Pixmap, batch: &PointBatch, scale: f64, clip: &Clip) {
    let threads = rayon::current_num_threads().min(8);
    draw_batch_on(pixmap, batch, scale, clip, threads);
}

/// [`draw_batch`] using at most `threads` threads.
fn draw_batch_on(pixmap: &mut Pixmap, batch: &PointBatch, scale: f64, clip: &Clip, threads: usize) {
    let width = pixmap.width() as usize;
    let ph = i64::from(pixmap.height());
    let Some((x0, y0, x1, y1)) = clip.device_bounds(pixmap, scale) else { return };
    // Outline: device width, and for hairlines (< 1 px) one pixel at proportionally less alpha.
    let stroke = visible_stroke(&batch.stroke).map(|s| {
        let w = s.width * scale;
        if w < 1.0 { (1.0, premultiplied(s.color.with_opacity(w))) } else { (w, premultiplied(s.color)) }
    });
    let fill_table = match &batch.fill {
        PerPoint::Uniform(c) if c.a > 0 => Some(coverage_table(premultiplied(*c))),
        _ => None,
    };
    if matches!(&batch.fill, PerPoint::Uniform(c) if c.a == 0) && stroke.is_none() {
        return;
    }
    let mut plan = Plan {
        batch,
        scale,
        fills: Cache::new(),
        rings: Cache::new(),
        fill_table,
        stroke: stroke.map(|(w, src)| (w, coverage_table(src))),
        x0: x0 as f64,
        y0: y0 as f64,
        x1: x1 as f64,
        y1: y1 as f64,
    };
    let mask = clip.device_mask(scale);
    let n = batch.centers.len();
    let (keys, large) = plan.keys(0..n);
    plan.prepare(&keys);

    if large || n < PARALLEL_MIN_POINTS {
        // One pass in batch order; large points go through tiny-skia between stamps.
        let t = Target { width, row0: 0, x0, y0, x1, y1, mask };
        plan.visit(0..n, &mut |i, spot| {
            match spot {
                Some(spot) => plan.draw(&spot, pixmap.data_mut(), &t),
                None => generic_point(pixmap, batch, i, scale, clip),
            }
            true
        });
        return;
    }

    // Chunks of points are binned into horizontal bands (by up to `threads` threads, each
    // taking a slice of the chunk), then the bands are drawn (by up to `threads` threads, each
    // taking the next band from a queue). Bands are disjoint rows, so threads never share
    // pixels; within a band the slices are drawn in order, so overlapping points stack exactly
    // as one by one. Band buffers are reused from chunk to chunk, and a band's pixels stay in
    // cache while it is drawn.
    let threads = threads.clamp(1, 16);
    let nbands = (ph as usize).div_ceil(BAND_ROWS);
    let band_bytes = BAND_ROWS * width * 4;
    let part_len = POINT_CHUNK.div_ceil(threads);
    let mut parts: Vec<Vec<Vec<Spot>>> =
        (0..threads).map(|_| (0..nbands).map(|_| Vec::with_capacity(part_len / nbands + 64)).collect()).collect();
    let plan = &plan;
    let draw_band = |b: usize, rows: &mut [u8], parts: &[Vec<Vec<Spot>>]| {
        let row0 = (b * BAND_ROWS) as i64;
        let t = Target { width, row0, x0, y0: y0.max(row0), x1, y1: y1.min(row0 + BAND_ROWS as i64), mask };
        for part in parts {
            for spot in part.get(b).map_or(&[][..], |v| v.as_slice()) {
                plan.draw(spot, rows, &t);
            }
        }
    };
    for start in (0..n).step_by(POINT_CHUNK) {
        let end = (start + POINT_CHUNK).min(n);
        let step = (end - start).div_ceil(threads);
        let jobs: Vec<_> = parts
            .iter_mut()
            .enumerate()
            .map(|(t, part)| {
                let lo = (start + t * step).min(end);
                (lo..(lo + step).min(end), part)
            })
            .collect();
        in_parallel(threads, jobs, |(range, part)| plan.bin(range, part));
        let bands: Vec<_> = pixmap.data_mut().chunks_mut(band_bytes).enumerate().collect();
        let parts = &parts;
        in_parallel(threads, bands, |(b, rows)| draw_band(b, rows, parts));
    }
}

/// Runs `work` on every item: on the calling thread when `threads` is 1, otherwise on rayon's
/// shared pool (so charts rendered in parallel do not oversubscribe the cores).
pub(super) fn in_parallel<T: Send>(threads: usize, items: Vec<T>, work: impl Fn(T) + Sync + Send) {
    use rayon::prelude::*;
    if threads <= 1 || items.len() <= 1 {
        items.into_iter().for_each(work);
        return;
    }
    items.into_par_iter().for_each(work);
}

/// Draws point `i` of `batch` with tiny-skia paths (large points).
fn generic_point(pixmap: &mut Pixmap, batch: &PointBatch, i: usize, scale: f64, clip: &Clip) {
    let (Some(c), Some(r)) = (batch.centers.get(i), batch.radius.at(i)) else { return };
    let Some(path) = PathBuilder::from_circle(c.x as f32, c.y as f32, r as f32) else { return };
    let ts = Transform::from_scale(scale as f32, scale as f32);
    if let Some(f) = batch.fill.at(i).filter(|f| f.a > 0) {
        pixmap.fill_path(&path, &paint(f), FillRule::Winding, ts, clip.mask.as_ref());
    }
    if let Some(s) = visible_stroke(&batch.stroke) {
        let stroke = super::png::skia_stroke(s, std::f64::consts::TAU * r);
        pixmap.stroke_path(&path, &paint(s.color), &stroke, ts, clip.mask.as_ref());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Item, PerPoint, Point, Rect, Role, Scene, Shape, Stroke, Style};

    /// Draws the batch's points one by one with tiny-skia circles (the reference).
    fn reference(batch: &PointBatch, w: u32, h: u32, scale: f64) -> Pixmap {
        let Some(mut p) = Pixmap::new(w, h) else { panic!("pixmap") };
        p.fill(tiny_skia::Color::WHITE);
        for i in 0..batch.centers.len() {
            generic_point(&mut p, batch, i, scale, &Clip { rect: Rect::new(0.0, 0.0, 1e9, 1e9), mask: None });
        }
        p
    }

    fn fast(batch: &PointBatch, w: u32, h: u32, scale: f64) -> Pixmap {
        let Some(mut p) = Pixmap::new(w, h) else { panic!("pixmap") };
        p.fill(tiny_skia::Color::WHITE);
        let clip = Clip { rect: Rect::new(0.0, 0.0, f64::from(w) / scale, f64::from(h) / scale), mask: None };
        draw_batch(&mut p, batch, scale, &clip);
        p
    }

    /// Largest and mean per-channel difference.
    fn diff(a: &Pixmap, b: &Pixmap) -> (u8, f64) {
        let d = a.data().iter().zip(b.data()).map(|(x, y)| x.abs_diff(*y));
        let max = d.clone().max().unwrap_or(0);
        let sum: f64 = d.map(f64::from).sum();
        (max, sum / a.data().len().max(1) as f64)
    }

    /// Deterministic pseudo-random numbers in 0..1.
    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn blend_math() {
        assert_eq!(mul_lanes(0xFFFF_FFFF, 255), 0xFFFF_FFFF);
        assert_eq!(mul_lanes(0xFFFF_FFFF, 0), 0);
        assert_eq!(mul_lanes(0x80FF_4020, 128), 0x4080_2010);
        for x in 0..=255u32 {
            assert_eq!(mul_lanes(x * 0x0101_0101, 255), x * 0x0101_0101);
            assert_eq!(mul_lanes(x * 0x0101_0101, 0), 0);
        }
        // Half-covered opaque red over white.
        let red = mul_lanes(premultiplied(Color::rgb(255, 0, 0)), 128);
        assert_eq!(over(0xFFFF_FFFF, red).to_le_bytes(), [255, 127, 127, 255]);
    }

    #[test]
    fn stamps_match_tiny_skia_circles() {
        let mut seed = 7;
        for (radius, stroke, scale) in [
            (3.0, None, 1.0),
            (1.5, None, 1.0),
            (0.7, None, 1.0),
            (6.25, None, 1.0),
            (4.0, Some(Stroke::solid(Color::rgb(0, 0, 0), 1.5)), 1.0),
            (3.0, Some(Stroke::solid(Color::rgb(0, 90, 0).with_opacity(0.7), 0.5)), 1.0),
            (2.0, None, 2.0),
        ] {
            let centers: Vec<Point> =
                (0..40).map(|_| Point::new(5.0 + 90.0 * lcg(&mut seed), 5.0 + 70.0 * lcg(&mut seed))).collect();
            let n = centers.len();
            let colors = (0..n)
                .map(|k| Color::rgb((k * 50 % 256) as u8, 40, 200).with_opacity(if k % 3 == 0 { 0.5 } else { 1.0 }));
            let batch = PointBatch {
                centers,
                radius: PerPoint::Uniform(radius),
                fill: PerPoint::Each(colors.collect()),
                stroke: stroke.clone(),
            };
            let (w, h) = ((100.0 * scale) as u32, (80.0 * scale) as u32);
            // Centres on the 1/8-pixel stamp grid: the same coverage up to blending rounding and
            // f32 rounding where a circle edge falls exactly on a pixel boundary.
            let grid = PointBatch {
                centers: batch
                    .centers
                    .iter()
                    .map(|p| Point::new((p.x * 8.0).round() / 8.0, (p.y * 8.0).round() / 8.0))
                    .collect(),
                ..batch.clone()
            };
            let (d, _) = diff(&fast(&grid, w, h, scale), &reference(&grid, w, h, scale));
            let hairline = stroke.as_ref().is_some_and(|s| s.width * scale < 1.0);
            assert!(d <= if hairline { 40 } else { 16 }, "grid radius {radius} stroke {stroke:?}: max diff {d}");
            // Anywhere else the centre snaps by up to 1/16 px. tiny-skia's own coverage moves in
            // steps of 1/4 px (its supersampling), so single edge pixels may differ by one such
            // step, but the average stays well under one level.
            let (d, mean) = diff(&fast(&batch, w, h, scale), &reference(&batch, w, h, scale));
            assert!(d <= 72 && mean < 1.0, "radius {radius} stroke {stroke:?} scale {scale}: max {d} mean {mean}");
        }
    }

    #[test]
    fn per_point_radii_clip_and_bad_values() {
        let batch = PointBatch {
            centers: vec![
                Point::new(20.0, 20.0),
                Point::new(f64::NAN, 20.0),
                Point::new(60.0, 40.0),
                Point::new(1e300, 1e300),
                Point::new(50.0, 50.0),
            ],
            radius: PerPoint::Each(vec![2.0, 3.0, 40.0, 3.0, f64::INFINITY]),
            fill: PerPoint::Uniform(Color::rgb(255, 0, 0)),
            stroke: None,
        };
        let s = Scene {
            width: 100.0,
            height: 80.0,
            background: Color::WHITE,
            title: None,
            items: vec![Item::group(
                Role::DataMark,
                vec![Item::new(Role::DataMark, Shape::Points(batch), Style::default())],
                Some(Rect::new(10.0, 10.0, 60.0, 50.0)),
            )],
        };
        let p = match super::super::png::to_pixmap(&s, 1.0) {
            Ok(p) => p,
            Err(e) => panic!("{e}"),
        };
        let red = |x, y| p.pixel(x, y).map(|c| (c.red(), c.green()));
        assert_eq!(red(20, 20), Some((255, 0)));
        // The big (generic-path) point is clipped to the group rectangle.
        assert_eq!(red(65, 40), Some((255, 0)));
        assert_eq!(red(75, 40), Some((255, 255)));
        assert_eq!(red(60, 5), Some((255, 255)));
    }

    #[test]
    fn stamp_points_respect_clip_mask() {
        let batch = PointBatch {
            centers: (0..10).map(|k| Point::new(10.0 * k as f64, 20.0)).collect(),
            radius: PerPoint::Uniform(3.0),
            fill: PerPoint::Uniform(Color::BLACK),
            stroke: Some(Stroke::solid(Color::rgb(255, 0, 0), 1.0)),
        };
        let s = Scene {
            width: 100.0,
            height: 40.0,
            background: Color::WHITE,
            title: None,
            items: vec![Item::group(
                Role::DataMark,
                vec![Item::new(Role::DataMark, Shape::Points(batch), Style::default())],
                Some(Rect::new(30.5, 0.0, 40.0, 40.0)),
            )],
        };
        let p = match super::super::png::to_pixmap(&s, 1.0) {
            Ok(p) => p,
            Err(e) => panic!("{e}"),
        };
        let g = |x| p.pixel(x, 20).map(|c| c.green()).unwrap_or(0);
        assert_eq!(g(29), 255);
        assert!(g(30) > 100 && g(30) < 160, "half-covered clip edge: {}", g(30));
        assert!(g(40) < 255);
        assert_eq!(g(71), 255);
    }

    #[test]
    fn banded_drawing_matches_one_pass() {
        let mut seed = 11;
        let n = 3 * PARALLEL_MIN_POINTS;
        let centers: Vec<Point> =
            (0..n).map(|_| Point::new(-5.0 + 210.0 * lcg(&mut seed), -5.0 + 130.0 * lcg(&mut seed))).collect();
        let fills: Vec<Color> = (0..n).map(|k| Color::rgb((k % 200) as u8, 90, 200).with_opacity(0.5)).collect();
        let radii: Vec<f64> = (0..n).map(|k| 1.0 + (k % 5) as f64 * 0.7).collect();
        let each = PointBatch {
            centers: centers.clone(),
            radius: PerPoint::Each(radii),
            fill: PerPoint::Each(fills),
            stroke: Some(Stroke::solid(Color::BLACK.with_opacity(0.3), 0.8)),
        };
        let uniform = PointBatch {
            centers,
            radius: PerPoint::Uniform(2.3),
            fill: PerPoint::Uniform(Color::rgb(200, 30, 60).with_opacity(0.6)),
            stroke: None,
        };
        let (w, h) = (200u32, 120u32);
        let Some(mut mask) = tiny_skia::Mask::new(w, h) else { panic!("mask") };
        let Some(r) = tiny_skia::Rect::from_xywh(10.5, 7.25, 170.0, 100.0) else { panic!("rect") };
        mask.fill_path(&PathBuilder::from_rect(r), FillRule::Winding, true, Transform::identity());
        for (batch, masked) in [(&each, false), (&each, true), (&uniform, false), (&uniform, true)] {
            let clip = || Clip {
                rect: if masked { Rect::new(10.5, 7.25, 170.0, 100.0) } else { Rect::new(0.0, 0.0, 200.0, 120.0) },
                mask: masked.then(|| mask.clone()),
            };
            let mut results = Vec::new();
            for threads in [1, 3] {
                let Some(mut p) = Pixmap::new(w, h) else { panic!("pixmap") };
                p.fill(tiny_skia::Color::WHITE);
                draw_batch_on(&mut p, batch, 1.0, &clip(), threads);
                results.push(p);
            }
            // The same points drawn one pass at a time, in slices below the banding threshold.
            let Some(mut one) = Pixmap::new(w, h) else { panic!("pixmap") };
            one.fill(tiny_skia::Color::WHITE);
            for k in (0..n).step_by(PARALLEL_MIN_POINTS / 2) {
                let end = (k + PARALLEL_MIN_POINTS / 2).min(n);
                let part = PointBatch {
                    centers: batch.centers.get(k..end).map(|c| c.to_vec()).unwrap_or_default(),
                    radius: PerPoint::Each(batch.radius_slice(k..end)),
                    fill: PerPoint::Each(batch.fill_slice(k..end)),
                    stroke: batch.stroke.clone(),
                };
                draw_batch_on(&mut one, &part, 1.0, &clip(), 1);
            }
            for p in &results {
                assert!(p.data() == one.data(), "masked {masked}: banded output differs");
            }
        }
    }

    trait Slices {
        fn radius_slice(&self, r: std::ops::Range<usize>) -> Vec<f64>;
        fn fill_slice(&self, r: std::ops::Range<usize>) -> Vec<Color>;
    }

    impl Slices for PointBatch {
        fn radius_slice(&self, r: std::ops::Range<usize>) -> Vec<f64> {
            r.filter_map(|i| self.radius.at(i)).collect()
        }
        fn fill_slice(&self, r: std::ops::Range<usize>) -> Vec<Color> {
            r.filter_map(|i| self.fill.at(i)).collect()
        }
    }

    /// Timing of 1,000,000 points into a 1000×1000 canvas; run with
    /// `cargo test --release -- --ignored --nocapture time_million_points`
    /// (`POINTS_THREADS` and `POINTS_RUNS` override the thread count and repetitions).
    #[test]
    #[ignore]
    fn time_million_points() {
        let env = |k: &str, d: usize| std::env::var(k).ok().and_then(|v| v.parse().ok()).unwrap_or(d);
        let threads = env("POINTS_THREADS", std::thread::available_parallelism().map_or(1, |t| t.get()));
        let runs = env("POINTS_RUNS", 10);
        let mut seed = 1;
        let configs =
            [(1.0, None), (1.5, None), (2.0, None), (3.0, None), (2.0, Some(Stroke::solid(Color::BLACK, 0.5)))];
        let only: Option<usize> = std::env::var("POINTS_CONFIG").ok().and_then(|v| v.parse().ok());
        for (k, (radius, stroke)) in configs.into_iter().enumerate() {
            if only.is_some_and(|o| o != k) {
                continue;
            }
            let centers: Vec<Point> =
                (0..1_000_000).map(|_| Point::new(1000.0 * lcg(&mut seed), 1000.0 * lcg(&mut seed))).collect();
            let batch = PointBatch {
                centers,
                radius: PerPoint::Uniform(radius),
                fill: PerPoint::Uniform(Color::rgb(30, 90, 200).with_opacity(0.6)),
                stroke,
            };
            let Some(mut p) = Pixmap::new(1000, 1000) else { panic!("pixmap") };
            let clip = Clip { rect: Rect::new(0.0, 0.0, 1000.0, 1000.0), mask: None };
            let mut best = f64::INFINITY;
            for _ in 0..runs {
                p.fill(tiny_skia::Color::WHITE);
                let t0 = std::time::Instant::now();
                draw_batch_on(&mut p, &batch, 1.0, &clip, threads);
                best = best.min(t0.elapsed().as_secs_f64() * 1e3);
            }
            let stroke = batch.stroke.as_ref().map(|s| s.width);
            println!("1M points radius {radius} stroke {stroke:?}, {threads} threads: {best:.1} ms");
        }
    }
}
