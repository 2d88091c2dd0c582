//! `surface`: a gridded field drawn as a shaded 3D heightfield — the shared orthographic camera,
//! Lambert shading, the cells as one triangle [`Mesh`] whose hidden parts the renderers remove (a
//! z-buffer in rasters) — with projected axes and a colour bar.

use crate::data::Table;
use crate::enrich::camera::{Light, Shade, View};
use crate::enrich::surface::{self, AxisLine, SurfaceProjection};
use crate::guide::Theme;
use crate::guide::axis::title_with_unit;
use crate::guide::format::format_ticks;
use crate::guide::legend::Legend;
use crate::guide::ticks::extended;
use crate::mark::derived::Derived;
use crate::mark::gridded::{self, GridInput};
use crate::mark::registry::{ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Anchor, Baseline, Color, Item, Mesh, PathCmd, Point, Rect, Role, Shape, Style, Text};
use crate::spec::{Channel, Chart, ColorChannel, defaults};
use crate::text::measure;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "surface"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SurfaceOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node).
    pub x: Channel,
    /// Grid y coordinate: a numeric column of a long-form table (one row per grid node).
    pub y: Channel,
    /// The height: a column name, or `{ field, title, unit, scheme, midpoint }` (surface colours).
    pub z: ColorChannel,
    /// Viewing direction in degrees, counter-clockwise from +x (default −60).
    #[serde(default)]
    pub azimuth: Option<f64>,
    /// Height of the eye above the xy plane in degrees, 1 to 90 (default 30).
    #[serde(default)]
    #[schemars(range(min = 1.0, max = 90.0))]
    pub elevation: Option<f64>,
    /// Drawn z length per x/y unit (default: the z range drawn at half the larger horizontal extent).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    pub z_scale: Option<f64>,
}

/// Draw a surface chart.
pub fn draw(chart: &Chart, options: &SurfaceOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let z_opts = options.z.options();
    let GridInput { grid, rows, warnings, zmin, zmax, .. } =
        gridded::load_grid(chart, &x_opts, &y_opts, &z_opts, table)?;
    let map = encode::continuous_map(&["z", "scheme"], z_opts.scheme.as_deref())?;
    let (lo, hi) = encode::color_domain(&map, zmin, zmax, z_opts.midpoint);
    let view = View::new(options.azimuth.unwrap_or(-60.0), options.elevation.unwrap_or(30.0));
    let projection = surface::project(&grid, view, Light::default(), options.z_scale)
        .map_err(|e| MarkError::at(&["z"], format!("{e}"), "check the grid and the view"))?;

    let z_title = title_with_unit(z_opts.title.as_deref().unwrap_or(&z_opts.field), z_opts.unit.as_deref());
    let canvas = frame::PanelCanvas::new(
        chart,
        encode::shown_legends(Legend::ColorBar { title: z_title.clone(), map: map.clone(), domain: (lo, hi) }, &z_opts),
    );
    let (width, theme, title_h, _caption_h, room, legend_w) =
        (canvas.width, canvas.theme.clone(), canvas.title_h, canvas.caption_h, canvas.room, canvas.legend_w);
    let m = theme.margin;
    // Room around the box for tick labels and axis titles.
    let pad = theme.font_size * 5.0;
    let area = Rect::new(
        m + pad,
        m + title_h + pad * 0.5,
        width - 2.0 * m - legend_w - theme.font_size * 1.5 - 2.0 * pad,
        room - 1.5 * pad,
    );
    if area.w < 40.0 || area.h < 40.0 {
        return Err(MarkError::layout(crate::guide::layout::LayoutError::TooSmall {
            plot_width: area.w.max(0.0),
            plot_height: area.h.max(0.0),
        }));
    }
    // The projected box bounds every quad and axis line: fit it to the area, one scale for
    // both directions, centred (screen v runs up, canvas y down).
    let corners = projection.box_edges.iter().flat_map(|e| [e.start, e.end]).map(|(u, v)| [u, -v]);
    let fit = frame::Fit::new(corners, [area.x, area.y, area.w, area.h], 0.0, true);
    let to_px = |(u, v): (f64, f64)| fit.at([u, -v]);

    let mut items = vec![canvas.background()];
    let edge = |e: &surface::BoxEdge, color: Color| {
        Item::new(
            Role::Axis,
            Shape::Path(vec![PathCmd::MoveTo(to_px(e.start)), PathCmd::LineTo(to_px(e.end))]),
            Style::stroke(color, 1.0),
        )
    };
    for e in projection.box_edges.iter().filter(|e| e.hidden) {
        items.push(edge(e, theme.grid));
    }
    let mesh = cell_mesh(&projection, |value| map.at((value - lo) / (hi - lo)), &to_px);
    items.push(
        Item::new(Role::DataMark, Shape::Mesh(mesh), Style::default())
            .with_rows(rows.clone())
            .labelled(z_opts.field.clone()),
    );
    for e in projection.box_edges.iter().filter(|e| !e.hidden) {
        items.push(edge(e, theme.axis));
    }
    let titles = [
        title_with_unit(x_opts.title.as_deref().unwrap_or(&x_opts.field), x_opts.unit.as_deref()),
        title_with_unit(y_opts.title.as_deref().unwrap_or(&y_opts.field), y_opts.unit.as_deref()),
        z_title,
    ];
    let ranges = [projection.x_range, projection.y_range, projection.z_range];
    for (((line, title), range), name) in projection.axes.iter().zip(&titles).zip(ranges).zip(AXIS_NAMES) {
        items.extend(axis_items(&projection, line, (name, title), range, &to_px, &theme));
    }
    let scene = canvas.scene(chart, items, None);

    let derived = Derived::of_rows(rows, &[&x_opts.field, &y_opts.field, &z_opts.field]);
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, geometry: Default::default() })
}

