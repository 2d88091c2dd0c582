//! Readers: CSV, Parquet, Arrow IPC, JSON and GeoJSON files (any of them gzip- or
//! zstd-compressed) and inline `values`, all through polars, into [`Table`]s; per-column `parse`
//! rules applied before the conversion, and warnings for text columns that look like dates.

use std::fmt;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use polars::prelude::*;

use super::compressed::{self, Compression};
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
    /// A compressed file could not be decompressed (corrupt, cut short, or too large).
    Decompress {
        /// The file.
        path: PathBuf,
        /// The compression its extension names.
        compression: Compression,
        /// The decoder's message.
        message: String,
    },
    /// `json_path` does not lead to records or a grid.
    JsonPath {
        /// The file.
        origin: String,
        /// What is wrong.
        message: String,
        /// The keys that exist, a "did you mean".
        hint: String,
    },
    /// A JSON file nests arrays and objects deeper than its format's limit.
    TooDeep {
        /// The file.
        origin: String,
        /// The format read.
        format: DataFormat,
        /// How deep, where, and the limit.
        error: super::json_scan::TooDeep,
    },
    /// A `parse` rule could not be applied to its column.
    ColumnParse {
        /// The file (or `inline values`).
        origin: String,
        /// The column, rule and message.
        error: super::parse::ParseError,
    },
    /// A key was given that the source's format does not use (`json_path` on a CSV file,
    /// `parse` on a grid).
    NotApplicable {
        /// The key.
        key: &'static str,
        /// The format read.
        format: DataFormat,
    },
    /// A key the source's format needs was not given (`dims` for a raw volume).
    MissingKey {
        /// The key.
        key: &'static str,
        /// The format read.
        format: DataFormat,
    },
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
            LoadError::Decompress { path, compression, message } => {
                write!(f, "cannot decompress `{}` as {}: {message}", path.display(), compression.name())
            }
            LoadError::JsonPath { origin, message, .. } => write!(f, "in {origin}: {message}"),
            LoadError::TooDeep { origin, format, error } => {
                write!(f, "cannot read {origin} as {}: {error}", format_name(*format))
            }
            LoadError::ColumnParse { origin, error } => write!(
                f,
                "column `{}` of {origin} cannot be read with parse rule \"{}\": {}",
                error.column, error.rule, error.message
            ),
            LoadError::NotApplicable { key, format } => {
                write!(f, "`{key}` does not apply to {} files", format_name(*format))
            }
            LoadError::MissingKey { key, format } => write!(f, "reading {} needs `{key}`", format_name(*format)),
        }
    }
}

impl std::error::Error for LoadError {}

impl LoadError {
    /// The error for a failed open or read of `path`.
    pub fn from_io(path: &Path, e: std::io::Error) -> LoadError {
        match e.kind() {
            std::io::ErrorKind::NotFound => LoadError::NotFound(path.to_path_buf()),
            _ => LoadError::Io(path.to_path_buf(), e),
        }
    }

