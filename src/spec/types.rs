//! The spec file's types: what a user may write in a `dataink` TOML spec.
//!
//! Every field's doc comment is also its description in the JSON Schema (`dataink schema`), so
//! keep them short and written for the spec's author.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A whole spec file: named data sources and the charts drawn from them.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct Spec {
    /// Title of the collection (used by reports).
    #[serde(default)]
    pub title: Option<String>,
    /// Data sources by name, e.g. `[data.iris]`.
    #[serde(default)]
    pub data: BTreeMap<String, DataSource>,
    /// Named brushes by name, e.g. `[selection.small]`: rows that charts naming them in
    /// `highlight` draw in full colour.
    #[serde(default)]
    pub selection: BTreeMap<String, Selection>,
    /// Charts, each a `[[chart]]` table.
    #[serde(default)]
    pub chart: Vec<Chart>,
    /// Lint configuration for every chart: `[lint] allow = ["LB001"]`, `deny = ["SC004"]`.
    #[serde(default)]
    pub lint: Option<LintConfig>,
}

/// Which lint rules to silence or to treat as errors; rules are named by code (`LB001`) or name
/// (`missing-title`).
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct LintConfig {
    /// Rules whose findings are dropped (they still show as allowed in reports).
    #[serde(default)]
    #[schemars(example = example_rules())]
    pub allow: Option<Vec<String>>,
    /// Rules whose findings are errors, whatever their usual severity.
    #[serde(default)]
    #[schemars(example = example_rules())]
    pub deny: Option<Vec<String>>,
}

/// Schema example of a rule list.
fn example_rules() -> [&'static str; 2] {
    ["LB001", "overplotting"]
}

/// A named brush over one data source: numeric ranges and category sets that select rows.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct Selection {
    /// Name of the data source whose rows are selected (a key of `[data]`).
    #[schemars(example = &"iris")]
    pub data: String,
    /// Numeric ranges, inclusive: `{ petal_length = [1.0, 2.5] }`.
    #[serde(default)]
    pub range: Option<BTreeMap<String, [f64; 2]>>,
    /// Category sets: `{ species = ["setosa", "virginica"] }` (numbers match numeric columns).
    #[serde(default)]
    pub categories: Option<BTreeMap<String, Vec<CategoryValue>>>,
    /// How the conditions combine: `and` (default: a row meets all of them) or `or` (any).
    #[serde(default)]
    pub combine: Option<Combine>,
    /// Select the rows that do *not* meet the conditions.
    #[serde(default)]
    pub invert: Option<bool>,
}

/// One member of a category set: text, or a number for numeric codes.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum CategoryValue {
    /// A category name.
    Text(String),
    /// A numeric code (matches a numeric column's value exactly).
    Number(f64),
}

/// How a selection's conditions combine.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Combine {
    /// A row is selected when it meets every condition.
    And,
    /// A row is selected when it meets any condition.
    Or,
}

