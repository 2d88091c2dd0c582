//! What a chart's spec says about its encodings, in one shape for every kind: its cartesian
//! axes and its colour encodings, as each kind's [`Technique`] reports them. Rules read these
//! instead of matching every kind themselves.

pub use crate::mark::registry::{AxisSpec, ColourSpec};
use crate::mark::{Technique, technique};
use crate::spec::Chart;

/// The x and y axes of the kinds drawn on one cartesian frame (scatter, line, bar, interp1d,
/// contour, image, scattered, flow). Other kinds (small multiples, hierarchies, networks, polar
/// layouts) return an empty list. A line chart's y axis is its first y column.
pub fn cartesian_axes(chart: &Chart) -> Vec<AxisSpec> {
    technique(&chart.kind).cartesian_axes()
}

/// The colour encodings a chart's spec declares by column (`color = ...` or a field `z`
/// coloured by a map). Kinds that colour by a fixed rule (treemap branches, link weights, flow
/// speed) report their `scheme` through [`scheme_of`] instead.
pub fn colour_encodings(chart: &Chart) -> Vec<ColourSpec> {
    technique(&chart.kind).colour_encodings()
}

/// The chart-level `scheme` of kinds that have one outside a colour encoding, with its key.
pub fn scheme_of(chart: &Chart) -> Option<(&'static str, &str)> {
    let technique: &dyn Technique = technique(&chart.kind);
    technique.scheme().map(|s| ("scheme", s))
}
