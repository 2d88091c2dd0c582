//! `volume`: direct volume rendering by ray casting — front-to-back compositing through an
//! opacity and colour transfer function (optionally shaded), a maximum intensity projection or
//! an X-ray-like average — drawn as an image inside the volume's box with its axes.

use crate::enrich::volume::Sampler;
use crate::enrich::volume::census::census;
use crate::enrich::volume::raycast::{
    Classify, Job, Mode, RayCaster, Settings, Shading, TERMINATION, TransferFunction,
};
use crate::enrich::volume::shear_warp::shear_warp;
use crate::guide::axis::title_with_unit;
use crate::guide::color::ContinuousMap;
use crate::guide::format::format_value;
use crate::guide::legend::Legend;
use crate::guide::transfer_legend::TransferLegend;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Item, Raster, Role, Shape, Style};
use crate::timing::timed;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::box_frame::{self, BoxView, ProjectionKind, ValueLabel};
use super::labels::{Labels, VolumeLabel};
use super::{SHOWN_OPACITY, VolumeFacts};

/// Options of `kind = "volume"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct VolumeOptions {
    /// `composite` (default: colours and opacities from the transfer function, front to back),
    /// `mip` (the largest value along each ray) or `average` (the mean value, like an X-ray).
    #[serde(default)]
    pub mode: Option<RenderMode>,
    /// Opacity control points `[[value, opacity], ...]`, rising in value, opacity 0 to 1 per
    /// voxel length of ray (piecewise linear; the end opacities hold beyond them).
    #[serde(default)]
    pub opacity: Option<Vec<[f64; 2]>>,
    /// A starting transfer function when `opacity` is not given: `mri` (default: opacity rising
    /// over the upper half of the volume's values, by percentiles) or `ct` (Hounsfield units:
    /// air and fat clear, soft tissue faint, bone opaque).
    #[serde(default)]
    pub preset: Option<Preset>,
    /// Colour scheme over the transfer function's values (composite; default `magma`) or the
    /// values (mip, average; default `greys_r`).
    #[serde(default)]
    pub scheme: Option<String>,
    /// `after` (default: interpolate, then classify) or `before` (classify the voxels, then
    /// interpolate opacity-weighted colours).
    #[serde(default)]
    pub classify: Option<ClassifyWhen>,
    /// Diffuse shading from the gradient (composite; default true).
    #[serde(default)]
    pub shade: Option<bool>,
    /// `ray-casting` (default) or `shear-warp` (composite, orthographic: slices composited in
    /// memory order, one sample per voxel along the view, classified at the voxels; faster).
    #[serde(default)]
    pub renderer: Option<Renderer>,
    /// Distance between samples along a ray, in voxels of the smallest spacing (default 0.5;
    /// 0.05 to 4).
    #[serde(default)]
    pub step: Option<f64>,
    /// Rays across the image (default: one per canvas unit of the drawn box, at most 1024; 16
    /// to 2048).
    #[serde(default)]
    pub resolution: Option<u32>,
    /// Opacity scaled by the gradient magnitude (composite; default false): uniform regions
    /// fade and boundaries between materials stay. Full opacity from the 95th percentile of
    /// the volume's gradient magnitudes up.
    #[serde(default)]
    pub gradient_opacity: Option<bool>,
    /// A label volume (segmentation): `[{ value, name, color, opacity }, ...]`, one per
    /// whole-number voxel value shown; other values are transparent (composite, classified
    /// before interpolation; instead of `opacity`, `preset` and `scheme`).
    #[serde(default)]
    pub labels: Option<Vec<VolumeLabel>>,
    /// Legend title and unit: `{ title, unit }` (default `value`; `label` for labels).
    #[serde(default)]
    pub value: Option<ValueLabel>,
    /// Draw the legend: the transfer function over the histogram of the values, the colour bar
    /// (mip, average) or the labels (default true).
    #[serde(default)]
    pub legend: Option<bool>,
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
}

/// How rays become pixels.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum RenderMode {
    /// Front-to-back compositing through the transfer function.
    Composite,
    /// Maximum intensity projection.
    Mip,
    /// The mean value along each ray.
    Average,
}

/// How a composite image is computed.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Renderer {
    /// Rays cast from every pixel, sampled every `step`.
    RayCasting,
    /// Slices sheared into an intermediate image and warped into the final one.
    ShearWarp,
}

/// Starting transfer functions.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// CT numbers in Hounsfield units.
    Ct,
    /// MRI-like intensities, from the volume's percentiles.
    Mri,
}