    /// How to fix it.
    pub fn hint(&self) -> String {
        match self {
            LoadError::Path(e) => e.hint().to_string(),
            LoadError::NotFound(_) => "paths are relative to the spec file; check the spelling".into(),
            LoadError::UnknownFormat(_) => {
                "add `format = \"csv\"` to the data source, or one of parquet, json, arrow, \
                 geojson, npy, matrix, tree, nifti, raw; compressed files end in .gz or .zst after the format's extension"
                    .into()
            }
            LoadError::Io(..) => "check that the file is readable".into(),
            LoadError::Parse { format: DataFormat::Csv, .. } => {
                "CSV needs a header row, UTF-8 text and the same number of fields on every row".into()
            }
            LoadError::Parse { format: DataFormat::Json, .. } => {
                "JSON data must be an array of records, e.g. [{\"x\": 1, \"y\": 2}], or one record per line".into()
            }
            LoadError::Parse { format: DataFormat::Parquet, .. } => "the file is not a readable Parquet file".into(),
            LoadError::Parse { format: DataFormat::Npy, .. } => {
                "save a 2-D (grid) or 3-D (volume) float or integer array with numpy.save".into()
            }
            LoadError::Parse { format: DataFormat::Nifti, .. } => {
                "the file must be a NIfTI-1 volume as nibabel, FSL or dcm2niix write it (see README, Volumes); check it with nibabel.load"
                    .into()
            }
            LoadError::Parse { format: DataFormat::Raw, .. } => {
                "`dims`, `dtype`, `byte_order` and `header_bytes` must describe the file: its size is header_bytes + nx × ny × nz × bytes per voxel"
                    .into()
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
            LoadError::Parse { format: DataFormat::Arrow, .. } => {
                "the file is not a readable Arrow IPC file (Feather v2); write it with pyarrow.feather.write_feather, \
                 polars' write_ipc or DuckDB's COPY ... (FORMAT arrow)"
                    .into()
            }
            LoadError::Parse { format: DataFormat::Geojson, .. } => {
                "GeoJSON data must be a FeatureCollection: {\"type\": \"FeatureCollection\", \"features\": [...]}"
                    .into()
            }
            LoadError::Decompress { compression, .. } => format!(
                "the file is not valid {0} or is cut short (check it with `{0} -t`); if it is not compressed, drop the extension",
                compression.name()
            ),
            LoadError::JsonPath { hint, .. } => hint.clone(),
            LoadError::TooDeep { format, error, .. } => format!(
                "flatten the nested values: reading {} allows at most {} levels of arrays and objects (see README, Limits)",
                format_name(*format),
                error.limit
            ),
            LoadError::ColumnParse { error, .. } => error.hint.clone(),
            LoadError::NotApplicable { key, .. } => format!("remove `{key}` from the data source"),
            LoadError::MissingKey { .. } => {
                "describe the raw file: e.g. dims = [256, 256, 128], dtype = \"u16\", byte_order = \"little\", spacing = [1.0, 1.0, 2.0]".into()
            }
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
        DataFormat::Arrow => "Arrow IPC",
        DataFormat::Geojson => "GeoJSON",
        DataFormat::Nifti => "NIfTI-1",
        DataFormat::Raw => "a raw volume",
    }
}

/// The format of a path from its extension (the inner one for `.gz` and `.zst` files).
pub fn infer_format(path: &Path) -> Option<DataFormat> {
    let inner = compressed::inner_path(path);
    let ext = inner.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "csv" | "tsv" | "txt" => Some(DataFormat::Csv),
        "parquet" | "pq" => Some(DataFormat::Parquet),
        "json" | "jsonl" | "ndjson" => Some(DataFormat::Json),
        "npy" => Some(DataFormat::Npy),
        "arrow" | "feather" | "ipc" => Some(DataFormat::Arrow),
        "geojson" => Some(DataFormat::Geojson),
        "nii" | "hdr" => Some(DataFormat::Nifti),
        _ => None,
    }
}

/// A loaded source: its table and the warnings met while reading it (text columns that look
/// like dates in a non-ISO format).
#[derive(Debug)]
pub struct SourceData {
    /// The table.
    pub table: Table,
    /// Warnings, each a sentence with its fix.
    pub warnings: Vec<String>,
}

/// What a reader produced: a frame still to be parsed and converted, or a finished table (grids
/// and trees).
pub enum Reading {
    /// Rows read by polars, before parse rules and conversion.
    Frame(DataFrame),
    /// A table made by dataink's own readers.
    Table(Table),
}

/// The rows of a source as a polars frame, with its `parse` rules applied: the start of a
/// source's transforms when the file cannot be scanned lazily.
pub fn source_frame(source: &DataSource, spec_dir: &Path, policy: PathPolicy) -> Result<DataFrame, LoadError> {
    let rules = source.parse.clone().unwrap_or_default();
    let (read, origin) = match (&source.path, &source.values) {
        (Some(path), None) => {
            let resolved = resolve_data_path(spec_dir, path, policy).map_err(LoadError::Path)?;
            let format = match source.format {
                Some(f) => f,
                None => infer_format(&resolved).ok_or_else(|| LoadError::UnknownFormat(resolved.clone()))?,
            };
            (read_path(source, &resolved, format, None, &rules)?, format!("`{}`", resolved.display()))
        }
        (None, Some(values)) => (Reading::Frame(inline_frame(values)?), "inline values".to_string()),
        _ => return Err(LoadError::NoSource),
    };
    match read {
        Reading::Frame(df) => super::parse::apply(df, &rules).map_err(|error| LoadError::ColumnParse { origin, error }),
        Reading::Table(table) => super::frame::table_to_frame(&table).map_err(|e| LoadError::Parse {
            origin,
            format: DataFormat::Json,
            message: e.to_string(),
        }),
    }
}

/// Load one data source. `spec_dir` is the folder of the spec file. With `columns`, only those
/// columns are read from CSV, Parquet and Arrow files (all of them if any is missing, so that the
/// missing-column diagnostic can list the real ones).
pub fn load_source(
    source: &DataSource,
    spec_dir: &Path,
    policy: PathPolicy,
    columns: Option<&[String]>,
) -> Result<Table, LoadError> {
    load_source_with_warnings(source, spec_dir, policy, columns).map(|data| data.table)
}

/// [`load_source`], with the warnings met while reading.
pub fn load_source_with_warnings(
    source: &DataSource,
    spec_dir: &Path,
    policy: PathPolicy,
    columns: Option<&[String]>,
) -> Result<SourceData, LoadError> {
    let rules = source.parse.clone().unwrap_or_default();
    let (read, origin, format) = match (&source.path, &source.values) {
        (Some(path), None) => {
            let resolved = resolve_data_path(spec_dir, path, policy).map_err(LoadError::Path)?;
            let format = match source.format {
                Some(f) => f,
                None => infer_format(&resolved).ok_or_else(|| LoadError::UnknownFormat(resolved.clone()))?,
            };
            if source.json_path.is_some() && format != DataFormat::Json {
                return Err(LoadError::NotApplicable { key: "json_path", format });
            }
            if let Some(key) = super::volume::source::volume_key(source) {
                return Err(LoadError::NotApplicable { key, format });
            }
            // Columns the rules name are read too, as raw text where the reader guesses types.
            let wanted: Option<Vec<String>> = columns.map(|c| {
                c.iter().chain(rules.keys()).cloned().collect::<std::collections::BTreeSet<_>>().into_iter().collect()
            });
            let read = read_path(source, &resolved, format, wanted.as_deref(), &rules)?;
            (read, format!("`{}`", resolved.display()), format)
        }
        (None, Some(values)) => (Reading::Frame(inline_frame(values)?), "inline values".to_string(), DataFormat::Json),
        _ => return Err(LoadError::NoSource),
    };
    match read {
        Reading::Table(table) if rules.is_empty() => Ok(SourceData { table, warnings: Vec::new() }),
        Reading::Table(_) => Err(LoadError::NotApplicable { key: "parse", format }),
        Reading::Frame(df) => {
            let df = super::parse::apply(df, &rules)
                .map_err(|error| LoadError::ColumnParse { origin: origin.clone(), error })?;
            let table = frame_to_table(&df, &origin)?;
            // Columns with a rule are read as told; with `columns`, only those are looked at.
            let warnings = super::date_guess::date_warnings(&table, |name| {
                !rules.contains_key(name) && columns.is_none_or(|c| c.is_empty() || c.iter().any(|w| w == name))
            });
            Ok(SourceData { table, warnings })
        }
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

/// Read a resolved file of a known format; a panic in a reader (a malformed file meeting a
/// dependency's bug) becomes a parse error naming the file.
pub fn read_path(
    source: &DataSource,
    resolved: &Path,
    format: DataFormat,
    columns: Option<&[String]>,
    rules: &std::collections::BTreeMap<String, String>,
) -> Result<Reading, LoadError> {
    super::contained::contain(|| read_path_uncontained(source, resolved, format, columns, rules)).unwrap_or_else(
        |message| Err(LoadError::Parse { origin: format!("`{}`", resolved.display()), format, message }),
    )
}

fn read_path_uncontained(
    source: &DataSource,
    resolved: &Path,
    format: DataFormat,
    columns: Option<&[String]>,
    rules: &std::collections::BTreeMap<String, String>,
) -> Result<Reading, LoadError> {
    let origin = format!("`{}`", resolved.display());
    let inner = compressed::inner_path(resolved);
    let inner_ext = inner.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    let separator = source.delimiter.as_deref().and_then(|d| d.bytes().next()).unwrap_or(if inner_ext == "tsv" {
        b'\t'
    } else {
        b','
    });
    let parse_failed = |message: String| LoadError::Parse { origin: origin.clone(), format, message };
    match format {
        DataFormat::Npy => Ok(Reading::Table(super::matrix::read_npy(resolved)?.to_table(source.extent))),
        DataFormat::Matrix => Ok(Reading::Table(
            read_csv_matrix(resolved, separator, source.null_values.as_deref())?.to_table(source.extent),
        )),
        DataFormat::Tree => Ok(Reading::Table(super::nested::read_tree_json(resolved)?)),
        DataFormat::Json => {
            let bytes = compressed::read_bytes(resolved)?;
            let lines = inner_ext == "jsonl" || inner_ext == "ndjson";
            match super::json_path::read_json(&bytes, source.json_path.as_deref(), lines) {
                Ok(super::json_path::JsonContent::Frame(df)) => Ok(Reading::Frame(df)),
                Ok(super::json_path::JsonContent::Grid(m)) => Ok(Reading::Table(m.to_table(source.extent))),
                Err(super::json_path::JsonError::Syntax(message)) => Err(parse_failed(message)),
                Err(super::json_path::JsonError::Path { message, hint }) => {
                    Err(LoadError::JsonPath { origin: origin.clone(), message, hint })
                }
                Err(super::json_path::JsonError::TooDeep(error)) => {
                    Err(LoadError::TooDeep { origin: origin.clone(), format, error })
                }
            }
        }
        DataFormat::Geojson => {
            let bytes = compressed::read_bytes(resolved)?;
            super::json_scan::check_depth(&bytes, super::json_scan::MAX_RECORD_DEPTH)
                .map_err(|error| LoadError::TooDeep { origin: origin.clone(), format, error })?;
            let value: serde_json::Value = serde_json::from_slice(&bytes).map_err(|e| parse_failed(e.to_string()))?;
            Ok(Reading::Frame(super::geojson::read_geojson(&value).map_err(parse_failed)?))
        }
        DataFormat::Nifti | DataFormat::Raw => Err(parse_failed(
            "a volume is not a table: charts that draw tables cannot read it, nor can `from` or `transform`".into(),
        )),
        DataFormat::Csv | DataFormat::Parquet | DataFormat::Arrow => {
            let text: Vec<&str> = rules.keys().map(String::as_str).collect();
            let dialect = CsvDialect { separator, text_columns: &text, null_values: source.null_values.as_deref() };
            let read = |cols| read_frame(resolved, format, &dialect, cols);
            let df = match columns {
                Some(cols) if !cols.is_empty() => read(Some(cols)).or_else(|_| read(None)),
                _ => read(None),
            }?;
            Ok(Reading::Frame(df))
        }
    }
}

/// Load a CSV, Parquet or Arrow file, optionally only some of its columns.
pub fn load_file(
    path: &Path,
    format: DataFormat,
    separator: u8,
    columns: Option<&[String]>,
) -> Result<Table, LoadError> {
    let dialect = CsvDialect { separator, text_columns: &[], null_values: None };
    let df = read_frame(path, format, &dialect, columns)?;
    frame_to_table(&df, &format!("`{}`", path.display()))
}

/// How a CSV file is read.
#[derive(Clone, Copy, Debug)]
pub struct CsvDialect<'a> {
    /// The field separator.
    pub separator: u8,
    /// Columns read as raw text.
    pub text_columns: &'a [&'a str],
    /// Texts read as missing; [`super::missing::MISSING_TEXTS`] when `None`.
    pub null_values: Option<&'a [String]>,
}

/// Read a CSV, Parquet or Arrow file (decompressed first when its extension says so) into a
/// frame, optionally only some of its columns; CSV files are read as `dialect` says.
///
/// A CSV file under the default missing texts is first read without comparing each cell with
/// them (most files write none, and the comparison costs about a sixth of the read); only when
/// that read fails or a text column holds one of them is it read again with the list.
pub fn read_frame(
    path: &Path,
    format: DataFormat,
    dialect: &CsvDialect<'_>,
    columns: Option<&[String]>,
) -> Result<DataFrame, LoadError> {
    if format != DataFormat::Csv || dialect.null_values.is_some() {
        return read_frame_as(path, format, dialect, columns);
    }
    let plain = CsvDialect { null_values: Some(&[]), ..*dialect };
    match read_frame_as(path, format, &plain, columns) {
        Ok(df) if !super::missing::holds_missing_text(&df) => Ok(df),
        _ => read_frame_as(path, format, dialect, columns),
    }
}

/// [`read_frame`] in one read.
fn read_frame_as(
    path: &Path,
    format: DataFormat,
    dialect: &CsvDialect<'_>,
    columns: Option<&[String]>,
) -> Result<DataFrame, LoadError> {
    let origin = format!("`{}`", path.display());
    if Compression::of(path).is_some() {
        let bytes = compressed::read_bytes(path)?;
        if bytes.is_empty() {
            return Err(LoadError::NoColumns(origin));
        }
        let head = bytes.get(..8).unwrap_or(&bytes).to_vec();
        if format == DataFormat::Csv
            && super::csv_tail::ends_in_open_quote(&bytes[bytes.len().saturating_sub(2)..], dialect.separator)
        {
            return Err(LoadError::Parse { origin, format, message: super::csv_tail::MESSAGE.into() });
        }
        return frame_from(Cursor::new(bytes), &head, &origin, format, dialect, columns);
    }
    let mut file = super::regular_file::open(path).map_err(|e| LoadError::from_io(path, e))?;
    if file.metadata().map(|m| m.len() == 0).unwrap_or(false) {
        return Err(LoadError::NoColumns(origin));
    }
    if format == DataFormat::Csv {
        super::csv_tail::check_file(path, dialect.separator)
            .map_err(|e| LoadError::from_io(path, e))?
            .map_err(|message| LoadError::Parse { origin: origin.clone(), format, message: message.into() })?;
    }
    let mut head = [0u8; 8];
    let got = std::io::Read::read(&mut file, &mut head).map_err(|e| LoadError::from_io(path, e))?;
    std::io::Seek::rewind(&mut file).map_err(|e| LoadError::from_io(path, e))?;
    frame_from(file, head.get(..got).unwrap_or(&[]), &origin, format, dialect, columns)
}

/// Read a frame from a file or bytes in memory.
fn frame_from<R: polars::io::mmap::MmapBytesReader + 'static>(
    reader: R,
    head: &[u8],
    origin: &str,
    format: DataFormat,
    dialect: &CsvDialect<'_>,
    columns: Option<&[String]>,
) -> Result<DataFrame, LoadError> {
    let df = match format {
        DataFormat::Csv => {
            let text: Schema =
                dialect.text_columns.iter().map(|c| Field::new(PlSmallStr::from(*c), DataType::String)).collect();
            CsvReadOptions::default()
                .with_has_header(true)
                .with_columns(columns.map(|c| c.iter().map(|n| PlSmallStr::from(n.as_str())).collect()))
                .with_schema_overwrite((!dialect.text_columns.is_empty()).then(|| Arc::new(text)))
                .with_infer_schema_length(Some(10_000))
                .map_parse_options(|p| {
                    p.with_separator(dialect.separator)
                        .with_null_values(super::missing::csv_null_values(dialect.null_values))
                })
                .into_reader_with_file_handle(reader)
                .finish()
        }
        DataFormat::Parquet => {
            let mut reader = reader;
            super::parquet_bounds::check(&mut reader).map_err(|message| LoadError::Parse {
                origin: origin.to_string(),
                format,
                message,
            })?;
            ParquetReader::new(reader).with_columns(columns.map(<[String]>::to_vec)).finish()
        }
        DataFormat::Arrow => {
            return super::ipc::read_ipc(reader, head, columns).map_err(|message| LoadError::Parse {
                origin: origin.to_string(),
                format,
                message,
            });
        }
        _ => {
            return Err(LoadError::Parse {
                origin: origin.to_string(),
                format,
                message: "this format is read by load_source".into(),
            });
        }
    };
    df.map_err(|e| parse_error(origin, format, e))
}

fn parse_error(origin: &str, format: DataFormat, e: PolarsError) -> LoadError {
    LoadError::Parse { origin: origin.to_string(), format, message: first_line(&e) }
}

/// The first line of a polars message (the rest is long context that does not help the user),
/// bounded like any quoted value ([`super::transform::first_line`]).
pub(crate) fn first_line(e: &PolarsError) -> String {
    super::transform::first_line(&e.to_string())
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

/// A headerless CSV of numbers, read through polars, as a matrix (rows along y); cells whose text
/// is one of `null_values` (default [`super::missing::MISSING_TEXTS`]) are missing.
pub fn read_csv_matrix(
    path: &Path,
    separator: u8,
    null_values: Option<&[String]>,
) -> Result<super::matrix::Matrix, LoadError> {
    let file = Cursor::new(compressed::read_bytes(path)?);
    let origin = format!("`{}`", path.display());
    let df = CsvReadOptions::default()
        .with_has_header(false)
        .with_infer_schema_length(None)
        .map_parse_options(|p| {
            p.with_separator(separator).with_null_values(super::missing::csv_null_values(null_values))
        })
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
