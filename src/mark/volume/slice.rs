//! `slice`: planes through a volume drawn as images sharing one colour bar — along a world axis
//! at given positions, spread evenly through the volume (a lightbox), or oblique — with optional
//! contour lines on each slice and an inset showing where the planes lie in the volume.

use std::sync::Arc;

use crate::enrich::contour::{self, Saddle};
use crate::enrich::grid::Grid;
use crate::enrich::volume::{Interpolation, Sampler};
use crate::guide::axis::{self, Side, title_with_unit};
use crate::guide::color::{self, ContinuousMap};
use crate::guide::format::format_value;
use crate::guide::layout::LayoutError;
use crate::guide::legend::Legend;
use crate::guide::scale::{LinearScale, Scale};
use crate::guide::theme::Theme;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::level_labels::level_labels;
use crate::mark::raster::{MAX_RASTER_SIDE, NAN_COLOR};
use crate::mark::registry::{ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Raster, Rect, Role, Shape, Stroke, Style, Text};
use crate::spec::{Chart, ColorOptions, Levels};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::inset;
use super::planes::{self, Slice};

/// Options of `kind = "slice"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SliceOptions {
    /// The world axis the slices cross: `z` (default: axial, x across and y up), `y` (coronal: x
    /// across, z up) or `x` (sagittal: y across, z up).
    #[serde(default)]
    pub axis: Option<SliceAxis>,
    /// Where the slices cross `axis`, in world coordinates (the units of the volume's spacing),
    /// one panel each, at most 64.
    #[serde(default)]
    pub at: Option<Vec<f64>>,
    /// This many slices spread evenly through the volume along `axis` (a lightbox; 1 to 64),
    /// each on the nearest voxel plane. Default: one slice through the middle.
    #[serde(default)]
    pub count: Option<u32>,
    /// With `count`: the range along `axis` the slices spread over, `[lo, hi]` in world
    /// coordinates (default: the whole volume).
    #[serde(default)]
    pub between: Option<[f64; 2]>,
    /// Oblique planes instead of `axis`: each `{ point = [x, y, z], normal = [a, b, c] }` in
    /// world coordinates; a panel's axes `u` and `v` measure from the point.
    #[serde(default)]
    pub planes: Option<Vec<PlaneSpec>>,
    /// `trilinear` (default: smooth) or `nearest` (each pixel shows its voxel).
    #[serde(default)]
    pub resample: Option<VolumeResample>,
    /// How values are coloured: `{ title, unit, scheme, midpoint, domain, legend }`; `domain =
    /// [lo, hi]` fixes the colour bar's range (a CT window), values beyond it take the end
    /// colours. Default: the volume's whole range, black to white.
    #[serde(default)]
    pub value: Option<ValueColor>,
    /// Contour lines on every slice: a number of nice levels or the levels themselves.
    #[serde(default)]
    pub contours: Option<Levels>,
    /// Panels per row (default: the count that draws the slices largest).
    #[serde(default)]
    pub columns: Option<u32>,
    /// Draw the inset showing the planes in the volume's box (default true).
    #[serde(default)]
    pub inset: Option<bool>,
    /// Colour of missing voxels (default light grey, `#d9d9d9`).
    #[serde(default)]
    pub nan_color: Option<String>,
}

/// A world axis a slice crosses.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SliceAxis {
    /// Sagittal planes (x constant).
    X,
    /// Coronal planes (y constant).
    Y,
    /// Axial planes (z constant).
    Z,
}

/// An oblique plane: a point on it and its normal, in world coordinates.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// A point on the plane, `[x, y, z]`.
    pub point: [f64; 3],
    /// The plane's normal, `[a, b, c]` (any non-zero length).
    pub normal: [f64; 3],
}

/// How a volume is read between voxel centres.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum VolumeResample {
    /// Each pixel shows the voxel it falls in.
    Nearest,
    /// Each pixel interpolates the eight voxels around it.
    Trilinear,
}

