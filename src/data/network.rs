//! Networks from tables: an edge table (source, target, optional weight) and an optional node
//! table (id plus attributes), held in a petgraph [`DiGraph`].
//!
//! Rules, each reported so a chart can warn: rows with a missing endpoint or a non-finite
//! weight are dropped; self-loops are kept in the graph but layouts ignore them. A negative
//! weight, a duplicate node id, or (with a node table) an endpoint the node table lacks is an
//! error.

use std::collections::HashMap;
use std::fmt;

use petgraph::graph::{DiGraph, NodeIndex};

use super::Column;

/// A node: its id and the node-table row it came from (none without a node table).
#[derive(Clone, Debug, PartialEq)]
pub struct NodeInfo {
    /// The id as text (numbers in shortest form).
    pub id: String,
    /// Row in the node table.
    pub row: Option<u32>,
}

/// An edge: the edge-table row it came from and its weight (1 without a weight column).
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeInfo {
    /// Row in the edge table.
    pub row: u32,
    /// Weight (link statistic), finite and ≥ 0.
    pub weight: f64,
}

/// A network read from tables.
#[derive(Clone, Debug)]
pub struct Network {
    /// The directed graph (undirected kinds ignore direction).
    pub graph: DiGraph<NodeInfo, EdgeInfo>,
    /// Edge rows dropped for a missing endpoint.
    pub missing_endpoints: usize,
    /// Edge rows dropped for a non-finite weight.
    pub bad_weights: usize,
    /// Edges from a node to itself.
    pub self_loops: usize,
}

/// Why the tables are not a network.
#[derive(Clone, Debug, PartialEq)]
pub enum NetworkError {
    /// Neither edges nor nodes.
    Empty,
    /// Two node-table rows carry the same id.
    DuplicateNode {
        /// The id.
        id: String,
        /// First row.
        first: u32,
        /// Second row.
        second: u32,
    },
    /// A node-table row has no id.
    MissingNodeId {
        /// The row.
        row: u32,
    },
    /// An edge names a node the node table does not have.
    DanglingEndpoint {
        /// Edge-table row.
        row: u32,
        /// `source` or `target`.
        end: &'static str,
        /// The id it names.
        id: String,
    },
    /// A weight below zero.
    NegativeWeight {
        /// Edge-table row.
        row: u32,
        /// The weight.
        value: f64,
    },
}

impl fmt::Display for NetworkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => write!(f, "the network has no nodes and no edges"),
            Self::DuplicateNode { id, first, second } => {
                write!(f, "node id `{id}` appears twice in the node table (rows {} and {})", first + 1, second + 1)
            }
            Self::MissingNodeId { row } => write!(f, "node-table row {} has no id", row + 1),
            Self::DanglingEndpoint { row, end, id } => {
                write!(f, "edge row {} names {end} `{id}`, which is not in the node table", row + 1)
            }
            Self::NegativeWeight { row, value } => write!(f, "edge row {} has weight {value}, below zero", row + 1),
        }
    }
}

impl std::error::Error for NetworkError {}

impl NetworkError {
    /// How to fix it.
    pub fn hint(&self) -> &'static str {
        match self {
            Self::Empty => "give the edge table at least one row",
            Self::DuplicateNode { .. } => "make node ids unique",
            Self::MissingNodeId { .. } => "fill in every node's id",
            Self::DanglingEndpoint { .. } => "add the node to the node table, or fix the edge's id",
            Self::NegativeWeight { .. } => "weights are link statistics (traffic, counts) and must be ≥ 0",
        }
    }
}

/// The edges' columns.
#[derive(Clone, Copy, Debug)]
pub struct EdgeColumns<'t> {
    /// Source node ids.
    pub source: &'t Column,
    /// Target node ids.
    pub target: &'t Column,
    /// Weights, if any.
    pub weight: Option<&'t Column>,
}

