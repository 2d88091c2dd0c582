//! DI001 `nonzero-baseline`: a bar's length is its value only when the bars start at zero. A
//! value axis that leaves zero out stretches every difference between bars.
//!
//! The rule reads the drawn bars (data-mark rectangles), finds each one's value in the chart's
//! derived table by its name (whether its rows are held or stayed in the plan), and compares the drawn lengths with the values. It reports Tufte's lie
//! factor (*The Visual Display of Quantitative Information*, 1983): the size of the effect shown
//! divided by the size of the effect in the data, where the size of an effect between the
//! smallest and the largest bar is `(largest − smallest) / smallest`. Bars from zero have a lie
//! factor of 1; with the axis starting at `b` it is `smallest / (smallest − b)`.

use std::collections::HashMap;

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::DerivedColumn;
use crate::mark::cartesian::bar::bar_name;
use crate::scene::{Role, Shape};
use crate::spec::ChartKind;

/// The rule.
pub static RULE: Rule = Rule {
    code: "DI001",
    name: "nonzero-baseline",
    category: Category::Integrity,
    severity: Severity::Error,
    summary: "Bars whose value axis does not start at zero, so their lengths exaggerate the differences.",
    check,
};

/// Lie factors this close to 1 count as honest (floating-point noise in pixel positions).
const TOLERANCE: f64 = 0.005;

/// One drawn bar: its label, its value and its rectangle's top and bottom edges.
struct DrawnBar {
    label: String,
    value: f64,
    top: f64,
    bottom: f64,
}

/// The lie factor of two bars: (shown effect) / (data effect), with effects measured from the
/// smaller bar. `None` when the data effect is zero or undefined.
pub fn lie_factor(small_value: f64, large_value: f64, small_length: f64, large_length: f64) -> Option<f64> {
    let data = (large_value - small_value) / small_value;
    if !(data.is_finite() && data != 0.0) {
        return None;
    }
    let shown = (large_length - small_length) / small_length;
    Some(if small_length <= 0.0 { f64::INFINITY } else { shown / data })
}

