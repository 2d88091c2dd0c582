//! What a drawn chart exposes for interaction: where its plots and axes are and the scales that
//! map data onto them, so that a pointer position can be turned back into data values (brushing,
//! hover, zoom). Filled by the kinds that the explorer brushes and navigates (the cartesian
//! kinds, `splom`, `parallel`, `hypertree`); empty for the others.

use crate::data::Column;
use crate::guide::layout::Frame;
use crate::guide::scale::Scale;
use crate::scene::{Point, Rect};

/// One positional scale of a plot and the column it places.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotScale {
    /// The column.
    pub field: String,
    /// Data to canvas units.
    pub scale: Scale,
}

impl PlotScale {
    /// `scale` as the scale of column `field`, if it places that column's own values: a
    /// continuous scale over numbers, or a band scale over text or over numbers whose bands are
    /// their values written out (so a brush's categories select the rows drawn in them). `None`
    /// for a band scale of binned or formatted values.
    pub fn of_column(field: &str, scale: &Scale, column: &Column) -> Option<PlotScale> {
        let places = match scale {
            Scale::Band(band) => match column.numbers() {
                None => column.categories().is_some(),
                Some(values) => bands_are_values(band.categories(), values),
            },
            _ => column.numbers().is_some(),
        };
        places.then(|| PlotScale { field: field.to_string(), scale: scale.clone() })
    }
}

/// Whether every band label is a number that `values` holds: one pass over the values, each
/// looked up among the (few) sorted labels.
fn bands_are_values(labels: &[String], values: &[f64]) -> bool {
    let Ok(mut wanted) = labels.iter().map(|c| c.trim().parse::<f64>()).collect::<Result<Vec<f64>, _>>() else {
        return false;
    };
    wanted.sort_by(f64::total_cmp);
    let mut found = vec![false; wanted.len()];
    for v in values {
        if let Ok(k) = wanted.binary_search_by(|w| w.total_cmp(v)) {
            found[k] = true;
        }
    }
    found.iter().all(|&f| f)
}

/// A cartesian plot area: a scatter chart's plot, one off-diagonal cell of a splom, the frame of
/// a histogram, bar, area, line, box, violin or heatmap chart.
#[derive(Clone, Debug, PartialEq)]
pub struct Plot {
    /// The plot area in canvas units.
    pub rect: Rect,
    /// Horizontal scale, when it places a column's values (a horizontal bar's summed lengths
    /// place none: a brush cannot select rows by them).
    pub x: Option<PlotScale>,
    /// Vertical scale (upwards), when it places a column's values (a histogram's counts, an
    /// area's stacked totals place none).
    pub y: Option<PlotScale>,
}

impl Plot {
    /// The plot of `frame`, brushed through the columns its x and y scales place (`None`: the
    /// axis places no column, e.g. counts or sums).
    pub fn of_frame(frame: &Frame, x: Option<(&str, &Column)>, y: Option<(&str, &Column)>) -> Plot {
        Plot {
            rect: frame.plot,
            x: x.and_then(|(field, column)| PlotScale::of_column(field, &frame.x, column)),
            y: y.and_then(|(field, column)| PlotScale::of_column(field, &frame.y, column)),
        }
    }

    /// A plot whose two scales place columns.
    pub fn xy(rect: Rect, x: PlotScale, y: PlotScale) -> Plot {
        Plot { rect, x: Some(x), y: Some(y) }
    }

    /// The scales that place columns: x, then y.
    pub fn scales(&self) -> impl Iterator<Item = &PlotScale> {
        self.x.iter().chain(self.y.iter())
    }
}

/// One vertical axis of parallel coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct ParallelAxis {
    /// The column.
    pub field: String,
    /// Horizontal position of the axis line.
    pub x: f64,
    /// Top of the axis.
    pub top: f64,
    /// Bottom of the axis.
    pub bottom: f64,
    /// Data to vertical canvas position.
    pub scale: Scale,
}

/// One node of a hyperbolic tree as drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct DiskNode {
    /// Position in the unit (Poincaré) disk after the view's transform.
    pub position: [f64; 2],
    /// Drawn radius in canvas units (0 when too small to draw).
    pub radius: f64,
    /// The node's label.
    pub label: String,
    /// The table row it came from, if any.
    pub row: Option<u32>,
}

/// A hyperbolic tree's disk on the canvas.
#[derive(Clone, Debug, PartialEq)]
pub struct Disk {
    /// Centre of the disk in canvas units.
    pub center: Point,
    /// Radius of the disk in canvas units.
    pub radius: f64,
    /// Every node, in node order.
    pub nodes: Vec<DiskNode>,
}

impl Disk {
    /// Canvas position of a disk point.
    pub fn to_canvas(&self, z: [f64; 2]) -> Point {
        Point::new(self.center.x + self.radius * z[0], self.center.y - self.radius * z[1])
    }

    /// Disk point under a canvas position (may lie outside the unit disk).
    pub fn to_disk(&self, p: Point) -> [f64; 2] {
        if self.radius <= 0.0 {
            return [0.0, 0.0];
        }
        [(p.x - self.center.x) / self.radius, (self.center.y - p.y) / self.radius]
    }
}

/// Cells of a drawn chart that are drawn again, whole, for another selection (a splom's
/// diagonal distributions), with the same code that drew them.
pub trait RedrawnCells: Send + Sync + std::fmt::Debug {
    /// The cell containing `p`, by index into the cells drawn.
    fn cell_at(&self, p: Point) -> Option<usize>;

    /// The data marks of every cell (in the order of [`RedrawnCells::cell_at`]) with the rows of
    /// `selected` (one flag per table row) lit.
    fn marks(&self, table: &crate::data::Table, name: &str, selected: &[bool]) -> Vec<Vec<crate::scene::Item>>;
}

/// The interactive geometry of one drawn chart.
#[derive(Clone, Debug, Default)]
pub struct Geometry {
    /// Cartesian plot areas (scatter: one; splom: one per drawn off-diagonal cell).
    pub plots: Vec<Plot>,
    /// Parallel-coordinate axes, left to right.
    pub axes: Vec<ParallelAxis>,
    /// A hyperbolic tree's disk.
    pub disk: Option<Disk>,
    /// A splom's diagonal cells (histograms or densities), to draw again for a selection.
    pub diagonals: Option<std::sync::Arc<dyn RedrawnCells>>,
}

impl Geometry {
    /// The geometry of a chart with one plot; empty when the plot places no column.
    pub fn of_plot(plot: Plot) -> Geometry {
        let plots = if plot.x.is_some() || plot.y.is_some() { vec![plot] } else { Vec::new() };
        Geometry { plots, ..Geometry::default() }
    }

    /// Whether the chart exposes nothing to interact with.
    pub fn is_empty(&self) -> bool {
        self.plots.is_empty() && self.axes.is_empty() && self.disk.is_none()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_bands_place_their_column_only_when_every_label_is_one_of_its_values() {
        let labels = |l: &[&str]| l.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let years = [1972.0, 1970.0, 1971.0, 1970.0];
        assert!(bands_are_values(&labels(&["1970", "1971", " 1972"]), &years));
        // A formatted label ("1.97k") or a binned one ("1970–1980") is not a value.
        assert!(!bands_are_values(&labels(&["1.97k", "1971"]), &years));
        assert!(!bands_are_values(&labels(&["1970–1980"]), &years));
        // A label whose value no row holds would select nothing where rows are drawn.
        assert!(!bands_are_values(&labels(&["1970", "1973"]), &years));
    }
}
