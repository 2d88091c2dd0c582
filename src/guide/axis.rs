//! Axes: tick marks, tick labels, axis titles and grid lines for a scale along one side of a plot.

use super::Theme;
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

/// The ticks that will be labelled: all of them unless neighbouring labels would overlap, in which
/// case every k-th tick is kept (the smallest k that leaves a gap between labels).
pub fn visible_ticks(scale: &Scale, side: Side, theme: &Theme) -> Vec<Tick> {
    visible_ticks_within(scale, side, theme, (f64::NEG_INFINITY, f64::INFINITY))
}

/// [`visible_ticks`] among the ticks whose labels fit inside `span` (along x for a bottom axis,
/// along y for a left one), so that small multiples never push labels into their neighbours'.
pub fn visible_ticks_within(scale: &Scale, side: Side, theme: &Theme, span: (f64, f64)) -> Vec<Tick> {
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

/// How far the axis (ticks, labels and title) extends outside the plot area.
pub fn thickness(scale: &Scale, side: Side, title: Option<&str>, theme: &Theme) -> f64 {
    let ticks = visible_ticks(scale, side, theme);
    let labels = match side {
        Side::Bottom => measure("0", theme.font_size).ascent + measure("0", theme.font_size).descent,
        Side::Left => ticks.iter().map(|t| measure(&t.label, theme.font_size).width).fold(0.0, f64::max),
    };
    let title_extent = match title {
        Some(t) if !t.is_empty() => {
            let m = measure(t, theme.label_size);
            gap(theme) * 2.0 + m.ascent + m.descent
        }
        _ => 0.0,
    };
    theme.tick_length + gap(theme) + labels + title_extent
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
    draw_within(scale, side, plot, title, theme, (f64::NEG_INFINITY, f64::INFINITY))
}

/// [`draw`] labelling only ticks whose labels fit inside `span` (see [`visible_ticks_within`]).
pub fn draw_within(
    scale: &Scale,
    side: Side,
    plot: Rect,
    title: Option<&str>,
    theme: &Theme,
    span: (f64, f64),
) -> Vec<Item> {
    let ticks = visible_ticks_within(scale, side, theme, span);
    let name = axis_name(side);
    let mut items = vec![axis_line(&ticks, side, plot, theme)];
    let label_offset = theme.tick_length + gap(theme);
    for t in &ticks {
        let (at, anchor, baseline) = match side {
            Side::Bottom => (Point::new(t.position, plot.bottom() + label_offset), Anchor::Middle, Baseline::Top),
            Side::Left => (Point::new(plot.x - label_offset, t.position), Anchor::End, Baseline::Middle),
        };
        items.push(
            Item::text(
                Role::TickLabel,
                Text {
                    at,
                    content: t.label.clone(),
                    size: theme.font_size,
                    anchor,
                    baseline,
                    angle: 0.0,
                    color: theme.muted_text,
                },
            )
            .labelled(name),
        );
    }
    if let Some(title) = title.filter(|t| !t.is_empty()) {
        let outer = thickness(scale, side, Some(title), theme);
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
    vec![axis_line(&visible_ticks(scale, side, theme), side, plot, theme)]
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
    fn unit_goes_in_parentheses() {
        assert_eq!(title_with_unit("Petal length", Some("cm")), "Petal length (cm)");
        assert_eq!(title_with_unit("Count", None), "Count");
        assert_eq!(title_with_unit("Count", Some("  ")), "Count");
        assert_eq!(title_with_unit("Temperature (°C)", Some("°C")), "Temperature (°C)");
        assert_eq!(title_with_unit("Mass (g) per bird", Some(" g ")), "Mass (g) per bird");
    }
}
