//! Marks: one module per chart kind, each turning a table and a chart spec into a [`Scene`],
//! grouped in family folders (`cartesian`, `grid`, `multivariate`, `hierarchy`, `network`,
//! `vector`, and `volume` for what comes next) and listed once in [`registry`].
//!
//! Pieces two kinds share — reading channels from the table, the non-finite policy, colour and
//! size encodings, frames, rasters, labels — live in [`shared`] (re-exported here by name), so
//! that kinds only describe their own geometry. No kind imports another kind.

pub mod cartesian;
pub mod facet;
pub mod grid;
pub mod hierarchy;
pub mod multivariate;
pub mod network;
pub mod registry;
pub mod shared;
pub mod vector;
pub mod volume;

pub use shared::{
    annotate, axis3d, bands, categorical, density, derived, encode, frame, geojson, geometry, gridded, grouped,
    highlight, level_labels, network_input, node_link, overplot, panel, plan_rows, raster, size, spread, tooltip,
    tree_input, trend, warning,
};

use std::fmt;

pub use derived::{Derived, DerivedColumn};
pub use registry::{ChartContext, FRAME_SIZE, KindInfo, Technique, technique};
pub use warning::Warning;

use crate::data::Table;
use crate::guide::layout::LayoutError;
use crate::scene::Scene;
use crate::selection::Highlight;
use crate::spec::{Chart, ChartKind, PathSeg};

/// A chart drawn: its scene, its derived geometry and the warnings raised on the way.
#[derive(Clone, Debug)]
pub struct ChartOutput {
    /// What to render.
    pub scene: Scene,
    /// Derived geometry in data coordinates (`--format csv`).
    pub derived: Derived,
    /// Non-fatal notes, e.g. rows dropped for non-finite values.
    pub warnings: Vec<Warning>,
    /// Derived geometry as a GeoJSON FeatureCollection in data coordinates (`--format geojson`),
    /// for kinds whose output is geometry (contour lines and bands).
    pub geojson: Option<geojson::ContourFeatures>,
    /// Surfaces in world coordinates (`--format glb`, `ply`, `obj`), for kinds that make them.
    pub meshes: Vec<crate::scene::WorldMesh>,
    /// What a volume chart showed of its volume, for the lint rules (`None` for other kinds).
    pub volume: Option<volume::VolumeFacts>,
    /// Where the plots, axes or disk are and their scales, for the explorer (empty for kinds
    /// that expose nothing to brush or navigate).
    pub geometry: geometry::Geometry,
}

/// Why a chart could not be drawn. Kinds raise it about the chart being drawn, with a path
/// relative to the chart; [`draw_in`] places it once, as it leaves the kind: the chart's name
/// before the message and `chart[i]` before the path.
#[derive(Clone, Debug, PartialEq)]
pub struct MarkError {
    /// What went wrong.
    pub message: String,
    /// How to fix it.
    pub hint: String,
    /// Where in the spec (e.g. `chart[2].x`; relative to the chart until placed).
    pub path: Vec<PathSeg>,
    /// Whether the chart's name and index have been added.
    placed: bool,
    /// Not a failure: a facet panel measured (see [`MarkError::measured`]).
    measured: bool,
}

impl fmt::Display for MarkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for MarkError {}

impl MarkError {
    /// An error about the chart being drawn, pointing at `keys` within it (or the whole chart
    /// if empty).
    pub fn at(keys: &[&str], message: impl Into<String>, hint: impl Into<String>) -> MarkError {
        let path = keys.iter().map(|k| PathSeg::Key(k.to_string())).collect();
        MarkError { message: message.into(), hint: hint.into(), path, placed: false, measured: false }
    }

    /// An error about the chart being drawn, pointing at `path` within it (keys and list
    /// positions, e.g. `annotate[2].x`).
    pub fn at_path(path: Vec<PathSeg>, message: impl Into<String>, hint: impl Into<String>) -> MarkError {
        MarkError { message: message.into(), hint: hint.into(), path, placed: false, measured: false }
    }

