//! One-dimensional interpolants: a curve drawn through sample points `(x, y)`.
//!
//! Methods ([`Method`]):
//! - nearest neighbour (piecewise constant, jumps at the midpoints between knots),
//! - linear (straight segments),
//! - piecewise cubic Hermite, with knot slopes ([`Slopes`]) given by a column, by the arithmetic
//!   mean of the adjacent chord slopes, or by their weighted harmonic mean (monotone; identical
//!   to SciPy's `PchipInterpolator`, the Fritsch–Carlson / Fritsch–Butland method with the
//!   three-point shape-preserving end conditions).
//!
//! The `bounded` option keeps every cubic piece within the range of its two knots' values
//! (Fritsch–Carlson slope limiting, see [`Interpolant::new`]).
//!
//! [`Interpolant::new`] validates the input (lengths, finiteness, distinct x; unsorted x are
//! sorted) and returns an [`Interp1dError`] instead of panicking. Evaluation never fails: a point
//! outside `[x0, xn]` (or a NaN point) evaluates to NaN. Evaluating many points at once with
//! [`Interpolant::eval_many`] walks the intervals forward when the points are sorted, so a sorted
//! batch costs O(knots + points), and falls back to binary search otherwise.

use std::fmt;

/// Largest number of points [`Interpolant::sample`] returns; larger requests are capped.
pub const MAX_SAMPLES: usize = 1 << 24;

/// How the curve runs between knots.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// Piecewise constant: each point takes the value of the nearest knot. The switch happens at
    /// the midpoint `x_k + (x_{k+1} - x_k) / 2`; a point exactly at a midpoint takes the value of
    /// the right-hand (larger-x) knot. Accepts a single knot (the domain is then that one x).
    Nearest,
    /// Straight segments between consecutive knots.
    Linear,
    /// Piecewise cubic Hermite: on each interval the cubic that matches the knot values and the
    /// knot slopes chosen by [`Slopes`].
    Hermite(Slopes),
}

/// Where the knot slopes of a cubic Hermite interpolant come from.
///
/// Notation: knots `x_0 < … < x_{n-1}`, widths `h_k = x_{k+1} - x_k`, chord slopes
/// `Δ_k = (y_{k+1} - y_k) / h_k`, knot slopes `d_k`.
#[derive(Debug, Clone, PartialEq)]
pub enum Slopes {
    /// One slope per knot, in the order of the input x (for example a derivative column); they
    /// are reordered together with the knots when x is unsorted.
    Given(Vec<f64>),
    /// Interior knots: `d_k = (Δ_{k-1} + Δ_k) / 2`. End knots: the one-sided chord slope,
    /// `d_0 = Δ_0` and `d_{n-1} = Δ_{n-2}`. Not shape preserving unless `bounded` is set.
    ArithmeticMean,
    /// Monotone PCHIP, matching SciPy's `PchipInterpolator`: interior slopes are the weighted
    /// harmonic mean `(w1 + w2) / (w1 / Δ_{k-1} + w2 / Δ_k)` with `w1 = 2 h_k + h_{k-1}` and
    /// `w2 = h_k + 2 h_{k-1}`, or 0 where the chord slopes change sign or either is 0. End
    /// slopes use the three-point non-centred formula `((2 h_0 + h_1) Δ_0 - h_0 Δ_1) / (h_0 + h_1)`,
    /// set to 0 if its sign differs from `Δ_0`'s, and to `3 Δ_0` if `Δ_0` and `Δ_1` differ in
    /// sign and it exceeds `3 |Δ_0|` (mirrored at the right end). With two knots: linear.
    HarmonicMean,
}

/// Why an interpolant could not be built (or a batch not evaluated).
#[derive(Debug, Clone, PartialEq)]
pub enum Interp1dError {
    /// Fewer knots than the method needs (two, or one for nearest neighbour).
    TooFewKnots {
        /// Number of knots given.
        count: usize,
        /// Number of knots the method needs.
        min: usize,
    },
    /// `x` and `y` have different lengths.
    LengthMismatch {
        /// Length of `x`.
        x: usize,
        /// Length of `y`.
        y: usize,
    },
    /// [`Slopes::Given`] has a different length from the knots.
    SlopesLength {
        /// Number of knots.
        knots: usize,
        /// Number of slopes given.
        slopes: usize,
    },
    /// A NaN or infinite input value (the first one found, scanning rows in input order).
    NonFinite {
        /// Which input: `"x"`, `"y"` or `"slope"`.
        column: &'static str,
        /// Position in the input slice.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// Two knots have the same x.
    DuplicateX {
        /// The repeated x value.
        x: f64,
        /// Input position of its first occurrence.
        first: usize,
        /// Input position of its second occurrence.
        second: usize,
    },
    /// An interval's width, chord slope or cubic coefficients do not fit in an `f64`.
    Overflow {
        /// Left end of the interval.
        x0: f64,
        /// Right end of the interval.
        x1: f64,
    },
    /// [`Interpolant::eval_many`] got an output slice of a different length from the queries.
    OutputLength {
        /// Number of query points.
        queries: usize,
        /// Length of the output slice.
        out: usize,
    },
}

impl fmt::Display for Interp1dError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooFewKnots { count, min } => write!(
                f,
                "interpolation needs at least {min} knot{}, got {count}; add sample points \
                 (nearest-neighbour interpolation accepts a single point)",
                if *min == 1 { "" } else { "s" }
            ),
            Self::LengthMismatch { x, y } => {
                write!(f, "x has {x} values but y has {y}; give exactly one y per x")
            }
            Self::SlopesLength { knots, slopes } => {
                write!(f, "{slopes} slopes given for {knots} knots; give exactly one slope per knot")
            }
            Self::NonFinite { column, index, value } => write!(
                f,
                "{column}[{index}] = {value:?} is not a finite number; drop or fill that row before interpolating"
            ),
            Self::DuplicateX { x, first, second } => write!(
                f,
                "x = {x:?} appears twice (rows {first} and {second}); knots need distinct x: drop or \
                 average the duplicates"
            ),
            Self::Overflow { x0, x1 } => write!(
                f,
                "the interval from x = {x0:?} to x = {x1:?} gives a width, slope or curve coefficient \
                 too large for f64; rescale x or y"
            ),
            Self::OutputLength { queries, out } => write!(
                f,
                "{queries} query points but an output slice of length {out}; pass an output slice \
                 as long as the queries"
            ),
        }
    }
}

impl std::error::Error for Interp1dError {}

/// How pieces are evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// Piece `[y_left, y_right, midpoint, 0]`.
    Nearest,
    /// Piece `[c0, c1, c2, c3]`: `c0 + s (c1 + s (c2 + s c3))` with `s = t - x_k`.
    Polynomial,
}

