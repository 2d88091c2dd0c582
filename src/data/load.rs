//! Readers: CSV, Parquet and JSON files and inline `values`, all through polars, into [`Table`]s.

use std::fmt;
use std::fs::File;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use polars::prelude::*;

use super::paths::{PathError, PathPolicy, resolve_data_path};
use super::table::{Categories, Column as TableColumn, ColumnValues, Table};
use crate::spec::{DataFormat, DataSource};

/// Why a data source could not be loaded.
#[derive(Debug)]
pub enum LoadError {
    /// The path was refused by the path policy.
    Path(PathError),
    /// The file does not exist.
    NotFound(PathBuf),
    /// The format could not be inferred from the extension.
    UnknownFormat(PathBuf),
    /// The file could not be opened or read.
    Io(PathBuf, std::io::Error),
    /// The reader rejected the contents.
    Parse {
        /// The file (or `inline values`).
        origin: String,
        /// The format that was read.
        format: DataFormat,
        /// The reader's message.
        message: String,
    },
    /// The source has no columns (an empty file).
    NoColumns(String),
    /// A column has a type that charts cannot use.
    UnsupportedType {
        /// The file (or `inline values`).
        origin: String,
        /// Column name.
        column: String,
        /// The type polars read.
        dtype: String,
    },
    /// Neither `path` nor `values` (or both) were given.
    NoSource,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoadError::Path(e) => e.fmt(f),
            LoadError::NotFound(p) => write!(f, "data file `{}` does not exist", p.display()),
            LoadError::UnknownFormat(p) => {
                write!(f, "cannot tell the format of `{}` from its extension", p.display())
            }
            LoadError::Io(p, e) => write!(f, "cannot read `{}`: {e}", p.display()),
            LoadError::Parse { origin, format, message } => {
                write!(f, "cannot read {origin} as {}: {message}", format_name(*format))
            }
            LoadError::NoColumns(origin) => write!(f, "{origin} has no columns (is the file empty?)"),
            LoadError::UnsupportedType { origin, column, dtype } => {
                write!(f, "column `{column}` of {origin} has type {dtype}, which charts cannot use")
            }
            LoadError::NoSource => write!(f, "a data source needs exactly one of `path` or `values`"),
        }
    }
}

impl std::error::Error for LoadError {}

impl LoadError {
    /// How to fix it.
    pub fn hint(&self) -> String {
        match self {
            LoadError::Path(e) => e.hint().to_string(),
            LoadError::NotFound(_) => "paths are relative to the spec file; check the spelling".into(),
            LoadError::UnknownFormat(_) => "add `format = \"csv\"` (or parquet, json) to the data source".into(),
            LoadError::Io(..) => "check that the file is readable".into(),
            LoadError::Parse { format: DataFormat::Csv, .. } => {
                "CSV needs a header row, UTF-8 text and the same number of fields on every row".into()
            }
            LoadError::Parse { format: DataFormat::Json, .. } => {
                "JSON data must be an array of records, e.g. [{\"x\": 1, \"y\": 2}], or one record per line".into()
            }
            LoadError::Parse { format: DataFormat::Parquet, .. } => "the file is not a readable Parquet file".into(),
            LoadError::Parse { format: DataFormat::Npy, .. } => {
                "save a 2-D float or integer array with numpy.save".into()
            }
            LoadError::Parse { format: DataFormat::Tree, .. } => {
                "a tree file is one JSON object with a `children` array of objects of the same shape".into()
            }
            LoadError::Parse { format: DataFormat::Matrix, .. } => {
                "a CSV matrix has no header and the same number of numbers on every line".into()
            }
            LoadError::NoColumns(_) => "the source needs a header row and at least one column".into(),
            LoadError::UnsupportedType { .. } => {
                "use numbers, text, booleans, dates or date-times; flatten nested values first".into()
            }
            LoadError::NoSource => "write either path = \"data/file.csv\" or values = [{ x = 1, y = 2 }]".into(),
        }
    }
}

fn format_name(format: DataFormat) -> &'static str {
    match format {
        DataFormat::Csv => "CSV",
        DataFormat::Parquet => "Parquet",
        DataFormat::Json => "JSON",
        DataFormat::Npy => "NumPy .npy",
        DataFormat::Matrix => "a CSV matrix",
        DataFormat::Tree => "a nested JSON tree",
    }
}

/// The format of a path from its extension.
pub fn infer_format(path: &Path) -> Option<DataFormat> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "csv" | "tsv" | "txt" => Some(DataFormat::Csv),
        "parquet" | "pq" => Some(DataFormat::Parquet),
        "json" | "jsonl" | "ndjson" => Some(DataFormat::Json),
        "npy" => Some(DataFormat::Npy),
        _ => None,
    }
}

