//! Ticks for time axes. Instants are `f64` milliseconds since the Unix epoch, in UTC.
//!
//! An interval is picked from a calendar ladder (milliseconds, seconds, minutes, hours, days,
//! Monday-aligned weeks, months, years) so that the tick count is closest to the target, and ticks
//! sit on calendar boundaries: multiples of the interval since midnight for clock intervals, month
//! starts whose month number is a multiple of the interval (Jan/Apr/Jul/Oct for 3 months), and
//! 1 January of years divisible by the interval.
//!
//! Labels depend on the interval: years `2024`, months `Mar 2024`, days and weeks `Mar 05`, hours
//! and minutes `14:30`, seconds `14:30:05`, milliseconds `14:30:05.250`.

use chrono::{DateTime, Datelike, NaiveDate, Utc};

use super::format::format_value;
use super::ticks::MAX_TARGET;

/// Instants further than this from the epoch (about 253,000 years) get no ticks.
pub const MAX_ABS_MS: f64 = 8.0e15;
/// Most ticks [`time_ticks`] returns.
pub const MAX_TIME_TICKS: usize = 2 * MAX_TARGET + 2;

const SECOND: i64 = 1000;
const MINUTE: i64 = 60 * SECOND;
const HOUR: i64 = 60 * MINUTE;
const DAY: i64 = 24 * HOUR;
const WEEK: i64 = 7 * DAY;
/// 1970-01-05 00:00 UTC, the first Monday after the epoch.
const FIRST_MONDAY: i64 = 4 * DAY;
/// Mean month and year lengths, used only to rank intervals.
const MONTH_MS: f64 = 30.436_875 * DAY as f64;
const YEAR_MS: f64 = 365.2425 * DAY as f64;

/// What a tick label shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unit {
    Millis,
    Seconds,
    Minutes,
    Hours,
    Days,
    Months,
    Years,
}

/// A tick interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Interval {
    /// A fixed duration; boundaries are `offset + n·ms`.
    Fixed { ms: i64, offset: i64, unit: Unit },
    /// Calendar months; boundaries are month starts with `(12·year + month0) % n == 0`.
    Months(i64),
    /// Calendar years; boundaries are 1 January of years divisible by `n`.
    Years(i64),
}

impl Interval {
    fn fixed(ms: i64, unit: Unit) -> Interval {
        Interval::Fixed { ms, offset: 0, unit }
    }

    /// Rough length in milliseconds.
    fn approx_ms(self) -> f64 {
        match self {
            Interval::Fixed { ms, .. } => ms as f64,
            Interval::Months(n) => n as f64 * MONTH_MS,
            Interval::Years(n) => n as f64 * YEAR_MS,
        }
    }

    fn unit(self) -> Unit {
        match self {
            Interval::Fixed { unit, .. } => unit,
            Interval::Months(_) => Unit::Months,
            Interval::Years(_) => Unit::Years,
        }
    }

    /// The last boundary at or before `t`.
    fn floor(self, t: i64) -> Option<i64> {
        match self {
            Interval::Fixed { ms, offset, .. } => Some(offset + (t - offset).div_euclid(ms) * ms),
            Interval::Months(n) => {
                let total = month_index(t)?;
                month_start(total - total.rem_euclid(n))
            }
            Interval::Years(n) => {
                let year = i64::from(DateTime::<Utc>::from_timestamp_millis(t)?.year());
                month_start((year - year.rem_euclid(n)) * 12)
            }
        }
    }

    /// The boundary after boundary `b`.
    fn next(self, b: i64) -> Option<i64> {
        match self {
            Interval::Fixed { ms, .. } => b.checked_add(ms),
            Interval::Months(n) => month_start(month_index(b)? + n),
            Interval::Years(n) => month_start(month_index(b)? + 12 * n),
        }
    }

    /// The first boundary at or after `t`.
    fn ceil(self, t: i64) -> Option<i64> {
        let f = self.floor(t)?;
        if f == t { Some(f) } else { self.next(f) }
    }
}

