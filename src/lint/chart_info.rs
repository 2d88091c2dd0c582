//! What a chart's spec says about its encodings, in one shape for every kind: its cartesian
//! axes and its colour encodings. Rules read these instead of matching every kind themselves.

use crate::spec::{ChannelOptions, Chart, ChartKind, ColorOptions, ScaleKind};

/// A cartesian axis of a chart, as its spec declares it.
#[derive(Clone, Debug)]
pub struct AxisSpec {
    /// The axis's name in the scene (`"x axis"` or `"y axis"`), matching its items' labels.
    pub name: &'static str,
    /// The spec key of the channel, relative to the chart (`"x"`, `"y"`, `"y[1]"` is not used:
    /// a line chart's several y columns share the key `"y"`).
    pub key: &'static str,
    /// The channel's options (defaults for a bare column name).
    pub options: ChannelOptions,
}

impl AxisSpec {
    /// The scale kind the spec asks for, if it names one.
    pub fn scale(&self) -> Option<ScaleKind> {
        self.options.scale
    }
}

/// The x and y axes of the kinds drawn on one cartesian frame (scatter, line, bar, interp1d, contour,
/// image, section, scattered, flow). Other kinds (small multiples, hierarchies, networks,
/// polar layouts) return an empty list. A line chart's y axis is its first y column.
pub fn cartesian_axes(chart: &Chart) -> Vec<AxisSpec> {
    let pair = |x: &crate::spec::Channel, y: &crate::spec::Channel| {
        vec![
            AxisSpec { name: "x axis", key: "x", options: x.options() },
            AxisSpec { name: "y axis", key: "y", options: y.options() },
        ]
    };
    match &chart.kind {
        ChartKind::Scatter(o) => pair(&o.x, &o.y),
        ChartKind::Line(o) => match o.y.as_slice().first() {
            Some(y) => pair(&o.x, y),
            None => Vec::new(),
        },
        ChartKind::Bar(o) => {
            // Bars place every x value in a band, numbers included.
            let mut axes = pair(&o.x, &o.y);
            if let Some(x) = axes.first_mut() {
                x.options.scale = Some(ScaleKind::Band);
            }
            axes
        }
        ChartKind::Interp1d(o) => pair(&o.x, &o.y),
        ChartKind::Contour(o) => pair(&o.x, &o.y),
        ChartKind::Image(o) => pair(&o.x, &o.y),
        ChartKind::Scattered(o) => pair(&o.x, &o.y),
        ChartKind::Flow(o) => pair(&o.x, &o.y),
        _ => Vec::new(),
    }
}

/// A colour encoding of a chart: the spec key and its options.
#[derive(Clone, Debug)]
pub struct ColourSpec {
    /// The spec key, relative to the chart (`"color"`, `"z"`).
    pub key: &'static str,
    /// The encoding's options (defaults for a bare column name).
    pub options: ColorOptions,
}

/// The colour encodings a chart's spec declares by column (`color = ...` or a field `z`
/// coloured by a map). Kinds that colour by a fixed rule (treemap branches, link weights, flow
/// speed) report their `scheme` through [`scheme_of`] instead.
pub fn colour_encodings(chart: &Chart) -> Vec<ColourSpec> {
    let colour = |c: &Option<crate::spec::ColorChannel>| {
        c.as_ref().map(|c| ColourSpec { key: "color", options: c.options() }).into_iter().collect::<Vec<_>>()
    };
    let z = |c: &crate::spec::ColorChannel| vec![ColourSpec { key: "z", options: c.options() }];
    match &chart.kind {
        ChartKind::Scatter(o) => colour(&o.color),
        ChartKind::Line(o) => colour(&o.color),
        ChartKind::Bar(o) => colour(&o.color),
        ChartKind::Splom(o) => colour(&o.color),
        ChartKind::Parallel(o) => colour(&o.color),
        ChartKind::Daisy(o) => colour(&o.color),
        ChartKind::Faces(o) => colour(&o.color),
        ChartKind::Treemap(o) => colour(&o.color),
        ChartKind::Hypertree(o) => colour(&o.color),
        ChartKind::Contour(o) => z(&o.z),
        ChartKind::Image(o) => z(&o.z),
        ChartKind::Scattered(o) => z(&o.z),
        ChartKind::Surface(o) => z(&o.z),
        ChartKind::Hyperslice(o) => z(&o.z),
        _ => Vec::new(),
    }
}

/// The chart-level `scheme` of kinds that have one outside a colour encoding, with its key.
pub fn scheme_of(chart: &Chart) -> Option<(&'static str, &str)> {
    let s = match &chart.kind {
        ChartKind::Line(o) => o.scheme.as_deref(),
        ChartKind::Interp1d(o) => o.scheme.as_deref(),
        ChartKind::Section(o) => o.scheme.as_deref(),
        ChartKind::Segments(o) => o.scheme.as_deref(),
        ChartKind::Treemap(o) => o.scheme.as_deref(),
        ChartKind::Hypertree(o) => o.scheme.as_deref(),
        ChartKind::Graph(o) => o.scheme.as_deref(),
        ChartKind::Linkmap(o) => o.scheme.as_deref(),
        ChartKind::Flow(o) => o.scheme.as_deref(),
        _ => None,
    }?;
    Some(("scheme", s))
}
