//! Circle segments: the numeric core of Keim's pixel display for many ordered records.
//!
//! A disk of `diameter × diameter` raster pixels is cut into `k` equal wedges ("segments"), one
//! per variable, the first starting at 12 o'clock and the others following clockwise. The
//! records, already sorted by some column, are laid out pixel by pixel from the centre outward,
//! at the same relative positions in every segment, and each pixel takes the colour of its
//! variable's value: a record is one "ring position" read across all the wedges.
//!
//! Fill order inside a segment (Keim's layout): pixels are ranked by their depth, the floor of
//! their distance from the centre measured along the segment's bisector, so that each depth is a
//! short chord perpendicular to the bisector that lengthens outward; within a chord they run
//! back and forth (even depths clockwise, odd depths counter-clockwise), so consecutive records
//! stay adjacent on screen. With a single segment the bisector is undefined and depth is the
//! plain distance from the centre (rings, again traversed back and forth).
//!
//! Pixel `(x, y)` is in the disk when its centre `(x + 0.5, y + 0.5)` lies within `diameter / 2`
//! of the raster centre, and it belongs to the segment containing the angle of that centre, so
//! every disk pixel belongs to exactly one segment. Pixel indices are `y * diameter + x`.
//!
//! [`SegmentLayout::new`] computes the order once; [`paint`] then maps any number of value
//! columns (and selections) to an RGBA raster, averaging records that share a pixel.

use std::f64::consts::{PI, TAU};
use std::fmt;
use std::ops::Range;

use rayon::prelude::*;

/// Largest diameter accepted: pixel indices `y * diameter + x` must fit in a `u32`.
pub const MAX_DIAMETER: u32 = 65_535;

/// Marks a raster pixel outside the disk (in the owner and slot maps).
const OUTSIDE: u32 = u32::MAX;

/// How close (in units of one segment's width) a pixel centre's angle must be to a border for
/// the pixel to count as lying on it.
const BORDER_TOLERANCE: f64 = 1e-9;

/// Pixels painted per parallel task.
const PAINT_CHUNK: usize = 4096;

/// Where each record goes: for every segment, its pixels in record order (centre outward).
#[derive(Clone)]
pub struct SegmentLayout {
    diameter: u32,
    segments: usize,
    /// The pixel lists of all segments, one after the other.
    order: Vec<u32>,
    /// Segment `s` owns `order[offsets[s]..offsets[s + 1]]`.
    offsets: Vec<usize>,
    /// For each raster pixel, its position in `order`, or [`OUTSIDE`].
    slot: Vec<u32>,
}

impl SegmentLayout {
    /// Lay out a disk of `diameter` pixels (square raster `diameter × diameter`) split into
    /// `segments` equal wedges, the first starting at 12 o'clock (angle pointing up) and going
    /// clockwise.
    ///
    /// Pixel `(x, y)` belongs to the disk when its centre `(x + 0.5, y + 0.5)` is within
    /// `diameter / 2` of the raster centre, and to the segment whose angular span contains that
    /// centre (centres exactly on a border alternate between its two sides), so every disk pixel
    /// belongs to exactly one segment. Each segment's pixels are ordered by depth along the
    /// bisector, then back and forth along each chord (see the module documentation).
    ///
    /// # Panics
    ///
    /// If `segments` is 0 or `u32::MAX` or more, or `diameter` exceeds [`MAX_DIAMETER`].
    pub fn new(diameter: u32, segments: usize) -> SegmentLayout {
        let disk = Disk::new(diameter, segments);
        let owners = disk.owners();
        let (mut order, offsets) = group_by_owner(&owners, segments);
        split_mut(&mut order, &offsets)
            .into_par_iter()
            .enumerate()
            .for_each(|(s, pixels)| order_segment(pixels, &disk, &Wedge::new(s, segments)));
        let mut slot = owners;
        slot.fill(OUTSIDE);
        for (position, &p) in order.iter().enumerate() {
            slot[p as usize] = position as u32;
        }
        SegmentLayout { diameter, segments, order, offsets, slot }
    }

    /// Side of the square raster, in pixels; the disk's diameter.
    pub fn diameter(&self) -> u32 {
        self.diameter
    }

    /// Number of segments (wedges), one per variable.
    pub fn segments(&self) -> usize {
        self.segments
    }

    /// Pixel indices (`y * diameter + x`) of segment `s`, in fill order.
    ///
    /// # Panics
    ///
    /// If `s >= self.segments()`.
    pub fn pixels(&self, s: usize) -> &[u32] {
        &self.order[self.offsets[s]..self.offsets[s + 1]]
    }

    /// The smallest number of pixels any segment has (a record count beyond it needs
    /// aggregation: several records then share a pixel).
    pub fn min_pixels(&self) -> usize {
        self.offsets.windows(2).map(|w| w[1] - w[0]).min().unwrap_or(0)
    }

    /// Angle (radians, clockwise from 12 o'clock) of the middle of segment `s` ([`mid_angle`]).
    pub fn mid_angle(&self, s: usize) -> f64 {
        mid_angle(s, self.segments)
    }

