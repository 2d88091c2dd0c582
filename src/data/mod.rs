//! Data: sources read through polars into small columnar [`Table`]s that chart kinds consume.
//!
//! Readers (CSV, Parquet, JSON records, inline `values`) live in [`load`], with the formats beyond
//! them each in its own module: Arrow IPC ([`ipc`]), GeoJSON ([`geojson`]), JSON paths and grids
//! ([`json_path`]), the depth limit and wide-integer quoting applied before any JSON parse
//! ([`json_scan`]), gzip/zstd files ([`compressed`]), per-column `parse` rules ([`parse`]), the
//! texts read as missing ([`missing`]) and the non-ISO date warning ([`date_guess`]); a source's
//! transform steps, compiled onto a polars lazy plan, in [`transform`]; the rule for which
//! paths may be read lives in [`paths`]. Chart kinds never see polars: they get plain columns of
//! numbers, times (milliseconds since the Unix epoch, UTC) or categories.

pub mod compressed;
pub mod contained;
pub mod csv_tail;
pub mod date_guess;
pub mod density;
pub mod engine;
pub mod frame;
pub mod geojson;
pub mod ipc;
pub mod ipc_bounds;
pub mod json_path;
pub mod json_scan;
pub mod load;
pub mod matrix;
pub mod missing;
pub mod nested;
pub mod network;
pub mod npy;
pub mod parquet_bounds;
pub mod parse;
pub mod paths;
pub mod regular_file;
pub mod table;
pub mod time;
pub mod transform;
pub mod tree;
pub mod volume;

pub use load::{LoadError, SourceData, load_source, load_source_with_warnings};
pub use paths::{PathError, PathPolicy, resolve_data_path};
pub use table::{Categories, Column, ColumnValues, GridAxis, NonFinite, Table};
