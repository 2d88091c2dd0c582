//! A gridded field resampled to a plot's pixels (nearest node or bilinear) as a colour raster,
//! shared by the image and hyperslice kinds.

use crate::enrich::grid::Grid;
use crate::guide::scale::Scale;
use crate::scene::{Color, Raster, Rect};
use crate::spec::Resample;
use std::sync::Arc;

/// Default colour of missing cells.
pub const NAN_COLOR: Color = Color::rgb(0xd9, 0xd9, 0xd9);
/// Largest raster side in pixels.
pub const MAX_RASTER_SIDE: usize = 4096;

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
pub fn raster(grid: &Grid, xs: &[f64], ys: &[f64], resample: Resample, color: impl Fn(f64) -> Color) -> Vec<u8> {
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
