//! `isosurface`: surfaces of constant value through a volume — marching cubes with the topology
//! of the trilinear interpolant (or marching tetrahedra) — shaded and drawn through the shared
//! 3-D camera, several of them in depth order with transparency, in the volume's box with its
//! axes; `--format glb`, `ply` or `obj` writes the surfaces themselves.

use crate::enrich::camera::{Camera, Light, Projection, Specular, View, equal_extent};
use crate::enrich::volume::isosurface::{self, IsoMesh, Method, NormalRule};
use crate::enrich::volume::{Interpolation, Sampler};
use crate::guide::axis::title_with_unit;
use crate::guide::color;
use crate::guide::format::format_value;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, frame};
use crate::scene::{Color, Item, Mesh, Point, Rect, Role, Shape, Style, WorldMesh};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::box_frame;

/// Options of `kind = "isosurface"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct IsosurfaceOptions {
    /// The value of the surface, or several values (at most 8), one surface each.
    pub levels: IsoValues,
    /// `cubes` (default: marching cubes with the topology of the trilinear interpolant) or
    /// `tetrahedra` (six per cube, for comparison).
    #[serde(default)]
    pub method: Option<IsoMethod>,
    /// Vertex normals: `gradient` (default: of the trilinear field) or `faces` (averaged
    /// triangle normals).
    #[serde(default)]
    pub normals: Option<IsoNormals>,
    /// One colour per surface (CSS names or `#rrggbb`; default: the `okabe-ito` palette).
    #[serde(default)]
    pub colors: Option<Vec<String>>,
    /// Opacity of every surface, or one per surface, each 0.05 to 1 (default 1; with several
    /// surfaces, 1 for the innermost (the smallest box around it) and 0.35 for the others).
    #[serde(default)]
    pub opacity: Option<Opacities>,
    /// Legend title and unit of the values: `{ title, unit }` (default `value`).
    #[serde(default)]
    pub value: Option<IsoValueLabel>,
    /// Viewing direction in degrees counter-clockwise from +x (default −60).
    #[serde(default)]
    pub azimuth: Option<f64>,
    /// Degrees above the x-y plane (default 25).
    #[serde(default)]
    pub elevation: Option<f64>,
    /// Magnification about the centre (default 1; 0.01 to 100).
    #[serde(default)]
    pub zoom: Option<f64>,
    /// `orthographic` (default) or `perspective`.
    #[serde(default)]
    pub projection: Option<ProjectionKind>,
    /// Perspective field of view in degrees (default 30).
    #[serde(default)]
    pub fov: Option<f64>,
    /// Add Blinn–Phong highlights (default false).
    #[serde(default)]
    pub specular: Option<bool>,
}

/// One iso value or several.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum IsoValues {
    /// One surface.
    One(f64),
    /// Several surfaces.
    Many(Vec<f64>),
}

/// One opacity for all surfaces or one each.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum Opacities {
    /// The same for every surface.
    All(f64),
    /// One per surface.
    Each(Vec<f64>),
}

/// The title of the values in the legend.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct IsoValueLabel {
    /// Legend title (default `value`).
    #[serde(default)]
    pub title: Option<String>,
    /// Unit of the values.
    #[serde(default)]
    pub unit: Option<String>,
}

/// How surfaces are extracted.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum IsoMethod {
    /// Marching cubes, ambiguities resolved as the trilinear interpolant has them.
    Cubes,
    /// Marching tetrahedra, six per cube.
    Tetrahedra,
}

/// How vertex normals are found.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum IsoNormals {
    /// The gradient of the trilinear field.
    Gradient,
    /// The average of the adjacent triangles' normals.
    Faces,
}

/// The camera's projection.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ProjectionKind {
    /// Parallel projection.
    Orthographic,
    /// Central projection.
    Perspective,
}

/// Most surfaces one chart draws.
pub const MAX_SURFACES: usize = 8;

/// One extracted surface with how it is drawn.
struct Surface {
    iso: f64,
    mesh: IsoMesh,
    color: Color,
    opacity: f64,
}

