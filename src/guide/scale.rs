//! Scales: maps from a data domain to a pixel range, with ticks.
//!
//! Every constructor takes the raw data extent and the pixel range; a range may run backwards
//! (a y axis goes up: `(bottom, top)`). Domains are stored ascending (reversed bounds are swapped:
//! orientation comes from the range). Degenerate domains are widened by documented rules:
//!
//! - linear: all values `v` → `v ± |v|/10`, or `v ± 1` when `v` is 0 (see [`pad_degenerate`]);
//! - log: all values `v` → `v/10 .. v·10`;
//! - time: all instants `v` → `v ± 1 day`;
//!
//! and a NaN or infinite bound is an error. Mapping never panics: a value the scale cannot place
//! (NaN, or ≤ 0 on a log scale) maps to NaN.

use std::collections::HashMap;
use std::fmt;

use super::format::{format_log_tick, format_ticks};
use super::ticks::{MAX_TARGET, TickSet, exact_decimal, extended, pad_degenerate};
use super::time::{MAX_ABS_MS, nice_time_domain, time_ticks};

/// Ticks a [`LogScale`] aims at unless told otherwise.
pub const DEFAULT_LOG_TICK_TARGET: usize = 10;
/// Half-width of the domain of a [`TimeScale`] whose instants are all the same: one day.
pub const TIME_PAD_MS: f64 = 86_400_000.0;

/// One tick: data value, pixel position along the range, and label.
#[derive(Clone, Debug, PartialEq)]
pub struct Tick {
    /// The data value (for a band scale, the band index).
    pub value: f64,
    /// Position in pixels along the scale's range.
    pub position: f64,
    /// The label, formatted consistently across the axis.
    pub label: String,
}

/// Why a scale could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum ScaleError {
    /// Every value is missing, NaN or infinite.
    NoFiniteValues,
    /// A domain bound is NaN or infinite.
    NonFiniteDomain {
        /// Lower bound as given.
        min: f64,
        /// Upper bound as given.
        max: f64,
    },
    /// A pixel range bound is NaN or infinite.
    NonFiniteRange {
        /// Start of the range as given.
        start: f64,
        /// End of the range as given.
        end: f64,
    },
    /// A log scale was given a value ≤ 0.
    LogNonPositive {
        /// The smallest value.
        min: f64,
    },
    /// A time domain lies beyond what the calendar can represent.
    TimeOutOfRange {
        /// Lower bound in ms since the epoch.
        min: f64,
        /// Upper bound in ms since the epoch.
        max: f64,
    },
    /// A band scale was given no categories.
    EmptyCategories,
    /// Band padding outside its valid range.
    InvalidPadding {
        /// Inner padding as given.
        inner: f64,
        /// Outer padding as given.
        outer: f64,
    },
}

impl fmt::Display for ScaleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScaleError::NoFiniteValues => write!(
                f,
                "no finite values to scale: every value is missing, NaN or infinite; check the column, or filter out missing values"
            ),
            ScaleError::NonFiniteDomain { min, max } => write!(
                f,
                "the data extent {min:?}..{max:?} is not finite; filter out NaN and infinite values before scaling"
            ),
            ScaleError::NonFiniteRange { start, end } => {
                write!(f, "the pixel range {start:?}..{end:?} is not finite; check the chart size and margins")
            }
            ScaleError::LogNonPositive { min } => write!(
                f,
                "a log scale needs values greater than 0, but the smallest value is {min:?}; use a linear scale, or filter out values ≤ 0"
            ),
            ScaleError::TimeOutOfRange { min, max } => write!(
                f,
                "the time extent {min:?}..{max:?} ms is beyond ±{MAX_ABS_MS:e} ms (about 253,000 years from 1970); check that the column holds milliseconds since the epoch"
            ),
            ScaleError::EmptyCategories => {
                write!(
                    f,
                    "a band scale needs at least one category, but there are none; check that the column has values"
                )
            }
            ScaleError::InvalidPadding { inner, outer } => write!(
                f,
                "band padding must be finite with inner in 0..=1 and outer ≥ 0, but inner is {inner:?} and outer is {outer:?}"
            ),
        }
    }
}

impl std::error::Error for ScaleError {}

/// The smallest and largest finite values, ignoring NaN and ±∞; [`ScaleError::NoFiniteValues`]
/// if there are none.
pub fn extent(values: impl IntoIterator<Item = f64>) -> Result<(f64, f64), ScaleError> {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |acc: Option<(f64, f64)>, v| Some(acc.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v)))))
        .ok_or(ScaleError::NoFiniteValues)
}

