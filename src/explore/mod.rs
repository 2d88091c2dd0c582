//! `dataink explore`: brushing, linking and navigation over the charts of a spec.
//!
//! Everything here but the window itself (`app`, behind the `explore` feature) is plain code
//! over canvas coordinates, tested without a display:
//!
//! - [`brush`]: pointer rectangles and axis ranges turned into data ranges through a chart's
//!   scales, and composed (replace, add, subtract) into one row set per data source;
//! - [`light`]: relighting a drawn chart's marks for a new row set without drawing it again;
//! - [`counts`]: relighting batches of tens of thousands of rows within a frame, by per-pixel
//!   ink counts that a frame updates only for the rows that changed;
//! - [`view`]: what is under the pointer (plot, axis, nearest row, tree node), the hover text,
//!   and zoom and pan as new axis domains;
//! - [`hyper`]: dragging and click-to-focus in a hyperbolic tree, with its animation;
//! - [`orbit`]: turning a 3-D chart (isosurface, volume rendering) and moving its iso value;
//! - [`session`]: the whole state — every chart drawn into raster tiles
//!   ([`crate::render::tiles`]), the shared row sets, and the actions as methods.
//!
//! The charts are drawn by the same mark code as `dataink render` and rasterized by the same
//! PNG renderer, so the window shows what the files show.

#[cfg(feature = "explore")]
pub mod app;
pub mod brush;
pub mod counts;
pub mod hyper;
pub mod light;
pub mod orbit;
pub mod session;
pub mod view;

pub use session::{ChartView, Session, Target};
