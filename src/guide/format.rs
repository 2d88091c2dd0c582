//! Number formatting for tick labels, legends, hover text and lint messages.
//!
//! Conventions shared by every function here: negatives use the real minus sign U+2212 (`−`), never
//! "-0"; NaN is `NaN`, infinities are `∞` and `−∞`; exponents are written with superscript digits
//! (`1.5×10⁻⁵`); SI suffixes are `k` (10³), `M` (10⁶), `G` (10⁹) and `T` (10¹²).

use std::collections::HashMap;

/// The minus sign used in every label (U+2212).
pub const MINUS: char = '\u{2212}';
/// Most decimals any label is given before falling back to the shortest exact form.
const MAX_DECIMALS: usize = 17;

/// How a whole axis is written.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Style {
    /// Plain digits with a fixed number of decimals: `250000`, `0.25`.
    Fixed,
    /// Mantissa divided by `10^power` plus an SI suffix: `2.5M`.
    Si { power: i32, suffix: &'static str },
    /// Mantissa divided by `10^exp` with a common exponent: `2.5×10¹⁵`.
    Scientific { exp: i32 },
}

/// Labels for the tick values of one axis, in one consistent format.
///
/// Rules, by the largest magnitude `M` among the finite values:
/// - `M ≥ 10¹⁵` or `0 < M < 10⁻⁴`: scientific with one common exponent, `1.5×10¹⁵`;
/// - `10⁶ ≤ M < 10¹⁵` and a step of at least a thousandth of the suffix unit: SI suffix
///   (`M`, `G`, `T`, chosen by `M`), `2.5M`;
/// - otherwise plain digits without separators, `250000`, `0.25`.
///
/// Decimals are just enough to write `step` exactly (0.25 → 2), the same for every label, and
/// more if some value is not a multiple of the step (up to 12 decimals, ignoring float noise such
/// as 0.30000000000000004); zero is written `0` under a suffix or exponent. If two distinct values would still get the same
/// label, decimals are added until they differ (falling back to the shortest exact form), so
/// distinct values always get distinct labels. A step that is not finite and positive is
/// replaced by the smallest gap between the values.
pub fn format_ticks(values: &[f64], step: f64) -> Vec<String> {
    let max_abs = values.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    let step = effective_step(values, step);
    let style = choose_style(max_abs, step);
    let step_decimals = step.map(|s| decimals_for(in_units(s, style))).unwrap_or(0);
    let value_decimals = values.iter().map(|v| decimals_for(in_units(v.abs(), style))).max().unwrap_or(0);
    let base = step_decimals.max(value_decimals);
    for decimals in base..=MAX_DECIMALS {
        let labels: Vec<String> = values.iter().map(|&v| render(v, style, decimals)).collect();
        if all_distinct(values, &labels) {
            return labels;
        }
    }
    values.iter().map(|&v| shortest(v)).collect()
}

/// A general readable form of one number, with at most 4 significant digits: `0.1235`, `1235`,
/// `12.35k`, `1.5M`, `2.5×10¹⁵`, `1.235×10⁻⁵`.
///
/// `|v| < 10⁴` is written in plain digits (down to 10⁻⁴), `10⁴ ≤ |v| < 10¹⁵` with an SI suffix,
/// anything else in scientific notation; trailing zeros are dropped.
pub fn format_value(v: f64) -> String {
    if let Some(s) = special(v) {
        return s;
    }
    let (digits, exp) = significant(v.abs(), 4);
    let body = if !(-4..15).contains(&exp) {
        scientific(&digits, exp)
    } else if exp >= 4 {
        let (power, suffix) = si_for_exponent(exp);
        format!("{}{suffix}", place_point(&digits, exp - power))
    } else {
        place_point(&digits, exp)
    };
    with_sign(v < 0.0, body)
}

/// A label for a log-scale tick such as `1`, `0.05`, `20`, `1k`, `5M` or `10⁻³`.
///
/// `10⁻² ≤ v < 10³` is written in plain digits, `10³ ≤ v < 10¹⁵` with an SI suffix, anything
/// else as a power of ten (`10⁻³`, `2×10⁻³`). Up to 4 significant digits are kept.
pub fn format_log_tick(v: f64) -> String {
    if let Some(s) = special(v) {
        return s;
    }
    let (digits, exp) = significant(v.abs(), 4);
    let body = if !(-2..15).contains(&exp) {
        let mantissa = place_point(&digits, 0);
        if mantissa == "1" { format!("10{}", superscript(exp)) } else { scientific(&digits, exp) }
    } else if exp >= 3 {
        let (power, suffix) = si_for_exponent(exp);
        format!("{}{suffix}", place_point(&digits, exp - power))
    } else {
        place_point(&digits, exp)
    };
    with_sign(v < 0.0, body)
}

