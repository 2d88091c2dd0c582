//! What the network kinds (graph, linkmap) share: the network read from the edge table and the
//! optional node table, node labels, and node positions from the chosen layout, fitted into
//! the plot.

use crate::data::network::{EdgeColumns, Network};
use crate::data::{Column, Table};
use crate::layout::{circular, force, layered};
use crate::mark::warning::Warning;
use crate::mark::{MarkError, encode};
use crate::spec::{Chart, GraphLayout, NodeTable};

/// A network with its node table and labels.
pub struct NetworkInput<'t> {
    /// The network.
    pub network: Network,
    /// The node table, when the spec names one.
    pub nodes: Option<&'t Table>,
    /// Each node's label.
    pub labels: Vec<String>,
    /// Non-fatal notes (dropped rows, self-loops).
    pub warnings: Vec<Warning>,
}

/// Most edge rows a graph or linkmap chart reads: layouts and the drawing grow with them, and
/// past this many a node-link view is a solid blot (aggregate parallel edges into weights).
pub const MAX_EDGE_ROWS: usize = 250_000;

/// Read the network of a graph or linkmap chart. Nodes without a link are left out (with a
/// warning) unless `nodes.isolated` or, when the spec does not say, `keep_isolated` keeps them.
pub fn network_of<'t>(
    chart: &Chart,
    (source, target, weight): (&str, &str, Option<&str>),
    (node_spec, keep_isolated): (Option<&NodeTable>, bool),
    edges: &Table,
    nodes: Option<&'t Table>,
) -> Result<NetworkInput<'t>, MarkError> {
    if edges.rows > MAX_EDGE_ROWS {
        return Err(MarkError::at(
            &["data"],
            format!("the edge table has {} rows but a network chart draws at most {MAX_EDGE_ROWS}", edges.rows),
            "aggregate parallel edges into weights first, e.g. transform = [{ aggregate = { n = \"count()\" }, \
             groupby = [\"source\", \"target\"] }] with weight = \"n\", or filter the edges",
        ));
    }
    let source = encode::column(chart, "source", source, edges)?;
    let target = encode::column(chart, "target", target, edges)?;
    let weight = match weight {
        Some(w) => {
            let col = encode::column(chart, "weight", w, edges)?;
            encode::require_numeric("weight", col, "an edge weight", "weigh edges by a numeric column")?;
            Some(col)
        }
        None => None,
    };
    let node_ids: Option<(usize, &Column)> = match (node_spec, nodes) {
        (Some(spec), Some(table)) => Some((table.rows, node_column(spec, "id", &spec.id, table)?)),
        (Some(spec), None) => {
            return Err(MarkError::at(
                &["nodes", "data"],
                format!("node data \"{}\" was not loaded", spec.data),
                "check the name of the node table's data source",
            ));
        }
        _ => None,
    };
    let network = Network::from_tables(edges.rows, EdgeColumns { source, target, weight }, node_ids)
        .map_err(|e| MarkError::at(&["source"], format!("{e}"), e.hint()))?;
    let mut warnings = Vec::new();
    let network = match node_spec.and_then(|s| s.isolated).unwrap_or(keep_isolated) {
        true => network,
        false => {
            let (network, left_out) = network.without_isolated();
            if left_out > 0 {
                warnings.push(Warning::from(format!(
                    "{left_out} nodes without a link were left out (`nodes.isolated = true` draws them)"
                )));
            }
            network
        }
    };
    if network.missing_endpoints > 0 {
        warnings.push(Warning::from(format!(
            "{} edges without a source or target were left out",
            network.missing_endpoints
        )));
    }
    if network.bad_weights > 0 {
        warnings.push(Warning::from(format!("{} edges with a missing weight were left out", network.bad_weights)));
    }
    if network.self_loops > 0 {
        warnings.push(Warning::from(format!("{} self-loops are not drawn", network.self_loops)));
    }
    let labels = match (node_spec.and_then(|s| s.label.as_deref().map(|l| (s, l))), nodes) {
        (Some((spec, field)), Some(table)) => {
            let column = node_column(spec, "label", field, table)?;
            network
                .graph
                .node_weights()
                .map(|n| n.row.and_then(|r| column.key(r as usize)).unwrap_or_else(|| n.id.clone()))
                .collect()
        }
        _ => network.graph.node_weights().map(|n| n.id.clone()).collect(),
    };
    Ok(NetworkInput { network, nodes, labels, warnings })
}

