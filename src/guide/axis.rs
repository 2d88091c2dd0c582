//! Axes: tick marks, tick labels, axis titles and grid lines for a scale along one side of a plot.
//!
//! Numeric axes label every k-th tick when neighbouring labels would overlap (a reader
//! interpolates between the numbers shown). Category axes label every category
//! ([`super::category_labels`]): wrapped, turned or cut, and left out only as a last resort.

use super::Theme;
use super::category_labels::{self, CategoryLabel};
use super::scale::{Scale, Tick};
use crate::scene::{Anchor, Baseline, Item, PathCmd, Point, Rect, Role, Shape, Style, Text};
use crate::text::measure;

/// Which side of the plot area an axis is drawn on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Below the plot; ticks run along x.
    Bottom,
    /// Left of the plot; ticks run along y.
    Left,
}

/// Gap between tick marks and their labels, and between labels and the axis title.
fn gap(theme: &Theme) -> f64 {
    theme.font_size * 0.35
}

/// The room an axis' tick labels may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LabelRoom {
    /// The stretch along the axis (x for a bottom axis, y for a left one) that labels set
    /// across it must stay inside, so that small multiples never push labels into their
    /// neighbours'.
    pub span: (f64, f64),
    /// The longest a category label may be (a turned bottom label, a left label), in pixels;
    /// longer ones are wrapped or cut with an ellipsis.
    pub reach: f64,
}

impl LabelRoom {
    /// No bounds along the axis, and category labels up to fifteen font sizes long.
    pub fn unbounded(theme: &Theme) -> LabelRoom {
        LabelRoom { span: (f64::NEG_INFINITY, f64::INFINITY), reach: theme.font_size * 15.0 }
    }

    /// The room on a `width` × `height` canvas: turned bottom labels up to 30% of its height,
    /// left labels up to a third of its width.
    pub fn on_canvas(side: Side, width: f64, height: f64, theme: &Theme) -> LabelRoom {
        let reach = match side {
            Side::Bottom => height * 0.3,
            Side::Left => width / 3.0,
        };
        let reach = if reach.is_finite() { reach.max(theme.font_size * 6.0) } else { theme.font_size * 15.0 };
        LabelRoom { span: (f64::NEG_INFINITY, f64::INFINITY), reach }
    }

    /// The same room with labels kept inside `span`.
    pub fn within(self, span: (f64, f64)) -> LabelRoom {
        LabelRoom { span, ..self }
    }
}

/// The tick labels of an axis as they are set.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisLabels {
    /// The labelled ticks with the lines drawn for each.
    pub labels: Vec<CategoryLabel>,
    /// Rotation of the labels in degrees, clockwise (0, or −45/−90 for turned category labels).
    pub angle: f64,
    /// Category labels left out because the bands are too narrow even for turned labels
    /// (always 0 on numeric axes, which leave out ticks by design).
    pub left_out: usize,
    /// Every tick of the scale, labelled or not: the tick marks of a category axis.
    all: Vec<Tick>,
    /// Whether the scale is a category (band) scale.
    categories: bool,
}

impl AxisLabels {
    /// The labelled ticks.
    pub fn ticks(&self) -> Vec<Tick> {
        self.labels.iter().map(|l| l.tick.clone()).collect()
    }

    /// The ticks that get a tick mark: every category of a category axis, the labelled ticks
    /// of a numeric one.
    fn marked(&self) -> Vec<Tick> {
        match self.categories {
            true => self.all.clone(),
            false => self.ticks(),
        }
    }

    /// The text items of the labels along `side` of `plot`: one per line, each carrying the
    /// full category name as hover text when its lines shorten it.
    pub fn items(&self, side: Side, plot: Rect, theme: &Theme) -> Vec<Item> {
        let offset = theme.tick_length + gap(theme);
        let line = category_labels::line_height(theme);
        let mut items = Vec::new();
        for label in &self.labels {
            let n = label.lines.len();
            for (k, content) in label.lines.iter().enumerate() {
                let pos = label.tick.position;
                let (at, anchor, baseline) = match side {
                    Side::Bottom if self.angle != 0.0 => {
                        (Point::new(pos, plot.bottom() + offset), Anchor::End, Baseline::Middle)
                    }
                    Side::Bottom => {
                        (Point::new(pos, plot.bottom() + offset + k as f64 * line), Anchor::Middle, Baseline::Top)
                    }
                    Side::Left => {
                        let shift = (k as f64 - (n as f64 - 1.0) / 2.0) * line;
                        (Point::new(plot.x - offset, pos + shift), Anchor::End, Baseline::Middle)
                    }
                };
                let text = Text {
                    at,
                    content: content.clone(),
                    size: theme.font_size,
                    anchor,
                    baseline,
                    angle: self.angle,
                    color: theme.muted_text,
                };
                let item = Item::text(Role::TickLabel, text).labelled(axis_name(side));
                items.push(match label.shortened() {
                    true => item.with_tooltip(label.tick.label.clone()),
                    false => item,
                });
            }
        }
        items
    }

