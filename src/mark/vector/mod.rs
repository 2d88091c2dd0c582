//! Kinds drawing vector fields: flow.

pub mod flow;
