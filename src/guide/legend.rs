//! Legends: categorical swatches, continuous colour bars, transfer functions and marker-size
//! keys.

use std::sync::Arc;

use super::Theme;
use super::color::ContinuousMap;
use super::count_scale::{CountColours, CountScale};
use super::scale::{LinearScale, Scale};
use super::transfer_legend::TransferLegend;
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Raster, Rect, Role, Shape, Style, Text};
use crate::text::measure;

/// Entries beyond this many are summarised as "… and N more".
pub const MAX_ENTRIES: usize = 24;
/// Entry labels wider than this many pixels (at the legend font size) are truncated with "…".
const MAX_LABEL_WIDTH: f64 = 200.0;

/// How a categorical legend draws its swatch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Symbol {
    /// A filled circle (scatter points).
    Circle,
    /// A short line (line series).
    Line,
    /// A filled square (areas: treemap cells, matrix cells).
    Square,
}

/// A legend block placed beside the plot.
#[derive(Clone, Debug)]
pub enum Legend {
    /// One swatch per category.
    Categorical {
        /// Legend title.
        title: String,
        /// Labels and their colours, in display order.
        entries: Vec<(String, Color)>,
        /// Swatch shape.
        symbol: Symbol,
    },
    /// A continuous colour ramp with a numeric axis.
    ColorBar {
        /// Colour-bar title.
        title: String,
        /// The colour map.
        map: ContinuousMap,
        /// Data values at the bottom and top of the ramp.
        domain: (f64, f64),
    },
    /// Discrete colour steps (filled contour bands): one block per interval, edges labelled.
    Steps {
        /// Legend title.
        title: String,
        /// Interval edges, ascending; `colors.len() + 1` of them.
        edges: Vec<f64>,
        /// Colour of each interval, bottom to top.
        colors: Vec<Color>,
    },
    /// Lines of text under a title: a key that is not a colour or size (e.g. which column
    /// drives which facial feature).
    Notes {
        /// Legend title.
        title: String,
        /// The lines, top to bottom.
        lines: Vec<String>,
    },
    /// A volume's transfer function: colour ramp, opacity curve and the histogram of the
    /// volume's values along one value axis.
    TransferFunction {
        /// Legend title.
        title: String,
        /// The ramp, curve and histogram.
        function: TransferLegend,
    },
    /// The counts of a density view: the ramp as its bins are shaded, ticks at real counts
    /// wherever the shading puts them.
    Counts {
        /// Legend title.
        title: String,
        /// How a bin is coloured from its ramp position.
        colours: CountColours,
        /// Where each count falls on the ramp.
        scale: CountScale,
    },
    /// Reference circles for a size (area) encoding.
    Size {
        /// Legend title.
        title: String,
        /// Labels and radii of the reference circles, smallest first.
        entries: Vec<(String, f64)>,
        /// Circle colour.
        color: Color,
    },
}

const COLOR_BAR_WIDTH: f64 = 12.0;

