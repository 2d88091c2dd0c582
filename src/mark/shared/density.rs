//! Density views of point layers too big for one mark per row: the spec's options (mode,
//! shading, bin size, minimum opacity, spreading), the bins laid over a plot's pixels, and the
//! count grid drawn as a raster with its count legend and its CSV of non-empty bins.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::derived::{Derived, DerivedColumn};
use crate::data::density::{Bins, CategoryGrid, CountGrid};
use crate::guide::color;
use crate::guide::count_scale::{CountColours, CountScale, Shading};
use crate::guide::legend::Legend;
use crate::guide::scale::Scale;
use crate::scene::{Color, Item, Raster, Rect, Role, Shape, Style};

/// Above this many rows, `mode = "auto"` counts rows in bins instead of drawing markers.
pub const AUTO_DENSITY_ROWS: u64 = 200_000;

/// How a point layer is drawn.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum PointMode {
    /// One marker per row.
    Points,
    /// Rows counted in small bins, each bin shaded by its count.
    Density,
    /// Points up to 200,000 rows, density above.
    #[default]
    Auto,
}

impl PointMode {
    /// Whether a layer of `rows` rows is drawn as a density.
    pub fn is_density(self, rows: u64) -> bool {
        match self {
            PointMode::Points => false,
            PointMode::Density => true,
            PointMode::Auto => rows > AUTO_DENSITY_ROWS,
        }
    }
}

/// How a density view shades its counts.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ShadingOption {
    /// In proportion to the count.
    Linear,
    /// By the logarithm of the count.
    Log,
    /// Histogram-equalized: each part of the ramp colours about as many bins (default).
    #[default]
    EqHist,
}

impl From<ShadingOption> for Shading {
    fn from(s: ShadingOption) -> Shading {
        match s {
            ShadingOption::Linear => Shading::Linear,
            ShadingOption::Log => Shading::Log,
            ShadingOption::EqHist => Shading::EqHist,
        }
    }
}

/// The look of a density view, from the spec with its defaults.
#[derive(Clone, Debug)]
pub struct DensityLook {
    /// The shading of the counts.
    pub shading: Shading,
    /// Side of a bin in pixels.
    pub bin_px: f64,
    /// How a bin is coloured.
    pub colours: CountColours,
    /// Bins an isolated non-empty bin grows by on each side.
    pub spread: usize,
}

/// Default side of a bin in pixels.
pub const DEFAULT_BIN_PX: f64 = 2.0;
/// Default opacity of the bins with the fewest rows.
pub const DEFAULT_MIN_ALPHA: f64 = 0.4;

impl DensityLook {
    /// The look from the spec's options (`None`: the defaults).
    pub fn new(
        shading: Option<ShadingOption>,
        bin_px: Option<f64>,
        min_alpha: Option<f64>,
        spread: Option<u32>,
    ) -> Self {
        let map = color::continuous("blues").unwrap_or_else(|| color::continuous("viridis").expect("viridis"));
        DensityLook {
            shading: shading.unwrap_or_default().into(),
            bin_px: bin_px.unwrap_or(DEFAULT_BIN_PX).clamp(1.0, 50.0),
            colours: CountColours {
                map: map.starting_at(0.3),
                fixed: None,
                min_alpha: min_alpha.unwrap_or(DEFAULT_MIN_ALPHA),
            },
            spread: spread.unwrap_or(0).min(5) as usize,
        }
    }

    /// The legend before the counts are known, for laying out the frame: its labels are no wider
    /// than those of a grid holding all `rows` rows in one bin.
    pub fn provisional_legend(&self, rows: u64) -> Legend {
        self.legend(CountScale::new(&[1, rows.max(1)], self.shading))
    }

    /// The legend of counts shaded by `scale`.
    pub fn legend(&self, scale: CountScale) -> Legend {
        Legend::Counts { title: "rows per bin".into(), colours: self.colours.clone(), scale }
    }

    /// The bins over `plot`, about [`DensityLook::bin_px`] pixels square, from the scales' values
    /// at the plot's edges (`None` when a scale maps the plot to no extent).
    pub fn bins(&self, plot: Rect, x: &Scale, y: &Scale) -> Option<(Bins, Bins)> {
        let n = |px: f64| ((px / self.bin_px).round() as usize).max(1);
        let log = |s: &Scale| matches!(s, Scale::Log(_));
        let xb = Bins::new(x.invert(plot.x)?, x.invert(plot.right())?, n(plot.w), log(x))?;
        let yb = Bins::new(y.invert(plot.bottom())?, y.invert(plot.y)?, n(plot.h), log(y))?;
        Some((xb, yb))
    }

