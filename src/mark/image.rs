//! `image`: a gridded scalar field as a colour image (heatmap) with a colour bar, resampled to
//! the plot's pixels by nearest node or bilinear interpolation.

use std::sync::Arc;

use super::derived::Derived;
use super::gridded::{self, GridInput};
use super::registry::{AxisSpec, ChartContext, ColourSpec, KindInfo, Technique};
use super::{ChartOutput, MarkError, encode, frame};
use crate::data::Table;
use crate::enrich::grid::Grid;
use crate::guide::axis::title_with_unit;
use crate::guide::color;
use crate::guide::layout::Domain;
use crate::guide::legend::Legend;
use crate::guide::scale::Scale;
use crate::scene::{Color, Item, Raster, Rect, Role, Shape, Style};
use crate::spec::defaults;
use crate::spec::{Chart, ImageOptions, Resample};

/// Default colour of missing cells.
pub const NAN_COLOR: Color = Color::rgb(0xd9, 0xd9, 0xd9);
/// Largest raster side in pixels.
pub const MAX_RASTER_SIDE: usize = 4096;

/// Draw an image chart.
pub fn draw(chart: &Chart, options: &ImageOptions, index: usize, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let z_opts = options.z.options();
    let GridInput { grid, rows, warnings, x_col, y_col, zmin, zmax } =
        gridded::load_grid(chart, index, &x_opts, &y_opts, &z_opts, table)?;
    let map = encode::continuous_map(index, &["z", "scheme"], z_opts.scheme.as_deref())?;
    let (lo, hi) = encode::color_domain(&map, zmin, zmax, z_opts.midpoint);
    let nan_color = match options.nan_color.as_deref() {
        None => NAN_COLOR,
        Some(s) => color::parse_color(s).ok_or_else(|| {
            MarkError::at(index, &["nan_color"], format!("`{s}` is not a colour"), "use a CSS colour name or #rrggbb")
        })?,
    };
    let resample = options.resample.unwrap_or(Resample::Nearest);

    let mut x_axis = encode::position_axis(chart, index, "x", &x_opts, x_col, &rows)?;
    let mut y_axis = encode::position_axis(chart, index, "y", &y_opts, y_col, &rows)?;
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
    let (frame, theme) = frame::cartesian(chart, index, x_axis, y_axis, encode::shown_legends(legend, &z_opts))?;

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
    let scene = frame::scene(chart, frame, &theme, marks);

    let derived = Derived::of_rows(rows, &[&x_opts.field, &y_opts.field, &z_opts.field]);
    Ok(ChartOutput { scene, derived, warnings, geojson: None, geometry: Default::default() })
}

/// The data extent an image covers: node to node for bilinear; for nearest, half a cell beyond
/// the outer nodes, so that every node's cell is whole.
pub fn image_extent(coords: &[f64], resample: Resample) -> Option<(f64, f64)> {
    let (&first, &last) = (coords.first()?, coords.last()?);
    match resample {
        Resample::Bilinear if coords.len() > 1 => Some((first, last)),
        _ => {
            let lead = coords.get(1).map(|c| (c - first) / 2.0).unwrap_or(0.5);
            let trail =
                coords.len().checked_sub(2).and_then(|k| coords.get(k)).map(|c| (last - c) / 2.0).unwrap_or(0.5);
            Some((first - lead, last + trail))
        }
    }
}

/// The grid resampled to the pixels of `plot` (through the scales, so uneven grids and log axes
/// stay exact) and coloured by `color`.
pub fn raster_for(
    grid: &Grid,
    plot: Rect,
    x: &Scale,
    y: &Scale,
    resample: Resample,
    color: impl Fn(f64) -> Color,
) -> Raster {
    let width = (plot.w.round().max(1.0) as usize).min(MAX_RASTER_SIDE);
    let height = (plot.h.round().max(1.0) as usize).min(MAX_RASTER_SIDE);
    let sample = |scale: &Scale, start: f64, extent: f64, n: usize| -> Vec<f64> {
        (0..n).map(|k| scale.invert(start + extent * (k as f64 + 0.5) / n as f64).unwrap_or(f64::NAN)).collect()
    };
    let px_x = sample(x, plot.x, plot.w, width);
    let px_y = sample(y, plot.y, plot.h, height);
    let rgba = raster(grid, &px_x, &px_y, resample, color);
    Raster { dest: plot, width: width as u32, height: height as u32, rgba: Arc::new(rgba), smooth: false }
}

