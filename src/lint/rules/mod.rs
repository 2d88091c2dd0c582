//! Every lint rule, one file each (a file may hold a few rules that share their measurement).
//! A rule's file holds its [`Rule`] statics and checks; trigger and non-trigger specs for every
//! rule are in `tests/suite/lint.rs` (the colour rules' in `tests/suite/lint_colour.rs`).

use super::Rule;

pub use hidden_values::one_dropped_rows_per_source;

mod axis_ticks;
mod axis_unit;
mod banking;
pub mod colour_keys;
mod colour_legend;
mod contour_labels;
mod cvd_confusable;
mod diverging_midpoint;
mod edge_crossings;
mod faces_key;
mod flow_key;
mod hidden_values;
mod missing_title;
mod nominal_continuous;
mod nonzero_baseline;
mod numbers_as_text;
mod overplotting;
mod rainbow_map;
mod repeated_x;
mod size_by_radius;
mod text_clipped;
mod text_contrast;
mod text_overlap;
mod text_size;
mod tiny_treemap_leaves;
mod too_many_categories;
mod unshared_scales;
mod volume_checks;

/// Every rule, in code order. Codes are stable: a retired rule's code is never reused.
pub static ALL: &[&Rule] = &[
    // Scale.
    &axis_ticks::AXIS_WITHOUT_TICKS,
    &axis_unit::RULE,
    &axis_ticks::TICK_COUNT,
    &colour_legend::RULE,
    &numbers_as_text::RULE,
    &volume_checks::WITHOUT_LEGEND,
    // Labelling.
    &missing_title::RULE,
    &text_overlap::RULE,
    &text_clipped::RULE,
    &text_size::RULE,
    &text_contrast::RULE,
    // Integrity.
    &nonzero_baseline::RULE,
    &size_by_radius::RULE,
    &hidden_values::LOG_NONPOSITIVE,
    &hidden_values::DROPPED_ROWS,
    &hidden_values::OUTSIDE_DOMAIN,
    &banking::RULE,
    &repeated_x::RULE,
    &volume_checks::ISO_OUTSIDE_RANGE,
    // Colour.
    &rainbow_map::RULE,
    &diverging_midpoint::RULE,
    &cvd_confusable::RULE,
    &too_many_categories::RULE,
    &nominal_continuous::RULE,
    // Comparison.
    &unshared_scales::RULE,
    &overplotting::RULE,
    // Technique.
    &tiny_treemap_leaves::RULE,
    &edge_crossings::RULE,
    &contour_labels::RULE,
    &flow_key::RULE,
    &faces_key::RULE,
    &volume_checks::COVERAGE,
];