/// When values become colours.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ClassifyWhen {
    /// Interpolate, then classify.
    After,
    /// Classify the voxels, then interpolate.
    Before,
}

/// The CT preset's opacity control points (Hounsfield units).
const CT_OPACITY: [[f64; 2]; 6] =
    [[-1000.0, 0.0], [-100.0, 0.0], [40.0, 0.02], [150.0, 0.03], [300.0, 0.3], [1200.0, 0.85]];

/// Most rays across an image by default, and the bounds of `resolution`.
const DEFAULT_MAX_RESOLUTION: f64 = 1024.0;
const RESOLUTION_RANGE: (u32, u32) = (16, 2048);

/// Bins of the histogram behind the transfer function in the legend.
const LEGEND_BINS: usize = 96;

/// The gradient magnitude quantile at which `gradient_opacity` reaches full opacity.
const GRADIENT_FULL_QUANTILE: f64 = 0.95;

/// What colours the rays: a transfer function with its control points, labels, or a colour
/// map over the values a maximum or mean finds.
enum Look {
    Function { tf: TransferFunction, points: Vec<[f64; 2]>, colours: (f64, f64) },
    Labels { tf: TransferFunction, labels: Labels },
    Reduce(Mode),
}

/// Draw a volume-rendering chart.
pub fn draw(cx: &ChartContext<'_>, options: &VolumeOptions) -> Result<ChartOutput, MarkError> {
    let chart = &cx.chart;
    let volume = cx.volume()?;
    let caster = timed("prepare the ray caster", || RayCaster::new(&volume))
        .map_err(|e| MarkError::at(&["data"], e, "choose a volume with depth"))?;
    let sampler =
        Sampler::new(&volume).map_err(|e| MarkError::at(&["data"], e, "check the file's orientation header"))?;
    let mode = options.mode.unwrap_or(RenderMode::Composite);
    check_combination(options, mode)?;
    let step_voxels = options.step.unwrap_or(0.5);
    if !(0.05..=4.0).contains(&step_voxels) {
        return Err(MarkError::at(
            &["step"],
            format!("step {step_voxels} is not in 0.05 to 4 voxels"),
            "give the distance between samples in voxels, e.g. step = 0.5",
        ));
    }
    let voxel = volume.spacing().into_iter().fold(f64::INFINITY, f64::min);
    let step = step_voxels * voxel;
    let (lo, hi) = timed("value range", || volume.range()).0.ok_or_else(|| {
        MarkError::at(&["data"], "every voxel of the volume is missing (NaN)", "check the file and its data type")
    })?;
    let default_scheme = if mode == RenderMode::Composite { "magma" } else { "greys_r" };
    let map = encode::continuous_map(&["scheme"], Some(options.scheme.as_deref().unwrap_or(default_scheme)))?;
    let view = box_frame::view(options.azimuth, options.elevation, options.zoom, options.projection, options.fov);
    let label = options.value.clone().unwrap_or_default();
    let default_title = if options.labels.is_some() { "label" } else { "value" };
    let title = title_with_unit(label.title.as_deref().unwrap_or(default_title), label.unit.as_deref());

    let look = match (mode, &options.labels) {
        (RenderMode::Composite, Some(given)) => {
            let labels = Labels::resolve(given, &volume)?;
            Look::Labels { tf: labels.transfer_function()?, labels }
        }
        (RenderMode::Composite, None) => {
            let points = opacity_points(options, &volume)?;
            let colours = (points[0][0], points[points.len() - 1][0]).max_span();
            let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p[0], p[1])).collect();
            let (c0, c1) = colours;
            let tf = TransferFunction::new(|v| rgb(&map, (v - c0) / (c1 - c0)), &pairs)
                .map_err(|e| MarkError::at(&["opacity"], e, "give [value, opacity] pairs rising in value"))?;
            Look::Function { tf, points, colours }
        }
        (RenderMode::Mip, _) => Look::Reduce(Mode::Mip),
        (RenderMode::Average, _) => Look::Reduce(Mode::Average),
    };
    // The value axis of a transfer-function legend: the data's range and every control point.
    let axis = match &look {
        Look::Function { points, .. } => (lo.min(points[0][0]), hi.max(points[points.len() - 1][0])).max_span(),
        _ => (lo, hi).max_span(),
    };
    let counted = match &look {
        Look::Function { tf, .. } | Look::Labels { tf, .. } => Some(timed("legend histogram", || {
            census(
                caster.values(),
                axis,
                LEGEND_BINS,
                |v| tf.at(v)[3] >= SHOWN_OPACITY,
                |a, b| tf.opacity_at_least_throughout((a, b), SHOWN_OPACITY),
            )
        })),
        Look::Reduce(_) => None,
    };
    // The legend before the image, so the rays fit the room it leaves; a colour bar's domain is
    // known only once the rays have found their values (the first one only sizes the box).
    let legend = |domain: (f64, f64)| -> Vec<Legend> {
        if options.legend == Some(false) {
            return Vec::new();
        }
        vec![match &look {
            Look::Function { points, colours, .. } => Legend::TransferFunction {
                title: title.clone(),
                function: TransferLegend {
                    map: map.clone(),
                    colour_domain: *colours,
                    domain: axis,
                    opacity: points.clone(),
                    counts: counted.as_ref().map(|c| c.counts.clone()).unwrap_or_default(),
                },
            },
            Look::Labels { labels, .. } => labels.legend(title.clone()),
            Look::Reduce(_) => Legend::ColorBar { title: title.clone(), map: map.clone(), domain },
        }]
    };
    let canvas = frame::PanelCanvas::new(chart, legend((lo, hi).max_span()));
    let boxed = BoxView::new(&sampler, view, &canvas)?;
    let side = match options.resolution {
        Some(r) if (RESOLUTION_RANGE.0..=RESOLUTION_RANGE.1).contains(&r) => r as usize,
        Some(r) => {
            return Err(MarkError::at(
                &["resolution"],
                format!("resolution {r} is not in {} to {}", RESOLUTION_RANGE.0, RESOLUTION_RANGE.1),
                "give the rays across the image, e.g. resolution = 512",
            ));
        }
        None => boxed.square.w.round().clamp(16.0, DEFAULT_MAX_RESOLUTION) as usize,
    };
    let ray = |x: usize, y: usize| {
        let (sx, sy) = ((x as f64 + 0.5) / side as f64, 1.0 - (y as f64 + 0.5) / side as f64);
        let (m, d) = boxed.camera.ray(sx, sy);
        let origin = boxed.camera.data(m);
        let ahead = boxed.camera.data([m[0] + d[0], m[1] + d[1], m[2] + d[2]]);
        let dir = [ahead[0] - origin[0], ahead[1] - origin[1], ahead[2] - origin[2]];
        let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        (origin, dir.map(|c| c / len))
    };
    let mut domain = (lo, hi).max_span();
    let (rgba, how) = match &look {
        Look::Function { tf, .. } | Look::Labels { tf, .. } => {
            let labelled = matches!(look, Look::Labels { .. });
            let classify = match options.classify {
                _ if labelled => Classify::Before,
                Some(ClassifyWhen::Before) => Classify::Before,
                _ => Classify::After,
            };
            let shading = options.shade.unwrap_or(true).then(|| {
                let light = box_frame::light_for(&view, false);
                Shading { light: light.direction(), ambient: 0.35, diffuse: 0.65 }
            });
            let gradient_opacity = options
                .gradient_opacity
                .unwrap_or(false)
                .then(|| caster.gradient_quantile(GRADIENT_FULL_QUANTILE).unwrap_or(1.0));
            let settings =
                Settings { step, reference: voxel, termination: TERMINATION, classify, shading, gradient_opacity };
            let scaled = gradient_opacity.is_some();
            match options.renderer.unwrap_or(Renderer::RayCasting) {
                Renderer::RayCasting => {
                    let pixels = timed("cast rays", || caster.image((side, side), &ray, Job::Composite(tf, &settings)));
                    (composited_rgba(&pixels), composite_note(side, step_voxels, classify, scaled))
                }
                Renderer::ShearWarp => {
                    let pixels = shear_warp(&caster, tf, &settings, (side, side), &ray)
                        .map_err(|e| MarkError::at(&["projection"], e, "use projection = \"orthographic\""))?;
                    let scaled = if scaled { ", opacity scaled by the gradient magnitude" } else { "" };
                    (
                        composited_rgba(&pixels),
                        format!("shear-warp: {side} × {side} pixels, a sample per voxel{scaled}"),
                    )
                }
            }
        }
        Look::Reduce(reduce) => {
            // Sampled from the entry on: a step dividing the voxel spacing meets every voxel
            // plane of an axis-aligned ray.
            let pixels = caster.image((side, side), &ray, Job::Reduce(*reduce, step));
            let what = if *reduce == Mode::Mip { "maximum intensity projection" } else { "mean along each ray" };
            // The colours span the values the rays found, not the whole volume's.
            let found = pixels.iter().map(|p| p[0]).filter(|v| v.is_finite());
            let (a, b) = found.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
            if a <= b {
                domain = (a, b).max_span();
            }
            (mapped_rgba(&pixels, &map, domain), format!("{what}: {side} × {side} rays"))
        }
    };
    // The rays are cast in the camera's unit square, so the image fits whatever room the final
    // legend leaves.
    let canvas = frame::PanelCanvas::new(chart, legend(domain));
    let theme = canvas.theme.clone();
    let boxed = BoxView::new(&sampler, view, &canvas)?;
    let image = Raster { dest: boxed.square, width: side as u32, height: side as u32, rgba: rgba.into(), smooth: true };

    let mut items = vec![canvas.background()];
    let to_px = |p: [f64; 3]| boxed.to_px(p);
    let (back, front) = box_frame::edges(&boxed.camera, boxed.ranges, &to_px, &theme);
    items.push(back);
    items.push(
        Item::new(Role::DataMark, Shape::Image(image), Style::default()).labelled(format!("{mode:?}").to_lowercase()),
    );
    items.push(front);
    items.extend(boxed.axes(volume.unit().map(|u| u.symbol()), &theme));
    let caption = match &chart.caption {
        Some(c) => format!("{c} — {how}"),
        None => how,
    };
    let scene = canvas.scene(chart, items, Some(&caption));
    let derived = match &look {
        Look::Function { points, colours, .. } => derived(Some(points), *colours, &map),
        Look::Labels { labels, .. } => labels.derived(),
        Look::Reduce(_) => derived(None, domain, &map),
    };
    let facts = VolumeFacts {
        range: Some((lo, hi)),
        levels: Vec::new(),
        shown: counted.map(|c| c.kept_share()),
        coloured: true,
    };
    Ok(ChartOutput {
        scene,
        derived,
        warnings: Vec::new(),
        meshes: Vec::new(),
        geojson: None,
        volume: Some(facts),
        geometry: Default::default(),
    })
}