    /// How far the labels reach out from the plot's edge past the tick marks and their gap:
    /// the height of a bottom axis' labels (one line at least), the width of a left axis'.
    fn depth(&self, side: Side, theme: &Theme) -> f64 {
        let size = theme.font_size;
        let one_line = measure("0", size).ascent + measure("0", size).descent;
        if self.angle == 0.0 {
            return match side {
                Side::Bottom => {
                    let lines = self.labels.iter().map(|l| l.lines.len()).max().unwrap_or(1).max(1);
                    one_line + (lines - 1) as f64 * category_labels::line_height(theme)
                }
                Side::Left => {
                    self.labels.iter().flat_map(|l| &l.lines).map(|l| measure(l, size).width).fold(0.0, f64::max)
                }
            };
        }
        let offset = theme.tick_length + gap(theme);
        let nominal = Rect::new(0.0, 0.0, 0.0, 0.0);
        let boxes = self.items(side, nominal, theme).into_iter().filter_map(|item| match item.shape {
            Shape::Text(t) => Some(crate::text::bounds(&t)),
            _ => None,
        });
        match side {
            Side::Bottom => boxes.map(|b| b.bottom() - offset).fold(one_line, f64::max),
            Side::Left => boxes.map(|b| -b.x - offset).fold(0.0, f64::max),
        }
    }

    /// The smallest and largest coordinate along the axis that the labels cover (x for a
    /// bottom axis, y for a left one); `None` without labels.
    pub fn along(&self, side: Side, theme: &Theme) -> Option<(f64, f64)> {
        let nominal = Rect::new(0.0, 0.0, 0.0, 0.0);
        self.items(side, nominal, theme)
            .into_iter()
            .filter_map(|item| match item.shape {
                Shape::Text(t) => Some(crate::text::bounds(&t)),
                _ => None,
            })
            .map(|b| match side {
                Side::Bottom => (b.x, b.right()),
                Side::Left => (b.y, b.bottom()),
            })
            .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
    }

    /// The widest any one label reaches along the axis, counted from its tick both ways: the
    /// gap small multiples keep between panels so their end labels do not meet. Turned labels
    /// end at their tick and lie parallel to their neighbours', so only their thickness counts.
    pub fn widest_along(&self, side: Side, theme: &Theme) -> f64 {
        let nominal = Rect::new(0.0, 0.0, 0.0, 0.0);
        let mut widest = 0.0f64;
        for item in self.items(side, nominal, theme) {
            let Shape::Text(t) = &item.shape else { continue };
            let b = crate::text::bounds(t);
            let reach = match (side, self.angle != 0.0) {
                (Side::Bottom, true) => 2.0 * (b.right() - t.at.x).max(0.0),
                (Side::Bottom, false) => b.w,
                (Side::Left, _) => b.h,
            };
            widest = widest.max(reach);
        }
        widest
    }
}

/// The tick labels of `scale` along `side` within `room`: category labels set by
/// [`category_labels`], numeric ones thinned as [`visible_ticks_within`] does.
pub fn labels(scale: &Scale, side: Side, theme: &Theme, room: &LabelRoom) -> AxisLabels {
    match scale {
        Scale::Band(_) => {
            let all = scale.ticks();
            let fit = match side {
                Side::Bottom => category_labels::fit_bottom(all.clone(), theme, room.span, room.reach),
                Side::Left => category_labels::fit_left(all.clone(), theme, room.reach),
            };
            AxisLabels { labels: fit.labels, angle: fit.angle, left_out: fit.left_out, all, categories: true }
        }
        _ => {
            let ticks = visible_ticks_within(scale, side, theme, room.span);
            let labels =
                ticks.iter().cloned().map(|tick| CategoryLabel { lines: vec![tick.label.clone()], tick }).collect();
            AxisLabels { labels, angle: 0.0, left_out: 0, all: ticks, categories: false }
        }
    }
}

