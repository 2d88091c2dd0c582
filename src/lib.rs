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
//!    with the hierarchy and network kinds laid out by the plain functions in [`layout`],
//!    using the shared [`guide`]s (scales, ticks, axes, legends, colour maps).
//! 4. [`render`] — draw a scene as SVG or PNG with the one embedded font in [`text`]. Rendering a
//!    valid scene cannot fail: sizes are checked before anything is allocated.
//!    User text is cleaned by the one rule in [`visible`] (no control or bidi characters) there,
//!    in the report and in diagnostics.
//!
//! 5. [`lint`] — check each drawn chart against "good visualization" rules (scale shown, labels,
//!    integrity, colour, comparison), reading the scene the reader will see.
//! 6. [`report`] — one self-contained HTML page (inline SVGs, findings, data provenance with
//!    SHA-256 hashes, the spec) and a Markdown summary for CI, from minijinja templates that
//!    escape every value.
//!
//! [`pipeline`] strings the stages together for the command-line tool; [`explore`] holds the
//! interactive window's brushing, linking and navigation (the window itself needs the
//! `explore` feature).
//!
//! Used as a library, the stages run one by one:
//!
//! ```
//! use std::path::Path;
//! use dataink::data::{PathPolicy, load_source};
//! use dataink::spec::{SourceFile, parse_spec};
//!
//! let source = SourceFile::new(
//!     "inline.toml",
//!     r#"
//! [data.d]
//! values = [{ x = 1, y = 2.0 }, { x = 2, y = 3.5 }, { x = 3, y = 3.0 }]
//!
//! [[chart]]
//! name = "c"
//! kind = "line"
//! data = "d"
//! x = { field = "x", unit = "s" }
//! y = { field = "y", unit = "m" }
//! "#,
//! );
//! let parsed = parse_spec(&source).expect("a valid spec");
//! let table = load_source(&parsed.spec.data["d"], Path::new("."), PathPolicy::InsideSpecFolder, None)
//!     .expect("inline rows load");
//! let chart = dataink::mark::draw(&parsed.spec.chart[0], 0, &table, None).expect("the chart draws");
//! let svg = dataink::render::svg::to_svg(&chart.scene);
//! assert!(svg.contains("<svg") && svg.contains("y (m)"));
//! let png = dataink::render::png::to_png(&chart.scene, 2.0).expect("a PNG");
//! assert_eq!(&png[1..4], b"PNG");
//! ```

pub mod data;
pub mod enrich;
pub mod excerpt;
pub mod explore;
pub mod guide;
pub mod layout;
pub mod lint;
pub mod mark;
pub mod output;
pub mod pipeline;
pub mod render;
pub mod report;
pub mod scene;
pub mod selection;
#[cfg(feature = "serve")]
pub mod serve;
pub mod spec;
pub mod text;
pub mod timing;
pub mod visible;
