//! Placing labels: each label's candidate placements are tried in order, and the first inside
//! the plot and clear of the text already drawn (with lint's overlap test, plus a margin) and of
//! the lines labels must not cross wins. When none is, the least bad one is moved inside the plot,
//! or at least onto the canvas.

use crate::scene::{Item, PathCmd, Point, Rect, Shape};
use crate::text::{bounds, boxes_overlap};

/// Room kept between a placed label and other text, in pixels.
const MARGIN: f64 = 2.0;

/// What labels must keep clear of: text already placed, and straight lines.
pub struct Obstacles {
    /// Glyph boxes of the text drawn or placed so far.
    boxes: Vec<Rect>,
    /// Straight segments a label must not cross (rules, arrow shafts).
    segments: Vec<(Point, Point)>,
}

impl Obstacles {
    /// The text of the items in `texts` (groups included) and the straight segments of the paths
    /// in `lines`.
    pub fn new(texts: &[&[Item]], lines: &[Item]) -> Obstacles {
        let mut boxes = Vec::new();
        for items in texts {
            text_boxes(items, &mut boxes);
        }
        let segments = lines.iter().flat_map(segments).collect();
        Obstacles { boxes, segments }
    }

    /// The best of `choices` (text items, best first), moved inside `plot` (or onto `canvas`)
    /// when even the best is not; later labels keep clear of it. `None` without choices.
    pub fn place(&mut self, choices: &[Item], plot: Rect, canvas: Rect) -> Option<Item> {
        let boxes: Vec<Rect> = choices.iter().map(glyph_box).collect();
        let inside = |b: &Rect| plot.contains_rect(b, 0.5);
        let best = boxes
            .iter()
            .position(|b| inside(b) && self.clear(b))
            .or_else(|| (0..boxes.len()).min_by_key(|&k| self.cost(&boxes[k], inside(&boxes[k]))))?;
        let placed = fit(choices.get(best)?.clone(), boxes[best], plot, canvas);
        self.boxes.push(glyph_box(&placed));
        Some(placed)
    }

    /// Whether a label's box keeps its margin from every text and crosses no line.
    fn clear(&self, b: &Rect) -> bool {
        let grown = Rect::new(b.x - MARGIN, b.y - MARGIN, b.w + 2.0 * MARGIN, b.h + 2.0 * MARGIN);
        !self.boxes.iter().any(|o| boxes_overlap(&grown, o)) && !self.segments.iter().any(|&s| crosses(s, b))
    }

    /// How bad a placement is: texts it overlaps count most, then lines it crosses, then
    /// leaving the plot.
    fn cost(&self, b: &Rect, inside: bool) -> usize {
        let texts = self.boxes.iter().filter(|o| boxes_overlap(b, o)).count();
        let lines = self.segments.iter().filter(|&&s| crosses(s, b)).count();
        4 * texts + 2 * lines + usize::from(!inside)
    }
}

/// The glyph box of a text item (an empty box for other items).
fn glyph_box(item: &Item) -> Rect {
    match &item.shape {
        Shape::Text(t) => bounds(t),
        _ => Rect::new(0.0, 0.0, 0.0, 0.0),
    }
}

/// Glyph boxes of the non-blank text among `items`, groups walked.
fn text_boxes(items: &[Item], out: &mut Vec<Rect>) {
    for item in items {
        match &item.shape {
            Shape::Text(t) if !t.content.trim().is_empty() => out.push(bounds(t)),
            Shape::Group { items, .. } => text_boxes(items, out),
            _ => {}
        }
    }
}

/// The straight segments of a path item (curves are left out).
fn segments(item: &Item) -> Vec<(Point, Point)> {
    let Shape::Path(cmds) = &item.shape else { return Vec::new() };
    let mut out = Vec::new();
    let (mut start, mut last) = (None, None);
    for cmd in cmds {
        match *cmd {
            PathCmd::MoveTo(p) => (start, last) = (Some(p), Some(p)),
            PathCmd::LineTo(p) => {
                out.extend(last.map(|q| (q, p)));
                last = Some(p);
            }
            PathCmd::QuadTo(_, p) | PathCmd::CubicTo(_, _, p) => last = Some(p),
            PathCmd::Close => {
                if let (Some(q), Some(s)) = (last, start) {
                    out.push((q, s));
                }
                last = start;
            }
        }
    }
    out
}

/// Whether the segment `a`–`b` passes through `r` shrunk by half a pixel (Liang–Barsky).
fn crosses((a, b): (Point, Point), r: &Rect) -> bool {
    let (x0, y0, x1, y1) = (r.x + 0.5, r.y + 0.5, r.right() - 0.5, r.bottom() - 0.5);
    if x1 <= x0 || y1 <= y0 {
        return false;
    }
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-dx, a.x - x0), (dx, x1 - a.x), (-dy, a.y - y0), (dy, y1 - a.y)] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
            continue;
        }
        let t = q / p;
        if p < 0.0 {
            t0 = t0.max(t);
        } else {
            t1 = t1.min(t);
        }
        if t0 > t1 {
            return false;
        }
    }
    true
}

