//! `isosurface`: surfaces of constant value through a volume — marching cubes with the topology
//! of the trilinear interpolant (or marching tetrahedra) — shaded and drawn through the shared
//! 3-D camera, several of them in depth order with transparency, in the volume's box with its
//! axes; `--format glb`, `ply` or `obj` writes the surfaces themselves.

use crate::enrich::camera::{Camera, Light};
use crate::enrich::volume::Sampler;
use crate::enrich::volume::isosurface::{self, IsoMesh, Method, NormalRule};
use crate::guide::axis::title_with_unit;
use crate::guide::color;
use crate::guide::format::format_value;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, frame};
use crate::scene::{Color, Item, Mesh, Point, Role, Shape, Style, WorldMesh};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::sync::{Arc, Mutex};

use super::VolumeFacts;
use super::box_frame::{self, BoxView, ProjectionKind, ValueLabel};

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
    /// One colour per surface (CSS names or `#rrggbb`; default: a light bone tone for one surface,
    /// the `okabe-ito` palette for several).
    #[serde(default)]
    pub colors: Option<Vec<String>>,
    /// Opacity of every surface, or one per surface, each 0.05 to 1 (default 1, except 0.35 for
    /// a surface around another: one whose bounding box holds another surface's).
    #[serde(default)]
    pub opacity: Option<Opacities>,
    /// Legend title and unit of the values: `{ title, unit }` (default `value`).
    #[serde(default)]
    pub value: Option<ValueLabel>,
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

/// Most surfaces one chart draws.
pub const MAX_SURFACES: usize = 8;

/// One extracted surface with how it is drawn.
struct Surface {
    iso: f64,
    mesh: Arc<IsoMesh>,
    /// The smallest box around the mesh's vertices (`None` when it is empty).
    bounds: Option<([f64; 3], [f64; 3])>,
    color: Color,
    opacity: f64,
}

/// The surfaces of an isosurface chart kept between its draws, so that drawing it again with
/// another camera (the explorer's turns) does not extract them again: the last
/// [`KEPT_SURFACES`] extracted, by volume shape, iso value, method and normals. One cache
/// serves one chart (its data source does not change).
#[derive(Debug, Default)]
pub struct SurfaceCache {
    kept: Mutex<Vec<(SurfaceKey, Arc<IsoMesh>)>>,
}

/// Most surfaces a [`SurfaceCache`] keeps (a chart draws at most [`MAX_SURFACES`]).
pub const KEPT_SURFACES: usize = MAX_SURFACES;

/// What a kept surface was extracted from.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SurfaceKey {
    dims: [usize; 3],
    iso: u64,
    method: Method,
    normals: NormalRule,
}

impl SurfaceKey {
    fn new(volume: &crate::data::volume::Volume, iso: f64, method: Method, normals: NormalRule) -> SurfaceKey {
        SurfaceKey { dims: volume.dims(), iso: iso.to_bits(), method, normals }
    }
}

impl SurfaceCache {
    /// The kept surface for `key`, or the one `extract` makes (then kept, the oldest dropped).
    fn get_or_extract(
        &self,
        key: SurfaceKey,
        extract: impl FnOnce() -> Result<IsoMesh, MarkError>,
    ) -> Result<Arc<IsoMesh>, MarkError> {
        if let Some((_, mesh)) = self.lock().iter().find(|(k, _)| *k == key) {
            return Ok(Arc::clone(mesh));
        }
        let mesh = Arc::new(extract()?);
        let mut kept = self.lock();
        kept.push((key, Arc::clone(&mesh)));
        if kept.len() > KEPT_SURFACES {
            kept.remove(0);
        }
        Ok(mesh)
    }

    /// How many surfaces are kept.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// The kept surfaces (a draw that panicked while holding them left them whole: each entry
    /// is pushed complete).
    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<(SurfaceKey, Arc<IsoMesh>)>> {
        self.kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Whether no surface is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
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
        let extract = || {
            // The cells from the caller's index of the source's volume, when it keeps one.
            let indexed = cx.span_space.filter(|_| cx.volume.is_some()).map(|index| index.active_cells(&volume, iso));
            isosurface::extract(&volume, iso, method, normals, indexed.as_deref())
                .map_err(|e| MarkError::at(&["levels"], format!("{e}"), "choose another value or crop the volume"))
        };
        let mesh = match cx.surfaces {
            Some(cache) => cache.get_or_extract(SurfaceKey::new(&volume, iso, method, normals), extract)?,
            None => Arc::new(extract()?),
        };
        surfaces.push(Surface { iso, bounds: bounding_box(&mesh), mesh, color: colors[k], opacity: opacities[k] });
    }
    if options.opacity.is_none() {
        see_through_outer(&mut surfaces);
    }
    let view = box_frame::view(options.azimuth, options.elevation, options.zoom, options.projection, options.fov);
    let sampler =
        Sampler::new(&volume).map_err(|e| MarkError::at(&["data"], e, "check the file's orientation header"))?;
    let light = box_frame::light_for(&view, options.specular.unwrap_or(false));

