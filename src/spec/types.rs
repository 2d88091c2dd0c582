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

/// Where a table comes from: a file next to the spec, rows written inline, or another source;
/// then optional transforms.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct DataSource {
    /// File path relative to the spec file (`.csv`, `.parquet`, `.json`, `.arrow`, `.geojson`,
    /// `.npy`; any of them may end in `.gz` or `.zst`).
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
    /// A 2-D NumPy array (`.npy`), read as a grid: columns along x, rows along y.
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
    /// (scatter, splom, parallel, daisy, faces, segments).
    #[serde(default)]
    #[schemars(example = &"small")]
    pub highlight: Option<String>,
    /// Lint configuration for this chart, applied on top of the spec's `[lint]`:
    /// `lint = { allow = ["CM002"] }`.
    #[serde(default)]
    pub lint: Option<LintConfig>,
    /// What to draw and how.
    #[serde(flatten)]
    pub kind: ChartKind,
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

/// The chart kinds. Each kind has its own options.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum ChartKind {
    /// Points at (x, y), optionally coloured and sized by columns.
    Scatter(ScatterOptions),
    /// One or more series drawn as lines through (x, y).
    Line(LineOptions),
    /// Vertical bars from zero: one per category of `x` (grouped side by side by `color`), rows
    /// of the same category summed.
    Bar(BarOptions),
    /// Sample points and the curves of one or more 1D interpolation methods through them.
    Interp1d(Interp1dOptions),
    /// Contour lines and filled bands of a scalar field on a regular grid.
    Contour(ContourOptions),
    /// A scalar field on a regular grid as a colour image (heatmap) with a colour bar.
    Image(ImageOptions),
    /// Cross-sections of a gridded field: z along x at chosen y values (or along y at chosen x).
    Section(SectionOptions),
    /// Scattered points: Delaunay triangulation, linear interpolation in the triangles, contours
    /// on the triangulation, and Voronoi tiles.
    Scattered(ScatteredOptions),
    /// A gridded field as a shaded 3D surface (orthographic, hidden surfaces removed).
    Surface(SurfaceOptions),
    /// A matrix of 2D slices through gridded data of more than two dimensions, around a focus point.
    Hyperslice(HypersliceOptions),
    /// Scatter-plot matrix: every pair of columns, sharing one scale per column.
    Splom(SplomOptions),
    /// Parallel coordinates: one vertical axis per column, one polyline per row.
    Parallel(ParallelOptions),
    /// Daisy chart: columns on arcs around a circle, each row a closed curve through its values.
    Daisy(DaisyOptions),
    /// Chernoff faces: one face per row, columns driving facial features.
    Faces(FacesOptions),
    /// Circle segments: one wedge per column, rows as pixels from the centre outward.
    Segments(SegmentsOptions),
    /// Treemap: a hierarchy as nested rectangles whose areas are the leaves' values.
    Treemap(TreemapOptions),
    /// Hyperbolic tree: a hierarchy laid out in the Poincaré disk around a focus node.
    Hypertree(HypertreeOptions),
    /// Node-link diagram of a network: force-directed, circular or layered layout.
    Graph(GraphOptions),
    /// SeeNet-style link view: links drawn thin to thick by their statistic, or an
    /// adjacency matrix for dense networks.
    Linkmap(LinkmapOptions),
    /// A 2-D vector field: speed image, arrows, streamlines, particle traces, line integral
    /// convolution and vector field topology, as layers.
    Flow(FlowOptions),
}

impl ChartKind {
    /// The kind's name as written in the spec (from its entry in the technique registry).
    pub fn name(&self) -> &'static str {
        crate::mark::technique(self).info().name
    }
}