impl Legend {
    /// Width and height the legend needs, given the height available beside the plot.
    pub fn extent(&self, theme: &Theme, available_height: f64) -> (f64, f64) {
        let title_h = self.title_height(theme);
        let row = row_height(theme);
        match self {
            Legend::Categorical { title, entries, .. } => {
                let shown = displayed_entries(entries, rows_fitting(available_height - title_h, row));
                let label_w = shown.iter().map(|(l, _)| measure(l, theme.font_size).width).fold(0.0, f64::max);
                let w = (swatch_width(theme) + theme.font_size * 0.5 + label_w)
                    .max(measure(&shown_title(title, theme), theme.label_size).width);
                (w, title_h + row * shown.len() as f64)
            }
            Legend::ColorBar { title, .. } => {
                let h = color_bar_length(available_height - title_h) + title_h;
                let scale = self.color_bar_scale(theme, available_height);
                let label_w = scale
                    .map(|s| s.ticks().iter().map(|t| measure(&t.label, theme.font_size).width).fold(0.0, f64::max))
                    .unwrap_or(0.0);
                let w = (COLOR_BAR_WIDTH + theme.tick_length + 3.0 + label_w)
                    .max(measure(&shown_title(title, theme), theme.label_size).width);
                (w, h + theme.font_size * 0.5)
            }
            Legend::Steps { title, edges, .. } => {
                let h = color_bar_length(available_height - title_h) + title_h;
                let labels = step_labels(edges);
                let label_w = labels.iter().map(|l| measure(l, theme.font_size).width).fold(0.0, f64::max);
                let w = (COLOR_BAR_WIDTH + theme.tick_length + 3.0 + label_w)
                    .max(measure(&shown_title(title, theme), theme.label_size).width);
                (w, h + theme.font_size * 0.5)
            }
            Legend::Counts { title, scale, .. } => {
                let length = color_bar_length(available_height - title_h);
                let label_w =
                    scale.ticks(length, theme).iter().map(|t| measure(&t.1, theme.font_size).width).fold(0.0, f64::max);
                let w = (COLOR_BAR_WIDTH + theme.tick_length + 3.0 + label_w)
                    .max(measure(&shown_title(title, theme), theme.label_size).width);
                (w, length + title_h + theme.font_size * 0.5)
            }
            Legend::TransferFunction { title, function } => {
                let length = color_bar_length(available_height - title_h - theme.font_size * 2.0);
                let (w, h) = function.extent(theme, length);
                (w.max(measure(&shown_title(title, theme), theme.label_size).width), title_h + h)
            }
            Legend::Notes { title, lines } => {
                let w = lines.iter().map(|l| measure(l, theme.font_size).width).fold(0.0, f64::max);
                (w.max(measure(&shown_title(title, theme), theme.label_size).width), title_h + row * lines.len() as f64)
            }
            Legend::Size { title, entries, .. } => {
                let max_r = entries.iter().map(|e| e.1).fold(0.0, f64::max);
                let label_w = entries.iter().map(|(l, _)| measure(l, theme.font_size).width).fold(0.0, f64::max);
                let h: f64 = entries.iter().map(|e| (2.0 * e.1).max(row)).sum::<f64>() + 4.0 * entries.len() as f64;
                let w = (2.0 * max_r + theme.font_size * 0.5 + label_w)
                    .max(measure(&shown_title(title, theme), theme.label_size).width);
                (w, title_h + h)
            }
        }
    }

    /// The legend's title.
    pub fn title(&self) -> &str {
        match self {
            Legend::Categorical { title, .. }
            | Legend::ColorBar { title, .. }
            | Legend::Steps { title, .. }
            | Legend::Notes { title, .. }
            | Legend::TransferFunction { title, .. }
            | Legend::Counts { title, .. }
            | Legend::Size { title, .. } => title,
        }
    }

    fn title_height(&self, theme: &Theme) -> f64 {
        if self.title().is_empty() { 0.0 } else { theme.label_size * 1.6 }
    }

    fn color_bar_scale(&self, theme: &Theme, available_height: f64) -> Option<Scale> {
        let Legend::ColorBar { domain, .. } = self else { return None };
        value_scale(*domain, color_bar_length(available_height - self.title_height(theme)), theme)
    }

