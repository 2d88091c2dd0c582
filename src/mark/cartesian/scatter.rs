//! `scatter`: points at (x, y), coloured and sized by columns, drawn as one compact point batch.

use super::scatter_density::{self, Rows};
use crate::data::Table;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::density::{PointMode, ShadingOption};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode::{self};
use crate::mark::geometry::{Geometry, Plot, PlotScale};
use crate::mark::overplot::{point_opacity, point_radius};
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::size::{mapped_radius, size_legend_mapped};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, categorical, frame, highlight};
use crate::scene::{Color, Item, PerPoint, PointBatch, Role, Shape, Stroke, Style};
use crate::selection::Highlight;
use crate::spec::{Channel, Chart, ColorChannel, SizeChannel, Trend};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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
    /// A trend line: `"linear"` (least squares, with its equation and R²), `"loess"`, or
    /// `{ method, span, groups, equation }` (`groups = true`: one line per colour category).
    #[serde(default)]
    #[schemars(example = &"linear")]
    pub trend: Option<Trend>,
    /// `points` (one marker per row), `density` (rows counted in bins of a few pixels, each bin
    /// shaded by its count) or `auto` (default: density above 200,000 rows).
    #[serde(default)]
    #[schemars(example = &"density")]
    pub mode: Option<PointMode>,
    /// How density bins are shaded by their counts: `eq_hist` (default; histogram-equalized),
    /// `log` or `linear`. The legend's ticks are counts under any shading.
    #[serde(default)]
    pub shading: Option<ShadingOption>,
    /// Side of a density bin in pixels, 1 to 50 (default 2).
    #[serde(default)]
    #[schemars(range(min = 1, max = 50))]
    pub bin: Option<f64>,
    /// Opacity of the density bins with the fewest rows, 0.05 to 1 (default 0.4), so that a
    /// single row stays visible.
    #[serde(default)]
    #[schemars(range(min = 0.05, max = 1))]
    pub min_alpha: Option<f64>,
    /// Grow each isolated density bin (no non-empty neighbour) by this many bins on each side,
    /// 0 to 5 (default 0), so lone rows are not lost as single dots.
    #[serde(default)]
    #[schemars(range(min = 0, max = 5))]
    pub spread: Option<u32>,
}