/// Options of `kind = "scatter"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ScatterOptions {
    /// Horizontal position: a column name or a table with `field`, `title`, `unit`, `scale`, ...
    #[schemars(example = &"sepal_length")]
    pub x: Channel,
    /// Vertical position: a column name or a table with `field`, `title`, `unit`, `scale`, ...
    #[schemars(example = &"petal_length")]
    pub y: Channel,
    /// Colour by a column (categorical columns get a legend, numeric ones a colour bar).
    #[serde(default)]
    #[schemars(example = &"species")]
    pub color: Option<ColorChannel>,
    /// Marker area proportional to a numeric column.
    #[serde(default)]
    #[schemars(example = &"population")]
    pub point_size: Option<SizeChannel>,
    /// Marker radius in pixels, at most 100, when `point_size` is not given (default: 3, smaller for many points).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100), example = 3)]
    pub radius: Option<f64>,
    /// Marker colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
    /// Marker opacity in 0..=1 (default: 0.8, lower for many points).
    #[serde(default)]
    #[schemars(range(min = 0, max = 1), example = 0.5)]
    pub opacity: Option<f64>,
}

/// Options of `kind = "line"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct LineOptions {
    /// Horizontal position: a column name or a table with `field`, `title`, `unit`, `scale`, ...
    #[schemars(example = &"date")]
    pub x: Channel,
    /// Vertical position: one column (long form, split by `series`) or several (one series each).
    #[schemars(example = &"price")]
    pub y: OneOrMany<Channel>,
    /// Column whose values split the rows into series (long-form data).
    #[serde(default)]
    pub series: Option<String>,
    /// Split the rows into series by a column's categories, one colour each, as `series` does
    /// (how Vega-Lite and ggplot write it); a table adds the colour options (`scheme`, `domain`,
    /// `range`, `title`, `legend`), and a category has the same colour as in the spec's other
    /// charts colouring by that column. Give this or `series`, not both.
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Title of the y axis when several y columns are drawn (their own titles name the series).
    #[serde(default)]
    pub y_title: Option<String>,
    /// Draw a marker at every data point.
    #[serde(default)]
    pub markers: Option<bool>,
    /// Line width in pixels, at most 100 (default 2).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100), example = 2)]
    pub stroke_width: Option<f64>,
    /// Categorical colour scheme for the series (default `okabe-ito`).
    #[serde(default)]
    pub scheme: Option<String>,
    /// Line colour when there is a single series (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

impl LineOptions {
    /// The column splitting the rows into series: `series`, else the `color` encoding's field.
    pub fn split_field(&self) -> Option<&str> {
        self.series.as_deref().or(self.color.as_ref().map(ColorChannel::field))
    }
}

/// Options of `kind = "bar"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct BarOptions {
    /// The categories along the horizontal axis: a text column, or numbers treated as categories
    /// (one band each, in ascending order).
    #[schemars(example = &"state")]
    pub x: Channel,
    /// The bar length: a numeric column; rows with the same `x` (and `color`) are summed. Bars
    /// start at zero unless `zero = false` or a `domain` leaves zero out (lint rule DI001).
    #[schemars(example = &"flights")]
    pub y: Channel,
    /// Group bars side by side within each category by a categorical column, with a legend.
    #[serde(default)]
    #[schemars(example = &"origin")]
    pub color: Option<ColorChannel>,
    /// Bar colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// Options of `kind = "interp1d"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct Interp1dOptions {
    /// The knots' positions: a numeric column (rows are sorted by it; values must be distinct).
    pub x: Channel,
    /// The knots' values: a numeric column.
    pub y: Channel,
    /// Interpolation methods to overlay (default `["pchip"]`).
    #[serde(default)]
    pub methods: Option<Vec<InterpMethod>>,
    /// Column of slopes dy/dx at the knots, used by the `hermite` method.
    #[serde(default)]
    pub slopes: Option<String>,
    /// Keep `hermite` and `hermite-mean` curves within the range of neighbouring data.
    #[serde(default)]
    pub bounded: Option<bool>,
    /// Points per curve in the derived CSV and on non-linear scales (default 512).
    #[serde(default)]
    #[schemars(range(min = 2, max = 100000))]
    pub samples: Option<u32>,
    /// Draw the knots as points (default true).
    #[serde(default)]
    pub knots: Option<bool>,
    /// Line width in pixels, at most 100 (default 2).
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 100))]
    pub stroke_width: Option<f64>,
    /// Categorical colour scheme for the methods (default `okabe-ito`).
    #[serde(default)]
    pub scheme: Option<String>,
}