/// Keys that do not go together: labels with a transfer function's keys or another mode,
/// composite-only keys with a maximum or mean.
fn check_combination(options: &VolumeOptions, mode: RenderMode) -> Result<(), MarkError> {
    let composite_only = [
        ("labels", options.labels.is_some()),
        ("opacity", options.opacity.is_some()),
        ("preset", options.preset.is_some()),
        ("gradient_opacity", options.gradient_opacity.is_some()),
        ("classify", options.classify.is_some()),
        ("renderer", options.renderer.is_some()),
    ];
    if mode != RenderMode::Composite
        && let Some((key, _)) = composite_only.iter().find(|(_, given)| *given)
    {
        return Err(MarkError::at(
            &[key],
            format!("`{key}` applies to mode = \"composite\", not to a maximum or mean"),
            format!("leave out `{key}`, or use mode = \"composite\""),
        ));
    }
    if options.renderer == Some(Renderer::ShearWarp) {
        let clash = [
            ("classify", options.classify == Some(ClassifyWhen::After)),
            ("step", options.step.is_some()),
            ("projection", options.projection == Some(ProjectionKind::Perspective)),
        ];
        if let Some((key, _)) = clash.iter().find(|(_, given)| *given) {
            return Err(MarkError::at(
                &[key],
                format!(
                    "`{key}` does not go with renderer = \"shear-warp\": it samples once per voxel along the view, \
                     classified at the voxels, in orthographic views"
                ),
                format!("leave out `{key}`, or use renderer = \"ray-casting\""),
            ));
        }
    }
    if options.labels.is_some() {
        let clash = [
            ("opacity", options.opacity.is_some()),
            ("preset", options.preset.is_some()),
            ("scheme", options.scheme.is_some()),
            ("classify", options.classify == Some(ClassifyWhen::After)),
        ];
        if let Some((key, _)) = clash.iter().find(|(_, given)| *given) {
            return Err(MarkError::at(
                &[key],
                format!("`{key}` does not go with `labels`: each label has its own colour and opacity"),
                format!("leave out `{key}`, or give colours and opacities in `labels`"),
            ));
        }
    }
    Ok(())
}