/// Where a table or a volume comes from: a file next to the spec, rows written inline, or another
/// source; then optional transforms (tables only).
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct DataSource {
    /// File path relative to the spec file (`.csv`, `.parquet`, `.json`, `.arrow`, `.geojson`,
    /// `.npy`, `.nii`, `.hdr`; any of them may end in `.gz` or `.zst`). A 3-D `.npy` array and a
    /// NIfTI-1 file are read as volumes.
    #[serde(default)]
    #[schemars(example = &"data/iris.csv")]
    pub path: Option<String>,
    /// File format; inferred from the path's extension when omitted.
    #[serde(default)]
    pub format: Option<DataFormat>,
    /// Inline rows, e.g. `values = [{ x = 1, y = 2 }, { x = 2, y = 3 }]` (instead of `path`).
    #[serde(default)]
    pub values: Option<Vec<BTreeMap<String, serde_json::Value>>>,
    /// For grid files (`npy`, `matrix`): coordinates `[x_first, x_last, y_first, y_last]` of the
    /// first and last column and row (default: the column and row indices). The table gets the
    /// columns `x`, `y` and `value`.
    #[serde(default)]
    pub extent: Option<[f64; 4]>,
    /// CSV field separator (one character; default `,`).
    #[serde(default)]
    #[schemars(length(min = 1, max = 1), example = &";")]
    pub delimiter: Option<String>,
    /// A query engine the source lives on: `"sc://HOST:PORT"` (Spark Connect; parameters
    /// `/;token=...;user_id=...` as Spark's clients take them). Its `path` (or `table`) is read
    /// by the cluster, its `filter`, `calculate` and `sql` steps run there, and only what the
    /// charts need comes back: a density view's counted bins, or the rows of other charts.
    #[serde(default)]
    #[schemars(example = &"sc://127.0.0.1:15002")]
    pub engine: Option<String>,
    /// For an `engine` source: a table of the engine's catalog (`name` or `db.name`), instead of
    /// a `path`.
    #[serde(default)]
    #[schemars(example = &"trips")]
    pub table: Option<String>,
    /// For an `engine` source: seconds one query may take before it is given up (default 600).
    #[serde(default)]
    #[schemars(range(min = 0.001), example = 120.0)]
    pub timeout: Option<f64>,
    /// Another data source whose rows (after its own transforms) this one starts from, instead
    /// of `path` or `values`: one file can feed several shapes.
    #[serde(default)]
    #[schemars(example = &"cars")]
    pub from: Option<String>,
    /// Steps run in order over the rows before any chart sees them, compiled into one lazy
    /// plan with the file scan: `filter`, `calculate`, `cast`, `bin`, `aggregate`, `fold`,
    /// `pivot`, `sort`, `sample`, `window`, `join`, `lookup`, `flatten`, `sql`.
    #[serde(default)]
    pub transform: Option<Vec<super::transform::TransformStep>>,
    /// For JSON files: the dotted path of the array of records (or the grid) inside the file's
    /// top-level object, e.g. `json_path = "nodes"` or `"data.rows"`.
    #[serde(default)]
    #[schemars(example = &"nodes")]
    pub json_path: Option<String>,
    /// How to read named columns instead of guessing: `"text"`, `"number"`, `"boolean"`, `"date"`
    /// (ISO 8601) or `"date:FORMAT"` with a strftime format, e.g.
    /// `parse = { when = "date:%b %d %Y", id = "text" }`.
    #[serde(default)]
    pub parse: Option<BTreeMap<String, String>>,
    /// For CSV files: the cell texts read as missing, in every column. Default: empty, `NA`,
    /// `N/A`, `n/a`, `NaN`, `nan`, `-nan`, `-NaN`, `null`, `NULL`, `None`, `#N/A`, `<NA>`; a list
    /// replaces it (`null_values = ["-999"]`), and `null_values = []` reads every text as written
    /// (an empty cell is still missing in a numeric column).
    #[serde(default)]
    #[schemars(example = &["-999", "NA"])]
    pub null_values: Option<Vec<String>>,
    /// For volumes from a 3-D `.npy` array or a raw file: the distance between neighbouring voxels
    /// along x, y and z, each positive (default `[1, 1, 1]`; NIfTI files carry their own).
    #[serde(default)]
    #[schemars(transform = positive_items, example = [1.0, 1.0, 2.5])]
    pub spacing: Option<[f64; 3]>,
    /// For volumes from a 3-D `.npy` array or a raw file: the world position of voxel
    /// `(0, 0, 0)` (default `[0, 0, 0]`; NIfTI files carry their own).
    #[serde(default)]
    #[schemars(example = [-1.0, -1.0, -1.0])]
    pub origin: Option<[f64; 3]>,
    /// For raw volumes (`format = "raw"`): the number of voxels along x, y and z, x varying
    /// fastest in the file.
    #[serde(default)]
    #[schemars(inner(range(min = 1)), example = [256, 256, 128])]
    pub dims: Option<[u64; 3]>,
    /// For raw volumes: the voxel type, `u8`, `i8`, `u16`, `i16`, `u32`, `i32`, `f32` or `f64`.
    #[serde(default)]
    pub dtype: Option<VoxelType>,
    /// For raw volumes: the byte order of multi-byte voxels, `little` (default) or `big`.
    #[serde(default)]
    pub byte_order: Option<ByteOrder>,
    /// For raw volumes: bytes to skip at the start of the file before the first voxel (default 0).
    #[serde(default)]
    #[schemars(example = 512)]
    pub header_bytes: Option<u64>,
    /// For NIfTI files with several volumes (a 4-D time series): which one to read, from 0
    /// (default 0, with a warning naming how many there are).
    #[serde(default)]
    #[schemars(example = 0)]
    pub frame: Option<u64>,
}

