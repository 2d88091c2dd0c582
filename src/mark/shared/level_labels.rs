//! Contour level labels placed along their lines with collision checks, shared by the
//! contour kinds (gridded and scattered).

use crate::guide::format::format_ticks;
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Role, Shape, Style, Text};
use crate::text::measure;

/// One label per level, on that level's longest line, rotated along it, over a white halo.
/// `lines` are `(level, points in data coordinates)`; labels that would collide with one placed
/// before are moved along their line or dropped.
pub fn level_labels<'a>(
    lines: impl Iterator<Item = (f64, &'a [(f64, f64)])> + Clone,
    levels: &[f64],
    to_px: &impl Fn((f64, f64)) -> Point,
    size: f64,
) -> Vec<Item> {
    let step = levels.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
    let texts = format_ticks(levels, if step.is_finite() { step } else { 1.0 });
    let mut items = Vec::new();
    let mut placed: Vec<crate::scene::Rect> = Vec::new();
    for (level, label) in levels.iter().zip(texts) {
        let best = lines
            .clone()
            .filter(|(l, _)| *l == *level)
            .map(|(_, points)| {
                let px: Vec<Point> = points.iter().map(|&p| to_px(p)).collect();
                let len: f64 = px.windows(2).map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y)).sum();
                (len, px)
            })
            .max_by(|a, b| a.0.total_cmp(&b.0));
        let Some((len, px)) = best else { continue };
        let width = measure(&label, size).width;
        if len < width * 3.0 {
            continue;
        }
        // Try points along the line (half, quarter, three quarters, ...) until the label's box
        // clears every label placed so far.
        let m = measure(&label, size);
        let (hw, hh) = (m.width / 2.0 + 2.0, (m.ascent + m.descent) / 2.0 + 1.0);
        let mut at = None;
        for fraction in [0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875] {
            let Some((p, angle)) = point_along(&px, len * fraction) else { continue };
            let r = hw.max(hh);
            let bounds = crate::scene::Rect::new(p.x - r, p.y - r, 2.0 * r, 2.0 * r);
            if placed.iter().all(|b: &crate::scene::Rect| !b.intersects(&bounds)) {
                placed.push(bounds);
                at = Some((p, angle));
                break;
            }
        }
        let Some((p, angle)) = at else { continue };
        let (s, c) = angle.to_radians().sin_cos();
        let corner = |dx: f64, dy: f64| Point::new(p.x + dx * c - dy * s, p.y + dx * s + dy * c);
        items.push(Item::new(
            Role::Annotation,
            Shape::Path(vec![
                PathCmd::MoveTo(corner(-hw, -hh)),
                PathCmd::LineTo(corner(hw, -hh)),
                PathCmd::LineTo(corner(hw, hh)),
                PathCmd::LineTo(corner(-hw, hh)),
                PathCmd::Close,
            ]),
            Style::fill(Color::WHITE.with_opacity(0.8)),
        ));
        items.push(Item::text(
            Role::Annotation,
            Text {
                at: p,
                content: label,
                size,
                anchor: Anchor::Middle,
                baseline: Baseline::Middle,
                angle,
                color: Color::rgb(0x22, 0x22, 0x22),
            },
        ));
    }
    items
}

/// The point at arc length `distance` along a polyline and the direction there in degrees,
/// turned to read left to right.
fn point_along(px: &[Point], distance: f64) -> Option<(Point, f64)> {
    let mut walked = 0.0;
    for w in px.windows(2) {
        let seg = (w[1].x - w[0].x).hypot(w[1].y - w[0].y);
        if walked + seg >= distance && seg > 0.0 {
            let t = (distance - walked) / seg;
            let p = Point::new(w[0].x + t * (w[1].x - w[0].x), w[0].y + t * (w[1].y - w[0].y));
            let mut angle = (w[1].y - w[0].y).atan2(w[1].x - w[0].x).to_degrees();
            if angle > 90.0 {
                angle -= 180.0;
            } else if angle < -90.0 {
                angle += 180.0;
            }
            return Some((p, angle));
        }
        walked += seg;
    }
    None
}