/// The opacity control points: the spec's, a preset's, or the MRI preset from the volume's
/// percentiles.
fn opacity_points(options: &VolumeOptions, volume: &crate::data::volume::Volume) -> Result<Vec<[f64; 2]>, MarkError> {
    if let Some(points) = &options.opacity {
        if points.is_empty() {
            return Err(MarkError::at(&["opacity"], "no opacity control points", "give [[value, opacity], ...]"));
        }
        return Ok(points.clone());
    }
    Ok(match options.preset.unwrap_or(Preset::Mri) {
        Preset::Ct => CT_OPACITY.to_vec(),
        Preset::Mri => {
            let q = percentiles(volume, &[0.5, 0.9, 0.99]);
            let ([a, b, c], (_, hi)) = (q, volume.range().0.unwrap_or((0.0, 1.0)));
            let b = b.max(a);
            vec![[a, 0.0], [b, 0.03], [c.max(b), 0.25], [hi.max(c), 0.6]]
        }
    })
}

/// The values at fractions `qs` of the non-missing voxels (from at most about a million of
/// them, evenly strided).
fn percentiles<const N: usize>(volume: &crate::data::volume::Volume, qs: &[f64; N]) -> [f64; N] {
    let stride = (volume.len() / 1_000_000).max(1);
    let mut sample: Vec<f64> = volume.values().step_by(stride).filter(|v| v.is_finite()).collect();
    sample.sort_by(f64::total_cmp);
    let last = sample.len().saturating_sub(1);
    qs.map(|q| sample.get((q * last as f64).round() as usize).copied().unwrap_or(0.0))
}