/// Values written on or beside marks (bar labels), in one style for all of them: plain digits,
/// an SI suffix or a common exponent, chosen from the largest magnitude as [`format_ticks`]
/// chooses. `decimals` is the number of digits after the point as written (of the mantissa under
/// a suffix or exponent); by default about three significant digits of the largest magnitude
/// ([`decimals_for_three_digits`]), and no more than any value needs, so whole numbers get none.
/// Unlike tick labels, equal-looking labels of distinct values are allowed: every label has the
/// same precision.
pub fn format_labels(values: &[f64], decimals: Option<usize>) -> Vec<String> {
    let max_abs = values.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    let style = choose_style(max_abs, None);
    let decimals = decimals.map(|d| d.min(MAX_DECIMALS)).unwrap_or_else(|| {
        let needed = values.iter().map(|v| decimals_for(in_units(v.abs(), style))).max().unwrap_or(0);
        decimals_for_three_digits(in_units(max_abs, style)).min(needed)
    });
    values.iter().map(|&v| render(v, style, decimals)).collect()
}

/// Decimals that give about three significant digits to a number of magnitude `largest`: 2 for
/// 1.23, 0 for 123 and above, at most 6; 0 for zero or a non-finite magnitude.
pub fn decimals_for_three_digits(largest: f64) -> usize {
    if largest == 0.0 || !largest.is_finite() {
        return 0;
    }
    (2 - largest.abs().log10().floor() as i64).clamp(0, 6) as usize
}

/// An integer exponent in superscript digits: `-3` → `⁻³`.
pub fn superscript(exp: i32) -> String {
    exp.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            other => other,
        })
        .collect()
}

/// Labels for NaN and the infinities; `None` for finite numbers.
fn special(v: f64) -> Option<String> {
    if v.is_nan() {
        Some("NaN".to_string())
    } else if v == f64::INFINITY {
        Some("∞".to_string())
    } else if v == f64::NEG_INFINITY {
        Some(format!("{MINUS}∞"))
    } else if v == 0.0 {
        Some("0".to_string())
    } else {
        None
    }
}

/// `step` if usable, else the smallest positive gap between the finite values.
fn effective_step(values: &[f64], step: f64) -> Option<f64> {
    if step.is_finite() && step != 0.0 {
        return Some(step.abs());
    }
    let mut finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    finite.sort_by(f64::total_cmp);
    let gaps = finite.windows(2).filter_map(|w| match w {
        [a, b] if b > a => Some(b - a),
        _ => None,
    });
    gaps.reduce(f64::min)
}

fn choose_style(max_abs: f64, step: Option<f64>) -> Style {
    if max_abs == 0.0 || !max_abs.is_finite() {
        return Style::Fixed;
    }
    if !(1e-4..1e15).contains(&max_abs) {
        return Style::Scientific { exp: significant(max_abs, 17).1 };
    }
    if max_abs >= 1e6 {
        let (power, suffix) = si_for_exponent(significant(max_abs, 17).1);
        let unit = 10f64.powi(power);
        if step.is_none_or(|s| s >= unit / 1000.0) {
            return Style::Si { power, suffix };
        }
    }
    Style::Fixed
}

/// `v` as a mantissa in the style's unit (`v / 10^power`), accurate even for subnormal units.
fn in_units(v: f64, style: Style) -> f64 {
    match style {
        Style::Fixed => v,
        Style::Si { power, .. } => v / 10f64.powi(power),
        // 10^exp is zero or subnormal below 1e-300: scale up first.
        Style::Scientific { exp } if exp < -300 => (v * 1e300) / pow10(exp + 300),
        Style::Scientific { exp } => v / pow10(exp),
    }
}

/// The exact power of ten (nearest `f64`), even far outside the range `powi` is exact in.
fn pow10(exp: i32) -> f64 {
    format!("1e{exp}").parse().unwrap_or(f64::NAN)
}

/// The fewest decimals (at most 12) that write `x` exactly, within rounding noise.
fn decimals_for(x: f64) -> usize {
    if !x.is_finite() || x <= 0.0 {
        return 0;
    }
    (0..=12)
        .find(|&d| {
            let scaled = x * 10f64.powi(d);
            (scaled - scaled.round()).abs() <= 1e-9 * scaled.max(1.0)
        })
        .map(|d| d as usize)
        .unwrap_or(12)
}