/// Draw a scatter chart.
/// Also returns the interactive geometry (for brushing and zooming).
pub fn draw(
    chart: &Chart,
    options: &ScatterOptions,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    let size_opts = options.point_size.as_ref().map(|s| s.options());
    let size_col = match &size_opts {
        Some(o) => Some(encode::column(chart, "point_size", &o.field, table)?),
        None => None,
    };
    if let (Some(col), Some(o)) = (size_col, &size_opts)
        && col.numbers().is_none()
    {
        return Err(MarkError::at(
            &["point_size"],
            format!("`point_size` column `{}` holds text; marker area needs numbers", o.field),
            "size by a numeric column, or colour by this one instead",
        ));
    }
    let color_numeric = options.color.as_ref().and_then(|c| table.column(c.field())).filter(|c| c.numbers().is_some());

    let mut numeric: Vec<(&str, &crate::data::Column)> = Vec::new();
    for (field, col) in [(x_opts.field.as_str(), x_col), (y_opts.field.as_str(), y_col)] {
        if col.numbers().is_some() {
            numeric.push((field, col));
        }
    }
    if let (Some(col), Some(o)) = (size_col, &size_opts) {
        numeric.push((&o.field, col));
    }
    if let (Some(col), Some(c)) = (color_numeric, &options.color) {
        numeric.push((c.field(), col));
    }
    let log = encode::log_fields(&[&x_opts, &y_opts]);
    let (mut rows, warning) = encode::placeable_rows(&chart.name, table.rows, &numeric, &log);
    let mut warnings: Vec<Warning> = warning.into_iter().collect();

    // Marker area is proportional to the value, so negative sizes have no honest mark.
    let mut max_size = 0.0f64;
    if let Some(values) = size_col.and_then(|c| c.numbers()) {
        let before = rows.len();
        rows.retain(|&r| values.get(r as usize).is_some_and(|v| *v >= 0.0));
        if rows.len() < before {
            warnings.push(Warning::from(format!(
                "dropped {} rows with negative `point_size` values (marker area cannot be negative)",
                before - rows.len()
            )));
        }
        max_size = rows.iter().filter_map(|&r| values.get(r as usize)).fold(0.0, |a, &b| a.max(b));
        if let Some(panel) = &chart.panel {
            max_size = panel.share_size_max(max_size);
        }
    }
    if rows.is_empty() {
        return Err(encode::no_rows(chart, table, warnings.first()));
    }

    let n = rows.len();
    let opacity = options.opacity.unwrap_or_else(|| point_opacity(n));
    let (colors, color_legend) = encode::color_encoding(
        chart,
        options.color.as_ref(),
        options.mark_color.as_deref(),
        table,
        &rows,
        Symbol::Circle,
    )?;
    let max_radius = size_opts.as_ref().and_then(|o| o.max_radius).unwrap_or(12.0);
    let mapping = size_opts.as_ref().and_then(|o| o.mapping).unwrap_or_default();
    let mut legends: Vec<Legend> = color_legend.into_iter().collect();
    if let Some(h) = highlight {
        legends.push(highlight::legend(h, &rows, Symbol::Circle));
    }
    if let (Some(o), true) = (&size_opts, max_size > 0.0) {
        let title = o.title.clone().unwrap_or(o.field.clone());
        legends.push(size_legend_mapped(&title, o.unit.as_deref(), max_size, max_radius, mapping));
    }

    let base_radius = options.radius.unwrap_or_else(|| point_radius(n));
    let largest_radius = if size_col.is_some() && max_size > 0.0 { max_radius } else { base_radius };
    let mut x_axis = encode::position_axis("x", &x_opts, x_col, &rows)?;
    let mut y_axis = encode::position_axis("y", &y_opts, y_col, &rows)?;
    x_axis.inset = largest_radius + 1.0;
    y_axis.inset = largest_radius + 1.0;
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, legends)?;

    let x_pos = encode::Positioner::new(&frame.x, x_col);
    let y_pos = encode::Positioner::new(&frame.y, y_col);
    // Large markers get a thin outline so overlapping ones stay distinguishable.
    let stroke = (size_col.is_some() || (n <= 2_000 && base_radius >= 3.0))
        .then(|| Stroke::solid(Color::WHITE.with_opacity(0.8), 0.6));
    let sizes = size_col.and_then(|c| c.numbers()).filter(|_| max_size > 0.0);
    let batch = |rows: &[u32], context: bool| {
        let centers = encode::centers(&x_pos, &y_pos, rows);
        let fill = highlight::point_fill(&colors, rows, context, opacity);
        let radius = match sizes {
            Some(values) => PerPoint::Each(
                rows.iter()
                    .map(|&r| {
                        mapped_radius(values.get(r as usize).copied().unwrap_or(0.0), max_size, max_radius, mapping)
                    })
                    .collect(),
            ),
            None => PerPoint::Uniform(base_radius),
        };
        let label = if context { format!("{} (not selected)", chart.name) } else { chart.name.clone() };
        vec![
            Item::new(
                Role::DataMark,
                Shape::Points(PointBatch { centers, radius, fill, stroke: stroke.clone() }),
                Style::default(),
            )
            .with_rows(rows.to_vec())
            .labelled(label),
        ]
    };
    let mut marks: Vec<Item> = highlight
        .and_then(|h| highlight::brush(h, frame.plot, (&x_opts.field, &frame.x), Some((&y_opts.field, &frame.y))))
        .into_iter()
        .collect();
    marks.extend(highlight::layers(&rows, highlight, batch));
    if let Some(trend) = &options.trend {
        let groups = match (&options.color, trend.options().groups) {
            (Some(channel), Some(true)) => Some(categorical::row_groups(&colors, Some(channel), &rows)?),
            _ => None,
        };
        let fitted = crate::mark::trend::Fitted { x: x_col, y: y_col, rows: &rows, groups: groups.as_ref() };
        marks.extend(crate::mark::trend::marks(&trend.options(), &fitted, &frame, &theme)?);
    }
    warnings.extend((frame::raster_note(&marks)).into_iter().map(Warning::from));
    let plot = Plot::xy(
        frame.plot,
        PlotScale { field: x_opts.field.clone(), scale: frame.x.clone() },
        PlotScale { field: y_opts.field.clone(), scale: frame.y.clone() },
    );
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

    let mut derived = Derived::over(rows);
    derived.push("row", DerivedColumn::RowIndex);
    derived.push(&x_opts.field, DerivedColumn::Source(x_opts.field.clone()));
    derived.push(&y_opts.field, DerivedColumn::Source(y_opts.field.clone()));
    if let Some(c) = &options.color {
        derived.push(c.field(), DerivedColumn::Source(c.field().to_string()));
    }
    if let Some(o) = &size_opts {
        derived.push(&o.field, DerivedColumn::Source(o.field.clone()));
    }
    if let Some(h) = highlight {
        derived.push("selected", DerivedColumn::Selected(h.selected.clone()));
    }
    let geometry = Geometry { plots: vec![plot], ..Geometry::default() };
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// `kind = "scatter"`.
pub static KIND: KindInfo = KindInfo::new("scatter", &["x", "y", "color", "point_size"])
    .counting_rows(crate::mark::registry::RowCounting {
        modes: Some(&["density", "auto"]),
        // `color` categories are counted from rows in memory.
        unless: &["color", "point_size", "trend", "highlight", "tooltip", "facet"],
        on_engine: true,
    })
    .drawing_selections()
    .taking_aspect()
    .faceted(crate::mark::registry::Faceting::Frame)
    .drawing_annotations();

impl Technique for ScatterOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        if let Some(plan) = cx.plan {
            return scatter_density::draw(&cx.chart, self, Rows::Plan(plan), cx.highlight);
        }
        let mode = self.mode.unwrap_or_default();
        if cx.chart.panel.is_some() {
            // Each panel would shade its own counts under one legend: not honest yet.
            if mode == PointMode::Density {
                return Err(MarkError::at(
                    &["mode"],
                    "a faceted scatter cannot be drawn in density mode yet",
                    "draw one chart per panel (a `filter` step each), or mode = \"points\"",
                ));
            }
        } else if mode.is_density(cx.table.rows as u64) {
            return scatter_density::draw(&cx.chart, self, Rows::Table(cx.table), cx.highlight);
        }
        draw(&cx.chart, self, cx.table, cx.highlight)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        AxisSpec::pair(&self.x, &self.y)
    }

    crate::mark::registry::color_key!();
}