/// 1D interpolation methods.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum InterpMethod {
    /// Nearest neighbour: steps at the midpoints between knots.
    Nearest,
    /// Straight lines between knots.
    Linear,
    /// Cubic Hermite with the slopes given by the `slopes` column.
    Hermite,
    /// Cubic Hermite with slopes from the arithmetic mean of the adjacent chord slopes.
    HermiteMean,
    /// Cubic Hermite with harmonic-mean slopes (monotone; matches SciPy's PchipInterpolator).
    Pchip,
}

/// Options of `kind = "contour"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ContourOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node).
    pub x: Channel,
    /// Grid y coordinate: a numeric column of a long-form table (one row per grid node).
    pub y: Channel,
    /// The field's value at each node: a column name, or `{ field, title, unit, scheme, midpoint }`
    /// (the colour map of the filled bands, default `viridis`).
    pub z: ColorChannel,
    /// A number of levels (nice round values are chosen; default 10) or the levels themselves.
    #[serde(default)]
    pub levels: Option<Levels>,
    /// How saddle cells are resolved: `asymptotic` (default, the bilinear patch's true topology)
    /// or `center` (the mean of the four corners).
    #[serde(default)]
    pub saddle: Option<SaddleRule>,
    /// Fill the bands between levels (default true).
    #[serde(default)]
    pub fill: Option<bool>,
    /// Draw the contour lines (default true).
    #[serde(default)]
    pub lines: Option<bool>,
    /// Write each level's value on its longest line (default true).
    #[serde(default)]
    pub labels: Option<bool>,
}

/// Options of `kind = "image"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ImageOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node).
    pub x: Channel,
    /// Grid y coordinate: a numeric column of a long-form table (one row per grid node).
    pub y: Channel,
    /// The field's value: a column name, or `{ field, title, unit, scheme, midpoint }`.
    pub z: ColorChannel,
    /// `nearest` (default: each node colours the cell around it) or `bilinear` (smooth).
    #[serde(default)]
    pub resample: Option<Resample>,
    /// Colour of missing cells (default light grey, `#d9d9d9`).
    #[serde(default)]
    pub nan_color: Option<String>,
}

/// How an image is resampled to pixels.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Resample {
    /// Each pixel takes the value of the nearest grid node.
    Nearest,
    /// Each pixel takes the bilinear interpolation of the four surrounding nodes.
    Bilinear,
}

/// Options of `kind = "section"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SectionOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node).
    pub x: Channel,
    /// Grid y coordinate: a numeric column of a long-form table (one row per grid node).
    pub y: Channel,
    /// The field's value: a column name, or `{ field, title, unit }`.
    pub z: ColorChannel,
    /// Sections along x at these y values (give this or `at_x`).
    #[serde(default)]
    pub at_y: Option<Vec<f64>>,
    /// Sections along y at these x values (give this or `at_y`).
    #[serde(default)]
    pub at_x: Option<Vec<f64>>,
    /// `overlay` (default: one plot, a line per section) or `multiples` (one panel per
    /// section, stacked, sharing both scales).
    #[serde(default)]
    pub layout: Option<SectionLayout>,
    /// With `layout = "multiples"`: give every panel the same value scale (default true), or
    /// `false` for a scale per panel fitted to its own section (for sections of very different
    /// magnitude; the panels can then no longer be compared by height, and lint rule CM001 says so).
    #[serde(default)]
    pub shared_scale: Option<bool>,
    /// Line width in pixels, at most 100 (default 2).
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 100))]
    pub stroke_width: Option<f64>,
    /// Categorical colour scheme for the sections (default `okabe-ito`).
    #[serde(default)]
    pub scheme: Option<String>,
}

/// How sections are arranged.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SectionLayout {
    /// All sections in one plot.
    Overlay,
    /// One panel per section, sharing scales.
    Multiples,
}