/// The type of one voxel of a raw volume.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum VoxelType {
    /// Unsigned 8-bit integers.
    U8,
    /// Signed 8-bit integers.
    I8,
    /// Unsigned 16-bit integers.
    U16,
    /// Signed 16-bit integers.
    I16,
    /// Unsigned 32-bit integers.
    U32,
    /// Signed 32-bit integers.
    I32,
    /// 32-bit floats.
    F32,
    /// 64-bit floats.
    F64,
}

/// The byte order of multi-byte values in a file.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ByteOrder {
    /// Least significant byte first (x86, ARM; the usual one).
    Little,
    /// Most significant byte first.
    Big,
}

/// Supported file formats.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum DataFormat {
    /// Comma-separated values with a header row.
    Csv,
    /// Apache Parquet.
    Parquet,
    /// A JSON array of records (`[{"x": 1}, ...]`) or newline-delimited records.
    Json,
    /// A NumPy array (`.npy`): 2-D, read as a grid (columns along x, rows along y), or 3-D of
    /// shape `(nz, ny, nx)`, read as a volume.
    Npy,
    /// A CSV file of numbers without a header, read as a grid: columns along x, rows along y.
    Matrix,
    /// A nested JSON tree (an object with a `children` array), flattened into columns `id`,
    /// `parent`, `path`, `name`, `depth` and one per field.
    Tree,
    /// Apache Arrow IPC file (Feather v2): `.arrow`, `.feather`, `.ipc`.
    Arrow,
    /// A GeoJSON FeatureCollection: one row per feature, its properties as columns, points as
    /// `lon`/`lat`, other geometries as GeoJSON text in `geometry` with `geometry_type`.
    Geojson,
    /// A NIfTI-1 volume (`.nii`, `.nii.gz`, or a `.hdr`/`.img` pair): voxel spacing, orientation
    /// and value scaling from its header.
    Nifti,
    /// A raw volume: voxels only, described by `dims`, `dtype`, `byte_order`, `spacing` and
    /// `header_bytes`.
    Raw,
}

