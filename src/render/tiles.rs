//! A scene cut into raster tiles for interactive display (the explorer window).
//!
//! The scene's items are flattened in paint order and cut into runs: every item that the caller
//! marks as dynamic (the data-mark batches a selection relights) becomes a tile of its own, and
//! the static items between them form one tile per run. Each tile is rasterized by the PNG
//! renderer on a transparent canvas covering only its bounds, at whole device pixels, so the
//! tiles painted in order over the scene's background give exactly the pixels of
//! [`super::png::to_pixmap`]. When the selection changes only the dynamic tiles are redrawn, in
//! parallel.

use rayon::prelude::*;

use super::png::to_pixmap;
use crate::scene::{Color, Item, PathCmd, Rect, Scene, Shape};

/// Room added around every item's bounds for anti-aliasing and stroke joins, in canvas units.
const MARGIN: f64 = 2.0;

/// One leaf item in paint order, with the clip rectangle of its groups.
#[derive(Clone, Debug)]
struct Leaf {
    item: Item,
    clip: Option<Rect>,
}

/// One raster tile: premultiplied RGBA pixels and where they go.
#[derive(Clone, Debug)]
pub struct Tile {
    /// Where the tile goes, in canvas units (whole device pixels at the tiles' scale).
    pub rect: Rect,
    /// Pixel columns.
    pub width: u32,
    /// Pixel rows.
    pub height: u32,
    /// Premultiplied RGBA bytes, row-major, `width * height * 4` long.
    pub rgba: Vec<u8>,
    /// Bumped whenever the pixels change (for texture caches).
    pub version: u64,
    /// Whether the tile is redrawn by [`Tiles::redraw_dynamic`].
    pub dynamic: bool,
    leaves: Vec<Leaf>,
}

/// A scene as raster tiles, in paint order over its background.
#[derive(Clone, Debug)]
pub struct Tiles {
    /// Canvas width in canvas units.
    pub width: f64,
    /// Canvas height in canvas units.
    pub height: f64,
    /// Canvas background, painted before the tiles.
    pub background: Color,
    /// Device pixels per canvas unit.
    pub scale: f64,
    /// The tiles, first at the back.
    pub tiles: Vec<Tile>,
    /// Different for every [`Tiles::new`] (texture caches start over when it changes).
    pub id: u64,
}

/// Source of [`Tiles::id`].
static NEXT_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

impl Tiles {
    /// Cut `scene` into tiles at `scale` device pixels per canvas unit and rasterize them.
    /// `dynamic` marks the items that get tiles of their own and are redrawn by
    /// [`Tiles::redraw_dynamic`].
    pub fn new(scene: &Scene, scale: f64, dynamic: impl Fn(&Item) -> bool) -> Tiles {
        let scale = if scale.is_finite() && scale > 0.0 { scale } else { 1.0 };
        let canvas = Rect::new(0.0, 0.0, scene.width.max(0.0), scene.height.max(0.0));
        let mut leaves = Vec::new();
        flatten(&scene.items, None, &mut leaves);
        let mut tiles = Vec::new();
        let mut run: Vec<Leaf> = Vec::new();
        let flush = |run: &mut Vec<Leaf>, tiles: &mut Vec<Tile>| {
            if !run.is_empty() {
                tiles.push(Tile::planned(std::mem::take(run), false, canvas, scale));
            }
        };
        for leaf in leaves {
            if dynamic(&leaf.item) {
                flush(&mut run, &mut tiles);
                tiles.push(Tile::planned(vec![leaf], true, canvas, scale));
            } else {
                run.push(leaf);
            }
        }
        flush(&mut run, &mut tiles);
        tiles.retain(|t| t.rect.w > 0.0 && t.rect.h > 0.0);
        tiles.par_iter_mut().for_each(|t| {
            let leaves = t.leaves.clone();
            t.draw(&leaves, scale);
        });
        let id = NEXT_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Tiles { width: canvas.w, height: canvas.h, background: scene.background, scale, tiles, id }
    }

    /// Redraw every dynamic tile from `replace(original item)`, the items to draw in its place
    /// (for example the item split into grey context and lit rows). Tiles keep their bounds, so
    /// replacements must stay inside the original item's clip (or bounds). Runs in parallel.
    pub fn redraw_dynamic(&mut self, replace: impl Fn(&Item) -> Vec<Item> + Sync) {
        self.redraw_dynamic_where(|_| true, replace);
    }

