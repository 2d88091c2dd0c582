//! The cartesian frame every x/y chart kind shares: canvas size and theme from the chart spec,
//! the laid-out frame, and the final scene with the data marks clipped to the plot.

use super::{DEFAULT_SIZE, MarkError};
use crate::guide::Theme;
use crate::guide::layout::{self, Frame, FrameSpec, PositionAxis};
use crate::guide::legend::Legend;
use crate::scene::{Item, Role, Scene};
use crate::spec::Chart;

/// Lay out the frame of chart `index` around its axes and legends.
pub fn cartesian(
    chart: &Chart,
    index: usize,
    x: PositionAxis,
    y: PositionAxis,
    legends: Vec<Legend>,
) -> Result<(Frame, Theme), MarkError> {
    let [width, height] = chart.size.unwrap_or(DEFAULT_SIZE);
    let theme = Theme::with_font_size(chart.font_size.unwrap_or(12.0));
    let frame = layout::cartesian(&FrameSpec {
        width,
        height,
        title: chart.title.clone(),
        caption: chart.caption.clone(),
        x,
        y,
        legends,
        theme: theme.clone(),
    })
    .map_err(|e| MarkError::layout(index, &chart.name, e))?;
    Ok((frame, theme))
}

/// The chart's scene: background and grid, the marks clipped to the plot, then axes and legends.
pub fn scene(chart: &Chart, frame: Frame, theme: &Theme, marks: Vec<Item>) -> Scene {
    let [width, height] = chart.size.unwrap_or(DEFAULT_SIZE);
    let mut items = frame.under;
    items.push(Item::group(Role::DataMark, marks, Some(frame.plot)));
    items.extend(frame.over);
    Scene { width, height, background: theme.background, title: chart.title.clone(), items }
}
