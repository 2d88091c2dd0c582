//! DI006 `banking`: line charts read best when their segments average about 45° (Cleveland's
//! banking to 45°); a much flatter or steeper aspect ratio hides or exaggerates change.

use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{PathCmd, Role, Shape};
use crate::spec::ChartKind;

/// The rule.
pub static RULE: Rule = Rule {
    code: "DI006",
    name: "banking",
    category: Category::Integrity,
    severity: Severity::Note,
    summary: "A line chart's aspect ratio is far from banking its segments to 45°.",
    check,
};

/// Median absolute slopes beyond this factor from 1 (about 18° or 72°) are reported.
const FACTOR: f64 = 3.0;

/// The median absolute slope (|dy/dx| in pixels) of the line segments of the chart's data paths.
pub fn median_abs_slope(s: &Subject<'_>) -> Option<f64> {
    let mut slopes = Vec::new();
    s.output.scene.walk(|item| {
        if item.role != Role::DataMark {
            return;
        }
        if let Shape::Path(cmds) = &item.shape {
            let mut last = None;
            for c in cmds {
                match *c {
                    PathCmd::MoveTo(p) => last = Some(p),
                    PathCmd::LineTo(p) => {
                        if let Some(q) = last {
                            let (dx, dy) = ((p.x - q.x).abs(), (p.y - q.y).abs());
                            if dx > 1e-9 && (dx > 0.0 || dy > 0.0) {
                                slopes.push(dy / dx);
                            }
                        }
                        last = Some(p);
                    }
                    PathCmd::CubicTo(_, _, p) | PathCmd::QuadTo(_, p) => last = Some(p),
                    PathCmd::Close => {}
                }
            }
        }
    });
    // Flat runs carry no slope information about the aspect ratio.
    slopes.retain(|s| *s > 0.0 && s.is_finite());
    if slopes.len() < 3 {
        return None;
    }
    slopes.sort_by(f64::total_cmp);
    Some(slopes[slopes.len() / 2])
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    if !matches!(s.chart.kind, ChartKind::Line(_)) {
        return Vec::new();
    }
    let Some(m) = median_abs_slope(s) else { return Vec::new() };
    if (1.0 / FACTOR..=FACTOR).contains(&m) {
        return Vec::new();
    }
    let (w, h) = (s.output.scene.width, s.output.scene.height);
    // The plot area: the clip of the data marks' group (the whole canvas if there is none).
    let mut plot_h = h;
    s.output.scene.walk(|item| {
        if let (Role::DataMark, Shape::Group { clip: Some(c), .. }) = (item.role, &item.shape) {
            plot_h = c.h;
        }
    });
    // Scaling the plot's height by 1/m brings the median slope to 1 (45°); the guides keep
    // their room.
    let banked_h = (h - plot_h + plot_h / m).round().clamp(120.0, 16384.0);
    let angle = m.atan().to_degrees();
    vec![Issue::new(
        "lines",
        "size",
        format!("the line segments' median angle is {angle:.0}°, far from 45° (median |slope| {m:.2} at {w}×{h})"),
        format!("for banking to 45°, try `size = [{w}, {banked_h:.0}]` (or keep the height and widen the chart)"),
    )]
}
