//! The technique registry: every chart kind is one type implementing [`Technique`] (its options
//! type from the spec), with its static facts in a [`KindInfo`], and listed once in [`registry!`]'s
//! invocation below, as `lint::rules::ALL` lists rules.
//!
//! Everything that used to match on the kind — the spec's kind names, the keys naming columns,
//! conventional default columns, default canvas sizes, which kinds draw selections, take
//! `aspect` or draw annotations, what lint reads of the encodings, the node table of network kinds, the explorer's
//! interactive geometry — is read from here.

use super::volume::isosurface::SurfaceCache;
use super::{ChartOutput, MarkError};
use std::borrow::Cow;

use crate::data::Table;
use crate::data::density::plan::PlanRows;
use crate::data::volume::Volume;
use crate::enrich::volume::SpanSpace;
use crate::layout::hyperbolic::Mobius;
use crate::selection::Highlight;
use crate::spec::defaults::Convention;
use crate::spec::{Channel, ChannelOptions, Chart, ColorChannel, ColorOptions, ScaleKind};

/// What is known of a kind before its options are read: enough for the spec checks, the
/// conventional defaults and the column reads that run on the raw spec.
#[derive(Debug)]
pub struct KindInfo {
    /// The name as written in the spec (`kind = "scatter"`).
    pub name: &'static str,
    /// The spec keys whose values name columns (a string, a table with `field`, a list of
    /// those, or a table of names such as `tree` and `features`).
    pub column_keys: &'static [&'static str],
    /// The keys that default to a column of a conventional name when left out.
    pub conventions: &'static [Convention],
    /// The canvas size when the spec gives none (see [`Technique::default_size`] for kinds
    /// whose default depends on their options).
    pub default_size: [f64; 2],
    /// Whether the kind draws a selection (`highlight`) and takes part in brushing.
    pub draws_selection: bool,
    /// Whether the kind applies `aspect = "equal"` (one x/y frame, or given node positions).
    pub applies_aspect: bool,
    /// Whether the kind draws a chart's `annotate` notes (the kinds laid out in one x/y frame).
    pub draws_annotations: bool,
    /// How the kind is drawn as facet panels (`facet = ...`), if it can be.
    pub faceting: Faceting,
    /// Whether the kind draws a volume source (the others draw tables and refuse volumes).
    pub draws_volumes: bool,
    /// Whether, and when, a chart of the kind can be drawn from rows that stay in their
    /// source's plan, only counted.
    pub counts_rows: Option<RowCounting>,
}

/// When a kind's chart only counts its rows, so they can stay in their source's plan (see
/// `ChartContext::plan`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RowCounting {
    /// The `mode` values under which it counts (the key left out counts too); `None`: the kind
    /// has no `mode`.
    pub modes: Option<&'static [&'static str]>,
    /// Keys any of which makes the chart need its rows one by one.
    pub unless: &'static [&'static str],
    /// Whether a query engine can count them too (else only polars' plan in this process).
    pub on_engine: bool,
}

impl RowCounting {
    /// Whether `chart` (the spec's table of it) only counts its rows (`engine`: on an engine).
    pub fn counts(&self, chart: &serde_json::Value, engine: bool) -> bool {
        let mode = chart.get("mode").and_then(serde_json::Value::as_str);
        let mode_counts = match (self.modes, mode) {
            (_, None) => true,
            (Some(modes), Some(mode)) => modes.contains(&mode),
            (None, Some(_)) => false,
        };
        (self.on_engine || !engine) && mode_counts && self.unless.iter().all(|k| chart.get(*k).is_none())
    }
}

/// How a kind's charts split into small multiples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Faceting {
    /// Not at all: the kind does not draw from rows one by one (grids, trees, networks).
    Not,
    /// Each panel is one cartesian frame: shared scales, outer axes only.
    Frame,
    /// Each panel is a whole chart of its own layout (parallel coordinates, faces, ...), the
    /// legends drawn once.
    Canvas,
}

