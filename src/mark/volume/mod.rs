//! Kinds drawing 3-D scalar fields: `slice` (planes through a volume as images) so far.

pub mod inset;
pub mod planes;
pub mod slice;