/// `item`, whose glyph box is `b`, moved the least so that the box lies inside `plot` along each
/// axis, or where it is larger than the plot, inside `canvas` (starting at the canvas's edge
/// when larger still).
fn fit(item: Item, b: Rect, plot: Rect, canvas: Rect) -> Item {
    let shift = |lo: f64, len: f64, rooms: [(f64, f64); 2]| {
        let (start, end) = rooms.into_iter().find(|(s, e)| len <= e - s).unwrap_or((rooms[1].0, rooms[1].0 + len));
        if lo < start {
            start - lo
        } else if lo + len > end {
            end - (lo + len)
        } else {
            0.0
        }
    };
    let dx = shift(b.x, b.w, [(plot.x, plot.right()), (canvas.x, canvas.right())]);
    let dy = shift(b.y, b.h, [(plot.y, plot.bottom()), (canvas.y, canvas.bottom())]);
    if dx == 0.0 && dy == 0.0 { item } else { item.translated(dx, dy) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Anchor, Baseline, Color, Role, Style, Text};

    fn label(content: &str, x: f64, y: f64) -> Item {
        let text = Text {
            at: Point::new(x, y),
            content: content.into(),
            size: 12.0,
            anchor: Anchor::Start,
            baseline: Baseline::Top,
            angle: 0.0,
            color: Color::BLACK,
        };
        Item::text(Role::Annotation, text)
    }

    const PLOT: Rect = Rect::new(50.0, 20.0, 300.0, 200.0);
    const CANVAS: Rect = Rect::new(0.0, 0.0, 600.0, 260.0);

    #[test]
    fn the_first_clear_choice_inside_the_plot_wins() {
        let drawn = [label("taken", 100.0, 100.0)];
        let mut obstacles = Obstacles::new(&[&drawn], &[]);
        // Outside the plot, then on the drawn text, then clear.
        let choices = [label("a", 10.0, 100.0), label("b", 102.0, 101.0), label("c", 100.0, 150.0)];
        let placed = obstacles.place(&choices, PLOT, CANVAS).expect("a choice");
        assert_eq!(placed, choices[2]);
        // The placed label is taken now too.
        let again = obstacles.place(&[label("d", 101.0, 151.0), label("e", 200.0, 60.0)], PLOT, CANVAS);
        assert_eq!(again.map(|i| glyph_box(&i).x), Some(200.0));
    }

    #[test]
    fn labels_do_not_cross_lines() {
        let line = Item::new(
            Role::Annotation,
            Shape::Path(vec![PathCmd::MoveTo(Point::new(50.0, 105.0)), PathCmd::LineTo(Point::new(350.0, 105.0))]),
            Style::stroke(Color::BLACK, 1.0),
        );
        let mut obstacles = Obstacles::new(&[], &[line]);
        let choices = [label("across the line", 100.0, 100.0), label("above it", 100.0, 80.0)];
        assert_eq!(obstacles.place(&choices, PLOT, CANVAS), Some(choices[1].clone()));
        assert!(crosses((Point::new(0.0, 0.0), Point::new(10.0, 10.0)), &Rect::new(4.0, 4.0, 2.0, 2.0)));
        assert!(!crosses((Point::new(0.0, 0.0), Point::new(10.0, 0.0)), &Rect::new(4.0, 1.0, 2.0, 2.0)));
    }

    #[test]
    fn a_label_with_no_room_moves_into_the_plot_then_onto_the_canvas() {
        let mut obstacles = Obstacles::new(&[], &[]);
        let placed = obstacles.place(&[label("near the edge", 340.0, 100.0)], PLOT, CANVAS).expect("placed");
        let b = glyph_box(&placed);
        assert!(PLOT.contains_rect(&b, 1e-9), "{b:?}");
        assert!((b.right() - PLOT.right()).abs() < 1e-9, "moved just far enough: {b:?}");
        let long = "a label far wider than the plot, though not wider than the canvas";
        let b = glyph_box(&obstacles.place(&[label(long, 60.0, 100.0)], PLOT, CANVAS).expect("placed"));
        assert!(b.w > PLOT.w && CANVAS.contains_rect(&b, 1e-9), "{b:?}");
        let longer = long.repeat(3);
        let b = glyph_box(&obstacles.place(&[label(&longer, 60.0, 100.0)], PLOT, CANVAS).expect("placed"));
        assert_eq!(b.x, 0.0, "starts at the canvas's edge");
        assert!(obstacles.place(&[], PLOT, CANVAS).is_none());
    }
}