impl KindInfo {
    /// A kind named `name` whose `column_keys` name columns, drawn at [`FRAME_SIZE`], with no
    /// conventional defaults, drawing no selections and leaving `aspect` alone.
    pub const fn new(name: &'static str, column_keys: &'static [&'static str]) -> KindInfo {
        KindInfo {
            name,
            column_keys,
            conventions: &[],
            default_size: FRAME_SIZE,
            draws_selection: false,
            applies_aspect: false,
            draws_annotations: false,
            faceting: Faceting::Not,
            draws_volumes: false,
            counts_rows: None,
        }
    }

    /// Drawn from rows left in their source's plan when `counting` says.
    pub const fn counting_rows(mut self, counting: RowCounting) -> KindInfo {
        self.counts_rows = Some(counting);
        self
    }

    /// Drawn as facet panels in the given way.
    pub const fn faceted(mut self, faceting: Faceting) -> KindInfo {
        self.faceting = faceting;
        self
    }

    /// With keys that default to conventional columns.
    pub const fn conventions(mut self, conventions: &'static [Convention]) -> KindInfo {
        self.conventions = conventions;
        self
    }

    /// Drawn at `size` when the spec gives none.
    pub const fn sized(mut self, size: [f64; 2]) -> KindInfo {
        self.default_size = size;
        self
    }

    /// Drawing `highlight` selections and taking part in brushing.
    pub const fn drawing_selections(mut self) -> KindInfo {
        self.draws_selection = true;
        self
    }

    /// Applying `aspect = "equal"`.
    pub const fn taking_aspect(mut self) -> KindInfo {
        self.applies_aspect = true;
        self
    }

    /// Drawing the chart's `annotate` notes in its x/y frame.
    pub const fn drawing_annotations(mut self) -> KindInfo {
        self.draws_annotations = true;
        self
    }

    /// Drawing volume sources.
    pub const fn drawing_volumes(mut self) -> KindInfo {
        self.draws_volumes = true;
        self
    }
}

/// The canvas size of the kinds drawn in one cartesian frame.
pub const FRAME_SIZE: [f64; 2] = [640.0, 420.0];

/// A cartesian axis of a chart, as its spec declares it.
#[derive(Clone, Debug)]
pub struct AxisSpec {
    /// The axis's name in the scene (`"x axis"` or `"y axis"`), matching its items' labels.
    pub name: &'static str,
    /// The spec key of the channel, relative to the chart (a line chart's several y columns
    /// share the key `"y"`).
    pub key: &'static str,
    /// The channel's options (defaults for a bare column name).
    pub options: ChannelOptions,
}

impl AxisSpec {
    /// The scale kind the spec asks for, if it names one.
    pub fn scale(&self) -> Option<ScaleKind> {
        self.options.scale
    }

    /// The x and y axes of one frame.
    pub fn pair(x: &Channel, y: &Channel) -> Vec<AxisSpec> {
        vec![
            AxisSpec { name: "x axis", key: "x", options: x.options() },
            AxisSpec { name: "y axis", key: "y", options: y.options() },
        ]
    }
}

/// A colour encoding of a chart: the spec key and its options.
#[derive(Clone, Debug)]
pub struct ColourSpec {
    /// The spec key, relative to the chart (`"color"`, `"z"`).
    pub key: &'static str,
    /// The encoding's options (defaults for a bare column name).
    pub options: ColorOptions,
}

impl ColourSpec {
    /// The encoding of a chart's optional `color` key.
    pub fn color(channel: &Option<ColorChannel>) -> Vec<ColourSpec> {
        channel.iter().map(|c| ColourSpec { key: "color", options: c.options() }).collect()
    }

    /// The encoding of a field `z` coloured by a map.
    pub fn z(channel: &ColorChannel) -> Vec<ColourSpec> {
        vec![ColourSpec { key: "z", options: channel.options() }]
    }
}

/// One chart bound for drawing: its spec (with `size` filled in), its place in the spec, the
/// data it reads and the view it is drawn in. Errors and warnings name the chart through it.
#[derive(Clone, Debug)]
pub struct ChartContext<'a> {
    /// The chart's spec, with `size` filled in by its kind's default.
    pub chart: Chart,
    /// Its index among the spec's charts (the `chart[i]` of error paths).
    pub index: usize,
    /// The table of its `data`.
    pub table: &'a Table,
    /// The rows of its `highlight` selection, evaluated, for kinds that draw selections.
    pub highlight: Option<&'a Highlight>,
    /// The node table of a network chart's `nodes`, when it names one.
    pub nodes: Option<&'a Table>,
    /// A view moved after the spec's own (the explorer's hyperbolic drag), if any.
    pub view: Option<&'a Mobius>,
    /// The volume of its `data`, when that source is a volume (its `table` is then empty).
    pub volume: Option<&'a Volume>,
    /// A span-space index of that volume, kept by a caller that extracts isosurfaces of it
    /// again and again (the explorer's iso value slider).
    pub span_space: Option<&'a SpanSpace>,
    /// Surfaces kept from the chart's earlier draws, by a caller that draws it again and again
    /// (the explorer turning the camera).
    pub surfaces: Option<&'a SurfaceCache>,
    /// The rows of its `data` left in the source's lazy plan, for kinds that only count them
    /// (its `table` then has the columns and no rows).
    pub plan: Option<&'a PlanRows>,
}

