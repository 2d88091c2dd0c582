//! Direct volume rendering by ray casting: each ray is clipped to the volume's box, sampled at
//! equal steps by trilinear interpolation, and reduced to a colour (compositing through a
//! transfer function), to its largest value (maximum intensity projection) or to its mean
//! value (an X-ray-like average).
//!
//! Rules:
//! - **Where rays sample.** Rays run in world coordinates; samples are taken in fractional voxel
//!   indices through the inverse voxel-to-world matrix, so spacing and orientation are honoured.
//!   A ray covers the box of the voxel centres (the trilinear interpolant's domain). Composited
//!   samples sit at `t0 + (n + ½)·step` between its entry `t0` and exit (the midpoint rule);
//!   maxima and means sample from the entry, `t0 + n·step`, so a step dividing the spacing
//!   meets every voxel plane an axis-aligned ray crosses and its maximum is the exact one.
//! - **Transfer function.** Opacity is given per [`Settings::reference`] length of ray (one
//!   voxel by default): a sample `step` long takes `α' = 1 − (1 − α)^(step / reference)`, so
//!   the picture does not darken or fade when the step changes (opacity correction).
//! - **Classification.** [`Classify::After`] interpolates the value, then looks up its colour
//!   and opacity (fine detail between voxels); [`Classify::Before`] looks up the eight voxels'
//!   colours and opacities and interpolates the opacity-weighted colours (smoother, blurs thin
//!   features, as classic pre-classified renderers do).
//! - **Compositing.** Front to back: `C += (1 − A)·α'·c`, `A += (1 − A)·α'`. A ray stops once
//!   `A ≥` [`TERMINATION`], where what is left could change no 8-bit channel by more than 1/2
//!   of a level.
//! - **Empty space.** The volume is cut into blocks of 8³ cells with their value ranges; an
//!   image's rays jump over a block the transfer function leaves wholly transparent — over the
//!   whole cube of clear blocks around it that [`clear_reach`] finds — and a maximum over a
//!   block no higher than the maximum found so far. Only samples that would add nothing are
//!   skipped, so the image is the same.
//! - **Missing voxels.** A sample with a missing (NaN) voxel among its eight is skipped: it adds
//!   nothing (transparent; left out of maxima and means).
//! - **Gradient opacity.** Optional: a sample's opacity is scaled by `min(1, |∇f| / full)`
//!   before the step correction ([`Settings::gradient_opacity`]), with the same gradient the
//!   shading uses; [`RayCaster::gradient_quantile`] picks `full` from the volume.
//! - **Shading.** Optional: the colour is scaled by `ambient + diffuse·|n·l|` with `n` the
//!   normalised world gradient (central differences of the interpolant, half a voxel each way,
//!   one-sided at the faces), lit from both sides; where the gradient vanishes the sample takes
//!   the ambient plus half the diffuse light.

use rayon::prelude::*;

use std::borrow::Cow;

use crate::data::volume::{Volume, Voxels};

use super::sample::invert;

/// Accumulated opacity at which a ray stops: `1 − 1/512`.
pub const TERMINATION: f64 = 1.0 - 1.0 / 512.0;

/// Entries in a transfer function's lookup table.
const LUT_SIZE: usize = 4096;

/// How a ray is reduced to a pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Front-to-back compositing through the transfer function.
    Composite,
    /// The largest value along the ray.
    Mip,
    /// The mean value along the ray.
    Average,
}

/// When values become colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Classify {
    /// Interpolate the value, then classify it.
    After,
    /// Classify the voxels, then interpolate opacity-weighted colours.
    Before,
}

/// Diffuse lighting of composited samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shading {
    /// Unit vector toward the light, in world coordinates.
    pub light: [f64; 3],
    /// Light every sample gets.
    pub ambient: f64,
    /// Strength of the light from `light`.
    pub diffuse: f64,
}

/// How rays are sampled and composited.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Distance between samples along a ray, in world units.
    pub step: f64,
    /// The ray length the transfer function's opacities refer to, in world units.
    pub reference: f64,
    /// Accumulated opacity at which a composited ray stops ([`TERMINATION`]; 1 never stops).
    pub termination: f64,
    /// When values become colours.
    pub classify: Classify,
    /// Lighting, if any.
    pub shading: Option<Shading>,
    /// Opacity scaled by the gradient magnitude, if any: a sample's opacity is multiplied by
    /// `min(1, |∇f| / full)` with `full` this gradient magnitude (world units), so uniform
    /// regions fade and boundaries between materials stay (Levoy 1988).
    pub gradient_opacity: Option<f64>,
}

impl Settings {
    /// A sample's opacity scaled by its gradient's magnitude (with `gradient_opacity`) and the
    /// light it gets (with `shading`; 1 without), from `alpha` and its world gradient (asked
    /// for only when needed); `None` when the scaling leaves it transparent.
    pub(super) fn lit(&self, alpha: f64, gradient: impl FnOnce() -> [f64; 3]) -> Option<(f64, f64)> {
        if self.shading.is_none() && self.gradient_opacity.is_none() {
            return Some((alpha, 1.0));
        }
        let n = gradient();
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let alpha = match self.gradient_opacity {
            Some(full) => alpha * (len / full).min(1.0),
            None => alpha,
        };
        if !(alpha > 0.0) {
            return None;
        }
        let light = self.shading.map_or(1.0, |s| {
            let cos = if len > 1e-12 {
                ((n[0] * s.light[0] + n[1] * s.light[1] + n[2] * s.light[2]) / len).abs()
            } else {
                0.5
            };
            (s.ambient + s.diffuse * cos).min(1.0)
        });
        Some((alpha, light))
    }
}

/// Colour and opacity as piecewise-linear functions of the value, tabulated over a domain.
#[derive(Clone, Debug, PartialEq)]
pub struct TransferFunction {
    domain: (f64, f64),
    /// Straight colour (0 to 1) and opacity per reference length, at equal steps over `domain`.
    table: Vec<[f64; 4]>,
    /// Table steps per unit of value (a function table; labels take one entry per unit).
    per_value: f64,
    /// What values outside the domain look up: `None` holds the end entries.
    outside: Option<[f64; 4]>,
}

/// Most labels a label transfer function spans (largest minus smallest value, plus one).
pub const MAX_LABEL_SPAN: i64 = 65_536;

impl TransferFunction {
    /// A transfer function with `colour(value)` (RGB, 0 to 1) and opacity through the control
    /// points `opacity` (value, alpha), sorted by value; below the first and above the last
    /// point the end alphas hold. Tabulated over the control points' span.
    pub fn new(colour: impl Fn(f64) -> [f64; 3], opacity: &[(f64, f64)]) -> Result<TransferFunction, String> {
        let Some((&first, &last)) = opacity.first().zip(opacity.last()) else {
            return Err("an opacity transfer function needs at least one control point".into());
        };
        if let Some(w) = opacity.windows(2).find(|w| !(w[0].0 <= w[1].0)) {
            return Err(format!("opacity control points must rise in value: {} comes after {}", w[1].0, w[0].0));
        }
        if let Some(p) = opacity.iter().find(|p| !(p.0.is_finite() && (0.0..=1.0).contains(&p.1))) {
            return Err(format!(
                "the opacity control point [{}, {}] needs a finite value and an opacity from 0 to 1",
                p.0, p.1
            ));
        }
        let (lo, hi) = (first.0, if last.0 > first.0 { last.0 } else { first.0 + 1.0 });
        let table = (0..LUT_SIZE)
            .map(|k| {
                let v = lo + (hi - lo) * k as f64 / (LUT_SIZE - 1) as f64;
                let [r, g, b] = colour(v);
                [r, g, b, piecewise(opacity, v)]
            })
            .collect();
        let per_value = (LUT_SIZE - 1) as f64 / (hi - lo);
        Ok(TransferFunction { domain: (lo, hi), table, per_value, outside: None })
    }

