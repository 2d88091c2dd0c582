//! DI002 `size-by-radius`: readers judge a circle by its area, so a marker whose radius is
//! proportional to the value shows a value twice as large as four times the ink.
//!
//! The rule fires for scatter charts whose size encoding says `mapping = "radius"`, and reports
//! the lie factor measured on the drawn markers: the ratio of the areas of the markers of the
//! largest and the smallest non-zero value, divided by the ratio of those values (1 for the
//! default `area` mapping; the value ratio itself for `radius`).

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{PerPoint, Role, Shape};
use crate::spec::{ChartKind, SizeMapping};

/// The rule.
pub static RULE: Rule = Rule {
    code: "DI002",
    name: "size-by-radius",
    category: Category::Integrity,
    severity: Severity::Warning,
    summary: "Marker radius, not area, is proportional to the value, so areas exaggerate differences.",
    check,
};

/// Area ratio over value ratio of the markers of the largest and smallest non-zero values, from
/// `(value, drawn radius)` pairs; `None` without two markers of positive value and radius.
pub fn lie_factor(markers: &[(f64, f64)]) -> Option<(f64, f64, f64)> {
    let usable = markers.iter().filter(|(v, r)| *v > 0.0 && v.is_finite() && *r > 0.0);
    let small = usable.clone().min_by(|a, b| a.0.total_cmp(&b.0))?;
    let large = usable.max_by(|a, b| a.0.total_cmp(&b.0))?;
    let values = large.0 / small.0;
    let areas = (large.1 / small.1).powi(2);
    Some((areas / values, large.0, small.0))
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let ChartKind::Scatter(options) = &s.chart.kind else { return Vec::new() };
    let Some(size) = &options.point_size else { return Vec::new() };
    let size = size.options();
    if size.mapping != Some(SizeMapping::Radius) {
        return Vec::new();
    }
    let values = s.table.column(&size.field).and_then(|c| c.numbers()).unwrap_or(&[]);
    let mut markers = Vec::new();
    s.output.scene.walk(|item| {
        if item.role == Role::DataMark
            && let Shape::Points(batch) = &item.shape
            && let PerPoint::Each(radii) = &batch.radius
        {
            for (&row, &r) in item.rows.iter().zip(radii) {
                markers.push((values.get(row as usize).copied().unwrap_or(f64::NAN), r));
            }
        }
    });
    let fmt = crate::guide::format::format_value;
    let measured = match lie_factor(&markers) {
        Some((factor, large, small)) if large > small => format!(
            ": the largest value ({}) is {:.2}× the smallest non-zero one ({}) but its marker covers {:.2}× the \
             area, a lie factor of {factor:.2}",
            fmt(large),
            large / small,
            fmt(small),
            factor * large / small,
        ),
        _ => " (the drawn values are all equal here, but any difference would be exaggerated)".to_string(),
    };
    vec![Issue::new(
        "size key",
        "point_size.mapping",
        format!("marker radius, not area, is proportional to `{}`{measured}", size.field),
        "remove `mapping = \"radius\"`: the default `area` makes each marker's area proportional to its value",
    )]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_proportional_to_value_gives_the_value_ratio() {
        // Values 1 and 4 with radii 2 and 8: areas 16×, values 4×, lie factor 4.
        let (f, large, small) = lie_factor(&[(1.0, 2.0), (4.0, 8.0), (0.0, 0.0)]).unwrap_or_default();
        assert!((f - 4.0).abs() < 1e-12);
        assert_eq!((large, small), (4.0, 1.0));
        // Area proportional to value: radii 2 and 4, lie factor 1.
        let (f, _, _) = lie_factor(&[(1.0, 2.0), (4.0, 4.0)]).unwrap_or_default();
        assert!((f - 1.0).abs() < 1e-12);
        assert_eq!(lie_factor(&[(0.0, 0.0)]), None);
    }
}