impl Network {
    /// Build the network from `edges` (with `rows` rows) and, optionally, a node table's id
    /// column (with its row count). Without a node table, nodes are the endpoints in order of
    /// first appearance; with one, the node table's order, and every endpoint must be in it.
    pub fn from_tables(
        rows: usize,
        edges: EdgeColumns,
        nodes: Option<(usize, &Column)>,
    ) -> Result<Network, NetworkError> {
        let mut graph: DiGraph<NodeInfo, EdgeInfo> = DiGraph::new();
        let mut index: HashMap<String, NodeIndex> = HashMap::new();
        let closed = nodes.is_some();
        if let Some((count, ids)) = nodes {
            for row in 0..count {
                let id = ids.key(row).ok_or(NetworkError::MissingNodeId { row: row as u32 })?;
                if let Some(&first) = index.get(&id) {
                    let first = graph[first].row.unwrap_or(0);
                    return Err(NetworkError::DuplicateNode { id, first, second: row as u32 });
                }
                let node = graph.add_node(NodeInfo { id: id.clone(), row: Some(row as u32) });
                index.insert(id, node);
            }
        }
        let weights = edges.weight.and_then(Column::numbers);
        let (mut missing_endpoints, mut bad_weights, mut self_loops) = (0, 0, 0);
        for row in 0..rows {
            let (Some(s), Some(t)) = (edges.source.key(row), edges.target.key(row)) else {
                missing_endpoints += 1;
                continue;
            };
            let weight = match weights {
                Some(w) => w.get(row).copied().unwrap_or(f64::NAN),
                None => 1.0,
            };
            if !weight.is_finite() {
                bad_weights += 1;
                continue;
            }
            if weight < 0.0 {
                return Err(NetworkError::NegativeWeight { row: row as u32, value: weight });
            }
            let mut endpoint = |id: String, end: &'static str| -> Result<NodeIndex, NetworkError> {
                if let Some(&node) = index.get(&id) {
                    return Ok(node);
                }
                if closed {
                    return Err(NetworkError::DanglingEndpoint { row: row as u32, end, id });
                }
                let node = graph.add_node(NodeInfo { id: id.clone(), row: None });
                index.insert(id, node);
                Ok(node)
            };
            let a = endpoint(s, "source")?;
            let b = endpoint(t, "target")?;
            self_loops += usize::from(a == b);
            graph.add_edge(a, b, EdgeInfo { row: row as u32, weight });
        }
        if graph.node_count() == 0 {
            return Err(NetworkError::Empty);
        }
        Ok(Network { graph, missing_endpoints, bad_weights, self_loops })
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.graph.node_count()
    }

    /// Every edge as (source, target) node indices, self-loops included, in edge order.
    pub fn edge_pairs(&self) -> Vec<(u32, u32)> {
        self.graph.raw_edges().iter().map(|e| (e.source().index() as u32, e.target().index() as u32)).collect()
    }

    /// Every edge's weight, in edge order.
    pub fn weights(&self) -> Vec<f64> {
        self.graph.raw_edges().iter().map(|e| e.weight.weight).collect()
    }

    /// Each node's degree (in + out, a self-loop counting twice).
    pub fn degrees(&self) -> Vec<usize> {
        let mut degree = vec![0; self.node_count()];
        for e in self.graph.raw_edges() {
            degree[e.source().index()] += 1;
            degree[e.target().index()] += 1;
        }
        degree
    }

    /// The number of connected components, ignoring direction.
    pub fn components(&self) -> usize {
        petgraph::algo::connected_components(&self.graph)
    }

    /// Whether following edge directions can lead back to a node.
    pub fn has_cycle(&self) -> bool {
        petgraph::algo::is_cyclic_directed(&self.graph)
    }

    /// The network without its isolated nodes (no link to another node; a self-loop alone does
    /// not count) and how many were left out. Kept nodes and edges keep their order. When no node
    /// has a link, nothing is left out: the nodes are all there is to draw.
    pub fn without_isolated(self) -> (Network, usize) {
        let mut linked = vec![false; self.node_count()];
        for e in self.graph.raw_edges().iter().filter(|e| e.source() != e.target()) {
            linked[e.source().index()] = true;
            linked[e.target().index()] = true;
        }
        let isolated = linked.iter().filter(|&&l| !l).count();
        if isolated == 0 || isolated == linked.len() {
            return (self, 0);
        }
        let graph = self.graph.filter_map(
            |node, info| linked.get(node.index()).copied().unwrap_or(false).then(|| info.clone()),
            |_, info| Some(info.clone()),
        );
        let self_loops = graph.raw_edges().iter().filter(|e| e.source() == e.target()).count();
        (Network { graph, self_loops, ..self }, isolated)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{Categories, ColumnValues};

    fn text(values: &[&str]) -> Column {
        let cats = Categories::from_values(values.iter().map(|v| if v.is_empty() { None } else { Some(*v) }));
        Column { name: "c".into(), values: ColumnValues::Text(cats) }
    }

    fn numbers(values: &[f64]) -> Column {
        Column { name: "w".into(), values: ColumnValues::Number(values.to_vec()) }
    }

    #[test]
    fn endpoints_become_nodes_in_order_of_first_appearance() {
        let (s, t) = (text(&["a", "b", "c", "a", ""]), text(&["b", "c", "a", "a", "b"]));
        let net = Network::from_tables(5, EdgeColumns { source: &s, target: &t, weight: None }, None).unwrap();
        let ids: Vec<&str> = net.graph.node_weights().map(|n| n.id.as_str()).collect();
        assert_eq!(ids, vec!["a", "b", "c"]);
        assert_eq!(net.edge_pairs(), vec![(0, 1), (1, 2), (2, 0), (0, 0)]);
        assert_eq!((net.missing_endpoints, net.self_loops), (1, 1));
        assert_eq!(net.degrees(), vec![4, 2, 2]);
        assert!(net.has_cycle());
        assert_eq!(net.components(), 1);
    }

    #[test]
    fn a_node_table_fixes_the_nodes_and_catches_dangling_edges() {
        let (s, t) = (text(&["x", "y"]), text(&["y", "x"]));
        let ids = text(&["y", "x", "z"]);
        let net =
            Network::from_tables(2, EdgeColumns { source: &s, target: &t, weight: None }, Some((3, &ids))).unwrap();
        assert_eq!(net.node_count(), 3);
        assert_eq!(net.edge_pairs(), vec![(1, 0), (0, 1)]);
        assert_eq!(net.components(), 2);
        let short = text(&["y"]);
        let err = Network::from_tables(2, EdgeColumns { source: &s, target: &t, weight: None }, Some((1, &short)))
            .unwrap_err();
        assert_eq!(err, NetworkError::DanglingEndpoint { row: 0, end: "source", id: "x".into() });
        let dup = text(&["x", "x"]);
        let err =
            Network::from_tables(2, EdgeColumns { source: &s, target: &t, weight: None }, Some((2, &dup))).unwrap_err();
        assert_eq!(err, NetworkError::DuplicateNode { id: "x".into(), first: 0, second: 1 });
    }

    #[test]
    fn weights_drop_non_finite_rows_and_refuse_negative_ones() {
        let (s, t) = (text(&["a", "b", "c"]), text(&["b", "c", "a"]));
        let w = numbers(&[2.0, f64::NAN, 5.0]);
        let net = Network::from_tables(3, EdgeColumns { source: &s, target: &t, weight: Some(&w) }, None).unwrap();
        assert_eq!(net.weights(), vec![2.0, 5.0]);
        assert_eq!(net.bad_weights, 1);
        assert!(!net.has_cycle());
        let w = numbers(&[2.0, -1.0, 5.0]);
        let err = Network::from_tables(3, EdgeColumns { source: &s, target: &t, weight: Some(&w) }, None).unwrap_err();
        assert_eq!(err, NetworkError::NegativeWeight { row: 1, value: -1.0 });
        let none = text(&[]);
        assert_eq!(
            Network::from_tables(0, EdgeColumns { source: &none, target: &none, weight: None }, None).unwrap_err(),
            NetworkError::Empty
        );
    }

    #[test]
    fn isolated_nodes_are_left_out_in_order() {
        // Nodes a..e from a node table; links a-c, c-e and a self-loop on d: b and d are isolated.
        let ids = text(&["a", "b", "c", "d", "e"]);
        let (s, t) = (text(&["a", "c", "d"]), text(&["c", "e", "d"]));
        let edges = EdgeColumns { source: &s, target: &t, weight: None };
        let net = Network::from_tables(3, edges, Some((5, &ids))).unwrap();
        let (kept, left_out) = net.without_isolated();
        assert_eq!(left_out, 2);
        let names: Vec<&str> = kept.graph.node_weights().map(|n| n.id.as_str()).collect();
        assert_eq!(names, ["a", "c", "e"]);
        assert_eq!(kept.edge_pairs(), vec![(0, 1), (1, 2)]);
        assert_eq!(kept.self_loops, 0);
        // No links at all: every node stays.
        let (lone_s, lone_t) = (text(&["b"]), text(&["b"]));
        let edges = EdgeColumns { source: &lone_s, target: &lone_t, weight: None };
        let net = Network::from_tables(1, edges, Some((5, &ids))).unwrap();
        assert_eq!(net.without_isolated().1, 0);
    }
}
