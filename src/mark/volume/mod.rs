//! Kinds drawing 3-D scalar fields: `slice` (planes through a volume as images) and
//! `isosurface` (surfaces of constant value, shaded in 3-D), with the volume's box as both draw
//! it (`box_frame`).

pub mod box_frame;
pub mod inset;
pub mod isosurface;
pub mod planes;
pub mod slice;
