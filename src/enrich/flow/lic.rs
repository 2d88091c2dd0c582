//! Line integral convolution of white noise along a [`VectorField`]: the basic per-pixel method
//! of Cabral & Leedom (1993) and the fast method of Stalling & Hege (1995), both with a box kernel.
//!
//! The output raster of `width × height` pixels covers the field's domain; pixel `(c, r)` is
//! centred at `x = x0 + (c + ½)(x1 − x0) / width`, `y = y0 + (r + ½)(y1 − y0) / height` (row 0
//! at the smallest y: flip rows for a top-down image). The flow's unit direction in pixel space is
//! first sampled at every pixel centre (one field evaluation per pixel) and interpolated
//! bilinearly between centres. Streamlines are traced in pixel space with the midpoint rule (RK2)
//! in steps of `step` pixels; tracing stops at the raster edge, next to holes and where the
//! direction vanishes, which truncates the kernel there. Noise is a seeded white-noise texture of
//! the raster's size, sampled at the pixel under each streamline point.
//!
//! - [`LicMethod::PerPixel`] (Cabral & Leedom): for every pixel, average the noise over `n =
//!   length / step` points forward and backward along the streamline through its centre.
//! - [`LicMethod::Fast`] (Stalling & Hege): from each pixel not yet hit, trace one long
//!   streamline (up to `4n + 16` points each way), slide the box window of `2n + 1` points along
//!   it with prefix sums, and add each window's mean to the pixel under the window's centre;
//!   a pixel's value is the mean of its hits. Far fewer field lookups per pixel.
//!
//! The result is contrast-stretched: mean ± 2.5 standard deviations (over all defined pixels)
//! maps linearly onto `[0, 1]`, clamped. Pixels outside the domain or in holes are NaN.
//! Parallelism (rayon) is over fixed bands of rows: the per-pixel method computes each pixel from
//! its own inputs, and the fast method traces each band's lines independently (depositing only
//! into that band), so the output is bit-identical for a given seed whatever the thread count.

use std::fmt;

use rayon::prelude::*;

use super::field::VectorField;

/// Largest number of output pixels (2²⁶ ≈ 67 million).
pub const MAX_PIXELS: usize = 1 << 26;

/// Largest number of kernel steps per direction.
pub const MAX_KERNEL_STEPS: usize = 4096;

/// Why [`lic`] refused its options.
#[derive(Debug, Clone, PartialEq)]
pub enum LicError {
    /// The raster has no pixels, or too many.
    RasterSize {
        /// Requested width.
        width: usize,
        /// Requested height.
        height: usize,
    },
    /// The kernel half-length is not a positive finite number of pixels.
    KernelLength {
        /// The offending value.
        length: f64,
    },
    /// The step is not a positive finite number of pixels, or gives too many steps per kernel.
    Step {
        /// The offending value.
        step: f64,
        /// The kernel half-length it was used with.
        length: f64,
    },
}

impl fmt::Display for LicError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LicError::RasterSize { width, height } => write!(
                f,
                "a {width} x {height} LIC raster is unusable; give a width and height of at least 1 with at most \
                 {MAX_PIXELS} pixels in all"
            ),
            LicError::KernelLength { length } => {
                write!(f, "LIC kernel length {length} is not a positive number of pixels; try 10 to 30")
            }
            LicError::Step { step, length } => write!(
                f,
                "LIC step {step} is unusable with kernel length {length}: give a positive step with at most \
                 {MAX_KERNEL_STEPS} steps per kernel half (length / step); try 0.5 to 1 pixel"
            ),
        }
    }
}

impl std::error::Error for LicError {}

/// Which LIC algorithm to run; see the module docs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LicMethod {
    /// Stalling & Hege (1995): long streamlines reused by many pixels.
    Fast,
    /// Cabral & Leedom (1993): one short streamline per pixel.
    PerPixel,
}

/// Parameters of [`lic`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LicOptions {
    /// Algorithm.
    pub method: LicMethod,
    /// Output width in pixels.
    pub width: usize,
    /// Output height in pixels.
    pub height: usize,
    /// Kernel half-length in pixels (the box kernel spans `2 × length`).
    pub length: f64,
    /// Integration step in pixels.
    pub step: f64,
    /// Seed of the white-noise texture.
    pub seed: u64,
}

impl LicOptions {
    /// A `width × height` raster, fast method, kernel half-length 10 pixels, 1-pixel steps, seed 0.
    pub fn new(width: usize, height: usize) -> LicOptions {
        LicOptions { method: LicMethod::Fast, width, height, length: 10.0, step: 1.0, seed: 0 }
    }
}