/// One chart: options shared by every kind, plus the options of its `kind`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct Chart {
    /// Output file stem: letters, digits, `-`, `_` and `.` only.
    #[schemars(pattern(r"^[A-Za-z0-9._-]+$"), example = &"iris-scatter")]
    pub name: String,
    /// Name of the data source (a key of `[data]`).
    #[schemars(example = &"iris")]
    pub data: String,
    /// Title drawn above the chart.
    #[serde(default)]
    pub title: Option<String>,
    /// Caption drawn below the chart (source, notes).
    #[serde(default)]
    pub caption: Option<String>,
    /// Canvas size `[width, height]` in CSS pixels, each at most 16384 (default: the kind's own, `[640, 420]` for one x/y frame).
    #[serde(default)]
    #[schemars(inner(range(max = 16384)), transform = positive_items, example = example_size())]
    pub size: Option<[f64; 2]>,
    /// Base font size in CSS pixels for tick labels, 1 to 200 (titles scale from it; default 12).
    #[serde(default)]
    #[schemars(range(min = 1, max = 200), example = 12)]
    pub font_size: Option<f64>,
    /// Aspect of the plot area of the kinds drawn in one x/y frame: `"equal"` makes one data
    /// unit as long on x as on y, shrinking the plot along one axis (centred) instead of
    /// stretching the data; `"auto"` (default) fills the room. Both axes must be linear.
    #[serde(default)]
    pub aspect: Option<Aspect>,
    /// Name of a selection (`[selection.NAME]`) over the same data: its rows are drawn in full
    /// colour, the rest as grey context, and its ranges are marked on the axes
    /// (scatter, box, violin, splom, parallel, daisy, faces, segments).
    #[serde(default)]
    #[schemars(example = &"small")]
    pub highlight: Option<String>,
    /// Lint configuration for this chart, applied on top of the spec's `[lint]`:
    /// `lint = { allow = ["CM002"] }`.
    #[serde(default)]
    pub lint: Option<LintConfig>,
    /// Hover text in SVG output: each data mark carries a `<title>` with its row's values of
    /// the chart's columns (default, for charts of at most 5,000 marks), of the columns listed
    /// here (however many marks), or none (`false`). Marks drawn from several rows show their
    /// label and row count.
    #[serde(default)]
    #[schemars(example = &["name", "value"])]
    pub tooltip: Option<Tooltip>,
    /// Notes over the data of the kinds drawn in one x/y frame, each a `[[chart.annotate]]`
    /// table: a rule (`y = 50`), a band (`x = [a, b]`), text at a point (`text`, `at`) or an
    /// arrow (`arrow`), in the data's values (dates and categories as text).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub annotate: Vec<super::annotation::Annotation>,
    /// Small multiples: one panel per value of a column, `facet = "species"` (panels wrapped
    /// into a near-square grid), or `facet = { row = "sex", column = "island" }` for a grid of
    /// two columns' values. Panels share their scales unless `resolve` says otherwise; each has
    /// its value as a header, and only the outer panels carry tick labels.
    #[serde(default)]
    pub facet: Option<Facet>,
    /// Set while a facet panel is drawn: the scales and plot the panel must use, and what it
    /// saw of its own. Never read from or written to a spec.
    #[serde(skip)]
    #[schemars(skip)]
    pub panel: Option<crate::mark::panel::PanelHandle>,
    /// What to draw and how.
    #[serde(flatten)]
    pub kind: ChartKind,
}

/// Small multiples of a chart: a column, or a table of options.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum Facet {
    /// One panel per value of this column, wrapped into a near-square grid.
    Field(String),
    /// `{ row, column, wrap, resolve, sort }`.
    Detailed(FacetOptions),
}

impl Facet {
    /// The options, with a bare column read as `column` wrapped into a near-square grid.
    pub fn options(&self) -> FacetOptions {
        match self {
            Facet::Field(field) => {
                FacetOptions { row: None, column: Some(field.clone()), wrap: None, resolve: None, sort: None }
            }
            Facet::Detailed(options) => options.clone(),
        }
    }

    /// Whether panels wrap into a near-square grid when `wrap` is not given (a bare column).
    pub fn wraps_by_default(&self) -> bool {
        matches!(self, Facet::Field(_))
    }
}

/// Options of small multiples.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FacetOptions {
    /// Column whose values make the rows of panels (headers on the right).
    #[serde(default)]
    #[schemars(example = &"sex")]
    pub row: Option<String>,
    /// Column whose values make the columns of panels (headers on top).
    #[serde(default)]
    #[schemars(example = &"island")]
    pub column: Option<String>,
    /// With `column` alone: at most this many panels side by side, the rest wrapping onto
    /// further rows (default: all in one row), 1 to 50.
    #[serde(default)]
    #[schemars(range(min = 1, max = 50), example = 3)]
    pub wrap: Option<u32>,
    /// Whether each channel's scale is shared by all panels (default) or each panel's own:
    /// `resolve = { y = "independent" }`. Unshared scales are reported by lint rule CM001.
    #[serde(default)]
    pub resolve: Option<FacetResolve>,
    /// Panel order: `"ascending"` values (default; numbers and dates by value) or `"data"`
    /// (order of first appearance).
    #[serde(default)]
    pub sort: Option<FacetSort>,
}

/// Which position scales facet panels share. Colours are always shared: one category has one
/// colour, and one colour bar spans every panel's values.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FacetResolve {
    /// The x axis (default `"shared"`).
    #[serde(default)]
    pub x: Option<Sharing>,
    /// The y axis (default `"shared"`).
    #[serde(default)]
    pub y: Option<Sharing>,
}