/// Options of `kind = "scattered"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ScatteredOptions {
    /// Point x coordinate (numeric).
    pub x: Channel,
    /// Point y coordinate (numeric).
    pub y: Channel,
    /// The value at each point: a column name, or `{ field, title, unit, scheme, midpoint }`.
    pub z: ColorChannel,
    /// Fill the triangulation with the linear interpolant of z (default true).
    #[serde(default)]
    pub fill: Option<bool>,
    /// Draw the edges of the Delaunay triangles (default true).
    #[serde(default)]
    pub mesh: Option<bool>,
    /// Overlay the Voronoi (Dirichlet) tiles of the points (default false).
    #[serde(default)]
    pub voronoi: Option<bool>,
    /// Contour lines on the triangulation: a number of nice levels or the levels themselves
    /// (default: none).
    #[serde(default)]
    pub levels: Option<Levels>,
    /// Draw the points on top (default true).
    #[serde(default)]
    pub points: Option<bool>,
}

/// Options of `kind = "surface"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SurfaceOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node).
    pub x: Channel,
    /// Grid y coordinate: a numeric column of a long-form table (one row per grid node).
    pub y: Channel,
    /// The height: a column name, or `{ field, title, unit, scheme, midpoint }` (surface colours).
    pub z: ColorChannel,
    /// Viewing direction in degrees, counter-clockwise from +x (default −60).
    #[serde(default)]
    pub azimuth: Option<f64>,
    /// Height of the eye above the xy plane in degrees, 1 to 90 (default 30).
    #[serde(default)]
    #[schemars(range(min = 1.0, max = 90.0))]
    pub elevation: Option<f64>,
    /// Drawn z length per x/y unit (default: the z range drawn at half the larger horizontal extent).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    pub z_scale: Option<f64>,
}

/// Options of `kind = "hyperslice"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct HypersliceOptions {
    /// The grid's coordinate columns, one per dimension (2 to 16), in a long-form table with one
    /// row per grid node.
    pub axes: Vec<String>,
    /// The value: a column name, or `{ field, title, unit, scheme, midpoint }`.
    pub z: ColorChannel,
    /// The focus point, one coordinate per axis (default: the middle node of each axis); each
    /// slice holds the other axes at the grid node nearest the focus.
    #[serde(default)]
    pub focus: Option<Vec<f64>>,
}

/// Options of `kind = "splom"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SplomOptions {
    /// The columns, 2 to 12: names, or tables with `field`, `title`, `unit`, `scale`, `domain`, ...
    #[schemars(length(min = 2, max = 12), example = example_columns())]
    pub columns: Vec<Channel>,
    /// Colour points by a column (categories get a legend, numbers a colour bar).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Which cells to draw: `full` (default), `lower` or `upper` triangle.
    #[serde(default)]
    pub layout: Option<MatrixLayout>,
    /// The diagonal cells: `histogram` (default), `density` (kernel density) or `label`.
    #[serde(default)]
    pub diagonal: Option<Diagonal>,
    /// Histogram bins on the diagonal, 2 to 200 (default: Freedman–Diaconis, at most 50).
    #[serde(default)]
    #[schemars(range(min = 2, max = 200))]
    pub bins: Option<u32>,
    /// `points` (one marker per row), `density` (counts per small bin, for large tables) or
    /// `auto` (default: density above 200,000 rows).
    #[serde(default)]
    pub mode: Option<SplomMode>,
    /// Marker radius in pixels, at most 100 (default: from the row count).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100))]
    pub radius: Option<f64>,
    /// Marker opacity in 0..=1 (default: from the row count).
    #[serde(default)]
    #[schemars(range(min = 0, max = 1))]
    pub opacity: Option<f64>,
    /// Marker colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// Which cells of a matrix are drawn.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum MatrixLayout {
    /// Every cell.
    Full,
    /// The diagonal and the cells below it.
    Lower,
    /// The diagonal and the cells above it.
    Upper,
}

/// What the diagonal cells of a scatter-plot matrix show.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Diagonal {
    /// A histogram of the column.
    Histogram,
    /// A Gaussian kernel density estimate of the column (Silverman's bandwidth).
    Density,
    /// The column's name only.
    Label,
}

/// How a scatter-plot matrix draws its rows.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SplomMode {
    /// One marker per row.
    Points,
    /// Rows counted in small bins, drawn as a shaded raster.
    Density,
    /// Points up to 200,000 rows, density above.
    Auto,
}

