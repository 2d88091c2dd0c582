//! Fast rasterization of line batches: tens of thousands of thin, semi-transparent polylines
//! (parallel coordinates, daisy charts).
//!
//! Stroking every polyline as its own tiny-skia path costs a path, a stroker run and a scan
//! conversion per row. Instead each segment is drawn straight into the pixmap's premultiplied
//! RGBA buffer. Stepping along the segment's major axis one device pixel column (or row) at a
//! time, the stroke's extent across the minor axis at that column's centre — the width
//! measured perpendicular to the segment, times √(1 + slope²) — is blended into the pixels it
//! overlaps, with fractional coverage (in 1/256 pixel) at both ends of the span. So a segment
//! of length L and width w deposits L·w of coverage, as an exact area rasterizer would. The
//! centre line is stepped in exact fixed-point arithmetic, so nothing drifts along a segment.
//!
//! Polyline ends are butt caps cut across the major axis, with fractional coverage in the
//! first and last column. Where two segments of a polyline meet, the columns are split
//! half-open at the shared vertex (a column belongs to the segment whose major-axis range
//! holds its centre), so segments stepping along the same axis join without a seam and the
//! vertex is not blended twice. Where the polyline turns, the two strokes still overlap near
//! the vertex (more so where a shallow segment meets a steep one, or in a V). There each
//! segment keeps the coverage it leaves in a small box around its end vertex, and the next
//! segment, after a disc of the stroke's width (the round join the SVG output asks for),
//! composites only what it adds: every pixel of the joint ends up blended once, at the larger
//! coverage, as when a whole polyline is stroked as one path. Crossings between segments that
//! do not share a vertex are blended twice. Strokes thinner than one device pixel are drawn one
//! pixel wide with proportionally less alpha, as tiny-skia draws hairlines.
//!
//! Every segment is first clipped (Liang–Barsky, in canvas units so that huge coordinates stay
//! finite) to the visible area plus a margin, so off-canvas geometry costs nothing. Large
//! batches are drawn in horizontal bands in parallel: each band walks all segments in batch
//! order and writes only its own rows, so overlapping polylines stack exactly as when drawn
//! one by one, and the result does not depend on the number of bands. A batch in one colour
//! blends through a precomputed table of coverage-scaled colours.

use tiny_skia::Pixmap;

use crate::scene::{LineBatch, PerPoint, Point};

use super::finite_point;
use super::png::Clip;
use super::points::{Target, coverage_table, in_parallel, mul_lanes, over, premultiplied};

/// Bits of fraction of the fixed-point minor coordinates (see [`Seg`]).
const FIX_BITS: u32 = 24;
/// Fixed-point steps per device pixel.
const FIX: f64 = (1u64 << FIX_BITS) as f64;

/// Batches with fewer segments than this are drawn in one band on the calling thread.
const PARALLEL_MIN_SEGMENTS: usize = 4_096;
/// Bands per thread (more bands than threads balance uneven ink across the canvas).
const BANDS_PER_THREAD: usize = 4;
/// Fewest device rows per band.
const MIN_BAND_ROWS: usize = 8;

/// One segment clipped to the visible area, in device pixels, ready to draw; compact, since
/// every band reads all of them.
///
/// The major axis is x for shallow segments and y for steep ones (`steep`). Minor coordinates
/// are fixed point, [`FIX`] steps per pixel: the centre line crosses the centre of major-axis
/// pixel `i` at `base + i · step`, exactly, so it can be stepped incrementally and every band
/// sees the same values.
#[derive(Clone, Copy, Debug)]
struct Seg {
    /// Minor coordinate of the centre line at the centre of major-axis pixel 0.
    base: i64,
    /// Its change from one major-axis pixel to the next.
    step: i64,
    /// Half the stroke's extent along the minor axis at a fixed major coordinate.
    half: i64,
    /// Half-open range of major-axis pixels to step over.
    first: i32,
    last: i32,
    /// Half-open range of device rows the segment may touch.
    row0: i32,
    row1: i32,
    /// Premultiplied colour (used by batches with a colour per polyline).
    color: u32,
    /// Coverage share, in 1/256, of the first and last major-axis pixels (256 at a joint, less
    /// at a cap that covers the pixel only in part).
    w_first: u16,
    w_last: u16,
    /// Whether y is the major axis.
    steep: bool,
    /// Whether the segment continues the previous one of its polyline (it starts at a joint),
    /// and whether the next one continues it (it ends at a joint).
    join_start: bool,
    join_end: bool,
    /// Index of the polyline, and the corners of the joint boxes (see [`JointBox`]) around the
    /// segment's start and end vertices, in device pixels.
    line: u32,
    start_box: [i32; 2],
    end_box: [i32; 2],
    /// The start vertex in device pixels (the centre of its round join).
    start: [f32; 2],
}

impl Seg {
    /// Coverage share, in 1/256, of major-axis pixel `i`.
    #[inline(always)]
    fn weight(&self, i: i64) -> u32 {
        if i == i64::from(self.first) {
            u32::from(self.w_first)
        } else if i + 1 == i64::from(self.last) {
            u32::from(self.w_last)
        } else {
            256
        }
    }

    /// The top (left) and bottom (right) of the stroke's span where the centre line is at
    /// `mid`, in 1/256 pixel (rounded down), clamped to the pixel range `min..max`.
    #[inline(always)]
    fn span(&self, mid: i64, min: i64, max: i64) -> (i64, i64) {
        let shift = FIX_BITS - 8;
        (((mid - self.half) >> shift).max(min << 8), ((mid + self.half) >> shift).min(max << 8))
    }
}

/// What the segments are clipped to and how they are measured.
struct View {
    /// Device pixels per canvas unit.
    scale: f64,
    /// Half the device stroke width.
    half_width: f64,
    /// Half the side of a joint box, in device pixels.
    joint_reach: i64,
    /// Clip area in canvas units (the visible device rectangle plus a margin that the stroke
    /// cannot cross): x min, y min, x max, y max.
    area: [f64; 4],
}

/// Draws every polyline of `batch` (canvas units, `scale` device pixels per unit) inside
/// `clip`, in batch order.
///
/// Segments touching a non-finite vertex are skipped; a stride below 2 or a non-finite or
/// non-positive width draws nothing.
pub(crate) fn draw_batch(pixmap: &mut Pixmap, batch: &LineBatch, scale: f64, clip: &Clip) {
    let threads = rayon::current_num_threads().min(8);
    draw_batch_on(pixmap, batch, scale, clip, threads);
}