    /// Draw the legend with its top-left corner at `at`.
    pub fn draw(&self, at: Point, theme: &Theme, available_height: f64) -> Vec<Item> {
        let mut items = Vec::new();
        let title_h = self.title_height(theme);
        if title_h > 0.0 {
            items.push(Item::text(
                Role::Legend,
                Text {
                    at,
                    content: shown_title(self.title(), theme),
                    size: theme.label_size,
                    anchor: Anchor::Start,
                    baseline: Baseline::Top,
                    angle: 0.0,
                    color: theme.text,
                },
            ));
        }
        let top = at.y + title_h;
        let row = row_height(theme);
        match self {
            Legend::Categorical { entries, symbol, .. } => {
                let fitting = rows_fitting(available_height - title_h, row);
                for (i, (label, color)) in displayed_entries(entries, fitting).iter().enumerate() {
                    let cy = top + row * (i as f64 + 0.5);
                    if *color != Color::TRANSPARENT {
                        items.push(swatch(*symbol, Point::new(at.x, cy), *color, theme));
                    }
                    items.push(entry_label(
                        Point::new(at.x + swatch_width(theme) + theme.font_size * 0.5, cy),
                        label,
                        theme,
                    ));
                }
            }
            Legend::ColorBar { map, .. } => {
                let length = color_bar_length(available_height - title_h);
                let bar = Rect::new(at.x, top + theme.font_size * 0.5, COLOR_BAR_WIDTH, length);
                items.push(Item::new(Role::Legend, Shape::Image(ramp(map, bar)), Style::default()));
                items.push(Item::new(Role::Legend, Shape::Rect(bar), Style::stroke(theme.axis, 0.5)));
                if let Some(scale) = self.color_bar_scale(theme, available_height) {
                    let mut ticks = Vec::new();
                    for t in scale.ticks() {
                        bar_tick(&mut ticks, &mut items, bar, bar.y + t.position, &t.label, theme);
                    }
                    items.push(Item::new(Role::Legend, Shape::Path(ticks), Style::stroke(theme.axis, 1.0)));
                }
            }
            Legend::Steps { edges, colors, .. } => {
                let length = color_bar_length(available_height - title_h);
                let bar = Rect::new(at.x, top + theme.font_size * 0.5, COLOR_BAR_WIDTH, length);
                let n = colors.len().max(1) as f64;
                let step = length / n;
                for (i, c) in colors.iter().enumerate() {
                    let y = bar.bottom() - step * (i as f64 + 1.0);
                    items.push(Item::new(Role::Legend, Shape::Rect(Rect::new(bar.x, y, bar.w, step)), Style::fill(*c)));
                }
                items.push(Item::new(Role::Legend, Shape::Rect(bar), Style::stroke(theme.axis, 0.5)));
                // Label every edge if they fit, else every k-th.
                let labels = step_labels(edges);
                let every = ((theme.font_size * 1.2) / step.max(1e-9)).ceil().max(1.0) as usize;
                let mut ticks = Vec::new();
                // The outer edges are the data's extremes, not levels: they stay unlabelled.
                let last = labels.len().saturating_sub(1);
                for (i, label) in labels.iter().enumerate().step_by(every).filter(|(i, _)| *i != 0 && *i != last) {
                    bar_tick(&mut ticks, &mut items, bar, bar.bottom() - step * i as f64, label, theme);
                }
                items.push(Item::new(Role::Legend, Shape::Path(ticks), Style::stroke(theme.axis, 1.0)));
            }
            Legend::TransferFunction { function, .. } => {
                let length = color_bar_length(available_height - title_h - theme.font_size * 2.0);
                items.extend(function.draw(Point::new(at.x, top), theme, length));
            }
            Legend::Counts { colours, scale, .. } => {
                let length = color_bar_length(available_height - title_h);
                let bar = Rect::new(at.x, top + theme.font_size * 0.5, COLOR_BAR_WIDTH, length);
                items.push(Item::new(Role::Legend, Shape::Image(count_ramp(colours, bar)), Style::default()));
                items.push(Item::new(Role::Legend, Shape::Rect(bar), Style::stroke(theme.axis, 0.5)));
                let mut ticks = Vec::new();
                for (t, label) in scale.ticks(length, theme) {
                    bar_tick(&mut ticks, &mut items, bar, bar.bottom() - t * length, &label, theme);
                }
                items.push(Item::new(Role::Legend, Shape::Path(ticks), Style::stroke(theme.axis, 1.0)));
            }
            Legend::Notes { lines, .. } => {
                for (i, line) in lines.iter().enumerate() {
                    items.push(entry_label(Point::new(at.x, top + row * (i as f64 + 0.5)), line, theme));
                }
            }
            Legend::Size { entries, color, .. } => {
                let max_r = entries.iter().map(|e| e.1).fold(0.0, f64::max);
                let mut y = top;
                for (label, r) in entries {
                    let h = (2.0 * r).max(row);
                    let cy = y + h / 2.0;
                    items.push(Item::new(
                        Role::Legend,
                        Shape::Circle { center: Point::new(at.x + max_r, cy), radius: *r },
                        Style {
                            fill: Some(color.with_opacity(0.35)),
                            stroke: Some(crate::scene::Stroke::solid(*color, 1.0)),
                        },
                    ));
                    items.push(entry_label(Point::new(at.x + 2.0 * max_r + theme.font_size * 0.5, cy), label, theme));
                    y += h + 4.0;
                }
            }
        }
        items
    }
}

/// Vertical gap between stacked legends.
fn stack_gap(theme: &Theme) -> f64 {
    theme.font_size * 1.5
}

/// Width of a column of legends stacked top to bottom (0 for none).
pub fn stack_width(legends: &[Legend], theme: &Theme, available_height: f64) -> f64 {
    legends.iter().map(|l| l.extent(theme, available_height).0).fold(0.0, f64::max)
}

/// Room a legend column takes beside a plot: its width plus a gap, or 0 without legends.
pub fn stack_room(legends: &[Legend], theme: &Theme, available_height: f64) -> f64 {
    let w = stack_width(legends, theme, available_height);
    if w > 0.0 { w + theme.font_size * 1.5 } else { 0.0 }
}

