//! Marker sizes by value (area or radius proportional) and the size key that explains them,
//! shared by the kinds that size marks by a column (scatter, graph).

use crate::guide::format::format_value;
use crate::guide::legend::Legend;
use crate::guide::ticks::extended;
use crate::scene::Color;
use crate::spec::SizeMapping;

/// Radius whose area is proportional to `value` (the largest value gets `max_radius`).
pub fn area_radius(value: f64, max_value: f64, max_radius: f64) -> f64 {
    if max_value <= 0.0 || !value.is_finite() || value <= 0.0 {
        return 0.0;
    }
    max_radius * (value / max_value).sqrt()
}

/// Radius whose length is proportional to `value` (the largest value gets `max_radius`): areas
/// then grow with the square of the value, which exaggerates differences (lint rule DI002).
pub fn linear_radius(value: f64, max_value: f64, max_radius: f64) -> f64 {
    if max_value <= 0.0 || !value.is_finite() || value <= 0.0 {
        return 0.0;
    }
    max_radius * (value / max_value)
}

/// The marker radius of `value` under `mapping`.
pub fn mapped_radius(value: f64, max_value: f64, max_radius: f64, mapping: SizeMapping) -> f64 {
    match mapping {
        SizeMapping::Area => area_radius(value, max_value, max_radius),
        SizeMapping::Radius => linear_radius(value, max_value, max_radius),
    }
}

/// A size key (areas) with three nice reference values up to the largest value.
pub fn size_legend(title: &str, unit: Option<&str>, max_value: f64, max_radius: f64) -> Legend {
    size_legend_mapped(title, unit, max_value, max_radius, SizeMapping::Area)
}

/// A size key drawn with the same `mapping` as the markers, with three nice reference values up
/// to the largest value.
pub fn size_legend_mapped(
    title: &str,
    unit: Option<&str>,
    max_value: f64,
    max_radius: f64,
    mapping: SizeMapping,
) -> Legend {
    let ticks = extended(0.0, max_value, 3, false);
    let mut values: Vec<f64> = ticks.values.into_iter().filter(|v| *v > 0.0 && *v <= max_value * 1.0001).collect();
    if values.is_empty() {
        values.push(max_value);
    }
    let entries = values.iter().map(|&v| (format_value(v), mapped_radius(v, max_value, max_radius, mapping))).collect();
    Legend::Size {
        title: crate::guide::axis::title_with_unit(title, unit),
        entries,
        color: Color::rgb(0x55, 0x55, 0x55),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn area_not_radius_is_proportional_to_value() {
        let r1 = area_radius(1.0, 4.0, 10.0);
        let r4 = area_radius(4.0, 4.0, 10.0);
        assert!((r4 - 10.0).abs() < 1e-12);
        // Four times the value, four times the area: twice the radius.
        assert!((r4 / r1 - 2.0).abs() < 1e-12);
        assert_eq!(area_radius(-1.0, 4.0, 10.0), 0.0);
        assert_eq!(area_radius(f64::NAN, 4.0, 10.0), 0.0);
    }

    #[test]
    fn radius_mapping_makes_radius_proportional_to_value() {
        let r1 = mapped_radius(1.0, 4.0, 10.0, SizeMapping::Radius);
        let r4 = mapped_radius(4.0, 4.0, 10.0, SizeMapping::Radius);
        assert!((r4 - 10.0).abs() < 1e-12);
        assert!((r4 / r1 - 4.0).abs() < 1e-12);
        assert_eq!(mapped_radius(2.0, 4.0, 10.0, SizeMapping::Area), area_radius(2.0, 4.0, 10.0));
        assert_eq!(linear_radius(-1.0, 4.0, 10.0), 0.0);
    }
}