fn check_range(range: (f64, f64)) -> Result<(), ScaleError> {
    if range.0.is_finite() && range.1.is_finite() {
        Ok(())
    } else {
        Err(ScaleError::NonFiniteRange { start: range.0, end: range.1 })
    }
}

/// Finite bounds, ascending.
fn check_domain(domain: (f64, f64)) -> Result<(f64, f64), ScaleError> {
    let (a, b) = domain;
    if !a.is_finite() || !b.is_finite() {
        return Err(ScaleError::NonFiniteDomain { min: a, max: b });
    }
    Ok(if a <= b { (a, b) } else { (b, a) })
}

/// Where `v` lies between `a` (0) and `b` (1), without overflow; 0 when `a == b`.
fn unlerp(a: f64, b: f64, v: f64) -> f64 {
    let den = b * 0.5 - a * 0.5;
    if den == 0.0 { 0.0 } else { (v * 0.5 - a * 0.5) / den }
}

/// The point a fraction `t` of the way from `a` to `b`, without overflow; exact at 0 and 1.
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a * (1.0 - t) + b * t
}

/// Half the width of an interval, never overflowing.
fn half_width(lo: f64, hi: f64) -> f64 {
    hi * 0.5 - lo * 0.5
}

/// A linear scale.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearScale {
    domain: (f64, f64),
    range: (f64, f64),
    ticks: Vec<Tick>,
}

impl LinearScale {
    /// A linear scale from the data extent `domain` onto `range`, with about `tick_target` ticks
    /// (0 for none). With `nice`, the domain is widened to the outermost of the extended-Wilkinson
    /// ticks that cover it. Degenerate domains: see the module docs.
    pub fn new(
        domain: (f64, f64),
        range: (f64, f64),
        nice: bool,
        tick_target: usize,
    ) -> Result<LinearScale, ScaleError> {
        check_range(range)?;
        let (mut lo, mut hi) = check_domain(domain)?;
        let width = hi - lo;
        if !width.is_normal() && !width.is_infinite() {
            (lo, hi) = pad_degenerate(lo);
        }
        let set = if nice {
            let set = extended(lo, hi, tick_target.max(2), true);
            if let (Some(first), Some(last)) = (set.values.first(), set.values.last()) {
                (lo, hi) = (lo.min(*first), hi.max(*last));
            }
            set
        } else {
            within_domain_ticks(lo, hi, tick_target)
        };
        let mut scale = LinearScale { domain: (lo, hi), range, ticks: Vec::new() };
        if tick_target > 0 {
            let tol = half_width(lo, hi) * 2e-9;
            let values: Vec<f64> = set.values.into_iter().filter(|v| *v >= lo - tol && *v <= hi + tol).collect();
            scale.ticks = make_ticks(&values, format_ticks(&values, set.step), |v| scale.map(v));
        }
        Ok(scale)
    }

    /// Pixel position of `v` (NaN for NaN; values outside the domain extrapolate).
    pub fn map(&self, v: f64) -> f64 {
        lerp(self.range.0, self.range.1, unlerp(self.domain.0, self.domain.1, v))
    }

    /// Data value at pixel `px` (the domain start if the range has zero length).
    pub fn invert(&self, px: f64) -> f64 {
        lerp(self.domain.0, self.domain.1, unlerp(self.range.0, self.range.1, px))
    }

    /// Ticks with pixel positions and labels.
    pub fn ticks(&self) -> Vec<Tick> {
        self.ticks.clone()
    }

    /// The (possibly padded or niced) domain, ascending.
    pub fn domain(&self) -> (f64, f64) {
        self.domain
    }

    /// The pixel range, as given.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }
}

fn make_ticks(values: &[f64], labels: Vec<String>, map: impl Fn(f64) -> f64) -> Vec<Tick> {
    values.iter().zip(labels).map(|(&value, label)| Tick { value, position: map(value), label }).collect()
}

/// A base-10 logarithmic scale.
#[derive(Clone, Debug, PartialEq)]
pub struct LogScale {
    domain: (f64, f64),
    /// `log10` of the domain bounds.
    log_domain: (f64, f64),
    range: (f64, f64),
    tick_target: usize,
}