    /// Start and end angles (radians, clockwise from 12 o'clock) of segment `s`; the last
    /// segment ends at 2π.
    ///
    /// # Panics
    ///
    /// If `s >= self.segments()`.
    pub fn span(&self, s: usize) -> (f64, f64) {
        assert!(s < self.segments, "segment {s} out of range (the layout has {})", self.segments);
        let width = TAU / self.segments as f64;
        (s as f64 * width, (s + 1) as f64 * width)
    }
}

/// The angle (radians, clockwise from 12 o'clock) through the middle of segment `s` of
/// `segments` equal wedges.
pub fn mid_angle(s: usize, segments: usize) -> f64 {
    (s as f64 + 0.5) * TAU / segments.max(1) as f64
}

impl fmt::Debug for SegmentLayout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SegmentLayout")
            .field("diameter", &self.diameter)
            .field("segments", &self.segments)
            .field("disk_pixels", &self.order.len())
            .field("min_pixels", &self.min_pixels())
            .finish()
    }
}

/// Smallest diameter whose every segment has at least `records` pixels, capped at
/// `max_diameter` (and at [`MAX_DIAMETER`]).
///
/// The result is at least 1 (an empty raster is never proposed) unless `max_diameter` is 0; it
/// is the cap itself when even the cap has too few pixels per segment.
///
/// # Panics
///
/// If `segments` is 0 or `u32::MAX` or more.
pub fn diameter_for(records: usize, segments: usize, max_diameter: u32) -> u32 {
    let cap = max_diameter.min(MAX_DIAMETER);
    if cap == 0 {
        return 0;
    }
    let fits = |d: u32| Disk::new(d, segments).min_count() >= records;
    // Each segment of an ideal disk holds π d² / (4 k) pixels; the lattice adds only a border
    // effect, so a few unit steps from this estimate reach the exact answer.
    let estimate = (4.0 * segments as f64 * records as f64 / PI).sqrt().ceil();
    let mut d = (estimate.min(cap as f64) as u32).max(1);
    if fits(d) {
        while d > 1 && fits(d - 1) {
            d -= 1;
        }
    } else {
        while d < cap && !fits(d) {
            d += 1;
        }
    }
    d
}

/// Paint the raster (straight RGBA, 4 bytes per pixel, row by row, `diameter²` pixels).
///
/// `values[s][i]` is variable `s` of the `i`-th record in order, already scaled to [0, 1]; a
/// non-finite value (NaN) is missing. Pixel `j` of segment `s`, which has `n_s` pixels, shows
/// records `i` in `[j n / n_s, (j + 1) n / n_s)`: the mean of their finite values when several
/// records share a pixel (`n > n_s`), or the single record `floor(j n / n_s)` when records are
/// fewer than pixels, so each record gets a contiguous run of pixels and the segment is always
/// fully filled. `color(t)` maps a mean in [0, 1] to straight RGBA; `missing` is used for pixels
/// whose records are all missing, and for every disk pixel when there are no records; pixels
/// outside the disk are fully transparent.
///
/// `highlight`, when given, is one flag per record (same order). A pixel whose records are all
/// unselected is drawn with `context(c)`, `c` being the colour it would have had without a
/// selection (possibly `missing`); a pixel with any selected record shows the mean of the
/// selected records only (`missing` if they are all missing).
///
/// # Panics
///
/// If `values` does not hold one column per segment, the columns differ in length, or
/// `highlight` is not one flag per record.
pub fn paint(
    layout: &SegmentLayout,
    values: &[&[f64]],
    color: &(dyn Fn(f64) -> [u8; 4] + Sync),
    missing: [u8; 4],
    highlight: Option<&[bool]>,
    context: &(dyn Fn([u8; 4]) -> [u8; 4] + Sync),
) -> Vec<u8> {
    assert_eq!(values.len(), layout.segments, "paint needs one value column per segment");
    let records = values.first().map_or(0, |column| column.len());
    assert!(values.iter().all(|column| column.len() == records), "value columns differ in length");
    if let Some(flags) = highlight {
        assert_eq!(flags.len(), records, "highlight needs one flag per record");
    }
    let palette = Palette { color, missing, context };
    let mut colours = vec![missing; layout.order.len()];
    if records > 0 {
        split_mut(&mut colours, &layout.offsets).into_par_iter().zip(values).for_each(|(part, &column)| {
            let pixels = part.len();
            part.par_chunks_mut(PAINT_CHUNK).enumerate().for_each(|(c, chunk)| {
                let spans = RecordSpans::new(c * PAINT_CHUNK, records, pixels);
                for (out, span) in chunk.iter_mut().zip(spans) {
                    *out = palette.pixel(column, span, highlight);
                }
            });
        });
    }
    let side = layout.diameter as usize;
    let mut raster = vec![0u8; side * side * 4];
    if side > 0 {
        raster.par_chunks_mut(side * 4).zip(layout.slot.par_chunks(side)).for_each(|(row, slots)| {
            for (out, &slot) in row.chunks_exact_mut(4).zip(slots) {
                if slot != OUTSIDE {
                    out.copy_from_slice(&colours[slot as usize]);
                }
            }
        });
    }
    raster
}