/// The projected cells as one mesh: four vertices per cell in its flat shaded colour (its base
/// colour from `colour` of its mean value, times its Lambert shade), two triangles, in painter's
/// order, each vertex with its z-buffer depth.
fn cell_mesh(
    projection: &SurfaceProjection,
    colour: impl Fn(f64) -> Color,
    to_px: &impl Fn((f64, f64)) -> Point,
) -> Mesh {
    let n = projection.quads.len();
    let (mut positions, mut colors, mut indices) =
        (Vec::with_capacity(4 * n), Vec::with_capacity(4 * n), Vec::with_capacity(2 * n));
    for q in &projection.quads {
        let base = colour(q.value);
        let [r, g, b] = Shade { diffuse: q.shade, specular: 0.0 }.apply([base.r, base.g, base.b]);
        let first = positions.len() as u32;
        for (corner, depth) in q.corners.iter().zip(q.depths) {
            let p = to_px(*corner);
            positions.push([p.x as f32, p.y as f32, depth as f32]);
            colors.push(Color::rgb(r, g, b));
        }
        indices.push([first, first + 1, first + 2]);
        indices.push([first, first + 2, first + 3]);
    }
    Mesh { positions: positions.into(), indices: indices.into(), colors: colors.into(), normals: None }
}

/// The scene labels of the projected axes' items, in the order x, y, z.
const AXIS_NAMES: [&str; 3] = ["x axis", "y axis", "z axis"];

/// Nice tick values within `range` (at least two when a finer step gives them: a short axis
/// over a narrow range can hold a single nice value, which shows no scale) and their step.
fn ticks_inside(range: (f64, f64), target: usize) -> (Vec<f64>, f64) {
    let within = |target: usize| {
        let ticks = extended(range.0, range.1, target, false);
        let inside: Vec<f64> =
            ticks.values.iter().copied().filter(|v| *v >= range.0 - 1e-12 && *v <= range.1 + 1e-12).collect();
        (inside, ticks.step)
    };
    let first = within(target);
    if first.0.len() >= 2 || range.1 <= range.0 {
        return first;
    }
    (target + 1..=MAX_TICKS).map(within).find(|(inside, _)| inside.len() >= 2).unwrap_or(first)
}

/// The most ticks [`ticks_inside`] asks for on one projected axis.
const MAX_TICKS: usize = 10;

/// Tick marks, tick labels and the title of one projected axis; the ticks and their labels
/// are labelled with the axis's `name`.
fn axis_items(
    projection: &SurfaceProjection,
    line: &AxisLine,
    (name, title): (&str, &str),
    range: (f64, f64),
    to_px: &impl Fn((f64, f64)) -> Point,
    theme: &Theme,
) -> Vec<Item> {
    let mut items = Vec::new();
    let (start, end) = (to_px(line.start), to_px(line.end));
    let length = (end.x - start.x).hypot(end.y - start.y);
    let target = ((length / (theme.font_size * 6.0)).round() as usize).clamp(2, 6);
    let (inside, step) = ticks_inside(range, target);
    let labels = format_ticks(&inside, step);
    // `outward` is in screen units with y up; canvas y runs down.
    let (nx, ny) = (line.outward.0, -line.outward.1);
    let anchor = if nx > 0.3 {
        Anchor::Start
    } else if nx < -0.3 {
        Anchor::End
    } else {
        Anchor::Middle
    };
    let baseline = if ny > 0.3 {
        Baseline::Top
    } else if ny < -0.3 {
        Baseline::Bottom
    } else {
        Baseline::Middle
    };
    let mut cmds = Vec::new();
    let mut widest: f64 = 0.0;
    for (v, label) in inside.iter().zip(labels) {
        let [x, y, z] = line.at(*v);
        let p = to_px(projection.project_point(x, y, z));
        let tip = Point::new(p.x + nx * theme.tick_length, p.y + ny * theme.tick_length);
        cmds.push(PathCmd::MoveTo(p));
        cmds.push(PathCmd::LineTo(tip));
        widest = widest.max(measure(&label, theme.font_size).width);
        items.push(
            Item::text(
                Role::TickLabel,
                Text {
                    at: Point::new(tip.x + nx * 3.0, tip.y + ny * 3.0),
                    content: label,
                    size: theme.font_size,
                    anchor,
                    baseline,
                    angle: 0.0,
                    color: theme.muted_text,
                },
            )
            .labelled(name),
        );
    }
    items.push(Item::new(Role::Axis, Shape::Path(cmds), Style::stroke(theme.axis, 1.0)).labelled(name));
    let mid = Point::new((start.x + end.x) / 2.0, (start.y + end.y) / 2.0);
    let away = theme.tick_length + 6.0 + if nx.abs() > 0.3 { widest } else { theme.font_size * 1.2 };
    items.push(Item::text(
        Role::AxisTitle,
        Text {
            at: Point::new(mid.x + nx * away, mid.y + ny * (away + theme.font_size * 0.3)),
            content: title.to_string(),
            size: theme.label_size,
            anchor,
            baseline,
            angle: 0.0,
            color: theme.text,
        },
    ));
    items
}

/// `kind = "surface"`.
pub static KIND: KindInfo = KindInfo::new("surface", &["x", "y", "z"]).conventions(defaults::GRID);

impl Technique for SurfaceOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        ColourSpec::z(&self.z)
    }
}