impl LogScale {
    /// A log scale from the data extent `domain` onto `range`. Every value must be > 0
    /// ([`ScaleError::LogNonPositive`] names the smallest). Identical values `v` give `v/10..v·10`;
    /// with `nice`, the domain is widened to powers of ten. Aims at
    /// [`DEFAULT_LOG_TICK_TARGET`] ticks (see [`LogScale::with_tick_target`]).
    pub fn new(domain: (f64, f64), range: (f64, f64), nice: bool) -> Result<LogScale, ScaleError> {
        check_range(range)?;
        let (lo, hi) = check_domain(domain)?;
        if lo <= 0.0 {
            return Err(ScaleError::LogNonPositive { min: lo });
        }
        let mut bounds = (lo, hi);
        if hi.log10() - lo.log10() < 1e-12 {
            bounds = ((lo / 10.0).max(f64::from_bits(1)), (hi * 10.0).min(f64::MAX));
        }
        let (mut l0, mut l1) = (bounds.0.log10(), bounds.1.log10());
        if nice {
            (l0, l1) = (l0.floor(), l1.ceil());
            bounds = (pow10_clamped(l0), pow10_clamped(l1));
        }
        Ok(LogScale { domain: bounds, log_domain: (l0, l1), range, tick_target: DEFAULT_LOG_TICK_TARGET })
    }

    /// The same scale aiming at `target` ticks (0 for none).
    pub fn with_tick_target(mut self, target: usize) -> LogScale {
        self.tick_target = target;
        self
    }

    /// Pixel position of `v`; NaN for `v ≤ 0` or NaN.
    pub fn map(&self, v: f64) -> f64 {
        if v.is_nan() || v <= 0.0 {
            return f64::NAN;
        }
        let (l0, l1) = self.log_domain;
        lerp(self.range.0, self.range.1, (v.log10() - l0) / (l1 - l0))
    }

    /// Data value at pixel `px`.
    pub fn invert(&self, px: f64) -> f64 {
        let (l0, l1) = self.log_domain;
        10f64.powf(lerp(l0, l1, unlerp(self.range.0, self.range.1, px)))
    }

    /// Ticks at powers of ten; when `3·(decades − 1) + 1` ticks fit the target also at 2× and 5×;
    /// with no power of ten inside, at integer multiples `m·10ᵉ`; with more decades than the
    /// target only at every k-th power (exponents divisible by k); ordinary linear ticks if all
    /// of these give fewer than two. Labels like `1`, `20`,
    /// `1k`, `10⁻³`.
    pub fn ticks(&self) -> Vec<Tick> {
        let target = self.tick_target.min(MAX_TARGET);
        if target == 0 {
            return Vec::new();
        }
        let (values, labels) = match self.log_tick_values(target) {
            values if values.len() >= 2 => {
                let labels = values.iter().map(|&v| format_log_tick(v)).collect();
                (values, labels)
            }
            _ => self.linear_fallback(target),
        };
        make_ticks(&values, labels, |v| self.map(v))
    }

    fn inside(&self, v: f64) -> bool {
        let l = v.log10();
        v > 0.0 && l >= self.log_domain.0 - 1e-9 && l <= self.log_domain.1 + 1e-9
    }

    /// `m × 10^e` for each multiplier `m` and each exponent in `lo..=hi` (at most ~650 of them),
    /// kept if inside the domain.
    fn multiples(&self, lo: i32, hi: i32, multipliers: &[i128], stride: i32) -> Vec<f64> {
        (lo..=hi)
            .filter(|e| e.rem_euclid(stride.max(1)) == 0)
            .flat_map(|e| multipliers.iter().map(move |&m| exact_decimal(m, e)))
            .filter(|&v| self.inside(v))
            .collect()
    }

    fn log_tick_values(&self, target: usize) -> Vec<f64> {
        let (l0, l1) = self.log_domain;
        let lo = (l0 - 1e-9).ceil() as i32;
        let hi = (l1 + 1e-9).floor() as i32;
        let decades = (i64::from(hi) - i64::from(lo) + 1).max(0) as usize;
        let ones_twos_fives = || self.multiples(lo.saturating_sub(1), hi, &[1, 2, 5], 1);
        if decades > target {
            let stride = decades.div_ceil(target) as i32;
            self.multiples(lo, hi, &[1], stride)
        } else if decades == 0 {
            // No power of ten inside: every integer multiple, if that is not too many.
            let all = self.multiples(lo.saturating_sub(1), hi, &[1, 2, 3, 4, 5, 6, 7, 8, 9], 1);
            if all.len() <= target { all } else { ones_twos_fives() }
        } else if 3 * (decades - 1) < target {
            ones_twos_fives()
        } else {
            self.multiples(lo, hi, &[1], 1)
        }
    }

    /// Ordinary linear ticks, for domains too narrow for multiples of powers of ten.
    fn linear_fallback(&self, target: usize) -> (Vec<f64>, Vec<String>) {
        let set = extended(self.domain.0, self.domain.1, target, false);
        let values: Vec<f64> = set.values.into_iter().filter(|&v| self.inside(v)).collect();
        let labels = format_ticks(&values, set.step);
        (values, labels)
    }