/// A LIC raster: `data[r * width + c]`, row 0 at the smallest y; NaN where undefined.
#[derive(Debug, Clone, PartialEq)]
pub struct LicImage {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Intensities in `[0, 1]`, or NaN outside the domain and in holes.
    pub data: Vec<f32>,
}

/// The flow's unit direction in pixel space, sampled at pixel centres (NaN where the field is
/// undefined, `[0, 0]` where it vanishes), interpolated bilinearly between them.
struct Directions {
    width: usize,
    height: usize,
    data: Vec<[f32; 2]>,
}

impl Directions {
    /// Samples `field` at every pixel centre of a `width × height` raster over its domain.
    fn sample(field: &VectorField, width: usize, height: usize) -> Directions {
        let [x0, x1, y0, y1] = field.bounds();
        let (sx, sy) = ((x1 - x0) / width as f64, (y1 - y0) / height as f64);
        let mut data = vec![[f32::NAN; 2]; width * height];
        data.par_chunks_mut(width).enumerate().for_each(|(r, row)| {
            let y = y0 + (r as f64 + 0.5) * sy;
            for (c, out) in row.iter_mut().enumerate() {
                if let Some([u, v]) = field.velocity(x0 + (c as f64 + 0.5) * sx, y) {
                    let (a, b) = (u / sx, v / sy);
                    let n = a.hypot(b);
                    *out = if n > 0.0 && n.is_finite() { [(a / n) as f32, (b / n) as f32] } else { [0.0; 2] };
                }
            }
        });
        Directions { width, height, data }
    }

    /// Whether pixel `k`'s centre is inside the domain and not in a hole.
    #[inline]
    fn defined(&self, k: usize) -> bool {
        self.data.get(k).is_some_and(|d| !d[0].is_nan())
    }

    /// Index of the pixel under pixel-space position `p`, if inside the raster.
    #[inline]
    fn pixel(&self, p: [f64; 2]) -> Option<usize> {
        if !(p[0] >= 0.0 && p[1] >= 0.0) {
            return None;
        }
        let (c, r) = (p[0] as usize, p[1] as usize);
        (c < self.width && r < self.height).then(|| r * self.width + c)
    }

    /// Lattice index and fraction along one raster axis of `n` pixel centres.
    #[inline]
    fn axis(p: f64, n: usize) -> (usize, usize, f64) {
        let g = (p - 0.5).clamp(0.0, (n - 1) as f64);
        let i = (g as usize).min(n.saturating_sub(2));
        (i, (i + 1).min(n - 1), g - i as f64)
    }

    /// Unit direction at pixel-space position `p`; `None` outside the raster, next to a hole, or
    /// where the interpolated direction vanishes.
    #[inline]
    fn at(&self, p: [f64; 2]) -> Option<[f64; 2]> {
        if !(p[0] >= 0.0 && p[1] >= 0.0 && p[0] <= self.width as f64 && p[1] <= self.height as f64) {
            return None;
        }
        let (i0, i1, fx) = Directions::axis(p[0], self.width);
        let (j0, j1, fy) = Directions::axis(p[1], self.height);
        let get = |i: usize, j: usize| self.data.get(j * self.width + i).copied().unwrap_or([f32::NAN; 2]);
        let (d00, d10, d01, d11) = (get(i0, j0), get(i1, j0), get(i0, j1), get(i1, j1));
        let lerp = |c: usize| {
            let bottom = f64::from(d00[c]) + fx * f64::from(d10[c] - d00[c]);
            let top = f64::from(d01[c]) + fx * f64::from(d11[c] - d01[c]);
            bottom + fy * (top - bottom)
        };
        let (a, b) = (lerp(0), lerp(1));
        // Components are at most 1 in magnitude: no overflow without `hypot` (which is slow).
        let n2 = a * a + b * b;
        if n2.is_nan() || n2 <= 0.0 {
            return None;
        }
        let inv = 1.0 / n2.sqrt();
        Some([a * inv, b * inv])
    }

    /// Sum and count of noise samples along `steps` midpoint steps of `h` pixels from `p`,
    /// stopping at the raster edge, at holes and where the direction vanishes.
    #[inline]
    fn walk(&self, noise: &[f32], mut p: [f64; 2], h: f64, steps: usize) -> (f64, u32) {
        let (mut sum, mut count) = (0.0f64, 0u32);
        for _ in 0..steps {
            let Some(k1) = self.at(p) else { break };
            let Some(k2) = self.at([p[0] + 0.5 * h * k1[0], p[1] + 0.5 * h * k1[1]]) else {
                break;
            };
            p = [p[0] + h * k2[0], p[1] + h * k2[1]];
            let Some(k) = self.pixel(p).filter(|&k| self.defined(k)) else {
                break;
            };
            let Some(&n) = noise.get(k) else { break };
            sum += f64::from(n);
            count += 1;
        }
        (sum, count)
    }
}

