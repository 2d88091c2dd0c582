//! The orientation inset of slice charts: the volume's box seen obliquely, world axes marked,
//! and every slice's plane drawn where it cuts the box, so a reader knows where each panel lies.

use crate::enrich::camera::{Camera, View, equal_extent};
use crate::enrich::volume::{Interpolation, Sampler};
use crate::mark::frame::PanelCanvas;
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Rect, Role, Shape, Stroke, Style, Text};

use super::planes::Slice;

/// The inset's width in font sizes (the legend column is widened to it).
pub const WIDTH_EMS: f64 = 9.0;

/// Where the inset views the box from: in front of it, to the right and a little above.
const VIEW: (f64, f64) = (-55.0, 22.0);

/// The colour planes are drawn in.
const PLANE: Color = Color::rgb(0xd9, 0x5f, 0x02);

/// The inset's items in the legend column below `legend_bottom`, or none when there is no room.
pub fn draw(
    sampler: &Sampler<'_>,
    how: Interpolation,
    slices: &[Slice],
    canvas: &PanelCanvas,
    legend_bottom: f64,
) -> Vec<Item> {
    let theme = &canvas.theme;
    let fs = theme.font_size;
    let title_h = theme.label_size * 1.6;
    let x = canvas.width - theme.margin - canvas.legend_w;
    let top = if canvas.legends.is_empty() { canvas.top() } else { legend_bottom + fs };
    let bottom = canvas.top() + canvas.room;
    let side = canvas.legend_w.min(bottom - top - title_h);
    if side < 4.0 * fs {
        return Vec::new();
    }
    let corners = sampler.corners(how);
    let ranges = [0, 1, 2]
        .map(|a| corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| (lo.min(c[a]), hi.max(c[a]))));
    let Ok(camera) = Camera::new(ranges, equal_extent(ranges), View::new(VIEW.0, VIEW.1)) else {
        return Vec::new();
    };
    let pad = fs * 1.1;
    let square = Rect::new(x + pad, top + title_h + pad, side - 2.0 * pad, side - 2.0 * pad);
    let to_px = |p: [f64; 3]| {
        let (sx, sy) = camera.project(p);
        Point::new(square.x + sx * square.w, square.y + (1.0 - sy) * square.h)
    };
    let mut items = vec![Item::text(
        Role::Annotation,
        Text {
            at: Point::new(x, top),
            content: "Slice planes".into(),
            size: theme.label_size,
            anchor: Anchor::Start,
            baseline: Baseline::Top,
            angle: 0.0,
            color: theme.text,
        },
    )];
    let mut edges = Vec::new();
    for a in 0..8usize {
        for bit in [1usize, 2, 4] {
            if a & bit == 0 {
                edges.push(PathCmd::MoveTo(to_px(corners[a])));
                edges.push(PathCmd::LineTo(to_px(corners[a | bit])));
            }
        }
    }
    items.push(
        Item::new(Role::Annotation, Shape::Path(edges), Style::stroke(theme.muted_text, 0.8)).labelled("volume box"),
    );
    for slice in slices {
        let mut cmds: Vec<PathCmd> = slice
            .outline
            .iter()
            .enumerate()
            .map(|(k, &(u, v))| {
                let p = to_px(slice.plane.world(u, v));
                if k == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) }
            })
            .collect();
        cmds.push(PathCmd::Close);
        let style = Style { fill: Some(PLANE.with_opacity(0.18)), stroke: Some(Stroke::solid(PLANE, 1.0)) };
        items.push(Item::new(Role::Annotation, Shape::Path(cmds), style).labelled(slice.label.clone()));
    }
    items.extend(axis_names(ranges, &to_px, theme.muted_text, fs * 0.85));
    items
}

/// The names of the world axes, each beside the middle of an outer edge of the box running
/// along it (outside the box, so no plane is under the letter).
fn axis_names(ranges: [(f64, f64); 3], to_px: &impl Fn([f64; 3]) -> Point, color: Color, size: f64) -> Vec<Item> {
    let centre = to_px(ranges.map(|r| (r.0 + r.1) / 2.0));
    let mut items = Vec::new();
    for (a, name) in ["x", "y", "z"].into_iter().enumerate() {
        // The four edges along axis a: their middles, the outermost on screen.
        let middles = (0..4).map(|c: usize| {
            let others: Vec<usize> = (0..3).filter(|&b| b != a).collect();
            let mut p = [0.0; 3];
            p[a] = (ranges[a].0 + ranges[a].1) / 2.0;
            for (bit, &b) in others.iter().enumerate() {
                p[b] = if c >> bit & 1 == 1 { ranges[b].1 } else { ranges[b].0 };
            }
            to_px(p)
        });
        let away = |p: &Point| (p.x - centre.x).hypot(p.y - centre.y);
        let Some(m) = middles.max_by(|p, q| away(p).total_cmp(&away(q))) else { continue };
        let length = away(&m).max(1e-9);
        items.push(Item::text(
            Role::Annotation,
            Text {
                at: Point::new(
                    m.x + (m.x - centre.x) / length * size * 0.9,
                    m.y + (m.y - centre.y) / length * size * 0.9,
                ),
                content: name.into(),
                size,
                anchor: Anchor::Middle,
                baseline: Baseline::Middle,
                angle: 0.0,
                color,
            },
        ));
    }
    items
}