    /// The (possibly padded or niced) domain, ascending.
    pub fn domain(&self) -> (f64, f64) {
        self.domain
    }

    /// The pixel range, as given.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }
}

/// `10^l`, exact for integer `l`, kept within the positive finite `f64` range.
fn pow10_clamped(l: f64) -> f64 {
    let v = if l.fract() == 0.0 && l.abs() < 400.0 { exact_decimal(1, l as i32) } else { 10f64.powf(l) };
    v.clamp(f64::from_bits(1), f64::MAX)
}

/// A linear scale over instants in milliseconds since the Unix epoch (UTC), with calendar ticks.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeScale {
    domain: (f64, f64),
    range: (f64, f64),
    tick_target: usize,
}

impl TimeScale {
    /// A time scale from the extent `domain` (ms since the epoch) onto `range`, with about
    /// `tick_target` ticks. Identical instants `v` give `v ± 1 day`; bounds beyond
    /// ±[`MAX_ABS_MS`] are [`ScaleError::TimeOutOfRange`].
    pub fn new(domain: (f64, f64), range: (f64, f64), tick_target: usize) -> Result<TimeScale, ScaleError> {
        check_range(range)?;
        let (mut lo, mut hi) = check_domain(domain)?;
        if lo < -MAX_ABS_MS || hi > MAX_ABS_MS {
            return Err(ScaleError::TimeOutOfRange { min: lo, max: hi });
        }
        if lo == hi {
            (lo, hi) = ((lo - TIME_PAD_MS).max(-MAX_ABS_MS), (hi + TIME_PAD_MS).min(MAX_ABS_MS));
        }
        Ok(TimeScale { domain: (lo, hi), range, tick_target })
    }

    /// The same scale with its domain widened to the calendar boundaries of its tick interval
    /// (e.g. month or year starts); unchanged if a boundary is out of range.
    pub fn niced(mut self) -> TimeScale {
        if let Some(d) = nice_time_domain(self.domain.0, self.domain.1, self.tick_target.max(2)) {
            self.domain = d;
        }
        self
    }

    /// Pixel position of the instant `ms`.
    pub fn map(&self, ms: f64) -> f64 {
        lerp(self.range.0, self.range.1, unlerp(self.domain.0, self.domain.1, ms))
    }

    /// Instant (ms) at pixel `px`.
    pub fn invert(&self, px: f64) -> f64 {
        lerp(self.domain.0, self.domain.1, unlerp(self.range.0, self.range.1, px))
    }

    /// Calendar ticks (see `time::time_ticks`) with pixel positions.
    pub fn ticks(&self) -> Vec<Tick> {
        time_ticks(self.domain.0, self.domain.1, self.tick_target)
            .into_iter()
            .map(|(value, label)| Tick { value, position: self.map(value), label })
            .collect()
    }

    /// The (possibly padded or niced) domain in ms, ascending.
    pub fn domain(&self) -> (f64, f64) {
        self.domain
    }

    /// The pixel range, as given.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }
}

/// Equal-width bands for categories, with inner and outer padding given as fractions of the
/// distance between band starts (as in d3's band scale).
///
/// With `n` bands, `step = |range| / max(1, n − inner + 2·outer)`, each band is
/// `step·(1 − inner)` wide, neighbours are `step·inner` apart and the outer gaps are
/// `step·outer`. Band 0 sits at the `range.0` end.
#[derive(Clone, Debug, PartialEq)]
pub struct BandScale {
    categories: Vec<String>,
    index: HashMap<String, usize>,
    range: (f64, f64),
    inner: f64,
    outer: f64,
    /// Signed distance between band starts (negative for a reversed range).
    step: f64,
}

impl BandScale {
    /// A band scale for `categories` (duplicates after the first are dropped) onto `range`.
    /// `padding_inner` must be in 0..=1 and `padding_outer` ≥ 0, both finite.
    pub fn new(
        categories: Vec<String>,
        range: (f64, f64),
        padding_inner: f64,
        padding_outer: f64,
    ) -> Result<BandScale, ScaleError> {
        check_range(range)?;
        let valid = (0.0..=1.0).contains(&padding_inner) && padding_outer >= 0.0 && padding_outer.is_finite();
        if !valid {
            return Err(ScaleError::InvalidPadding { inner: padding_inner, outer: padding_outer });
        }
        let mut index = HashMap::new();
        let mut unique = Vec::new();
        for c in categories {
            if !index.contains_key(&c) {
                index.insert(c.clone(), unique.len());
                unique.push(c);
            }
        }
        if unique.is_empty() {
            return Err(ScaleError::EmptyCategories);
        }
        let slots = (unique.len() as f64 - padding_inner + 2.0 * padding_outer).max(1.0);
        let step = range.1 / slots - range.0 / slots;
        Ok(BandScale { categories: unique, index, range, inner: padding_inner, outer: padding_outer, step })
    }

