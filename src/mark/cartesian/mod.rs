//! Kinds drawn in one x/y frame from rows: scatter, line, bar, interp1d.

pub mod bar;
pub mod interp1d;
pub mod line;
pub mod scatter;
