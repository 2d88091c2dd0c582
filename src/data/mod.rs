//! Data: sources read through polars into small columnar [`Table`]s that chart kinds consume.
//!
//! Readers (CSV, Parquet, JSON records, inline `values`) live in [`load`]; a source's transform
//! steps, compiled onto a polars lazy plan, in [`transform`]; the rule for which
//! paths may be read lives in [`paths`]. Chart kinds never see polars: they get plain columns of
//! numbers, times (milliseconds since the Unix epoch, UTC) or categories.

pub mod frame;
pub mod load;
pub mod matrix;
pub mod nested;
pub mod network;
pub mod paths;
pub mod table;
pub mod time;
pub mod transform;
pub mod tree;

pub use load::{LoadError, load_source};
pub use paths::{PathError, PathPolicy, resolve_data_path};
pub use table::{Categories, Column, ColumnValues, NonFinite, Table};