/// The raster geometry shared by layout and sizing: which pixel lies in which segment.
struct Disk {
    diameter: u32,
    segments: usize,
    /// Raster centre, on both axes, and the disk's radius.
    centre: f64,
    radius_sq: f64,
}

impl Disk {
    /// Checks the arguments (see [`SegmentLayout::new`]).
    fn new(diameter: u32, segments: usize) -> Disk {
        assert!(segments > 0, "circle segments need at least one segment");
        assert!(segments < OUTSIDE as usize, "too many segments: {segments}");
        assert!(diameter <= MAX_DIAMETER, "diameter {diameter} exceeds {MAX_DIAMETER}");
        let centre = diameter as f64 / 2.0;
        Disk { diameter, segments, centre, radius_sq: centre * centre }
    }

    /// Offset of pixel `p`'s centre from the raster centre, as (rightward, upward).
    fn offset(&self, p: u32) -> (f64, f64) {
        let d = self.diameter;
        self.offset_xy(p % d, p / d)
    }

    /// Offset of pixel `(x, y)`'s centre from the raster centre, as (rightward, upward).
    fn offset_xy(&self, x: u32, y: u32) -> (f64, f64) {
        (x as f64 + 0.5 - self.centre, self.centre - (y as f64 + 0.5))
    }

    /// Segment of pixel `(x, y)`, or [`OUTSIDE`].
    fn owner(&self, x: u32, y: u32) -> u32 {
        let (right, up) = self.offset_xy(x, y);
        if right * right + up * up > self.radius_sq {
            return OUTSIDE;
        }
        let k = self.segments;
        let position = clockwise_angle(right, up) * k as f64 / TAU;
        let border = position.round();
        let s = if (position - border).abs() < BORDER_TOLERANCE {
            // On a border (lattice symmetry puts whole rays of pixels there, e.g. the diagonals):
            // alternate sides along the ray so neither neighbour collects all of them.
            let ring = right.abs().max(up.abs()) as usize;
            border as usize + k - ring % 2
        } else {
            position as usize
        };
        (s % k) as u32
    }

    /// The owner of every raster pixel, row by row.
    fn owners(&self) -> Vec<u32> {
        let side = self.diameter as usize;
        let mut owners = vec![OUTSIDE; side * side];
        if side > 0 {
            owners.par_chunks_mut(side).enumerate().for_each(|(y, row)| {
                for (x, owner) in row.iter_mut().enumerate() {
                    *owner = self.owner(x as u32, y as u32);
                }
            });
        }
        owners
    }

    /// The fewest pixels any segment owns, without building the layout.
    fn min_count(&self) -> usize {
        let k = self.segments;
        let counts = (0..self.diameter)
            .into_par_iter()
            .fold(
                || vec![0usize; k],
                |mut counts, y| {
                    for x in 0..self.diameter {
                        let owner = self.owner(x, y);
                        if owner != OUTSIDE {
                            counts[owner as usize] += 1;
                        }
                    }
                    counts
                },
            )
            .reduce(|| vec![0usize; k], |a, b| a.iter().zip(&b).map(|(x, y)| x + y).collect());
        counts.into_iter().min().unwrap_or(0)
    }
}

/// Angle in [0, 2π] of an offset (rightward, upward), clockwise from 12 o'clock.
fn clockwise_angle(right: f64, up: f64) -> f64 {
    let angle = right.atan2(up);
    if angle < 0.0 { angle + TAU } else { angle }
}

/// How one segment ranks its pixels: depth along the bisector, then the lateral coordinate.
struct Wedge {
    /// Bisector direction as (rightward, upward) = (sin φ, cos φ), φ the mid angle.
    sin: f64,
    cos: f64,
    /// A single segment has no useful bisector: depth is then the distance from the centre.
    radial: bool,
}

impl Wedge {
    /// The ranking of segment `s` out of `segments`.
    fn new(s: usize, segments: usize) -> Wedge {
        let (sin, cos) = ((s as f64 + 0.5) * TAU / segments as f64).sin_cos();
        Wedge { sin, cos, radial: segments == 1 }
    }

    /// Depth index and lateral coordinate (growing clockwise) of a pixel centre offset.
    fn place(&self, (right, up): (f64, f64)) -> (usize, f64) {
        if self.radial {
            (right.hypot(up) as usize, clockwise_angle(right, up))
        } else {
            // Non-negative inside a wedge at most a half-turn wide, up to rounding at the tip.
            let depth = right * self.sin + up * self.cos;
            (depth.max(0.0) as usize, right * self.cos - up * self.sin)
        }
    }
}

/// Pixel indices grouped by owning segment (ascending within each), and each segment's start
/// in that list (`segments + 1` offsets).
fn group_by_owner(owners: &[u32], segments: usize) -> (Vec<u32>, Vec<usize>) {
    let mut offsets = vec![0usize; segments + 1];
    for &owner in owners.iter().filter(|&&o| o != OUTSIDE) {
        offsets[owner as usize + 1] += 1;
    }
    prefix_sum(&mut offsets);
    let mut cursor = offsets.clone();
    let mut order = vec![0u32; offsets[segments]];
    for (p, &owner) in owners.iter().enumerate().filter(|(_, o)| **o != OUTSIDE) {
        order[cursor[owner as usize]] = p as u32;
        cursor[owner as usize] += 1;
    }
    (order, offsets)
}