/// Options of `kind = "parallel"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct ParallelOptions {
    /// The axes' columns, 2 to 64: numeric columns get nice-ticked scales, text columns one
    /// position per category.
    #[schemars(length(min = 2, max = 64), example = example_columns())]
    pub columns: Vec<Channel>,
    /// Colour lines by a column (categories get a legend, numbers a colour bar).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// `given` (default: as listed) or `correlation` (neighbouring axes strongly correlated,
    /// starting from the first column).
    #[serde(default)]
    pub order: Option<AxisOrder>,
    /// Columns whose axes run top to bottom (high values at the bottom).
    #[serde(default)]
    pub invert: Option<Vec<String>>,
    /// One scale shared by every numeric axis (default false: each axis its own).
    #[serde(default)]
    pub shared_scale: Option<bool>,
    /// Line opacity in 0..=1 (default: from the row count).
    #[serde(default)]
    #[schemars(range(min = 0, max = 1))]
    pub opacity: Option<f64>,
    /// Line width in pixels, at most 100 (default: from the row count).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100))]
    pub stroke_width: Option<f64>,
    /// Line colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// How the axes of parallel coordinates are ordered.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum AxisOrder {
    /// As listed in `columns`.
    Given,
    /// Greedy: each next axis is the remaining column most correlated (|Pearson r|) with the
    /// previous one.
    Correlation,
}

/// Options of `kind = "daisy"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct DaisyOptions {
    /// The columns, 3 to 24, placed clockwise from the top, each on its own arc and scale.
    #[schemars(length(min = 3, max = 24), example = example_columns())]
    pub columns: Vec<Channel>,
    /// Colour curves by a column (categories get a legend, numbers a colour bar).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Curve opacity in 0..=1 (default: from the row count).
    #[serde(default)]
    #[schemars(range(min = 0, max = 1))]
    pub opacity: Option<f64>,
    /// Curve width in pixels, at most 100 (default: from the row count).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 100))]
    pub stroke_width: Option<f64>,
    /// Curve colour when `color` is not given (CSS name or `#rrggbb`).
    #[serde(default)]
    pub mark_color: Option<String>,
}

/// Options of `kind = "faces"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct FacesOptions {
    /// Up to 15 numeric columns, assigned to features in the order face width, face height,
    /// face shape, eye size, eye spacing, eye slant, pupil position, brow slant, brow height,
    /// nose length, nose width, mouth curvature, mouth width, mouth openness, ear size
    /// (give this or `features`).
    #[serde(default)]
    #[schemars(example = example_columns())]
    pub columns: Option<Vec<String>>,
    /// Columns by feature, e.g. `{ mouth_curvature = "mpg", hair = "hp" }` (up to 15).
    #[serde(default)]
    pub features: Option<FaceFeatures>,
    /// Column whose values label the faces (default: the row number).
    #[serde(default)]
    pub label: Option<String>,
    /// Colour the faces by a column (categories get a legend).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Faces per row of the grid (default: from the canvas' aspect ratio).
    #[serde(default)]
    #[schemars(range(min = 1, max = 100))]
    pub per_row: Option<u32>,
    /// Draw the feature key saying which column drives which feature (default true). Without it
    /// the faces cannot be read; lint rule TQ005 reports that.
    #[serde(default)]
    pub key: Option<bool>,
}

/// Columns driving facial features; a feature without a column stays neutral.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct FaceFeatures {
    /// Narrow to wide face.
    #[serde(default)]
    pub face_width: Option<String>,
    /// Short to tall face.
    #[serde(default)]
    pub face_height: Option<String>,
    /// Round to pointed chin.
    #[serde(default)]
    pub face_shape: Option<String>,
    /// Small to large eyes.
    #[serde(default)]
    pub eye_size: Option<String>,
    /// Close-set to wide-set eyes.
    #[serde(default)]
    pub eye_spacing: Option<String>,
    /// Eyes slanting down to up at the outer corners.
    #[serde(default)]
    pub eye_slant: Option<String>,
    /// Pupils looking left to right.
    #[serde(default)]
    pub pupil_position: Option<String>,
    /// Brows slanting down to up at the outer ends.
    #[serde(default)]
    pub brow_slant: Option<String>,
    /// Low to high brows.
    #[serde(default)]
    pub brow_height: Option<String>,
    /// Short to long nose.
    #[serde(default)]
    pub nose_length: Option<String>,
    /// Narrow to wide nose.
    #[serde(default)]
    pub nose_width: Option<String>,
    /// Frown to smile.
    #[serde(default)]
    pub mouth_curvature: Option<String>,
    /// Narrow to wide mouth.
    #[serde(default)]
    pub mouth_width: Option<String>,
    /// Closed to open mouth.
    #[serde(default)]
    pub mouth_openness: Option<String>,
    /// Small to large ears.
    #[serde(default)]
    pub ear_size: Option<String>,
    /// No hair to full hair.
    #[serde(default)]
    pub hair: Option<String>,
}