    /// A transfer function for a label volume (a segmentation): each `(label, colour, opacity)`
    /// gives whole-number voxel value `label` its colour and opacity; every other value is
    /// transparent. Values are rounded to the nearest whole number.
    pub fn labels(entries: &[(i64, [f64; 3], f64)]) -> Result<TransferFunction, String> {
        let lo = entries.iter().map(|e| e.0).min().ok_or("a label transfer function needs at least one label")?;
        let hi = entries.iter().map(|e| e.0).max().unwrap_or(lo);
        if hi - lo >= MAX_LABEL_SPAN {
            return Err(format!("labels {lo} to {hi} span more than {MAX_LABEL_SPAN} values"));
        }
        if let Some(e) = entries.iter().find(|e| !(0.0..=1.0).contains(&e.2)) {
            return Err(format!("label {} has opacity {}: give 0 to 1", e.0, e.2));
        }
        let mut table = vec![[0.0; 4]; (hi - lo + 1) as usize];
        for &(label, [r, g, b], a) in entries {
            table[(label - lo) as usize] = [r, g, b, a];
        }
        // One entry per whole number: the domain's ends are half a label beyond the end labels.
        let domain = (lo as f64 - 0.5, hi as f64 + 0.5);
        Ok(TransferFunction { domain, table, per_value: 1.0, outside: Some([0.0; 4]) })
    }

    /// Colour and opacity at `value`: the nearest table entry; beyond the domain the end entries
    /// (a label function: transparent).
    #[inline]
    pub fn at(&self, value: f64) -> [f64; 4] {
        match self.outside {
            Some(outside) if !(value >= self.domain.0 && value < self.domain.1) => outside,
            _ => self.table[self.entry(value)],
        }
    }

    /// The table entry `value` looks up (monotone in the value; clamped to the table; entry 0
    /// for NaN, which clamps to NaN and truncates to 0). No division and no call to libm's
    /// floor or round: truncation floors what is not negative, and adding ½ first rounds.
    #[inline]
    fn entry(&self, value: f64) -> usize {
        let last = (self.table.len() - 1) as u32 as f64;
        match self.outside {
            // Label tables: entry k covers [lo + k, lo + k + 1); the domain is as many values
            // wide as the table is long.
            Some(_) => (value - self.domain.0).clamp(0.0, last) as u32 as usize,
            // Through `u32` (tables are far shorter), whose conversion from `f64` is one
            // instruction, unlike `usize`'s.
            None => (((value - self.domain.0) * self.per_value).clamp(0.0, last) + 0.5) as u32 as usize,
        }
    }

    /// Whether every value from `a` to `b` (a ≤ b) has an opacity of at least `threshold`, when
    /// they all agree; `None` when they differ (or may: the test goes by table entries).
    pub fn opacity_at_least_throughout(&self, (a, b): (f64, f64), threshold: f64) -> Option<bool> {
        let shown = |e: &[f64; 4]| e[3] >= threshold;
        let mut answer: Option<bool> = None;
        let mut agree = |k: bool| match answer {
            Some(seen) => seen == k,
            None => {
                answer = Some(k);
                true
            }
        };
        let (d0, d1) = self.domain;
        if let Some(outside) = self.outside
            && (a < d0 || b >= d1)
            && !agree(shown(&outside))
        {
            return None;
        }
        let (from, to) = match self.outside {
            Some(_) => (a.max(d0), b.min(d1)),
            None => (a, b),
        };
        if from <= to {
            let entries = &self.table[self.entry(from)..=self.entry(to)];
            let first = shown(&entries[0]);
            if !(entries.iter().all(|e| shown(e) == first) && agree(first)) {
                return None;
            }
        }
        answer
    }

    /// The same function with each opacity `α` replaced by `1 − (1 − α)^exponent`: the opacity
    /// of a sample `exponent` reference lengths long.
    pub fn corrected(&self, exponent: f64) -> TransferFunction {
        let table = self.table.iter().map(|&[r, g, b, a]| [r, g, b, 1.0 - (1.0 - a.min(1.0)).powf(exponent)]).collect();
        TransferFunction { table, ..self.clone() }
    }

    /// The values the table spans.
    pub fn domain(&self) -> (f64, f64) {
        self.domain
    }
}

/// The piecewise-linear function through `points` at `v`, holding the end values beyond them.
pub fn piecewise(points: &[(f64, f64)], v: f64) -> f64 {
    let Some(&(x0, y0)) = points.first() else { return 0.0 };
    if v <= x0 {
        return y0;
    }
    for w in points.windows(2) {
        let ((a, ya), (b, yb)) = (w[0], w[1]);
        if v <= b {
            return if b > a { ya + (yb - ya) * (v - a) / (b - a) } else { yb };
        }
    }
    points.last().map_or(0.0, |p| p.1)
}

/// A volume prepared for ray casting: its values as `f32`, x fastest (borrowed when the volume
/// holds unscaled `f32` voxels, converted otherwise), and its world-to-index map.
#[derive(Clone, Debug)]
pub struct RayCaster<'v> {
    dims: [usize; 3],
    values: Cow<'v, [f32]>,
    /// Rows of `index = inverse · (x, y, z, 1)`.
    inverse: [[f64; 4]; 3],
    /// The smallest and largest voxel value of each block of [`BLOCK`]³ cells (its voxels and the
    /// next ones, which its cells' corners reach), x fastest; NaN voxels left out.
    blocks: Vec<(f32, f32)>,
    /// Blocks along x, y and z.
    block_dims: [usize; 3],
}

/// Pixels along each side of the tiles an image is cast in.
const TILE: usize = 8;

/// Cells along each side of the blocks used to skip empty space.
pub(super) const BLOCK: usize = 8;

impl<'v> RayCaster<'v> {
    /// A ray caster over `volume`, or why there is none: fewer than two voxels along an axis, or
    /// a voxel-to-world matrix without an inverse.
    pub fn new(volume: &'v Volume) -> Result<RayCaster<'v>, String> {
        let dims = volume.dims();
        if let Some(a) = (0..3).find(|&a| dims[a] < 2) {
            return Err(format!(
                "the volume is {} × {} × {} voxels: rays need at least two voxels along {}",
                dims[0],
                dims[1],
                dims[2],
                ["x", "y", "z"][a]
            ));
        }
        let inverse = invert(volume.affine()).ok_or_else(|| {
            format!(
                "the voxel-to-world matrix {:?} flattens the volume (its 3 × 3 part has no inverse)",
                volume.affine()
            )
        })?;
        let values: Cow<'v, [f32]> = match (volume.voxels(), volume.scale()) {
            (Voxels::F32(stored), None) => Cow::Borrowed(stored),
            _ => Cow::Owned((0..volume.len()).into_par_iter().map(|n| volume.get(n) as f32).collect()),
        };
        let (blocks, block_dims) = block_ranges(&values, dims);
        Ok(RayCaster { dims, values, inverse, blocks, block_dims })
    }