/// Turns counts into running totals in place.
fn prefix_sum(values: &mut [usize]) {
    for i in 1..values.len() {
        values[i] += values[i - 1];
    }
}

/// Cuts `items` into consecutive mutable parts `items[offsets[i]..offsets[i + 1]]`.
fn split_mut<'a, T>(mut items: &'a mut [T], offsets: &[usize]) -> Vec<&'a mut [T]> {
    offsets
        .windows(2)
        .map(|w| {
            let (part, rest) = std::mem::take(&mut items).split_at_mut(w[1] - w[0]);
            items = rest;
            part
        })
        .collect()
}

/// Sorts one segment's pixels into fill order: by depth (a counting sort, depths being small
/// integers), then along each chord, alternating direction with the depth's parity.
fn order_segment(pixels: &mut [u32], disk: &Disk, wedge: &Wedge) {
    let placed: Vec<(usize, f64)> = pixels.iter().map(|&p| wedge.place(disk.offset(p))).collect();
    let depths = placed.iter().map(|&(depth, _)| depth + 1).max().unwrap_or(0);
    let mut starts = vec![0usize; depths + 1];
    for &(depth, _) in &placed {
        starts[depth + 1] += 1;
    }
    prefix_sum(&mut starts);
    let mut cursor = starts.clone();
    let mut chords = vec![(0.0f64, 0u32); pixels.len()];
    for (&(depth, lateral), &p) in placed.iter().zip(pixels.iter()) {
        let along = if depth % 2 == 0 { lateral } else { -lateral };
        chords[cursor[depth]] = (along, p);
        cursor[depth] += 1;
    }
    for w in starts.windows(2) {
        chords[w[0]..w[1]].sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }
    for (out, &(_, p)) in pixels.iter_mut().zip(&chords) {
        *out = p;
    }
}

/// The record ranges `[j n / m, (j + 1) n / m)` of pixels `j = first, first + 1, …` for `n`
/// records on `m` pixels, computed exactly by integer stepping; an empty range (fewer records
/// than pixels) becomes the single record `floor(j n / m)`.
struct RecordSpans {
    /// `floor(j n / m)` for the next pixel `j`, and the remainder `j n mod m`.
    low: usize,
    remainder: usize,
    step: usize,
    step_remainder: usize,
    pixels: usize,
}

impl RecordSpans {
    fn new(first: usize, records: usize, pixels: usize) -> RecordSpans {
        let start = first as u128 * records as u128;
        let m = pixels.max(1) as u128;
        RecordSpans {
            low: (start / m) as usize,
            remainder: (start % m) as usize,
            step: records / pixels.max(1),
            step_remainder: records % pixels.max(1),
            pixels: pixels.max(1),
        }
    }
}

impl Iterator for RecordSpans {
    type Item = Range<usize>;

    fn next(&mut self) -> Option<Range<usize>> {
        let low = self.low;
        let mut high = low + self.step;
        self.remainder += self.step_remainder;
        if self.remainder >= self.pixels {
            self.remainder -= self.pixels;
            high += 1;
        }
        self.low = high;
        Some(low..high.max(low + 1))
    }
}

/// The colour functions of one [`paint`] call.
struct Palette<'a> {
    color: &'a (dyn Fn(f64) -> [u8; 4] + Sync),
    missing: [u8; 4],
    context: &'a (dyn Fn([u8; 4]) -> [u8; 4] + Sync),
}

impl Palette<'_> {
    /// Colour of a pixel showing `records` of one variable's `column`.
    fn pixel(&self, column: &[f64], records: Range<usize>, highlight: Option<&[bool]>) -> [u8; 4] {
        let values = &column[records.clone()];
        match highlight.map(|flags| &flags[records]) {
            Some(flags) if flags.contains(&true) => {
                let selected = values.iter().zip(flags).filter(|&(_, &on)| on).map(|(&v, _)| v);
                self.of_mean(finite_mean(selected))
            }
            Some(_) => (self.context)(self.of_mean(finite_mean(values.iter().copied()))),
            None => self.of_mean(finite_mean(values.iter().copied())),
        }
    }

    /// `color` of a mean (clamped to [0, 1]), or `missing` when there is none.
    fn of_mean(&self, mean: Option<f64>) -> [u8; 4] {
        mean.map_or(self.missing, |m| (self.color)(m.clamp(0.0, 1.0)))
    }
}