/// Line integral convolution of seeded white noise over `field`; see the module docs.
pub fn lic(field: &VectorField, options: &LicOptions) -> Result<LicImage, LicError> {
    let (width, height) = (options.width, options.height);
    match width.checked_mul(height) {
        Some(n) if n > 0 && n <= MAX_PIXELS => {}
        _ => return Err(LicError::RasterSize { width, height }),
    }
    let length = options.length;
    if !(length > 0.0 && length.is_finite()) {
        return Err(LicError::KernelLength { length });
    }
    let steps = (length / options.step).ceil();
    if !(options.step > 0.0 && steps <= MAX_KERNEL_STEPS as f64) {
        return Err(LicError::Step { step: options.step, length });
    }
    let steps = steps as usize;
    let h = length / steps as f64;
    let directions = Directions::sample(field, width, height);
    let noise = white_noise(width * height, options.seed);
    let mut data = vec![f32::NAN; width * height];
    match options.method {
        LicMethod::PerPixel => data.par_chunks_mut(width).enumerate().for_each(|(r, row)| {
            for (c, out) in row.iter_mut().enumerate() {
                let k = r * width + c;
                if !directions.defined(k) {
                    continue;
                }
                let p = [c as f64 + 0.5, r as f64 + 0.5];
                let centre = noise.get(k).copied().map_or(0.0, f64::from);
                let (fs, fc) = directions.walk(&noise, p, h, steps);
                let (bs, bc) = directions.walk(&noise, p, -h, steps);
                *out = ((centre + fs + bs) / f64::from(1 + fc + bc)) as f32;
            }
        }),
        LicMethod::Fast => data.par_chunks_mut(width * BAND_ROWS).enumerate().for_each(|(band, rows)| {
            let mut fast = FastBand::new(&directions, &noise, band * BAND_ROWS, rows.len() / width, steps, h);
            fast.run(rows);
        }),
    }
    stretch(&mut data);
    Ok(LicImage { width, height, data })
}

/// Rows per band of the fast method (fixed, so results do not depend on the thread count).
const BAND_ROWS: usize = 32;

/// One band of rows of the fast method, with its hit accumulators and reusable line buffers.
struct FastBand<'a> {
    dirs: &'a Directions,
    noise: &'a [f32],
    /// First row of the band and number of rows.
    row0: usize,
    rows: usize,
    /// Kernel half-width in points and step in pixels.
    n: usize,
    h: f64,
    sum: Vec<f64>,
    hits: Vec<u32>,
    back: Vec<usize>,
    line: Vec<usize>,
    prefix: Vec<f64>,
}

