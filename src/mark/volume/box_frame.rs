//! The box of a volume as 3-D kinds draw it around their picture: its twelve edges split into
//! those behind the data (drawn first) and those in front (drawn last), and each world axis
//! named beside an outer edge running along it, with the box's extent at the edge's ends.

use crate::enrich::camera::Camera;
use crate::guide::Theme;
use crate::guide::format::format_value;
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Role, Shape, Style, Text};

/// The box's edges seen by `camera`: those with both neighbouring faces turned away (behind
/// everything inside) and the others, as two path items.
pub fn edges(
    camera: &Camera,
    ranges: [(f64, f64); 3],
    to_px: &impl Fn([f64; 3]) -> Point,
    theme: &Theme,
) -> (Item, Item) {
    let toward = camera.toward_camera();
    // Face (axis, side) faces the viewer when its outward normal points toward the camera.
    let facing = |axis: usize, high: bool| if high { toward[axis] > 0.0 } else { toward[axis] < 0.0 };
    let (mut back, mut front) = (Vec::new(), Vec::new());
    for a in 0..3 {
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        for (hb, hc) in [(false, false), (true, false), (false, true), (true, true)] {
            let mut from = [0.0; 3];
            from[b] = if hb { ranges[b].1 } else { ranges[b].0 };
            from[c] = if hc { ranges[c].1 } else { ranges[c].0 };
            let mut to = from;
            from[a] = ranges[a].0;
            to[a] = ranges[a].1;
            let target = if facing(b, hb) || facing(c, hc) { &mut front } else { &mut back };
            target.push(PathCmd::MoveTo(to_px(from)));
            target.push(PathCmd::LineTo(to_px(to)));
        }
    }
    let style = Style::stroke(theme.muted_text.with_opacity(0.7), 0.8);
    (
        Item::new(Role::Axis, Shape::Path(back), style.clone()).labelled("volume box (behind)"),
        Item::new(Role::Axis, Shape::Path(front), style).labelled("volume box (in front)"),
    )
}

/// Each world axis named beside the middle of the outermost box edge running along it, outside
/// the box; with `extent`, the box's low and high coordinate at that edge's ends.
pub fn axis_labels(
    ranges: [(f64, f64); 3],
    to_px: &impl Fn([f64; 3]) -> Point,
    role: Role,
    color: Color,
    size: f64,
    extent: bool,
) -> Vec<Item> {
    let centre = to_px(ranges.map(|r| (r.0 + r.1) / 2.0));
    let away = |p: &Point| (p.x - centre.x).hypot(p.y - centre.y);
    let outward = |p: Point, by: f64| {
        let d = away(&p).max(1e-9);
        Point::new(p.x + (p.x - centre.x) / d * by, p.y + (p.y - centre.y) / d * by)
    };
    let text = |at: Point, content: String, size: f64| {
        Item::text(
            role,
            Text { at, content, size, anchor: Anchor::Middle, baseline: Baseline::Middle, angle: 0.0, color },
        )
    };
    let mut items = Vec::new();
    for (a, name) in ["x", "y", "z"].into_iter().enumerate() {
        // The four edges along axis a, as (low end, high end); the outermost on screen.
        let edge = |c: usize| {
            let mut p = [0.0; 3];
            for (bit, b) in [(a + 1) % 3, (a + 2) % 3].into_iter().enumerate() {
                p[b] = if c >> bit & 1 == 1 { ranges[b].1 } else { ranges[b].0 };
            }
            let (mut lo, mut hi) = (p, p);
            lo[a] = ranges[a].0;
            hi[a] = ranges[a].1;
            (to_px(lo), to_px(hi))
        };
        let middle = |(l, h): (Point, Point)| Point::new((l.x + h.x) / 2.0, (l.y + h.y) / 2.0);
        let Some((lo, hi)) = (0..4).map(edge).max_by(|p, q| away(&middle(*p)).total_cmp(&away(&middle(*q)))) else {
            continue;
        };
        items.push(
            text(outward(middle((lo, hi)), size * 1.1), name.to_string(), size).labelled(format!("box {name} axis")),
        );
        if extent {
            for (end, value) in [(lo, ranges[a].0), (hi, ranges[a].1)] {
                items.push(
                    Item::text(
                        if role == Role::AxisTitle { Role::TickLabel } else { role },
                        Text {
                            at: outward(end, size * 1.1),
                            content: format_value(value),
                            size: size * 0.85,
                            anchor: Anchor::Middle,
                            baseline: Baseline::Middle,
                            angle: 0.0,
                            color,
                        },
                    )
                    .labelled(format!("box {name} axis")),
                );
            }
        }
    }
    items
}
