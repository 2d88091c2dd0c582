//! Sizes and colours of the non-data ink: text, axes, grid, background.

use crate::scene::Color;

/// Smallest text dataink draws on purpose, in CSS pixels (about 6.75 pt): labels that would be
/// smaller are hidden instead, and lint rule LB004 reports any text below it.
pub const MIN_TEXT_SIZE: f64 = 9.0;

/// The look of guides. Derived from the chart's base font size so everything scales together.
#[derive(Clone, Debug, PartialEq)]
pub struct Theme {
    /// Tick labels and legend entries.
    pub font_size: f64,
    /// Axis and legend titles.
    pub label_size: f64,
    /// The chart title.
    pub title_size: f64,
    /// The caption.
    pub caption_size: f64,
    /// Main text colour.
    pub text: Color,
    /// Secondary text (captions, tick labels).
    pub muted_text: Color,
    /// Axis lines and ticks.
    pub axis: Color,
    /// Grid lines.
    pub grid: Color,
    /// Canvas background.
    pub background: Color,
    /// Length of tick marks.
    pub tick_length: f64,
    /// Outer margin of the canvas.
    pub margin: f64,
}

impl Theme {
    /// The default theme for a base font size (tick labels) in CSS pixels.
    pub fn with_font_size(font_size: f64) -> Theme {
        let f = if font_size.is_finite() && font_size > 0.0 { font_size } else { 12.0 };
        Theme {
            font_size: f,
            label_size: f * 13.0 / 12.0,
            title_size: f * 16.0 / 12.0,
            caption_size: f * 11.0 / 12.0,
            text: Color::rgb(0x22, 0x22, 0x22),
            muted_text: Color::rgb(0x44, 0x44, 0x44),
            axis: Color::rgb(0x55, 0x55, 0x55),
            grid: Color::rgb(0xe6, 0xe6, 0xe6),
            background: Color::WHITE,
            tick_length: (f * 0.4).max(3.0),
            margin: (f * 1.2).max(8.0),
        }
    }
}

impl Default for Theme {
    fn default() -> Theme {
        Theme::with_font_size(12.0)
    }
}
