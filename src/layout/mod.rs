//! Layout algorithms for hierarchies and networks: plain functions from a shape (a
//! [`hierarchy::Hierarchy`] or an edge list) to positions, each with its own tests.

pub mod hierarchy;