/// Index of the node nearest `v` along sorted `coords` (cell boundaries at midpoints).
fn nearest(coords: &[f64], v: f64) -> Option<usize> {
    if !v.is_finite() || coords.is_empty() {
        return None;
    }
    let k = coords.partition_point(|c| *c < v);
    match (k.checked_sub(1), coords.get(k)) {
        (Some(a), Some(&b)) => Some(if v - coords[a] < b - v { a } else { k }),
        (None, Some(_)) => Some(0),
        (Some(a), None) => Some(a),
        (None, None) => None,
    }
}

/// RGBA pixels, row-major from the top, for pixel centres at data positions `xs` × `ys`.
fn raster(grid: &Grid, xs: &[f64], ys: &[f64], resample: Resample, color: impl Fn(f64) -> Color) -> Vec<u8> {
    let mut rgba = Vec::with_capacity(xs.len() * ys.len() * 4);
    let columns: Vec<Option<usize>> = xs.iter().map(|&x| nearest(grid.xs(), x)).collect();
    for &y in ys {
        let row = nearest(grid.ys(), y);
        for (&x, col) in xs.iter().zip(&columns) {
            let v = match (resample, col, row) {
                (Resample::Bilinear, _, _) => grid.bilinear(x, y),
                (Resample::Nearest, Some(i), Some(j)) => grid.value(*i, j),
                _ => f64::NAN,
            };
            let c = color(v);
            rgba.extend_from_slice(&[c.r, c.g, c.b, c.a]);
        }
    }
    rgba
}

/// `kind = "image"`.
pub static KIND: KindInfo = KindInfo::new("image", &["x", "y", "z"]).conventions(defaults::GRID).taking_aspect();

impl Technique for ImageOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.index, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        AxisSpec::pair(&self.x, &self.y)
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        ColourSpec::z(&self.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_uses_midpoints_between_uneven_nodes() {
        let c = [0.0, 1.0, 3.0];
        assert_eq!(nearest(&c, -5.0), Some(0));
        assert_eq!(nearest(&c, 0.49), Some(0));
        assert_eq!(nearest(&c, 0.51), Some(1));
        assert_eq!(nearest(&c, 1.99), Some(1));
        assert_eq!(nearest(&c, 2.01), Some(2));
        assert_eq!(nearest(&c, 9.0), Some(2));
        assert_eq!(nearest(&c, f64::NAN), None);
    }

    #[test]
    fn extents_cover_whole_cells_for_nearest() {
        assert_eq!(image_extent(&[0.0, 1.0, 3.0], Resample::Nearest), Some((-0.5, 4.0)));
        assert_eq!(image_extent(&[0.0, 1.0, 3.0], Resample::Bilinear), Some((0.0, 3.0)));
        assert_eq!(image_extent(&[2.0], Resample::Bilinear), Some((1.5, 2.5)));
        assert_eq!(image_extent(&[], Resample::Nearest), None);
    }

    #[test]
    fn raster_samples_nodes_and_marks_holes() {
        let grid = Grid::new(vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0, 1.0, 2.0, f64::NAN]).expect("grid");
        let grey = |v: f64| if v.is_finite() { Color::rgb((v * 100.0) as u8, 0, 0) } else { Color::rgb(0, 0, 255) };
        // Pixel rows from the top: y = 1 then y = 0.
        let px = raster(&grid, &[0.0, 1.0], &[1.0, 0.0], Resample::Nearest, grey);
        assert_eq!(px, vec![200, 0, 0, 255, 0, 0, 255, 255, 0, 0, 0, 255, 100, 0, 0, 255]);
        // Bilinear: a cell with a missing corner is a hole; a whole cell interpolates.
        let hole = raster(&grid, &[0.5], &[0.0], Resample::Bilinear, grey);
        assert_eq!(&hole[..3], &[0, 0, 255]);
        let whole = Grid::new(vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0, 1.0, 2.0, 1.0]).expect("grid");
        let mid = raster(&whole, &[0.5], &[0.0], Resample::Bilinear, grey);
        assert_eq!(&mid[..3], &[50, 0, 0]);
    }
}