/// The ticks that will be labelled: for a numeric axis all of them unless neighbouring labels
/// would overlap, in which case every k-th tick is kept (the smallest k that leaves a gap
/// between labels); for a category axis see [`labels`].
pub fn visible_ticks(scale: &Scale, side: Side, theme: &Theme) -> Vec<Tick> {
    labels(scale, side, theme, &LabelRoom::unbounded(theme)).ticks()
}

/// The numeric ticks whose labels fit inside `span` (along x for a bottom axis, along y for a
/// left one), thinned to every k-th when neighbours would overlap.
fn visible_ticks_within(scale: &Scale, side: Side, theme: &Theme, span: (f64, f64)) -> Vec<Tick> {
    let extent = |t: &Tick| match side {
        Side::Bottom => measure(&t.label, theme.font_size).width,
        Side::Left => theme.font_size,
    };
    let ticks: Vec<Tick> = scale
        .ticks()
        .into_iter()
        .filter(|t| t.position - extent(t) / 2.0 >= span.0 - 0.5 && t.position + extent(t) / 2.0 <= span.1 + 0.5)
        .collect();
    let min_gap = theme.font_size * 0.6;
    for step in 1..=ticks.len().max(1) {
        let kept: Vec<&Tick> = ticks.iter().step_by(step).collect();
        let fits = kept.windows(2).all(|pair| {
            let distance = (pair[1].position - pair[0].position).abs();
            distance >= (extent(pair[0]) + extent(pair[1])) / 2.0 + min_gap
        });
        if fits {
            return kept.into_iter().cloned().collect();
        }
    }
    ticks.into_iter().take(1).collect()
}

/// How far the axis (ticks, labels and title) extends outside the plot area, with its labels
/// set within `room`.
pub fn thickness(scale: &Scale, side: Side, title: Option<&str>, theme: &Theme, room: &LabelRoom) -> f64 {
    labels_thickness(&labels(scale, side, theme, room), side, title, theme)
}

/// [`thickness`] of labels already set.
pub fn labels_thickness(labels: &AxisLabels, side: Side, title: Option<&str>, theme: &Theme) -> f64 {
    let title_extent = match title {
        Some(t) if !t.is_empty() => {
            let m = measure(t, theme.label_size);
            gap(theme) * 2.0 + m.ascent + m.descent
        }
        _ => 0.0,
    };
    theme.tick_length + gap(theme) + labels.depth(side, theme) + title_extent
}

/// Grid lines across the plot at each visible tick.
pub fn grid(scale: &Scale, side: Side, plot: Rect, theme: &Theme) -> Vec<Item> {
    let mut cmds = Vec::new();
    for tick in visible_ticks(scale, side, theme) {
        let p = snap(tick.position);
        match side {
            Side::Bottom => {
                cmds.push(PathCmd::MoveTo(Point::new(p, plot.y)));
                cmds.push(PathCmd::LineTo(Point::new(p, plot.bottom())));
            }
            Side::Left => {
                cmds.push(PathCmd::MoveTo(Point::new(plot.x, p)));
                cmds.push(PathCmd::LineTo(Point::new(plot.right(), p)));
            }
        }
    }
    if cmds.is_empty() {
        return Vec::new();
    }
    vec![Item::new(Role::Grid, Shape::Path(cmds), Style::stroke(theme.grid, 1.0))]
}

/// Half-pixel snapping so 1-px lines are crisp in the PNG.
fn snap(v: f64) -> f64 {
    v.round() + 0.5
}

/// The axis line, tick marks, tick labels and title.
pub fn draw(scale: &Scale, side: Side, plot: Rect, title: Option<&str>, theme: &Theme) -> Vec<Item> {
    draw_within(scale, side, plot, title, theme, &LabelRoom::unbounded(theme))
}

/// [`draw`] with the labels set within `room` (see [`labels`]).
pub fn draw_within(
    scale: &Scale,
    side: Side,
    plot: Rect,
    title: Option<&str>,
    theme: &Theme,
    room: &LabelRoom,
) -> Vec<Item> {
    draw_labels(&labels(scale, side, theme, room), side, plot, title, theme)
}

