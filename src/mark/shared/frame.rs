//! The cartesian frame every x/y chart kind shares: canvas size and theme from the chart spec,
//! the laid-out frame, and the final scene with the data marks clipped to the plot.

use crate::guide::Theme;
use crate::guide::layout::{self, FixedPlot, Frame, FrameSpec, PositionAxis};
use crate::guide::legend::truncate_to_width;
use crate::guide::legend::{self, Legend};
use crate::mark::{FRAME_SIZE, MarkError, Warning, annotate};
use crate::scene::{
    Anchor, Baseline, Color, Item, LineBatch, PathCmd, PerPoint, Point, PointBatch, Rect, Role, Scene, Shape, Style,
    Text,
};
use crate::spec::Chart;

/// Lay out the frame of chart `index` around its axes (widened to take in its annotations) and
/// legends, with its annotations placed in it.
///
/// A facet panel ([`Chart::panel`]) takes the domains and plot area its layout fixed, and
/// records its axes and legends instead of drawing the legends.
pub fn cartesian(
    chart: &Chart,
    mut x: PositionAxis,
    mut y: PositionAxis,
    mut legends: Vec<Legend>,
) -> Result<(Frame, Theme), MarkError> {
    annotate::widen(chart, &mut x, &mut y);
    let [width, height] = chart.size.unwrap_or(FRAME_SIZE);
    let theme = Theme::with_font_size(chart.font_size.unwrap_or(12.0));
    let mut fixed = None;
    if let Some(panel) = &chart.panel {
        panel.saw_axes(&x, &y);
        panel.saw_legends(&legends);
        if panel.measuring {
            return Err(MarkError::measured());
        }
        legends.clear();
        if let Some(domain) = &panel.x {
            x.domain = domain.clone();
        }
        if let Some(domain) = &panel.y {
            y.domain = domain.clone();
        }
        fixed = panel.plot.map(|plot| FixedPlot {
            plot,
            x_labels: panel.x_labels,
            y_labels: panel.y_labels,
            overhang: panel.overhang,
        });
    }
    let mut frame = layout::cartesian(&FrameSpec {
        width,
        height,
        title: chart.title.clone(),
        caption: chart.caption.clone(),
        x,
        y,
        legends,
        theme: theme.clone(),
        equal_aspect: chart.aspect == Some(crate::spec::Aspect::Equal),
        fixed,
    })
    .map_err(|e| MarkError::layout(e))?;
    frame.overlay = annotate::resolve(chart, &frame, &theme)?;
    Ok((frame, theme))
}

/// The chart's scene: background and grid, annotated bands, the marks clipped to the plot, the
/// other annotations, then axes and legends. The frame's notes (category labels left out) go
/// to `warnings`.
pub fn scene(chart: &Chart, frame: Frame, theme: &Theme, marks: Vec<Item>, warnings: &mut Vec<Warning>) -> Scene {
    warnings.extend(frame.notes.iter().cloned().map(Warning::from));
    let [width, height] = chart.size.unwrap_or(FRAME_SIZE);
    let canvas = Rect::new(0.0, 0.0, width, height);
    let notes = annotate::draw(frame.overlay, frame.plot, canvas, theme, &[&marks, &frame.over]);
    let mut items = frame.under;
    items.extend(notes.under);
    items.push(Item::group(Role::DataMark, marks, Some(frame.plot)));
    items.extend(notes.over);
    items.extend(frame.over);
    Scene { width, height, background: theme.background, title: chart.title.clone(), items }
}

/// The warning of a chart whose point batches are too large for vector output: how many points
/// the SVG carries as embedded rasters (see [`PointBatch::drawn_as_raster`]); `None` when none.
pub fn raster_note(items: &[Item]) -> Option<String> {
    fn count(items: &[Item]) -> usize {
        items
            .iter()
            .map(|item| match &item.shape {
                Shape::Points(batch) if batch.drawn_as_raster() => batch.centers.len(),
                Shape::Group { items, .. } => count(items),
                _ => 0,
            })
            .sum()
    }
    let points = count(items);
    (points > 0).then(|| {
        format!(
            "{points} points drawn as an embedded raster in the SVG (more than {} in one layer)",
            PointBatch::VECTOR_LIMIT
        )
    })
}

/// The chart title (top left, `top` from the canvas edge) and caption (bottom left), for kinds
/// that lay out their own panels instead of one cartesian frame. `caption` overrides the spec's.
pub fn title_and_caption(chart: &Chart, theme: &Theme, top: f64, caption: Option<&str>) -> Vec<Item> {
    let [width, height] = chart.size.unwrap_or(FRAME_SIZE);
    let m = theme.margin;
    let line = |role, at, content: &str, size, baseline, color| {
        Item::text(
            role,
            Text {
                at,
                content: truncate_to_width(content, width - 2.0 * m, size),
                size,
                anchor: Anchor::Start,
                baseline,
                angle: 0.0,
                color,
            },
        )
    };
    let mut items = Vec::new();
    if let Some(t) = &chart.title {
        items.push(line(Role::Title, Point::new(m, top), t, theme.title_size, Baseline::Top, theme.text));
    }
    if let Some(c) = caption.or(chart.caption.as_deref()) {
        items.push(line(
            Role::Caption,
            Point::new(m, height - top),
            c,
            theme.caption_size,
            Baseline::Bottom,
            theme.muted_text,
        ));
    }
    items
}

/// A polyline (closed with `Close` when `closed`) through data points mapped by `to_px`.
pub fn polyline(points: &[(f64, f64)], closed: bool, to_px: &impl Fn((f64, f64)) -> Point) -> Vec<PathCmd> {
    let mut cmds: Vec<PathCmd> = points
        .iter()
        .enumerate()
        .map(|(k, &p)| if k == 0 { PathCmd::MoveTo(to_px(p)) } else { PathCmd::LineTo(to_px(p)) })
        .collect();
    if closed && !cmds.is_empty() {
        cmds.push(PathCmd::Close);
    }
    cmds
}