fn render(v: f64, style: Style, decimals: usize) -> String {
    if !v.is_finite() {
        return special(v).unwrap_or_default();
    }
    match style {
        Style::Fixed => fix_sign(format!("{v:.decimals$}")),
        Style::Si { suffix, .. } => {
            let m = fix_sign(format!("{:.decimals$}", in_units(v, style)));
            if is_zero(&m) { "0".to_string() } else { format!("{m}{suffix}") }
        }
        Style::Scientific { exp } => {
            let m = fix_sign(format!("{:.decimals$}", in_units(v, style)));
            if is_zero(&m) { "0".to_string() } else { format!("{m}×10{}", superscript(exp)) }
        }
    }
}

/// Whether a formatted number is all zeros.
fn is_zero(s: &str) -> bool {
    s.chars().all(|c| c == '0' || c == '.')
}

/// Replace an ASCII '-' by the minus sign, and drop the sign of a rounded zero.
fn fix_sign(s: String) -> String {
    match s.strip_prefix('-') {
        Some(rest) if is_zero(rest) => rest.to_string(),
        Some(rest) => format!("{MINUS}{rest}"),
        None => s,
    }
}

fn with_sign(negative: bool, body: String) -> String {
    if negative { format!("{MINUS}{body}") } else { body }
}

/// The shortest form that reads back as exactly `v` (distinct for distinct values).
fn shortest(v: f64) -> String {
    special(v).unwrap_or_else(|| fix_sign(format!("{v}")))
}

/// Whether distinct values got distinct labels.
fn all_distinct(values: &[f64], labels: &[String]) -> bool {
    let mut seen: HashMap<&str, f64> = HashMap::new();
    for (v, label) in values.iter().zip(labels) {
        match seen.get(label.as_str()) {
            Some(other) if other != v && !(other.is_nan() && v.is_nan()) => return false,
            Some(_) => {}
            None => {
                seen.insert(label.as_str(), *v);
            }
        }
    }
    true
}

/// `x > 0` rounded to `sig` significant digits: the digits (no point) and the decimal exponent,
/// so that `x ≈ d.ddd × 10^exp`.
fn significant(x: f64, sig: usize) -> (String, i32) {
    let s = format!("{:.*e}", sig.saturating_sub(1), x);
    let (mantissa, exp) = s.split_once('e').unwrap_or((s.as_str(), "0"));
    (mantissa.replace('.', ""), exp.parse().unwrap_or(0))
}

/// Digits `d₀d₁d₂…` as the decimal `d₀.d₁d₂… × 10^exp`, trailing zeros dropped.
fn place_point(digits: &str, exp: i32) -> String {
    let int_len = exp + 1;
    let (int_part, frac_part) = if int_len <= 0 {
        let zeros = "0".repeat(int_len.unsigned_abs() as usize);
        ("0".to_string(), format!("{zeros}{digits}"))
    } else {
        let n = int_len as usize;
        let int: String = digits.chars().chain(std::iter::repeat('0')).take(n).collect();
        (int, digits.chars().skip(n).collect())
    };
    let frac = frac_part.trim_end_matches('0');
    if frac.is_empty() { int_part } else { format!("{int_part}.{frac}") }
}

/// `d.ddd×10ⁿ` with trailing zeros of the mantissa dropped.
fn scientific(digits: &str, exp: i32) -> String {
    format!("{}×10{}", place_point(digits, 0), superscript(exp))
}

