//! Enrichment: pure numeric functions that make new data from the loaded data before mapping —
//! interpolation and resampling, grids, contours, and the shared 3-D camera.

pub mod camera;
pub mod contour;
pub mod distribution;
pub mod flow;
pub mod grid;
pub mod histogram;
pub mod hyperslice;
pub mod interp1d;
pub mod regression;
pub mod scattered;
pub mod segments;
pub mod stack;
pub mod surface;
pub mod volume;
