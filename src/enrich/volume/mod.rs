//! Numbers on volumes, shared by the volume kinds: reading a value anywhere in the world by
//! nearest voxel or trilinear interpolation ([`sample`]) and planes through a volume with their
//! own 2-D coordinates ([`plane`]), isosurfaces ([`isosurface`]), a span-space index of the
//! cells a level crosses, reused across levels ([`span_space`]), ray casting ([`raycast`]) and
//! its faster reordering by slices ([`shear_warp`]), and counts over the values ([`census`]).

pub mod census;
pub mod isosurface;
pub mod plane;
pub mod raycast;
pub mod sample;
pub mod shear_warp;
pub mod span_space;

pub use plane::Plane;
pub use sample::{Interpolation, Sampler};
pub use span_space::SpanSpace;
