//! Scene: the immutable tree of geometry that every renderer draws and every lint rule reads
//! (shapes, text, rasters, point and line batches, and depth-tested triangle [`Mesh`]es).
//!
//! Coordinates are floats in canvas units (CSS pixels at scale 1), origin top-left, y down.
//! Every item carries a [`Role`] and, for data marks, the source rows it was drawn from, so that
//! lint rules can reason about what the reader sees and the explorer can link views by row.

pub mod world_mesh;
pub use world_mesh::WorldMesh;

use std::sync::Arc;

/// An RGBA colour with straight (non-premultiplied) 8-bit channels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Color {
    /// Red channel.
    pub r: u8,
    /// Green channel.
    pub g: u8,
    /// Blue channel.
    pub b: u8,
    /// Alpha channel: 0 transparent, 255 opaque.
    pub a: u8,
}

impl Color {
    /// Opaque black.
    pub const BLACK: Color = Color::rgb(0, 0, 0);
    /// Opaque white.
    pub const WHITE: Color = Color::rgb(255, 255, 255);
    /// Fully transparent.
    pub const TRANSPARENT: Color = Color { r: 0, g: 0, b: 0, a: 0 };

    /// An opaque colour.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Color {
        Color { r, g, b, a: 255 }
    }

    /// The same colour with its alpha multiplied by `opacity` (clamped to 0..=1).
    pub fn with_opacity(self, opacity: f64) -> Color {
        let o = if opacity.is_finite() { opacity.clamp(0.0, 1.0) } else { 1.0 };
        Color { a: (self.a as f64 * o).round() as u8, ..self }
    }

    /// `#rrggbb` (alpha is written separately by renderers).
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }

    /// Alpha as a fraction in 0..=1.
    pub fn alpha(self) -> f64 {
        self.a as f64 / 255.0
    }
}

/// A point in canvas coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Horizontal position, growing rightwards.
    pub x: f64,
    /// Vertical position, growing downwards.
    pub y: f64,
}

impl Point {
    /// A point at (x, y).
    pub const fn new(x: f64, y: f64) -> Point {
        Point { x, y }
    }
}

/// An axis-aligned rectangle in canvas coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Left edge.
    pub x: f64,
    /// Top edge.
    pub y: f64,
    /// Width (≥ 0).
    pub w: f64,
    /// Height (≥ 0).
    pub h: f64,
}

impl Rect {
    /// A rectangle from its left, top, width and height.
    pub const fn new(x: f64, y: f64, w: f64, h: f64) -> Rect {
        Rect { x, y, w, h }
    }
    /// Right edge.
    pub fn right(&self) -> f64 {
        self.x + self.w
    }
    /// Bottom edge.
    pub fn bottom(&self) -> f64 {
        self.y + self.h
    }
    /// Whether the two rectangles share interior area.
    pub fn intersects(&self, other: &Rect) -> bool {
        self.x < other.right() && other.x < self.right() && self.y < other.bottom() && other.y < self.bottom()
    }
    /// Whether `other` lies entirely inside this rectangle (within `eps`).
    pub fn contains_rect(&self, other: &Rect, eps: f64) -> bool {
        other.x >= self.x - eps
            && other.y >= self.y - eps
            && other.right() <= self.right() + eps
            && other.bottom() <= self.bottom() + eps
    }
}

/// What an item is for. Lint rules and the explorer select items by role.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    /// The canvas or plot background.
    Background,
    /// A mark that encodes data rows (points, lines, bars, cells).
    DataMark,
    /// An axis line or tick mark.
    Axis,
    /// The text of a tick label.
    TickLabel,
    /// The title of an axis.
    AxisTitle,
    /// A grid line.
    Grid,
    /// Any part of a legend or colour bar (swatches, ramp, labels, title).
    Legend,
    /// The chart title.
    Title,
    /// The chart caption or subtitle.
    Caption,
    /// Any other annotation (reference lines, notes).
    Annotation,
}

/// A stroke: colour, width in canvas units, and optional dash pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct Stroke {
    /// Stroke colour (alpha included).
    pub color: Color,
    /// Line width in canvas units.
    pub width: f64,
    /// Dash lengths, alternating on/off, in canvas units; empty for a solid line.
    pub dash: Vec<f64>,
}

impl Stroke {
    /// A solid stroke.
    pub fn solid(color: Color, width: f64) -> Stroke {
        Stroke { color, width, dash: Vec::new() }
    }
}