    /// Not a failure: a facet panel's measuring pass ([`panel::Panel::measuring`]) stops here,
    /// once its frame has recorded its axes and legends, without drawing its marks.
    pub(crate) fn measured() -> MarkError {
        MarkError { measured: true, ..MarkError::at(&[], "a facet panel measured, not drawn", "") }
    }

    /// Whether this is the stop of a facet panel's measuring pass, not a failure.
    pub(crate) fn is_measured(&self) -> bool {
        self.measured
    }

    /// A layout error of the chart being drawn.
    pub fn layout(error: LayoutError) -> MarkError {
        let (key, hint) = match &error {
            LayoutError::TooSmall { .. } => ("size", "make `size` larger or `font_size` smaller"),
            LayoutError::AspectNeedsLinear => ("aspect", "remove `aspect`, or use linear scales on both axes"),
            LayoutError::Scale { axis, .. } => {
                (if *axis == "x" { "x" } else { "y" }, "check the axis' scale and the column's values")
            }
        };
        MarkError::at(&[key], error.to_string(), hint)
    }

    /// The error placed in chart number `index`, named `name` (an error already placed is
    /// returned as it is).
    pub fn in_chart(mut self, index: usize, name: &str) -> MarkError {
        if !self.placed {
            self.message = format!("chart \"{name}\": {}", self.message);
            let mut path = vec![PathSeg::Key("chart".into()), PathSeg::Index(index)];
            path.append(&mut self.path);
            self.path = path;
            self.placed = true;
        }
        self
    }
}

/// Draw chart number `index` of a spec from its table, with the rows of `highlight` (the
/// chart's evaluated selection, if it names one) drawn in full colour.
pub fn draw(
    chart: &Chart,
    index: usize,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    draw_in(&ChartContext::new(chart, index, table).with_highlight(highlight))
}

/// Draw a chart bound to its data. Errors and notes leave with the chart's name (and errors
/// with its place in the spec) added here, once.
pub fn draw_in(cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
    let name = &cx.chart.name;
    let drawn = match &cx.chart.facet {
        Some(facet) => facet::draw(cx, facet),
        None => technique(&cx.chart.kind).draw(cx),
    };
    let mut output = drawn.map_err(|e| e.in_chart(cx.index, name))?;
    for warning in &mut output.warnings {
        if let Warning::Note(text) | Warning::OutsideDomain { text, .. } = warning {
            *text = format!("chart \"{name}\": {text}");
        }
    }
    Ok(output)
}

/// The spec keys of a chart kind whose values name columns (a string, a table with `field`, or
/// a list of those). Used to check column names even when the rest of the spec has errors.
pub fn column_keys(kind: &str) -> &'static [&'static str] {
    registry::kind_info(kind).map_or(&[], |k| k.column_keys)
}

/// The chart with `size` filled in by its kind's default ([`default_size`]) when the spec gives
/// none.
/// A faceted chart keeps `size` unset: its default depends on the number of panels.
pub fn with_default_size(chart: &Chart) -> Chart {
    let mut chart = chart.clone();
    if chart.facet.is_some() {
        return chart;
    }
    chart.size = Some(canvas_size(&chart));
    chart
}

/// The canvas size a kind draws at when the spec gives none.
pub fn default_size(kind: &ChartKind) -> [f64; 2] {
    technique(kind).default_size()
}

/// The canvas size a chart draws at from `table`: as [`canvas_size`], except that a faceted
/// chart without `size` grows with its panels.
pub fn canvas_size_in(chart: &Chart, table: &Table) -> [f64; 2] {
    match (&chart.facet, chart.size) {
        (Some(facet), None) => facet::default_size(chart, facet, table).unwrap_or_else(|_| canvas_size(chart)),
        _ => canvas_size(chart),
    }
}

/// The canvas size a chart draws at: its `size`, else its kind's default (for a faceted chart,
/// whose default depends on its data, see [`canvas_size_in`]).
pub fn canvas_size(chart: &Chart) -> [f64; 2] {
    chart.size.unwrap_or_else(|| default_size(&chart.kind))
}
