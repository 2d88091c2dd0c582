//! `image`: a gridded scalar field as a colour image (heatmap) with a colour bar, resampled to
//! the plot's pixels by nearest node or bilinear interpolation.

use std::sync::Arc;

use crate::data::Table;
use crate::guide::axis::title_with_unit;
use crate::guide::color;
use crate::guide::layout::Domain;
use crate::guide::legend::Legend;
use crate::guide::scale::Scale;
use crate::mark::derived::Derived;
use crate::mark::gridded::{self, GridInput};
use crate::mark::raster::{MAX_RASTER_SIDE, NAN_COLOR, image_extent, raster};
use crate::mark::registry::{AxisSpec, ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Item, Raster, Role, Shape, Style};
use crate::spec::{Channel, Chart, ColorChannel, Resample, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "image"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ImageOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node).
    pub x: Channel,
    /// Grid y coordinate: a numeric column of a long-form table (one row per grid node).
    pub y: Channel,
    /// The field's value: a column name, or `{ field, title, unit, scheme, midpoint }`.
    pub z: ColorChannel,
    /// `nearest` (default: each node colours the cell around it) or `bilinear` (smooth).
    #[serde(default)]
    pub resample: Option<Resample>,
    /// Colour of missing cells (default light grey, `#d9d9d9`).
    #[serde(default)]
    pub nan_color: Option<String>,
}

/// Draw an image chart.
pub fn draw(chart: &Chart, options: &ImageOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let z_opts = options.z.options();
    let GridInput { grid, rows, mut warnings, x_col, y_col, zmin, zmax } =
        gridded::load_grid(chart, &x_opts, &y_opts, &z_opts, table)?;
    let map = encode::continuous_map(&["z", "scheme"], z_opts.scheme.as_deref())?;
    let (lo, hi) = encode::color_domain(&map, zmin, zmax, z_opts.midpoint);
    let nan_color = match options.nan_color.as_deref() {
        None => NAN_COLOR,
        Some(s) => color::parse_color(s).ok_or_else(|| {
            MarkError::at(&["nan_color"], format!("`{s}` is not a colour"), "use a CSS colour name or #rrggbb")
        })?,
    };
    let resample = options.resample.unwrap_or(Resample::Nearest);

    let mut x_axis = encode::position_axis("x", &x_opts, x_col, &rows)?;
    let mut y_axis = encode::position_axis("y", &y_opts, y_col, &rows)?;
    for (axis, opts, coords) in [(&mut x_axis, &x_opts, grid.xs()), (&mut y_axis, &y_opts, grid.ys())] {
        axis.nice = false;
        axis.grid = false;
        if opts.domain.is_none()
            && let Some(extent) = image_extent(coords, resample)
        {
            axis.domain = Domain::Continuous(extent.0, extent.1);
        }
    }
    let title = title_with_unit(z_opts.title.as_deref().unwrap_or(&z_opts.field), z_opts.unit.as_deref());
    let legend = Legend::ColorBar { title, map: map.clone(), domain: (lo, hi) };
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, encode::shown_legends(legend, &z_opts))?;

    let width = (frame.plot.w.round().max(1.0) as usize).min(MAX_RASTER_SIDE);
    let height = (frame.plot.h.round().max(1.0) as usize).min(MAX_RASTER_SIDE);
    let sample = |scale: &Scale, start: f64, extent: f64, n: usize| -> Vec<f64> {
        (0..n).map(|k| scale.invert(start + extent * (k as f64 + 0.5) / n as f64).unwrap_or(f64::NAN)).collect()
    };
    let px_x = sample(&frame.x, frame.plot.x, frame.plot.w, width);
    let px_y = sample(&frame.y, frame.plot.y, frame.plot.h, height);
    let rgba =
        raster(&grid, &px_x, &px_y, resample, |v| if v.is_finite() { map.at((v - lo) / (hi - lo)) } else { nan_color });
    let image =
        Raster { dest: frame.plot, width: width as u32, height: height as u32, rgba: Arc::new(rgba), smooth: false };
    let marks = vec![
        Item::new(Role::DataMark, Shape::Image(image), Style::default())
            .with_rows(rows.clone())
            .labelled(z_opts.field.clone()),
    ];
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

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

/// `kind = "image"`.
pub static KIND: KindInfo =
    KindInfo::new("image", &["x", "y", "z"]).conventions(defaults::GRID).taking_aspect().drawing_annotations();

impl Technique for ImageOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        AxisSpec::pair(&self.x, &self.y)
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        ColourSpec::z(&self.z)
    }
}
