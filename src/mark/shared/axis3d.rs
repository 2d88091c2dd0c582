//! Axes of a 3-D box as 3-D kinds draw them: nice ticks along the box edge that
//! [`axis_lines`](crate::enrich::camera::axis_lines) picks for each axis, tick marks and labels
//! pointing away from the box, and the axis title beside the edge's middle.

use crate::enrich::camera::AxisLine;
use crate::guide::Theme;
use crate::guide::format::format_ticks;
use crate::guide::ticks::extended;
use crate::scene::{Anchor, Baseline, Item, PathCmd, Point, Role, Shape, Style, Text};
use crate::text::{bounds, measure};

/// Nice tick values within `range` (at least two when a finer step gives them: a short axis
/// over a narrow range can hold a single nice value, which shows no scale) and their step.
fn ticks_inside(range: (f64, f64), target: usize) -> (Vec<f64>, f64) {
    let within = |target: usize| {
        let ticks = extended(range.0, range.1, target, false);
        let inside: Vec<f64> =
            ticks.values.iter().copied().filter(|v| *v >= range.0 - 1e-12 && *v <= range.1 + 1e-12).collect();
        (inside, ticks.step)
    };
    let first = within(target);
    if first.0.len() >= 2 || range.1 <= range.0 {
        return first;
    }
    (target + 1..=MAX_TICKS).map(within).find(|(inside, _)| inside.len() >= 2).unwrap_or(first)
}

/// The most ticks [`ticks_inside`] asks for on one projected axis.
const MAX_TICKS: usize = 10;

/// Tick marks, tick labels and the title of one projected axis (`project` takes a data point to
/// the canvas); the ticks and their labels are labelled with the axis's `name`.
pub fn draw(
    line: &AxisLine,
    (name, title): (&str, &str),
    range: (f64, f64),
    project: &impl Fn([f64; 3]) -> Point,
    theme: &Theme,
) -> Vec<Item> {
    let mut items = Vec::new();
    let (start, end) = (project(line.from), project(line.to));
    let length = (end.x - start.x).hypot(end.y - start.y);
    let target = ((length / (theme.font_size * 6.0)).round() as usize).clamp(2, 6);
    let (inside, step) = ticks_inside(range, target);
    let labels = format_ticks(&inside, step);
    // `outward` is in screen units with y up; canvas y runs down.
    let (nx, ny) = (line.outward.0, -line.outward.1);
    let anchor = if nx > 0.3 {
        Anchor::Start
    } else if nx < -0.3 {
        Anchor::End
    } else {
        Anchor::Middle
    };
    let baseline = if ny > 0.3 {
        Baseline::Top
    } else if ny < -0.3 {
        Baseline::Bottom
    } else {
        Baseline::Middle
    };
    let mut cmds = Vec::new();
    let mut widest: f64 = 0.0;
    for (v, label) in inside.iter().zip(labels) {
        let p = project(line.at(*v));
        let tip = Point::new(p.x + nx * theme.tick_length, p.y + ny * theme.tick_length);
        cmds.push(PathCmd::MoveTo(p));
        cmds.push(PathCmd::LineTo(tip));
        widest = widest.max(measure(&label, theme.font_size).width);
        items.push(
            Item::text(
                Role::TickLabel,
                Text {
                    at: Point::new(tip.x + nx * 3.0, tip.y + ny * 3.0),
                    content: label,
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
    items.push(Item::new(Role::Axis, Shape::Path(cmds), Style::stroke(theme.axis, 1.0)).labelled(name));
    let mid = Point::new((start.x + end.x) / 2.0, (start.y + end.y) / 2.0);
    let away = theme.tick_length + 6.0 + if nx.abs() > 0.3 { widest } else { theme.font_size * 1.2 };
    items.push(Item::text(
        Role::AxisTitle,
        Text {
            at: Point::new(mid.x + nx * away, mid.y + ny * (away + theme.font_size * 0.3)),
            content: title.to_string(),
            size: theme.label_size,
            anchor,
            baseline,
            angle: 0.0,
            color: theme.text,
        },
    ));
    items
}

/// The three axes of a box ([`draw`] for each of `lines`, with their titles and data ranges;
/// an axis seen nearly end-on is left out), leaving out a tick label that would overlap one already placed (at a corner two axes
/// share, the first axis keeps its label).
pub fn draw_all(
    lines: &[AxisLine; 3],
    titles: [&str; 3],
    ranges: [(f64, f64); 3],
    project: &impl Fn([f64; 3]) -> Point,
    theme: &Theme,
) -> Vec<Item> {
    let mut items: Vec<Item> = Vec::new();
    for (line, title) in lines.iter().zip(titles) {
        // An axis seen end-on (looking straight down z) has no length to carry ticks.
        let (a, b) = (project(line.from), project(line.to));
        if (b.x - a.x).hypot(b.y - a.y) < 3.0 * theme.font_size {
            continue;
        }
        let name = AXIS_NAMES.get(line.axis).copied().unwrap_or("axis");
        let range = ranges.get(line.axis).copied().unwrap_or((0.0, 1.0));
        for item in draw(line, (name, title), range, project, theme) {
            let clashes = match &item.shape {
                Shape::Text(t) if item.role == Role::TickLabel => {
                    let b = bounds(t);
                    items.iter().any(|placed| match &placed.shape {
                        Shape::Text(p) if placed.role == Role::TickLabel => bounds(p).intersects(&b),
                        _ => false,
                    })
                }
                _ => false,
            };
            if !clashes {
                items.push(item);
            }
        }
    }
    items
}

/// The scene labels of the axes' items, by axis.
pub const AXIS_NAMES: [&str; 3] = ["x axis", "y axis", "z axis"];