/// Fill and stroke of a shape. Either may be absent.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Style {
    /// Interior colour.
    pub fill: Option<Color>,
    /// Outline.
    pub stroke: Option<Stroke>,
}

impl Style {
    /// Filled, no outline.
    pub fn fill(color: Color) -> Style {
        Style { fill: Some(color), stroke: None }
    }
    /// Outlined, no fill.
    pub fn stroke(color: Color, width: f64) -> Style {
        Style { fill: None, stroke: Some(Stroke::solid(color, width)) }
    }
}

/// Vector backends (SVG) draw a path of more commands than this as an embedded raster: a contour
/// band or a network's edges with millions of vertices would make a file of hundreds of
/// megabytes.
pub const PATH_VECTOR_LIMIT: usize = 400_000;

/// Points of a path's commands (end and control points), for its bounds.
pub fn path_points(cmds: &[PathCmd]) -> impl Iterator<Item = Point> + '_ {
    cmds.iter()
        .flat_map(|c| match *c {
            PathCmd::MoveTo(p) | PathCmd::LineTo(p) => [Some(p), None, None],
            PathCmd::QuadTo(a, b) => [Some(a), Some(b), None],
            PathCmd::CubicTo(a, b, c) => [Some(a), Some(b), Some(c)],
            PathCmd::Close => [None, None, None],
        })
        .flatten()
}

/// One drawing command of a path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathCmd {
    /// Start a new subpath.
    MoveTo(Point),
    /// Straight segment.
    LineTo(Point),
    /// Quadratic Bézier segment: control, end.
    QuadTo(Point, Point),
    /// Cubic Bézier segment: control 1, control 2, end.
    CubicTo(Point, Point, Point),
    /// Close the current subpath.
    Close,
}

/// Horizontal anchoring of text relative to its position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// Text starts at the position.
    Start,
    /// Text is centred on the position.
    Middle,
    /// Text ends at the position.
    End,
}

/// Vertical anchoring of text relative to its position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Baseline {
    /// The top of the em box (ascent) is at the position.
    Top,
    /// The middle of the em box is at the position.
    Middle,
    /// The alphabetic baseline is at the position.
    Alphabetic,
    /// The bottom of the em box (descent) is at the position.
    Bottom,
}

/// A single line of text drawn with the embedded font.
#[derive(Clone, Debug, PartialEq)]
pub struct Text {
    /// Anchor position.
    pub at: Point,
    /// The text itself, as given by the user (renderers escape it).
    pub content: String,
    /// Font size in canvas units.
    pub size: f64,
    /// Horizontal anchoring.
    pub anchor: Anchor,
    /// Vertical anchoring.
    pub baseline: Baseline,
    /// Rotation in degrees, clockwise, about the anchor position.
    pub angle: f64,
    /// Text colour.
    pub color: Color,
}

/// A value given once for all points of a batch, or once per point.
#[derive(Clone, Debug, PartialEq)]
pub enum PerPoint<T> {
    /// The same value for every point.
    Uniform(T),
    /// One value per point, in point order.
    Each(Vec<T>),
}

impl<T: Copy> PerPoint<T> {
    /// The value for point `i` (falls back to the first value if `i` is out of range).
    pub fn at(&self, i: usize) -> Option<T> {
        match self {
            PerPoint::Uniform(v) => Some(*v),
            PerPoint::Each(vs) => vs.get(i).or(vs.first()).copied(),
        }
    }
}

/// Many circles drawn the same way: the scatter plot's mark, kept compact for millions of points.
#[derive(Clone, Debug, PartialEq)]
pub struct PointBatch {
    /// Centres, in drawing order.
    pub centers: Vec<Point>,
    /// Radii in canvas units.
    pub radius: PerPoint<f64>,
    /// Fill colours (alpha included).
    pub fill: PerPoint<Color>,
    /// Optional outline, the same for every point.
    pub stroke: Option<Stroke>,
}

impl PointBatch {
    /// Vector backends (SVG) draw a batch of more points than this as one embedded raster: a
    /// million `<circle>` elements make a file of tens of megabytes that viewers struggle with.
    pub const VECTOR_LIMIT: usize = 100_000;

    /// Whether vector backends embed this batch as a raster (more than [`Self::VECTOR_LIMIT`] points).
    pub fn drawn_as_raster(&self) -> bool {
        self.centers.len() > Self::VECTOR_LIMIT
    }
}