/// Options of `kind = "segments"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SegmentsOptions {
    /// The numeric columns, 2 to 64, one segment each, clockwise from the top.
    #[schemars(length(min = 2, max = 64), example = example_columns())]
    pub columns: Vec<Channel>,
    /// Column the rows are sorted by before they are laid out from the centre outward
    /// (default: the rows' order in the data).
    #[serde(default)]
    pub order_by: Option<String>,
    /// Sort `order_by` from high to low (default false).
    #[serde(default)]
    pub descending: Option<bool>,
    /// Continuous colour map (default `viridis`; append `_r` to reverse).
    #[serde(default)]
    pub scheme: Option<String>,
    /// `column` (default: each column scaled from its own minimum to maximum) or `shared` (one
    /// scale over all columns, for columns in the same unit).
    #[serde(default)]
    pub scale: Option<SegmentScale>,
    /// Colour of pixels whose rows are all missing (default light grey, `#d9d9d9`).
    #[serde(default)]
    pub nan_color: Option<String>,
}

/// How circle-segment colours are scaled.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SegmentScale {
    /// Each column from its own minimum (bottom of the colour bar) to its maximum (top).
    Column,
    /// One domain over all columns.
    Shared,
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

/// Options of `kind = "treemap"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct TreemapOptions {
    /// The tree's columns: `{ id = "id", parent = "parent" }` or `{ path = "path" }`.
    pub tree: TreeSource,
    /// Numeric column of leaf sizes (default: every leaf counts 1). Inner nodes are the sum of
    /// their leaves; negative and missing values count as 0, with a warning.
    #[serde(default)]
    #[schemars(example = &"size")]
    pub value: Option<String>,
    /// Unit of `value`, shown in labels and the caption.
    #[serde(default)]
    pub unit: Option<String>,
    /// Column of node labels (default: the id, or the last path segment).
    #[serde(default)]
    pub label: Option<String>,
    /// Colour leaves by a column (text: categories; numbers: a colour map).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Without `color`: `branch` (default: one hue per top-level branch), `depth`, or `value`
    /// (a colour map of each leaf's value).
    #[serde(default)]
    pub color_by: Option<TreemapColor>,
    /// Colour scheme: categorical for `branch`, continuous for `depth` and `value`.
    #[serde(default)]
    pub scheme: Option<String>,
    /// `squarified` (default; Bruls et al.), `slice-dice` (alternating by depth) or `strip`
    /// (ordered rows keeping the data order).
    #[serde(default)]
    pub tiling: Option<Tiling>,
    /// Gap in pixels between siblings and inside each parent's border (default 2).
    #[serde(default)]
    #[schemars(range(min = 0, max = 50))]
    pub padding: Option<f64>,
    /// Draw a header band with its name over each inner node (default true).
    #[serde(default)]
    pub headers: Option<bool>,
    /// Deepest level drawn below the root (default: all); deeper nodes fold into their
    /// ancestor at that level.
    #[serde(default)]
    #[schemars(range(min = 1, max = 64))]
    pub depth: Option<u32>,
}

/// What colours a treemap without a `color` column.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum TreemapColor {
    /// One hue per child of the root; everything below it shares that hue.
    Branch,
    /// A colour map of each node's depth.
    Depth,
    /// A colour map of each leaf's value.
    Value,
}

