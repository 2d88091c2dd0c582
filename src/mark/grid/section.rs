//! `section`: cross-sections of a gridded field — z along x at chosen y values (or along y at
//! chosen x values) — overlaid in one plot or as stacked panels sharing both scales (or, with
//! `shared_scale = false`, each with its own value scale).

use crate::data::Table;
use crate::guide::Theme;
use crate::guide::axis::title_with_unit;
use crate::guide::format::format_value;
use crate::guide::layout::{self, Domain, FrameSpec, PositionAxis};
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::gridded::{self, GridInput};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::{ChartOutput, FRAME_SIZE, MarkError, encode, frame};
use crate::scene::{Color, Item, PathCmd, Point, Rect, Role, Scene, Shape, Style};
use crate::spec::{Channel, Chart, ColorChannel, ScaleKind, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "section"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SectionOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node).
    pub x: Channel,
    /// Grid y coordinate: a numeric column of a long-form table (one row per grid node).
    pub y: Channel,
    /// The field's value: a column name, or `{ field, title, unit }`.
    pub z: ColorChannel,
    /// Sections along x at these y values (give this or `at_x`).
    #[serde(default)]
    pub at_y: Option<Vec<f64>>,
    /// Sections along y at these x values (give this or `at_y`).
    #[serde(default)]
    pub at_x: Option<Vec<f64>>,
    /// `overlay` (default: one plot, a line per section) or `multiples` (one panel per
    /// section, stacked, sharing both scales).
    #[serde(default)]
    pub layout: Option<SectionLayout>,
    /// With `layout = "multiples"`: give every panel the same value scale (default true), or
    /// `false` for a scale per panel fitted to its own section (for sections of very different
    /// magnitude; the panels can then no longer be compared by height, and lint rule CM001 says so).
    #[serde(default)]
    pub shared_scale: Option<bool>,
    /// Line width in pixels, at most 100 (default 2).
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 100))]
    pub stroke_width: Option<f64>,
    /// Categorical colour scheme for the sections (default `okabe-ito`).
    #[serde(default)]
    pub scheme: Option<String>,
}

/// How sections are arranged.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SectionLayout {
    /// All sections in one plot.
    Overlay,
    /// One panel per section, sharing scales.
    Multiples,
}

/// One cross-section: where it is cut and its (position, z) samples at the grid's nodes.
struct Cut {
    at: f64,
    points: Vec<(f64, f64)>,
}