/// Many open polylines with the same number of vertices, drawn the same way: one per data row
/// (parallel coordinates, daisy charts), kept compact for tens of thousands of rows.
#[derive(Clone, Debug, PartialEq)]
pub struct LineBatch {
    /// Vertices, `stride` per polyline, polylines in drawing order. A non-finite vertex breaks its polyline (the
    /// segments touching it are skipped).
    pub points: Vec<Point>,
    /// Vertices per polyline (at least 2).
    pub stride: usize,
    /// Stroke colour (alpha included), once or per polyline.
    pub color: PerPoint<Color>,
    /// Stroke width in canvas units.
    pub width: f64,
}

impl LineBatch {
    /// Vector backends (SVG) draw a batch of more vertices than this as one embedded raster, as
    /// they do large point batches.
    pub const VECTOR_LIMIT: usize = 400_000;

    /// Whether vector backends embed this batch as a raster (more than [`Self::VECTOR_LIMIT`]
    /// vertices).
    pub fn drawn_as_raster(&self) -> bool {
        self.points.len() > Self::VECTOR_LIMIT
    }

    /// Number of whole polylines (`points.len() / stride`; trailing vertices that do not make a whole polyline
    /// are ignored, and a stride below 2 gives none).
    pub fn len(&self) -> usize {
        if self.stride < 2 { 0 } else { self.points.len() / self.stride }
    }

    /// Whether the batch has no whole polyline.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The vertices of polyline `i` (`None` past the last whole polyline).
    pub fn polyline(&self, i: usize) -> Option<&[Point]> {
        if i >= self.len() {
            return None;
        }
        self.points.get(i * self.stride..(i + 1) * self.stride)
    }
}

/// An RGBA raster placed into a rectangle of the canvas (heatmaps, LIC, pixel displays).
#[derive(Clone, Debug, PartialEq)]
pub struct Raster {
    /// Where the image goes.
    pub dest: Rect,
    /// Pixel columns.
    pub width: u32,
    /// Pixel rows.
    pub height: u32,
    /// Straight-alpha RGBA bytes, row-major, `width * height * 4` long.
    pub rgba: Arc<Vec<u8>>,
    /// Bilinear smoothing when scaled (otherwise nearest neighbour).
    pub smooth: bool,
}

/// Indexed triangles in 3-D with one colour per vertex, drawn depth-correctly: surfaces and,
/// later, isosurfaces. Vertices are already projected and lit by their maker (the 3-D kinds use
/// `enrich::camera`): x and y are canvas units, z is a depth where **larger is nearer**,
/// varying linearly across the canvas within each triangle (what a z-buffer interpolates).
///
/// The raster backend keeps, at every pixel, the nearest triangle (z-buffer) with its colour
/// interpolated from the vertices (Gouraud), so intersecting or unsorted triangles come out
/// right; the vector backend writes triangles back to front by mean depth (painter's order), each
/// in the mean colour of its vertices, or embeds the raster above [`Mesh::VECTOR_LIMIT`]
/// triangles. A triangle with an index out of range or a non-finite vertex is skipped, and so is
/// one with no area.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Vertex positions `[x, y, depth]`: canvas units, depth larger = nearer.
    pub positions: Arc<Vec<[f32; 3]>>,
    /// Triangles as indices into `positions` (and `colors`, `normals`).
    pub indices: Arc<Vec<[u32; 3]>>,
    /// Colour of each vertex, already shaded (alpha included; overlapping triangles of one mesh
    /// do not blend: the nearest wins). A vertex without a colour is drawn transparent.
    pub colors: Arc<Vec<Color>>,
    /// Optional unit normal of each vertex in model space, for makers that relight a mesh;
    /// renderers do not read it.
    pub normals: Option<Arc<Vec<[f32; 3]>>>,
}

impl Mesh {
    /// Vector backends (SVG) embed a mesh of more triangles than this as a raster: one `<path>`
    /// per triangle makes a file of megabytes that viewers draw slowly.
    pub const VECTOR_LIMIT: usize = 20_000;

    /// Whether vector backends embed this mesh as a raster (more than [`Self::VECTOR_LIMIT`]
    /// triangles).
    pub fn drawn_as_raster(&self) -> bool {
        self.indices.len() > Self::VECTOR_LIMIT
    }