    pub(super) fn index_of(&self, w: [f64; 3]) -> [f64; 3] {
        self.inverse.map(|row| row[0] * w[0] + row[1] * w[1] + row[2] * w[2] + row[3])
    }

    pub(super) fn index_direction(&self, d: [f64; 3]) -> [f64; 3] {
        self.inverse.map(|row| row[0] * d[0] + row[1] * d[1] + row[2] * d[2])
    }

    /// The part of the ray `origin + t·dir` (t ≥ 0, `dir` of unit length) inside the box of the
    /// voxel centres, as `(t_in, t_out)`.
    fn clip(&self, p: [f64; 3], d: [f64; 3]) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for a in 0..3 {
            let hi = (self.dims[a] - 1) as f64;
            if d[a].abs() < 1e-300 {
                if p[a] < 0.0 || p[a] > hi {
                    return None;
                }
                continue;
            }
            let (ta, tb) = ((0.0 - p[a]) / d[a], (hi - p[a]) / d[a]);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
        (t0.is_finite() && t1 > t0).then_some((t0, t1))
    }

    /// The lower corner and fractional offsets of index point `p` (clamped into the box).
    #[inline(always)]
    fn cell(&self, p: [f64; 3]) -> ([usize; 3], [f64; 3]) {
        let mut lower = [0usize; 3];
        let mut t = [0.0; 3];
        for a in 0..3 {
            let x = p[a].clamp(0.0, (self.dims[a] - 1) as f64);
            // Not negative: truncation floors. Through `u32` (sides are far shorter), whose
            // conversions to and from `f64` are single instructions, unlike `usize`'s.
            let i0 = (x as u32).min(self.dims[a] as u32 - 2);
            lower[a] = i0 as usize;
            t[a] = x - f64::from(i0);
        }
        (lower, t)
    }

    /// The block (its numbers along x, y and z) holding the cell of index point `p`.
    #[inline]
    fn block_at(&self, p: [f64; 3]) -> [usize; 3] {
        let (lower, _) = self.cell(p);
        lower.map(|l| l / BLOCK)
    }

    /// The number of block `[bx, by, bz]`, x fastest.
    #[inline]
    fn block_number(&self, [bx, by, bz]: [usize; 3]) -> usize {
        (bz * self.block_dims[1] + by) * self.block_dims[0] + bx
    }

    /// The block holding the cell of index point `p`.
    fn block_of(&self, p: [f64; 3]) -> usize {
        self.block_number(self.block_at(p))
    }

    /// Where the ray `p0 + t·d` leaves the block holding the cell of `p0 + t·d` (a `t`).
    fn block_exit(&self, p0: [f64; 3], d: [f64; 3], t: f64) -> f64 {
        cube_exit(p0, d, self.block_at([p0[0] + t * d[0], p0[1] + t * d[1], p0[2] + t * d[2]]), 1)
    }

    /// The eight voxel values around a cell's lower corner, bit 0 of the index picking +x,
    /// bit 1 +y, bit 2 +z.
    #[inline(always)]
    fn corners(&self, [i, j, k]: [usize; 3]) -> [f32; 8] {
        let (nx, ny) = (self.dims[0], self.dims[1]);
        let base = (k * ny + j) * nx + i;
        let (sy, sz) = (nx, nx * ny);
        // One bounds check for the cube; the pairs along x as two-element arrays.
        let cube = &self.values[base..base + sz + sy + 2];
        let pair = |at: usize| -> [f32; 2] { [cube[at], cube[at + 1]] };
        let ([c0, c1], [c2, c3], [c4, c5], [c6, c7]) = (pair(0), pair(sy), pair(sz), pair(sz + sy));
        [c0, c1, c2, c3, c4, c5, c6, c7]
    }

    /// The trilinear value at index point `p` (NaN when a corner is missing).
    #[inline(always)]
    fn value(&self, p: [f64; 3]) -> f64 {
        let (lower, t) = self.cell(p);
        let c = self.corners(lower).map(f64::from);
        trilinear(&c, t)
    }

    /// The world gradient of the interpolant at index point `p` by central differences half a
    /// voxel each way (one-sided within half a voxel of a face).
    fn gradient(&self, p: [f64; 3]) -> [f64; 3] {
        let mut g = [0.0; 3];
        for (a, ga) in g.iter_mut().enumerate() {
            let (mut lo, mut hi) = (p, p);
            lo[a] = (p[a] - 0.5).max(0.0);
            hi[a] = (p[a] + 0.5).min((self.dims[a] - 1) as f64);
            *ga = if hi[a] > lo[a] { (self.value(hi) - self.value(lo)) / (hi[a] - lo[a]) } else { 0.0 };
        }
        // ∂f/∂w_c = Σ_r ∂f/∂i_r · ∂i_r/∂w_c.
        [0, 1, 2].map(|c| (0..3).map(|r| g[r] * self.inverse[r][c]).sum())
    }