/// How a treemap splits a rectangle among children.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Tiling {
    /// Rows of near-square rectangles, largest first (Bruls, Huizing & van Wijk 2000).
    Squarified,
    /// Slices across, alternating horizontal and vertical by depth (Shneiderman 1992).
    SliceDice,
    /// Ordered strips that keep the data order (Bederson, Shneiderman & Wattenberg 2002).
    Strip,
}

/// Options of `kind = "hypertree"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct HypertreeOptions {
    /// The tree's columns: `{ id = "id", parent = "parent" }` or `{ path = "path" }`.
    pub tree: TreeSource,
    /// Column of node labels (default: the id, or the last path segment).
    #[serde(default)]
    pub label: Option<String>,
    /// Node brought to the centre: its id (its full path for path trees), or a label only one
    /// node has (default: the root).
    #[serde(default)]
    #[schemars(example = &"flare/vis")]
    pub focus: Option<String>,
    /// Colour nodes by a column (default: one hue per top-level branch).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Categorical scheme of the branch colours.
    #[serde(default)]
    pub scheme: Option<String>,
    /// Hyperbolic distance between a parent and its children (default 1.2; larger spreads the
    /// tree out and pushes deep levels to the rim).
    #[serde(default)]
    #[schemars(range(min = 0.2, max = 5))]
    pub spacing: Option<f64>,
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

/// Options of `kind = "graph"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct GraphOptions {
    /// Column of edge sources (node ids).
    #[schemars(example = &"from")]
    pub source: String,
    /// Column of edge targets (node ids).
    #[schemars(example = &"to")]
    pub target: String,
    /// Numeric column of edge weights: edge width and colour (default: all edges alike).
    #[serde(default)]
    pub weight: Option<String>,
    /// Node table with ids and attributes (default: nodes are the edges' endpoints).
    #[serde(default)]
    pub nodes: Option<NodeTable>,
    /// `force` (default), `circular`, `layered` or `given`.
    #[serde(default)]
    pub layout: Option<GraphLayout>,
    /// Seed of the force layout (default 1): the same seed gives the same picture.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Draw arrowheads (default: true for `layered`, false otherwise).
    #[serde(default)]
    pub directed: Option<bool>,
    /// Label nodes (default: when there are at most 150); labels that would overlap are left out.
    #[serde(default)]
    pub labels: Option<bool>,
    /// Node radius in pixels, at most 200, without a size column (default from the node count).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 200))]
    pub node_radius: Option<f64>,
    /// Continuous scheme of edge colours by weight (default `greys`).
    #[serde(default)]
    pub scheme: Option<String>,
}

/// How a link view shows the network.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LinkMode {
    /// Nodes and links, links drawn thin to thick in order of their statistic.
    Links,
    /// An adjacency matrix with rows and columns ordered by clustering.
    Matrix,
}

/// Options of `kind = "linkmap"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct LinkmapOptions {
    /// Column of link sources (node ids).
    #[schemars(example = &"from")]
    pub source: String,
    /// Column of link targets (node ids).
    #[schemars(example = &"to")]
    pub target: String,
    /// Numeric column of the link statistic (traffic, calls, flow): width and colour.
    #[schemars(example = &"traffic")]
    pub weight: String,
    /// Unit of `weight`, shown in the legend.
    #[serde(default)]
    pub unit: Option<String>,
    /// Node table with ids and attributes, or given positions (`x`, `y`).
    #[serde(default)]
    pub nodes: Option<NodeTable>,
    /// `links` (default) or `matrix`.
    #[serde(default)]
    pub mode: Option<LinkMode>,
    /// Node placement in `links` mode: `force` (default), `circular`, `layered` or `given`.
    #[serde(default)]
    pub layout: Option<GraphLayout>,
    /// Seed of the force layout (default 1).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Continuous scheme of the link statistic (default `viridis_r`: low values light, high dark).
    #[serde(default)]
    pub scheme: Option<String>,
    /// Label nodes (default: when there are at most 150).
    #[serde(default)]
    pub labels: Option<bool>,
}

