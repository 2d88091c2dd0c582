//! Kinds drawing 3-D scalar fields: `slice` (planes through a volume as images),
//! `isosurface` (surfaces of constant value, shaded in 3-D) and `volume` (direct volume
//! rendering by ray casting, in `direct`), with the volume's box as they draw it (`box_frame`).

pub mod box_frame;
pub mod direct;
pub mod inset;
pub mod isosurface;
pub mod planes;
pub mod slice;