/// Mean of the finite values, if any.
fn finite_mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, count) =
        values.fold((0.0, 0usize), |(sum, count), v| if v.is_finite() { (sum + v, count + 1) } else { (sum, count) });
    (count > 0).then(|| sum / count as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;
    use std::time::Instant;

    /// Grey of a value: dark for 0, light for 1.
    fn gray(t: f64) -> [u8; 4] {
        let v = (t * 255.0).round() as u8;
        [v, v, v, 255]
    }

    /// A context colour recognisably different from anything `gray` makes.
    fn dim(c: [u8; 4]) -> [u8; 4] {
        [c[0] / 2, c[1] / 2, c[2] / 2, 77]
    }

    const MISSING: [u8; 4] = [255, 0, 0, 255];

    /// Independent check of disk membership and distance of pixel `p`'s centre from the centre.
    fn distance(d: u32, p: u32) -> f64 {
        let c = d as f64 / 2.0;
        let (x, y) = ((p % d) as f64 + 0.5, (p / d) as f64 + 0.5);
        ((x - c).powi(2) + (y - c).powi(2)).sqrt()
    }

    fn in_disk(d: u32, p: u32) -> bool {
        distance(d, p) <= d as f64 / 2.0
    }

    fn rgba(raster: &[u8], p: u32) -> [u8; 4] {
        raster[p as usize * 4..p as usize * 4 + 4].try_into().unwrap()
    }

    fn paint_plain(layout: &SegmentLayout, columns: &[Vec<f64>]) -> Vec<u8> {
        let refs: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
        paint(layout, &refs, &gray, MISSING, None, &dim)
    }

    /// The same column for every segment.
    fn replicate(layout: &SegmentLayout, column: Vec<f64>) -> Vec<Vec<f64>> {
        vec![column; layout.segments()]
    }

    /// Deterministic noise in [-1, 1).
    fn noise(i: usize) -> f64 {
        let mut h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
        h ^= h >> 29;
        h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        h ^= h >> 32;
        (h >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    #[test]
    fn every_disk_pixel_belongs_to_exactly_one_segment() {
        for d in [0, 1, 2, 3, 4, 7, 10, 57, 200, 201] {
            for k in [1, 2, 3, 4, 5, 7, 8, 12, 40] {
                let layout = SegmentLayout::new(d, k);
                assert_eq!((layout.diameter(), layout.segments()), (d, k));
                let mut seen = HashSet::new();
                for s in 0..k {
                    for &p in layout.pixels(s) {
                        assert!(p < d * d && in_disk(d, p), "d={d} k={k}: pixel {p} outside the disk");
                        assert!(seen.insert(p), "d={d} k={k}: pixel {p} in two segments");
                    }
                }
                let disk = (0..d * d).filter(|&p| in_disk(d, p)).count();
                assert_eq!(seen.len(), disk, "d={d} k={k}: some disk pixel has no segment");
                let min = (0..k).map(|s| layout.pixels(s).len()).min().unwrap();
                assert_eq!(layout.min_pixels(), min);
            }
        }
    }

    #[test]
    fn segments_have_nearly_equal_sizes() {
        for d in [100, 301, 640] {
            for k in 1..=12 {
                let layout = SegmentLayout::new(d, k);
                let sizes: Vec<usize> = (0..k).map(|s| layout.pixels(s).len()).collect();
                let (min, max) = (*sizes.iter().min().unwrap(), *sizes.iter().max().unwrap());
                assert!(max - min <= max / 50 + 4, "d={d} k={k}: sizes {sizes:?}");
            }
        }
    }

    #[test]
    fn pixels_lie_within_their_segment_span() {
        let (d, k) = (151, 7);
        let layout = SegmentLayout::new(d, k);
        for s in 0..k {
            let (start, end) = layout.span(s);
            assert!((layout.mid_angle(s) - (start + end) / 2.0).abs() < 1e-12);
            for &p in layout.pixels(s) {
                let c = d as f64 / 2.0;
                let (right, up) = ((p % d) as f64 + 0.5 - c, c - ((p / d) as f64 + 0.5));
                let angle = clockwise_angle(right, up);
                let within = |a: f64| a >= start - 1e-9 && a <= end + 1e-9;
                assert!(within(angle) || within(angle + TAU), "segment {s}: angle {angle}");
            }
        }
        assert_eq!(layout.span(0).0, 0.0);
        assert!((layout.span(k - 1).1 - TAU).abs() < 1e-12);
        assert!((layout.mid_angle(0) - TAU / 14.0).abs() < 1e-12);
    }

    #[test]
    fn fill_order_goes_outward() {
        for (d, k) in [(120, 1), (120, 2), (121, 3), (200, 5), (300, 8), (300, 16)] {
            let layout = SegmentLayout::new(d, k);
            for s in 0..k {
                let pixels = layout.pixels(s);
                let tenth = pixels.len() / 10;
                let mean = |ps: &[u32]| ps.iter().map(|&p| distance(d, p)).sum::<f64>() / ps.len() as f64;
                let (inner, outer) = (mean(&pixels[..tenth]), mean(&pixels[pixels.len() - tenth..]));
                assert!(inner < outer, "d={d} k={k} s={s}: first tenth at {inner}, last at {outer}");
                // Two segments are half-disks whose first chord is the whole diameter.
                if k > 2 {
                    assert!(distance(d, pixels[0]) < 3.0, "d={d} k={k} s={s}: fill does not start at the centre");
                }
            }
        }
    }

    #[test]
    fn consecutive_pixels_are_neighbours() {
        for (d, k) in [(120, 1), (120, 2), (121, 3), (200, 5), (300, 8), (301, 12)] {
            let layout = SegmentLayout::new(d, k);
            for s in 0..k {
                let pixels = layout.pixels(s);
                let step = |w: &[u32]| {
                    let (a, b) = (w[0], w[1]);
                    (((a % d) as f64 - (b % d) as f64).powi(2) + ((a / d) as f64 - (b / d) as f64).powi(2)).sqrt()
                };
                let near = pixels.windows(2).filter(|w| step(w) <= 1.5).count();
                let share = near as f64 / (pixels.len() - 1) as f64;
                assert!(share >= 0.95, "d={d} k={k} s={s}: only {share:.3} of steps are adjacent");
            }
        }
    }

    #[test]
    fn first_segment_starts_at_twelve_and_segments_run_clockwise() {
        for d in [40, 41] {
            let layout = SegmentLayout::new(d, 4);
            let owner = |x: u32, y: u32| (0..4).find(|&s| layout.pixels(s).contains(&(y * d + x))).unwrap();
            let (cx, cy) = (d / 2, d / 2);
            assert_eq!(owner(cx, cy - 10), 0, "d={d}: straight above the centre");
            assert_eq!(owner(cx + 10, cy + 1), 1, "d={d}: right of the centre, just below");
            assert_eq!(owner(cx - 1, cy + 10), 2, "d={d}: below the centre, just left");
            assert_eq!(owner(cx - 10, cy - 1), 3, "d={d}: left of the centre, just above");
            let eight = SegmentLayout::new(d, 8);
            assert!(eight.pixels(0).contains(&((cy - 10) * d + cx + 2)), "d={d}: just right of 12 o'clock");
            assert!(eight.pixels(7).contains(&((cy - 10) * d + cx - 2)), "d={d}: just left of 12 o'clock");
        }
    }

    #[test]
    fn diameter_for_is_the_smallest_sufficient_diameter() {
        for (records, k) in [(0, 3), (1, 1), (1, 40), (10, 4), (1000, 6), (12_345, 8), (50_000, 3), (7, 100)] {
            let d = diameter_for(records, k, 2000);
            assert!(SegmentLayout::new(d, k).min_pixels() >= records, "records={records} k={k}: d={d} too small");
            if d > 1 {
                assert!(SegmentLayout::new(d - 1, k).min_pixels() < records, "records={records} k={k}: d={d}");
            }
        }
        assert_eq!(diameter_for(1_000_000_000, 8, 300), 300);
        assert_eq!(diameter_for(10, 8, 0), 0);
        assert_eq!(diameter_for(0, 8, 50), 1);
    }

    #[test]
    fn few_records_fill_every_pixel_in_record_order() {
        let layout = SegmentLayout::new(60, 5);
        let n = layout.min_pixels() / 3;
        // Record i has value i / n, encoded exactly in the colour's red and green bytes.
        let encode = |t: f64| {
            let i = (t * n as f64).round() as u16;
            [(i >> 8) as u8, i as u8, 9, 255]
        };
        let column: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
        let columns = replicate(&layout, column);
        let refs: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
        let raster = paint(&layout, &refs, &encode, MISSING, None, &dim);
        assert_eq!(raster.len(), 60 * 60 * 4);
        for p in 0..60 * 60 {
            let alpha = rgba(&raster, p)[3];
            assert_eq!(alpha, if in_disk(60, p) { 255 } else { 0 }, "pixel {p}");
        }
        for s in 0..5 {
            let pixels = layout.pixels(s);
            let shown: Vec<usize> =
                pixels.iter().map(|&p| rgba(&raster, p)).map(|c| ((c[0] as usize) << 8) | c[1] as usize).collect();
            assert_eq!(shown[0], 0, "segment {s} does not start with record 0");
            for (j, &record) in shown.iter().enumerate() {
                assert_eq!(record, j * n / pixels.len(), "segment {s}, pixel {j}");
            }
            assert!(shown.windows(2).all(|w| w[1] == w[0] || w[1] == w[0] + 1));
            assert_eq!(*shown.last().unwrap(), n - 1);
        }
    }

    #[test]
    fn two_records_make_a_dark_inner_and_light_outer_half() {
        let layout = SegmentLayout::new(81, 6);
        let raster = paint_plain(&layout, &replicate(&layout, vec![0.0, 1.0]));
        for s in 0..6 {
            let pixels = layout.pixels(s);
            let half = pixels.len().div_ceil(2);
            assert!(pixels[..half].iter().all(|&p| rgba(&raster, p) == gray(0.0)), "segment {s} inner half");
            assert!(pixels[half..].iter().all(|&p| rgba(&raster, p) == gray(1.0)), "segment {s} outer half");
            let mean = |ps: &[u32]| ps.iter().map(|&p| distance(81, p)).sum::<f64>() / ps.len() as f64;
            assert!(mean(&pixels[..half]) < mean(&pixels[half..]));
        }
    }

    /// Four segments on an even raster are exact quarter turns of each other: equal sizes.
    fn quarters() -> SegmentLayout {
        let layout = SegmentLayout::new(64, 4);
        assert!((0..4).all(|s| layout.pixels(s).len() == layout.min_pixels()));
        layout
    }

    #[test]
    fn shared_pixels_show_the_mean() {
        let layout = quarters();
        let n = 2 * layout.min_pixels();
        let raster = paint_plain(&layout, &replicate(&layout, (0..n).map(|i| (i % 2) as f64).collect()));
        for s in 0..4 {
            assert!(layout.pixels(s).iter().all(|&p| rgba(&raster, p) == gray(0.5)), "segment {s}");
        }
        // Uneven sharing: three records per pixel, means of thirds.
        let n = 3 * layout.min_pixels();
        let raster = paint_plain(&layout, &replicate(&layout, (0..n).map(|i| (i % 3 == 0) as u8 as f64).collect()));
        assert!(layout.pixels(2).iter().all(|&p| rgba(&raster, p) == gray(1.0 / 3.0)));
    }

    #[test]
    fn missing_values_are_skipped_or_painted_missing() {
        let layout = quarters();
        let m = layout.min_pixels();
        // Pixel j holds records 2j and 2j+1: both missing when j % 3 == 0, one when j % 3 == 1.
        let column: Vec<f64> = (0..2 * m)
            .map(|i| match ((i / 2) % 3, i % 2) {
                (0, _) | (1, 0) => f64::NAN,
                (1, _) => 0.25,
                _ => 0.75,
            })
            .collect();
        let raster = paint_plain(&layout, &replicate(&layout, column));
        for s in 0..4 {
            for (j, &p) in layout.pixels(s).iter().enumerate() {
                let expected = [MISSING, gray(0.25), gray(0.75)][j % 3];
                assert_eq!(rgba(&raster, p), expected, "segment {s}, pixel {j}");
            }
        }
    }

    #[test]
    fn highlight_uses_selected_records_and_greys_the_rest() {
        let layout = quarters();
        let m = layout.min_pixels();
        let column: Vec<f64> = (0..2 * m).map(|i| if i % 2 == 0 { 0.2 } else { 0.8 }).collect();
        // Pixel j: none selected (j % 3 == 0), only its first record (1), both records (2).
        let flags: Vec<bool> = (0..2 * m).map(|i| ((i / 2) % 3 == 1 && i % 2 == 0) || (i / 2) % 3 == 2).collect();
        let columns = replicate(&layout, column);
        let refs: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
        let raster = paint(&layout, &refs, &gray, MISSING, Some(&flags), &dim);
        for s in 0..4 {
            for (j, &p) in layout.pixels(s).iter().enumerate() {
                let expected = [dim(gray(0.5)), gray(0.2), gray(0.5)][j % 3];
                assert_eq!(rgba(&raster, p), expected, "segment {s}, pixel {j}");
            }
        }
        // With fewer records than pixels, unselected records are greyed over their whole run.
        let flags = [true, false];
        let raster = paint(&layout, &[&[0.0, 1.0][..]; 4], &gray, MISSING, Some(&flags), &dim);
        let pixels = layout.pixels(1);
        assert_eq!(rgba(&raster, pixels[0]), gray(0.0));
        assert_eq!(rgba(&raster, *pixels.last().unwrap()), dim(gray(1.0)));
        // Unselected, all-missing pixels get the context of the missing colour.
        let raster = paint(&layout, &[&[f64::NAN][..]; 4], &gray, MISSING, Some(&[false]), &dim);
        assert_eq!(rgba(&raster, pixels[3]), dim(MISSING));
    }

    #[test]
    fn no_records_paint_the_disk_missing() {
        let layout = SegmentLayout::new(20, 3);
        let raster = paint(&layout, &[&[][..]; 3], &gray, MISSING, Some(&[]), &dim);
        for p in 0..400 {
            assert_eq!(rgba(&raster, p), if in_disk(20, p) { MISSING } else { [0; 4] });
        }
    }

    #[test]
    fn degenerate_rasters() {
        let empty = SegmentLayout::new(0, 3);
        assert_eq!(empty.min_pixels(), 0);
        assert!(paint(&empty, &[&[0.5][..]; 3], &gray, MISSING, None, &dim).is_empty());
        // More segments than pixels: empty segments paint nothing, the rest still work.
        let tiny = SegmentLayout::new(2, 8);
        assert_eq!(tiny.min_pixels(), 0);
        let raster = paint(&tiny, &[&[0.0, 1.0][..]; 8], &gray, MISSING, None, &dim);
        assert!(raster.chunks(4).all(|c| c[3] == 255));
        assert!(format!("{tiny:?}").contains("disk_pixels: 4"));
    }

    #[test]
    fn record_spans_are_exact() {
        for (n, m) in [(10, 3), (3, 10), (1_000_003, 997), (7, 7), (1, 5)] {
            let all: Vec<Range<usize>> = RecordSpans::new(0, n, m).take(m).collect();
            for (j, span) in all.iter().enumerate() {
                let (lo, hi) = (j * n / m, (j + 1) * n / m);
                assert_eq!(*span, lo..hi.max(lo + 1), "n={n} m={m} j={j}");
                let resumed = RecordSpans::new(j, n, m).next().unwrap();
                assert_eq!(resumed, *span);
            }
        }
    }

    #[test]
    #[should_panic(expected = "one value column per segment")]
    fn paint_rejects_wrong_column_count() {
        let layout = SegmentLayout::new(10, 3);
        paint(&layout, &[&[0.5][..]; 2], &gray, MISSING, None, &dim);
    }

    #[test]
    #[should_panic(expected = "at least one segment")]
    fn zero_segments_are_rejected() {
        SegmentLayout::new(10, 0);
    }

    /// Times layout and painting at full size: `cargo test --release -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn benchmark() {
        let best = |runs: usize, mut f: Box<dyn FnMut() + '_>| {
            (0..runs)
                .map(|_| {
                    let start = Instant::now();
                    f();
                    start.elapsed().as_secs_f64() * 1e3
                })
                .fold(f64::INFINITY, f64::min)
        };
        let new_ms = best(10, Box::new(|| drop(SegmentLayout::new(1200, 8))));
        let layout = SegmentLayout::new(1200, 8);
        println!("new(1200, 8): best of 10 {new_ms:.1} ms; min_pixels {}", layout.min_pixels());
        let n = 1_000_000;
        let columns: Vec<Vec<f64>> =
            (0..8).map(|v| (0..n).map(|i| (0.5 + 0.5 * noise(i * 8 + v)).clamp(0.0, 1.0)).collect()).collect();
        let refs: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
        let plain = best(10, Box::new(|| drop(paint(&layout, &refs, &gray, MISSING, None, &dim))));
        println!("paint 1M records x 8 on d=1200: best of 10 {plain:.1} ms");
        let flags: Vec<bool> = (0..n).map(|i| i % 7 == 0).collect();
        let lit = best(10, Box::new(|| drop(paint(&layout, &refs, &gray, MISSING, Some(&flags), &dim))));
        println!("paint 1M records x 8 with highlight: best of 10 {lit:.1} ms");
        let sizing = best(
            5,
            Box::new(|| {
                std::hint::black_box(diameter_for(n, 8, 4000));
            }),
        );
        println!("diameter_for(1M, 8) = {}: best of 5 {sizing:.1} ms", diameter_for(n, 8, 4000));
    }

    /// A viridis-like ramp through five hand-picked stops.
    fn viridis(t: f64) -> [u8; 4] {
        const STOPS: [[f64; 3]; 5] =
            [[68.0, 1.0, 84.0], [59.0, 82.0, 139.0], [33.0, 145.0, 140.0], [94.0, 201.0, 98.0], [253.0, 231.0, 37.0]];
        let x = t.clamp(0.0, 1.0) * 4.0;
        let i = (x as usize).min(3);
        let f = x - i as f64;
        let channel = |c: usize| (STOPS[i][c] + (STOPS[i + 1][c] - STOPS[i][c]) * f).round() as u8;
        [channel(0), channel(1), channel(2), 255]
    }

    /// Writes `target/circle_segments.pam` (6 variables, 200k records, a missing band in the
    /// last one) and `target/circle_segments_rank.pam` (a 48-pixel disk coloured by record rank)
    /// for a visual check: `convert target/circle_segments.pam out.png`.
    #[test]
    #[ignore]
    fn visual_check() {
        let n = 200_000;
        let k = 6;
        let frequencies = [1.0, 2.0, 3.0, 5.0, 8.0, 13.0];
        let columns: Vec<Vec<f64>> = (0..k)
            .map(|v| {
                (0..n)
                    .map(|i| {
                        let t = i as f64 / n as f64;
                        if v == k - 1 && (0.6..0.65).contains(&t) {
                            return f64::NAN;
                        }
                        (0.5 + 0.4 * (TAU * frequencies[v] * t).sin() + 0.08 * noise(i * k + v)).clamp(0.0, 1.0)
                    })
                    .collect()
            })
            .collect();
        let d = diameter_for(n, k, 2000);
        let layout = SegmentLayout::new(d, k);
        let refs: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
        let raster = paint(&layout, &refs, &viridis, [255, 0, 255, 255], None, &dim);
        write_pam("circle_segments.pam", d, &raster);
        println!("diameter {d}, min_pixels {}", layout.min_pixels());
        // The fill order itself: a small disk whose pixels show their record's rank.
        let small = SegmentLayout::new(48, k);
        let n = small.min_pixels();
        let rank: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let raster = paint(&small, &[rank.as_slice(); 6], &viridis, [255, 0, 255, 255], None, &dim);
        write_pam("circle_segments_rank.pam", 48, &raster);
    }

    /// Writes an RGBA raster as a PAM file under `target/`.
    fn write_pam(name: &str, side: u32, raster: &[u8]) {
        let header = format!("P7\nWIDTH {side}\nHEIGHT {side}\nDEPTH 4\nMAXVAL 255\nTUPLTYPE RGB_ALPHA\nENDHDR\n");
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target").join(name);
        std::fs::write(&path, [header.as_bytes(), raster].concat()).unwrap();
        println!("wrote {}", path.display());
    }
}