/// `12·year + month0` of the instant `t`.
fn month_index(t: i64) -> Option<i64> {
    let dt = DateTime::<Utc>::from_timestamp_millis(t)?;
    Some(i64::from(dt.year()) * 12 + i64::from(dt.month0()))
}

/// Milliseconds at 00:00 UTC on the first day of month `12·year + month0`.
fn month_start(index: i64) -> Option<i64> {
    let year = i32::try_from(index.div_euclid(12)).ok()?;
    let month = u32::try_from(index.rem_euclid(12) + 1).ok()?;
    Some(NaiveDate::from_ymd_opt(year, month, 1)?.and_hms_opt(0, 0, 0)?.and_utc().timestamp_millis())
}

/// Every interval, shortest first.
fn ladder() -> Vec<Interval> {
    let mut out = Vec::new();
    out.extend([1, 2, 5, 10, 20, 50, 100, 200, 500].map(|n| Interval::fixed(n, Unit::Millis)));
    out.extend([1, 2, 5, 10, 15, 30].map(|n| Interval::fixed(n * SECOND, Unit::Seconds)));
    out.extend([1, 2, 5, 10, 15, 30].map(|n| Interval::fixed(n * MINUTE, Unit::Minutes)));
    out.extend([1, 3, 6, 12].map(|n| Interval::fixed(n * HOUR, Unit::Hours)));
    out.extend([1, 2].map(|n| Interval::fixed(n * DAY, Unit::Days)));
    out.push(Interval::Fixed { ms: WEEK, offset: FIRST_MONDAY, unit: Unit::Days });
    out.extend([1, 3, 6].map(Interval::Months));
    let mut decade = 1;
    while decade <= 100_000 {
        out.extend([1, 2, 5].map(|n| Interval::Years(n * decade)));
        decade *= 10;
    }
    out
}

/// The interval whose tick count over `span_ms` is closest (by ratio) to `target`.
fn choose_interval(span_ms: f64, target: usize) -> Interval {
    let ladder = ladder();
    let first = Interval::fixed(1, Unit::Millis);
    if span_ms.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return first;
    }
    let target = target.clamp(1, MAX_TARGET) as f64;
    let misfit = |i: &Interval| (span_ms / i.approx_ms() / target).ln().abs();
    ladder.into_iter().min_by(|a, b| misfit(a).total_cmp(&misfit(b))).unwrap_or(first)
}

fn valid(ms: f64) -> bool {
    ms.is_finite() && ms.abs() <= MAX_ABS_MS
}

/// Both bounds valid, ascending.
fn ordered(min_ms: f64, max_ms: f64) -> Option<(f64, f64)> {
    if !valid(min_ms) || !valid(max_ms) {
        return None;
    }
    Some(if min_ms <= max_ms { (min_ms, max_ms) } else { (max_ms, min_ms) })
}

/// Ticks on calendar boundaries within `min_ms..=max_ms`, about `target` of them, each with its
/// label. Reversed bounds are swapped. No ticks for `target == 0`, a non-finite bound or one
/// further than [`MAX_ABS_MS`] from the epoch; never more than [`MAX_TIME_TICKS`].
pub fn time_ticks(min_ms: f64, max_ms: f64, target: usize) -> Vec<(f64, String)> {
    let Some((lo, hi)) = ordered(min_ms, max_ms) else { return Vec::new() };
    if target == 0 {
        return Vec::new();
    }
    let interval = choose_interval(hi - lo, target);
    let end = hi.floor() as i64;
    let mut out = Vec::new();
    let mut t = interval.ceil(lo.ceil() as i64);
    while let Some(b) = t {
        if b > end || out.len() >= MAX_TIME_TICKS {
            break;
        }
        out.push((b as f64, label(b, interval.unit())));
        t = interval.next(b);
    }
    out
}