/// A validated 1D interpolant, ready to evaluate.
///
/// Holds the knots (sorted, strictly increasing x), the knot slopes for Hermite methods, and
/// one piece per knot: piece `k` covers `[x_k, x_{k+1})`, and the last one covers `x_{n-1}`
/// alone, so every knot evaluates to exactly its `y`.
#[derive(Debug, Clone, PartialEq)]
pub struct Interpolant {
    x: Vec<f64>,
    y: Vec<f64>,
    slopes: Vec<f64>,
    kind: Kind,
    pieces: Vec<[f64; 4]>,
}

impl Interpolant {
    /// Builds an interpolant through the points `(x[i], y[i])`.
    ///
    /// Requirements: `x` and `y` of equal length, at least two points (one for
    /// [`Method::Nearest`]), every value finite, x values distinct. Unsorted x are accepted: the
    /// pairs (and given slopes) are sorted by x. Given slopes must be one per knot and finite.
    ///
    /// `bounded` limits the slopes of [`Slopes::Given`] and [`Slopes::ArithmeticMean`] so that
    /// each cubic piece stays within `[min(y_k, y_{k+1}), max(y_k, y_{k+1})]` (Fritsch–Carlson):
    /// on a flat interval (`Δ_k = 0`) both end slopes become 0; a slope whose sign differs from an
    /// adjacent chord slope becomes 0 (so local extrema of the data are flat); and each slope is
    /// clipped to `|d| ≤ 3 |Δ|` for both adjacent chords. That is the box `0 ≤ α, β ≤ 3` for
    /// `α = d_k / Δ_k`, `β = d_{k+1} / Δ_k`, which lies inside Fritsch and Carlson's
    /// monotonicity region (and contains their smaller disk `α² + β² ≤ 9`), so each piece is
    /// monotone and never leaves the range of its end values, up to rounding in the last bits.
    /// For [`Slopes::HarmonicMean`] (already monotone and inside the box) and for nearest and
    /// linear, `bounded` changes nothing.
    ///
    /// # Errors
    ///
    /// [`Interp1dError::LengthMismatch`], [`Interp1dError::TooFewKnots`],
    /// [`Interp1dError::SlopesLength`], [`Interp1dError::NonFinite`] (first bad row),
    /// [`Interp1dError::DuplicateX`], or [`Interp1dError::Overflow`] when an interval's width,
    /// chord slope or cubic coefficients do not fit in an `f64`.
    pub fn new(x: &[f64], y: &[f64], method: Method, bounded: bool) -> Result<Self, Interp1dError> {
        if x.len() != y.len() {
            return Err(Interp1dError::LengthMismatch { x: x.len(), y: y.len() });
        }
        let min = if method == Method::Nearest { 1 } else { 2 };
        if x.len() < min {
            return Err(Interp1dError::TooFewKnots { count: x.len(), min });
        }
        let given = match &method {
            Method::Hermite(Slopes::Given(s)) => {
                if s.len() != x.len() {
                    return Err(Interp1dError::SlopesLength { knots: x.len(), slopes: s.len() });
                }
                Some(s.as_slice())
            }
            _ => None,
        };
        for (index, (&xi, &yi)) in x.iter().zip(y).enumerate() {
            if !xi.is_finite() {
                return Err(Interp1dError::NonFinite { column: "x", index, value: xi });
            }
            if !yi.is_finite() {
                return Err(Interp1dError::NonFinite { column: "y", index, value: yi });
            }
        }
        if let Some(s) = given
            && let Some((index, &value)) = s.iter().enumerate().find(|(_, v)| !v.is_finite())
        {
            return Err(Interp1dError::NonFinite { column: "slope", index, value });
        }

        let (xs, ys, given) = sort_knots(x, y, given)?;

        // Interval widths and chord slopes.
        let mut h = Vec::with_capacity(xs.len().saturating_sub(1));
        let mut m = Vec::with_capacity(xs.len().saturating_sub(1));
        for (xw, yw) in xs.windows(2).zip(ys.windows(2)) {
            if let ([x0, x1], [y0, y1]) = (xw, yw) {
                let hk = x1 - x0;
                let mk = (y1 - y0) / hk;
                if !hk.is_finite() || !mk.is_finite() {
                    return Err(Interp1dError::Overflow { x0: *x0, x1: *x1 });
                }
                h.push(hk);
                m.push(mk);
            }
        }

        let slopes = match method {
            Method::Nearest | Method::Linear => Vec::new(),
            Method::Hermite(Slopes::Given(_)) => given,
            Method::Hermite(Slopes::ArithmeticMean) => arithmetic_slopes(&m),
            Method::Hermite(Slopes::HarmonicMean) => pchip_slopes(&h, &m),
        };
        let mut slopes = slopes;
        if bounded && matches!(method, Method::Hermite(Slopes::Given(_) | Slopes::ArithmeticMean)) {
            limit_slopes(&m, &mut slopes);
        }

        let (kind, pieces) = match method {
            Method::Nearest => (Kind::Nearest, nearest_pieces(&xs, &ys, &h)),
            Method::Linear => (Kind::Polynomial, linear_pieces(&ys, &m)),
            Method::Hermite(_) => (Kind::Polynomial, hermite_pieces(&ys, &h, &m, &slopes)),
        };
        if let Some(k) = pieces.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            let x0 = xs.get(k).copied().unwrap_or(f64::NAN);
            let x1 = xs.get(k + 1).copied().unwrap_or(x0);
            return Err(Interp1dError::Overflow { x0, x1 });
        }
        Ok(Self { x: xs, y: ys, slopes, kind, pieces })
    }

    /// The knot x values, sorted and strictly increasing.
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The knot y values, in the order of [`Interpolant::x`].
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// The knot slopes actually used (after sorting and `bounded` limiting) for Hermite methods;
    /// empty for nearest and linear.
    pub fn slopes(&self) -> &[f64] {
        &self.slopes
    }

    /// The interval `(x_0, x_{n-1})` where the interpolant is defined.
    pub fn domain(&self) -> (f64, f64) {
        match (self.x.first(), self.x.last()) {
            (Some(&lo), Some(&hi)) => (lo, hi),
            _ => (f64::NAN, f64::NAN),
        }
    }

    /// Value at `t`. Returns exactly `y_k` at a knot `x_k`, and NaN when `t` is NaN or outside
    /// [`Interpolant::domain`] (no extrapolation).
    pub fn eval(&self, t: f64) -> f64 {
        let (lo, hi) = self.domain();
        if !(t >= lo && t <= hi) {
            return f64::NAN;
        }
        // Number of knots <= t is at least 1 because t >= x_0.
        let k = self.x.partition_point(|&v| v <= t).saturating_sub(1);
        match (self.pieces.get(k), self.x.get(k)) {
            (Some(p), Some(&xk)) => match self.kind {
                Kind::Nearest => nearest_value(p, xk, t),
                Kind::Polynomial => poly_value(p, xk, t),
            },
            _ => f64::NAN,
        }
    }

    /// Evaluates every point of `ts` into the same position of `out`, with the rules of
    /// [`Interpolant::eval`] (identical results). Sorted `ts` are evaluated by walking the
    /// intervals forward; a point behind the current interval, or far ahead of it, is located by
    /// binary search. No allocation.
    ///
    /// # Errors
    ///
    /// [`Interp1dError::OutputLength`] (and nothing written) if `out` is not as long as `ts`.
    pub fn eval_many(&self, ts: &[f64], out: &mut [f64]) -> Result<(), Interp1dError> {
        if ts.len() != out.len() {
            return Err(Interp1dError::OutputLength { queries: ts.len(), out: out.len() });
        }
        match self.kind {
            Kind::Nearest => self.walk(ts, out, nearest_value),
            Kind::Polynomial => self.walk(ts, out, poly_value),
        }
        Ok(())
    }

    /// `n` points `(t, value)` evenly spaced over [`Interpolant::domain`], both ends included,
    /// for drawing the curve. `n = 1` gives the left end; `n` is capped at [`MAX_SAMPLES`].
    pub fn sample(&self, n: usize) -> Vec<(f64, f64)> {
        let n = n.min(MAX_SAMPLES);
        let (lo, hi) = self.domain();
        let last = n.saturating_sub(1);
        let ts: Vec<f64> = (0..n)
            .map(|j| {
                if j == 0 {
                    lo
                } else if j == last {
                    hi
                } else {
                    // Convex combination: no overflow even when hi - lo would overflow.
                    let u = j as f64 / last as f64;
                    (lo * (1.0 - u) + hi * u).max(lo).min(hi)
                }
            })
            .collect();
        let mut vs = vec![f64::NAN; ts.len()];
        // Lengths are equal by construction, so this cannot fail; values stay NaN if it did.
        let _ = self.eval_many(&ts, &mut vs);
        ts.into_iter().zip(vs).collect()
    }

    /// The batch loop: keeps the current interval `k` and only moves it when a point leaves
    /// `[x_k, x_{k+1})`. Points go in chunks; a chunk lying wholly inside the current interval
    /// (the common case for sorted points) is evaluated without per-point branches.
    #[inline]
    fn walk(&self, ts: &[f64], out: &mut [f64], value: impl Fn(&[f64; 4], f64, f64) -> f64) {
        const CHUNK: usize = 8;
        let mut cur = Cursor::new(self);
        let mut t_chunks = ts.chunks_exact(CHUNK);
        let mut o_chunks = out.chunks_exact_mut(CHUNK);
        for (tc, oc) in (&mut t_chunks).zip(&mut o_chunks) {
            let (xk, next) = (cur.xk, cur.next);
            // `&` rather than `&&`: no early exit, so this compiles to straight-line compares.
            // NaN fails both compares, so NaN points take the careful path.
            let inside = tc.iter().fold(true, |all, &t| all & (t >= xk) & (t < next));
            if inside {
                for (o, &t) in oc.iter_mut().zip(tc) {
                    *o = value(&cur.piece, xk, t);
                }
            } else {
                for (o, &t) in oc.iter_mut().zip(tc) {
                    *o = cur.eval(self, t, &value);
                }
            }
        }
        for (o, &t) in o_chunks.into_remainder().iter_mut().zip(t_chunks.remainder()) {
            *o = cur.eval(self, t, &value);
        }
    }

    /// Index of the piece containing `t` (with `x_0 <= t <= x_{n-1}`), searching from piece `k`:
    /// a few steps forward first (sorted queries), then binary search.
    fn locate_from(&self, mut k: usize, t: f64) -> usize {
        const STEPS: usize = 8;
        if self.x.get(k).is_some_and(|&xk| t >= xk) {
            for _ in 0..STEPS {
                match self.x.get(k + 1) {
                    Some(&nx) if t >= nx => k += 1,
                    _ => return k,
                }
            }
        }
        self.x.partition_point(|&v| v <= t).saturating_sub(1)
    }
}