    /// The grid as a raster over `plot` (empty bins transparent), and its counts' scale.
    pub fn raster(&self, grid: &CountGrid, plot: Rect, label: &str) -> (Item, CountScale) {
        let scale = CountScale::new(&grid.counts, self.shading);
        let item = self.paint(grid, plot, label, |_, count| {
            let colour = self.colours.at(scale.position(count as f64));
            [colour.r, colour.g, colour.b, colour.a]
        });
        (item, scale)
    }

    /// The non-empty bins of `grid` as a raster over `plot`, each in the colour `colour_of`
    /// gives for its cell and count (bin rows run from the bottom, raster rows from the top),
    /// isolated bins spread.
    fn paint(&self, grid: &CountGrid, plot: Rect, label: &str, colour_of: impl Fn(usize, u64) -> [u8; 4]) -> Item {
        let (nx, ny) = (grid.x.len(), grid.y.len());
        let mut rgba = vec![0u8; nx * ny * 4];
        for j in 0..ny {
            let row = (ny - 1 - j) * nx;
            for i in 0..nx {
                let cell = j * nx + i;
                let count = grid.counts[cell];
                if count > 0 {
                    rgba[(row + i) * 4..(row + i) * 4 + 4].copy_from_slice(&colour_of(cell, count));
                }
            }
        }
        spread_isolated(&mut rgba, nx, ny, self.spread);
        let raster =
            Raster { dest: plot, width: nx as u32, height: ny as u32, rgba: std::sync::Arc::new(rgba), smooth: false };
        Item::new(Role::DataMark, Shape::Image(raster), Style::default()).labelled(label)
    }
}

/// The grey a categorical density's legend draws its counts in (the bins' own colours are the
/// mix of their categories' colours).
const COUNT_INK: Color = Color { r: 80, g: 80, b: 80, a: 255 };

impl DensityLook {
    /// The same look for bins coloured by the mix of their categories: counts show as opacity.
    pub fn by_category(mut self) -> DensityLook {
        self.colours.fixed = Some(COUNT_INK);
        self
    }

    /// The categories' counts as a raster over `plot`: each bin in the mean of its categories'
    /// `colours` weighted by their counts (the last colour for rows of a missing category), its
    /// opacity from the shading of its total; and the totals' scale.
    pub fn mixed_raster(&self, grid: &CategoryGrid, colours: &[Color], plot: Rect, label: &str) -> (Item, CountScale) {
        let scale = CountScale::new(&grid.totals.counts, self.shading);
        let item = self.paint(&grid.totals, plot, label, |cell, total| {
            let counts = &grid.by_category[cell * grid.categories..(cell + 1) * grid.categories];
            let mut mix = [0.0f64; 3];
            for (&c, colour) in counts.iter().zip(colours) {
                for (m, v) in mix.iter_mut().zip([colour.r, colour.g, colour.b]) {
                    *m += c as f64 * f64::from(v);
                }
            }
            let [r, g, b] = mix.map(|m| (m / total as f64).round().clamp(0.0, 255.0) as u8);
            let a = (self.colours.alpha(scale.position(total as f64)) * 255.0).round() as u8;
            [r, g, b, a]
        });
        (item, scale)
    }
}

/// Grow every isolated non-empty pixel (no non-empty neighbour among its eight) into the empty
/// pixels up to `by` pixels away on each side, in its own colour, so a lone row is not lost as a
/// single dot. Pixels with neighbours are left alone: spreading them would blur real structure.
fn spread_isolated(rgba: &mut [u8], nx: usize, ny: usize, by: usize) {
    if by == 0 {
        return;
    }
    let filled = |rgba: &[u8], i: usize, j: usize| rgba[(j * nx + i) * 4 + 3] > 0;
    let mut lone = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            if !filled(rgba, i, j) {
                continue;
            }
            let (i0, i1, j0, j1) = (i.saturating_sub(1), (i + 1).min(nx - 1), j.saturating_sub(1), (j + 1).min(ny - 1));
            let neighbours = (j0..=j1).flat_map(|b| (i0..=i1).map(move |a| (a, b))).filter(|&(a, b)| (a, b) != (i, j));
            if neighbours.clone().all(|(a, b)| !filled(rgba, a, b)) {
                lone.push((i, j));
            }
        }
    }
    for (i, j) in lone {
        let colour: [u8; 4] = rgba[(j * nx + i) * 4..(j * nx + i) * 4 + 4].try_into().expect("4 bytes");
        for b in j.saturating_sub(by)..=(j + by).min(ny - 1) {
            for a in i.saturating_sub(by)..=(i + by).min(nx - 1) {
                if !filled(rgba, a, b) {
                    rgba[(b * nx + a) * 4..(b * nx + a) * 4 + 4].copy_from_slice(&colour);
                }
            }
        }
    }
}