/// `min_ms..max_ms` widened outwards to the boundaries of the interval [`time_ticks`] would pick;
/// `None` when the bounds are invalid (see [`time_ticks`]) or a boundary is out of range.
pub fn nice_time_domain(min_ms: f64, max_ms: f64, target: usize) -> Option<(f64, f64)> {
    let (lo, hi) = ordered(min_ms, max_ms)?;
    let interval = choose_interval(hi - lo, target);
    let lo = interval.floor(lo.floor() as i64)?;
    let hi = interval.ceil(hi.ceil() as i64)?;
    Some((lo as f64, hi as f64))
}

/// A full timestamp for hover text and messages: `2024-03-05 14:30:05` (with `.250` when there
/// are milliseconds). Instants chrono cannot represent are written as plain numbers.
pub fn format_timestamp(ms: f64) -> String {
    let whole = ms.round();
    let dt = if valid(whole) { DateTime::<Utc>::from_timestamp_millis(whole as i64) } else { None };
    match dt {
        Some(dt) if (whole as i64).rem_euclid(SECOND) != 0 => dt.format("%Y-%m-%d %H:%M:%S%.3f").to_string(),
        Some(dt) => dt.format("%Y-%m-%d %H:%M:%S").to_string(),
        None => format_value(ms),
    }
}

