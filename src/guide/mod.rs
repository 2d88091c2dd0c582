//! Guides shared by every chart kind: scales and ticks, number and time formats, colour maps,
//! axes, legends and colour bars, and the frame that places them around a plot area.

pub mod axis;
pub mod category_labels;
pub mod color;
pub mod colour_science;
pub mod count_scale;
pub mod format;
pub mod layout;
pub mod legend;
pub mod scale;
pub mod theme;
pub mod ticks;
pub mod time;
pub mod transfer_legend;

pub use theme::Theme;
