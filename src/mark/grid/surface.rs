//! `surface`: a gridded field drawn as a shaded 3D heightfield — the shared orthographic camera,
//! Lambert shading, the cells as one triangle [`Mesh`] whose hidden parts the renderers remove (a
//! z-buffer in rasters) — with projected axes and a colour bar.

use crate::data::Table;
use crate::enrich::camera::{Light, Shade, View};
use crate::enrich::surface::{self, SurfaceProjection};
use crate::guide::axis::title_with_unit;
use crate::guide::legend::Legend;
use crate::mark::derived::Derived;
use crate::mark::gridded::{self, GridInput};
use crate::mark::registry::{ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, axis3d, encode, frame};
use crate::scene::{Color, Item, Mesh, PathCmd, Point, Rect, Role, Shape, Style};
use crate::spec::{Channel, Chart, ColorChannel, defaults};
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
    let project = |p: [f64; 3]| to_px(projection.project_point(p[0], p[1], p[2]));
    let [tx, ty, tz] = &titles;
    items.extend(axis3d::draw_all(&projection.axes, [tx, ty, tz], ranges, &project, &theme));
    let scene = canvas.scene(chart, items, None);

    let derived = Derived::of_rows(rows, &[&x_opts.field, &y_opts.field, &z_opts.field]);
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