/// The label of the boundary `ms` for ticks of the given unit.
fn label(ms: i64, unit: Unit) -> String {
    let Some(dt) = DateTime::<Utc>::from_timestamp_millis(ms) else { return format_value(ms as f64) };
    let pattern = match unit {
        Unit::Millis => "%H:%M:%S%.3f",
        Unit::Seconds => "%H:%M:%S",
        Unit::Minutes | Unit::Hours => "%H:%M",
        Unit::Days => "%b %d",
        Unit::Months => "%b %Y",
        Unit::Years => "%Y",
    };
    dt.format(pattern).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Milliseconds of a UTC date and time (test helper; panics on bad test input).
    fn ms(y: i32, mo: u32, d: u32, h: u32, mi: u32, s: u32) -> f64 {
        NaiveDate::from_ymd_opt(y, mo, d).unwrap().and_hms_opt(h, mi, s).unwrap().and_utc().timestamp_millis() as f64
    }

    fn labels(t: &[(f64, String)]) -> Vec<&str> {
        t.iter().map(|(_, l)| l.as_str()).collect()
    }

    #[test]
    fn quarters_over_a_year() {
        let t = time_ticks(ms(2024, 1, 1, 0, 0, 0), ms(2024, 12, 31, 0, 0, 0), 6);
        assert_eq!(labels(&t), ["Jan 2024", "Apr 2024", "Jul 2024", "Oct 2024"]);
        assert_eq!(t[1].0, ms(2024, 4, 1, 0, 0, 0));
    }

    #[test]
    fn years_divisible_by_the_interval() {
        let t = time_ticks(ms(1998, 6, 1, 0, 0, 0), ms(2024, 3, 1, 0, 0, 0), 5);
        assert_eq!(labels(&t), ["2000", "2005", "2010", "2015", "2020"]);
        let t = time_ticks(ms(1961, 3, 1, 0, 0, 0), ms(1970, 1, 1, 0, 0, 0), 5);
        assert_eq!(labels(&t), ["1962", "1964", "1966", "1968", "1970"]);
        assert_eq!(t[0].0, ms(1962, 1, 1, 0, 0, 0));
    }

    #[test]
    fn days_and_mondays() {
        let t = time_ticks(ms(2024, 3, 1, 0, 0, 0), ms(2024, 3, 8, 0, 0, 0), 8);
        assert_eq!(labels(&t), ["Mar 01", "Mar 02", "Mar 03", "Mar 04", "Mar 05", "Mar 06", "Mar 07", "Mar 08"]);
        let t = time_ticks(ms(2024, 3, 1, 0, 0, 0), ms(2024, 4, 15, 0, 0, 0), 6);
        assert_eq!(labels(&t), ["Mar 04", "Mar 11", "Mar 18", "Mar 25", "Apr 01", "Apr 08", "Apr 15"]);
    }

    #[test]
    fn clock_intervals() {
        let t = time_ticks(ms(2024, 3, 5, 0, 0, 0), ms(2024, 3, 5, 12, 0, 0), 4);
        assert_eq!(labels(&t), ["00:00", "03:00", "06:00", "09:00", "12:00"]);
        let t = time_ticks(ms(2024, 3, 5, 14, 0, 0), ms(2024, 3, 5, 15, 0, 0), 4);
        assert_eq!(labels(&t), ["14:00", "14:15", "14:30", "14:45", "15:00"]);
        let t = time_ticks(ms(2024, 3, 5, 14, 30, 0), ms(2024, 3, 5, 14, 30, 10), 5);
        assert_eq!(labels(&t), ["14:30:00", "14:30:02", "14:30:04", "14:30:06", "14:30:08", "14:30:10"]);
        let t = time_ticks(1000.0, 1010.0, 5);
        assert_eq!(labels(&t)[..2], ["00:00:01.000", "00:00:01.002"]);
    }

    #[test]
    fn bad_input() {
        assert!(time_ticks(f64::NAN, 1.0, 5).is_empty());
        assert!(time_ticks(0.0, f64::INFINITY, 5).is_empty());
        assert!(time_ticks(0.0, 1e300, 5).is_empty());
        assert!(time_ticks(0.0, 1e9, 0).is_empty());
        let fwd = time_ticks(ms(2020, 1, 1, 0, 0, 0), ms(2021, 1, 1, 0, 0, 0), 5);
        assert_eq!(time_ticks(ms(2021, 1, 1, 0, 0, 0), ms(2020, 1, 1, 0, 0, 0), 5), fwd);
        // A single instant: one tick if it lies on a millisecond, none otherwise.
        assert_eq!(time_ticks(5.0, 5.0, 5).len(), 1);
        assert!(time_ticks(5.5, 5.5, 5).is_empty());
    }

    #[test]
    fn counts_stay_bounded() {
        for &(lo, hi) in &[(-MAX_ABS_MS, MAX_ABS_MS), (0.0, 1.0), (0.0, 3e10), (-1e14, 1e12), (1e15, 1e15 + 5e8)] {
            for target in [1, 2, 5, 10, 50, 1000] {
                let t = time_ticks(lo, hi, target);
                let cap = 2 * target.min(MAX_TARGET) + 2;
                assert!(t.len() <= cap, "{lo}..{hi} target {target}: {} ticks", t.len());
                assert!(t.windows(2).all(|w| w[1].0 > w[0].0));
                assert!(t.iter().all(|(v, _)| *v >= lo && *v <= hi));
            }
        }
    }

    #[test]
    fn nice_domain_extends_to_boundaries() {
        // About 79 days per tick: quarters.
        let d = nice_time_domain(ms(2024, 1, 10, 0, 0, 0), ms(2024, 11, 20, 0, 0, 0), 4);
        assert_eq!(d, Some((ms(2024, 1, 1, 0, 0, 0), ms(2025, 1, 1, 0, 0, 0))));
        // About 53 days per tick: months.
        let d = nice_time_domain(ms(2024, 1, 10, 0, 0, 0), ms(2024, 11, 20, 0, 0, 0), 6);
        assert_eq!(d, Some((ms(2024, 1, 1, 0, 0, 0), ms(2024, 12, 1, 0, 0, 0))));
        assert_eq!(nice_time_domain(f64::NAN, 0.0, 5), None);
    }

    #[test]
    fn timestamps() {
        assert_eq!(format_timestamp(ms(2024, 3, 5, 14, 30, 5)), "2024-03-05 14:30:05");
        assert_eq!(format_timestamp(ms(2024, 3, 5, 14, 30, 5) + 250.0), "2024-03-05 14:30:05.250");
        assert_eq!(format_timestamp(f64::NAN), "NaN");
    }
}
