//! Kinds drawn in one x/y frame from rows: scatter, line, bar, box, violin, interp1d.

pub mod bar;
pub mod box_plot;
pub mod interp1d;
pub mod line;
pub mod scatter;
pub mod violin;