/// Polylines of `stride` vertices each, one per row of `rows` (in order), stroked `width` wide
/// in the row's colour, as one compact batch. A non-finite vertex breaks its polyline.
pub fn polylines(
    vertices: Vec<Point>,
    stride: usize,
    rows: &[u32],
    color: impl Fn(u32) -> Color,
    width: f64,
) -> Vec<Item> {
    if rows.is_empty() {
        return Vec::new();
    }
    let colors: Vec<Color> = rows.iter().map(|&r| color(r)).collect();
    let color =
        if colors.windows(2).all(|w| w[0] == w[1]) { PerPoint::Uniform(colors[0]) } else { PerPoint::Each(colors) };
    let batch = LineBatch { points: vertices, stride, color, width };
    vec![Item::new(Role::DataMark, Shape::Lines(batch), Style::default()).with_rows(rows.to_vec())]
}

/// A point at `radius` from `center`, `angle` radians clockwise from 12 o'clock.
pub fn polar(center: Point, radius: f64, angle: f64) -> Point {
    Point::new(center.x + radius * angle.sin(), center.y - radius * angle.cos())
}

/// The canvas of a kind that lays out its own panels (surface, hyperslice, splom, parallel,
/// daisy, faces, segments): size, theme, the room left between title and caption, and a column
/// of legends on the right.
pub struct PanelCanvas {
    /// Canvas width.
    pub width: f64,
    /// Canvas height.
    pub height: f64,
    /// Sizes and colours.
    pub theme: Theme,
    /// Height of the title block (0 without a title).
    pub title_h: f64,
    /// Height of the caption block (0 without a caption).
    pub caption_h: f64,
    /// Height available between title and caption.
    pub room: f64,
    /// The legends, stacked top to bottom on the right.
    pub legends: Vec<Legend>,
    /// Width the legend column needs.
    pub legend_w: f64,
}

impl PanelCanvas {
    /// Measure the canvas of `chart` with `legends` on the right.
    /// A facet panel records its legends instead, for its layout to draw them once.
    pub fn new(chart: &Chart, mut legends: Vec<Legend>) -> PanelCanvas {
        if let Some(panel) = &chart.panel {
            panel.saw_legends(&legends);
            legends.clear();
        }
        let [width, height] = chart.size.unwrap_or(FRAME_SIZE);
        let theme = Theme::with_font_size(chart.font_size.unwrap_or(12.0));
        let title_h = chart.title.as_ref().map(|_| theme.title_size * 1.8).unwrap_or(0.0);
        let caption_h = chart.caption.as_ref().map(|_| theme.caption_size * 1.8).unwrap_or(0.0);
        let room = height - title_h - caption_h - 2.0 * theme.margin;
        let legend_w = legend::stack_width(&legends, &theme, room);
        PanelCanvas { width, height, theme, title_h, caption_h, room, legends, legend_w }
    }

    /// Top of the room below the title.
    pub fn top(&self) -> f64 {
        self.theme.margin + self.title_h
    }

    /// Width the legend column takes from the right of the room, gap included (0 without legends).
    pub fn legend_room(&self) -> f64 {
        legend::stack_room(&self.legends, &self.theme, self.room)
    }

    /// The canvas background, the first item of the scene.
    pub fn background(&self) -> Item {
        Item::new(
            Role::Background,
            Shape::Rect(Rect::new(0.0, 0.0, self.width, self.height)),
            Style::fill(self.theme.background),
        )
    }

    /// The finished scene: `items`, then title, caption (overridden by `caption`) and legends.
    pub fn scene(self, chart: &Chart, mut items: Vec<Item>, caption: Option<&str>) -> Scene {
        let m = self.theme.margin;
        items.extend(title_and_caption(chart, &self.theme, m, caption));
        let at = Point::new(self.width - m - self.legend_w, self.top());
        items.extend(legend::draw_stack(&self.legends, at, &self.theme, self.room));
        Scene {
            width: self.width,
            height: self.height,
            background: self.theme.background,
            title: chart.title.clone(),
            items,
        }
    }
}

/// Maps layout units (y down) into a pixel rectangle `[x, y, w, h]`, keeping the aspect ratio when asked,
/// centred, with `inset` pixels kept free on every side.
#[derive(Clone, Copy, Debug)]
pub struct Fit {
    sx: f64,
    sy: f64,
    ox: f64,
    oy: f64,
}

impl Fit {
    /// The fit of `points` into `rect` (x, y, width, height).
    pub fn new(points: impl Iterator<Item = [f64; 2]>, rect: [f64; 4], inset: f64, uniform: bool) -> Fit {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if !lo[0].is_finite() {
            (lo, hi) = ([0.0; 2], [1.0; 2]);
        }
        let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
        let room = [(rect[2] - 2.0 * inset).max(1.0), (rect[3] - 2.0 * inset).max(1.0)];
        let (mut sx, mut sy) = (room[0] / span[0], room[1] / span[1]);
        if uniform {
            sx = sx.min(sy);
            sy = sx;
        }
        // A single point (or a line) sits in the middle.
        let ox = rect[0] + rect[2] / 2.0 - sx * (lo[0] + hi[0]) / 2.0;
        let oy = rect[1] + rect[3] / 2.0 - sy * (lo[1] + hi[1]) / 2.0;
        Fit { sx, sy, ox, oy }
    }

    /// A layout point in pixels.
    pub fn at(&self, p: [f64; 2]) -> Point {
        Point::new(self.ox + self.sx * p[0], self.oy + self.sy * p[1])
    }
}
