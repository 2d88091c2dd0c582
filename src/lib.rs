//! # dataink
//!
//! Declarative visualization: a TOML spec names data sources and charts; dataink turns each chart
//! into SVG and PNG (and its derived geometry into CSV), with errors that point at the exact
//! place in the spec.
//!
//! The pipeline, one module per stage, each returning a new immutable value:
//!
//! 1. [`spec`] — parse the TOML with positions, validate it against the schema generated from
//!    the spec types, and report every problem at once as a [`spec::Diagnostic`].
//! 2. [`data`] — load the named sources through polars (CSV, Parquet, JSON, inline values) into
//!    plain columnar [`data::Table`]s.
//! 3. [`mark`] — one module per chart kind maps a table and a chart spec to a [`scene::Scene`],
//!    using the shared [`guide`]s (scales, ticks, axes, legends, colour maps).
//! 4. [`render`] — draw a scene as SVG or PNG with the one embedded font in [`text`]. Rendering a
//!    valid scene cannot fail: sizes are checked before anything is allocated.
//!
//! [`pipeline`] strings the stages together for the command-line tool.

pub mod data;
pub mod enrich;
pub mod guide;
pub mod mark;
pub mod pipeline;
pub mod render;
pub mod scene;
pub mod spec;
pub mod text;
