//! The integration suite, one test binary: every module below exercises the public library or the
//! command-line tool. Keeping them in one binary links the heavy dependency set once, not once
//! per file.

mod annotate;
mod architecture;
mod area;
mod bad_input;
mod bar;
mod bar_stats;
mod big_scatter;
mod box_violin;
mod category_labels;
mod charts;
mod cli;
mod colours;
mod common;
mod datasets;
mod defaults;
mod density;
mod engine;
mod explore;
mod facet;
mod flow;
mod frame_fit;
mod gltf;
mod golden;
mod heatmap;
mod histogram;
mod hostile_inputs;
mod hostile_work;
mod isosurfaces;
mod layout;
mod line_band;
mod lint;
mod lint_colour;
mod lint_technique;
mod multivariate;
mod networks;
mod report;
mod resources;
mod safe_output;
mod slices;
mod tooltips;
mod transform;
mod trend;
mod volume_rendering;
mod volumes;