impl<'a> ChartContext<'a> {
    /// Bind chart number `index` to its table; `size` is filled in from the kind's default.
    pub fn new(chart: &Chart, index: usize, table: &'a Table) -> ChartContext<'a> {
        ChartContext {
            chart: super::with_default_size(chart),
            index,
            table,
            highlight: None,
            nodes: None,
            view: None,
            volume: None,
            span_space: None,
            surfaces: None,
            plan: None,
        }
    }

    /// The same chart reading its rows from `plan` instead of its table.
    pub fn with_plan(mut self, plan: Option<&'a PlanRows>) -> ChartContext<'a> {
        self.plan = plan;
        self
    }

    /// The same chart drawing the rows of `highlight` in full colour.
    pub fn with_highlight(mut self, highlight: Option<&'a Highlight>) -> ChartContext<'a> {
        self.highlight = highlight;
        self
    }

    /// The same chart reading its node table from `nodes`.
    pub fn with_nodes(mut self, nodes: Option<&'a Table>) -> ChartContext<'a> {
        self.nodes = nodes;
        self
    }

    /// The same chart with its view moved by `view`.
    pub fn with_view(mut self, view: Option<&'a Mobius>) -> ChartContext<'a> {
        self.view = view;
        self
    }

    /// The same chart reading the volume `volume` (its data source is one).
    pub fn with_volume(mut self, volume: Option<&'a Volume>) -> ChartContext<'a> {
        self.volume = volume;
        self
    }

    /// The same chart finding its isosurfaces' cells through `index`, a span-space index of
    /// its volume.
    pub fn with_span_space(mut self, index: Option<&'a SpanSpace>) -> ChartContext<'a> {
        self.span_space = index;
        self
    }

    /// The same chart keeping its extracted isosurfaces in `cache` for its next draws.
    pub fn with_surfaces(mut self, cache: Option<&'a SurfaceCache>) -> ChartContext<'a> {
        self.surfaces = cache;
        self
    }

    /// The chart's data as a volume: the source's own, or its table's columns `x`, `y`, `z` and
    /// `value` when their rows lie on a regular lattice ([`crate::data::volume::table`]).
    pub fn volume(&self) -> Result<Cow<'a, Volume>, MarkError> {
        if let Some(volume) = self.volume {
            return Ok(Cow::Borrowed(volume));
        }
        crate::data::volume::table::from_table(self.table, ["x", "y", "z", "value"]).map(Cow::Owned).map_err(|message| {
            MarkError::at(
                &["data"],
                format!("data \"{}\" is not a volume: {message}", self.chart.data),
                "name a NIfTI file, a 3-D .npy array or a raw volume, or a table of x, y, z and value on a regular lattice",
            )
        })
    }
}

/// One chart kind. Implemented by the kind's options type; everything that differs between
/// kinds is asked of this trait or of its [`KindInfo`].
pub trait Technique: Sync {
    /// The kind's static facts.
    fn info(&self) -> &'static KindInfo;

    /// Draw the chart: its scene, derived geometry, warnings, and the interactive geometry the
    /// explorer brushes and navigates (empty for kinds that expose none).
    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError>;

    /// The canvas size when the spec gives none.
    fn default_size(&self) -> [f64; 2] {
        self.info().default_size
    }

    /// The x and y axes of a kind drawn on one cartesian frame; empty for other kinds.
    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        Vec::new()
    }

    /// The colour encodings the spec declares by column (`color = ...`, or a field `z` coloured
    /// by a map). Kinds that colour by a fixed rule report their `scheme` instead.
    fn colour_encodings(&self) -> Vec<ColourSpec> {
        Vec::new()
    }

    /// The chart-level `scheme`, for kinds with one outside a colour encoding.
    fn scheme(&self) -> Option<&str> {
        None
    }

    /// The categorical colour channel whose categories are shared across the spec, and the data
    /// source it reads when that is not the chart's own (a graph's `nodes.color`).
    fn color_channel_mut(&mut self) -> Option<(&mut ColorChannel, Option<String>)> {
        None
    }

    /// The data source of the node table the chart reads beside its own, if any.
    fn node_data(&self) -> Option<&str> {
        None
    }

    /// For facet panels: the kind's options with what must be the same in every panel fixed
    /// from the whole table (a histogram's bin edges), or `None` when nothing needs fixing.
    fn facet_shared(&self, _chart: &Chart, _table: &Table) -> Result<Option<ChartKind>, MarkError> {
        Ok(None)
    }
}

/// The two [`Technique`] methods of a kind whose options have a `color: Option<ColorChannel>`
/// key: its colour encoding (for lint) and its spec-wide categories (for shared colours). Used
/// inside the kind's `impl Technique`.
macro_rules! color_key {
    () => {
        fn colour_encodings(&self) -> Vec<$crate::mark::registry::ColourSpec> {
            $crate::mark::registry::ColourSpec::color(&self.color)
        }

        fn color_channel_mut(&mut self) -> Option<(&mut $crate::spec::ColorChannel, Option<String>)> {
            self.color.as_mut().map(|c| (c, None))
        }
    };
}
pub(crate) use color_key;

/// Lists every kind once: its doc line (its description in the JSON Schema), its `ChartKind`
/// variant with the options type its module defines, and its module. Generates [`ChartKind`],
/// [`options`] (every options type, re-exported by `spec`), [`KINDS`], [`technique`] and
/// [`technique_mut`].
macro_rules! registry {
    ($($(#[$doc:meta])* $variant:ident($options:ident) => $($module:ident)::+),* $(,)?) => {
        /// The chart kinds. Each kind has its own options.
        #[derive(Clone, Debug, serde::Deserialize, serde::Serialize, schemars::JsonSchema, PartialEq)]
        #[serde(tag = "kind", rename_all = "lowercase")]
        pub enum ChartKind {
            $($(#[$doc])* $variant(super::$($module)::+::$options),)*
        }

        /// Every kind's options type, where the spec's types re-export them from.
        pub mod options {
            $(pub use super::super::$($module)::+::$options;)*
        }

        /// Every kind's facts, in the order of the spec's `ChartKind` variants.
        pub static KINDS: &[&KindInfo] = &[$(&super::$($module)::+::KIND),*];

        /// The technique drawing a chart of `kind`.
        pub fn technique(kind: &ChartKind) -> &dyn Technique {
            match kind {
                $(ChartKind::$variant(options) => options,)*
            }
        }

        /// [`technique`], for changing the chart's options.
        pub fn technique_mut(kind: &mut ChartKind) -> &mut dyn Technique {
            match kind {
                $(ChartKind::$variant(options) => options,)*
            }
        }
    };
}

impl ChartKind {
    /// The kind's name as written in the spec (from its entry in the registry).
    pub fn name(&self) -> &'static str {
        technique(self).info().name
    }
}

registry! {
    /// Points at (x, y), optionally coloured and sized by columns.
    Scatter(ScatterOptions) => cartesian::scatter,
    /// One or more series drawn as lines through (x, y).
    Line(LineOptions) => cartesian::line,
    /// The area under a series, or series stacked on zero, normalised to 100%, centred or as a
    /// streamgraph.
    Area(AreaOptions) => cartesian::area,
    /// Vertical bars from zero: one per category of `x` (grouped side by side by `color`), rows
    /// of the same category summed.
    Bar(BarOptions) => cartesian::bar,
    /// The distribution of a numeric column as bars over equal-width bins: counts, percentages
    /// or densities, optionally cumulative, grouped by colour (stacked, layered or side by side).
    Histogram(HistogramOptions) => cartesian::histogram,
    /// A category × category matrix of a value (or of row counts) as coloured cells with a
    /// colour bar and the values written where they fit.
    Heatmap(HeatmapOptions) => cartesian::heatmap,
    /// Tukey box plots of a numeric column: quartiles, whiskers to 1.5 IQR and outliers, one box
    /// per category of `x` (dodged by `color`), vertical or horizontal.
    Box(BoxOptions) => cartesian::box_plot,
    /// Violins: each group's kernel density mirrored about its centre line, with a slim box of
    /// its quartiles inside, one per category of `x` (dodged by `color`), vertical or horizontal.
    Violin(ViolinOptions) => cartesian::violin,
    /// Sample points and the curves of one or more 1D interpolation methods through them.
    Interp1d(Interp1dOptions) => cartesian::interp1d,
    /// Contour lines and filled bands of a scalar field on a regular grid.
    Contour(ContourOptions) => grid::contour,
    /// A scalar field on a regular grid as a colour image (heatmap) with a colour bar.
    Image(ImageOptions) => grid::image,
    /// Cross-sections of a gridded field: z along x at chosen y values (or along y at chosen x).
    Section(SectionOptions) => grid::section,
    /// Scattered points: Delaunay triangulation, linear interpolation in the triangles, contours
    /// on the triangulation, and Voronoi tiles.
    Scattered(ScatteredOptions) => grid::scattered,
    /// A gridded field as a shaded 3D surface (orthographic, hidden surfaces removed).
    Surface(SurfaceOptions) => grid::surface,
    /// A matrix of 2D slices through gridded data of more than two dimensions, around a focus point.
    Hyperslice(HypersliceOptions) => grid::hyperslice,
    /// Scatter-plot matrix: every pair of columns, sharing one scale per column.
    Splom(SplomOptions) => multivariate::splom,
    /// Parallel coordinates: one vertical axis per column, one polyline per row.
    Parallel(ParallelOptions) => multivariate::parallel,
    /// Daisy chart: columns on arcs around a circle, each row a closed curve through its values.
    Daisy(DaisyOptions) => multivariate::daisy,
    /// Chernoff faces: one face per row, columns driving facial features.
    Faces(FacesOptions) => multivariate::faces,
    /// Circle segments: one wedge per column, rows as pixels from the centre outward.
    Segments(SegmentsOptions) => multivariate::segments,
    /// Treemap: a hierarchy as nested rectangles whose areas are the leaves' values.
    Treemap(TreemapOptions) => hierarchy::treemap,
    /// Hyperbolic tree: a hierarchy laid out in the Poincaré disk around a focus node.
    Hypertree(HypertreeOptions) => hierarchy::hypertree,
    /// Node-link diagram of a network: force-directed, circular or layered layout.
    Graph(GraphOptions) => network::graph,
    /// SeeNet-style link view: links drawn thin to thick by their statistic, or an
    /// adjacency matrix for dense networks.
    Linkmap(LinkmapOptions) => network::linkmap,
    /// A 2-D vector field: speed image, arrows, streamlines, particle traces, line integral
    /// convolution and vector field topology, as layers.
    Flow(FlowOptions) => vector::flow,
    /// Planes through a volume as images sharing one colour bar: along an axis at given
    /// positions, a lightbox of evenly spaced slices, or oblique planes, with optional contour
    /// lines and an inset showing where the planes lie.
    Slice(SliceOptions) => volume::slice,
    /// Surfaces of constant value through a volume (marching cubes with the topology of the
    /// trilinear interpolant, or marching tetrahedra), shaded in 3-D, several in depth order
    /// with transparency; `--format glb`, `ply` or `obj` writes the surfaces.
    Isosurface(IsosurfaceOptions) => volume::isosurface,
    /// Direct volume rendering by ray casting: compositing through an opacity and colour
    /// transfer function, maximum intensity projection or the mean along each ray.
    Volume(VolumeOptions) => volume::direct,
}

/// The facts of the kind named `name` in a spec, if there is one.
pub fn kind_info(name: &str) -> Option<&'static KindInfo> {
    KINDS.iter().copied().find(|k| k.name == name)
}

/// Every kind's name as written in the spec.
pub fn names() -> impl Iterator<Item = &'static str> {
    KINDS.iter().map(|k| k.name)
}

/// The names of the kinds with a property, e.g. `names_where(|k| k.draws_selection)`.
pub fn names_where(keep: impl Fn(&KindInfo) -> bool) -> Vec<&'static str> {
    KINDS.iter().filter(|k| keep(k)).map(|k| k.name).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kinds_that_count_rows_say_when() {
        let counts = |chart: serde_json::Value, engine: bool| {
            let kind = chart["kind"].as_str().unwrap();
            kind_info(kind).and_then(|k| k.counts_rows).is_some_and(|rule| rule.counts(&chart, engine))
        };
        use serde_json::json;
        assert!(counts(json!({"kind": "scatter", "x": "a", "y": "b"}), true));
        assert!(counts(json!({"kind": "scatter", "mode": "density"}), false));
        assert!(!counts(json!({"kind": "scatter", "mode": "points"}), false));
        assert!(!counts(json!({"kind": "scatter", "color": "c"}), false));
        assert!(counts(json!({"kind": "histogram", "x": "a"}), false));
        assert!(!counts(json!({"kind": "histogram", "x": "a"}), true), "histograms are counted in-process only");
        assert!(!counts(json!({"kind": "histogram", "rug": false}), false));
        assert!(counts(json!({"kind": "bar", "x": "a", "y": "b", "color": "c", "error": "ci95"}), false));
        assert!(!counts(json!({"kind": "bar", "x": "a", "highlight": "s"}), false));
        assert!(!counts(json!({"kind": "bar", "x": "a"}), true), "bars are grouped in-process only");
        assert!(counts(json!({"kind": "heatmap", "x": "a", "y": "b", "z": "c"}), false));
        assert!(!counts(json!({"kind": "heatmap", "x": "a", "facet": "f"}), false));
        assert!(counts(json!({"kind": "splom", "columns": ["a", "b"], "bins": 20}), false));
        assert!(!counts(json!({"kind": "splom", "mode": "points"}), false));
        assert!(!counts(json!({"kind": "splom", "diagonal": "density"}), false));
        assert!(!counts(json!({"kind": "line", "x": "a"}), false));
    }

    #[test]
    fn every_kind_is_listed_once_under_the_name_serde_reads() {
        let schema = crate::spec::spec_schema();
        let branches = schema["$defs"]["Chart"]["oneOf"].as_array().cloned().unwrap_or_default();
        let schema_names: Vec<String> =
            branches.iter().filter_map(|b| b["properties"]["kind"]["const"].as_str().map(str::to_owned)).collect();
        let names: Vec<&str> = names().collect();
        assert_eq!(names.len(), branches.len());
        assert_eq!(schema_names, names);
        let mut sorted = names.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), names.len(), "a name is listed twice");
    }

    #[test]
    fn kinds_are_found_by_name() {
        for info in KINDS {
            assert!(kind_info(info.name).is_some_and(|k| std::ptr::eq(k, *info)));
        }
        assert!(kind_info("pie").is_none());
    }

    #[test]
    fn faceted_kinds_are_the_documented_ones() {
        assert_eq!(
            names_where(|k| k.faceting == Faceting::Frame),
            ["scatter", "line", "area", "bar", "histogram", "heatmap", "box", "violin"]
        );
        assert_eq!(
            names_where(|k| k.faceting == Faceting::Canvas),
            ["splom", "parallel", "daisy", "faces", "segments"]
        );
    }

    #[test]
    fn selection_aspect_and_annotation_kinds_are_the_documented_ones() {
        assert_eq!(
            names_where(|k| k.draws_selection),
            ["scatter", "histogram", "box", "violin", "splom", "parallel", "daisy", "faces", "segments"]
        );
        assert_eq!(
            names_where(|k| k.applies_aspect),
            ["scatter", "line", "interp1d", "contour", "image", "scattered", "graph", "linkmap", "flow"]
        );
        assert_eq!(
            names_where(|k| k.draws_annotations),
            [
                "scatter",
                "line",
                "area",
                "bar",
                "histogram",
                "heatmap",
                "box",
                "violin",
                "interp1d",
                "contour",
                "image",
                "section",
                "scattered",
                "flow"
            ]
        );
    }
}