impl<'a> FastBand<'a> {
    fn new(dirs: &'a Directions, noise: &'a [f32], row0: usize, rows: usize, n: usize, h: f64) -> FastBand<'a> {
        let size = rows * dirs.width;
        FastBand {
            dirs,
            noise,
            row0,
            rows,
            n,
            h,
            sum: vec![0.0; size],
            hits: vec![0; size],
            back: Vec::new(),
            line: Vec::new(),
            prefix: Vec::new(),
        }
    }

    /// Fills the band's output rows.
    fn run(&mut self, out: &mut [f32]) {
        let width = self.dirs.width;
        for local in 0..out.len() {
            let global = self.row0 * width + local;
            if self.hits.get(local).is_some_and(|&h| h == 0) && self.dirs.defined(global) {
                let centre = [(local % width) as f64 + 0.5, (self.row0 + local / width) as f64 + 0.5];
                self.line_through(centre, global);
            }
        }
        for ((o, &s), &n) in out.iter_mut().zip(&self.sum).zip(&self.hits) {
            if n > 0 {
                *o = (s / f64::from(n)) as f32;
            }
        }
    }

    /// Pixels under up to `max` points traced from `p` in steps of `h`; `true` when the trace
    /// ended for a real reason (edge, hole, zero direction) rather than the cap or leaving the
    /// band's reach.
    fn trace(&self, mut p: [f64; 2], h: f64, max: usize, out: &mut Vec<usize>) -> bool {
        let reach = self.n as f64 * self.h.abs() + 2.0;
        let (lo, hi) = (self.row0 as f64 - reach, (self.row0 + self.rows) as f64 + reach);
        for _ in 0..max {
            let Some(k1) = self.dirs.at(p) else { return true };
            let Some(k2) = self.dirs.at([p[0] + 0.5 * h * k1[0], p[1] + 0.5 * h * k1[1]]) else {
                return true;
            };
            p = [p[0] + h * k2[0], p[1] + h * k2[1]];
            let Some(k) = self.dirs.pixel(p).filter(|&k| self.dirs.defined(k)) else {
                return true;
            };
            if p[1] < lo || p[1] > hi {
                return false;
            }
            out.push(k);
        }
        false
    }

    /// Traces the long streamline through pixel `seed` (centre `centre`) and deposits the box
    /// means of every fully supported window centred in the band.
    fn line_through(&mut self, centre: [f64; 2], seed: usize) {
        let (n, max) = (self.n, 4 * self.n + 16);
        let mut back = std::mem::take(&mut self.back);
        let mut line = std::mem::take(&mut self.line);
        back.clear();
        line.clear();
        let back_real = self.trace(centre, -self.h, max, &mut back);
        line.extend(back.iter().rev());
        line.push(seed);
        let fwd_real = self.trace(centre, self.h, max, &mut line);
        self.prefix.clear();
        self.prefix.push(0.0);
        let mut acc = 0.0;
        for &k in &line {
            acc += self.noise.get(k).copied().map_or(0.0, f64::from);
            self.prefix.push(acc);
        }
        let band = self.row0 * self.dirs.width..(self.row0 + self.rows) * self.dirs.width;
        let last = line.len() - 1;
        for (i, &k) in line.iter().enumerate() {
            if (i < n && !back_real) || (i + n > last && !fwd_real) || !band.contains(&k) {
                continue;
            }
            let (a, b) = (i.saturating_sub(n), (i + n).min(last));
            let mean = (self.prefix[b + 1] - self.prefix[a]) / (b + 1 - a) as f64;
            let local = k - band.start;
            if let (Some(s), Some(c)) = (self.sum.get_mut(local), self.hits.get_mut(local)) {
                *s += mean;
                *c += 1;
            }
        }
        self.back = back;
        self.line = line;
    }
}

/// White noise in `[0, 1)`: pixel `k` is a hash of `(seed, k)`, independent of evaluation order.
fn white_noise(n: usize, seed: u64) -> Vec<f32> {
    (0..n as u64).map(|k| (splitmix64(seed ^ splitmix64(k)) >> 40) as f32 / (1u64 << 24) as f32).collect()
}