    let label = options.value.clone().unwrap_or_default();
    let title = title_with_unit(label.title.as_deref().unwrap_or("value"), label.unit.as_deref());
    let entries: Vec<(String, Color)> =
        surfaces.iter().map(|s| (format_value(s.iso), s.color.with_opacity(s.opacity))).collect();
    let legend = Legend::Categorical { title, entries, symbol: Symbol::Square };
    let canvas = frame::PanelCanvas::new(chart, vec![legend]);
    let theme = canvas.theme.clone();
    let boxed = BoxView::new(&sampler, view, &canvas)?;
    let (camera, ranges) = (&boxed.camera, boxed.ranges);
    let to_px = |p: [f64; 3]| boxed.to_px(p);

    let mut items = vec![canvas.background()];
    let (back, front) = box_frame::edges(camera, ranges, &to_px, &theme);
    items.push(back);
    // The opaque surfaces as one mesh, so its depth buffer sorts them against each other; then
    // the translucent ones from the innermost (smallest box) out, each showing its nearest layer.
    let drawn: Vec<&Surface> = surfaces.iter().filter(|s| !s.mesh.triangles.is_empty()).collect();
    let (opaque, mut translucent): (Vec<&Surface>, Vec<&Surface>) = drawn.into_iter().partition(|s| s.opacity >= 1.0);
    let box_size = |s: &Surface| s.bounds.map_or(0.0, |(lo, hi)| (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]));
    translucent.sort_by(|a, b| box_size(a).total_cmp(&box_size(b)));
    if !opaque.is_empty() {
        let values: Vec<String> = opaque.iter().map(|s| format_value(s.iso)).collect();
        let label = format!("{} = {}", if values.len() == 1 { "value" } else { "values" }, values.join(", "));
        let meshes: Vec<Mesh> = opaque.iter().map(|s| screen_mesh(s, camera, &light, &to_px)).collect();
        items.push(Item::new(Role::DataMark, Shape::Mesh(joined(meshes)), Style::default()).labelled(label));
    }
    for s in translucent {
        items.push(
            Item::new(Role::DataMark, Shape::Mesh(screen_mesh(s, camera, &light, &to_px)), Style::default())
                .labelled(format!("value = {}", format_value(s.iso))),
        );
    }
    items.push(front);
    items.extend(boxed.axes(volume.unit().map(|u| u.symbol()), &theme));
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
        volume: Some(VolumeFacts { range, levels: values, shown: None, coloured: false }),
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

/// The colour of a lone surface when none is given: a light bone tone.
const SINGLE_SURFACE: Color = Color::rgb(226, 218, 200);

fn surface_colors(options: &IsosurfaceOptions, n: usize) -> Result<Vec<Color>, MarkError> {
    let palette = color::categorical(color::DEFAULT_CATEGORICAL).unwrap_or_default();
    match &options.colors {
        // One surface in a light neutral tone, so its shading reads; several in the palette.
        None if n == 1 => Ok(vec![SINGLE_SURFACE]),
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

/// With several surfaces and no opacity given, a surface whose bounding box holds another
/// surface's is drawn at [`SEE_THROUGH`], so what it encloses shows; surfaces side by side
/// (a positive and a negative blob) stay opaque.
fn see_through_outer(surfaces: &mut [Surface]) {
    let boxes: Vec<Option<([f64; 3], [f64; 3])>> = surfaces.iter().map(|s| s.bounds).collect();
    let holds = |outer: ([f64; 3], [f64; 3]), inner: ([f64; 3], [f64; 3])| {
        (0..3).all(|a| outer.0[a] <= inner.0[a] && inner.1[a] <= outer.1[a])
    };
    let outer: Vec<bool> = (0..surfaces.len())
        .map(|k| {
            boxes[k].is_some_and(|bk| {
                (0..surfaces.len()).any(|j| j != k && boxes[j].is_some_and(|bj| bj != bk && holds(bk, bj)))
            })
        })
        .collect();
    for (s, outer) in surfaces.iter_mut().zip(outer) {
        if outer {
            s.opacity = SEE_THROUGH;
        }
    }
}

/// The opacity of a surface drawn around another when no opacity is given.
const SEE_THROUGH: f64 = 0.35;

/// The smallest box around a mesh's vertices; `None` for an empty mesh.
fn bounding_box(mesh: &IsoMesh) -> Option<([f64; 3], [f64; 3])> {
    let first = *mesh.positions.first()?;
    Some(mesh.positions.iter().fold((first, first), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])], [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])])
    }))
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

/// The meshes as one, their triangles renumbered.
fn joined(meshes: Vec<Mesh>) -> Mesh {
    let (mut positions, mut colors, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    for m in meshes {
        let offset = positions.len() as u32;
        positions.extend(m.positions.iter().copied());
        colors.extend(m.colors.iter().copied());
        indices.extend(m.indices.iter().map(|t| t.map(|i| i + offset)));
    }
    Mesh { positions: positions.into(), indices: indices.into(), colors: colors.into(), normals: None }
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