/// Whether panels share a scale.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Sharing {
    /// One scale over every panel's data.
    #[default]
    Shared,
    /// Each panel's scale over its own data.
    Independent,
}

/// The order of facet panels.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum FacetSort {
    /// Ascending values: numbers and dates by value, text alphabetically.
    #[default]
    Ascending,
    /// The order in which values first appear in the data.
    Data,
}

/// A trend line through a scatter: a method, or a table of options.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum Trend {
    /// `"linear"` or `"loess"`, through all drawn points.
    Method(TrendMethod),
    /// `{ method, span, groups, equation }`.
    Detailed(TrendOptions),
}

impl Trend {
    /// The options, with defaults for a bare method.
    pub fn options(&self) -> TrendOptions {
        match self {
            Trend::Method(m) => TrendOptions { method: *m, span: None, groups: None, equation: None },
            Trend::Detailed(o) => o.clone(),
        }
    }
}

/// How a trend line is fitted.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum TrendMethod {
    /// Least squares: the line with its equation and R².
    Linear,
    /// Locally weighted linear regression with tricube weights (lowess without robustness
    /// iterations).
    Loess,
}

/// Options of a trend line.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct TrendOptions {
    /// `"linear"` or `"loess"`.
    pub method: TrendMethod,
    /// LOESS: the fraction of the points each local line is fitted to, above 0 and at most 1
    /// (default 0.75).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 1), example = 0.5)]
    pub span: Option<f64>,
    /// One line per colour category, in its colour (default: one line through all points).
    #[serde(default)]
    pub groups: Option<bool>,
    /// Write the linear fit's equation and R² in the plot (default true for linear fits).
    #[serde(default)]
    pub equation: Option<bool>,
}

/// Hover texts of a chart's marks: on or off, or the columns to list.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum Tooltip {
    /// `true` (default): the chart's own columns; `false`: no hover texts.
    Show(bool),
    /// These columns, in this order (at most 20).
    Fields(#[schemars(length(max = 20))] Vec<String>),
}

/// How the plot area's sides relate to the data's units.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Aspect {
    /// Fill the room the guides leave.
    #[default]
    Auto,
    /// One data unit is the same length on x and on y.
    Equal,
}

/// The chart kinds, each with its own options: generated from the technique registry
/// (`mark::registry`), where each kind is listed once.
pub use crate::mark::registry::ChartKind;
pub use crate::mark::registry::options::*;

/// How an image is resampled to pixels.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Resample {
    /// Each pixel takes the value of the nearest grid node.
    Nearest,
    /// Each pixel takes the bilinear interpolation of the four surrounding nodes.
    Bilinear,
}

/// Where a tree's shape comes from: an `id` and a `parent` column, or one `path` column.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct TreeSource {
    /// Column of node ids (with `parent`).
    #[serde(default)]
    #[schemars(example = &"id")]
    pub id: Option<String>,
    /// Column of each node's parent id; empty for top-level nodes (several top-level nodes get a
    /// root named `(all)` above them).
    #[serde(default)]
    #[schemars(example = &"parent")]
    pub parent: Option<String>,
    /// Column of paths such as `flare/vis/axis` (instead of `id` and `parent`); inner nodes a
    /// path implies are added.
    #[serde(default)]
    #[schemars(example = &"path")]
    pub path: Option<String>,
    /// Separator of `path` segments (default `/`).
    #[serde(default)]
    pub separator: Option<String>,
}

/// A node table for a network: ids matching the edges' endpoints, plus attributes.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct NodeTable {
    /// Data source of the nodes (a key of `[data]`).
    #[schemars(example = &"airports")]
    pub data: String,
    /// Column of node ids, matching the edges' `source` and `target`.
    #[schemars(example = &"code")]
    pub id: String,
    /// Column of node labels (default: the id).
    #[serde(default)]
    pub label: Option<String>,
    /// Numeric column scaling node area.
    #[serde(default)]
    pub size: Option<String>,
    /// Colour nodes by a column (text: categories; numbers: a colour map).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Column of given x positions (`layout = "given"`).
    #[serde(default)]
    pub x: Option<String>,
    /// Column of given y positions (`layout = "given"`).
    #[serde(default)]
    pub y: Option<String>,
    /// Draw nodes without a link to another node. Default: false for `linkmap` and for `graph`
    /// with `layout = "given"` (a table of places lists many without a route), true for the
    /// other graph layouts. Left-out nodes are counted in a warning.
    #[serde(default)]
    pub isolated: Option<bool>,
}

