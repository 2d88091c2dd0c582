//! Kinds drawn in one x/y frame from rows: scatter, line, area, bar, histogram, interp1d.

pub mod area;
pub mod bar;
pub mod histogram;
pub mod interp1d;
pub mod line;
pub mod scatter;
