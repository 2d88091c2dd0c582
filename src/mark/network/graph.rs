//! `graph`: a node-link diagram. Nodes are placed by a force-directed (multilevel Barnes–Hut),
//! circular, layered (Sugiyama) or given layout; node size and colour come from node-table
//! columns, edge width and colour from the weight; labels are placed greedily, biggest nodes
//! first, and left out where they would overlap.
//!
//! [`draw_network`] is the drawing core that `linkmap`'s link mode shares.

use crate::data::Table;
use crate::mark::network_input::network_of;
use crate::mark::node_link::{Look, draw_network};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, with_default_size};
use crate::spec::{Chart, GraphLayout, NodeTable, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "graph"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct GraphOptions {
    /// Column of edge sources (node ids).
    #[schemars(example = &"from")]
    pub source: String,
    /// Column of edge targets (node ids).
    #[schemars(example = &"to")]
    pub target: String,
    /// Numeric column of edge weights: edge width and colour (default: all edges alike).
    #[serde(default)]
    pub weight: Option<String>,
    /// Node table with ids and attributes (default: nodes are the edges' endpoints).
    #[serde(default)]
    pub nodes: Option<NodeTable>,
    /// `force` (default), `circular`, `layered` or `given`.
    #[serde(default)]
    pub layout: Option<GraphLayout>,
    /// Seed of the force layout (default 1): the same seed gives the same picture.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Draw arrowheads (default: true for `layered`, false otherwise).
    #[serde(default)]
    pub directed: Option<bool>,
    /// Label nodes (default: when there are at most 150); labels that would overlap are left out.
    #[serde(default)]
    pub labels: Option<bool>,
    /// Node radius in pixels, at most 200, without a size column (default from the node count).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 200))]
    pub node_radius: Option<f64>,
    /// Continuous scheme of edge colours by weight (default `greys`).
    #[serde(default)]
    pub scheme: Option<String>,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [760.0, 620.0];
/// Draw a graph.
pub fn draw(
    chart: &Chart,
    options: &GraphOptions,
    table: &Table,
    nodes: Option<&Table>,
) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let channels = (options.source.as_str(), options.target.as_str(), options.weight.as_deref());
    let layout = options.layout.unwrap_or(GraphLayout::Force);
    let keep_isolated = layout != GraphLayout::Given;
    let input = network_of(chart, channels, (options.nodes.as_ref(), keep_isolated), table, nodes)?;
    let look = Look {
        layout,
        seed: options.seed.unwrap_or(1),
        directed: options.directed.unwrap_or(layout == GraphLayout::Layered),
        labels: options.labels,
        node_radius: options.node_radius,
        weight: options.weight.as_deref().map(|w| (w, None)),
        scheme: options.scheme.as_deref().unwrap_or("greys"),
        widths: (0.6, 4.0),
        fade: (0.25, false),
        nodes: options.nodes.as_ref(),
    };
    draw_network(chart, input, &look)
}

/// `kind = "graph"`.
pub static KIND: KindInfo = KindInfo::new("graph", &["source", "target", "weight"])
    .conventions(defaults::NETWORK)
    .sized(DEFAULT_SIZE)
    .taking_aspect();

impl Technique for GraphOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.nodes)
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }

    fn color_channel_mut(&mut self) -> Option<(&mut crate::spec::ColorChannel, Option<String>)> {
        let nodes = self.nodes.as_mut()?;
        nodes.color.as_mut().map(|c| (c, Some(nodes.data.clone())))
    }

    fn node_data(&self) -> Option<&str> {
        self.nodes.as_ref().map(|n| n.data.as_str())
    }
}