    /// [`Tiles::redraw_dynamic`] for the dynamic tiles whose index `which` accepts.
    pub fn redraw_dynamic_where(
        &mut self,
        which: impl Fn(usize) -> bool + Sync,
        replace: impl Fn(&Item) -> Vec<Item> + Sync,
    ) {
        let scale = self.scale;
        self.tiles.par_iter_mut().enumerate().filter(|(i, t)| t.dynamic && which(*i)).for_each(|(_, t)| {
            let leaves: Vec<Leaf> = t
                .leaves
                .iter()
                .flat_map(|leaf| replace(&leaf.item).into_iter().map(|item| Leaf { item, clip: leaf.clip }))
                .collect();
            t.draw(&leaves, scale);
        });
    }

    /// The original item of a tile made of one item (every dynamic tile is), with the clip
    /// rectangle of its groups.
    pub fn single_item(&self, tile: usize) -> Option<(&Item, Option<Rect>)> {
        match self.tiles.get(tile)?.leaves.as_slice() {
            [leaf] => Some((&leaf.item, leaf.clip)),
            _ => None,
        }
    }

    /// The original items of the dynamic tiles, in paint order.
    pub fn dynamic_items(&self) -> impl Iterator<Item = &Item> {
        self.tiles.iter().filter(|t| t.dynamic).flat_map(|t| t.leaves.iter().map(|l| &l.item))
    }

    /// The whole canvas as premultiplied RGBA at the tiles' scale: the background with every
    /// tile composited over it in order (what the window shows; equal to the PNG renderer's
    /// pixels). Returns `(width, height, bytes)`.
    pub fn composite(&self) -> (u32, u32, Vec<u8>) {
        let w = (self.width * self.scale).round().max(0.0) as u32;
        let h = (self.height * self.scale).round().max(0.0) as u32;
        let bg = self.background;
        let a = u32::from(bg.a);
        let pre = |c: u8| ((u32::from(c) * a + 127) / 255) as u8;
        let mut out = [pre(bg.r), pre(bg.g), pre(bg.b), bg.a].repeat((w as usize) * (h as usize));
        for tile in &self.tiles {
            let ox = (tile.rect.x * self.scale).round() as i64;
            let oy = (tile.rect.y * self.scale).round() as i64;
            for ty in 0..tile.height as i64 {
                let y = oy + ty;
                if y < 0 || y >= i64::from(h) {
                    continue;
                }
                for tx in 0..tile.width as i64 {
                    let x = ox + tx;
                    if x < 0 || x >= i64::from(w) {
                        continue;
                    }
                    let s = ((ty * i64::from(tile.width) + tx) * 4) as usize;
                    let d = ((y * i64::from(w) + x) * 4) as usize;
                    let (Some(src), Some(dst)) = (tile.rgba.get(s..s + 4), out.get_mut(d..d + 4)) else { continue };
                    let inv = 255 - u32::from(src[3]);
                    for k in 0..4 {
                        dst[k] = (u32::from(src[k]) + (u32::from(dst[k]) * inv + 127) / 255).min(255) as u8;
                    }
                }
            }
        }
        (w, h, out)
    }
}

impl Tile {
    /// A tile for `leaves` with its bounds computed (pixels are drawn later).
    fn planned(leaves: Vec<Leaf>, dynamic: bool, canvas: Rect, scale: f64) -> Tile {
        let mut bounds: Option<Rect> = None;
        for leaf in &leaves {
            let Some(mut b) = item_bounds(&leaf.item) else { continue };
            if let Some(c) = leaf.clip {
                b = intersect(b, c);
            }
            b = intersect(b, canvas);
            if b.w <= 0.0 || b.h <= 0.0 {
                continue;
            }
            bounds = Some(match bounds {
                Some(u) => union(u, b),
                None => b,
            });
        }
        let rect = bounds.map(|b| snap(b, canvas, scale)).unwrap_or(Rect::new(0.0, 0.0, 0.0, 0.0));
        Tile { rect, width: 0, height: 0, rgba: Vec::new(), version: 0, dynamic, leaves }
    }

    /// Rasterize `leaves` into this tile's rectangle.
    fn draw(&mut self, leaves: &[Leaf], scale: f64) {
        let (dx, dy) = (-self.rect.x, -self.rect.y);
        let items = leaves
            .iter()
            .map(|l| {
                Item::group(l.item.role, vec![l.item.clone().translated(dx, dy)], l.clip.map(|c| c.offset(dx, dy)))
            })
            .collect();
        let scene =
            Scene { width: self.rect.w, height: self.rect.h, background: Color::TRANSPARENT, title: None, items };
        match to_pixmap(&scene, scale) {
            Ok(pixmap) => {
                self.width = pixmap.width();
                self.height = pixmap.height();
                self.rgba = pixmap.take();
            }
            Err(_) => {
                self.width = 0;
                self.height = 0;
                self.rgba = Vec::new();
            }
        }
        self.version += 1;
    }
}