/// How a network's nodes are placed.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum GraphLayout {
    /// Force-directed, multilevel with a Barnes–Hut approximation; deterministic for a `seed`.
    Force,
    /// Nodes on a circle, ordered to reduce crossings.
    Circular,
    /// Layers top to bottom along the edges' direction (Sugiyama), for directed acyclic graphs.
    Layered,
    /// Positions from the node table's `x` and `y` columns.
    Given,
}

/// Contour levels: how many, or which.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum Levels {
    /// About this many nice round levels (1 to 100) between the field's minimum and maximum.
    Count(#[schemars(range(min = 1, max = 100))] u32),
    /// Exactly these levels (at most 1000).
    Values(#[schemars(length(max = 1000))] Vec<f64>),
}

/// `field()` and `options()` for a channel written either as a bare column name or as a table of
/// options with a `field` key.
macro_rules! field_channel {
    ($channel:ident, $options:ident) => {
        impl $channel {
            /// The column name.
            pub fn field(&self) -> &str {
                match self {
                    $channel::Field(f) => f,
                    $channel::Detailed(o) => &o.field,
                }
            }
            /// The options, with defaults for a bare column name.
            pub fn options(&self) -> $options {
                match self {
                    $channel::Field(f) => $options { field: f.clone(), ..$options::default() },
                    $channel::Detailed(o) => o.clone(),
                }
            }
        }
    };
}

/// A single value or a list of them.
///
/// A list is tried first: serde reads a struct from a sequence of its fields in order, so with
/// `One` first a list of names `["a", "b"]` would become one channel with field `a` and title `b`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum OneOrMany<T> {
    /// Several.
    Many(Vec<T>),
    /// Just one.
    One(T),
}

impl<T> OneOrMany<T> {
    /// The values as a slice.
    pub fn as_slice(&self) -> &[T] {
        match self {
            OneOrMany::One(v) => std::slice::from_ref(v),
            OneOrMany::Many(vs) => vs,
        }
    }
}

/// A positional encoding: a column name, or a table with options.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum Channel {
    /// Just the column name.
    Field(String),
    /// A column with axis options.
    Detailed(ChannelOptions),
}

/// Axis options of a positional encoding.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ChannelOptions {
    /// Column name.
    #[schemars(example = &"petal_length")]
    pub field: String,
    /// Axis title (default: the column name).
    #[serde(default)]
    pub title: Option<String>,
    /// Unit shown in the axis title, e.g. `"cm"` → "Petal length (cm)".
    #[serde(default)]
    pub unit: Option<String>,
    /// Scale type (default: `time` for date/time columns, `band` for text, else `linear`).
    #[serde(default)]
    pub scale: Option<ScaleKind>,
    /// Fixed domain `[min, max]` instead of the data's extent.
    #[serde(default)]
    #[schemars(example = example_domain())]
    pub domain: Option<[f64; 2]>,
    /// Include zero in the domain.
    #[serde(default)]
    pub zero: Option<bool>,
    /// Extend the domain to nice tick values (default true).
    #[serde(default)]
    pub nice: Option<bool>,
    /// Approximate number of ticks, 2 to 50 (default: from the axis length).
    #[serde(default)]
    #[schemars(range(min = 2, max = 50), example = 5)]
    pub ticks: Option<u32>,
    /// Draw grid lines at the ticks (default true).
    #[serde(default)]
    pub grid: Option<bool>,
}

field_channel!(Channel, ChannelOptions);

/// Scale types.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ScaleKind {
    /// Linear numbers.
    Linear,
    /// Base-10 logarithm (rows with values ≤ 0 are dropped, with a warning).
    Log,
    /// Dates and times.
    Time,
    /// Categories placed in equal bands.
    Band,
}