/// Draw a section chart.
pub fn draw(chart: &Chart, options: &SectionOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let z_opts = options.z.options();
    let GridInput { grid, mut warnings, .. } = gridded::load_grid(chart, &x_opts, &y_opts, &z_opts, table)?;
    let (along_x, at, key) = match (&options.at_y, &options.at_x) {
        (Some(v), None) => (true, v.clone(), "at_y"),
        (None, Some(v)) => (false, v.clone(), "at_x"),
        _ => {
            return Err(MarkError::at(
                &[],
                format!("a section needs exactly one of `at_y` or `at_x`"),
                "at_y = [0.5, 1.0] draws z along x at those y values; at_x does the same along y",
            ));
        }
    };
    if at.is_empty() {
        return Err(MarkError::at(&[key], format!("`{key}` is empty"), "give at least one value"));
    }
    let (positions, across) = if along_x { (grid.xs(), grid.ys()) } else { (grid.ys(), grid.xs()) };
    let (lo_c, hi_c) = (across.first().copied().unwrap_or(0.0), across.last().copied().unwrap_or(0.0));
    let mut cuts = Vec::new();
    for (k, &v) in at.iter().enumerate() {
        if !(v.is_finite() && v >= lo_c && v <= hi_c) {
            let mut e = MarkError::at(
                &[key],
                format!(
                    "{} = {} lies outside the grid's {} range [{}, {}]",
                    key,
                    format_value(v),
                    if along_x { "y" } else { "x" },
                    format_value(lo_c),
                    format_value(hi_c)
                ),
                "cut the field inside the grid",
            );
            e.path.push(crate::spec::PathSeg::Index(k));
            return Err(e);
        }
        let points =
            positions.iter().map(|&p| (p, if along_x { grid.bilinear(p, v) } else { grid.bilinear(v, p) })).collect();
        cuts.push(Cut { at: v, points });
    }
    let (pos_opts, cut_name) = if along_x { (&x_opts, &y_opts.field) } else { (&y_opts, &x_opts.field) };
    let (mut zlo, mut zhi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (_, z) in cuts.iter().flat_map(|c| &c.points) {
        if z.is_finite() {
            zlo = zlo.min(*z);
            zhi = zhi.max(*z);
        }
    }
    if zlo > zhi {
        return Err(MarkError::at(
            &[key],
            format!("every section crosses only missing values"),
            "cut the field where it has values",
        ));
    }
    let position_axis = PositionAxis {
        title: title_with_unit(pos_opts.title.as_deref().unwrap_or(&pos_opts.field), pos_opts.unit.as_deref()),
        kind: ScaleKind::Linear,
        domain: Domain::Continuous(positions.first().copied().unwrap_or(0.0), positions.last().copied().unwrap_or(1.0)),
        nice: false,
        ticks: pos_opts.ticks,
        grid: true,
        inset: 0.0,
    };
    let value_axis = PositionAxis {
        title: title_with_unit(z_opts.title.as_deref().unwrap_or(&z_opts.field), z_opts.unit.as_deref()),
        kind: ScaleKind::Linear,
        domain: Domain::Continuous(zlo, zhi),
        nice: true,
        ticks: None,
        grid: true,
        inset: 1.0,
    };
    let palette = encode::palette(&["scheme"], options.scheme.as_deref())?;
    let colors: Vec<Color> =
        (0..cuts.len()).map(|i| palette.get(i % palette.len().max(1)).copied().unwrap_or(Color::BLACK)).collect();
    let label = |c: &Cut| format!("{cut_name} = {}", format_value(c.at));
    let stroke_width = options.stroke_width.unwrap_or(2.0);
    let scene = match options.layout.unwrap_or(SectionLayout::Overlay) {
        SectionLayout::Overlay => {
            let legend = Legend::Categorical {
                title: "Section".into(),
                entries: cuts.iter().zip(&colors).map(|(c, col)| (label(c), *col)).collect(),
                symbol: Symbol::Line,
            };
            let (frame, theme) = frame::cartesian(chart, position_axis, value_axis, vec![legend])?;
            let marks = cuts
                .iter()
                .zip(&colors)
                .map(|(c, col)| section_path(c, &frame.x, &frame.y, *col, stroke_width).labelled(label(c)))
                .collect();
            frame::scene(chart, frame, &theme, marks, &mut warnings)
        }
        SectionLayout::Multiples if !chart.annotate.is_empty() => {
            return Err(MarkError::at(
                &["annotate"],
                "`annotate` draws on one frame, but `layout = \"multiples\"` draws a frame per section",
                "draw the sections overlaid (`layout = \"overlay\"`, the default) to annotate them",
            ));
        }
        SectionLayout::Multiples => {
            let shared = options.shared_scale.unwrap_or(true);
            multiples(chart, &cuts, &colors, position_axis, value_axis, shared, stroke_width, &label)?
        }
    };

    let mut derived = Derived::default();
    derived.push(cut_name, DerivedColumn::Number(cuts.iter().flat_map(|c| c.points.iter().map(|_| c.at)).collect()));
    derived
        .push(&pos_opts.field, DerivedColumn::Number(cuts.iter().flat_map(|c| c.points.iter().map(|p| p.0)).collect()));
    derived
        .push(&z_opts.field, DerivedColumn::Number(cuts.iter().flat_map(|c| c.points.iter().map(|p| p.1)).collect()));
    Ok(ChartOutput {
        scene,
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// A section's polyline, broken where the field is missing.
fn section_path(
    cut: &Cut,
    x: &crate::guide::scale::Scale,
    y: &crate::guide::scale::Scale,
    color: Color,
    width: f64,
) -> Item {
    let mut cmds = Vec::new();
    let mut pen_down = false;
    for &(p, z) in &cut.points {
        if !z.is_finite() {
            pen_down = false;
            continue;
        }
        let pt = Point::new(x.map(p), y.map(z));
        cmds.push(if pen_down { PathCmd::LineTo(pt) } else { PathCmd::MoveTo(pt) });
        pen_down = true;
    }
    Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(color, width))
}

/// Stacked panels, one per section, each a full frame under one title: with the same scales, or
/// unless `shared`, each with a value scale fitted to its own section.
#[allow(clippy::too_many_arguments)]
fn multiples(
    chart: &Chart,
    cuts: &[Cut],
    colors: &[Color],
    position_axis: PositionAxis,
    value_axis: PositionAxis,
    shared: bool,
    stroke_width: f64,
    label: &dyn Fn(&Cut) -> String,
) -> Result<Scene, MarkError> {
    let [width, height] = chart.size.unwrap_or(FRAME_SIZE);
    let theme = Theme::with_font_size(chart.font_size.unwrap_or(12.0));
    let m = theme.margin;
    let title_h = if chart.title.is_some() { theme.title_size * 1.6 } else { 0.0 };
    let caption_h = if chart.caption.is_some() { theme.caption_size * 1.6 } else { 0.0 };
    let panel_h = (height - title_h - caption_h) / cuts.len() as f64;
    let mut panel_theme = theme.clone();
    panel_theme.title_size = theme.label_size;
    panel_theme.margin = m / 2.0;
    let mut items = vec![Item::new(
        Role::Background,
        Shape::Rect(Rect::new(0.0, 0.0, width, height)),
        Style::fill(theme.background),
    )];
    for (k, (cut, color)) in cuts.iter().zip(colors).enumerate() {
        let mut value_axis = value_axis.clone();
        if !shared && let Some(extent) = encode::finite_extent(cut.points.iter().map(|p| p.1)) {
            value_axis.domain = Domain::Continuous(extent.0, extent.1);
        }
        let spec = FrameSpec {
            width,
            height: panel_h,
            title: Some(label(cut)),
            caption: None,
            x: position_axis.clone(),
            y: value_axis,
            legends: Vec::new(),
            theme: panel_theme.clone(),
            equal_aspect: false,
            fixed: None,
        };
        let frame = layout::cartesian(&spec).map_err(|e| MarkError::layout(e))?;
        let dy = title_h + panel_h * k as f64;
        let mark = section_path(cut, &frame.x, &frame.y, *color, stroke_width).labelled(label(cut));
        let mut panel = frame.under;
        panel.retain(|i| i.role != Role::Background);
        panel.push(Item::group(Role::DataMark, vec![mark], Some(frame.plot)));
        panel.extend(frame.over.into_iter().map(|mut i| {
            // Panel titles are section labels, not chart titles.
            if i.role == Role::Title {
                i.role = Role::Annotation;
            }
            i
        }));
        items.extend(panel.into_iter().map(|i| i.translated(0.0, dy)));
    }
    items.extend(frame::title_and_caption(chart, &theme, m / 2.0, None));
    Ok(Scene { width, height, background: theme.background, title: chart.title.clone(), items })
}

/// `kind = "section"`.
pub static KIND: KindInfo =
    KindInfo::new("section", &["x", "y", "z"]).conventions(defaults::GRID).drawing_annotations();

impl Technique for SectionOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }
}