/// Draw an isosurface chart.
pub fn draw(cx: &ChartContext<'_>, options: &IsosurfaceOptions) -> Result<ChartOutput, MarkError> {
    let chart = &cx.chart;
    let volume = cx.volume()?;
    let values = iso_values(options)?;
    let colors = surface_colors(options, values.len())?;
    let opacities = surface_opacities(options, values.len())?;
    let method = match options.method.unwrap_or(IsoMethod::Cubes) {
        IsoMethod::Cubes => Method::MarchingCubes,
        IsoMethod::Tetrahedra => Method::Tetrahedra,
    };
    let normals = match options.normals.unwrap_or(IsoNormals::Gradient) {
        IsoNormals::Gradient => NormalRule::Gradient,
        IsoNormals::Faces => NormalRule::Faces,
    };
    let mut warnings = Vec::new();
    let range = volume.range().0;
    let mut surfaces = Vec::new();
    for (k, &iso) in values.iter().enumerate() {
        if let Some((lo, hi)) = range.filter(|(lo, hi)| iso < *lo || iso > *hi) {
            warnings.push(Warning::Note(format!(
                "level {} is outside the volume's values ({} to {}): no surface",
                format_value(iso),
                format_value(lo),
                format_value(hi)
            )));
        }
        let mesh = isosurface::extract(&volume, iso, method, normals, None)
            .map_err(|e| MarkError::at(&["levels"], format!("{e}"), "choose another value or crop the volume"))?;
        surfaces.push(Surface { iso, mesh, color: colors[k], opacity: opacities[k] });
    }
    if options.opacity.is_none() {
        see_through_outer(&mut surfaces);
    }
    let view = view_of(options)?;
    let sampler =
        Sampler::new(&volume).map_err(|e| MarkError::at(&["data"], e, "check the file's orientation header"))?;
    let corners = sampler.corners(Interpolation::Trilinear);
    let ranges = [0, 1, 2]
        .map(|a| corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| (lo.min(c[a]), hi.max(c[a]))));
    let camera = Camera::new(ranges, equal_extent(ranges), view)
        .map_err(|e| MarkError::at(&["azimuth"], format!("{e}"), "check the view settings"))?;
    let light = light_for(&view, options.specular.unwrap_or(false));

    let label = options.value.clone().unwrap_or_default();
    let title = title_with_unit(label.title.as_deref().unwrap_or("value"), label.unit.as_deref());
    let entries: Vec<(String, Color)> = surfaces.iter().map(|s| (format_value(s.iso), s.color)).collect();
    let legend = Legend::Categorical { title, entries, symbol: Symbol::Square };
    let canvas = frame::PanelCanvas::new(chart, vec![legend]);
    let theme = canvas.theme.clone();
    let m = theme.margin;
    let room_w = canvas.width - 2.0 * m - canvas.legend_room();
    let side = room_w.min(canvas.room).max(1.0);
    let square = Rect::new(m + (room_w - side) / 2.0, canvas.top() + (canvas.room - side) / 2.0, side, side);
    let to_px = |p: [f64; 3]| {
        let (sx, sy) = camera.project(p);
        Point::new(square.x + sx * square.w, square.y + (1.0 - sy) * square.h)
    };

    let mut items = vec![canvas.background()];
    let (back, front) = box_frame::edges(&camera, ranges, &to_px, &theme);
    items.push(back);
    // Opaque surfaces first, then translucent ones from the farthest to the nearest.
    let mut order: Vec<usize> = (0..surfaces.len()).collect();
    let centre_distance = |s: &Surface| {
        let n = s.mesh.positions.len().max(1) as f64;
        let c = s.mesh.positions.iter().fold([0.0; 3], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n, a[2] + p[2] / n]);
        camera.distance(camera.model(c))
    };
    order.sort_by(|&a, &b| {
        let (sa, sb) = (&surfaces[a], &surfaces[b]);
        (sa.opacity < 1.0).cmp(&(sb.opacity < 1.0)).then(centre_distance(sb).total_cmp(&centre_distance(sa)))
    });
    for &k in &order {
        let s = &surfaces[k];
        if s.mesh.triangles.is_empty() {
            continue;
        }
        items.push(
            Item::new(Role::DataMark, Shape::Mesh(screen_mesh(s, &camera, &light, &to_px)), Style::default())
                .labelled(format!("value = {}", format_value(s.iso))),
        );
    }
    items.push(front);
    items.extend(box_frame::axis_labels(ranges, &to_px, Role::AxisTitle, theme.text, theme.font_size, true));
    let triangles: usize = surfaces.iter().map(|s| s.mesh.triangles.len()).sum();
    let how = match method {
        Method::MarchingCubes => "marching cubes, trilinear topology",
        Method::Tetrahedra => "marching tetrahedra",
    };
    let note = format!("{} triangles ({how})", group_thousands(triangles));
    let caption = match &chart.caption {
        Some(c) => format!("{c} — {note}"),
        None => note,
    };
    let scene = canvas.scene(chart, items, Some(&caption));
    let meshes = surfaces.iter().filter(|s| !s.mesh.triangles.is_empty()).map(world_mesh).collect();
    Ok(ChartOutput {
        scene,
        derived: derived(&surfaces),
        warnings,
        meshes,
        geojson: None,
        geometry: Default::default(),
    })
}

