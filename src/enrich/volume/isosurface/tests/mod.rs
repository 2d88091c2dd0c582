//! Tests of the isosurface extraction.

mod reference;