/// How a volume's values are coloured.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ValueColor {
    /// Colour-bar title (default `value`).
    #[serde(default)]
    pub title: Option<String>,
    /// Unit shown in the colour-bar title.
    #[serde(default)]
    pub unit: Option<String>,
    /// A continuous colour scheme (default `greys_r`, black to white; `viridis`, `magma`, `rdbu`, ...; append `_r`
    /// to reverse).
    #[serde(default)]
    pub scheme: Option<String>,
    /// Centre of a diverging scheme (default: the middle of the domain).
    #[serde(default)]
    pub midpoint: Option<f64>,
    /// The range the colours span, `[lo, hi]` (default: the volume's range).
    #[serde(default)]
    pub domain: Option<[f64; 2]>,
    /// Draw the colour bar (default true).
    #[serde(default)]
    pub legend: Option<bool>,
}

impl ValueColor {
    /// The encoding as lint reads colour encodings, for the volume's values.
    pub fn options(&self) -> ColorOptions {
        ColorOptions {
            field: "value".into(),
            title: self.title.clone(),
            unit: self.unit.clone(),
            scheme: Some(self.scheme.clone().unwrap_or_else(|| DEFAULT_SCHEME.into())),
            r#type: None,
            midpoint: self.midpoint,
            legend: self.legend,
            domain: None,
            range: None,
        }
    }
}

/// The colour scheme of slices when the spec names none: black to white, as radiologists read
/// CT and MRI.
pub const DEFAULT_SCHEME: &str = "greys_r";

/// Most contour nodes along a slice's side.
const MAX_CONTOUR_NODES: usize = 1024;

/// The colours of a slice: the map, the range it spans and the colour of missing voxels.
struct Colouring {
    map: ContinuousMap,
    lo: f64,
    hi: f64,
    nan: Color,
}

impl Colouring {
    fn of(&self, value: Option<f64>) -> Color {
        match value {
            None => Color::TRANSPARENT,
            Some(v) if v.is_finite() => self.map.at((v - self.lo) / (self.hi - self.lo)),
            Some(_) => self.nan,
        }
    }
}