/// Position of a batch evaluation: the current piece `k` covers `[xk, next)`. For the last
/// knot's piece `next` is `x_{n-1}` itself, so no point counts as inside it without a check.
struct Cursor {
    k: usize,
    xk: f64,
    next: f64,
    piece: [f64; 4],
    lo: f64,
    hi: f64,
}

impl Cursor {
    fn new(ip: &Interpolant) -> Self {
        let (lo, hi) = ip.domain();
        let mut cur = Self { k: 0, xk: lo, next: hi, piece: [f64::NAN; 4], lo, hi };
        cur.move_to(ip, 0);
        cur
    }

    fn move_to(&mut self, ip: &Interpolant, k: usize) {
        self.k = k;
        self.xk = ip.x.get(k).copied().unwrap_or(f64::NAN);
        self.next = ip.x.get(k + 1).copied().unwrap_or(self.hi);
        self.piece = ip.pieces.get(k).copied().unwrap_or([f64::NAN; 4]);
    }

    /// One point with every check: NaN outside the domain, otherwise move to its piece first.
    #[inline]
    fn eval(&mut self, ip: &Interpolant, t: f64, value: impl Fn(&[f64; 4], f64, f64) -> f64) -> f64 {
        if !(t >= self.lo && t <= self.hi) {
            return f64::NAN;
        }
        if !(t >= self.xk && t < self.next) {
            let k = ip.locate_from(self.k, t);
            self.move_to(ip, k);
        }
        value(&self.piece, self.xk, t)
    }
}

/// Nearest-neighbour piece: left value before the midpoint, right value from it on.
#[inline]
fn nearest_value(p: &[f64; 4], _xk: f64, t: f64) -> f64 {
    let [left, right, mid, _] = *p;
    if t < mid { left } else { right }
}

/// Polynomial piece in Horner form around the interval's left knot.
#[inline]
fn poly_value(p: &[f64; 4], xk: f64, t: f64) -> f64 {
    let [c0, c1, c2, c3] = *p;
    let s = t - xk;
    c0 + s * (c1 + s * (c2 + s * c3))
}

/// Validated, finite rows sorted by x (already-sorted input is copied as is). Returns x, y and
/// the given slopes (empty when there are none).
#[allow(clippy::type_complexity)]
fn sort_knots(x: &[f64], y: &[f64], given: Option<&[f64]>) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>), Interp1dError> {
    let increasing = x.windows(2).all(|w| matches!(w, [a, b] if a < b));
    if increasing {
        return Ok((x.to_vec(), y.to_vec(), given.map(<[f64]>::to_vec).unwrap_or_default()));
    }
    let slopes = given.unwrap_or(&[]);
    // (x, y, slope, input position); slope is 0 when none are given.
    let mut rows: Vec<(f64, f64, f64, usize)> =
        x.iter().zip(y).enumerate().map(|(i, (&xi, &yi))| (xi, yi, slopes.get(i).copied().unwrap_or(0.0), i)).collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    for w in rows.windows(2) {
        if let [a, b] = w
            && a.0 == b.0
        {
            return Err(Interp1dError::DuplicateX { x: a.0, first: a.3.min(b.3), second: a.3.max(b.3) });
        }
    }
    let xs = rows.iter().map(|r| r.0).collect();
    let ys = rows.iter().map(|r| r.1).collect();
    let ss = if given.is_some() { rows.iter().map(|r| r.2).collect() } else { Vec::new() };
    Ok((xs, ys, ss))
}