    /// The voxel values as `f32`, x fastest (NaN where missing).
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// For each voxel-run block, whether `tf` leaves it wholly transparent, and a function
    /// from a voxel to its block: a voxel of a clear block is transparent.
    pub(super) fn clear_voxels(&self, tf: &TransferFunction) -> impl Fn([usize; 3]) -> bool + Sync + '_ {
        let clear = clear_blocks(self, tf);
        move |p: [usize; 3]| {
            let [bx, by, bz] = [0, 1, 2].map(|a| (p[a] / BLOCK).min(self.block_dims[a] - 1));
            clear[(bz * self.block_dims[1] + by) * self.block_dims[0] + bx]
        }
    }

    /// Voxels along x, y and z.
    pub(super) fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The value of voxel number `n` (x fastest; NaN where missing).
    pub(super) fn voxel(&self, n: usize) -> f32 {
        self.values[n]
    }

    /// The world gradient at voxel `(i, j, k)`: central differences over the neighbouring
    /// voxels, one-sided at the faces — what [`RayCaster::gradient`] gives at a voxel, without
    /// interpolating.
    pub(super) fn voxel_gradient(&self, [i, j, k]: [usize; 3]) -> [f64; 3] {
        let [nx, ny, _] = self.dims;
        let at = |i: usize, j: usize, k: usize| f64::from(self.values[(k * ny + j) * nx + i]);
        let mut g = [0.0; 3];
        let p = [i, j, k];
        for (a, ga) in g.iter_mut().enumerate() {
            let (lo, hi) = (p[a].saturating_sub(1), (p[a] + 1).min(self.dims[a] - 1));
            let (mut q0, mut q1) = (p, p);
            q0[a] = lo;
            q1[a] = hi;
            *ga = (at(q1[0], q1[1], q1[2]) - at(q0[0], q0[1], q0[2])) / (hi - lo) as f64;
        }
        [0, 1, 2].map(|c| (0..3).map(|r| g[r] * self.inverse[r][c]).sum())
    }

    /// The `q` quantile (0 to 1) of the world gradient magnitude at the voxels where it is not
    /// zero (central differences, one-sided at the faces), from at most about a million voxels
    /// evenly strided; `None` when the volume is uniform.
    pub fn gradient_quantile(&self, q: f64) -> Option<f64> {
        let [nx, ny, _] = self.dims;
        let stride = (self.values.len() / 1_000_000).max(1);
        let mut magnitudes: Vec<f64> = (0..self.values.len())
            .into_par_iter()
            .step_by(stride)
            .filter_map(|n| {
                let p = [(n % nx) as f64, (n / nx % ny) as f64, (n / (nx * ny)) as f64];
                let g = self.gradient(p);
                let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
                (len > 0.0).then_some(len)
            })
            .collect();
        magnitudes.sort_by(f64::total_cmp);
        let last = magnitudes.len().checked_sub(1)?;
        Some(magnitudes[(q.clamp(0.0, 1.0) * last as f64).round() as usize])
    }

    /// Colour and opacity of the sample at index point `p`, classified as `settings` says.
    #[inline(always)]
    fn classified(&self, p: [f64; 3], tf: &TransferFunction, classify: Classify) -> Option<[f64; 4]> {
        match classify {
            Classify::After => {
                let v = self.value(p);
                (!v.is_nan()).then(|| tf.at(v))
            }
            Classify::Before => {
                let (lower, t) = self.cell(p);
                let c = self.corners(lower);
                if c.iter().any(|v| v.is_nan()) {
                    return None;
                }
                // Opacity-weighted colours interpolated, then divided back by the opacity.
                let looked: [[f64; 4]; 8] = c.map(|v| tf.at(f64::from(v)));
                let mut out = [0.0; 4];
                for ch in 0..4 {
                    let w: [f64; 8] = looked.map(|q| if ch < 3 { q[ch] * q[3] } else { q[3] });
                    out[ch] = trilinear(&w, t);
                }
                let a = out[3];
                Some(if a > 0.0 { [out[0] / a, out[1] / a, out[2] / a, a] } else { [0.0, 0.0, 0.0, 0.0] })
            }
        }
    }

    /// The composited colour of the ray from world point `origin` along unit `dir`:
    /// premultiplied RGB and accumulated opacity, all 0 to 1.
    pub fn composite(&self, origin: [f64; 3], dir: [f64; 3], tf: &TransferFunction, settings: &Settings) -> [f64; 4] {
        self.composite_skipping(origin, dir, tf, settings, None, false)
    }

    /// [`RayCaster::composite`], jumping over the blocks a transfer function leaves wholly
    /// transparent, as far as `reach` (see [`clear_reach`]) says clear space goes around each:
    /// the samples skipped would add nothing, so the colour is the same. With `corrected`, `tf`'s
    /// opacities are already corrected for the step (see [`TransferFunction::corrected`]).
    fn composite_skipping(
        &self,
        origin: [f64; 3],
        dir: [f64; 3],
        tf: &TransferFunction,
        settings: &Settings,
        reach: Option<&[u32]>,
        corrected: bool,
    ) -> [f64; 4] {
        let (p0, d) = (self.index_of(origin), self.index_direction(dir));
        let Some((t0, t1)) = self.clip(p0, d) else { return [0.0; 4] };
        let exponent = settings.step / settings.reference;
        let step = settings.step;
        let mut acc = [0.0f64; 4];
        // Sample n sits at t0 + (n + ½)·step; `n` is the next one to take. A float that counts
        // whole numbers exactly, which saves a conversion a sample.
        let mut n = 0.0f64;
        loop {
            let t = t0 + (n + 0.5) * step;
            if t >= t1 {
                return acc;
            }
            // The samples before `end` lie in the block of sample n (up to rounding at its
            // walls) and are taken without asking again; or they lie in the cube of clear
            // blocks around it and are skipped. A sample taken in a clear block adds nothing,
            // so the colour is the same.
            let end = match reach {
                Some(reach) => {
                    let block = self.block_at([p0[0] + t * d[0], p0[1] + t * d[1], p0[2] + t * d[2]]);
                    let clear = reach[self.block_number(block)] as usize;
                    let exit = cube_exit(p0, d, block, clear.max(1));
                    let end = (n + 1.0).max(ceil_not_negative((exit - t0) / step - 0.5));
                    if clear > 0 {
                        n = end;
                        continue;
                    }
                    end
                }
                None => f64::INFINITY,
            };
            while n < end {
                let t = t0 + (n + 0.5) * step;
                if t >= t1 {
                    return acc;
                }
                n += 1.0;
                let p = [p0[0] + t * d[0], p0[1] + t * d[1], p0[2] + t * d[2]];
                let Some([r, g, b, alpha]) = self.classified(p, tf, settings.classify) else { continue };
                if alpha <= 0.0 {
                    continue;
                }
                let Some((alpha, light)) = settings.lit(alpha, || self.gradient(p)) else { continue };
                let a = if corrected { alpha } else { 1.0 - (1.0 - alpha.min(1.0)).powf(exponent) };
                let w = (1.0 - acc[3]) * a;
                acc[0] += w * r * light;
                acc[1] += w * g * light;
                acc[2] += w * b * light;
                acc[3] += w;
                if acc[3] >= settings.termination {
                    return acc;
                }
            }
        }
    }

    /// The largest (`Mode::Mip`) or mean (`Mode::Average`) value along the ray, or `None` when
    /// it misses the volume or meets only missing voxels.
    pub fn reduce(&self, origin: [f64; 3], dir: [f64; 3], mode: Mode, step: f64) -> Option<f64> {
        let (p0, d) = (self.index_of(origin), self.index_direction(dir));
        let (t0, t1) = self.clip(p0, d)?;
        // From the entry point on, so a step that divides the voxel spacing lands on every
        // voxel plane an axis-aligned ray crosses.
        let samples = ((t1 - t0) / step + 1e-9).floor() as usize + 1;
        let at = |s: usize| {
            let t = t0 + s as f64 * step;
            self.value([p0[0] + t * d[0], p0[1] + t * d[1], p0[2] + t * d[2]])
        };
        if mode == Mode::Mip {
            return self.largest(p0, d, (t0, step, samples), at);
        }
        let (mut sum, mut n) = (0.0, 0usize);
        for v in (0..samples).map(at).filter(|v| !v.is_nan()) {
            sum += v;
            n += 1;
        }
        (n > 0).then(|| sum / n as f64)
    }

    /// The largest of the ray's `samples` (`at(s)` for `s` in `0..samples`, at `t0 + s·step`):
    /// the samples are grouped by the block they fall in, the blocks visited from the highest
    /// block maximum down, and the search stops at a block no higher than what it has found —
    /// the same maximum as visiting every sample.
    fn largest(
        &self,
        p0: [f64; 3],
        d: [f64; 3],
        (t0, step, samples): (f64, f64, usize),
        at: impl Fn(usize) -> f64,
    ) -> Option<f64> {
        // (block maximum, first sample, end), in ray order.
        let mut runs: Vec<(f32, usize, usize)> = Vec::new();
        let mut s = 0;
        while s < samples {
            let t = t0 + s as f64 * step;
            let block = self.block_of([p0[0] + t * d[0], p0[1] + t * d[1], p0[2] + t * d[2]]);
            let exit = self.block_exit(p0, d, t);
            let end = (s + 1).max(ceil_not_negative((exit - t0) / step) as usize).min(samples);
            runs.push((self.blocks[block].1, s, end));
            s = end;
        }
        runs.sort_by(|a, b| b.0.total_cmp(&a.0));
        let (mut best, mut found) = (f64::NEG_INFINITY, false);
        for (most, start, end) in runs {
            if found && f64::from(most) <= best {
                break;
            }
            for v in (start..end).map(&at).filter(|v| !v.is_nan()) {
                best = best.max(v);
                found = true;
            }
        }
        found.then_some(best)
    }

    /// One value (`Mip`, `Average`) or premultiplied colour (`Composite`) per pixel of a
    /// `width × height` image whose pixel `(x, y)` casts `ray(x, y)` (world origin and unit
    /// direction), rows in parallel. Values are NaN where a ray has none.
    pub fn image(
        &self,
        (width, height): (usize, usize),
        ray: &(dyn Fn(usize, usize) -> ([f64; 3], [f64; 3]) + Sync),
        job: Job<'_>,
    ) -> Vec<[f64; 4]> {
        let mut out = vec![[0.0; 4]; width * height];
        let reach = match job {
            Job::Composite(tf, _) => clear_reach(&clear_blocks(self, tf), self.block_dims),
            Job::Reduce(..) => Vec::new(),
        };
        // Classified after interpolation and not scaled by the gradient, a sample's opacity is
        // a table entry: correct the table once instead of every sample.
        let corrected = match job {
            Job::Composite(tf, s) if s.classify == Classify::After && s.gradient_opacity.is_none() => {
                Some(tf.corrected(s.step / s.reference))
            }
            _ => None,
        };
        let cast = |x: usize, y: usize| {
            let (o, d) = ray(x, y);
            match job {
                Job::Composite(tf, settings) => match &corrected {
                    Some(c) => self.composite_skipping(o, d, c, settings, Some(&reach), true),
                    None => self.composite_skipping(o, d, tf, settings, Some(&reach), false),
                },
                Job::Reduce(mode, step) => [self.reduce(o, d, mode, step).unwrap_or(f64::NAN), 0.0, 0.0, 0.0],
            }
        };
        // Bands of TILE rows in parallel, each cast tile by tile: neighbouring rays read
        // neighbouring voxels, which are then still in the core's cache.
        let width = width.max(1);
        out.par_chunks_mut(width * TILE).enumerate().for_each(|(band, rows)| {
            let height = rows.len() / width;
            for x0 in (0..width).step_by(TILE) {
                for dy in 0..height {
                    for x in x0..(x0 + TILE).min(width) {
                        rows[dy * width + x] = cast(x, band * TILE + dy);
                    }
                }
            }
        });
        out
    }
}

