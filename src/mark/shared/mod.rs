//! Pieces the kinds share: categories in bands (`bands`), channels and the non-finite policy (`encode`), the cartesian frame,
//! selections drawn (`highlight`), derived output, categorical colours, gridded input, trees and
//! networks read from tables, marker sizes, rasters, contour labels, node-link drawing, hover texts (`tooltip`),
//! group spreads (mean, stdev, standard error, t-based confidence intervals, range: `spread`), trend lines (`trend`), annotations (`annotate`) and the axes of a 3-D box (`axis3d`).
//! Nothing here imports a kind.

pub mod annotate;
pub mod axis3d;
pub mod bands;
pub mod categorical;
pub mod density;
pub mod derived;
pub mod encode;
pub mod frame;
pub mod geojson;
pub mod geometry;
pub mod gridded;
pub mod grouped;
pub mod highlight;
pub mod level_labels;
pub mod network_input;
pub mod node_link;
pub mod overplot;
pub mod panel;
pub mod plan_rows;
pub mod raster;
pub mod size;
pub mod spread;
pub mod tooltip;
pub mod tree_input;
pub mod trend;
pub mod warning;
