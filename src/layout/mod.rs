//! Layout algorithms for hierarchies and networks: plain functions from a shape (a
//! [`hierarchy::Hierarchy`] or an edge list) to positions, each with its own tests.

pub mod circular;
pub mod force;
pub mod hierarchy;
pub mod hyperbolic;
pub mod layered;
pub mod matrix_order;
pub mod quadtree;
pub mod quality;
pub mod split_mix;
pub mod treemap;