/// A column of the node table, or an error pointing at `nodes.KEY`.
pub fn node_column<'t>(spec: &NodeTable, key: &str, field: &str, table: &'t Table) -> Result<&'t Column, MarkError> {
    table.column(field).ok_or_else(|| {
        let (message, hint) = encode::missing_column(&spec.data, field, table);
        MarkError::at(&["nodes", key], message, hint)
    })
}

/// Node positions in layout units (y down) and, for the layered layout, each edge's path.
pub struct Placement {
    /// One position per node.
    pub positions: Vec<[f64; 2]>,
    /// Per edge (in edge order): bend points from source to target, when the layout routes
    /// edges; empty for straight edges.
    pub paths: Vec<Vec<[f64; 2]>>,
    /// Keep the aspect ratio when fitting into the plot (false for layers).
    pub uniform: bool,
    /// What the caption says about the layout.
    pub description: String,
}

/// Place the nodes with `layout`.
pub fn place(
    layout: GraphLayout,
    seed: u64,
    input: &NetworkInput,
    node_spec: Option<&NodeTable>,
) -> Result<Placement, MarkError> {
    let network = &input.network;
    let n = network.node_count();
    let edges = network.edge_pairs();
    let fail = |e: &dyn std::fmt::Display| MarkError::at(&["layout"], format!("{e}"), "try another `layout`");
    match layout {
        GraphLayout::Force => {
            let options = force::ForceOptions { seed, ..force::ForceOptions::default() };
            let weights = network.weights();
            let positions = force::force_layout(n, &edges, Some(&weights), &options).map_err(|e| fail(&e))?;
            let description = format!("force-directed layout (seed {seed})");
            Ok(Placement { positions, paths: Vec::new(), uniform: true, description })
        }
        GraphLayout::Circular => {
            let positions =
                circular::circular_layout(n, &edges, &circular::CircularOptions::default()).map_err(|e| fail(&e))?;
            Ok(Placement { positions, paths: Vec::new(), uniform: true, description: "circular layout".into() })
        }
        GraphLayout::Layered => {
            let layout =
                layered::layered_layout(n, &edges, &layered::LayeredOptions::default()).map_err(|e| fail(&e))?;
            let reversed = layout.reversed.iter().filter(|r| **r).count();
            let mut description = format!("layered layout, {} layers", layout.layers.iter().max().map_or(0, |l| l + 1));
            if reversed > 0 {
                description.push_str(&format!(", {reversed} edges reversed to break cycles (they point up)"));
            }
            Ok(Placement { positions: layout.positions, paths: layout.edge_paths, uniform: false, description })
        }
        GraphLayout::Given => {
            let positions = given_positions(input, node_spec)?;
            Ok(Placement { positions, paths: Vec::new(), uniform: true, description: "given positions".into() })
        }
    }
}

/// Positions from the node table's `x` and `y` columns (y up, as in maps and plots).
fn given_positions(input: &NetworkInput, node_spec: Option<&NodeTable>) -> Result<Vec<[f64; 2]>, MarkError> {
    let needs = || {
        MarkError::at(
            &["layout"],
            format!("`layout = \"given\"` needs a node table with `x` and `y` columns"),
            "add `nodes = { data = \"...\", id = \"...\", x = \"lon\", y = \"lat\" }`",
        )
    };
    let (Some(spec), Some(table)) = (node_spec, input.nodes) else { return Err(needs()) };
    let (Some(xf), Some(yf)) = (spec.x.as_deref(), spec.y.as_deref()) else { return Err(needs()) };
    let x = node_column(spec, "x", xf, table)?;
    let y = node_column(spec, "y", yf, table)?;
    let (Some(xs), Some(ys)) = (x.numbers(), y.numbers()) else {
        return Err(MarkError::at(
            &["nodes"],
            format!("node positions `{xf}` and `{yf}` must be numeric"),
            "name numeric columns in `nodes.x` and `nodes.y`",
        ));
    };
    input
        .network
        .graph
        .node_weights()
        .map(|node| {
            let at = node.row.map(|r| (xs.get(r as usize).copied(), ys.get(r as usize).copied()));
            match at {
                Some((Some(px), Some(py))) if px.is_finite() && py.is_finite() => Ok([px, -py]),
                _ => Err(MarkError::at(
                    &["nodes"],
                    format!("node `{}` has no finite position in `{xf}`, `{yf}`", node.id),
                    "give every node a position, or use `layout = \"force\"`",
                )),
            }
        })
        .collect()
}