/// The SI power (3, 6, 9, 12) and suffix for a decimal exponent in 3..15.
fn si_for_exponent(exp: i32) -> (i32, &'static str) {
    match exp {
        i32::MIN..=5 => (3, "k"),
        6..=8 => (6, "M"),
        9..=11 => (9, "G"),
        _ => (12, "T"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ticks(values: &[f64], step: f64) -> Vec<String> {
        format_ticks(values, step)
    }

    #[test]
    fn fixed_decimals_follow_the_step() {
        assert_eq!(ticks(&[0.0, 0.25, 0.5, 0.75, 1.0], 0.25), ["0.00", "0.25", "0.50", "0.75", "1.00"]);
        assert_eq!(ticks(&[0.0, 20.0, 40.0], 20.0), ["0", "20", "40"]);
        assert_eq!(ticks(&[0.1, 0.2, 0.30000000000000004], 0.1), ["0.1", "0.2", "0.3"]);
        assert_eq!(ticks(&[0.0, 50000.0, 100000.0, 250000.0], 50000.0), ["0", "50000", "100000", "250000"]);
    }

    #[test]
    fn negatives_use_the_minus_sign_and_no_negative_zero() {
        assert_eq!(ticks(&[-2.0, -1.0, -0.0, 1.0], 1.0), ["\u{2212}2", "\u{2212}1", "0", "1"]);
        assert_eq!(ticks(&[-1e-17, 0.5], 0.5), ["0.0", "0.5"]);
        assert_eq!(ticks(&[-0.25, 0.0, 0.25], 0.25), ["\u{2212}0.25", "0.00", "0.25"]);
    }

    #[test]
    fn si_and_scientific() {
        assert_eq!(ticks(&[0.0, 2e6, 4e6, 6e6], 2e6), ["0", "2M", "4M", "6M"]);
        assert_eq!(ticks(&[1e6, 1.5e6, 2e6], 5e5), ["1.0M", "1.5M", "2.0M"]);
        assert_eq!(ticks(&[2e9, 4e9], 2e9), ["2G", "4G"]);
        // A step too fine for a suffix keeps plain digits.
        assert_eq!(ticks(&[1000000.0, 1000001.0, 1000002.0], 1.0), ["1000000", "1000001", "1000002"]);
        assert_eq!(ticks(&[0.0, 5e14, 1e15, 1.5e15], 5e14), ["0", "0.5×10¹⁵", "1.0×10¹⁵", "1.5×10¹⁵"]);
        assert_eq!(ticks(&[0.0, 2e-5, 4e-5], 2e-5), ["0", "2×10⁻⁵", "4×10⁻⁵"]);
        assert_eq!(ticks(&[-3e-5, 0.0], 3e-5), ["\u{2212}3×10⁻⁵", "0"]);
        // Subnormals are not exact decimals; the labels show the digits that tell them apart.
        assert_eq!(ticks(&[0.0, 5e-324, 1e-323], 5e-324), ["0", "4.94065646×10⁻³²⁴", "9.88131292×10⁻³²⁴"]);
        assert_eq!(ticks(&[-1e300, 0.0, 1e300], 1e300), ["\u{2212}1×10³⁰⁰", "0", "1×10³⁰⁰"]);
    }

    #[test]
    fn labels_stay_distinct() {
        // The given step is too coarse for these values; they get the decimals they need.
        assert_eq!(ticks(&[1.0, 1.25, 1.5], 1.0), ["1.00", "1.25", "1.50"]);
        // No usable step: the smallest gap is used.
        assert_eq!(ticks(&[0.0, 0.5, 2.0], f64::NAN), ["0.0", "0.5", "2.0"]);
        // Non-finite values pass through.
        assert_eq!(ticks(&[f64::NAN, f64::NEG_INFINITY, 1.0], 1.0), ["NaN", "\u{2212}∞", "1"]);
        assert!(ticks(&[], 1.0).is_empty());
        // Values closer than 12 decimals: decimals are added until the labels differ.
        let close = [1.0, 1.0 + f64::EPSILON];
        assert_eq!(ticks(&close, f64::EPSILON), ["1.0000000000000000", "1.0000000000000002"]);
    }

    #[test]
    fn general_values() {
        assert_eq!(format_value(0.0), "0");
        assert_eq!(format_value(-0.0), "0");
        assert_eq!(format_value(1234.5678), "1235");
        assert_eq!(format_value(1.23456), "1.235");
        assert_eq!(format_value(-0.5), "\u{2212}0.5");
        assert_eq!(format_value(0.0001), "0.0001");
        assert_eq!(format_value(0.0000123456), "1.235×10⁻⁵");
        assert_eq!(format_value(12346.0), "12.35k");
        assert_eq!(format_value(9999.6), "10k");
        assert_eq!(format_value(999_999.9), "1M");
        assert_eq!(format_value(1.5e6), "1.5M");
        assert_eq!(format_value(2.5e15), "2.5×10¹⁵");
        assert_eq!(format_value(100.0), "100");
        assert_eq!(format_value(f64::NAN), "NaN");
        assert_eq!(format_value(f64::INFINITY), "∞");
        assert_eq!(format_value(f64::NEG_INFINITY), "\u{2212}∞");
        assert_eq!(format_value(f64::MAX), "1.798×10³⁰⁸");
        assert_eq!(format_value(5e-324), "4.941×10⁻³²⁴");
    }

    #[test]
    fn log_ticks() {
        let got: Vec<String> = [1e-3, 0.01, 0.05, 1.0, 20.0, 100.0, 1e3, 5e5, 1e6, 2e9, 1e15, 3e-7]
            .iter()
            .map(|&v| format_log_tick(v))
            .collect();
        assert_eq!(got, ["10⁻³", "0.01", "0.05", "1", "20", "100", "1k", "500k", "1M", "2G", "10¹⁵", "3×10⁻⁷"]);
    }

    #[test]
    fn superscripts() {
        assert_eq!(superscript(-12), "⁻¹²");
        assert_eq!(superscript(308), "³⁰⁸");
    }
}