    /// The three vertices (`[x, y, depth]`) and colours of triangle `i`, or `None` when it is
    /// past the end, an index is out of range, a coordinate is not finite or it has no area.
    pub fn triangle(&self, i: usize) -> Option<([[f32; 3]; 3], [Color; 3])> {
        let tri = self.indices.get(i)?;
        let v = |k: usize| self.positions.get(*tri.get(k)? as usize).copied();
        let p = [v(0)?, v(1)?, v(2)?];
        if p.iter().flatten().any(|c| !c.is_finite()) {
            return None;
        }
        let [a, b, c] = p.map(|q| [f64::from(q[0]), f64::from(q[1])]);
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area == 0.0 || !area.is_finite() {
            return None;
        }
        let colour =
            |k: usize| tri.get(k).and_then(|&j| self.colors.get(j as usize)).copied().unwrap_or(Color::TRANSPARENT);
        Some((p, [colour(0), colour(1), colour(2)]))
    }

    /// The rectangle covering every finite vertex (`None` when there is none).
    pub fn bounds(&self) -> Option<Rect> {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in self.positions.iter() {
            let (x, y) = (f64::from(p[0]), f64::from(p[1]));
            if x.is_finite() && y.is_finite() {
                (lo[0], lo[1]) = (lo[0].min(x), lo[1].min(y));
                (hi[0], hi[1]) = (hi[0].max(x), hi[1].max(y));
            }
        }
        (lo[0] <= hi[0]).then(|| Rect::new(lo[0], lo[1], hi[0] - lo[0], hi[1] - lo[1]))
    }
}

/// The geometry of one item.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A rectangle.
    Rect(Rect),
    /// A circle.
    Circle {
        /// Centre.
        center: Point,
        /// Radius.
        radius: f64,
    },
    /// A path of lines and curves.
    Path(Vec<PathCmd>),
    /// A line of text.
    Text(Text),
    /// An embedded raster image.
    Image(Raster),
    /// Many circles at once.
    Points(PointBatch),
    /// Many polylines at once.
    Lines(LineBatch),
    /// Triangles drawn with hidden surfaces removed.
    Mesh(Mesh),
    /// A group of items, optionally clipped to a rectangle.
    Group {
        /// Children, drawn in order.
        items: Vec<Item>,
        /// Clip rectangle for the children.
        clip: Option<Rect>,
    },
}

/// One node of the scene tree.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// What the item is for.
    pub role: Role,
    /// Its geometry.
    pub shape: Shape,
    /// How it is painted (ignored for text, images and groups).
    pub style: Style,
    /// Source rows: for a data mark the rows it encodes (for a point batch, one per point, in
    /// order; for a line batch, one per polyline, in order); empty for everything else.
    pub rows: Vec<u32>,
    /// An optional human-readable name (e.g. the series or axis), used by lint messages and SVG ids.
    pub label: Option<String>,
    /// Hover text of a data mark, written as SVG `<title>`s: one for a single shape, or one per
    /// point of a point batch and per polyline of a line batch; empty for none.
    pub tooltips: Vec<String>,
}

impl Item {
    /// An item with no source rows and no label.
    pub fn new(role: Role, shape: Shape, style: Style) -> Item {
        Item { role, shape, style, rows: Vec::new(), label: None, tooltips: Vec::new() }
    }
    /// The same item with a label.
    pub fn labelled(mut self, label: impl Into<String>) -> Item {
        self.label = Some(label.into());
        self
    }
    /// The same item with one hover text (see [`Item::tooltips`]).
    pub fn with_tooltip(mut self, text: impl Into<String>) -> Item {
        self.tooltips = vec![text.into()];
        self
    }
    /// The same item with its source rows.
    pub fn with_rows(mut self, rows: Vec<u32>) -> Item {
        self.rows = rows;
        self
    }
    /// A group of items.
    pub fn group(role: Role, items: Vec<Item>, clip: Option<Rect>) -> Item {
        Item::new(role, Shape::Group { items, clip }, Style::default())
    }
    /// A text item.
    pub fn text(role: Role, text: Text) -> Item {
        Item::new(role, Shape::Text(text), Style::default())
    }
}

/// A finished chart: canvas size, background and the items drawn on it.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Canvas width in canvas units.
    pub width: f64,
    /// Canvas height in canvas units.
    pub height: f64,
    /// Canvas background.
    pub background: Color,
    /// Accessible title (SVG `<title>`), usually the chart title.
    pub title: Option<String>,
    /// Items drawn in order, first at the back.
    pub items: Vec<Item>,
}

impl Scene {
    /// Visit every item depth-first (groups before their children).
    pub fn walk<'a>(&'a self, mut visit: impl FnMut(&'a Item)) {
        fn go<'a>(items: &'a [Item], visit: &mut impl FnMut(&'a Item)) {
            for item in items {
                visit(item);
                if let Shape::Group { items, .. } = &item.shape {
                    go(items, visit);
                }
            }
        }
        go(&self.items, &mut visit);
    }
}