/// Leaves of `items` in paint order, each with the intersection of its groups' clips.
fn flatten(items: &[Item], clip: Option<Rect>, out: &mut Vec<Leaf>) {
    for item in items {
        match &item.shape {
            Shape::Group { items, clip: own } => {
                let clip = match (clip, own) {
                    (Some(a), Some(b)) => Some(intersect(a, *b)),
                    (a, b) => a.or(*b),
                };
                flatten(items, clip, out);
            }
            _ => out.push(Leaf { item: item.clone(), clip }),
        }
    }
}

/// Bounds of one non-group item, strokes and anti-aliasing included; `None` when nothing of it
/// is finite.
fn item_bounds(item: &Item) -> Option<Rect> {
    let stroke = item.style.stroke.as_ref().map_or(0.0, |s| if s.width.is_finite() { s.width } else { 0.0 });
    let mut b = Bounds::default();
    match &item.shape {
        Shape::Rect(r) => {
            b.add(r.x, r.y);
            b.add(r.right(), r.bottom());
            return b.rect(stroke / 2.0 + MARGIN);
        }
        Shape::Circle { center, radius } => {
            b.add(center.x - radius, center.y - radius);
            b.add(center.x + radius, center.y + radius);
            return b.rect(stroke / 2.0 + MARGIN);
        }
        Shape::Path(cmds) => {
            for c in cmds {
                match *c {
                    PathCmd::MoveTo(p) | PathCmd::LineTo(p) => b.add(p.x, p.y),
                    PathCmd::QuadTo(a, p) => {
                        b.add(a.x, a.y);
                        b.add(p.x, p.y);
                    }
                    PathCmd::CubicTo(a, c2, p) => {
                        b.add(a.x, a.y);
                        b.add(c2.x, c2.y);
                        b.add(p.x, p.y);
                    }
                    PathCmd::Close => {}
                }
            }
            // Miter joins reach up to 4 stroke widths past a vertex.
            return b.rect(stroke * 4.0 + MARGIN);
        }
        Shape::Text(t) => {
            let r = crate::text::bounds(t);
            b.add(r.x, r.y);
            b.add(r.right(), r.bottom());
        }
        Shape::Image(r) => {
            b.add(r.dest.x, r.dest.y);
            b.add(r.dest.right(), r.dest.bottom());
        }
        Shape::Points(batch) => {
            let mut reach: f64 = 0.0;
            for (i, c) in batch.centers.iter().enumerate() {
                b.add(c.x, c.y);
                if let Some(r) = batch.radius.at(i).filter(|r| r.is_finite()) {
                    reach = reach.max(r);
                }
            }
            let s = batch.stroke.as_ref().map_or(0.0, |s| if s.width.is_finite() { s.width } else { 0.0 });
            return b.rect(reach + s / 2.0 + MARGIN);
        }
        Shape::Lines(batch) => {
            for p in &batch.points {
                b.add(p.x, p.y);
            }
            let w = if batch.width.is_finite() { batch.width } else { 0.0 };
            return b.rect(w + MARGIN);
        }
        Shape::Mesh(mesh) => {
            let r = mesh.bounds()?;
            b.add(r.x, r.y);
            b.add(r.right(), r.bottom());
        }
        Shape::Group { .. } => return None,
    }
    b.rect(MARGIN)
}

/// A growing bounding box of finite points.
#[derive(Default)]
struct Bounds {
    min: Option<(f64, f64)>,
    max: (f64, f64),
}

impl Bounds {
    fn add(&mut self, x: f64, y: f64) {
        if !(x.is_finite() && y.is_finite()) {
            return;
        }
        match self.min {
            None => {
                self.min = Some((x, y));
                self.max = (x, y);
            }
            Some((mx, my)) => {
                self.min = Some((mx.min(x), my.min(y)));
                self.max = (self.max.0.max(x), self.max.1.max(y));
            }
        }
    }

    fn rect(&self, pad: f64) -> Option<Rect> {
        let (x0, y0) = self.min?;
        let pad = if pad.is_finite() { pad.max(0.0) } else { MARGIN };
        Some(Rect::new(x0 - pad, y0 - pad, self.max.0 - x0 + 2.0 * pad, self.max.1 - y0 + 2.0 * pad))
    }
}

/// The rectangle grown to whole device pixels at `scale` and kept inside `canvas`.
fn snap(r: Rect, canvas: Rect, scale: f64) -> Rect {
    let x0 = ((r.x * scale).floor() / scale).max(canvas.x);
    let y0 = ((r.y * scale).floor() / scale).max(canvas.y);
    let x1 = ((r.right() * scale).ceil() / scale).min(canvas.right());
    let y1 = ((r.bottom() * scale).ceil() / scale).min(canvas.bottom());
    Rect::new(x0, y0, (x1 - x0).max(0.0), (y1 - y0).max(0.0))
}

fn intersect(a: Rect, b: Rect) -> Rect {
    super::intersect(a, b)
}