    /// Index of the band for `category`, if it is one.
    pub fn band_of(&self, category: &str) -> Option<usize> {
        self.index.get(category).copied()
    }

    /// The categories in band order.
    pub fn categories(&self) -> &[String] {
        &self.categories
    }

    /// Number of bands.
    pub fn len(&self) -> usize {
        self.categories.len()
    }

    /// Whether there are no bands (never true for a constructed scale).
    pub fn is_empty(&self) -> bool {
        self.categories.is_empty()
    }

    /// Smaller pixel coordinate of band `i` (left or top edge); indices past the end extrapolate.
    pub fn start(&self, i: usize) -> f64 {
        let a = self.range.0 + self.step * (self.outer + i as f64);
        let b = a + self.step * (1.0 - self.inner);
        a.min(b)
    }

    /// Pixel coordinate of the centre of band `i`.
    pub fn center(&self, i: usize) -> f64 {
        self.map(i as f64)
    }

    /// Width of every band in pixels.
    pub fn bandwidth(&self) -> f64 {
        self.step.abs() * (1.0 - self.inner)
    }

    /// Distance in pixels between the starts of neighbouring bands.
    pub fn step(&self) -> f64 {
        self.step.abs()
    }

    /// The band containing pixel `px` (not counting the gaps between bands).
    pub fn index_at(&self, px: f64) -> Option<usize> {
        if self.step == 0.0 || !px.is_finite() {
            return None;
        }
        let t = (px - self.range.0) / self.step - self.outer;
        let i = t.floor();
        let inside = i >= 0.0 && i < self.categories.len() as f64 && t - i <= 1.0 - self.inner;
        inside.then_some(i as usize)
    }

    /// Centre of the band with (possibly fractional) index `v`.
    pub fn map(&self, v: f64) -> f64 {
        self.range.0 + self.step * (self.outer + v + (1.0 - self.inner) / 2.0)
    }

    /// One tick per band, at its centre, labelled with the category.
    pub fn ticks(&self) -> Vec<Tick> {
        self.categories
            .iter()
            .enumerate()
            .map(|(i, c)| Tick { value: i as f64, position: self.center(i), label: c.clone() })
            .collect()
    }

    /// Band indices as a numeric domain: `(0, number of bands)`.
    pub fn domain(&self) -> (f64, f64) {
        (0.0, self.categories.len() as f64)
    }

    /// The pixel range, as given.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }
}

/// Ticks inside a fixed domain: the extended search restricted to the domain, or when that
/// labels fewer than `min(target, 3)` values (short domains with awkward ends, where the strict
/// search may settle for two far-apart ticks), the nice ticks of a loose search that fall inside.
fn within_domain_ticks(lo: f64, hi: f64, target: usize) -> TickSet {
    let inside = |v: &f64| *v >= lo && *v <= hi;
    let wanted = target.clamp(2, 3);
    let strict = extended(lo, hi, target, false);
    if strict.values.iter().filter(|v| inside(v)).count() >= wanted || target < 2 {
        return strict;
    }
    for t in target..target + 4 {
        let mut loose = extended(lo, hi, t, true);
        loose.values.retain(inside);
        if loose.values.len() >= wanted {
            return loose;
        }
    }
    strict
}

/// Any scale.
#[derive(Clone, Debug, PartialEq)]
pub enum Scale {
    /// Linear numbers.
    Linear(LinearScale),
    /// Base-10 logarithmic numbers.
    Log(LogScale),
    /// Instants in ms since the epoch.
    Time(TimeScale),
    /// Categories.
    Band(BandScale),
}

impl Scale {
    /// Pixel position of `v` (for a band scale, `v` is a band index and maps to its centre).
    pub fn map(&self, v: f64) -> f64 {
        match self {
            Scale::Linear(s) => s.map(v),
            Scale::Log(s) => s.map(v),
            Scale::Time(s) => s.map(v),
            Scale::Band(s) => s.map(v),
        }
    }

    /// Data value at pixel `px`; `None` for a band scale (use [`BandScale::index_at`]).
    pub fn invert(&self, px: f64) -> Option<f64> {
        match self {
            Scale::Linear(s) => Some(s.invert(px)),
            Scale::Log(s) => Some(s.invert(px)),
            Scale::Time(s) => Some(s.invert(px)),
            Scale::Band(_) => None,
        }
    }