/// Height of a column of legends stacked top to bottom, as [`draw_stack`] draws them (0 for none).
pub fn stack_height(legends: &[Legend], theme: &Theme, available_height: f64) -> f64 {
    let mut y = 0.0;
    for (k, legend) in legends.iter().enumerate() {
        y += legend.extent(theme, available_height - y).1;
        if k + 1 < legends.len() {
            y += stack_gap(theme);
        }
    }
    y
}

/// Draw legends top to bottom from `at` (the column's top-left corner).
pub fn draw_stack(legends: &[Legend], at: Point, theme: &Theme, available_height: f64) -> Vec<Item> {
    let mut items = Vec::new();
    let mut y = at.y;
    for legend in legends {
        // Each legend gets the height the ones above it left.
        let left = available_height - (y - at.y);
        items.extend(legend.draw(Point::new(at.x, y), theme, left));
        y += legend.extent(theme, left).1 + stack_gap(theme);
    }
    items
}

/// Labels of the step edges: the interior edges formatted consistently (as tick labels of their
/// smallest step); the outer edges, the data's extremes, are left empty.
fn step_labels(edges: &[f64]) -> Vec<String> {
    let inner = edges.get(1..edges.len().saturating_sub(1)).unwrap_or(&[]);
    let step = inner.windows(2).map(|w| (w[1] - w[0]).abs()).filter(|d| *d > 0.0).fold(f64::INFINITY, f64::min);
    let mut labels = vec![String::new()];
    labels.extend(crate::guide::format::format_ticks(inner, if step.is_finite() { step } else { 1.0 }));
    if edges.len() > 1 {
        labels.push(String::new());
    }
    labels
}

/// The value scale along a bar `length` tall, bottom to top, with about one tick per three
/// lines of text (2 to 8).
pub(super) fn value_scale(domain: (f64, f64), length: f64, theme: &Theme) -> Option<Scale> {
    let target = ((length / (theme.font_size * 3.0)).floor() as usize).clamp(2, 8);
    LinearScale::new(domain, (length, 0.0), false, target).ok().map(Scale::Linear)
}

/// A tick mark on the right of a colour bar at height `y`, and its label.
pub(super) fn bar_tick(ticks: &mut Vec<PathCmd>, items: &mut Vec<Item>, bar: Rect, y: f64, label: &str, theme: &Theme) {
    ticks.push(PathCmd::MoveTo(Point::new(bar.right(), y)));
    ticks.push(PathCmd::LineTo(Point::new(bar.right() + theme.tick_length, y)));
    items.push(Item::text(
        Role::Legend,
        Text {
            at: Point::new(bar.right() + theme.tick_length + 3.0, y),
            content: label.to_string(),
            size: theme.font_size,
            anchor: Anchor::Start,
            baseline: Baseline::Middle,
            angle: 0.0,
            color: theme.muted_text,
        },
    ));
}

fn row_height(theme: &Theme) -> f64 {
    theme.font_size * 1.5
}

fn swatch_width(theme: &Theme) -> f64 {
    theme.font_size * 1.2
}

fn color_bar_length(available: f64) -> f64 {
    available.clamp(60.0, 220.0)
}

/// A legend title as drawn: cut with "…" to the width of the widest entry label allowed, so a
/// long title cannot squeeze the plot.
fn shown_title(title: &str, theme: &Theme) -> String {
    truncate_to_width(title, MAX_LABEL_WIDTH * theme.label_size / 12.0, theme.label_size)
}

/// How many legend rows of height `row` fit in `height` (at least one).
fn rows_fitting(height: f64, row: f64) -> usize {
    if row > 0.0 && height.is_finite() { ((height / row).floor().max(1.0)) as usize } else { usize::MAX }
}

/// Entries to show in at most `rows` rows: at most [`MAX_ENTRIES`] entries, labels truncated,
/// and a summary line for the rest (which takes the last row when they do not all fit).
fn displayed_entries(entries: &[(String, Color)], rows: usize) -> Vec<(String, Color)> {
    let fits = entries.len() <= MAX_ENTRIES && entries.len() <= rows;
    let keep = if fits { entries.len() } else { MAX_ENTRIES.min(rows.saturating_sub(1)) };
    let mut shown: Vec<(String, Color)> =
        entries.iter().take(keep).map(|(l, c)| (truncate_to_width(l, MAX_LABEL_WIDTH, 12.0), *c)).collect();
    if keep < entries.len() {
        shown.push((format!("… and {} more", entries.len() - keep), Color::TRANSPARENT));
    }
    shown
}

