//! Kinds drawing trees: treemap, hypertree.

pub mod hypertree;
pub mod treemap;
