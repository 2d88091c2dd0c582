//! `linkmap`: SeeNet-style views of a network's link statistics (Becker, Eick & Wilks 1995)
//! that ignore geography. In `links` mode, nodes are placed by a layout or given positions and
//! links are drawn thin to thick, light to dark, in order of their statistic, so heavy links
//! sit on top; in `matrix` mode, an adjacency matrix with rows and columns ordered by
//! clustering, each cell coloured by the statistic, for networks too dense for lines.

use crate::data::Table;
use crate::guide::axis::title_with_unit;
use crate::guide::layout::LayoutError;
use crate::guide::legend::Legend;
use crate::layout::matrix_order::cluster_order;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::network_input::{NetworkInput, network_of};
use crate::mark::node_link::{Look, draw_network};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, encode, frame, with_default_size};
use crate::scene::{Anchor, Baseline, Color, Item, Point, Rect, Role, Shape, Style, Text};
use crate::spec::{Chart, GraphLayout, NodeTable, defaults};
use crate::text::measure;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "linkmap"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct LinkmapOptions {
    /// Column of link sources (node ids).
    #[schemars(example = &"from")]
    pub source: String,
    /// Column of link targets (node ids).
    #[schemars(example = &"to")]
    pub target: String,
    /// Numeric column of the link statistic (traffic, calls, flow): width and colour.
    #[schemars(example = &"traffic")]
    pub weight: String,
    /// Unit of `weight`, shown in the legend.
    #[serde(default)]
    pub unit: Option<String>,
    /// Node table with ids and attributes, or given positions (`x`, `y`).
    #[serde(default)]
    pub nodes: Option<NodeTable>,
    /// `links` (default) or `matrix`.
    #[serde(default)]
    pub mode: Option<LinkMode>,
    /// Node placement in `links` mode: `force` (default), `circular`, `layered` or `given`.
    #[serde(default)]
    pub layout: Option<GraphLayout>,
    /// Seed of the force layout (default 1).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Continuous scheme of the link statistic (default `viridis_r`: low values light, high dark).
    #[serde(default)]
    pub scheme: Option<String>,
    /// Label nodes (default: when there are at most 150).
    #[serde(default)]
    pub labels: Option<bool>,
}

/// How a link view shows the network.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LinkMode {
    /// Nodes and links, links drawn thin to thick in order of their statistic.
    Links,
    /// An adjacency matrix with rows and columns ordered by clustering.
    Matrix,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [760.0, 640.0];
/// Canvas size of the matrix when the spec gives none: room for a square matrix with its labels
/// beside the colour bar.
pub(super) const MATRIX_SIZE: [f64; 2] = [700.0, 640.0];
/// Default scheme: low values light, high values dark.
const DEFAULT_SCHEME: &str = "viridis_r";
/// Fill of matrix cells without a link.
const EMPTY_CELL: Color = Color::rgb(0xf3, 0xf3, 0xf3);

/// Draw a link view.
pub fn draw(
    chart: &Chart,
    options: &LinkmapOptions,
    table: &Table,
    nodes: Option<&Table>,
) -> Result<ChartOutput, MarkError> {
    let mode = options.mode.unwrap_or(LinkMode::Links);
    let chart = &with_default_size(chart);
    let channels = (options.source.as_str(), options.target.as_str(), Some(options.weight.as_str()));
    let input = network_of(chart, channels, (options.nodes.as_ref(), false), table, nodes)?;
    match mode {
        LinkMode::Links => {
            let look = Look {
                layout: options.layout.unwrap_or(GraphLayout::Force),
                seed: options.seed.unwrap_or(1),
                directed: false,
                labels: options.labels,
                node_radius: None,
                weight: Some((options.weight.as_str(), options.unit.as_deref())),
                scheme: options.scheme.as_deref().unwrap_or(DEFAULT_SCHEME),
                widths: (0.3, 7.0),
                fade: (0.0, true),
                nodes: options.nodes.as_ref(),
            };
            draw_network(chart, input, &look)
        }
        LinkMode::Matrix => draw_matrix(chart, options, input),
    }
}