/// The value range of every block of [`BLOCK`]³ cells of a volume (see [`RayCaster`]), axis by
/// axis: each row's voxels into ranges per block along x, then those along y for each plane
/// (planes in parallel), then along z for each layer of blocks (in parallel). A block's voxels
/// reach one past its cells, so neighbouring blocks share a voxel plane.
fn block_ranges(values: &[f32], dims: [usize; 3]) -> (Vec<(f32, f32)>, [usize; 3]) {
    let block_dims = dims.map(|n| (n - 1).div_ceil(BLOCK));
    let [nx, ny, _] = dims;
    let [bnx, bny, bnz] = block_dims;
    // The voxels of block `b` along an axis of `n` voxels.
    let span = |b: usize, n: usize| (b * BLOCK)..=((b + 1) * BLOCK).min(n - 1);
    let empty = (f32::INFINITY, f32::NEG_INFINITY);
    let widen = |(lo, hi): (f32, f32), (a, b): (f32, f32)| (if a < lo { a } else { lo }, if b > hi { b } else { hi });
    // Per plane: the range of each (block row along y, block along x).
    let planes: Vec<Vec<(f32, f32)>> = values
        .par_chunks(nx * ny)
        .map(|plane| {
            let rows: Vec<(f32, f32)> = plane
                .chunks(nx)
                .flat_map(|row| {
                    (0..bnx).map(move |bx| {
                        // A NaN fails both comparisons: never a bound.
                        row[span(bx, nx)].iter().fold(empty, |acc, &v| widen(acc, (v, v)))
                    })
                })
                .collect();
            (0..bny)
                .flat_map(|by| {
                    let rows = &rows;
                    (0..bnx).map(move |bx| span(by, ny).map(|j| rows[j * bnx + bx]).fold(empty, widen))
                })
                .collect()
        })
        .collect();
    let ranges: Vec<(f32, f32)> = (0..bnz)
        .into_par_iter()
        .flat_map_iter(|bz| {
            let planes = &planes;
            (0..bny * bnx).map(move |b| span(bz, dims[2]).map(|k| planes[k][b]).fold(empty, widen))
        })
        .collect();
    (ranges, block_dims)
}

/// Which blocks a transfer function leaves wholly transparent: every table entry their value
/// range can look up has opacity 0.
fn clear_blocks(caster: &RayCaster<'_>, tf: &TransferFunction) -> Vec<bool> {
    // Prefix counts of entries with some opacity, for an O(1) test per block.
    let mut seen = Vec::with_capacity(tf.table.len() + 1);
    seen.push(0usize);
    for e in &tf.table {
        seen.push(seen[seen.len() - 1] + usize::from(e[3] > 0.0));
    }
    caster
        .blocks
        .iter()
        .map(|&(lo, hi)| {
            if lo > hi {
                return true; // only missing voxels
            }
            let (a, b) = (tf.entry(f64::from(lo)), tf.entry(f64::from(hi)));
            seen[b + 1] - seen[a] == 0
        })
        .collect()
}

/// How far clear space reaches around each block of a `dims` grid whose blocks `clear` marks:
/// 0 for a block that is not clear, and `r ≥ 1` when every block less than `r` blocks away
/// along every axis (the chessboard distance) is clear; blocks beyond the grid count as clear
/// (rays stop at the box), and `r` is at most the grid's longest side plus one. A ray in a
/// clear block can jump to where it leaves that cube of blocks.
///
/// Two raster passes (forward, then backward) that each take the smallest of a block's value
/// and its 13 neighbours' values before it plus one: exact for the chessboard distance
/// (Rosenfeld and Pfaltz 1966).
fn clear_reach(clear: &[bool], dims: [usize; 3]) -> Vec<u32> {
    let cap = dims.into_iter().max().unwrap_or(0) as u32 + 1;
    let mut reach: Vec<u32> = clear.iter().map(|&c| if c { cap } else { 0 }).collect();
    let [nx, ny, nz] = dims.map(|n| n as isize);
    // The 13 neighbours before a block in x-fastest raster order.
    let before: Vec<[isize; 3]> = (-1..=1)
        .flat_map(|dz| (-1..=1).flat_map(move |dy| (-1..=1).map(move |dx| [dx, dy, dz])))
        .filter(|&[dx, dy, dz]| dz < 0 || (dz == 0 && (dy < 0 || (dy == 0 && dx < 0))))
        .collect();
    let blocks = reach.len();
    let mut pass = |order: &mut dyn Iterator<Item = usize>, sign: isize| {
        for at in order {
            if reach[at] == 0 {
                continue;
            }
            let n = at as isize;
            let [x, y, z] = [n % nx, n / nx % ny, n / (nx * ny)];
            let mut best = reach[at];
            for &[dx, dy, dz] in &before {
                let (u, v, w) = (x + sign * dx, y + sign * dy, z + sign * dz);
                if (0..nx).contains(&u) && (0..ny).contains(&v) && (0..nz).contains(&w) {
                    best = best.min(reach[((w * ny + v) * nx + u) as usize] + 1);
                }
            }
            reach[at] = best;
        }
    };
    pass(&mut (0..blocks), 1);
    pass(&mut (0..blocks).rev(), -1);
    reach
}

