//! Numbers on volumes, shared by the volume kinds: reading a value anywhere in the world by
//! nearest voxel or trilinear interpolation ([`sample`]) and planes through a volume with their
//! own 2-D coordinates ([`plane`]), isosurfaces ([`isosurface`]) and ray casting ([`raycast`]).

pub mod isosurface;
pub mod plane;
pub mod raycast;
pub mod sample;

pub use plane::Plane;
pub use sample::{Interpolation, Sampler};