/// The adjacency matrix: row = source, column = target, in clustering order.
fn draw_matrix(chart: &Chart, options: &LinkmapOptions, input: NetworkInput) -> Result<ChartOutput, MarkError> {
    let network = &input.network;
    let n = network.node_count();
    let pairs = network.edge_pairs();
    let weights = network.weights();
    let weighted: Vec<(u32, u32, f64)> = pairs.iter().zip(&weights).map(|(&(s, t), &w)| (s, t, w)).collect();
    let order =
        cluster_order(n, &weighted).map_err(|e| MarkError::at(&["mode"], format!("{e}"), "use `mode = \"links\"`"))?;
    let mut slot = vec![0usize; n];
    for (k, &node) in order.iter().enumerate() {
        slot[node] = k;
    }
    // Sum repeated links into one cell.
    let mut cells: std::collections::BTreeMap<(usize, usize), (f64, u32)> = std::collections::BTreeMap::new();
    for ((&(s, t), &w), e) in pairs.iter().zip(&weights).zip(network.graph.raw_edges()) {
        let cell = cells.entry((slot[s as usize], slot[t as usize])).or_insert((0.0, e.weight.row));
        cell.0 += w;
    }
    let map = encode::continuous_map(&["scheme"], Some(options.scheme.as_deref().unwrap_or(DEFAULT_SCHEME)))?;
    let (lo, hi) = encode::finite_extent(cells.values().map(|c| c.0)).unwrap_or((0.0, 1.0));
    let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 0.5, hi + 0.5) };
    let legend = Legend::ColorBar {
        title: title_with_unit(&options.weight, options.unit.as_deref()),
        map: map.clone(),
        domain: (lo, hi),
    };

    let mut chart = chart.clone();
    chart.caption.get_or_insert_with(|| {
        format!("{n} nodes, {} links; rows: source, columns: target, both ordered by clustering.", cells.len())
    });
    let chart = &chart;
    let canvas = frame::PanelCanvas::new(chart, vec![legend]);
    let theme = &canvas.theme;
    let m = theme.margin;
    let width = canvas.width - 2.0 * m - canvas.legend_room();
    let label_size = theme.label_size * 0.85;
    let widest = input.labels.iter().map(|l| measure(l, label_size).width).fold(0.0, f64::max).min(140.0);
    let side_room = (width - widest - 6.0).min(canvas.room - widest - 6.0);
    // The matrix takes all the room (cells need not be whole pixels: their edges are), centred
    // across the width left of the legend.
    let cell = (side_room / n as f64).max(0.5);
    let side = cell * n as f64;
    if side_room < 40.0 {
        let error = LayoutError::TooSmall { plot_width: width, plot_height: canvas.room };
        return Err(MarkError::layout(error));
    }
    let show_labels = cell >= label_size * 0.9;
    let offset = if show_labels { widest + 6.0 } else { 0.0 };
    let spare = (width - offset - side).max(0.0);
    let (x0, y0) = ((m + offset + spare / 2.0).round(), (canvas.top() + offset).round());
    // Cell k spans edge(k)..edge(k + 1): whole pixels once cells are 2 px or more, so
    // neighbouring cells meet without anti-aliased seams.
    let edge = |k: usize| if cell >= 2.0 { (k as f64 * cell).round() } else { k as f64 * cell };

    let mut items = vec![canvas.background()];
    items.push(Item::new(Role::Grid, Shape::Rect(Rect::new(x0, y0, edge(n), edge(n))), Style::fill(EMPTY_CELL)));
    for (&(r, c), &(w, row)) in &cells {
        let rect = Rect::new(x0 + edge(c), y0 + edge(r), edge(c + 1) - edge(c), edge(r + 1) - edge(r));
        let color = map.at((w - lo) / (hi - lo));
        items.push(Item::new(Role::DataMark, Shape::Rect(rect), Style::fill(color)).with_rows(vec![row]));
    }
    if show_labels {
        for (k, &node) in order.iter().enumerate() {
            let label = crate::guide::legend::truncate_to_width(&input.labels[node], widest, label_size);
            let mid = k as f64 * cell + cell / 2.0;
            let text = |at: Point, anchor: Anchor, angle: f64| {
                Item::text(
                    Role::TickLabel,
                    Text {
                        at,
                        content: label.clone(),
                        size: label_size,
                        anchor,
                        baseline: Baseline::Middle,
                        angle,
                        color: theme.text,
                    },
                )
            };
            items.push(text(Point::new(x0 - 4.0, y0 + mid), Anchor::End, 0.0));
            items.push(text(Point::new(x0 + mid, y0 - 4.0), Anchor::Start, -90.0));
        }
    }

    let ids: Vec<String> = network.graph.node_weights().map(|w| w.id.clone()).collect();
    let mut d = Derived::default();
    d.push("source", DerivedColumn::Text(cells.keys().map(|&(r, _)| ids[order[r]].clone()).collect()));
    d.push("target", DerivedColumn::Text(cells.keys().map(|&(_, c)| ids[order[c]].clone()).collect()));
    d.push(&options.weight, DerivedColumn::Number(cells.values().map(|c| c.0).collect()));
    d.push("row", DerivedColumn::Number(cells.keys().map(|&(r, _)| r as f64).collect()));
    d.push("column", DerivedColumn::Number(cells.keys().map(|&(_, c)| c as f64).collect()));
    let scene = canvas.scene(chart, items, None);
    Ok(ChartOutput {
        scene,
        derived: d,
        warnings: input.warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// `kind = "linkmap"`.
pub static KIND: KindInfo = KindInfo::new("linkmap", &["source", "target", "weight"])
    .conventions(defaults::NETWORK)
    .sized(DEFAULT_SIZE)
    .taking_aspect();

impl Technique for LinkmapOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.nodes)
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }

    fn node_data(&self) -> Option<&str> {
        self.nodes.as_ref().map(|n| n.data.as_str())
    }

    fn default_size(&self) -> [f64; 2] {
        if self.mode == Some(LinkMode::Matrix) { MATRIX_SIZE } else { DEFAULT_SIZE }
    }
}
