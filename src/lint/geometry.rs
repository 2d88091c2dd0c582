//! Scene queries shared by the lint rules: the text a reader sees with its glyph boxes, the
//! colour painted under a point, and colour blending.

use crate::scene::{Color, Item, PathCmd, Rect, Role, Scene, Shape, Text};

/// One line of text in a scene, with the box its glyphs cover (rotation included).
#[derive(Clone, Debug)]
pub struct PlacedText<'a> {
    /// The item's role (tick label, title, legend, ...).
    pub role: Role,
    /// The item's label, e.g. the axis name of a tick label.
    pub label: Option<&'a str>,
    /// The text.
    pub text: &'a Text,
    /// Its glyph box in canvas units.
    pub bounds: Rect,
    /// The scene item that draws it (to ask what was painted before it).
    pub item: &'a Item,
}

/// What a reader calls text of this role, for messages.
pub fn role_name(role: Role) -> &'static str {
    match role {
        Role::Background => "background",
        Role::DataMark => "data label",
        Role::Axis => "axis",
        Role::TickLabel => "tick label",
        Role::AxisTitle => "axis title",
        Role::Grid => "grid",
        Role::Legend => "legend text",
        Role::Title => "title",
        Role::Caption => "caption",
        Role::Annotation => "label",
    }
}

impl PlacedText<'_> {
    /// The element as a reader names it: `"y axis title"`, `"legend text"`, `"title"`.
    pub fn element(&self) -> String {
        match (self.role, self.label) {
            (Role::AxisTitle | Role::TickLabel, Some(axis)) => {
                format!("{axis} {}", role_name(self.role).trim_start_matches("axis "))
            }
            _ => role_name(self.role).to_string(),
        }
    }
}

/// Every text item of `scene` in drawing order.
pub fn texts(scene: &Scene) -> Vec<PlacedText<'_>> {
    let mut out = Vec::new();
    scene.walk(|item| {
        if let Shape::Text(t) = &item.shape
            && !t.content.trim().is_empty()
        {
            out.push(PlacedText {
                role: item.role,
                label: item.label.as_deref(),
                text: t,
                bounds: crate::text::bounds(t),
                item,
            });
        }
    });
    out
}

/// The box `r` shrunk by `by` on every side (never below zero size).
pub fn shrink(r: &Rect, by: f64) -> Rect {
    Rect::new(r.x + by, r.y + by, (r.w - 2.0 * by).max(0.0), (r.h - 2.0 * by).max(0.0))
}

/// The area two rectangles share.
pub fn overlap_area(a: &Rect, b: &Rect) -> f64 {
    let w = (a.right().min(b.right()) - a.x.max(b.x)).max(0.0);
    let h = (a.bottom().min(b.bottom()) - a.y.max(b.y)).max(0.0);
    w * h
}