/// The non-empty bins as derived rows: their edges in data units and their counts.
pub fn derived_bins(grid: &CountGrid, x_field: &str, y_field: &str) -> Derived {
    let nx = grid.x.len();
    let mut columns: [Vec<f64>; 5] = Default::default();
    for (k, &c) in grid.counts.iter().enumerate().filter(|(_, c)| **c > 0) {
        let (i, j) = (k % nx, k / nx);
        for (column, v) in
            columns.iter_mut().zip([grid.x.edge(i), grid.x.edge(i + 1), grid.y.edge(j), grid.y.edge(j + 1), c as f64])
        {
            column.push(v);
        }
    }
    let mut derived = Derived::over(Vec::new());
    let [x0, x1, y0, y1, count] = columns;
    derived.push(&format!("{x_field}_from"), DerivedColumn::Number(x0));
    derived.push(&format!("{x_field}_to"), DerivedColumn::Number(x1));
    derived.push(&format!("{y_field}_from"), DerivedColumn::Number(y0));
    derived.push(&format!("{y_field}_to"), DerivedColumn::Number(y1));
    derived.push("rows", DerivedColumn::Number(count));
    derived
}

#[cfg(test)]
mod tests {
    use super::*;

    fn alpha_grid(rgba: &[u8], nx: usize) -> Vec<String> {
        rgba.chunks(nx * 4).map(|row| row.chunks(4).map(|p| if p[3] > 0 { '#' } else { '.' }).collect()).collect()
    }

    #[test]
    fn only_isolated_pixels_spread() {
        let (nx, ny) = (7, 5);
        let mut rgba = vec![0u8; nx * ny * 4];
        for (i, j) in [(1, 1), (5, 3), (6, 3)] {
            rgba[(j * nx + i) * 4 + 3] = 255;
        }
        spread_isolated(&mut rgba, nx, ny, 1);
        assert_eq!(alpha_grid(&rgba, nx), ["###....", "###....", "###....", ".....##", "......."]);
    }

    #[test]
    fn mixed_bins_take_the_count_weighted_mean_colour_and_opacity_from_the_total() {
        let (x, y) = (Bins::new(0.0, 3.0, 3, false).unwrap(), Bins::new(0.0, 1.0, 1, false).unwrap());
        // Bin 0: 4 rows of red; bin 1: 1 red and 3 blue; bin 2: empty. Two levels and "missing".
        let mut totals = CountGrid::new(x, y);
        totals.counts = vec![4, 4, 0];
        let grid = CategoryGrid { totals, categories: 3, by_category: vec![4, 0, 0, 1, 3, 0, 0, 0, 0] };
        let colours = [Color::rgb(200, 0, 0), Color::rgb(0, 0, 200), Color::rgb(100, 100, 100)];
        let look = DensityLook::new(Some(ShadingOption::Linear), None, Some(0.5), None).by_category();
        let (item, _) = look.mixed_raster(&grid, &colours, Rect::new(0.0, 0.0, 30.0, 10.0), "m");
        let Shape::Image(raster) = &item.shape else { panic!("a raster") };
        assert_eq!(&raster.rgba[0..4], &[200, 0, 0, 255]);
        assert_eq!(&raster.rgba[4..8], &[50, 0, 150, 255]);
        assert_eq!(raster.rgba[11], 0, "an empty bin stays clear");
        // The count legend shows opacity in one grey.
        assert_eq!(look.colours.at(0.0).a, 128);
        assert_eq!(look.colours.at(0.0).r, look.colours.at(1.0).r);
    }

    #[test]
    fn derived_bins_list_the_non_empty_bins_with_their_edges() {
        let mut grid = CountGrid::new(Bins::new(0.0, 4.0, 4, false).unwrap(), Bins::new(10.0, 12.0, 2, false).unwrap());
        grid.add(&[0.5, 0.5, 3.9, 4.0], &[10.0, 10.5, 11.5, 12.0]);
        let derived = derived_bins(&grid, "a", "b");
        assert_eq!(derived.column("a_from"), Some(&DerivedColumn::Number(vec![0.0, 3.0])));
        assert_eq!(derived.column("b_to"), Some(&DerivedColumn::Number(vec![11.0, 12.0])));
        assert_eq!(derived.column("rows"), Some(&DerivedColumn::Number(vec![2.0, 2.0])));
    }
}