/// Arithmetic-mean slopes: mean of adjacent chords inside, one-sided chord at the ends.
fn arithmetic_slopes(m: &[f64]) -> Vec<f64> {
    let mut d = Vec::with_capacity(m.len() + 1);
    if let Some(&first) = m.first() {
        d.push(first);
    }
    d.extend(m.windows(2).filter_map(|w| match w {
        [a, b] => Some((a + b) / 2.0),
        _ => None,
    }));
    if let Some(&last) = m.last() {
        d.push(last);
    }
    d
}

/// Sign as numpy's `sign`: -1, 0 or 1.
fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// PCHIP knot slopes (weighted harmonic mean inside, shape-preserving three-point ends).
fn pchip_slopes(h: &[f64], m: &[f64]) -> Vec<f64> {
    match (h, m) {
        ([_], &[m0]) => return vec![m0, m0],
        ([_, _, ..], [_, _, ..]) => {}
        _ => return Vec::new(),
    }
    let mut d = Vec::with_capacity(m.len() + 1);
    if let (&[h0, h1, ..], &[m0, m1, ..]) = (h, m) {
        d.push(end_slope(h0, h1, m0, m1));
    }
    for (hw, mw) in h.windows(2).zip(m.windows(2)) {
        if let (&[h_prev, h_next], &[m_prev, m_next]) = (hw, mw) {
            let dk = if m_prev == 0.0 || m_next == 0.0 || sign(m_prev) != sign(m_next) {
                0.0
            } else {
                let w1 = 2.0 * h_next + h_prev;
                let w2 = h_next + 2.0 * h_prev;
                1.0 / ((w1 / m_prev + w2 / m_next) / (w1 + w2))
            };
            d.push(dk);
        }
    }
    if let (Some(&[h1, h0]), Some(&[m1, m0])) = (h.last_chunk::<2>(), m.last_chunk::<2>()) {
        d.push(end_slope(h0, h1, m0, m1));
    }
    d
}

/// End slope from the end interval (`h0`, `m0`) and its neighbour (`h1`, `m1`): the
/// non-centred three-point estimate, zeroed if it points against `m0`, and limited to `3 m0`
/// when the data turn (`m0`, `m1` of different sign) and it is steeper than that.
fn end_slope(h0: f64, h1: f64, m0: f64, m1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if sign(d) != sign(m0) {
        0.0
    } else if sign(m0) != sign(m1) && d.abs() > 3.0 * m0.abs() {
        3.0 * m0
    } else {
        d
    }
}

/// Fritsch–Carlson limiting into the box `0 <= d/Δ <= 3` for both chords adjacent to a knot;
/// slopes only ever shrink towards 0, so the order of the intervals does not matter.
fn limit_slopes(m: &[f64], d: &mut [f64]) {
    for (k, &delta) in m.iter().enumerate() {
        for j in [k, k + 1] {
            if let Some(dj) = d.get_mut(j) {
                // Covers the flat interval too: sign(0) = 0, so any non-zero slope next to it goes.
                if sign(*dj) != sign(delta) {
                    *dj = 0.0;
                } else if dj.abs() > 3.0 * delta.abs() {
                    *dj = 3.0 * delta;
                }
            }
        }
    }
}

/// Nearest pieces `[y_k, y_{k+1}, midpoint, 0]`, plus the last knot's own piece.
fn nearest_pieces(x: &[f64], y: &[f64], h: &[f64]) -> Vec<[f64; 4]> {
    let mut pieces: Vec<[f64; 4]> = x
        .iter()
        .zip(h)
        .zip(y.windows(2))
        .filter_map(|((&xk, &hk), w)| match w {
            &[y0, y1] => Some([y0, y1, xk + 0.5 * hk, 0.0]),
            _ => None,
        })
        .collect();
    if let (Some(&xl), Some(&yl)) = (x.last(), y.last()) {
        pieces.push([yl, yl, xl, 0.0]);
    }
    pieces
}

/// Linear pieces `[y_k, Δ_k, 0, 0]`, plus the last knot's constant piece.
fn linear_pieces(y: &[f64], m: &[f64]) -> Vec<[f64; 4]> {
    let mut pieces: Vec<[f64; 4]> = y.iter().zip(m).map(|(&yk, &mk)| [yk, mk, 0.0, 0.0]).collect();
    if let Some(&yl) = y.last() {
        pieces.push([yl, 0.0, 0.0, 0.0]);
    }
    pieces
}