/// [`draw`] with labels already set.
pub fn draw_labels(labels: &AxisLabels, side: Side, plot: Rect, title: Option<&str>, theme: &Theme) -> Vec<Item> {
    let name = axis_name(side);
    let mut items = vec![axis_line(&labels.marked(), side, plot, theme)];
    items.extend(labels.items(side, plot, theme));
    if let Some(title) = title.filter(|t| !t.is_empty()) {
        let outer = labels_thickness(labels, side, Some(title), theme);
        let text = match side {
            Side::Bottom => Text {
                at: Point::new(plot.x + plot.w / 2.0, plot.bottom() + outer),
                content: title.to_string(),
                size: theme.label_size,
                anchor: Anchor::Middle,
                baseline: Baseline::Bottom,
                angle: 0.0,
                color: theme.text,
            },
            Side::Left => Text {
                at: Point::new(plot.x - outer, plot.y + plot.h / 2.0),
                content: title.to_string(),
                size: theme.label_size,
                anchor: Anchor::Middle,
                baseline: Baseline::Top,
                angle: -90.0,
                color: theme.text,
            },
        };
        items.push(Item::text(Role::AxisTitle, text).labelled(name));
    }
    items
}

/// The name an axis' items carry (`x axis`, `y axis`), which lint rules and the explorer read.
fn axis_name(side: Side) -> &'static str {
    match side {
        Side::Bottom => "x axis",
        Side::Left => "y axis",
    }
}

/// The axis line and its tick marks at `ticks`.
fn axis_line(ticks: &[Tick], side: Side, plot: Rect, theme: &Theme) -> Item {
    let mut marks = Vec::new();
    match side {
        Side::Bottom => {
            let y = snap(plot.bottom());
            marks.push(PathCmd::MoveTo(Point::new(plot.x, y)));
            marks.push(PathCmd::LineTo(Point::new(plot.right(), y)));
            for t in ticks {
                let x = snap(t.position);
                marks.push(PathCmd::MoveTo(Point::new(x, y)));
                marks.push(PathCmd::LineTo(Point::new(x, y + theme.tick_length)));
            }
        }
        Side::Left => {
            let x = snap(plot.x) - 1.0;
            marks.push(PathCmd::MoveTo(Point::new(x, plot.y)));
            marks.push(PathCmd::LineTo(Point::new(x, plot.bottom())));
            for t in ticks {
                let y = snap(t.position);
                marks.push(PathCmd::MoveTo(Point::new(x, y)));
                marks.push(PathCmd::LineTo(Point::new(x - theme.tick_length, y)));
            }
        }
    }
    Item::new(Role::Axis, Shape::Path(marks), Style::stroke(theme.axis, 1.0)).labelled(axis_name(side))
}

/// The axis line and tick marks without labels or title: the inner sides of facet panels,
/// whose scale the outer panels label.
pub fn draw_unlabelled(scale: &Scale, side: Side, plot: Rect, theme: &Theme) -> Vec<Item> {
    let ticks = match scale {
        Scale::Band(_) => scale.ticks(),
        _ => visible_ticks(scale, side, theme),
    };
    vec![axis_line(&ticks, side, plot, theme)]
}

/// An axis title with its unit: "Petal length (cm)". A title that already says the unit in
/// parentheses ("Temperature (°C)") is kept as it is.
pub fn title_with_unit(title: &str, unit: Option<&str>) -> String {
    match unit.map(str::trim).filter(|u| !u.is_empty()) {
        Some(u) if !title.contains(&format!("({u})")) => format!("{title} ({u})"),
        _ => title.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numeric_axes_still_thin_their_labels() {
        use crate::guide::scale::LinearScale;
        let theme = Theme::default();
        // Ticks every 100 000 over 120 px: labels like "1000000" cannot all sit side by side.
        let Ok(linear) = LinearScale::new((0.0, 1_000_000.0), (0.0, 120.0), true, 10) else { panic!("scale") };
        let scale = Scale::Linear(linear);
        let labels = labels(&scale, Side::Bottom, &theme, &LabelRoom::unbounded(&theme));
        assert!(labels.labels.len() < scale.ticks().len(), "{} of {}", labels.labels.len(), scale.ticks().len());
        assert_eq!((labels.angle, labels.left_out), (0.0, 0), "thinned numbers are neither turned nor counted");
        assert!(labels.labels.iter().all(|l| l.lines == vec![l.tick.label.clone()]));
    }

    #[test]
    fn unit_goes_in_parentheses() {
        assert_eq!(title_with_unit("Petal length", Some("cm")), "Petal length (cm)");
        assert_eq!(title_with_unit("Count", None), "Count");
        assert_eq!(title_with_unit("Count", Some("  ")), "Count");
        assert_eq!(title_with_unit("Temperature (°C)", Some("°C")), "Temperature (°C)");
        assert_eq!(title_with_unit("Mass (g) per bird", Some(" g ")), "Mass (g) per bird");
    }
}