    /// Ticks with pixel positions and labels.
    pub fn ticks(&self) -> Vec<Tick> {
        match self {
            Scale::Linear(s) => s.ticks(),
            Scale::Log(s) => s.ticks(),
            Scale::Time(s) => s.ticks(),
            Scale::Band(s) => s.ticks(),
        }
    }

    /// The domain, ascending (band scales: `(0, number of bands)`).
    pub fn domain(&self) -> (f64, f64) {
        match self {
            Scale::Linear(s) => s.domain(),
            Scale::Log(s) => s.domain(),
            Scale::Time(s) => s.domain(),
            Scale::Band(s) => s.domain(),
        }
    }

    /// The pixel range, as given.
    pub fn range(&self) -> (f64, f64) {
        match self {
            Scale::Linear(s) => s.range(),
            Scale::Log(s) => s.range(),
            Scale::Time(s) => s.range(),
            Scale::Band(s) => s.range(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
    }

    fn labels(ticks: &[Tick]) -> Vec<&str> {
        ticks.iter().map(|t| t.label.as_str()).collect()
    }

    #[test]
    fn linear_maps_and_inverts() {
        let s = LinearScale::new((0.0, 10.0), (100.0, 300.0), false, 5).unwrap();
        assert_eq!(s.map(0.0), 100.0);
        assert_eq!(s.map(10.0), 300.0);
        assert_eq!(s.map(2.5), 150.0);
        for v in [-3.0, 0.1, 4.2, 9.99, 20.0] {
            assert!(close(s.invert(s.map(v)), v), "{v}");
        }
        assert!(s.map(f64::NAN).is_nan());
    }

    #[test]
    fn reversed_range_puts_low_values_at_the_bottom() {
        let s = LinearScale::new((0.0, 100.0), (400.0, 0.0), true, 5).unwrap();
        assert_eq!(s.map(0.0), 400.0);
        assert_eq!(s.map(100.0), 0.0);
        assert_eq!(s.invert(100.0), 75.0);
        let t = s.ticks();
        assert_eq!(labels(&t), ["0", "25", "50", "75", "100"]);
        assert!(t.windows(2).all(|w| w[1].position < w[0].position));
    }

    #[test]
    fn nice_domain_contains_the_data() {
        let s = LinearScale::new((-1.3, 7.9), (0.0, 500.0), true, 5).unwrap();
        assert_eq!(s.domain(), (-2.0, 8.0));
        let t = s.ticks();
        assert_eq!(labels(&t), ["\u{2212}2", "0", "2", "4", "6", "8"]);
        assert_eq!(t.first().map(|t| t.position), Some(0.0));
        assert_eq!(t.last().map(|t| t.position), Some(500.0));
        // Without nice, the domain is the data and ticks stay inside it.
        let s = LinearScale::new((-1.3, 7.9), (0.0, 500.0), false, 5).unwrap();
        assert_eq!(s.domain(), (-1.3, 7.9));
        assert!(
            s.ticks().iter().all(|t| t.value >= -1.3 && t.value <= 7.9 && t.position >= 0.0 && t.position <= 500.0)
        );
        assert!(s.ticks().len() >= 3);
    }

    #[test]
    fn degenerate_linear_domains() {
        assert_eq!(LinearScale::new((5.0, 5.0), (0.0, 1.0), false, 5).unwrap().domain(), (4.5, 5.5));
        assert_eq!(LinearScale::new((0.0, 0.0), (0.0, 1.0), false, 5).unwrap().domain(), (-1.0, 1.0));
        assert_eq!(LinearScale::new((-20.0, -20.0), (0.0, 1.0), false, 5).unwrap().domain(), (-22.0, -18.0));
        assert_eq!(LinearScale::new((9.0, 1.0), (0.0, 1.0), false, 5).unwrap().domain(), (1.0, 9.0));
        assert!(LinearScale::new((0.0, 1.0), (0.0, 1.0), true, 0).unwrap().ticks().is_empty());
        // A zero-length range maps everything to one pixel and inverts to the domain start.
        let s = LinearScale::new((0.0, 1.0), (5.0, 5.0), false, 5).unwrap();
        assert_eq!(s.map(0.7), 5.0);
        assert_eq!(s.invert(5.0), 0.0);
    }

    #[test]
    fn bad_bounds_are_errors() {
        let e = LinearScale::new((f64::NAN, 1.0), (0.0, 1.0), true, 5).unwrap_err();
        assert!(matches!(e, ScaleError::NonFiniteDomain { .. }));
        assert!(e.to_string().contains("NaN") && e.to_string().contains("filter"));
        let e = LinearScale::new((0.0, 1.0), (0.0, f64::INFINITY), true, 5).unwrap_err();
        assert_eq!(e, ScaleError::NonFiniteRange { start: 0.0, end: f64::INFINITY });
        assert_eq!(extent([f64::NAN, 3.0, -1.0, f64::INFINITY]), Ok((-1.0, 3.0)));
        assert_eq!(extent([f64::NAN]), Err(ScaleError::NoFiniteValues));
        assert_eq!(extent(Vec::new()), Err(ScaleError::NoFiniteValues));
    }

    #[test]
    fn huge_domains_map_without_overflow() {
        let s = LinearScale::new((-f64::MAX, f64::MAX), (0.0, 100.0), true, 5).unwrap();
        assert_eq!(s.map(0.0), 50.0);
        assert_eq!(s.map(f64::MAX), 100.0);
        assert!(close(s.invert(75.0), f64::MAX / 2.0));
        let s = LinearScale::new((0.0, 1e-300), (0.0, 100.0), true, 5).unwrap();
        assert!(close(s.map(5e-301), 50.0));
    }

    #[test]
    fn log_scale_rejects_non_positive_values() {
        let e = LogScale::new((-3.0, 100.0), (0.0, 1.0), true).unwrap_err();
        assert_eq!(e, ScaleError::LogNonPositive { min: -3.0 });
        let msg = e.to_string();
        assert!(msg.contains("-3.0") && msg.contains("linear scale"), "{msg}");
        assert!(LogScale::new((0.0, 100.0), (0.0, 1.0), true).is_err());
    }

    #[test]
    fn log_scale_nices_to_powers_of_ten() {
        let s = LogScale::new((3.0, 700.0), (0.0, 300.0), true).unwrap();
        assert_eq!(s.domain(), (1.0, 1000.0));
        assert_eq!(s.map(1.0), 0.0);
        assert_eq!(s.map(10.0), 100.0);
        assert!(close(s.invert(200.0), 100.0));
        assert!(s.map(0.0).is_nan() && s.map(-1.0).is_nan());
        let t = s.ticks();
        assert_eq!(labels(&t), ["1", "2", "5", "10", "20", "50", "100", "200", "500", "1k"]);
        // Fewer ticks wanted: powers of ten only.
        let t = s.clone().with_tick_target(4).ticks();
        assert_eq!(labels(&t), ["1", "10", "100", "1k"]);
    }

    #[test]
    fn log_ticks_across_many_decades_and_within_one() {
        let s = LogScale::new((1e-10, 1e10), (0.0, 1.0), false).unwrap();
        assert_eq!(labels(&s.ticks()), ["10⁻⁹", "10⁻⁶", "10⁻³", "1", "1k", "1M", "1G"]);
        let s = LogScale::new((20.0, 80.0), (0.0, 1.0), false).unwrap();
        assert_eq!(labels(&s.ticks()), ["20", "30", "40", "50", "60", "70", "80"]);
        let s = LogScale::new((21.0, 29.0), (0.0, 1.0), false).unwrap();
        let t = s.ticks();
        assert!(t.len() >= 2 && t.iter().all(|t| t.value >= 21.0 && t.value <= 29.0), "{t:?}");
        let s = LogScale::new((5e-324, f64::MAX), (0.0, 1.0), true).unwrap();
        assert!(s.ticks().len() <= DEFAULT_LOG_TICK_TARGET + 1);
    }

    #[test]
    fn degenerate_log_domain() {
        let s = LogScale::new((50.0, 50.0), (0.0, 1.0), false).unwrap();
        assert_eq!(s.domain(), (5.0, 500.0));
        assert!(close(s.map(50.0), 0.5));
    }

    #[test]
    fn time_scale() {
        let day = TIME_PAD_MS;
        let s = TimeScale::new((10.0 * day, 10.0 * day), (0.0, 200.0), 5).unwrap();
        assert_eq!(s.domain(), (9.0 * day, 11.0 * day));
        assert_eq!(s.map(10.0 * day), 100.0);
        assert_eq!(s.invert(100.0), 10.0 * day);
        // 1970-01-01 .. 1970-01-11 with 5 ticks: every other day, labelled by day.
        let s = TimeScale::new((0.0, 10.0 * day), (0.0, 100.0), 5).unwrap();
        let t = s.ticks();
        assert_eq!(labels(&t), ["Jan 01", "Jan 03", "Jan 05", "Jan 07", "Jan 09", "Jan 11"]);
        assert_eq!(t[1].position, 20.0);
        let e = TimeScale::new((0.0, 1e300), (0.0, 1.0), 5).unwrap_err();
        assert!(matches!(e, ScaleError::TimeOutOfRange { .. }));
        let s = TimeScale::new((0.5 * day, 9.5 * day), (0.0, 1.0), 5).unwrap().niced();
        assert_eq!(s.domain(), (0.0, 10.0 * day));
    }

    #[test]
    fn band_geometry_fills_the_range() {
        let cats: Vec<String> = ["a", "b", "c", "d"].map(String::from).to_vec();
        let s = BandScale::new(cats.clone(), (0.0, 500.0), 0.2, 0.1).unwrap();
        let n = 4.0;
        let total = n * s.bandwidth() + (n - 1.0) * s.step() * 0.2 + 2.0 * s.step() * 0.1;
        assert!(close(total, 500.0));
        assert!(close(s.start(0), s.step() * 0.1));
        assert!(close(s.start(3) + s.bandwidth() + s.step() * 0.1, 500.0));
        assert!(close(s.center(1), s.start(1) + s.bandwidth() / 2.0));
        assert_eq!(s.band_of("c"), Some(2));
        assert_eq!(s.band_of("z"), None);
        assert_eq!(s.index_at(s.center(2)), Some(2));
        assert_eq!(s.index_at(s.start(1) - 1.0), None, "gap between bands");
        assert_eq!(s.index_at(-5.0), None);
        assert_eq!(labels(&s.ticks()), ["a", "b", "c", "d"]);
        // Reversed: band 0 at the range start (bottom), starts are still the smaller edge.
        let r = BandScale::new(cats, (500.0, 0.0), 0.2, 0.1).unwrap();
        assert!(r.center(0) > r.center(3));
        assert!(close(r.start(0), 500.0 - r.step() * 0.1 - r.bandwidth()));
        assert_eq!(r.index_at(r.center(1)), Some(1));
    }

    #[test]
    fn band_edge_cases() {
        assert_eq!(BandScale::new(Vec::new(), (0.0, 1.0), 0.1, 0.1), Err(ScaleError::EmptyCategories));
        assert!(matches!(
            BandScale::new(vec!["a".into()], (0.0, 1.0), f64::NAN, 0.0),
            Err(ScaleError::InvalidPadding { .. })
        ));
        assert!(BandScale::new(vec!["a".into()], (0.0, 1.0), 0.5, -1.0).is_err());
        let s = BandScale::new(vec!["x".into(), "y".into(), "x".into()], (0.0, 100.0), 0.0, 0.0).unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s.bandwidth(), 50.0);
        // One band with inner padding 1: zero width, no division by zero.
        let s = BandScale::new(vec!["a".into()], (0.0, 100.0), 1.0, 0.0).unwrap();
        assert_eq!(s.bandwidth(), 0.0);
        assert!(s.center(0).is_finite());
    }

    #[test]
    fn the_enum_forwards() {
        let band = Scale::Band(BandScale::new(vec!["a".into(), "b".into()], (0.0, 100.0), 0.0, 0.0).unwrap());
        assert_eq!(band.map(0.0), 25.0);
        assert_eq!(band.invert(10.0), None);
        assert_eq!(band.domain(), (0.0, 2.0));
        let lin = Scale::Linear(LinearScale::new((0.0, 1.0), (0.0, 10.0), false, 3).unwrap());
        assert_eq!(lin.invert(5.0), Some(0.5));
        assert_eq!(lin.range(), (0.0, 10.0));
        assert_eq!(labels(&lin.ticks()), ["0.0", "0.5", "1.0"]);
    }

    #[test]
    fn fixed_domains_label_at_least_two_ticks() {
        // The strict search alone labels only "4" on this padded iris extent.
        for target in 2..=6 {
            let s = LinearScale::new((0.764, 7.136), (0.0, 135.0), false, target).unwrap();
            let values: Vec<f64> = s.ticks().iter().map(|t| t.value).collect();
            assert!(values.len() >= target.min(3), "target {target}: {values:?}");
            assert!(values.iter().all(|v| (0.764..=7.136).contains(v)), "target {target}: {values:?}");
        }
        // Alone, the strict search settles for −2.5 and 5 (a step of 7.5) here.
        let s = LinearScale::new((-2.878, 5.507), (0.0, 105.0), false, 3).unwrap();
        let labels: Vec<String> = s.ticks().iter().map(|t| t.label.clone()).collect();
        assert!(labels.len() >= 3, "{labels:?}");
    }
}