/// Straight RGB (0 to 1) of `map` at `t` in `[0, 1]`.
fn rgb(map: &ContinuousMap, t: f64) -> [f64; 3] {
    let c = map.at(t.clamp(0.0, 1.0));
    [c.r, c.g, c.b].map(|v| f64::from(v) / 255.0)
}

/// Straight-alpha RGBA bytes of premultiplied composited pixels.
fn composited_rgba(pixels: &[[f64; 4]]) -> Vec<u8> {
    let mut out = Vec::with_capacity(pixels.len() * 4);
    for p in pixels {
        let a = p[3].clamp(0.0, 1.0);
        let straight = |c: f64| if a > 0.0 { ((c / a).clamp(0.0, 1.0) * 255.0).round() as u8 } else { 0 };
        out.extend([straight(p[0]), straight(p[1]), straight(p[2]), (a * 255.0).round() as u8]);
    }
    out
}

/// RGBA bytes of ray values through `map` over `domain`; transparent where a ray has none.
fn mapped_rgba(pixels: &[[f64; 4]], map: &ContinuousMap, (lo, hi): (f64, f64)) -> Vec<u8> {
    let mut out = Vec::with_capacity(pixels.len() * 4);
    for p in pixels {
        if p[0].is_nan() {
            out.extend([0, 0, 0, 0]);
        } else {
            let c = map.at(((p[0] - lo) / (hi - lo)).clamp(0.0, 1.0));
            out.extend([c.r, c.g, c.b, 255]);
        }
    }
    out
}

fn composite_note(side: usize, step: f64, classify: Classify, gradient_opacity: bool) -> String {
    let when = match classify {
        Classify::After => "classified after interpolation",
        Classify::Before => "classified before interpolation",
    };
    let scaled = if gradient_opacity { ", opacity scaled by the gradient magnitude" } else { "" };
    format!("ray casting: {side} × {side} rays, a sample every {} voxel, {when}{scaled}", format_value(step))
}

/// One row per opacity control point (value, opacity, colour), or the colour bar's ends.
fn derived(opacity: Option<&[[f64; 2]]>, (lo, hi): (f64, f64), map: &ContinuousMap) -> Derived {
    let points: Vec<[f64; 2]> = opacity.map_or_else(|| vec![[lo, 1.0], [hi, 1.0]], <[_]>::to_vec);
    let mut d = Derived::default();
    d.push("value", DerivedColumn::Number(points.iter().map(|p| p[0]).collect()));
    d.push("opacity", DerivedColumn::Number(points.iter().map(|p| p[1]).collect()));
    d.push(
        "color",
        DerivedColumn::Text(points.iter().map(|p| map.at(((p[0] - lo) / (hi - lo)).clamp(0.0, 1.0)).hex()).collect()),
    );
    d
}

/// A range widened to a span when its ends meet.
trait MaxSpan {
    fn max_span(self) -> Self;
}

impl MaxSpan for (f64, f64) {
    fn max_span(self) -> (f64, f64) {
        if self.1 > self.0 { self } else { (self.0, self.0 + 1.0) }
    }
}

/// `kind = "volume"`.
pub static KIND: KindInfo = KindInfo::new("volume", &[]).sized([640.0, 560.0]).drawing_volumes();

impl Technique for VolumeOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(cx, self)
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }
}
