//! Kinds drawing a scalar field on a grid or scattered points: contour, image, section,
//! scattered, surface, hyperslice.

pub mod contour;
pub mod hyperslice;
pub mod image;
pub mod scattered;
pub mod section;
pub mod surface;