/// Cubic Hermite pieces in power form around `x_k`:
/// `c0 = y_k`, `c1 = d_k`, `c3 = (d_k + d_{k+1} - 2Δ_k) / h_k²`, `c2 = (Δ_k - d_k) / h_k - c3 h_k`
/// (the cubic with values `y_k, y_{k+1}` and slopes `d_k, d_{k+1}` at the interval ends).
fn hermite_pieces(y: &[f64], h: &[f64], m: &[f64], d: &[f64]) -> Vec<[f64; 4]> {
    let mut pieces: Vec<[f64; 4]> = y
        .iter()
        .zip(h)
        .zip(m)
        .zip(d.windows(2))
        .filter_map(|(((&yk, &hk), &mk), w)| match w {
            &[d0, d1] => {
                let curv = (d0 + d1 - 2.0 * mk) / hk;
                Some([yk, d0, (mk - d0) / hk - curv, curv / hk])
            }
            _ => None,
        })
        .collect();
    if let Some(&yl) = y.last() {
        pieces.push([yl, 0.0, 0.0, 0.0]);
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One case of the committed SciPy fixture.
    struct Case {
        name: String,
        x: Vec<f64>,
        y: Vec<f64>,
        t: Vec<f64>,
        values: Vec<f64>,
        knot_slopes: Vec<f64>,
    }

    /// The fixture stores floats as repr strings: `str::parse` reads them back bit-exactly,
    /// which serde_json's default number parser does not promise.
    fn floats(v: &serde_json::Value, key: &str) -> Vec<f64> {
        v[key]
            .as_array()
            .unwrap_or_else(|| panic!("fixture: {key} is not an array"))
            .iter()
            .map(|n| {
                let s = n.as_str().unwrap_or_else(|| panic!("fixture: {key} has a non-string {n}"));
                s.parse::<f64>().unwrap_or_else(|e| panic!("fixture: {key}: {s:?}: {e}"))
            })
            .collect()
    }

    fn fixture() -> Vec<Case> {
        let doc: serde_json::Value =
            serde_json::from_str(include_str!("../../tests/fixtures/pchip.json")).expect("fixture parses");
        let cases: Vec<Case> = doc["cases"]
            .as_array()
            .expect("fixture has cases")
            .iter()
            .map(|c| Case {
                name: c["name"].as_str().expect("case name").to_string(),
                x: floats(c, "x"),
                y: floats(c, "y"),
                t: floats(c, "t"),
                values: floats(c, "values"),
                knot_slopes: floats(c, "knot_slopes"),
            })
            .collect();
        assert!(cases.len() >= 10, "fixture lost cases: {}", cases.len());
        cases
    }

    fn max_abs(v: &[f64]) -> f64 {
        v.iter().fold(0.0, |a, b| a.max(b.abs()))
    }

    fn chords(x: &[f64], y: &[f64]) -> Vec<f64> {
        x.windows(2).zip(y.windows(2)).map(|(a, b)| (b[1] - b[0]) / (a[1] - a[0])).collect()
    }

    const REL: f64 = 1e-12;

    /// Relative error with an absolute floor: `|got - want| / max(|want|, floor)`.
    fn rel_err(got: f64, want: f64, floor: f64) -> f64 {
        (got - want).abs() / want.abs().max(floor)
    }

    fn pchip(x: &[f64], y: &[f64]) -> Interpolant {
        Interpolant::new(x, y, Method::Hermite(Slopes::HarmonicMean), false).expect("valid pchip input")
    }

    fn all_methods() -> Vec<Method> {
        vec![
            Method::Nearest,
            Method::Linear,
            Method::Hermite(Slopes::ArithmeticMean),
            Method::Hermite(Slopes::HarmonicMean),
        ]
    }

    /// Dense sample of `[lo, hi]`: `n` evenly spaced points.
    fn dense(lo: f64, hi: f64, n: usize) -> Vec<f64> {
        (0..n).map(|j| lo + (hi - lo) * j as f64 / (n - 1) as f64).map(|t| t.min(hi)).collect()
    }

    // Values: floor = 1e-3 · max|y| of the case, i.e. relative 1e-12 for |value| above a
    // thousandth of the data scale, absolute 1e-15 · max|y| below it (a few ulps of the data).
    #[test]
    fn harmonic_mean_matches_scipy_values() {
        let mut worst = (0.0, String::new());
        let mut floored = 0;
        for case in fixture() {
            let p = pchip(&case.x, &case.y);
            let floor = 1e-3 * max_abs(&case.y);
            assert_eq!(case.t.len(), case.values.len(), "{}", case.name);
            for (&t, &want) in case.t.iter().zip(&case.values) {
                let got = p.eval(t);
                let e = rel_err(got, want, floor);
                assert!(e <= REL, "{}: at t = {t}: got {got}, scipy {want}, rel err {e:e}", case.name);
                if e > worst.0 {
                    worst = (e, case.name.clone());
                }
                if want.abs() < floor {
                    floored += 1;
                }
            }
        }
        println!("worst value rel err {:e} ({}); {floored} values under the floor", worst.0, worst.1);
    }

    // Knot slopes: floor = 1e-3 · max|chord slope| of the case. SciPy's derivative at the last
    // knot is evaluated at the right end of the last cubic, so an exact 0 comes back as ~1e-16.
    #[test]
    fn harmonic_mean_matches_scipy_knot_slopes() {
        let mut worst = (0.0, String::new());
        let mut floored = 0;
        for case in fixture() {
            let p = pchip(&case.x, &case.y);
            let floor = 1e-3 * max_abs(&chords(&case.x, &case.y));
            assert_eq!(p.slopes().len(), case.knot_slopes.len(), "{}", case.name);
            for (k, (&got, &want)) in p.slopes().iter().zip(&case.knot_slopes).enumerate() {
                let e = rel_err(got, want, floor);
                assert!(e <= REL, "{}: slope {k}: got {got}, scipy {want}, rel err {e:e}", case.name);
                if e > worst.0 {
                    worst = (e, case.name.clone());
                }
                if want.abs() < floor {
                    floored += 1;
                }
            }
        }
        println!("worst slope rel err {:e} ({}); {floored} slopes under the floor", worst.0, worst.1);
    }

    #[test]
    fn fixture_covers_the_end_clamps() {
        let case = fixture().into_iter().find(|c| c.name == "end_clamps").expect("end_clamps case");
        let p = pchip(&case.x, &case.y);
        // Left: three-point formula gives 11, clamped to 3 Δ_0 = 3. Right: wrong sign, so 0.
        assert_eq!(p.slopes().first(), Some(&3.0));
        assert_eq!(p.slopes().last(), Some(&0.0));
    }

    #[test]
    fn pchip_known_small_answers() {
        // Two knots: linear.
        let p = pchip(&[0.0, 2.0], &[1.0, 5.0]);
        assert_eq!(p.slopes(), &[2.0, 2.0]);
        assert_eq!(p.eval(0.5), 2.0);
        // Three knots, equal spacing h = 1, chords 1 and 3: interior harmonic mean with
        // w1 = w2 = 3 is 2 / (1/1 + 1/3) = 1.5; left end (3·1 - 3)/2 = 0; right end (3·3 - 1)/2 = 4.
        let p = pchip(&[0.0, 1.0, 2.0], &[0.0, 1.0, 4.0]);
        assert_eq!(p.slopes(), &[0.0, 1.5, 4.0]);
        // A peak: interior slope 0.
        let p = pchip(&[0.0, 1.0, 3.0], &[0.0, 2.0, 1.0]);
        assert_eq!(p.slopes().get(1), Some(&0.0));
    }

    #[test]
    fn linear_reproduces_linear_data_exactly() {
        // Dyadic data: every operation is exact, so equality is the right test.
        let x = [-4.0, -1.0, 0.5, 2.0, 7.25, 8.0];
        let y: Vec<f64> = x.iter().map(|v| 0.75 * v - 3.0).collect();
        let p = Interpolant::new(&x, &y, Method::Linear, false).expect("valid");
        for t in dense(-4.0, 8.0, 97) {
            assert_eq!(p.eval(t), 0.75 * t - 3.0, "t = {t}");
        }
        // A general line: within rounding.
        let x = [0.1, 0.7, 1.3, 2.9, 3.3];
        let y: Vec<f64> = x.iter().map(|v| -1.7 * v + 0.3).collect();
        let p = Interpolant::new(&x, &y, Method::Linear, false).expect("valid");
        for t in dense(0.1, 3.3, 101) {
            let want = -1.7 * t + 0.3;
            assert!((p.eval(t) - want).abs() <= 1e-14 * 6.0, "t = {t}: {} vs {want}", p.eval(t));
        }
        // Between two knots, linear is the chord: midpoint gives the mean.
        let p = Interpolant::new(&[0.0, 1.0, 3.0], &[0.0, 10.0, 4.0], Method::Linear, false).expect("valid");
        assert_eq!(p.eval(2.0), 7.0);
    }

    #[test]
    fn hermite_variants_reproduce_a_straight_line_exactly() {
        let x = [-3.0, -2.5, 0.0, 1.0, 4.0, 4.5, 10.0];
        let line = |v: f64| 2.0 * v - 0.25;
        let y: Vec<f64> = x.iter().map(|&v| line(v)).collect();
        let methods = [
            (Method::Hermite(Slopes::Given(vec![2.0; x.len()])), false),
            (Method::Hermite(Slopes::ArithmeticMean), false),
            (Method::Hermite(Slopes::ArithmeticMean), true),
            (Method::Hermite(Slopes::HarmonicMean), false),
        ];
        for (method, bounded) in methods {
            let p = Interpolant::new(&x, &y, method.clone(), bounded).expect("valid");
            assert!(p.slopes().iter().all(|&d| d == 2.0), "{method:?}: slopes {:?}", p.slopes());
            for t in dense(-3.0, 10.0, 209) {
                assert_eq!(p.eval(t), line(t), "{method:?} at t = {t}");
            }
        }
    }

    #[test]
    fn every_method_passes_through_the_knots_exactly() {
        for case in fixture() {
            let given = Slopes::Given(case.y.iter().map(|v| v.sin() * 7.0).collect());
            let mut methods: Vec<(Method, bool)> = all_methods().into_iter().map(|m| (m, false)).collect();
            methods.push((Method::Hermite(given.clone()), false));
            methods.push((Method::Hermite(given), true));
            methods.push((Method::Hermite(Slopes::ArithmeticMean), true));
            for (method, bounded) in methods {
                let p = Interpolant::new(&case.x, &case.y, method.clone(), bounded).expect("valid");
                for (&xk, &yk) in case.x.iter().zip(&case.y) {
                    assert_eq!(p.eval(xk), yk, "{} {method:?} at knot {xk}", case.name);
                }
            }
        }
    }

    #[test]
    fn pchip_is_monotone_on_monotone_data() {
        let mut checked = 0;
        for case in fixture() {
            let up = case.y.windows(2).all(|w| w[0] <= w[1]);
            let down = case.y.windows(2).all(|w| w[0] >= w[1]);
            if !(up || down) {
                continue;
            }
            let p = pchip(&case.x, &case.y);
            let (lo, hi) = p.domain();
            let ts = dense(lo, hi, 20_001);
            let mut vs = vec![0.0; ts.len()];
            p.eval_many(&ts, &mut vs).expect("same length");
            // Allowance: rounding of the Horner sum, a few ulps of the data scale.
            let tol = 8.0 * f64::EPSILON * max_abs(&case.y);
            for w in vs.windows(2) {
                let step = w[1] - w[0];
                assert!(if up { step >= -tol } else { step <= tol }, "{}: not monotone: {w:?}", case.name);
            }
            checked += 1;
        }
        assert!(checked >= 3, "fixture has too few monotone cases: {checked}");
    }

    /// Largest amount by which a dense sample leaves `[min(y_k, y_{k+1}), max(..)]` on any
    /// interval, relative to the data scale.
    fn worst_overshoot(p: &Interpolant) -> f64 {
        let mut worst: f64 = 0.0;
        for (xw, yw) in p.x().windows(2).zip(p.y().windows(2)) {
            let (lo, hi) = (yw[0].min(yw[1]), yw[0].max(yw[1]));
            for t in dense(xw[0], xw[1], 401) {
                let v = p.eval(t);
                worst = worst.max(lo - v).max(v - hi);
            }
        }
        worst / max_abs(p.y()).max(f64::MIN_POSITIVE)
    }

    #[test]
    fn bounded_never_overshoots() {
        let x = [0.0, 1.0, 1.2, 4.0, 4.5, 6.0, 6.1, 9.0, 10.0];
        let y = [0.0, 0.0, 5.0, 5.2, -3.0, -2.9, 8.0, 8.0, 7.0];
        // Wild given slopes, including wrong signs and slopes on flat intervals.
        let wild = vec![4.0, -30.0, 90.0, -7.0, 50.0, 200.0, -60.0, 3.0, 40.0];
        let tol = 8.0 * f64::EPSILON;
        for slopes in [Slopes::ArithmeticMean, Slopes::Given(wild)] {
            // The unbounded curve does overshoot here, so the bounded check below has teeth.
            let free = Interpolant::new(&x, &y, Method::Hermite(slopes.clone()), false).expect("valid");
            assert!(worst_overshoot(&free) > 0.01, "{slopes:?}: test data should overshoot when unbounded");
            let p = Interpolant::new(&x, &y, Method::Hermite(slopes.clone()), true).expect("valid");
            let over = worst_overshoot(&p);
            assert!(over <= tol, "{slopes:?}: bounded curve overshoots by {over:e} of the data scale");
            // The limited slopes sit in the box: same sign as both chords, at most 3 |chord|.
            let m = chords(p.x(), p.y());
            for (k, &d) in p.slopes().iter().enumerate() {
                for delta in [k.checked_sub(1).and_then(|i| m.get(i)), m.get(k)].into_iter().flatten() {
                    assert!(d * delta >= 0.0 && d.abs() <= 3.0 * delta.abs(), "slope {k} = {d} vs chord {delta}");
                }
            }
        }
        // Random data from the fixture, too.
        for case in fixture() {
            let p = Interpolant::new(&case.x, &case.y, Method::Hermite(Slopes::ArithmeticMean), true).expect("valid");
            let over = worst_overshoot(&p);
            assert!(over <= tol, "{}: bounded overshoot {over:e}", case.name);
        }
    }

    #[test]
    fn bounded_keeps_slopes_already_in_the_box() {
        // Slopes that already satisfy the box are left alone.
        let x = [0.0, 1.0, 2.0, 3.0];
        let y = [0.0, 1.0, 3.0, 4.0];
        let ok = vec![0.5, 1.0, 2.9, 0.0];
        let p = Interpolant::new(&x, &y, Method::Hermite(Slopes::Given(ok.clone())), true).expect("valid");
        assert_eq!(p.slopes(), ok.as_slice());
        // Too steep: clipped to 3 × the smaller adjacent chord (chords 1, 2, 1).
        let steep = vec![5.0, 9.0, 9.0, 9.0];
        let p = Interpolant::new(&x, &y, Method::Hermite(Slopes::Given(steep)), true).expect("valid");
        assert_eq!(p.slopes(), &[3.0, 3.0, 3.0, 3.0]);
    }

    #[test]
    fn bounded_is_a_no_op_for_pchip_nearest_and_linear() {
        for case in fixture() {
            for method in [Method::Nearest, Method::Linear, Method::Hermite(Slopes::HarmonicMean)] {
                let a = Interpolant::new(&case.x, &case.y, method.clone(), false).expect("valid");
                let b = Interpolant::new(&case.x, &case.y, method.clone(), true).expect("valid");
                assert_eq!(a, b, "{} {method:?}", case.name);
            }
            // And PCHIP's slopes are inside the box anyway (what makes the no-op correct).
            let p = pchip(&case.x, &case.y);
            let m = chords(&case.x, &case.y);
            for (k, &d) in p.slopes().iter().enumerate() {
                for delta in [k.checked_sub(1).and_then(|i| m.get(i)), m.get(k)].into_iter().flatten() {
                    assert!(
                        d * delta >= 0.0 && d.abs() <= 3.0 * delta.abs() * (1.0 + 1e-15),
                        "{}: slope {k} = {d} vs chord {delta}",
                        case.name
                    );
                }
            }
        }
    }

    #[test]
    fn arithmetic_mean_slopes_and_ends() {
        let x = [0.0, 1.0, 3.0, 4.0];
        let y = [0.0, 2.0, 0.0, 3.0]; // chords 2, -1, 3
        let p = Interpolant::new(&x, &y, Method::Hermite(Slopes::ArithmeticMean), false).expect("valid");
        assert_eq!(p.slopes(), &[2.0, 0.5, 1.0, 3.0]);
        // Bounded: knots 1 and 2 are extrema (chords change sign), so their slopes become 0.
        let p = Interpolant::new(&x, &y, Method::Hermite(Slopes::ArithmeticMean), true).expect("valid");
        assert_eq!(p.slopes(), &[2.0, 0.0, 0.0, 3.0]);
    }

    #[test]
    fn given_slopes_are_used_and_sorted_with_the_knots() {
        // Cubic y = t³ with exact slopes 3t² is reproduced exactly by Hermite interpolation.
        let x = [2.0, -1.0, 0.5, 1.5, -2.0];
        let y: Vec<f64> = x.iter().map(|v| v * v * v).collect();
        let d: Vec<f64> = x.iter().map(|v| 3.0 * v * v).collect();
        let p = Interpolant::new(&x, &y, Method::Hermite(Slopes::Given(d)), false).expect("valid");
        assert_eq!(p.x(), &[-2.0, -1.0, 0.5, 1.5, 2.0]);
        assert_eq!(p.slopes(), &[12.0, 3.0, 0.75, 6.75, 12.0]);
        for t in dense(-2.0, 2.0, 161) {
            assert!((p.eval(t) - t * t * t).abs() <= 1e-14 * 8.0, "t = {t}: {}", p.eval(t));
        }
    }

    #[test]
    fn unsorted_input_gives_the_same_interpolant_as_sorted() {
        let x = [0.0, 1.0, 2.5, 3.0, 5.0];
        let y = [1.0, -2.0, 0.5, 4.0, 4.5];
        let xr = [3.0, 0.0, 5.0, 2.5, 1.0];
        let yr = [4.0, 1.0, 4.5, 0.5, -2.0];
        for method in all_methods() {
            let a = Interpolant::new(&x, &y, method.clone(), false).expect("valid");
            let b = Interpolant::new(&xr, &yr, method.clone(), false).expect("valid");
            assert_eq!(a, b, "{method:?}");
        }
    }

    #[test]
    fn nearest_is_piecewise_constant_with_jumps_at_midpoints() {
        let x = [0.0, 1.0, 3.0, 7.0];
        let y = [10.0, 20.0, 30.0, 40.0];
        let p = Interpolant::new(&x, &y, Method::Nearest, false).expect("valid");
        assert!(p.slopes().is_empty());
        // Midpoints 0.5, 2, 5: below takes the left value, at or above takes the right.
        for (mid, left, right) in [(0.5, 10.0, 20.0), (2.0, 20.0, 30.0), (5.0, 30.0, 40.0)] {
            assert_eq!(p.eval(f64::from_bits(f64::to_bits(mid) - 1)), left, "just below {mid}");
            assert_eq!(p.eval(mid), right, "tie at {mid} goes right");
        }
        // Constant between midpoints.
        let expect = |t: f64| {
            if t < 0.5 {
                10.0
            } else if t < 2.0 {
                20.0
            } else if t < 5.0 {
                30.0
            } else {
                40.0
            }
        };
        for t in dense(0.0, 7.0, 701) {
            assert_eq!(p.eval(t), expect(t), "t = {t}");
        }
        // A single knot: the domain is that one point.
        let one = Interpolant::new(&[2.0], &[-1.0], Method::Nearest, false).expect("one knot is fine");
        assert_eq!(one.eval(2.0), -1.0);
        assert!(one.eval(2.5).is_nan());
        assert_eq!(one.sample(3), vec![(2.0, -1.0); 3]);
    }

    #[test]
    fn outside_the_range_and_nan_queries_give_nan() {
        let x = [1.0, 2.0, 4.0];
        let y = [0.0, 1.0, -1.0];
        for method in all_methods() {
            let p = Interpolant::new(&x, &y, method.clone(), false).expect("valid");
            for t in
                [0.999_999, f64::from_bits(4.0f64.to_bits() + 1), -1e300, f64::INFINITY, f64::NEG_INFINITY, f64::NAN]
            {
                assert!(p.eval(t).is_nan(), "{method:?} at {t}");
            }
            assert_eq!(p.eval(1.0), 0.0, "{method:?}");
            assert_eq!(p.eval(4.0), -1.0, "{method:?}");
        }
    }

    #[test]
    fn eval_many_equals_eval_for_sorted_and_unsorted_queries() {
        for case in fixture() {
            for method in all_methods() {
                let p = Interpolant::new(&case.x, &case.y, method.clone(), false).expect("valid");
                let (lo, hi) = p.domain();
                let mut sorted = dense(lo - 1.0, hi + 1.0, 3001);
                sorted.extend_from_slice(&case.x);
                sorted.sort_by(f64::total_cmp);
                // Unsorted: fixture order, plus NaN and out-of-range points, plus reversed.
                let mut unsorted = case.t.clone();
                unsorted.extend([f64::NAN, lo - 1.0, hi, lo, hi + 1.0]);
                unsorted.extend(sorted.iter().rev());
                for ts in [&sorted, &unsorted] {
                    let mut out = vec![0.0; ts.len()];
                    p.eval_many(ts, &mut out).expect("same length");
                    for (&t, &v) in ts.iter().zip(&out) {
                        let e = p.eval(t);
                        assert!(v.to_bits() == e.to_bits(), "{} {method:?} at {t}: {v} vs {e}", case.name);
                    }
                }
            }
        }
    }

    #[test]
    fn eval_many_with_sparse_sorted_queries_jumps_ahead() {
        // Far jumps (more than the forward-walk steps) must still land in the right interval.
        let x: Vec<f64> = (0..1000).map(f64::from).collect();
        let y: Vec<f64> = x.iter().map(|v| v * 0.5).collect();
        let p = Interpolant::new(&x, &y, Method::Linear, false).expect("valid");
        let ts = [0.25, 3.5, 500.75, 501.0, 998.5, 999.0];
        let mut out = [0.0; 6];
        p.eval_many(&ts, &mut out).expect("same length");
        assert_eq!(out, [0.125, 1.75, 250.375, 250.5, 499.25, 499.5]);
    }

    #[test]
    fn sample_spans_the_domain() {
        let p = pchip(&[-1.0, 0.0, 2.0], &[3.0, 1.0, 2.0]);
        let s = p.sample(5);
        let ts: Vec<f64> = s.iter().map(|q| q.0).collect();
        assert_eq!(ts, vec![-1.0, -0.25, 0.5, 1.25, 2.0]);
        assert!(s.iter().all(|&(t, v)| v == p.eval(t)));
        assert_eq!(p.sample(0), vec![]);
        assert_eq!(p.sample(1), vec![(-1.0, 3.0)]);
    }

    #[test]
    fn errors_name_the_problem() {
        use Interp1dError as E;
        let h = || Method::Hermite(Slopes::HarmonicMean);
        let err = |x: &[f64], y: &[f64], m: Method| Interpolant::new(x, y, m, false).expect_err("must fail");

        assert_eq!(err(&[1.0, 2.0], &[1.0], h()), E::LengthMismatch { x: 2, y: 1 });
        assert_eq!(err(&[1.0], &[1.0], Method::Linear), E::TooFewKnots { count: 1, min: 2 });
        assert_eq!(err(&[1.0], &[1.0], h()), E::TooFewKnots { count: 1, min: 2 });
        assert_eq!(err(&[], &[], Method::Nearest), E::TooFewKnots { count: 0, min: 1 });
        let e = err(&[0.0, 1.0, f64::NAN], &[0.0, f64::INFINITY, 1.0], h());
        assert_eq!(e, E::NonFinite { column: "y", index: 1, value: f64::INFINITY });
        let e = err(&[0.0, 1.0, f64::NAN], &[0.0, 1.0, 1.0], Method::Linear);
        assert!(matches!(e, E::NonFinite { column: "x", index: 2, value } if value.is_nan()));
        assert_eq!(err(&[3.0, 1.0, 2.0, 1.0], &[0.0; 4], h()), E::DuplicateX { x: 1.0, first: 1, second: 3 });
        assert_eq!(err(&[0.0, -0.0], &[1.0, 2.0], Method::Nearest), E::DuplicateX { x: -0.0, first: 0, second: 1 });
        assert_eq!(
            err(&[0.0, 1.0], &[0.0, 1.0], Method::Hermite(Slopes::Given(vec![1.0]))),
            E::SlopesLength { knots: 2, slopes: 1 }
        );
        assert_eq!(
            err(&[0.0, 1.0], &[0.0, 1.0], Method::Hermite(Slopes::Given(vec![1.0, f64::NEG_INFINITY]))),
            E::NonFinite { column: "slope", index: 1, value: f64::NEG_INFINITY }
        );
        assert_eq!(err(&[-1e308, 1e308], &[0.0, 1.0], Method::Linear), E::Overflow { x0: -1e308, x1: 1e308 });
        assert_eq!(err(&[0.0, 1e-300], &[-1e300, 1e300], h()), E::Overflow { x0: 0.0, x1: 1e-300 });

        let p = pchip(&[0.0, 1.0], &[0.0, 1.0]);
        let mut out = [0.0; 2];
        assert_eq!(p.eval_many(&[0.5], &mut out), Err(E::OutputLength { queries: 1, out: 2 }));

        // Messages keep the value and say what to do.
        let msg = E::NonFinite { column: "x", index: 4, value: f64::NAN }.to_string();
        assert!(msg.contains("x[4] = NaN") && msg.contains("drop or fill"), "{msg}");
        let msg = E::DuplicateX { x: 2.5, first: 0, second: 3 }.to_string();
        assert!(msg.contains("x = 2.5") && msg.contains("rows 0 and 3") && msg.contains("distinct"), "{msg}");
        let msg = E::TooFewKnots { count: 1, min: 2 }.to_string();
        assert!(msg.contains("at least 2 knots, got 1") && msg.contains("add sample points"), "{msg}");
        let msg = E::Overflow { x0: 0.0, x1: 1e-300 }.to_string();
        assert!(msg.contains("1e-300") && msg.contains("rescale"), "{msg}");
    }

    #[test]
    fn extreme_scales_build_and_stay_finite() {
        for scale in [1e-9, 1e9, 1e-150, 1e150] {
            let x: Vec<f64> = [0.0, 1.0, 1.5, 4.0].iter().map(|v| v * scale).collect();
            let y: Vec<f64> = [1.0, -2.0, 0.5, 0.25].iter().map(|v| v * scale).collect();
            for method in all_methods() {
                let p = Interpolant::new(&x, &y, method.clone(), true).expect("valid");
                for (t, v) in p.sample(101) {
                    assert!(v.is_finite(), "scale {scale} {method:?}: {v} at {t}");
                    assert!(v.abs() <= 4.0 * scale, "scale {scale} {method:?}: {v} at {t}");
                }
            }
        }
    }

    /// Benchmark: `cargo test --release -- --ignored --nocapture pchip_timing`.
    #[test]
    #[ignore]
    fn pchip_timing_1000_knots_10m_sorted_points() {
        let n = 1000;
        let x: Vec<f64> = (0..n).map(|i| f64::from(i) + 0.3 * (f64::from(i) * 0.7).sin()).collect();
        let y: Vec<f64> = x.iter().map(|v| (v * 0.05).sin() * 10.0 + v * 0.01).collect();
        let p = pchip(&x, &y);
        let (lo, hi) = p.domain();
        let m = 10_000_000;
        let ts: Vec<f64> = (0..m).map(|j| lo + (hi - lo) * (j as f64 / (m - 1) as f64)).map(|t| t.min(hi)).collect();
        let mut out = vec![0.0; m];
        let mut times = Vec::new();
        for _ in 0..5 {
            let start = std::time::Instant::now();
            p.eval_many(&ts, &mut out).expect("same length");
            times.push(start.elapsed().as_secs_f64());
        }
        assert!(out.iter().all(|v| v.is_finite()));
        let checksum: f64 = out.iter().sum();
        let best = times.iter().copied().fold(f64::INFINITY, f64::min);
        println!(
            "pchip 1000 knots, 10M sorted points: first {:.4} s, best of 5 {best:.4} s (checksum {checksum:.6e})",
            times.first().copied().unwrap_or(f64::NAN)
        );
    }
}
