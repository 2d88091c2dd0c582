//! Kinds drawn in one x/y frame from rows: scatter, line, area, bar, histogram, heatmap, box,
//! violin, interp1d.

pub mod area;
pub mod bar;
pub mod box_plot;
pub mod heatmap;
pub mod histogram;
pub mod interp1d;
pub mod line;
pub mod scatter;
pub mod scatter_density;
pub mod violin;
