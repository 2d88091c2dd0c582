//! Kinds for many columns at once: splom, parallel, daisy, faces (with its face geometry),
//! segments.

pub mod daisy;
pub mod face;
pub mod faces;
pub mod parallel;
pub mod segments;
pub mod splom;
mod splom_counted;