/// A colour encoding: a column name, or a table with options.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum ColorChannel {
    /// Just the column name.
    Field(String),
    /// A column with colour options.
    Detailed(ColorOptions),
}

/// Options of a colour encoding.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ColorOptions {
    /// Column name.
    #[schemars(example = &"petal_length")]
    pub field: String,
    /// Legend or colour-bar title (default: the column name).
    #[serde(default)]
    pub title: Option<String>,
    /// Unit shown in the colour-bar title.
    #[serde(default)]
    pub unit: Option<String>,
    /// Colour scheme: a categorical palette (`okabe-ito`, `tableau10`, ...) or a continuous map
    /// (`viridis`, `magma`, `rdbu`, ...; append `_r` to reverse).
    #[serde(default)]
    pub scheme: Option<String>,
    /// Treat the column as categories or as a continuous quantity (default: from its type).
    #[serde(default)]
    pub r#type: Option<ColorType>,
    /// Centre of a diverging scheme (default: the middle of the domain).
    #[serde(default)]
    pub midpoint: Option<f64>,
    /// Draw the legend or colour bar (default true). Without it the colours cannot be decoded;
    /// lint rule SC004 reports that.
    #[serde(default)]
    pub legend: Option<bool>,
    /// Categorical colours: the categories in colour and legend order, e.g. `["USA", "Japan"]`
    /// (numbers for numeric codes). Every category drawn must be listed (default: the spec-wide
    /// order of the column's categories, so a category has one colour in every chart).
    #[serde(default)]
    pub domain: Option<Vec<CategoryValue>>,
    /// Categorical colours: one colour per `domain` entry (CSS hex such as `"#1f77b4"` or a
    /// colour name), used instead of `scheme`; it needs at least as many colours as categories.
    #[serde(default)]
    pub range: Option<Vec<String>>,
}

field_channel!(ColorChannel, ColorOptions);

/// How a colour column is read.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ColorType {
    /// Distinct categories with a legend.
    Categorical,
    /// A continuous quantity with a colour bar.
    Continuous,
}

/// A size encoding: marker area proportional to a column.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum SizeChannel {
    /// Just the column name.
    Field(String),
    /// A column with size options.
    Detailed(SizeOptions),
}

/// Options of a size encoding.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SizeOptions {
    /// Column name (numeric, ≥ 0).
    #[schemars(example = &"population")]
    pub field: String,
    /// Legend title (default: the column name).
    #[serde(default)]
    pub title: Option<String>,
    /// Unit shown in the legend title.
    #[serde(default)]
    pub unit: Option<String>,
    /// Largest marker radius in pixels, at most 200 (default 12); area is proportional to the value.
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 200), example = 12)]
    pub max_radius: Option<f64>,
    /// How values map to markers: `area` (default: area proportional to the value, which reads
    /// true) or `radius` (radius proportional to the value, which exaggerates differences as their
    /// square; lint rule DI002 reports it). Scatter charts only.
    #[serde(default)]
    pub mapping: Option<SizeMapping>,
}

/// How a size encoding maps values to marker size.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SizeMapping {
    /// Marker area proportional to the value.
    #[default]
    Area,
    /// Marker radius proportional to the value (areas grow with its square).
    Radius,
}

field_channel!(SizeChannel, SizeOptions);

/// Schema transform: the items of an array field must be greater than zero.
fn positive_items(schema: &mut schemars::Schema) {
    if let Some(items) = schema.get_mut("items").and_then(serde_json::Value::as_object_mut) {
        items.insert("exclusiveMinimum".to_owned(), serde_json::Value::from(0));
    }
}

/// Schema example of `size`.
fn example_size() -> [u32; 2] {
    [800, 600]
}

/// Schema example of `columns`.
pub(crate) fn example_columns() -> [&'static str; 3] {
    ["sepal_length", "sepal_width", "petal_length"]
}

/// Schema example of `domain`.
fn example_domain() -> [u32; 2] {
    [0, 100]
}
