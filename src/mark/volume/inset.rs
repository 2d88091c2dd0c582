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
    items.extend(super::box_frame::axis_labels(ranges, &to_px, Role::Annotation, theme.muted_text, fs * 0.85, false));
    items
}