/// The iso values, 1 to [`MAX_SURFACES`], each finite.
fn iso_values(options: &IsosurfaceOptions) -> Result<Vec<f64>, MarkError> {
    let values = match &options.levels {
        IsoValues::One(v) => vec![*v],
        IsoValues::Many(v) => v.clone(),
    };
    if values.is_empty() || values.len() > MAX_SURFACES {
        return Err(MarkError::at(
            &["levels"],
            format!("{} iso values given; a chart draws 1 to {MAX_SURFACES} surfaces", values.len()),
            "give one value, e.g. levels = [300], or a short list",
        ));
    }
    if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
        return Err(MarkError::at(&["levels"], format!("iso value {bad} is not a number"), "give finite values"));
    }
    Ok(values)
}

fn surface_colors(options: &IsosurfaceOptions, n: usize) -> Result<Vec<Color>, MarkError> {
    let palette = color::categorical(color::DEFAULT_CATEGORICAL).unwrap_or_default();
    match &options.colors {
        None => Ok((0..n).map(|k| palette.get(k % palette.len().max(1)).copied().unwrap_or(Color::BLACK)).collect()),
        Some(given) if given.len() < n => Err(MarkError::at(
            &["colors"],
            format!("{} colours for {n} surfaces", given.len()),
            "give one colour per iso value",
        )),
        Some(given) => given
            .iter()
            .take(n)
            .map(|s| {
                color::parse_color(s).ok_or_else(|| {
                    MarkError::at(&["colors"], format!("`{s}` is not a colour"), "use a CSS colour name or #rrggbb")
                })
            })
            .collect(),
    }
}

fn surface_opacities(options: &IsosurfaceOptions, n: usize) -> Result<Vec<f64>, MarkError> {
    let values = match &options.opacity {
        None => vec![1.0; n],
        Some(Opacities::All(a)) => vec![*a; n],
        Some(Opacities::Each(each)) if each.len() == n => each.clone(),
        Some(Opacities::Each(each)) => {
            return Err(MarkError::at(
                &["opacity"],
                format!("{} opacities for {n} surfaces", each.len()),
                "give one opacity, or one per iso value",
            ));
        }
    };
    if let Some(bad) = values.iter().find(|a| !(0.05..=1.0).contains(*a)) {
        return Err(MarkError::at(&["opacity"], format!("opacity {bad} is not in 0.05 to 1"), "use e.g. 0.4"));
    }
    Ok(values)
}

fn view_of(options: &IsosurfaceOptions) -> Result<View, MarkError> {
    let projection = match options.projection.unwrap_or(ProjectionKind::Orthographic) {
        ProjectionKind::Orthographic => Projection::Orthographic,
        ProjectionKind::Perspective => Projection::Perspective { fov_deg: options.fov.unwrap_or(30.0) },
    };
    Ok(View {
        azimuth_deg: options.azimuth.unwrap_or(-60.0),
        elevation_deg: options.elevation.unwrap_or(25.0),
        zoom: options.zoom.unwrap_or(1.0),
        projection,
    })
}