#[cfg(test)]
impl RayCaster<'_> {
    /// The largest value along a ray sampled every `step` from its entry, no block skipped.
    fn reduce_all(&self, origin: [f64; 3], dir: [f64; 3], step: f64) -> Option<f64> {
        let (p0, d) = (self.index_of(origin), self.index_direction(dir));
        let (t0, t1) = self.clip(p0, d)?;
        let samples = ((t1 - t0) / step + 1e-9).floor() as usize + 1;
        (0..samples)
            .map(|s| t0 + s as f64 * step)
            .map(|t| self.value([p0[0] + t * d[0], p0[1] + t * d[1], p0[2] + t * d[2]]))
            .filter(|v| !v.is_nan())
            .reduce(f64::max)
    }
}

/// What [`RayCaster::image`] computes per pixel.
#[derive(Clone, Copy, Debug)]
pub enum Job<'a> {
    /// Composite through a transfer function.
    Composite(&'a TransferFunction, &'a Settings),
    /// The maximum or mean value, sampled every `step` world units.
    Reduce(Mode, f64),
}

/// Trilinear interpolation of eight corner values (bit 0 +x, bit 1 +y, bit 2 +z) at offsets `t`.
/// Where the ray `p0 + t·d` (index space) leaves the cube of blocks less than `reach` blocks
/// from block `b` along every axis (`reach` 1: block `b` itself), as a `t`.
#[inline]
fn cube_exit(p0: [f64; 3], d: [f64; 3], b: [usize; 3], reach: usize) -> f64 {
    let mut exit = f64::INFINITY;
    for a in 0..3 {
        let wall = if d[a] > 0.0 {
            (b[a] + reach) as f64
        } else if d[a] < 0.0 {
            b[a] as f64 - (reach - 1) as f64
        } else {
            continue;
        };
        exit = exit.min((wall * BLOCK as f64 - p0[a]) / d[a]);
    }
    exit
}

/// The smallest whole number at least `x`, for `x ≥ 0` (0 for negative `x` and NaN; at most
/// 2⁵³), as a float, without a call to libm.
fn ceil_not_negative(x: f64) -> f64 {
    let floor = (x.clamp(0.0, 9_007_199_254_740_992.0) as u64) as f64;
    if floor < x { floor + 1.0 } else { floor }
}