/// [`draw_batch`] using at most `threads` threads.
fn draw_batch_on(pixmap: &mut Pixmap, batch: &LineBatch, scale: f64, clip: &Clip, threads: usize) {
    let (pw, ph) = (i64::from(pixmap.width()), i64::from(pixmap.height()));
    let width = pixmap.width() as usize;
    let Some((x0, y0, x1, y1)) = clip.device_bounds(pixmap, scale) else { return };
    let device_width = batch.width * scale;
    // Written so that NaN fails too.
    if batch.is_empty() || !(device_width > 0.0 && device_width.is_finite()) {
        return;
    }
    // Hairlines: one pixel wide at proportionally less alpha. Wider than the canvas diagonal
    // twice over looks the same as any wider stroke, so the width is capped there to keep
    // the arithmetic small.
    let (device_width, fade) =
        if device_width < 1.0 { (1.0, device_width) } else { (device_width.min(2.0 * (pw + ph) as f64 + 4.0), 1.0) };
    let table = match &batch.color {
        PerPoint::Uniform(c) => {
            let c = c.with_opacity(fade);
            if c.a == 0 {
                return;
            }
            Some(coverage_table(premultiplied(c)))
        }
        PerPoint::Each(_) => None,
    };
    let mask = clip.device_mask(scale);

    let half_width = device_width / 2.0;
    // At a fixed major coordinate the stroke reaches at most half_width·√2 from its centre
    // line, and cap columns are sampled up to half a pixel past the ends.
    let margin = half_width * std::f64::consts::SQRT_2 + 2.0;
    let view = View {
        scale,
        half_width,
        joint_reach: joint_reach(device_width),
        area: [
            (x0 as f64 - margin) / scale,
            (y0 as f64 - margin) / scale,
            (x1 as f64 + margin) / scale,
            (y1 as f64 + margin) / scale,
        ],
    };
    // Segments are measured by up to `threads` threads, each taking a run of polylines.
    let n = batch.len();
    let parallel = threads > 1 && n.saturating_mul(batch.stride - 1) >= PARALLEL_MIN_SEGMENTS;
    let per_part = if parallel { n.div_ceil(threads) } else { n };
    let mut parts: Vec<Vec<Seg>> = (0..n.div_ceil(per_part)).map(|_| Vec::new()).collect();
    let jobs: Vec<_> = parts.iter_mut().enumerate().map(|(k, out)| (k * per_part, out)).collect();
    in_parallel(threads, jobs, |(start, out)| {
        segments(batch, start..(start + per_part).min(n), &view, table.is_none(), fade, out);
    });
    let count: usize = parts.iter().map(Vec::len).sum();
    if count == 0 {
        return;
    }

    let rows = (y1 - y0) as usize;
    let band_rows = if threads <= 1 || count < PARALLEL_MIN_SEGMENTS {
        rows
    } else {
        rows.div_ceil(threads * BANDS_PER_THREAD).max(MIN_BAND_ROWS)
    };
    let row_bytes = width * 4;
    let Some(visible) = pixmap.data_mut().get_mut(y0 as usize * row_bytes..y1 as usize * row_bytes) else { return };
    let bands: Vec<(i64, &mut [u8])> =
        visible.chunks_mut(band_rows * row_bytes).enumerate().map(|(b, d)| (y0 + (b * band_rows) as i64, d)).collect();
    let (parts, view) = (&parts, &view);
    let table = table.as_deref();
    in_parallel(threads, bands, |(row0, data)| {
        let (px, _) = data.as_chunks_mut::<4>();
        let row1 = row0 + (px.len() / width) as i64;
        let t = Target { width, row0, x0, y0: row0, x1, y1: row1, mask };
        let in_band = |s: &&Seg| i64::from(s.row1) > row0 && i64::from(s.row0) < row1;
        let mut joints = Joints::new(view.joint_reach, view.half_width);
        match table {
            Some(table) => {
                let alpha = table[255] >> 24;
                for seg in parts.iter().flatten().filter(in_band) {
                    draw_segment(seg, px, &t, |c| table[c as usize], alpha, &mut joints);
                }
            }
            None => {
                for seg in parts.iter().flatten().filter(in_band) {
                    draw_segment(seg, px, &t, |c| mul_lanes(seg.color, c), seg.color >> 24, &mut joints);
                }
            }
        }
    });
}

/// Appends the visible segments of polylines `range` of `batch` to `out`, clipped, in drawing
/// order. With `each_color`, every segment carries its polyline's premultiplied colour (faded
/// by `fade` for hairlines), and polylines without a visible colour are left out.
fn segments(
    batch: &LineBatch,
    range: std::ops::Range<usize>,
    view: &View,
    each_color: bool,
    fade: f64,
    out: &mut Vec<Seg>,
) {
    for k in range {
        let Some(line) = batch.polyline(k) else { break };
        let color = if each_color {
            match batch.color.at(k).map(|c| c.with_opacity(fade)) {
                Some(c) if c.a > 0 => premultiplied(c),
                _ => continue,
            }
        } else {
            0
        };
        let finite = |i: usize| line.get(i).is_some_and(|p| finite_point(*p));
        for (s, pair) in line.windows(2).enumerate() {
            let (p, q) = (pair[0], pair[1]);
            if !(finite_point(p) && finite_point(q)) {
                continue;
            }
            // An end with no drawn neighbour is a cap; otherwise a joint.
            let cap_p = s == 0 || !finite(s - 1);
            let cap_q = !finite(s + 2);
            if let Some(seg) = segment(p, q, cap_p, cap_q, view, color, k as u32) {
                out.push(seg);
            }
        }
    }
}