/// `text` shortened with a trailing "…" so that it measures at most `max_width` at `size`.
pub fn truncate_to_width(text: &str, max_width: f64, size: f64) -> String {
    if measure(text, size).width <= max_width {
        return text.to_string();
    }
    let chars: Vec<char> = text.chars().collect();
    let (mut lo, mut hi) = (0usize, chars.len());
    while lo < hi {
        let mid = (lo + hi).div_ceil(2);
        let candidate: String = chars[..mid].iter().collect::<String>() + "…";
        if measure(&candidate, size).width <= max_width { lo = mid } else { hi = mid - 1 }
    }
    chars[..lo].iter().collect::<String>() + "…"
}

fn swatch(symbol: Symbol, center: Point, color: Color, theme: &Theme) -> Item {
    let w = swatch_width(theme);
    match symbol {
        Symbol::Circle => Item::new(
            Role::Legend,
            Shape::Circle { center: Point::new(center.x + w / 2.0, center.y), radius: theme.font_size * 0.35 },
            Style::fill(color),
        ),
        Symbol::Line => Item::new(
            Role::Legend,
            Shape::Path(vec![
                PathCmd::MoveTo(Point::new(center.x, center.y)),
                PathCmd::LineTo(Point::new(center.x + w, center.y)),
            ]),
            Style::stroke(color, 2.5),
        ),
        Symbol::Square => {
            let side = theme.font_size * 0.75;
            Item::new(
                Role::Legend,
                Shape::Rect(Rect::new(center.x + (w - side) / 2.0, center.y - side / 2.0, side, side)),
                Style::fill(color),
            )
        }
    }
}

fn entry_label(at: Point, label: &str, theme: &Theme) -> Item {
    Item::text(
        Role::Legend,
        Text {
            at,
            content: label.to_string(),
            size: theme.font_size,
            anchor: Anchor::Start,
            baseline: Baseline::Middle,
            angle: 0.0,
            color: theme.text,
        },
    )
}

/// A 1-pixel-wide raster of the colour map, top = high values.
/// The ramp of a density legend, top (the most rows) to bottom, as its bins are coloured.
fn count_ramp(colours: &CountColours, dest: Rect) -> Raster {
    const STEPS: u32 = 256;
    let rgba = (0..STEPS)
        .flat_map(|i| {
            let c = colours.at(1.0 - i as f64 / (STEPS - 1) as f64);
            [c.r, c.g, c.b, c.a]
        })
        .collect();
    Raster { dest, width: 1, height: STEPS, rgba: Arc::new(rgba), smooth: true }
}

fn ramp(map: &ContinuousMap, dest: Rect) -> Raster {
    const STEPS: u32 = 256;
    let mut rgba = Vec::with_capacity(STEPS as usize * 4);
    for i in 0..STEPS {
        let t = 1.0 - i as f64 / (STEPS - 1) as f64;
        let c = map.at(t);
        rgba.extend_from_slice(&[c.r, c.g, c.b, c.a]);
    }
    Raster { dest, width: 1, height: STEPS, rgba: Arc::new(rgba), smooth: true }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn truncation_keeps_short_labels_and_shortens_long_ones() {
        assert_eq!(truncate_to_width("setosa", 100.0, 12.0), "setosa");
        let long = "a".repeat(500);
        let cut = truncate_to_width(&long, 100.0, 12.0);
        assert!(cut.ends_with('…'));
        assert!(measure(&cut, 12.0).width <= 100.0);
        assert!(cut.chars().count() > 5);
    }

    #[test]
    fn many_categories_are_summarised() {
        let entries: Vec<(String, Color)> = (0..30).map(|i| (format!("c{i}"), Color::BLACK)).collect();
        let shown = displayed_entries(&entries, usize::MAX);
        assert_eq!(shown.len(), MAX_ENTRIES + 1);
        assert_eq!(shown[MAX_ENTRIES].0, "… and 6 more");
        // Ten rows of room: nine entries and the summary.
        let shown = displayed_entries(&entries, 10);
        assert_eq!(shown.len(), 10);
        assert_eq!(shown[9].0, "… and 21 more");
        // Everything fits: no summary.
        assert_eq!(displayed_entries(&entries[..5], 10).len(), 5);
    }
}