/// Load one data source. `spec_dir` is the folder of the spec file. With `columns`, only those
/// columns are read from CSV and Parquet files (all of them if any is missing, so that the
/// missing-column diagnostic can list the real ones).
pub fn load_source(
    source: &DataSource,
    spec_dir: &Path,
    policy: PathPolicy,
    columns: Option<&[String]>,
) -> Result<Table, LoadError> {
    match (&source.path, &source.values) {
        (Some(path), None) => {
            let resolved = resolve_data_path(spec_dir, path, policy).map_err(LoadError::Path)?;
            let format = match source.format {
                Some(f) => f,
                None => infer_format(&resolved).ok_or_else(|| LoadError::UnknownFormat(resolved.clone()))?,
            };
            let separator = source.delimiter.as_deref().and_then(|d| d.bytes().next()).unwrap_or_else(|| {
                if resolved.extension().is_some_and(|e| e.eq_ignore_ascii_case("tsv")) { b'\t' } else { b',' }
            });
            match format {
                DataFormat::Npy => return Ok(super::matrix::read_npy(&resolved)?.to_table(source.extent)),
                DataFormat::Matrix => return Ok(read_csv_matrix(&resolved, separator)?.to_table(source.extent)),
                DataFormat::Tree => return super::nested::read_tree_json(&resolved),
                _ => {}
            }
            match columns {
                Some(cols) if !cols.is_empty() && format != DataFormat::Json => {
                    load_file(&resolved, format, separator, Some(cols))
                        .or_else(|_| load_file(&resolved, format, separator, None))
                }
                _ => load_file(&resolved, format, separator, None),
            }
        }
        (None, Some(values)) => frame_to_table(&inline_frame(values)?, "inline values"),
        _ => Err(LoadError::NoSource),
    }
}

/// Inline `values` rows as a frame.
pub fn inline_frame(values: &[std::collections::BTreeMap<String, serde_json::Value>]) -> Result<DataFrame, LoadError> {
    let bytes = serde_json::to_vec(values).map_err(|e| LoadError::Parse {
        origin: "inline values".into(),
        format: DataFormat::Json,
        message: e.to_string(),
    })?;
    JsonReader::new(Cursor::new(bytes))
        .with_json_format(JsonFormat::Json)
        .infer_schema_len(None)
        .finish()
        .map_err(|e| parse_error("inline values", DataFormat::Json, e))
}

/// Load a file of a known format, optionally only some of its columns (CSV and Parquet).
pub fn load_file(
    path: &Path,
    format: DataFormat,
    separator: u8,
    columns: Option<&[String]>,
) -> Result<Table, LoadError> {
    let df = read_frame(path, format, separator, columns)?;
    frame_to_table(&df, &format!("`{}`", path.display()))
}

/// Read a CSV, Parquet or JSON file into a frame, optionally only some of its columns (CSV and
/// Parquet).
pub fn read_frame(
    path: &Path,
    format: DataFormat,
    separator: u8,
    columns: Option<&[String]>,
) -> Result<DataFrame, LoadError> {
    let file = File::open(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => LoadError::NotFound(path.to_path_buf()),
        _ => LoadError::Io(path.to_path_buf(), e),
    })?;
    let origin = format!("`{}`", path.display());
    if file.metadata().map(|m| m.len() == 0).unwrap_or(false) {
        return Err(LoadError::NoColumns(origin));
    }
    let df = match format {
        DataFormat::Csv => CsvReadOptions::default()
            .with_has_header(true)
            .with_columns(columns.map(|c| c.iter().map(|n| PlSmallStr::from(n.as_str())).collect()))
            .with_infer_schema_length(Some(10_000))
            .map_parse_options(|p| p.with_separator(separator))
            .into_reader_with_file_handle(file)
            .finish(),
        DataFormat::Parquet => ParquetReader::new(file).with_columns(columns.map(<[String]>::to_vec)).finish(),
        DataFormat::Npy | DataFormat::Matrix | DataFormat::Tree => {
            return Err(LoadError::Parse { origin, format, message: "grid files are read by load_source".into() });
        }
        DataFormat::Json => {
            let lines =
                path.extension().is_some_and(|e| e.eq_ignore_ascii_case("jsonl") || e.eq_ignore_ascii_case("ndjson"));
            let json_format = if lines { JsonFormat::JsonLines } else { JsonFormat::Json };
            JsonReader::new(file).with_json_format(json_format).infer_schema_len(None).finish()
        }
    }
    .map_err(|e| parse_error(&origin, format, e))?;
    Ok(df)
}

fn parse_error(origin: &str, format: DataFormat, e: PolarsError) -> LoadError {
    let message = e.to_string();
    // polars messages can carry long tracebacks of context; the first line is what helps.
    let first = message.lines().next().unwrap_or("").trim().to_string();
    LoadError::Parse { origin: origin.to_string(), format, message: first }
}