/// A light from above and to the left of the viewer, turning with the view.
fn light_for(view: &View, specular: bool) -> Light {
    Light {
        azimuth_deg: view.azimuth_deg - 50.0,
        elevation_deg: (view.elevation_deg + 30.0).min(85.0),
        ambient: 0.3,
        diffuse: 0.95,
        specular: specular.then_some(Specular { strength: 0.35, shininess: 40.0 }),
    }
}

/// With several surfaces and no opacity given, all but the innermost (the smallest box around
/// its vertices) are drawn at 0.35, so what they enclose shows.
fn see_through_outer(surfaces: &mut [Surface]) {
    let size = |s: &Surface| -> f64 {
        let first = s.mesh.positions.first().copied().unwrap_or([0.0; 3]);
        let (lo, hi) = s.mesh.positions.iter().fold((first, first), |(lo, hi), p| {
            ([lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])], [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])])
        });
        (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
    };
    let drawn: Vec<usize> = (0..surfaces.len()).filter(|&k| !surfaces[k].mesh.triangles.is_empty()).collect();
    if drawn.len() < 2 {
        return;
    }
    let inner = drawn.iter().copied().min_by(|&a, &b| size(&surfaces[a]).total_cmp(&size(&surfaces[b])));
    for k in drawn {
        if Some(k) != inner {
            surfaces[k].opacity = 0.35;
        }
    }
}

/// The surface projected to the canvas and lit per vertex (Gouraud).
fn screen_mesh(s: &Surface, camera: &Camera, light: &Light, to_px: &impl Fn([f64; 3]) -> Point) -> Mesh {
    let mut positions = Vec::with_capacity(s.mesh.positions.len());
    let mut colors = Vec::with_capacity(s.mesh.positions.len());
    let rgb = [s.color.r, s.color.g, s.color.b];
    for (p, n) in s.mesh.positions.iter().zip(&s.mesh.normals) {
        let model = camera.model(*p);
        let px = to_px(*p);
        positions.push([px.x as f32, px.y as f32, camera.depth(model) as f32]);
        let [r, g, b] = light.shade(*n, camera.toward_eye_from(model)).apply(rgb);
        colors.push(Color::rgb(r, g, b).with_opacity(s.opacity));
    }
    Mesh { positions: positions.into(), indices: s.mesh.triangles.clone().into(), colors: colors.into(), normals: None }
}

fn world_mesh(s: &Surface) -> WorldMesh {
    let f = |p: &[f64; 3]| p.map(|c| c as f32);
    let alpha = (s.opacity * 255.0).round() as u8;
    WorldMesh {
        name: format!("value = {}", format_value(s.iso)),
        positions: s.mesh.positions.iter().map(f).collect(),
        normals: s.mesh.normals.iter().map(f).collect(),
        colors: vec![[s.color.r, s.color.g, s.color.b, alpha]; s.mesh.positions.len()],
        triangles: s.mesh.triangles.clone(),
    }
}

/// One row per surface: its value, size and shape.
fn derived(surfaces: &[Surface]) -> Derived {
    let mut d = Derived::default();
    let col = |f: &dyn Fn(&Surface) -> f64| DerivedColumn::Number(surfaces.iter().map(f).collect());
    d.push("iso", col(&|s| s.iso));
    d.push("triangles", col(&|s| s.mesh.triangles.len() as f64));
    d.push("vertices", col(&|s| s.mesh.positions.len() as f64));
    d.push("area", col(&|s| s.mesh.area()));
    d.push("enclosed_volume", col(&|s| s.mesh.enclosed_volume()));
    d.push("components", col(&|s| s.mesh.components() as f64));
    d.push("euler_characteristic", col(&|s| s.mesh.euler_characteristic() as f64));
    d
}

/// `1234567` as `1,234,567`.
fn group_thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `kind = "isosurface"`.
pub static KIND: KindInfo = KindInfo::new("isosurface", &[]).sized([640.0, 560.0]).drawing_volumes();

impl Technique for IsosurfaceOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(cx, self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_grouped_by_thousands() {
        assert_eq!(group_thousands(0), "0");
        assert_eq!(group_thousands(999), "999");
        assert_eq!(group_thousands(1000), "1,000");
        assert_eq!(group_thousands(1234567), "1,234,567");
    }
}