/// Options of `kind = "flow"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct FlowOptions {
    /// Grid x coordinate: a numeric column of a long-form table (one row per grid node and time).
    pub x: Channel,
    /// Grid y coordinate.
    pub y: Channel,
    /// Column of the velocity's x component.
    #[schemars(example = &"u")]
    pub u: String,
    /// Column of the velocity's y component.
    #[schemars(example = &"v")]
    pub v: String,
    /// Column of the time, for unsteady fields (one grid per distinct time).
    #[serde(default)]
    pub t: Option<String>,
    /// Unit of the speed, shown in the colour bar and the arrow key.
    #[serde(default)]
    pub unit: Option<String>,
    /// Layers drawn, bottom to top: `speed`, `lic`, `arrows`, `streamlines`, `pathlines`,
    /// `streaklines`, `timelines`, `topology` (default `["speed", "streamlines"]`).
    #[serde(default)]
    pub layers: Option<Vec<FlowLayer>>,
    /// Where streamlines and particle traces start: `evenly` (default for streamlines; Jobard–Lefer
    /// evenly spaced lines), `grid`, `rake` (along `rake`) or `circle` (around `circle`).
    #[serde(default)]
    pub seeds: Option<SeedKind>,
    /// Two end points `[[x0, y0], [x1, y1]]` of the seed rake.
    #[serde(default)]
    pub rake: Option<[[f64; 2]; 2]>,
    /// Centre and radius `[x, y, r]` of the seed circle.
    #[serde(default)]
    pub circle: Option<[f64; 3]>,
    /// Number of seeds on a rake or circle (default 12).
    #[serde(default)]
    #[schemars(range(min = 1, max = 10000))]
    pub seed_count: Option<u32>,
    /// Line and arrow density, like matplotlib's `density` (default 1): evenly spaced lines are
    /// 1/30 of the plot's width apart at density 1, and a grid has 30 seeds or arrows a side.
    #[serde(default)]
    #[schemars(range(min = 0.1, max = 10))]
    pub density: Option<f64>,
    /// Integrator: `euler`, `rk2`, `rk4` (default) or `rk45` (adaptive with error control; slower).
    #[serde(default)]
    pub integrator: Option<IntegratorKind>,
    /// Continuous scheme of speed (default `viridis`).
    #[serde(default)]
    pub scheme: Option<String>,
    /// Time of the snapshot for steady layers and the end of particle traces, for unsteady
    /// fields (default: the first time for snapshots, the last for traces).
    #[serde(default)]
    pub time: Option<f64>,
}

/// A layer of a flow chart.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum FlowLayer {
    /// Speed as a colour image with a colour bar.
    Speed,
    /// Line integral convolution of white noise along the flow (tinted by speed when `speed` is
    /// also drawn).
    Lic,
    /// Arrows on a regular grid, length proportional to speed, with a key arrow.
    Arrows,
    /// Streamlines of the (first or chosen) snapshot, with direction arrows.
    Streamlines,
    /// Paths of particles released at the seeds at the first time (unsteady fields).
    Pathlines,
    /// Where particles released continuously at the seeds are at the end time (unsteady fields).
    Streaklines,
    /// A line of particles released together along the seeds, drawn at several times.
    Timelines,
    /// Critical points classified by the Jacobian's eigenvalues, separatrices from saddles, and
    /// attachment and detachment points on the boundary.
    Topology,
}

/// Where traces start.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SeedKind {
    /// Evenly spaced streamlines (Jobard & Lefer 1997).
    Evenly,
    /// A regular grid of seeds.
    Grid,
    /// Seeds along the line `rake`.
    Rake,
    /// Seeds around the circle `circle`.
    Circle,
}

/// A numerical integrator for traces.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorKind {
    /// Forward Euler (first order).
    Euler,
    /// Midpoint rule (second order).
    Rk2,
    /// Classic Runge–Kutta (fourth order).
    Rk4,
    /// Dormand–Prince 5(4) with step-size control.
    Rk45,
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

/// Saddle-cell rules for contouring.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SaddleRule {
    /// Compare the level with the bilinear saddle value (f00·f11 − f01·f10)/(f00 + f11 − f01 − f10).
    Asymptotic,
    /// Compare the level with the mean of the cell's four corners.
    Center,
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
fn example_columns() -> [&'static str; 3] {
    ["sepal_length", "sepal_width", "petal_length"]
}

/// Schema example of `domain`.
fn example_domain() -> [u32; 2] {
    [0, 100]
}