/// Convert a polars frame into a [`Table`].
pub fn frame_to_table(df: &DataFrame, origin: &str) -> Result<Table, LoadError> {
    if df.width() == 0 {
        return Err(LoadError::NoColumns(origin.to_string()));
    }
    let mut columns = Vec::with_capacity(df.width());
    for column in df.columns() {
        let series = column.as_materialized_series();
        let name = series.name().as_str().trim_start_matches('\u{feff}').to_string();
        let values = series_values(series).ok_or_else(|| LoadError::UnsupportedType {
            origin: origin.to_string(),
            column: name.clone(),
            dtype: series.dtype().to_string(),
        })?;
        columns.push(TableColumn { name, values: detect_time_text(values) });
    }
    Ok(Table { columns, rows: df.height() })
}

fn series_values(series: &Series) -> Option<ColumnValues> {
    let dtype = series.dtype();
    // A column with no values at all (e.g. every CSV cell empty) is read as missing numbers, so
    // the non-finite policy counts it instead of it becoming one "(missing)" category.
    let all_missing = series.null_count() == series.len();
    if dtype.is_primitive_numeric() || matches!(dtype, DataType::Null) || all_missing {
        return Some(ColumnValues::Number(to_f64(series)?));
    }
    match dtype {
        DataType::Datetime(unit, _) => {
            let per_ms = match unit {
                TimeUnit::Milliseconds => 1.0,
                TimeUnit::Microseconds => 1e3,
                TimeUnit::Nanoseconds => 1e6,
            };
            let raw = to_f64(&series.cast(&DataType::Int64).ok()?)?;
            Some(ColumnValues::Time(raw.into_iter().map(|v| v / per_ms).collect()))
        }
        DataType::Date => {
            let raw = to_f64(&series.cast(&DataType::Int32).ok()?)?;
            Some(ColumnValues::Time(raw.into_iter().map(|d| d * 86_400_000.0).collect()))
        }
        DataType::String => Some(ColumnValues::Text(Categories::from_values(series.str().ok()?.iter()))),
        DataType::Boolean => {
            let bools = series.bool().ok()?;
            Some(ColumnValues::Text(Categories::from_values(
                bools.iter().map(|b| b.map(|b| if b { "true" } else { "false" })),
            )))
        }
        _ => None,
    }
}

fn to_f64(series: &Series) -> Option<Vec<f64>> {
    if series.null_count() == series.len() {
        return Some(vec![f64::NAN; series.len()]);
    }
    let cast = series.cast(&DataType::Float64).ok()?;
    let ca = cast.f64().ok()?;
    if ca.null_count() == 0 {
        let mut out = Vec::with_capacity(ca.len());
        for chunk in ca.downcast_iter() {
            out.extend_from_slice(chunk.values().as_slice());
        }
        Some(out)
    } else {
        Some(ca.iter().map(|v| v.unwrap_or(f64::NAN)).collect())
    }
}

/// A text column whose every value is an ISO date or date-time becomes a time column.
fn detect_time_text(values: ColumnValues) -> ColumnValues {
    let ColumnValues::Text(cats) = &values else { return values };
    if cats.levels.is_empty() {
        return values;
    }
    let mut parsed = Vec::with_capacity(cats.levels.len());
    for level in &cats.levels {
        match crate::data::time::parse_iso(level) {
            Some(ms) => parsed.push(ms),
            None => return values,
        }
    }
    ColumnValues::Time(cats.codes.iter().map(|&c| parsed.get(c as usize).copied().unwrap_or(f64::NAN)).collect())
}

/// A headerless CSV of numbers, read through polars, as a matrix (rows along y).
pub fn read_csv_matrix(path: &Path, separator: u8) -> Result<super::matrix::Matrix, LoadError> {
    let file = File::open(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => LoadError::NotFound(path.to_path_buf()),
        _ => LoadError::Io(path.to_path_buf(), e),
    })?;
    let origin = format!("`{}`", path.display());
    let df = CsvReadOptions::default()
        .with_has_header(false)
        .with_infer_schema_length(None)
        .map_parse_options(|p| p.with_separator(separator))
        .into_reader_with_file_handle(file)
        .finish()
        .map_err(|e| parse_error(&origin, DataFormat::Matrix, e))?;
    let (rows, cols) = (df.height(), df.width());
    if rows == 0 || cols == 0 {
        return Err(LoadError::NoColumns(origin));
    }
    let mut columns = Vec::with_capacity(cols);
    for column in df.columns() {
        let series = column.as_materialized_series();
        if !series.dtype().is_primitive_numeric() && series.null_count() != series.len() {
            return Err(LoadError::Parse {
                origin,
                format: DataFormat::Matrix,
                message: format!("column {} holds text ({})", columns.len() + 1, series.dtype()),
            });
        }
        columns.push(to_f64(series).unwrap_or_else(|| vec![f64::NAN; rows]));
    }
    let mut values = Vec::with_capacity(rows * cols);
    for i in 0..rows {
        for col in &columns {
            values.push(col.get(i).copied().unwrap_or(f64::NAN));
        }
    }
    Ok(super::matrix::Matrix { rows, cols, values })
}