/// Parameter range `[t0, t1]` of the part of segment `p`→`q` inside `area` (x min, y min,
/// x max, y max), by Liang–Barsky, or `None` if it misses. Everything is halved first (exactly)
/// so that differences of huge finite coordinates cannot overflow.
fn clip_segment(p: Point, q: Point, area: &[f64; 4]) -> Option<(f64, f64)> {
    let (px, py) = (p.x * 0.5, p.y * 0.5);
    let (dx, dy) = (q.x * 0.5 - px, q.y * 0.5 - py);
    let [xmin, ymin, xmax, ymax] = area.map(|v| v * 0.5);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    // Inside where den · t ≤ num for all four edges.
    for (den, num) in [(-dx, px - xmin), (dx, xmax - px), (-dy, py - ymin), (dy, ymax - py)] {
        if den == 0.0 {
            if num < 0.0 {
                return None;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then_some((t0, t1))
}

/// Segment `p`→`q` (canvas units) clipped and measured for drawing, or `None` if nothing of it
/// is visible. `cap_p` and `cap_q` say whether its ends are polyline ends.
fn segment(p: Point, q: Point, cap_p: bool, cap_q: bool, view: &View, color: u32, line: u32) -> Option<Seg> {
    let (t0, t1) = clip_segment(p, q, &view.area)?;
    let s = view.scale;
    // Points inside the area are bounded, so scaling them cannot overflow; clipped ends lie on
    // the margin, where nothing visible is drawn, so they are joints like any other.
    let at = |t: f64| {
        let (hx, hy) = (p.x * 0.5, p.y * 0.5);
        ((hx + t * (q.x * 0.5 - hx)) * 2.0 * s, (hy + t * (q.y * 0.5 - hy)) * 2.0 * s)
    };
    let (ax, ay, cap_a) = if t0 > 0.0 {
        let (x, y) = at(t0);
        (x, y, false)
    } else {
        (p.x * s, p.y * s, cap_p)
    };
    let (bx, by, cap_b) = if t1 < 1.0 {
        let (x, y) = at(t1);
        (x, y, false)
    } else {
        (q.x * s, q.y * s, cap_q)
    };
    let (dx, dy) = (bx - ax, by - ay);
    if !(dx.is_finite() && dy.is_finite()) || (dx == 0.0 && dy == 0.0) {
        return None;
    }
    // Unclipped ends that are not caps meet the neighbouring segment there.
    let (join_start, join_end) = (!cap_p && t0 <= 0.0, !cap_q && t1 >= 1.0);
    let corner = |x: f64, y: f64| [x, y].map(|v| (v.floor() as i64 - view.joint_reach) as i32);
    let steep = dy.abs() > dx.abs();
    let (ua, va, ub, vb) = if steep { (ay, ax, by, bx) } else { (ax, ay, bx, by) };
    let (lo, v_lo, cap_lo, hi, v_hi, cap_hi) =
        if ua <= ub { (ua, va, cap_a, ub, vb, cap_b) } else { (ub, vb, cap_b, ua, va, cap_a) };
    // |hi − lo| ≥ |v_hi − v_lo| and not both zero, so the slope is finite and within ±1.
    let slope = (v_hi - v_lo) / (hi - lo);
    let half = view.half_width * (1.0 + slope * slope).sqrt();
    // Caps take every pixel they overlap (weighted); joints the pixels whose centre they hold.
    let first = if cap_lo { lo.floor() } else { (lo - 0.5).ceil() };
    let last = if cap_hi { hi.ceil() } else { (hi - 0.5).ceil() };
    if first >= last {
        return None;
    }
    // The share of major-axis pixel `f` inside the segment, counting only its caps.
    let weight = |f: f64| {
        let a = if cap_lo { lo.max(f) } else { f };
        let b = if cap_hi { hi.min(f + 1.0) } else { f + 1.0 };
        ((b - a).clamp(0.0, 1.0) * 256.0).round() as u16
    };
    let (mut row0, mut row1) = if steep {
        (first, last)
    } else {
        ((v_lo.min(v_hi) - half - 1.0).floor(), (v_lo.max(v_hi) + half + 1.0).ceil())
    };
    if join_start {
        // The round join drawn with the segment.
        let r = view.half_width + 2.0;
        row0 = row0.min((ay - r).floor());
        row1 = row1.max((ay + r).ceil());
    }
    // Everything here lies within the clip area, whose size the canvas cap bounds, so the
    // conversions are exact.
    Some(Seg {
        base: ((v_lo + slope * (0.5 - lo)) * FIX).round() as i64,
        step: (slope * FIX).round() as i64,
        half: (half * FIX).round() as i64,
        first: first as i32,
        last: last as i32,
        row0: row0 as i32,
        row1: row1 as i32,
        color,
        w_first: weight(first),
        w_last: weight(last - 1.0),
        steep,
        join_start,
        join_end,
        line,
        start_box: corner(ax, ay),
        end_box: corner(bx, by),
        start: [ax as f32, ay as f32],
    })
}

/// Half the side of the joint boxes for strokes `device_width` pixels wide: where two
/// segments meeting at an angle of about 30° or more overlap, with pixels to spare (the inner
/// edges of two strokes `w` wide meeting at angle θ cross `w / 2 / sin(θ / 2)` from the vertex).
/// Sharper joints, and very wide strokes (the box is capped), may still be blended twice in
/// part.
fn joint_reach(device_width: f64) -> i64 {
    (2.0 * device_width).ceil().min(MAX_JOINT_REACH as f64) as i64 + 2
}

/// Largest [`joint_reach`] before its padding.
const MAX_JOINT_REACH: i64 = 30;

/// The coverage one polyline left in a square of pixels around one of its joints (within one
/// band), so that the segment on the other side composites only what it adds: each pixel ends
/// up covered by the larger of the two coverages, as if the polyline were one shape, instead
/// of being blended twice.
struct JointBox {
    /// Polyline and top-left pixel of the box.
    line: u32,
    corner: [i64; 2],
    /// Stamp of the cells written for this box (older stamps are stale).
    stamp: u32,
    /// Side length and cells (stamp, coverage 0..=255), row-major.
    side: i64,
    cells: Vec<(u32, u8)>,
}

impl JointBox {
    fn new(side: i64) -> JointBox {
        JointBox { line: u32::MAX, corner: [0, 0], stamp: 0, side, cells: vec![(0, 0); (side * side) as usize] }
    }

    /// Whether major-axis pixel `m` lies in the box's range along that axis.
    #[inline(always)]
    fn spans(&self, steep: bool, m: i64) -> bool {
        m.wrapping_sub(self.corner[usize::from(steep)]) as u64 <= (self.side - 1) as u64
    }

    /// The cell of pixel (`x`, `y`), if it lies in the box.
    #[inline(always)]
    fn cell(&mut self, x: i64, y: i64) -> Option<&mut (u32, u8)> {
        let (dx, dy) = (x.wrapping_sub(self.corner[0]), y.wrapping_sub(self.corner[1]));
        if (dx as u64) < self.side as u64 && (dy as u64) < self.side as u64 {
            self.cells.get_mut((dy * self.side + dx) as usize)
        } else {
            None
        }
    }
}

/// The joint boxes of one band: the one behind the segment being drawn (left by the previous
/// segment of its polyline, read) and the one ahead of it (written for the next segment).
struct Joints {
    behind: JointBox,
    ahead: JointBox,
    /// Whether each box applies to the segment being drawn.
    behind_on: bool,
    ahead_on: bool,
    stamp: u32,
    /// Radius of the round joins: half the device stroke width.
    radius: f64,
}

impl Joints {
    fn new(reach: i64, radius: f64) -> Joints {
        let side = 2 * reach + 1;
        let (behind, ahead) = (JointBox::new(side), JointBox::new(side));
        Joints { behind, ahead, behind_on: false, ahead_on: false, stamp: 0, radius }
    }

    /// Sets the boxes up for `seg`. Without the previous segment's box (it left no pixel in this
    /// band), the box behind starts empty, for the round join.
    fn begin(&mut self, seg: &Seg) {
        let start = seg.start_box.map(i64::from);
        self.behind_on = seg.join_start;
        if seg.join_start && (self.behind.line != seg.line || self.behind.corner != start) {
            self.stamp = self.stamp.wrapping_add(1);
            self.behind.stamp = self.stamp;
            self.behind.line = seg.line;
            self.behind.corner = start;
        }
        self.ahead_on = seg.join_end;
        if seg.join_end {
            self.stamp = self.stamp.wrapping_add(1);
            self.ahead.stamp = self.stamp;
            self.ahead.line = seg.line;
            self.ahead.corner = seg.end_box.map(i64::from);
        }
    }

    /// After `seg`: its end box is the next segment's box behind.
    fn end(&mut self) {
        if self.ahead_on {
            std::mem::swap(&mut self.behind, &mut self.ahead);
        } else {
            self.behind.line = u32::MAX;
        }
    }

    /// Whether major-axis pixel `m` of a segment crosses either box (then its pixels go
    /// through [`Joints::add`]).
    #[inline(always)]
    fn crossed(&self, steep: bool, m: i64) -> bool {
        (self.behind_on && self.behind.spans(steep, m)) || (self.ahead_on && self.ahead.spans(steep, m))
    }

    /// The coverage to blend at pixel (`x`, `y`) for a segment covering it by `c` (0..=255)
    /// in a colour of alpha `alpha`: all of it, or only what it adds to the coverage the
    /// previous segment left there. Records the pixel's coverage for the next segment.
    fn add(&mut self, x: i64, y: i64, c: u32, alpha: u32) -> u32 {
        let (mut add, mut total) = (c, c);
        if self.behind_on
            && let Some(&mut (stamp, before)) = self.behind.cell(x, y)
            && stamp == self.behind.stamp
        {
            let before = u32::from(before);
            total = c.max(before);
            add = increment(before, c, alpha);
        }
        if self.ahead_on {
            let stamp = self.ahead.stamp;
            if let Some(cell) = self.ahead.cell(x, y) {
                *cell = (stamp, total.min(255) as u8);
            }
        }
        add
    }
}

/// Draws the round join at the start of `seg` (a disc of the stroke's width around the vertex
/// it shares with the previous segment), compositing only what the disc adds to the coverage
/// the previous segment left, and recording the result for `seg`: together the two segments
/// and the disc cover each pixel once, with the rounded outer corner that SVG's
/// `stroke-linejoin="round"` draws.
fn round_join(
    px: &mut [[u8; 4]],
    t: &Target<'_>,
    seg: &Seg,
    src: &impl Fn(u32) -> u32,
    alpha: u32,
    joints: &mut Joints,
) {
    let [vx, vy] = seg.start.map(f64::from);
    let r = joints.radius;
    let range =
        |v: f64, lo: i64, hi: i64| (((v - r - 1.0).floor() as i64).max(lo), ((v + r + 1.0).ceil() as i64).min(hi));
    let ((x0, x1), (y0, y1)) = (range(vx, t.x0, t.x1), range(vy, t.y0, t.y1));
    let outer = (r + 0.5) * (r + 0.5);
    for y in y0..y1 {
        let dy = y as f64 + 0.5 - vy;
        for x in x0..x1 {
            let dx = x as f64 + 0.5 - vx;
            let d2 = dx * dx + dy * dy;
            if d2 >= outer {
                continue;
            }
            // Coverage of a pixel by a disc, to within a few per cent: its centre's depth inside.
            let depth = r + 0.5 - d2.sqrt();
            let cov = (depth.min(1.0) * 65_536.0) as u32;
            let c = coverage(cov, t.mask, y as usize * t.width + x as usize);
            let stamp = joints.behind.stamp;
            let Some(cell) = joints.behind.cell(x, y) else { continue };
            let before = if cell.0 == stamp { u32::from(cell.1) } else { 0 };
            *cell = (stamp, c.max(before).min(255) as u8);
            blend(px, (y - t.row0) as usize * t.width + x as usize, src(increment(before, c, alpha)));
        }
    }
}

/// The coverage (0..=255) that, blended over a pixel already blended at coverage `before` with a
/// colour of alpha `alpha`, leaves it as if it had been blended once at `max(before, after)`:
/// 0 if `after` ≤ `before`, else `(after − before) / (1 − alpha · before)` (all as fractions).
#[inline]
fn increment(before: u32, after: u32, alpha: u32) -> u32 {
    if after <= before {
        return 0;
    }
    let rest = 65_025 - alpha * before;
    if rest == 0 {
        return 0;
    }
    (((after - before) * 65_025 + rest / 2) / rest).min(255)
}

/// Draws one segment into a band, blending `src(coverage)` (a premultiplied colour of alpha
/// `alpha` scaled by a coverage in 0..=255) over each pixel it touches; pixels near its joints
/// go through `joints`.
#[inline(always)]
fn draw_segment(
    seg: &Seg,
    px: &mut [[u8; 4]],
    t: &Target<'_>,
    src: impl Fn(u32) -> u32,
    alpha: u32,
    joints: &mut Joints,
) {
    joints.begin(seg);
    if joints.behind_on {
        round_join(px, t, seg, &src, alpha, joints);
    }
    if seg.steep {
        // One device row at a time; the span runs along the row.
        let (j0, j1) = (i64::from(seg.first).max(t.y0), i64::from(seg.last).min(t.y1));
        let mut mid = seg.base + j0 * seg.step;
        for j in j0..j1 {
            let (a, b) = seg.span(mid, t.x0, t.x1);
            mid += seg.step;
            if a >= b {
                continue;
            }
            let w = seg.weight(j);
            let row = (j - t.row0) as usize * t.width;
            let mask_row = j as usize * t.width;
            let (k0, k1) = (a >> 8, (b + 255) >> 8);
            let slow = joints.crossed(true, j);
            for k in k0..k1 {
                let cov = (b.min((k + 1) << 8) - a.max(k << 8)) as u32;
                let mut c = coverage(cov * w, t.mask, mask_row + k as usize);
                if slow {
                    c = joints.add(k, j, c, alpha);
                }
                blend(px, row + k as usize, src(c));
            }
        }
        joints.end();
        return;
    }
    // One device column at a time, limited to the columns whose span can reach the band.
    let (mut i0, mut i1) = (i64::from(seg.first).max(t.x0), i64::from(seg.last).min(t.x1));
    if seg.step != 0 {
        // Where the centre line is within half the span plus a pixel of the band's rows.
        let reach = seg.half + (1 << FIX_BITS);
        let ia = ((t.y0 << FIX_BITS) - reach - seg.base) / seg.step;
        let ib = ((t.y1 << FIX_BITS) + reach - seg.base) / seg.step;
        i0 = i0.max(ia.min(ib) - 1);
        i1 = i1.min(ia.max(ib) + 2);
    }
    let mut mid = seg.base + i0 * seg.step;
    for i in i0..i1 {
        let (a, b) = seg.span(mid, t.y0, t.y1);
        mid += seg.step;
        if a >= b {
            continue;
        }
        let w = seg.weight(i);
        let (k0, k1) = (a >> 8, (b + 255) >> 8);
        let mut at = (k0 - t.row0) as usize * t.width + i as usize;
        let mut mask_at = k0 as usize * t.width + i as usize;
        let slow = joints.crossed(false, i);
        for k in k0..k1 {
            let cov = (b.min((k + 1) << 8) - a.max(k << 8)) as u32;
            let mut c = coverage(cov * w, t.mask, mask_at);
            if slow {
                c = joints.add(i, k, c, alpha);
            }
            blend(px, at, src(c));
            at += t.width;
            mask_at += t.width;
        }
    }
    joints.end();
}

/// A coverage in 1/65536 (a span overlap times a cap weight, both in 1/256) as 0..=255, scaled
/// by the clip mask at `mask_at` if there is one.
#[inline(always)]
fn coverage(cov: u32, mask: Option<&[u8]>, mask_at: usize) -> u32 {
    let c = (cov * 255 + 32_768) >> 16;
    match mask {
        Some(mask) => (c * mask.get(mask_at).copied().map_or(0, u32::from) + 255) >> 8,
        None => c,
    }
}

/// Blends the coverage-scaled premultiplied colour `s` over pixel `at` of the band (coverage
/// 0 leaves it exactly as it was).
#[inline(always)]
fn blend(px: &mut [[u8; 4]], at: usize, s: u32) {
    if let Some(d) = px.get_mut(at) {
        *d = over(u32::from_le_bytes(*d), s).to_le_bytes();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Color, Item, Rect, Role, Scene, Shape, Style};
    use tiny_skia::{FillRule, Mask, PathBuilder, Transform};

    /// Deterministic pseudo-random numbers in 0..1.
    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    fn pixmap(w: u32, h: u32, fill: tiny_skia::Color) -> Pixmap {
        let Some(mut p) = Pixmap::new(w, h) else { panic!("pixmap {w}×{h}") };
        p.fill(fill);
        p
    }

    fn whole(p: &Pixmap, scale: f64) -> Clip {
        Clip { rect: Rect::new(0.0, 0.0, f64::from(p.width()) / scale, f64::from(p.height()) / scale), mask: None }
    }

    fn batch(points: Vec<Point>, stride: usize, color: Color, width: f64) -> LineBatch {
        LineBatch { points, stride, color: PerPoint::Uniform(color), width }
    }

    fn px(p: &Pixmap, x: u32, y: u32) -> [u8; 4] {
        match p.pixel(x, y) {
            Some(c) => [c.red(), c.green(), c.blue(), c.alpha()],
            None => panic!("pixel {x},{y} outside"),
        }
    }

    /// Sum of alpha over the pixmap, in fully covered pixels.
    fn ink(p: &Pixmap) -> f64 {
        p.data().chunks_exact(4).map(|c| f64::from(c[3])).sum::<f64>() / 255.0
    }

    /// Largest and mean per-channel difference.
    fn diff(a: &Pixmap, b: &Pixmap) -> (u8, f64) {
        let d = a.data().iter().zip(b.data()).map(|(x, y)| x.abs_diff(*y));
        let max = d.clone().max().unwrap_or(0);
        let sum: f64 = d.map(f64::from).sum();
        (max, sum / a.data().len().max(1) as f64)
    }

    #[test]
    fn coverage_is_length_times_width() {
        let length = 80.0;
        for (angle, scale) in [(0.0, 1.0), (90.0, 1.0), (30.0, 1.0), (30.0, 2.0), (-63.0, 1.0), (180.0, 1.5)] {
            for width in [0.5, 1.0, 2.0, 3.0] {
                // Centred near the middle of a 150 × 150 canvas, off the pixel grid.
                let a = f64::to_radians(angle);
                let (dx, dy) = (length / 2.0 * a.cos(), length / 2.0 * a.sin());
                let start = Point::new(75.3 - dx, 74.6 - dy);
                let end = Point::new(75.3 + dx, 74.6 + dy);
                let mut p = pixmap((150.0 * scale) as u32, (150.0 * scale) as u32, tiny_skia::Color::TRANSPARENT);
                let clip = whole(&p, scale);
                draw_batch_on(&mut p, &batch(vec![start, end], 2, Color::BLACK, width), scale, &clip, 1);
                let expected = length * width * scale * scale;
                let got = ink(&p);
                // Exact up to rounding coverage to 8 bits (and, for the 0.5 hairline, its alpha).
                assert!(
                    (got - expected).abs() <= 0.01 * expected,
                    "angle {angle} width {width} scale {scale}: ink {got}, expected {expected}"
                );
            }
        }
    }

    /// Strokes the polylines one by one with tiny-skia (the reference), breaking them at
    /// non-finite vertices.
    fn reference(b: &LineBatch, w: u32, h: u32, join: tiny_skia::LineJoin) -> Pixmap {
        let mut p = pixmap(w, h, tiny_skia::Color::WHITE);
        for k in 0..b.len() {
            let (Some(line), Some(c)) = (b.polyline(k), b.color.at(k)) else { continue };
            let mut pb = PathBuilder::new();
            let mut open = false;
            for v in line {
                if !finite_point(*v) {
                    open = false;
                } else if open {
                    pb.line_to(v.x as f32, v.y as f32);
                } else {
                    pb.move_to(v.x as f32, v.y as f32);
                    open = true;
                }
            }
            let Some(path) = pb.finish() else { continue };
            let stroke = tiny_skia::Stroke {
                width: super::super::png::stroke_width(b.width),
                line_join: join,
                ..tiny_skia::Stroke::default()
            };
            p.stroke_path(&path, &super::super::png::paint(c), &stroke, Transform::identity(), None);
        }
        p
    }

    #[test]
    fn matches_tiny_skia_strokes() {
        let (w, h) = (240u32, 160u32);
        let mut seed = 5;
        let vertices = 7;
        let lines = 8;
        let points: Vec<Point> = (0..lines * vertices)
            .map(|k| {
                // Parallel-coordinates-like: x increases along each polyline, y anywhere.
                let x = 10.0 + (k % vertices) as f64 * 36.0 + 6.0 * lcg(&mut seed);
                Point::new(x, 5.0 + 150.0 * lcg(&mut seed))
            })
            .collect();
        let colors = (0..lines).map(|k| Color::rgb((k * 30) as u8, 60, 200 - (k * 20) as u8).with_opacity(0.5));
        let b = LineBatch { points, stride: vertices, color: PerPoint::Each(colors.collect()), width: 1.5 };
        let mut fast = pixmap(w, h, tiny_skia::Color::WHITE);
        let clip = whole(&fast, 1.0);
        draw_batch_on(&mut fast, &b, 1.0, &clip, 1);
        let ink_pixels = fast.data().chunks_exact(4).filter(|c| c != &[255, 255, 255, 255]).count();
        assert!(ink_pixels > 4_000, "{ink_pixels}");
        for join in [tiny_skia::LineJoin::Round, tiny_skia::LineJoin::Miter] {
            let slow = reference(&b, w, h, join);
            let (max, mean) = diff(&fast, &slow);
            assert!(mean < 2.0, "{join:?}: mean difference {mean} (max {max})");
            // Along the segments the two differ only by anti-aliasing: tiny-skia samples
            // coverage in quarter-pixel steps (4× supersampling), so an edge pixel may differ by
            // one such step of a 0.5-alpha stroke, 0.25 · 0.5 · 255 ≈ 32.
            //
            // Near vertices the shapes differ a little. Caps are cut across the major axis, not
            // square to the segment, which moves up to a third of a pixel's area at a cap corner
            // (for a 1.5 px stroke at 45°), and round joins are discs of approximate coverage:
            // within 3/8 of a layer, 48. Against tiny-skia's default mitred joins, the miter
            // tips are missing: up to a whole layer, 0.5 · 255 ≈ 128.
            let (mut near_max, mut far_max) = (0, 0);
            for (k, (a, c)) in fast.data().chunks_exact(4).zip(slow.data().chunks_exact(4)).enumerate() {
                let d = a.iter().zip(c).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
                let centre = Point::new((k % w as usize) as f64 + 0.5, (k / w as usize) as f64 + 0.5);
                let near = b.points.iter().any(|v| (v.x - centre.x).hypot(v.y - centre.y) <= 2.0 * b.width);
                if near {
                    near_max = near_max.max(d);
                } else {
                    far_max = far_max.max(d);
                }
            }
            assert!(far_max <= 32, "{join:?}: away from vertices, max difference {far_max}");
            let near_bound = if join == tiny_skia::LineJoin::Round { 48 } else { 130 };
            assert!(near_max <= near_bound, "{join:?}: near vertices, max difference {near_max}");
        }
    }

    #[test]
    fn later_polylines_are_drawn_over_earlier_ones() {
        let (red, blue) = (Color::rgb(255, 0, 0), Color::rgb(0, 0, 255));
        let cross = vec![
            Point::new(10.0, 30.5),
            Point::new(90.0, 30.5),
            Point::new(50.5, 5.0),
            Point::new(50.5, 55.0),
            Point::new(10.0, 10.0),
            Point::new(90.0, 50.0),
        ];
        for (colors, top) in [(vec![blue, red, red], red), (vec![red, blue, blue], blue)] {
            for alpha in [1.0, 0.6] {
                let colors = colors.iter().map(|c| c.with_opacity(alpha)).collect();
                let b = LineBatch { points: cross.clone(), stride: 2, color: PerPoint::Each(colors), width: 3.0 };
                let mut p = pixmap(100, 60, tiny_skia::Color::WHITE);
                let clip = whole(&p, 1.0);
                draw_batch_on(&mut p, &b, 1.0, &clip, 1);
                // Pixel (50, 30) is fully covered by all three lines; the last one's colour wins.
                let c = px(&p, 50, 30);
                if alpha == 1.0 {
                    assert_eq!(c, [top.r, top.g, top.b, 255]);
                } else {
                    let (r, b) = (i32::from(c[0]), i32::from(c[2]));
                    assert!(if top == red { r > b } else { b > r }, "{c:?}");
                }
            }
        }
    }

    #[test]
    fn collinear_segments_join_without_a_seam() {
        let color = Color::rgb(0, 0, 0).with_opacity(0.5);
        let draw = |points: Vec<Point>, stride| {
            let mut p = pixmap(120, 80, tiny_skia::Color::WHITE);
            let clip = whole(&p, 1.0);
            draw_batch_on(&mut p, &batch(points, stride, color, 2.0), 1.0, &clip, 1);
            p
        };
        let pt = Point::new;
        // Collinear horizontal, sloped and steep polylines against single segments.
        for (a, m, b) in [
            (pt(10.3, 20.5), pt(50.7, 20.5), pt(90.2, 20.5)),
            (pt(10.0, 10.0), pt(52.0, 31.0), pt(100.0, 55.0)),
            (pt(100.0, 75.0), pt(70.0, 15.0), pt(65.0, 5.0)),
        ] {
            let (max, _) = diff(&draw(vec![a, m, b], 3), &draw(vec![a, b], 2));
            assert!(max <= 1, "{a:?} {m:?} {b:?}: {max}");
        }
    }

    #[test]
    fn polylines_are_not_blended_twice_at_their_joints() {
        let pt = Point::new;
        let shapes = [
            // V shapes (steep down then up, 36° apart), a shallow-to-steep turn, a right angle,
            // a zigzag of shallow and steep segments, and a hairpin-free spiral.
            vec![pt(10.3, 10.2), pt(36.3, 90.4), pt(62.1, 12.7), pt(88.0, 88.8)],
            vec![pt(10.5, 60.0), pt(70.2, 40.3), pt(75.7, 5.1)],
            vec![pt(10.0, 10.5), pt(70.5, 10.5), pt(70.5, 80.0)],
            vec![pt(5.0, 50.0), pt(25.0, 20.0), pt(45.0, 70.0), pt(90.0, 60.0), pt(70.0, 10.0), pt(50.0, 30.0)],
            vec![pt(50.5, 50.5), pt(80.5, 50.5), pt(80.5, 80.5), pt(20.5, 80.5), pt(20.5, 20.5), pt(90.5, 20.5)],
        ];
        for width in [1.0, 2.5, 6.0] {
            for scale in [1.0, 1.5] {
                for shape in &shapes {
                    let b = batch(shape.clone(), shape.len(), Color::BLACK.with_opacity(0.5), width);
                    let mut p = pixmap((100.0 * scale) as u32, (100.0 * scale) as u32, tiny_skia::Color::TRANSPARENT);
                    let clip = whole(&p, scale);
                    draw_batch_on(&mut p, &b, scale, &clip, 1);
                    // One layer of a 0.5-alpha stroke is alpha 128; a pixel blended twice would
                    // reach up to 192.
                    let max = p.data().chunks_exact(4).map(|c| c[3]).max().unwrap_or(0);
                    assert!((128..=130).contains(&max), "width {width} scale {scale} {shape:?}: max alpha {max}");
                    // And the joints are not left thin either: the ink is that of the shape.
                    let length: f64 = shape.windows(2).map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y)).sum();
                    let ink = ink(&p) / (128.0 / 255.0) / (scale * scale);
                    let expected = length * width;
                    assert!(
                        (ink - expected).abs() < 0.05 * expected,
                        "width {width} {shape:?}: ink {ink} of {expected}"
                    );
                }
            }
        }
    }

    #[test]
    fn nothing_is_written_outside_the_clip() {
        let mut seed = 9;
        let points: Vec<Point> =
            (0..600).map(|_| Point::new(-20.0 + 140.0 * lcg(&mut seed), -20.0 + 120.0 * lcg(&mut seed))).collect();
        for clip_rect in [Rect::new(20.5, 10.25, 50.0, 40.0), Rect::new(20.0, 10.0, 50.0, 40.0)] {
            for width in [0.4, 1.0, 4.0] {
                let b = batch(points.clone(), 3, Color::BLACK.with_opacity(0.7), width);
                let s = Scene {
                    width: 100.0,
                    height: 80.0,
                    background: Color::WHITE,
                    title: None,
                    items: vec![Item::group(
                        Role::DataMark,
                        vec![Item::new(Role::DataMark, Shape::Lines(b), Style::default())],
                        Some(clip_rect),
                    )],
                };
                let p = match super::super::png::to_pixmap(&s, 2.0) {
                    Ok(p) => p,
                    Err(e) => panic!("{e}"),
                };
                let (x0, y0) = ((clip_rect.x * 2.0).floor() as u32, (clip_rect.y * 2.0).floor() as u32);
                let (x1, y1) = ((clip_rect.right() * 2.0).ceil() as u32, (clip_rect.bottom() * 2.0).ceil() as u32);
                let mut inside = 0;
                for y in 0..p.height() {
                    for x in 0..p.width() {
                        let c = px(&p, x, y);
                        if x >= x0 && x < x1 && y >= y0 && y < y1 {
                            inside += usize::from(c != [255; 4]);
                        } else {
                            assert_eq!(c, [255; 4], "{clip_rect:?} width {width}: pixel {x},{y} outside the clip");
                        }
                    }
                }
                assert!(inside > 500, "{inside}");
            }
        }
    }

    #[test]
    fn bad_values_skip_only_their_segments() {
        let nan = f64::NAN;
        let pt = Point::new;
        // NaN breaks the polyline: segments 0–1 and 3–4 are drawn, the two touching vertex 2 not.
        let b = batch(
            vec![pt(10.0, 10.5), pt(40.0, 10.5), pt(nan, 10.5), pt(60.0, 10.5), pt(90.0, 10.5)],
            5,
            Color::BLACK,
            1.0,
        );
        let mut p = pixmap(100, 20, tiny_skia::Color::WHITE);
        let clip = whole(&p, 1.0);
        draw_batch_on(&mut p, &b, 1.0, &clip, 1);
        assert_eq!(px(&p, 25, 10), [0, 0, 0, 255]);
        assert_eq!(px(&p, 50, 10), [255; 4]);
        assert_eq!(px(&p, 75, 10), [0, 0, 0, 255]);
        // Huge coordinates are clipped, not walked: these lines cross the canvas.
        let b = batch(vec![pt(-1e12, 15.5), pt(1e12, 15.5), pt(50.5, -1e12), pt(50.5, 1e12)], 2, Color::BLACK, 1.0);
        let mut p = pixmap(100, 20, tiny_skia::Color::WHITE);
        draw_batch_on(&mut p, &b, 1.0, &clip, 1);
        assert_eq!(px(&p, 20, 15), [0, 0, 0, 255]);
        assert_eq!(px(&p, 50, 5), [0, 0, 0, 255]);
        assert_eq!(px(&p, 20, 10), [255; 4]);
        // Nothing to draw, and no panic or hang.
        let inf = f64::INFINITY;
        let three = vec![pt(1.0, 1.0), pt(50.0, 10.0), pt(99.0, 1.0)];
        let empty = pixmap(100, 20, tiny_skia::Color::WHITE);
        for b in [
            batch(three.clone(), 0, Color::BLACK, 1.0),
            batch(three.clone(), 1, Color::BLACK, 1.0),
            batch(three.clone(), 4, Color::BLACK, 1.0),
            batch(vec![], 2, Color::BLACK, 1.0),
            batch(three.clone(), 3, Color::BLACK, 0.0),
            batch(three.clone(), 3, Color::BLACK, -2.0),
            batch(three.clone(), 3, Color::BLACK, nan),
            batch(three.clone(), 3, Color::BLACK, inf),
            batch(three.clone(), 3, Color::TRANSPARENT, 1.0),
            batch(vec![pt(nan, 1.0), pt(5.0, inf), pt(5.0, 5.0), pt(5.0, 5.0)], 2, Color::BLACK, 1.0),
            LineBatch { points: three.clone(), stride: 3, color: PerPoint::Each(vec![]), width: 1.0 },
        ] {
            for scale in [1.0, 0.01, 3.7] {
                let mut p = pixmap(100, 20, tiny_skia::Color::WHITE);
                let clip = whole(&p, 1.0);
                draw_batch_on(&mut p, &b, scale, &clip, 2);
                assert!(p.data() == empty.data(), "{b:?} at scale {scale} drew something");
            }
        }
        // Absurd widths and coordinates still finish and draw within the canvas.
        for b in [
            batch(three.clone(), 3, Color::BLACK, 1e30),
            batch(
                vec![pt(-1e300, -1e300), pt(1e300, 1e300), pt(f64::MAX, 3.0), pt(-f64::MAX, 3.0)],
                2,
                Color::BLACK,
                1e300,
            ),
            batch(
                vec![pt(-f64::MAX, -f64::MAX), pt(f64::MAX, f64::MAX), pt(f64::MAX, 3.0), pt(-f64::MAX, 3.0)],
                2,
                Color::BLACK,
                1.0,
            ),
            batch(
                vec![pt(5e-324, 0.0), pt(0.0, 5e-324), pt(1e-300, 10.0), pt(1e-300, 10.0 + 1e-14)],
                2,
                Color::BLACK,
                1e-300,
            ),
        ] {
            for scale in [1.0, 1e-300, 1e300] {
                let mut p = pixmap(100, 20, tiny_skia::Color::WHITE);
                let clip = whole(&p, 1.0);
                draw_batch_on(&mut p, &b, scale, &clip, 2);
            }
        }
    }

    #[test]
    fn banded_drawing_matches_one_band() {
        let mut seed = 13;
        let (w, h) = (300u32, 200u32);
        let stride = 6;
        let n = 2 * PARALLEL_MIN_SEGMENTS / (stride - 1);
        let points: Vec<Point> = (0..n * stride)
            .map(|k| {
                Point::new(-10.0 + (k % stride) as f64 * 64.0 + 5.0 * lcg(&mut seed), -10.0 + 220.0 * lcg(&mut seed))
            })
            .collect();
        let colors: Vec<Color> = (0..n).map(|k| Color::rgb((k % 256) as u8, 90, 200).with_opacity(0.3)).collect();
        let each = LineBatch { points: points.clone(), stride, color: PerPoint::Each(colors), width: 1.3 };
        let uniform = batch(points, stride, Color::rgb(200, 30, 60).with_opacity(0.2), 0.7);
        let Some(mut mask) = Mask::new(w, h) else { panic!("mask") };
        let Some(r) = tiny_skia::Rect::from_xywh(10.5, 7.25, 270.0, 180.0) else { panic!("rect") };
        mask.fill_path(&PathBuilder::from_rect(r), FillRule::Winding, true, Transform::identity());
        for b in [&each, &uniform] {
            for masked in [false, true] {
                let clip = || Clip {
                    rect: if masked { Rect::new(10.5, 7.25, 270.0, 180.0) } else { Rect::new(0.0, 0.0, 300.0, 200.0) },
                    mask: masked.then(|| mask.clone()),
                };
                let mut results = Vec::new();
                for threads in [1, 2, 3, 8] {
                    let mut p = pixmap(w, h, tiny_skia::Color::WHITE);
                    draw_batch_on(&mut p, b, 1.0, &clip(), threads);
                    results.push(p);
                }
                for p in &results[1..] {
                    assert!(p.data() == results[0].data(), "masked {masked}: banded output differs");
                }
            }
        }
    }

    #[test]
    fn hairlines_fade_and_polyline_helpers() {
        let pt = Point::new;
        let b = batch(vec![pt(0.0, 0.0), pt(1.0, 1.0), pt(2.0, 2.0), pt(3.0, 3.0), pt(4.0, 4.0)], 2, Color::BLACK, 1.0);
        assert_eq!(b.len(), 2);
        assert_eq!(b.polyline(1), Some(&[pt(2.0, 2.0), pt(3.0, 3.0)][..]));
        assert_eq!(b.polyline(2), None);
        let item = Item::new(Role::DataMark, Shape::Lines(b), Style::default()).translated(1.0, -1.0);
        let Shape::Lines(moved) = item.shape else { panic!("still a line batch") };
        assert_eq!(moved.points.first(), Some(&pt(1.0, -1.0)));
        // A 0.25 px line is drawn one pixel wide at a quarter of the alpha.
        let thin = batch(vec![pt(10.0, 10.5), pt(90.0, 10.5)], 2, Color::BLACK, 0.25);
        let mut p = pixmap(100, 20, tiny_skia::Color::TRANSPARENT);
        let clip = whole(&p, 1.0);
        draw_batch_on(&mut p, &thin, 1.0, &clip, 1);
        assert_eq!(px(&p, 50, 10)[3], 64);
        assert_eq!(px(&p, 50, 9)[3], 0);
    }

    /// Timing of 20,000 polylines × 8 vertices on an 800×440 canvas; run with
    /// `cargo test --release --lib -- --ignored --nocapture time_parallel_coordinates`.
    #[test]
    #[ignore]
    fn time_parallel_coordinates() {
        let mut seed = 3;
        let points: Vec<Point> = (0..20_000 * 8)
            .map(|k| Point::new(40.0 + (k % 8) as f64 * 720.0 / 7.0, 20.0 + 400.0 * lcg(&mut seed)))
            .collect();
        let b = batch(points, 8, Color::rgb(30, 90, 200).with_opacity(0.2), 1.0);
        let threads = rayon::current_num_threads().min(8);
        for threads in [1, threads] {
            let mut best = f64::INFINITY;
            for _ in 0..10 {
                let mut p = pixmap(800, 440, tiny_skia::Color::WHITE);
                let clip = whole(&p, 1.0);
                let t0 = std::time::Instant::now();
                draw_batch_on(&mut p, &b, 1.0, &clip, threads);
                best = best.min(t0.elapsed().as_secs_f64() * 1e3);
            }
            println!("20,000 × 8 polylines, {threads} threads: {best:.1} ms");
        }
    }
}