#[inline(always)]
fn trilinear(c: &[f64; 8], t: [f64; 3]) -> f64 {
    let lerp = |a: f64, b: f64, s: f64| a + (b - a) * s;
    let x00 = lerp(c[0], c[1], t[0]);
    let x10 = lerp(c[2], c[3], t[0]);
    let x01 = lerp(c[4], c[5], t[0]);
    let x11 = lerp(c[6], c[7], t[0]);
    lerp(lerp(x00, x10, t[1]), lerp(x01, x11, t[1]), t[2])
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// Seeded pseudo-random numbers (xorshift64) for the volume tests.
    pub(in crate::enrich::volume) fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        }
    }

    /// A volume of `f(i, j, k)` at each voxel, x fastest (shared with the shear-warp tests).
    pub(in crate::enrich::volume) fn volume(
        n: [usize; 3],
        spacing: [f64; 3],
        mut f: impl FnMut(f64, f64, f64) -> f64,
    ) -> Volume {
        let mut v = Vec::new();
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    v.push(f(i as f64, j as f64, k as f64) as f32);
                }
            }
        }
        Volume::new(n, Voxels::F32(v), spacing).expect("volume")
    }

    fn settings(step: f64, termination: f64) -> Settings {
        Settings { step, reference: 1.0, termination, classify: Classify::After, shading: None, gradient_opacity: None }
    }

    fn rng(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn mip_and_average_equal_the_exact_column_along_axis_aligned_rays() {
        let mut s = 7u64;
        let vol = volume([5, 4, 9], [1.0, 1.0, 2.0], |_, _, _| rng(&mut s));
        let caster = RayCaster::new(&vol).unwrap();
        for (i, j) in [(0, 0), (2, 1), (4, 3)] {
            let column: Vec<f64> = (0..9).map(|k| vol.value(i, j, k)).collect();
            let max = column.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            // Down the z axis from above; a step of one voxel (2 world units) lands the samples
            // half-way between voxel planes, a quarter voxel on them.
            let origin = [i as f64, j as f64, 100.0];
            let quarter = caster.reduce(origin, [0.0, 0.0, -1.0], Mode::Mip, 0.5).unwrap();
            assert!((quarter - max).abs() < 1e-6, "{quarter} vs {max}");
            let mean = caster.reduce(origin, [0.0, 0.0, -1.0], Mode::Average, 0.002).unwrap();
            // The mean of the piecewise-linear column: trapezoids over eight intervals.
            let exact = (0..8).map(|k| (column[k] + column[k + 1]) / 2.0).sum::<f64>() / 8.0;
            assert!((mean - exact).abs() < 1e-4, "{mean} vs {exact}");
        }
        // A ray beside the volume has nothing.
        assert_eq!(caster.reduce([10.0, 0.0, 100.0], [0.0, 0.0, -1.0], Mode::Mip, 0.5), None);
    }

    #[test]
    fn opacity_is_corrected_for_the_step() {
        // A constant volume of opacity 0.1 per voxel: 10 voxels of ray give 1 − 0.9^10 whatever
        // the step.
        let vol = volume([11, 3, 3], [1.0; 3], |_, _, _| 1.0);
        let caster = RayCaster::new(&vol).unwrap();
        let tf = TransferFunction::new(|_| [1.0, 1.0, 1.0], &[(0.0, 0.1), (2.0, 0.1)]).unwrap();
        let want = 1.0 - 0.9f64.powi(10);
        for step in [1.0, 0.5, 0.1, 1.0 / 3.0] {
            let c = caster.composite([-5.0, 1.0, 1.0], [1.0, 0.0, 0.0], &tf, &settings(step, 1.0));
            assert!((c[3] - want).abs() < 1e-9, "step {step}: {} vs {want}", c[3]);
            assert!((c[0] - c[3]).abs() < 1e-12, "white premultiplied");
        }
    }

    /// The composited colours of a few oblique rays through a smooth field.
    fn oblique(caster: &RayCaster, tf: &TransferFunction, s: &Settings) -> Vec<[f64; 4]> {
        (0..6)
            .map(|k| {
                let d = [1.0, 0.3 + 0.05 * k as f64, 0.2];
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                caster.composite([-1.0, 2.0 + k as f64, 3.0], d.map(|c| c / len), tf, s)
            })
            .collect()
    }

    #[test]
    fn compositing_converges_as_the_step_halves() {
        let vol = volume([24, 24, 24], [1.0; 3], |x, y, z| {
            ((x - 12.0).powi(2) + (y - 11.0).powi(2) + (z - 10.0).powi(2)).sqrt()
        });
        let caster = RayCaster::new(&vol).unwrap();
        let tf = TransferFunction::new(
            |v| [v / 20.0, 1.0 - v / 20.0, 0.5],
            &[(0.0, 0.3), (6.0, 0.05), (9.0, 0.4), (20.0, 0.0)],
        )
        .unwrap();
        let reference = oblique(&caster, &tf, &settings(1.0 / 256.0, 1.0));
        let error = |step: f64| {
            let got = oblique(&caster, &tf, &settings(step, 1.0));
            got.iter().zip(&reference).flat_map(|(a, b)| (0..4).map(move |c| (a[c] - b[c]).abs())).fold(0.0, f64::max)
        };
        let errors: Vec<f64> = [1.0, 0.5, 0.25, 0.125].map(error).to_vec();
        // The midpoint rule on a piecewise-smooth integrand: the error falls at least linearly
        // (second order between the kinks the trilinear cells put into it).
        for w in errors.windows(2) {
            let ratio = w[0] / w[1];
            assert!(ratio > 1.6, "{errors:?}");
        }
        assert!(errors[3] < 5e-3, "{errors:?}");
    }

    #[test]
    fn clear_reach_is_the_chessboard_distance_to_the_nearest_block_that_is_not_clear() {
        // Random grids (sparse and dense non-clear blocks) against a brute-force distance.
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        for (dims, one_in) in [([7, 5, 6], 9), ([9, 4, 3], 2), ([6, 6, 6], 60), ([3, 1, 2], 4)] {
            let clear: Vec<bool> = (0..dims.iter().product()).map(|_| next() % one_in != 0).collect();
            let reach = clear_reach(&clear, dims);
            let cap = *dims.iter().max().unwrap() as u32 + 1;
            let at = |n: usize| [n % dims[0], n / dims[0] % dims[1], n / (dims[0] * dims[1])];
            for (n, &r) in reach.iter().enumerate() {
                let p = at(n);
                let nearest = (0..clear.len())
                    .filter(|&m| !clear[m])
                    .map(|m| (0..3).map(|a| at(m)[a].abs_diff(p[a])).max().unwrap() as u32)
                    .min()
                    .map_or(cap, |d| d.min(cap));
                assert_eq!(r, nearest, "block {p:?} of {dims:?}");
            }
        }
    }

    #[test]
    fn block_ranges_are_the_ranges_of_each_blocks_voxels() {
        // Sides that are and are not one more than a multiple of the block, NaNs scattered and
        // one block of NaNs only.
        let dims = [19, 9, 26];
        let mut values: Vec<f32> =
            (0..dims.iter().product::<usize>()).map(|n| ((n * 7919) % 1009) as f32 - 500.0).collect();
        for n in (0..values.len()).step_by(13) {
            values[n] = f32::NAN;
        }
        let at = |i: usize, j: usize, k: usize| (k * dims[1] + j) * dims[0] + i;
        for k in 0..=8 {
            for j in 0..=8 {
                for i in 0..=8 {
                    values[at(i, j, k)] = f32::NAN;
                }
            }
        }
        let (ranges, block_dims) = block_ranges(&values, dims);
        assert_eq!(block_dims, [3, 1, 4]);
        for (b, &got) in ranges.iter().enumerate() {
            let (bx, by, bz) = (b % 3, b / 3 % 1, b / 3);
            let mut want = (f32::INFINITY, f32::NEG_INFINITY);
            for k in bz * BLOCK..=((bz + 1) * BLOCK).min(dims[2] - 1) {
                for j in by * BLOCK..=((by + 1) * BLOCK).min(dims[1] - 1) {
                    for i in bx * BLOCK..=((bx + 1) * BLOCK).min(dims[0] - 1) {
                        let v = values[at(i, j, k)];
                        if !v.is_nan() {
                            want = (want.0.min(v), want.1.max(v));
                        }
                    }
                }
            }
            assert_eq!(got, want, "block {b}");
        }
        assert!(ranges[0].0 > ranges[0].1, "the block of NaNs has no range: {:?}", ranges[0]);
    }

    #[test]
    fn skipping_clear_blocks_changes_nothing() {
        // A blob in a 40³ volume: most 8³ blocks are clear for a transfer function that is
        // transparent below 0.5.
        let vol = volume([40, 37, 33], [1.0, 1.5, 1.0], |x, y, z| {
            (-((x - 22.0).powi(2) + (y - 15.0).powi(2) + (z - 17.0).powi(2)) / 40.0).exp()
        });
        let caster = RayCaster::new(&vol).unwrap();
        let tf = TransferFunction::new(|v| [v, 0.5, 1.0 - v], &[(0.5, 0.0), (0.7, 0.3), (1.0, 0.9)]).unwrap();
        let clear = clear_blocks(&caster, &tf);
        let skipped = clear.iter().filter(|&&c| c).count();
        assert!(skipped > clear.len() / 2 && skipped < clear.len(), "{skipped} of {}", clear.len());
        let reach = clear_reach(&clear, caster.block_dims);
        assert!(reach.iter().any(|&r| r > 1), "{reach:?}");
        let mut s = settings(0.37, TERMINATION);
        for classify in [Classify::After, Classify::Before] {
            s.classify = classify;
            for k in 0..40 {
                let d = [1.0, 0.02 * k as f64 - 0.3, 0.45 - 0.01 * k as f64];
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let (o, d) = ([-5.0, 5.0 + 0.6 * k as f64, 10.0 + 0.3 * k as f64], d.map(|c| c / len));
                let all = caster.composite(o, d, &tf, &s);
                let skipping = caster.composite_skipping(o, d, &tf, &s, Some(&reach), false);
                assert_eq!(all, skipping, "ray {k}");
                let (plain, fast) = (caster.reduce_all(o, d, 0.25), caster.reduce(o, d, Mode::Mip, 0.25));
                assert_eq!(plain, fast, "ray {k}");
            }
        }
    }

    #[test]
    fn gradient_opacity_scales_opacity_by_the_gradient_magnitude() {
        // f = 2x: |∇f| = 2 everywhere. With full = 4 the opacity per voxel halves; with full = 1
        // it is unchanged; a uniform volume vanishes.
        let ramp = volume([12, 3, 3], [1.0; 3], |x, _, _| 2.0 * x);
        let caster = RayCaster::new(&ramp).unwrap();
        let tf = TransferFunction::new(|_| [1.0; 3], &[(0.0, 0.2), (30.0, 0.2)]).unwrap();
        let half = TransferFunction::new(|_| [1.0; 3], &[(0.0, 0.1), (30.0, 0.1)]).unwrap();
        let ray = ([-3.0, 1.0, 1.0], [1.0, 0.0, 0.0]);
        let with = |full| Settings { gradient_opacity: Some(full), ..settings(0.25, 1.0) };
        let scaled = caster.composite(ray.0, ray.1, &tf, &with(4.0));
        let plain = caster.composite(ray.0, ray.1, &half, &settings(0.25, 1.0));
        assert!((scaled[3] - plain[3]).abs() < 1e-9, "{scaled:?} vs {plain:?}");
        let full = caster.composite(ray.0, ray.1, &tf, &with(1.0));
        assert!((full[3] - (1.0 - 0.8f64.powi(11))).abs() < 1e-9, "{full:?}");
        let q = caster.gradient_quantile(0.5).unwrap();
        assert!((q - 2.0).abs() < 1e-9, "{q}");
        let uniform = volume([6, 6, 6], [1.0; 3], |_, _, _| 3.0);
        let flat = RayCaster::new(&uniform).unwrap();
        assert_eq!(flat.gradient_quantile(0.95), None);
        let c = flat.composite([-1.0, 2.0, 2.0], [1.0, 0.0, 0.0], &tf, &with(1.0));
        assert_eq!(c, [0.0; 4]);
    }

    #[test]
    fn label_functions_colour_listed_labels_only() {
        let red = [1.0, 0.0, 0.0];
        let tf = TransferFunction::labels(&[(2, red, 0.5), (5, [0.0, 0.0, 1.0], 1.0)]).unwrap();
        assert_eq!(tf.at(2.0), [1.0, 0.0, 0.0, 0.5]);
        assert_eq!(tf.at(2.4), [1.0, 0.0, 0.0, 0.5], "rounded to the nearest label");
        assert_eq!(tf.at(5.0), [0.0, 0.0, 1.0, 1.0]);
        for v in [0.0, 1.0, 3.0, 4.0, 6.0, 1000.0, -7.0] {
            assert_eq!(tf.at(v)[3], 0.0, "label {v} is not listed");
        }
        // Classified before interpolation: half-way between a label-2 voxel and background, red
        // at a quarter opacity (half of 0.5); the label value itself is never interpolated.
        let vol = volume([2, 2, 2], [1.0; 3], |x, _, _| if x == 0.0 { 0.0 } else { 2.0 });
        let caster = RayCaster::new(&vol).unwrap();
        let c = caster.classified([0.5, 0.5, 0.5], &tf, Classify::Before).unwrap();
        assert!((c[3] - 0.25).abs() < 1e-12 && (c[0] - 1.0).abs() < 1e-12 && c[2] == 0.0, "{c:?}");
    }

    #[test]
    fn an_image_is_its_rays_composited_one_by_one() {
        // The image corrects the table's opacities once, skips clear blocks and runs rows in
        // parallel; each pixel must still be exactly its ray's colour.
        let vol = volume([30, 26, 22], [1.0, 1.2, 1.0], |x, y, z| {
            (-((x - 14.0).powi(2) + (y - 12.0).powi(2) + (z - 10.0).powi(2)) / 30.0).exp()
        });
        let caster = RayCaster::new(&vol).unwrap();
        let tf = TransferFunction::new(|v| [v, 0.3, 1.0 - v], &[(0.3, 0.0), (0.6, 0.4), (1.0, 0.9)]).unwrap();
        let ray = |x: usize, y: usize| ([-5.0, 2.0 + 1.5 * x as f64, 1.0 + 1.2 * y as f64], [0.96, 0.2, 0.195]);
        for classify in [Classify::After, Classify::Before] {
            let s = Settings { classify, ..settings(0.37, TERMINATION) };
            let img = caster.image((16, 16), &ray, Job::Composite(&tf, &s));
            let shown = img.iter().filter(|p| p[3] > 0.1).count();
            assert!(shown > 20, "{shown}");
            for y in 0..16 {
                for x in 0..16 {
                    let (o, d) = ray(x, y);
                    assert_eq!(img[y * 16 + x], caster.composite(o, d, &tf, &s), "{classify:?} ({x}, {y})");
                }
            }
        }
    }

    #[test]
    fn early_termination_changes_no_channel_by_more_than_a_level() {
        let vol = volume([20, 20, 20], [1.0; 3], |x, y, z| x + 0.5 * y - 0.25 * z);
        let caster = RayCaster::new(&vol).unwrap();
        let tf = TransferFunction::new(|v| [v / 30.0, 0.2, 1.0 - v / 30.0], &[(-5.0, 0.0), (10.0, 0.6), (30.0, 0.9)])
            .unwrap();
        let mut rays = 0;
        for step in [0.5, 0.25] {
            let all = oblique(&caster, &tf, &settings(step, 1.0));
            let early = oblique(&caster, &tf, &settings(step, TERMINATION));
            for (a, b) in all.iter().zip(&early) {
                rays += usize::from(a[3] > TERMINATION);
                for c in 0..4 {
                    assert!((a[c] - b[c]).abs() * 255.0 <= 1.0, "{a:?} vs {b:?}");
                }
            }
        }
        assert!(rays > 0, "some rays reach the termination opacity");
    }

    #[test]
    fn classifying_before_interpolates_opacity_weighted_colours() {
        // Two voxel planes: value 0 (transparent) and 1 (opaque red). Half-way, classifying
        // after reads value 0.5; before mixes a transparent and a red voxel: red at half opacity.
        let vol = volume([2, 2, 2], [1.0; 3], |x, _, _| x);
        let caster = RayCaster::new(&vol).unwrap();
        let tf = TransferFunction::new(
            |v| if v > 0.75 { [1.0, 0.0, 0.0] } else { [0.0, 0.0, 1.0] },
            &[(0.0, 0.0), (1.0, 1.0)],
        )
        .unwrap();
        let before = caster.classified([0.5, 0.5, 0.5], &tf, Classify::Before).unwrap();
        assert!((before[3] - 0.5).abs() < 1e-3 && before[0] > 0.999 && before[2] < 1e-9, "{before:?}");
        let after = caster.classified([0.5, 0.5, 0.5], &tf, Classify::After).unwrap();
        assert!((after[3] - 0.5).abs() < 1e-3 && after[2] > 0.999, "{after:?}");
    }

    #[test]
    fn missing_voxels_are_transparent_and_bad_transfer_functions_say_why() {
        let vol = volume([4, 4, 4], [1.0; 3], |x, _, _| if x == 1.0 { f64::NAN } else { 1.0 });
        let caster = RayCaster::new(&vol).unwrap();
        // The ray along x meets NaN cells for x in [0, 2]; only [2, 3] remains.
        let mip = caster.reduce([-1.0, 1.0, 1.0], [1.0, 0.0, 0.0], Mode::Mip, 0.1);
        assert_eq!(mip, Some(1.0));
        let tf = TransferFunction::new(|_| [1.0; 3], &[(0.0, 0.5), (1.0, 0.5)]).unwrap();
        let c = caster.composite([-1.0, 1.0, 1.0], [1.0, 0.0, 0.0], &tf, &settings(0.1, 1.0));
        assert!((c[3] - 0.5).abs() < 1e-9, "one voxel of 0.5 opacity: {c:?}");
        assert!(TransferFunction::new(|_| [0.0; 3], &[]).is_err());
        let err = TransferFunction::new(|_| [0.0; 3], &[(1.0, 0.1), (0.5, 0.2)]).unwrap_err();
        assert!(err.contains("must rise"), "{err}");
        assert!(TransferFunction::new(|_| [0.0; 3], &[(1.0, 1.5)]).is_err());
        assert!(TransferFunction::labels(&[]).is_err());
        assert!(TransferFunction::labels(&[(0, [0.0; 3], 0.5), (70_000, [0.0; 3], 0.5)]).is_err());
        assert!(TransferFunction::labels(&[(1, [0.0; 3], 2.0)]).is_err());
        let thin = volume([4, 1, 4], [1.0; 3], |_, _, _| 0.0);
        assert!(RayCaster::new(&thin).unwrap_err().contains("at least two voxels along y"));
    }
}
