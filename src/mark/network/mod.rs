//! Kinds drawing networks: graph, linkmap.

pub mod graph;
pub mod linkmap;