/// Pairs of texts whose glyph boxes overlap by more than half a pixel on each side
/// ([`crate::text::texts_overlap`]: turned text by its turned box), as indices into `texts`. Sweeps boxes sorted by their left
/// edge, so it stays fast for thousands of labels.
pub fn overlapping_pairs(texts: &[PlacedText<'_>]) -> Vec<(usize, usize)> {
    let boxes: Vec<Rect> = texts.iter().map(|t| shrink(&t.bounds, 0.5)).collect();
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by(|&a, &b| boxes[a].x.total_cmp(&boxes[b].x));
    let mut pairs = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if boxes[j].x >= boxes[i].right() {
                break;
            }
            if crate::text::texts_overlap(texts[i].text, texts[j].text) {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

/// The opaque colour painted at `(x, y)` before the item `before` (an item of `scene`) is drawn: the topmost
/// filled rectangle, circle or raster pixel that covers the point, blended over the background.
/// Paths and batches are ignored (their coverage is not a simple box).
pub fn colour_under(scene: &Scene, x: f64, y: f64, before: &Item) -> Color {
    let limit: *const Item = before;
    let mut layers: Vec<Color> = Vec::new();
    let mut reached = false;
    fn visit(items: &[Item], x: f64, y: f64, limit: *const Item, layers: &mut Vec<Color>, reached: &mut bool) {
        for item in items {
            if *reached || std::ptr::eq(item, limit) {
                *reached = true;
                return;
            }
            match &item.shape {
                Shape::Group { items, clip }
                    if clip.is_none_or(|c| x >= c.x && x <= c.right() && y >= c.y && y <= c.bottom()) =>
                {
                    visit(items, x, y, limit, layers, reached);
                }
                Shape::Rect(r) if x >= r.x && x <= r.right() && y >= r.y && y <= r.bottom() => {
                    if let Some(fill) = item.style.fill {
                        layers.push(fill);
                    }
                }
                Shape::Circle { center, radius } if (x - center.x).hypot(y - center.y) <= *radius => {
                    if let Some(fill) = item.style.fill {
                        layers.push(fill);
                    }
                }
                Shape::Path(cmds) if item.style.fill.is_some() && inside_path(cmds, x, y) => {
                    if let Some(fill) = item.style.fill {
                        layers.push(fill);
                    }
                }
                Shape::Image(raster)
                    if x >= raster.dest.x
                        && x < raster.dest.right()
                        && y >= raster.dest.y
                        && y < raster.dest.bottom() =>
                {
                    let px = ((x - raster.dest.x) / raster.dest.w * raster.width as f64) as usize;
                    let py = ((y - raster.dest.y) / raster.dest.h * raster.height as f64) as usize;
                    let at = (py.min(raster.height.saturating_sub(1) as usize) * raster.width as usize
                        + px.min(raster.width.saturating_sub(1) as usize))
                        * 4;
                    if let Some(p) = raster.rgba.get(at..at + 4) {
                        layers.push(Color { r: p[0], g: p[1], b: p[2], a: p[3] });
                    }
                }
                _ => {}
            }
        }
    }
    visit(&scene.items, x, y, limit, &mut layers, &mut reached);
    layers.into_iter().fold(opaque(scene.background), |under, top| blend(top, under))
}

/// Whether `(x, y)` lies inside the filled path (even-odd rule; curves are taken as straight
/// segments to their end points, close enough for asking what colour is under a label).
fn inside_path(cmds: &[PathCmd], x: f64, y: f64) -> bool {
    let mut inside = false;
    let (mut start, mut last) = (None, None);
    let mut edge = |a: crate::scene::Point, b: crate::scene::Point| {
        if (a.y > y) != (b.y > y) && x < a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y) {
            inside = !inside;
        }
    };
    for c in cmds {
        match *c {
            PathCmd::MoveTo(p) => {
                if let (Some(s), Some(l)) = (start, last) {
                    edge(l, s);
                }
                start = Some(p);
                last = Some(p);
            }
            PathCmd::LineTo(p) | PathCmd::QuadTo(_, p) | PathCmd::CubicTo(_, _, p) => {
                if let Some(l) = last {
                    edge(l, p);
                }
                last = Some(p);
            }
            PathCmd::Close => {
                if let (Some(s), Some(l)) = (start, last) {
                    edge(l, s);
                }
                last = start;
            }
        }
    }
    if let (Some(s), Some(l)) = (start, last) {
        edge(l, s);
    }
    inside
}

/// `c` over white when it is not opaque (a canvas background is drawn over nothing).
fn opaque(c: Color) -> Color {
    blend(c, Color::WHITE)
}

/// `top` composited over the opaque colour `under`.
pub fn blend(top: Color, under: Color) -> Color {
    let a = top.alpha();
    let mix = |t: u8, u: u8| (t as f64 * a + u as f64 * (1.0 - a)).round() as u8;
    Color::rgb(mix(top.r, under.r), mix(top.g, under.g), mix(top.b, under.b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blending_half_black_over_white_gives_mid_grey() {
        let c = blend(Color::BLACK.with_opacity(0.5), Color::WHITE);
        assert!(c.r == 127 || c.r == 128, "{c:?}");
    }

    #[test]
    fn points_inside_a_square_path_with_a_hole() {
        use crate::scene::Point;
        let sq = |x0: f64, y0: f64, s: f64| {
            vec![
                PathCmd::MoveTo(Point::new(x0, y0)),
                PathCmd::LineTo(Point::new(x0 + s, y0)),
                PathCmd::LineTo(Point::new(x0 + s, y0 + s)),
                PathCmd::LineTo(Point::new(x0, y0 + s)),
                PathCmd::Close,
            ]
        };
        let mut cmds = sq(0.0, 0.0, 10.0);
        cmds.extend(sq(4.0, 4.0, 2.0));
        assert!(inside_path(&cmds, 1.0, 1.0));
        assert!(!inside_path(&cmds, 5.0, 5.0), "the hole");
        assert!(!inside_path(&cmds, 11.0, 5.0));
    }

    #[test]
    fn overlap_area_of_half_shifted_squares() {
        let a = Rect::new(0.0, 0.0, 10.0, 10.0);
        assert_eq!(overlap_area(&a, &Rect::new(5.0, 0.0, 10.0, 10.0)), 50.0);
        assert_eq!(overlap_area(&a, &Rect::new(20.0, 0.0, 10.0, 10.0)), 0.0);
    }
}