/// SplitMix64 finaliser (Steele, Lea & Flood 2014).
fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Maps mean ± 2.5 standard deviations of the defined values onto `[0, 1]` (clamped); a constant
/// image becomes 0.5. NaN stays NaN.
fn stretch(data: &mut [f32]) {
    let (mut n, mut sum, mut sum2) = (0.0f64, 0.0f64, 0.0f64);
    for &v in data.iter().filter(|v| !v.is_nan()) {
        n += 1.0;
        sum += f64::from(v);
        sum2 += f64::from(v) * f64::from(v);
    }
    if n == 0.0 {
        return;
    }
    let mean = sum / n;
    let sd = (sum2 / n - mean * mean).max(0.0).sqrt();
    for v in data.iter_mut().filter(|v| !v.is_nan()) {
        *v = if sd > 0.0 { ((f64::from(*v) - mean) / (5.0 * sd) + 0.5).clamp(0.0, 1.0) as f32 } else { 0.5 };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(n: usize, a: f64, b: f64) -> Vec<f64> {
        (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect()
    }

    /// Mean absolute difference between neighbours along x and along y.
    fn roughness(img: &LicImage) -> (f64, f64) {
        let (w, h) = (img.width, img.height);
        let at = |c: usize, r: usize| f64::from(img.data[r * w + c]);
        let (mut dx, mut dy) = (0.0, 0.0);
        for r in 0..h - 1 {
            for c in 0..w - 1 {
                dx += (at(c + 1, r) - at(c, r)).abs();
                dy += (at(c, r + 1) - at(c, r)).abs();
            }
        }
        (dx, dy)
    }

    #[test]
    fn uniform_flow_smears_noise_along_the_flow() {
        for method in [LicMethod::Fast, LicMethod::PerPixel] {
            let options = LicOptions { method, ..LicOptions::new(128, 128) };
            let field = VectorField::from_fn(axis(33, 0.0, 1.0), axis(33, 0.0, 1.0), |_, _| [1.0, 0.0]).unwrap();
            let img = lic(&field, &options).unwrap();
            assert!(img.data.iter().all(|v| (0.0..=1.0).contains(v)));
            let (dx, dy) = roughness(&img);
            assert!(dx / dy < 0.3, "{method:?}: along-flow / across-flow roughness {}", dx / dy);
            // Vertical flow: the other way round.
            let field = VectorField::from_fn(axis(33, 0.0, 1.0), axis(33, 0.0, 1.0), |_, _| [0.0, -2.0]).unwrap();
            let (dx, dy) = roughness(&lic(&field, &options).unwrap());
            assert!(dy / dx < 0.3, "{method:?}: along-flow / across-flow roughness {}", dy / dx);
        }
    }

    #[test]
    fn fast_and_per_pixel_methods_agree() {
        // A vortex: curved streamlines, so the two methods sample the noise differently.
        let field =
            VectorField::from_fn(axis(65, -1.0, 1.0), axis(65, -1.0, 1.0), |x, y| [-y + 0.2 * x, x + 0.2 * y]).unwrap();
        let fast = lic(&field, &LicOptions::new(160, 160)).unwrap();
        let slow = lic(&field, &LicOptions { method: LicMethod::PerPixel, ..LicOptions::new(160, 160) }).unwrap();
        let pairs: Vec<(f64, f64)> = fast
            .data
            .iter()
            .zip(&slow.data)
            .filter(|(a, b)| !a.is_nan() && !b.is_nan())
            .map(|(&a, &b)| (f64::from(a), f64::from(b)))
            .collect();
        let n = pairs.len() as f64;
        let (ma, mb) = (pairs.iter().map(|p| p.0).sum::<f64>() / n, pairs.iter().map(|p| p.1).sum::<f64>() / n);
        let cov: f64 = pairs.iter().map(|p| (p.0 - ma) * (p.1 - mb)).sum();
        let va: f64 = pairs.iter().map(|p| (p.0 - ma).powi(2)).sum();
        let vb: f64 = pairs.iter().map(|p| (p.1 - mb).powi(2)).sum();
        let correlation = cov / (va * vb).sqrt();
        assert!(correlation > 0.8, "correlation {correlation}");
    }

    #[test]
    fn deterministic_for_a_seed_and_thread_count_and_nan_in_holes() {
        let mut u = vec![1.0; 17 * 17];
        u[8 * 17 + 8] = f64::NAN; // node (8, 8): the four cells around (0.5, 0.5) are holes
        let field = VectorField::new(axis(17, 0.0, 1.0), axis(17, 0.0, 1.0), u, vec![0.5; 17 * 17]).unwrap();
        for method in [LicMethod::Fast, LicMethod::PerPixel] {
            let options = LicOptions { seed: 7, method, ..LicOptions::new(64, 80) };
            let a = lic(&field, &options).unwrap();
            let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
            let b = one_thread.install(|| lic(&field, &options)).unwrap();
            assert!(a.data.iter().zip(&b.data).all(|(x, y)| x.to_bits() == y.to_bits()), "{method:?}");
            let c = lic(&field, &LicOptions { seed: 8, ..options }).unwrap();
            assert!(a.data.iter().zip(&c.data).any(|(x, y)| x != y));
            // Pixel centre (0.5 + 1/128, 0.5 + 1/160) is in a hole; a corner pixel is not.
            assert!(a.data[40 * 64 + 32].is_nan());
            assert!(!a.data[0].is_nan());
            // Columns 28..=35 and rows 35..=44 have centres in [7/16, 9/16]².
            assert_eq!(a.data.iter().filter(|v| v.is_nan()).count(), 8 * 10, "{method:?}");
        }
    }

    #[test]
    fn bad_options_are_refused_with_the_value() {
        let field = VectorField::from_fn(axis(3, 0.0, 1.0), axis(3, 0.0, 1.0), |_, _| [1.0, 0.0]).unwrap();
        let e = lic(&field, &LicOptions::new(0, 10)).unwrap_err();
        assert_eq!(e, LicError::RasterSize { width: 0, height: 10 });
        let e = lic(&field, &LicOptions { length: f64::NAN, ..LicOptions::new(4, 4) }).unwrap_err();
        assert!(e.to_string().contains("length NaN"), "{e}");
        let e = lic(&field, &LicOptions { step: 0.0, ..LicOptions::new(4, 4) }).unwrap_err();
        assert!(e.to_string().contains("step 0"), "{e}");
    }
}