/// Draw a slice chart.
pub fn draw(cx: &ChartContext<'_>, options: &SliceOptions) -> Result<ChartOutput, MarkError> {
    let chart = &cx.chart;
    let volume = cx.volume()?;
    let sampler =
        Sampler::new(&volume).map_err(|e| MarkError::at(&["data"], e, "check the file's orientation header"))?;
    let how = match options.resample.unwrap_or(VolumeResample::Trilinear) {
        VolumeResample::Nearest => Interpolation::Nearest,
        VolumeResample::Trilinear => Interpolation::Trilinear,
    };
    let unit = volume.unit().map_or("", |u| u.symbol());
    let slices = planes::resolve(options, &sampler, how, unit)?;
    let value = options.value.clone().unwrap_or_default();
    let colouring = colouring(&value, options, &volume)?;
    let levels = contour_levels(options.contours.as_ref(), colouring.lo, colouring.hi)?;

    let title = title_with_unit(value.title.as_deref().unwrap_or("value"), value.unit.as_deref());
    let legends = encode::shown_legends(
        Legend::ColorBar { title, map: colouring.map.clone(), domain: (colouring.lo, colouring.hi) },
        &value.options(),
    );
    let mut canvas = frame::PanelCanvas::new(chart, legends);
    let caption = oblique_note(options, chart);
    if caption.is_some() && chart.caption.is_none() {
        // The caption the kind writes needs its room as one the spec gives would.
        let h = canvas.theme.caption_size * 1.8;
        canvas.caption_h = h;
        canvas.room -= h;
    }
    let show_inset = options.inset.unwrap_or(true);
    if show_inset {
        canvas.legend_w = canvas.legend_w.max(inset::WIDTH_EMS * canvas.theme.font_size);
    }
    let theme = canvas.theme.clone();
    let layout = Layout::new(&canvas, &slices, options.columns)?;

    let mut items = vec![canvas.background()];
    let mut derived = DerivedRows::default();
    for (k, slice) in slices.iter().enumerate() {
        let panel = layout.panel(k, slice);
        let (image, range) = slice_image(&sampler, how, slice, &panel, &colouring);
        derived.push(k, slice, range);
        items.push(Item::new(Role::DataMark, Shape::Image(image), Style::default()).labelled(slice.label.clone()));
        let outline: Vec<(f64, f64)> = slice.outline.clone();
        items.push(Item::new(
            Role::Axis,
            Shape::Path(frame::polyline(&outline, true, &|p| panel.to_px(p))),
            Style::stroke(theme.axis, 0.8),
        ));
        if !levels.is_empty() {
            items.extend(contour_items(&sampler, slice, &panel, &levels, &theme)?);
        }
        items.push(header(&slice.label, panel.rect, &theme));
        items.extend(panel_axes(&layout, k, slices.len(), slice, &panel, unit, &theme));
    }
    if show_inset {
        let legend_bottom = canvas.top() + crate::guide::legend::stack_height(&canvas.legends, &theme, canvas.room);
        items.extend(inset::draw(&sampler, how, &slices, &canvas, legend_bottom));
    }
    let scene = canvas.scene(chart, items, caption.as_deref());
    Ok(ChartOutput {
        scene,
        derived: derived.finish(),
        warnings: Vec::new(),
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// The colour map and its range: the spec's `domain`, or the volume's range (widened by the
/// diverging midpoint, as every colour bar is).
fn colouring(
    value: &ValueColor,
    options: &SliceOptions,
    volume: &crate::data::volume::Volume,
) -> Result<Colouring, MarkError> {
    let map = encode::continuous_map(&["value", "scheme"], Some(value.scheme.as_deref().unwrap_or(DEFAULT_SCHEME)))?;
    let (zmin, zmax) = match value.domain {
        Some([lo, hi]) if lo.is_finite() && hi.is_finite() && lo < hi => (lo, hi),
        Some(domain) => {
            return Err(MarkError::at(
                &["value", "domain"],
                format!("the domain {domain:?} is not two increasing numbers"),
                "give the colour bar's low and high ends, e.g. domain = [-160, 240]",
            ));
        }
        None => volume.range().0.ok_or_else(|| {
            MarkError::at(&["data"], "every voxel of the volume is missing (NaN)", "check the file and its data type")
        })?,
    };
    let (lo, hi) = if value.domain.is_some() && !map.is_diverging() {
        (zmin, zmax)
    } else {
        encode::color_domain(&map, zmin, zmax, value.midpoint)
    };
    let nan = match options.nan_color.as_deref() {
        None => NAN_COLOR,
        Some(s) => color::parse_color(s).ok_or_else(|| {
            MarkError::at(&["nan_color"], format!("`{s}` is not a colour"), "use a CSS colour name or #rrggbb")
        })?,
    };
    Ok(Colouring { map, lo, hi, nan })
}

/// The contour levels asked for, within the colour range (none when not asked).
fn contour_levels(contours: Option<&Levels>, lo: f64, hi: f64) -> Result<Vec<f64>, MarkError> {
    let levels = match contours {
        None => return Ok(Vec::new()),
        Some(Levels::Count(n)) => contour::nice_levels(lo, hi, (*n as usize).clamp(1, 100)),
        Some(Levels::Values(values)) => values.clone(),
    };
    contour::clean_levels(&levels).map_err(|e| MarkError::at(&["contours"], format!("{e}"), "give fewer levels"))
}

/// Where the panels lie: one scale (pixels per world unit) for all, so equal lengths look equal
/// in every slice, and each panel's plot at the top left of its cell.
struct Layout {
    scale: f64,
    columns: usize,
    origin: Point,
    cell: (f64, f64),
    step: (f64, f64),
    /// Whether every panel spans the same plane coordinates, so only the outer panels carry axes.
    shared: bool,
}

/// One panel's plot and its map from plane coordinates to the canvas.
struct PanelPlot {
    rect: Rect,
    scale: f64,
    bounds: (f64, f64, f64, f64),
}

impl PanelPlot {
    fn to_px(&self, (u, v): (f64, f64)) -> Point {
        Point::new(self.rect.x + (u - self.bounds.0) * self.scale, self.rect.y + (self.bounds.3 - v) * self.scale)
    }
}

impl Layout {
    fn new(canvas: &frame::PanelCanvas, slices: &[Slice], columns: Option<u32>) -> Result<Layout, MarkError> {
        let theme = &canvas.theme;
        let fs = theme.font_size;
        let m = theme.margin;
        let (left, bottom, header, gap) = (fs * 5.0, fs * 3.6, fs * 1.6, fs * 1.0);
        let legend_room = if canvas.legend_w > 0.0 { canvas.legend_w + fs * 1.5 } else { 0.0 };
        let width = canvas.width - 2.0 * m - legend_room;
        let height = canvas.room;
        let first = slices.first().map(|s| s.bounds()).unwrap_or_default();
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (a.abs() + b.abs()).max(1.0);
        let shared = slices.iter().all(|s| {
            let b = s.bounds();
            same(b.0, first.0) && same(b.1, first.1) && same(b.2, first.2) && same(b.3, first.3)
        });
        let spans: Vec<(f64, f64)> = slices
            .iter()
            .map(|s| {
                let b = s.bounds();
                (b.1 - b.0, b.3 - b.2)
            })
            .collect();
        let du = spans.iter().map(|s| s.0).fold(0.0, f64::max);
        let dv = spans.iter().map(|s| s.1).fold(0.0, f64::max);
        let n = slices.len().max(1);
        let fit = |c: usize| -> (f64, (f64, f64)) {
            let r = n.div_ceil(c);
            let (c_f, r_f) = (c as f64, r as f64);
            let (cell_w, cell_h) = if shared {
                ((width - left - gap * (c_f - 1.0)) / c_f, (height - bottom - header * r_f - gap * (r_f - 1.0)) / r_f)
            } else {
                ((width - (left + gap) * c_f + gap) / c_f, (height - (bottom + header + gap) * r_f + gap) / r_f)
            };
            ((cell_w / du).min(cell_h / dv), (cell_w, cell_h))
        };
        let columns = match columns {
            Some(c) => (c as usize).clamp(1, n),
            None => (1..=n).max_by(|&a, &b| fit(a).0.total_cmp(&fit(b).0)).unwrap_or(1),
        };
        let (scale, _) = fit(columns);
        let cell = (du * scale, dv * scale);
        if !(scale.is_finite() && cell.0.min(cell.1) >= 24.0) {
            return Err(MarkError::layout(LayoutError::TooSmall {
                plot_width: cell.0.max(0.0),
                plot_height: cell.1.max(0.0),
            }));
        }
        let step = if shared {
            (cell.0 + gap, cell.1 + header + gap)
        } else {
            (cell.0 + left + gap, cell.1 + header + bottom + gap)
        };
        let used_w = if shared { left + step.0 * columns as f64 - gap } else { step.0 * columns as f64 - gap };
        let origin = Point::new(m + (width - used_w).max(0.0) / 2.0 + left, canvas.top() + header);
        Ok(Layout { scale, columns, origin, cell, step, shared })
    }

    fn position(&self, k: usize) -> (usize, usize) {
        (k / self.columns, k % self.columns)
    }

    fn panel(&self, k: usize, slice: &Slice) -> PanelPlot {
        let (row, col) = self.position(k);
        let bounds = slice.bounds();
        let (w, h) = ((bounds.1 - bounds.0) * self.scale, (bounds.3 - bounds.2) * self.scale);
        let x = self.origin.x + col as f64 * self.step.0 + (self.cell.0 - w) / 2.0;
        let y = self.origin.y + row as f64 * self.step.1;
        PanelPlot { rect: Rect::new(x, y, w, h), scale: self.scale, bounds }
    }

    /// Whether panel `k` draws its bottom and its left axis.
    fn axes_of(&self, k: usize, count: usize) -> (bool, bool) {
        if !self.shared {
            return (true, true);
        }
        // The last panel of each column carries the bottom axis (the last row may be short).
        (k + self.columns >= count, self.position(k).1 == 0)
    }
}

/// The slice sampled at the pixel centres of its panel, and the range of the values it shows.
fn slice_image(
    sampler: &Sampler<'_>,
    how: Interpolation,
    slice: &Slice,
    panel: &PanelPlot,
    colouring: &Colouring,
) -> (Raster, Option<(f64, f64)>) {
    let width = (panel.rect.w.round().max(1.0) as usize).min(MAX_RASTER_SIDE);
    let height = (panel.rect.h.round().max(1.0) as usize).min(MAX_RASTER_SIDE);
    let (u0, u1, v0, v1) = panel.bounds;
    let mut rgba = Vec::with_capacity(width * height * 4);
    let mut range: Option<(f64, f64)> = None;
    for py in 0..height {
        let v = v1 - (v1 - v0) * (py as f64 + 0.5) / height as f64;
        for px in 0..width {
            let u = u0 + (u1 - u0) * (px as f64 + 0.5) / width as f64;
            let value = sampler.at(slice.plane.world(u, v), how);
            if let Some(x) = value.filter(|x| x.is_finite()) {
                range = Some(range.map_or((x, x), |(lo, hi)| (lo.min(x), hi.max(x))));
            }
            let c = colouring.of(value);
            rgba.extend_from_slice(&[c.r, c.g, c.b, c.a]);
        }
    }
    let raster =
        Raster { dest: panel.rect, width: width as u32, height: height as u32, rgba: Arc::new(rgba), smooth: false };
    (raster, range)
}

/// Contour lines of the slice (traced on a grid of four nodes per voxel, trilinear between
/// voxels), drawn white over a dark halo so they read on any colour map, with level labels.
fn contour_items(
    sampler: &Sampler<'_>,
    slice: &Slice,
    panel: &PanelPlot,
    levels: &[f64],
    theme: &Theme,
) -> Result<Vec<Item>, MarkError> {
    let step = sampler.volume().spacing().iter().copied().fold(f64::INFINITY, f64::min);
    let (u0, u1, v0, v1) = panel.bounds;
    // Four nodes per voxel, but no closer than two pixels: smooth lines at any zoom.
    let nodes = |span: f64, pixels: f64| {
        ((span / step * 4.0).min(pixels / 2.0).floor() as usize + 1).clamp(2, MAX_CONTOUR_NODES)
    };
    let (nu, nv) = (nodes(u1 - u0, panel.rect.w), nodes(v1 - v0, panel.rect.h));
    let along = |lo: f64, hi: f64, n: usize| -> Vec<f64> {
        (0..n).map(|k| lo + (hi - lo) * k as f64 / (n - 1) as f64).collect()
    };
    let grid = Grid::from_fn(along(u0, u1, nu), along(v0, v1, nv), |u, v| {
        sampler.at(slice.plane.world(u, v), Interpolation::Trilinear).unwrap_or(f64::NAN)
    })
    .map_err(|e| MarkError::at(&["contours"], format!("{e}"), "check the volume"))?;
    let lines = contour::contour_lines(&grid, levels, Saddle::Asymptotic)
        .map_err(|e| MarkError::at(&["contours"], format!("{e}"), "give fewer levels"))?;
    let to_px = |p: (f64, f64)| panel.to_px(p);
    let mut items = Vec::new();
    for same_level in lines.chunk_by(|a, b| a.level == b.level) {
        let level = same_level[0].level;
        let cmds: Vec<PathCmd> =
            same_level.iter().flat_map(|line| frame::polyline(&line.points, line.closed, &to_px)).collect();
        let halo = Stroke::solid(Color::BLACK.with_opacity(0.55), 2.4);
        items.push(
            Item::new(Role::DataMark, Shape::Path(cmds.clone()), Style { fill: None, stroke: Some(halo) })
                .labelled(format!("{}: value = {} (halo)", slice.label, format_value(level))),
        );
        items.push(Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(Color::WHITE, 1.0)).labelled(format!(
            "{}: value = {}",
            slice.label,
            format_value(level)
        )));
    }
    let pairs = lines.iter().map(|l| (l.level, l.points.as_slice()));
    items.extend(level_labels(pairs, levels, &to_px, theme.font_size * 0.85));
    Ok(items)
}

/// The panel's heading above its top left corner.
fn header(label: &str, rect: Rect, theme: &Theme) -> Item {
    Item::text(
        Role::Annotation,
        Text {
            at: Point::new(rect.x, rect.y - theme.font_size * 0.35),
            content: label.to_string(),
            size: theme.font_size,
            anchor: Anchor::Start,
            baseline: Baseline::Bottom,
            angle: 0.0,
            color: theme.text,
        },
    )
    .labelled("slice header")
}

/// The panel's axes: plane coordinates in world units, on the outer panels when every panel
/// spans the same coordinates, else on each.
fn panel_axes(
    layout: &Layout,
    k: usize,
    count: usize,
    slice: &Slice,
    panel: &PanelPlot,
    unit: &str,
    theme: &Theme,
) -> Vec<Item> {
    let (bottom, left) = layout.axes_of(k, count);
    let (u0, u1, v0, v1) = panel.bounds;
    let rect = panel.rect;
    let unit = (!unit.is_empty()).then_some(unit);
    let mut items = Vec::new();
    let target = |length: f64| ((length / (theme.font_size * 5.0)).floor() as usize).clamp(2, 8);
    if bottom && let Ok(x) = LinearScale::new((u0, u1), (rect.x, rect.right()), false, target(rect.w)) {
        items.extend(axis::draw(
            &Scale::Linear(x),
            Side::Bottom,
            rect,
            Some(&title_with_unit(slice.axis_names[0], unit)),
            theme,
        ));
    }
    if left && let Ok(y) = LinearScale::new((v0, v1), (rect.bottom(), rect.y), false, target(rect.h)) {
        items.extend(axis::draw(
            &Scale::Linear(y),
            Side::Left,
            rect,
            Some(&title_with_unit(slice.axis_names[1], unit)),
            theme,
        ));
    }
    items
}

/// For oblique planes, the caption names each plane's point and normal.
fn oblique_note(options: &SliceOptions, chart: &Chart) -> Option<String> {
    let planes = options.planes.as_ref()?;
    let fmt = |p: [f64; 3]| format!("({}, {}, {})", format_value(p[0]), format_value(p[1]), format_value(p[2]));
    let notes: Vec<String> = planes
        .iter()
        .enumerate()
        .map(|(k, p)| format!("plane {} through {} normal {}", k + 1, fmt(p.point), fmt(p.normal)))
        .collect();
    Some(match &chart.caption {
        Some(c) => format!("{c} — {}", notes.join("; ")),
        None => format!("{}; u and v measured from the point", notes.join("; ")),
    })
}

/// The derived table: one row per slice with its plane and the range of values it shows.
#[derive(Default)]
struct DerivedRows {
    panel: Vec<f64>,
    label: Vec<String>,
    point: [Vec<f64>; 3],
    normal: [Vec<f64>; 3],
    min: Vec<f64>,
    max: Vec<f64>,
}

impl DerivedRows {
    fn push(&mut self, k: usize, slice: &Slice, range: Option<(f64, f64)>) {
        self.panel.push(k as f64 + 1.0);
        self.label.push(slice.label.clone());
        for a in 0..3 {
            self.point[a].push(slice.plane.origin()[a]);
            self.normal[a].push(slice.plane.normal()[a]);
        }
        self.min.push(range.map_or(f64::NAN, |r| r.0));
        self.max.push(range.map_or(f64::NAN, |r| r.1));
    }

    fn finish(self) -> Derived {
        let mut derived = Derived::default();
        derived.push("panel", DerivedColumn::Number(self.panel));
        derived.push("label", DerivedColumn::Text(self.label));
        let [px, py, pz] = self.point;
        let [nx, ny, nz] = self.normal;
        for (name, column) in
            [("point_x", px), ("point_y", py), ("point_z", pz), ("normal_x", nx), ("normal_y", ny), ("normal_z", nz)]
        {
            derived.push(name, DerivedColumn::Number(column));
        }
        derived.push("min", DerivedColumn::Number(self.min));
        derived.push("max", DerivedColumn::Number(self.max));
        derived
    }
}

/// `kind = "slice"`.
pub static KIND: KindInfo = KindInfo::new("slice", &[]).sized([720.0, 520.0]).drawing_volumes();

impl Technique for SliceOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(cx, self)
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        vec![ColourSpec { key: "value", options: self.value.clone().unwrap_or_default().options() }]
    }
}