impl Point {
    /// The point moved by (dx, dy).
    pub fn offset(self, dx: f64, dy: f64) -> Point {
        Point::new(self.x + dx, self.y + dy)
    }
}

impl Rect {
    /// The rectangle moved by (dx, dy).
    pub fn offset(self, dx: f64, dy: f64) -> Rect {
        Rect::new(self.x + dx, self.y + dy, self.w, self.h)
    }
}

impl Item {
    /// The same item moved by (dx, dy), children and clips included (for panels laid out as
    /// separate frames and then placed on one canvas).
    pub fn translated(mut self, dx: f64, dy: f64) -> Item {
        self.shape = match self.shape {
            Shape::Rect(r) => Shape::Rect(r.offset(dx, dy)),
            Shape::Circle { center, radius } => Shape::Circle { center: center.offset(dx, dy), radius },
            Shape::Path(cmds) => Shape::Path(
                cmds.into_iter()
                    .map(|c| match c {
                        PathCmd::MoveTo(p) => PathCmd::MoveTo(p.offset(dx, dy)),
                        PathCmd::LineTo(p) => PathCmd::LineTo(p.offset(dx, dy)),
                        PathCmd::QuadTo(a, p) => PathCmd::QuadTo(a.offset(dx, dy), p.offset(dx, dy)),
                        PathCmd::CubicTo(a, b, p) => {
                            PathCmd::CubicTo(a.offset(dx, dy), b.offset(dx, dy), p.offset(dx, dy))
                        }
                        PathCmd::Close => PathCmd::Close,
                    })
                    .collect(),
            ),
            Shape::Text(mut t) => {
                t.at = t.at.offset(dx, dy);
                Shape::Text(t)
            }
            Shape::Image(mut r) => {
                r.dest = r.dest.offset(dx, dy);
                Shape::Image(r)
            }
            Shape::Points(mut b) => {
                for c in &mut b.centers {
                    *c = c.offset(dx, dy);
                }
                Shape::Points(b)
            }
            Shape::Lines(mut b) => {
                for p in &mut b.points {
                    *p = p.offset(dx, dy);
                }
                Shape::Lines(b)
            }
            Shape::Mesh(mut m) => {
                let (dx, dy) = (dx as f32, dy as f32);
                m.positions = Arc::new(m.positions.iter().map(|p| [p[0] + dx, p[1] + dy, p[2]]).collect());
                Shape::Mesh(m)
            }
            Shape::Group { items, clip } => Shape::Group {
                items: items.into_iter().map(|i| i.translated(dx, dy)).collect(),
                clip: clip.map(|r| r.offset(dx, dy)),
            },
        };
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_triangles_bounds_and_moves() {
        let m = Mesh {
            positions: Arc::new(vec![
                [0.0, 0.0, 1.0],
                [10.0, 0.0, 2.0],
                [0.0, 5.0, 3.0],
                [f32::NAN, 1.0, 0.0],
                [4.0, 0.0, 0.0],
            ]),
            indices: Arc::new(vec![[0, 1, 2], [0, 1, 3], [0, 1, 4], [0, 1, 5]]),
            colors: Arc::new(vec![Color::BLACK, Color::WHITE]),
            normals: None,
        };
        let Some((p, c)) = m.triangle(0) else { panic!("triangle 0 is whole") };
        assert_eq!(p[2], [0.0, 5.0, 3.0]);
        assert_eq!(c, [Color::BLACK, Color::WHITE, Color::TRANSPARENT], "a vertex without a colour is transparent");
        assert!(m.triangle(1).is_none(), "non-finite vertex");
        assert!(m.triangle(2).is_none(), "no area");
        assert!(m.triangle(3).is_none(), "index out of range");
        assert!(m.triangle(4).is_none(), "past the end");
        assert_eq!(m.bounds(), Some(Rect::new(0.0, 0.0, 10.0, 5.0)));
        assert!(!m.drawn_as_raster());
        let moved = Item::new(Role::DataMark, Shape::Mesh(m), Style::default()).translated(2.0, -1.0);
        let Shape::Mesh(moved) = moved.shape else { panic!("still a mesh") };
        assert_eq!(moved.bounds(), Some(Rect::new(2.0, -1.0, 10.0, 5.0)));
        assert_eq!(moved.positions[2], [2.0, 4.0, 3.0], "depth unchanged");
    }
}
