//! Kinds drawn in one x/y frame from rows: scatter, line, area, bar, histogram, heatmap, interp1d.

pub mod area;
pub mod bar;
pub mod heatmap;
pub mod histogram;
pub mod interp1d;
pub mod line;
pub mod scatter;
