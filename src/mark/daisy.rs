//! `daisy` (in progress).

use super::{ChartOutput, MarkError};
use crate::data::Table;
use crate::selection::Highlight;
use crate::spec::Chart;

/// Draw the chart.
pub fn draw(
    chart: &Chart,
    _options: &crate::spec::DaisyOptions,
    index: usize,
    _table: &Table,
    _highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    Err(MarkError::at(index, &[], format!("chart \"{}\": not yet drawn", chart.name), ""))
}
