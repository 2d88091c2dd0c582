//! Kinds drawn in one x/y frame from rows: scatter, line, bar, histogram, interp1d.

pub mod bar;
pub mod histogram;
pub mod interp1d;
pub mod line;
pub mod scatter;