/// Each bar's value by its name in the scene, from the chart's derived table (one row per bar:
/// its category, colour group and value), whether its rows are held or stayed in the plan.
fn bar_values(s: &Subject<'_>, x: &str, color: Option<&str>, y: &str) -> HashMap<String, f64> {
    let column = |name: &str| s.output.derived.columns.iter().find(|(n, _)| n == name).map(|(_, c)| c);
    let (Some(DerivedColumn::Text(categories)), Some(DerivedColumn::Number(values))) = (column(x), column(y)) else {
        return HashMap::new();
    };
    let groups = match color.and_then(column) {
        Some(DerivedColumn::Text(groups)) => groups.clone(),
        _ => vec![String::new(); categories.len()],
    };
    let several = groups.iter().any(|g| g != &groups[0]);
    categories
        .iter()
        .zip(&groups)
        .zip(values)
        .map(|((c, g), v)| (bar_name(c, several.then_some(g.as_str())), *v))
        .collect()
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let ChartKind::Bar(options) = &s.chart.kind else { return Vec::new() };
    let y = options.y.options();
    let horizontal = options.orientation == Some(crate::mark::grouped::Orientation::Horizontal);
    let values = bar_values(s, &options.x.options().field, options.color.as_ref().map(|c| c.field()), &y.field);
    let mut bars = Vec::new();
    s.output.scene.walk(|item| {
        if item.role == Role::DataMark
            && let Shape::Rect(r) = &item.shape
            && let Some(&value) = item.label.as_ref().and_then(|l| values.get(l))
        {
            // A horizontal bar's ends, mirrored so that "up" is away from the baseline as for
            // a vertical one.
            let (top, bottom) = if horizontal { (-r.right(), -r.x) } else { (r.y, r.bottom()) };
            bars.push(DrawnBar { label: item.label.clone().unwrap_or_default(), value, top, bottom });
        }
    });
    let value_axis = if horizontal { "x axis" } else { "y axis" };
    let key = if y.domain.is_some() {
        "y.domain"
    } else if y.zero == Some(false) {
        "y.zero"
    } else {
        "y"
    };
    let hint = "bars encode values by length, which must start at zero: remove `zero = false` or widen `domain` \
                to include 0; to show small differences between large values, use a line or dot chart instead";
    let spec_excludes_zero = y.zero == Some(false) || y.domain.is_some_and(|[a, b]| a.min(b) > 0.0 || a.max(b) < 0.0);

    let Some(base) = baseline_px(&bars) else {
        return Vec::new();
    };
    // Positive bars rise from the baseline, negative ones hang from it: compare bars of one sign.
    let signed_length = |b: &DrawnBar| {
        let up = (b.bottom - base).abs() <= (b.top - base).abs();
        let h = b.bottom - b.top;
        if (b.value >= 0.0) == up { h } else { -h }
    };
    let mut measured: Vec<(f64, f64, &str)> = Vec::new();
    let mut sign = 1.0;
    for positive in [true, false] {
        let same_sign: Vec<(f64, f64, &str)> = bars
            .iter()
            .filter(|b| if positive { b.value > 0.0 } else { b.value < 0.0 })
            .map(|b| (b.value.abs(), signed_length(b), b.label.as_str()))
            .collect();
        let distinct = same_sign.iter().any(|a| same_sign.first().is_some_and(|f| f.0 != a.0));
        if distinct {
            measured = same_sign;
            sign = if positive { 1.0 } else { -1.0 };
            break;
        }
    }
    let smallest = measured.iter().min_by(|a, b| a.0.total_cmp(&b.0));
    let largest = measured.iter().max_by(|a, b| a.0.total_cmp(&b.0));
    let (Some(&(v_small, l_small, small_label)), Some(&(v_large, l_large, large_label))) = (smallest, largest) else {
        // One bar height only: the lengths cannot be checked, the spec can.
        return if spec_excludes_zero {
            vec![Issue::new(
                value_axis,
                key,
                "the value axis of the bars does not start at zero, so their lengths are not proportional to their values",
                hint,
            )]
        } else {
            Vec::new()
        };
    };
    let Some(factor) = lie_factor(v_small, v_large, l_small, l_large) else { return Vec::new() };
    if (factor - 1.0).abs() <= TOLERANCE {
        return Vec::new();
    }
    let per_unit = (l_large - l_small) / (v_large - v_small);
    let start = if per_unit.is_finite() && per_unit != 0.0 {
        let b = sign * (v_large - l_large / per_unit);
        format!("starts at {} instead of 0", crate::guide::format::format_value(b))
    } else {
        "does not start at 0".to_string()
    };
    let fmt = crate::guide::format::format_value;
    let (large, small) =
        (format!("`{large_label}` ({})", fmt(sign * v_large)), format!("`{small_label}` ({})", fmt(sign * v_small)));
    let shown = if l_small > 0.0 {
        format!(
            "the bar for {large} is drawn {:.2}× as long as the one for {small}, though its value is",
            l_large / l_small
        )
    } else {
        format!("the bar for {small} has no visible length beside the one for {large}, whose value is")
    };
    let factor_text = if factor.is_finite() { format!("{factor:.2}") } else { "∞".to_string() };
    vec![Issue::new(
        value_axis,
        key,
        format!(
            "the value axis of the bars {start}: {shown} only {:.2}× as large; \
             lie factor {factor_text} (effect shown / effect in the data)",
            v_large / v_small,
        ),
        hint,
    )]
}

/// The pixel row every bar starts from: the edge that all bars share (`None` without bars, or
/// when no edge is common to all of them).
fn baseline_px(bars: &[DrawnBar]) -> Option<f64> {
    let first = bars.first()?;
    let shared = |y: f64| bars.iter().all(|b| (b.top - y).abs() < 1e-6 || (b.bottom - y).abs() < 1e-6);
    [first.bottom, first.top].into_iter().find(|&y| shared(y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lie_factor_of_bars_from_forty_is_five() {
        // Values 50 and 60 drawn from 40: lengths 10 and 20 (in any unit).
        let f = lie_factor(50.0, 60.0, 10.0, 20.0).unwrap_or(f64::NAN);
        assert!((f - 5.0).abs() < 1e-12, "{f}");
        // From zero the lengths are proportional and the factor is 1.
        let f = lie_factor(50.0, 60.0, 50.0, 60.0).unwrap_or(f64::NAN);
        assert!((f - 1.0).abs() < 1e-12, "{f}");
        assert_eq!(lie_factor(5.0, 5.0, 1.0, 1.0), None);
        assert_eq!(lie_factor(5.0, 6.0, 0.0, 1.0), Some(f64::INFINITY));
    }
}