fn union(a: Rect, b: Rect) -> Rect {
    let x0 = a.x.min(b.x);
    let y0 = a.y.min(b.y);
    Rect::new(x0, y0, a.right().max(b.right()) - x0, a.bottom().max(b.bottom()) - y0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{PerPoint, Point, PointBatch, Role, Style, Text};

    /// A small scene: a grid rect, a clipped point batch, a stroked path, a mesh of two
    /// intersecting triangles and a label.
    fn scene() -> Scene {
        let batch = PointBatch {
            centers: (0..40).map(|i| Point::new(20.0 + 3.0 * i as f64, 30.0 + (i % 7) as f64 * 9.0)).collect(),
            radius: PerPoint::Uniform(2.5),
            fill: PerPoint::Uniform(Color::rgb(200, 40, 40).with_opacity(0.6)),
            stroke: None,
        };
        let marks = Item::new(Role::DataMark, Shape::Points(batch), Style::default()).with_rows((0..40).collect());
        Scene {
            width: 160.0,
            height: 110.0,
            background: Color::WHITE,
            title: None,
            items: vec![
                Item::new(
                    Role::Grid,
                    Shape::Rect(Rect::new(10.0, 10.0, 130.0, 80.0)),
                    Style::stroke(Color::BLACK, 1.0),
                ),
                Item::group(Role::DataMark, vec![marks], Some(Rect::new(10.0, 10.0, 130.0, 80.0))),
                Item::new(
                    Role::Axis,
                    Shape::Path(vec![
                        PathCmd::MoveTo(Point::new(10.0, 95.0)),
                        PathCmd::LineTo(Point::new(140.0, 95.0)),
                    ]),
                    Style::stroke(Color::BLACK, 1.0),
                ),
                Item::new(
                    Role::DataMark,
                    Shape::Mesh(crate::scene::Mesh {
                        positions: std::sync::Arc::new(vec![
                            [100.3, 20.7, 0.0],
                            [150.9, 30.2, 1.0],
                            [120.4, 70.6, 0.5],
                            [101.1, 30.3, 1.0],
                            [149.2, 22.8, 0.0],
                            [130.7, 68.1, 0.5],
                        ]),
                        indices: std::sync::Arc::new(vec![[0, 1, 2], [3, 4, 5]]),
                        colors: std::sync::Arc::new(
                            vec![Color::rgb(20, 120, 60); 3]
                                .into_iter()
                                .chain(vec![Color::rgb(90, 30, 160); 3])
                                .collect(),
                        ),
                        normals: None,
                    }),
                    Style::default(),
                ),
                Item::text(
                    Role::Title,
                    Text {
                        at: Point::new(80.0, 108.0),
                        content: "Tiles".into(),
                        size: 10.0,
                        anchor: crate::scene::Anchor::Middle,
                        baseline: crate::scene::Baseline::Bottom,
                        angle: 0.0,
                        color: Color::BLACK,
                    },
                ),
            ],
        }
    }

    fn is_marks(item: &Item) -> bool {
        item.role == Role::DataMark && matches!(item.shape, Shape::Points(_))
    }

    #[test]
    fn tiles_composite_to_the_png_pixels() {
        let s = scene();
        for scale in [1.0, 2.0] {
            let tiles = Tiles::new(&s, scale, is_marks);
            assert_eq!(tiles.tiles.iter().filter(|t| t.dynamic).count(), 1);
            assert_eq!(tiles.tiles.len(), 3, "static run, marks, static run");
            let (w, h, pixels) = tiles.composite();
            let png = to_pixmap(&s, scale).unwrap();
            assert_eq!((w, h), (png.width(), png.height()));
            let worst = pixels.iter().zip(png.data()).map(|(a, b)| a.abs_diff(*b)).max().unwrap();
            assert!(worst <= 1, "tiles differ from the PNG by {worst} at scale {scale}");
        }
    }

    #[test]
    fn dynamic_tiles_stay_inside_their_clip_and_redraw() {
        let mut tiles = Tiles::new(&scene(), 1.0, is_marks);
        let marks = tiles.tiles.iter().position(|t| t.dynamic).unwrap();
        let r = tiles.tiles[marks].rect;
        assert!(Rect::new(10.0, 10.0, 130.0, 80.0).contains_rect(&r, 1.0), "{r:?}");
        let before = tiles.tiles[marks].rgba.clone();
        let version = tiles.tiles[marks].version;
        // Replacing the batch by nothing leaves a transparent tile.
        tiles.redraw_dynamic(|_| Vec::new());
        assert_eq!(tiles.tiles[marks].version, version + 1);
        assert!(before.iter().any(|&b| b > 0));
        assert!(tiles.tiles[marks].rgba.iter().all(|&b| b == 0));
    }
}
