//! `splom`: a scatter-plot matrix. Cell (i, j) plots column j across against column i up; every
//! column has one scale shared by its whole row and column, with ticks only on the outer edges.
//! The diagonal shows each column's distribution; a selection greys the other rows everywhere.

use rayon::prelude::*;

use super::splom_counted::{CellBins, CountedCells, CountedRows, DiagonalBins};
use crate::data::density::plan::PlanRows;
use crate::data::{Column, Table};
use crate::enrich::distribution::{bin_counts, freedman_diaconis_bins, kde, silverman_bandwidth};
use crate::guide::Theme;
use crate::guide::axis::{self, LabelRoom, Side};
use crate::guide::count_scale::CountScale;
use crate::guide::layout::{Domain, LayoutError, MIN_PLOT_SIDE, PositionAxis, build_scale};
use crate::guide::legend::{Legend, Symbol, truncate_to_width};
use crate::guide::scale::Scale;
use crate::mark::density::{DensityLook, PointMode, ShadingOption};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode::{self, ColorEncoding};
use crate::mark::geometry::{Geometry, Plot, PlotScale, RedrawnCells};
use crate::mark::overplot::{point_opacity, point_radius};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, frame, highlight, with_default_size};
use crate::scene::{
    Anchor, Baseline, Color, Item, PathCmd, PerPoint, Point, PointBatch, Raster, Rect, Role, Shape, Stroke, Style, Text,
};
use crate::selection::Highlight;
use crate::spec::{Channel, ChannelOptions, Chart, ColorChannel, ScaleKind};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "splom"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct SplomOptions {
    /// The columns, 2 to 12: names, or tables with `field`, `title`, `unit`, `scale`, `domain`, ...
    #[schemars(length(min = 2, max = 12), example = crate::spec::types::example_columns())]
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
    pub mode: Option<PointMode>,
    /// How density bins are shaded by their counts: `eq_hist` (default), `log` or `linear`; the
    /// legend's ticks are counts under any shading.
    #[serde(default)]
    pub shading: Option<ShadingOption>,
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

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [760.0, 720.0];
/// Side of a density bin in pixels.
const DENSITY_BIN_PX: f64 = 3.0;

/// Draw a scatter-plot matrix.
/// Also returns the interactive geometry (for brushing and zooming).
/// `plan`: the source's rows, when they stay in its plan and the table holds none (density mode).
pub fn draw(
    chart: &Chart,
    options: &SplomOptions,
    table: &Table,
    highlight: Option<&Highlight>,
    plan: Option<&PlanRows>,
) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let columns = encode::columns(chart, "columns", &options.columns, table)?;
    for (_, col) in &columns {
        encode::require_numeric(
            "columns",
            col,
            "a scatter-plot matrix",
            "colour by a text column instead (`color = \"...\"`)",
        )?;
    }
    let fields: Vec<(&str, &Column)> = columns.iter().map(|(o, c)| (o.field.as_str(), *c)).collect();
    let plan = plan.filter(|_| table.rows == 0);
    let counted = match plan {
        Some(plan) => {
            let names: Vec<&str> = fields.iter().map(|(f, _)| *f).collect();
            let asked = options.mode == Some(PointMode::Density);
            Some((plan, CountedRows::of(chart, plan, &names, asked)?))
        }
        None => None,
    };
    let (rows, mut warnings) = match &counted {
        Some((_, c)) => (Vec::new(), c.warnings.clone()),
        None => encode::drawn_rows(chart, table, fields, options.color.as_ref())?,
    };
    let n = counted.as_ref().map_or(rows.len(), |(_, c)| c.rows());
    let density = counted.is_some() || options.mode.unwrap_or_default().is_density(n as u64);
    if density && options.color.is_some() {
        warnings.push(Warning::from(format!("`color` is not drawn in density mode (bins count rows of every colour)")));
    }

    let (colors, color_legend) = encode::color_encoding(
        chart,
        options.color.as_ref().filter(|_| !density),
        options.mark_color.as_deref(),
        table,
        &rows,
        Symbol::Circle,
    )?;
    let radius = options.radius.unwrap_or_else(|| (point_radius(n) * 0.75).max(1.0));
    let opacity = options.opacity.unwrap_or_else(|| point_opacity(n));
    let look = DensityLook::new(options.shading, None, None, None);

    let mut axes = Vec::with_capacity(columns.len());
    for (k, (opts, col)) in columns.iter().enumerate() {
        let mut axis = match &counted {
            Some((plan, c)) => c.axis(k, opts, plan.is_time(&opts.field))?,
            None => encode::position_axis("columns", opts, col, &rows)?,
        };
        axis.inset = radius + 1.0;
        // Small multiples: the data's extent plus a margin, so end ticks sit inside the cells
        // rather than on the edges where neighbouring labels would meet.
        if let (Domain::Continuous(lo, hi), ScaleKind::Linear, None) = (&mut axis.domain, axis.kind, opts.domain) {
            let pad = if *hi > *lo { (*hi - *lo) * 0.04 } else { 0.5 };
            (*lo, *hi) = (*lo - pad, *hi + pad);
            axis.nice = false;
        }
        axes.push(axis);
    }
    if let Some(panel) = &chart.panel {
        panel.share_columns(&columns.iter().map(|(o, _)| o.field.as_str()).collect::<Vec<_>>(), &mut axes);
    }
    let mut legends: Vec<Legend> = color_legend.into_iter().collect();
    if density {
        // Bins hold at most every row; the real counts replace this bound once counted, so the
        // layout reserves room for the widest labels the legend can have.
        legends.insert(0, look.provisional_legend(n as u64));
    }
    legends.extend(highlight.map(|h| highlight::legend(h, &rows, Symbol::Circle)));
    let mut canvas = frame::PanelCanvas::new(chart, legends);
    let theme = canvas.theme.clone();
    let grid = Grid::lay_out(&canvas, &axes).map_err(|e| MarkError::layout(e))?;
    let layout = options.layout.unwrap_or(MatrixLayout::Full);
    let shown = |i: usize, j: usize| match layout {
        MatrixLayout::Full => true,
        MatrixLayout::Lower => j <= i,
        MatrixLayout::Upper => j >= i,
    };
    let values: Vec<&[f64]> = columns.iter().map(|(_, c)| c.numbers().unwrap_or(&[])).collect();
    let split = highlight.map(|h| h.split(&rows));
    let paint = CellPaint { colors: &colors, radius, opacity, highlight, split: split.as_ref(), rows: &rows };

    // The off-diagonal cells are independent and the bulk of the work: compute them in parallel.
    let pairs: Vec<(usize, usize)> = (0..columns.len())
        .flat_map(|i| (0..columns.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| i != j && shown(i, j))
        .collect();
    let mut counted_cells = match &counted {
        Some((_, c)) => Some(count_cells(c, options, &grid, &pairs, columns.len())?),
        None => None,
    };
    let mut cells: std::collections::HashMap<(usize, usize), CellMarks> = match &mut counted_cells {
        Some(counted) => {
            std::mem::take(&mut counted.cells).into_iter().map(|(k, c)| (k, CellMarks::Density(c))).collect()
        }
        None => pairs
            .par_iter()
            .map(|&(i, j)| {
                let (x, y) = (&grid.x[j], &grid.y[i]);
                let marks = if density {
                    CellMarks::Density(density_counts(grid.cell(i, j), x, y, values[j], values[i], &rows, highlight))
                } else {
                    CellMarks::Points(paint.points(x, y, values[j], values[i]))
                };
                ((i, j), marks)
            })
            .collect(),
    };
    // Density rasters share one shading, of every cell's counts.
    let shown_counts: Vec<u64> = cells
        .values()
        .flat_map(|c| match c {
            CellMarks::Density(counts) => counts.shown().iter().map(|&c| u64::from(c)).collect(),
            CellMarks::Points(_) => Vec::new(),
        })
        .collect();
    let scale = CountScale::new(&shown_counts, look.shading);
    if density && let Some(first) = canvas.legends.first_mut() {
        *first = look.legend(scale.clone());
    }

    let mut items = vec![canvas.background()];
    let mut geometry = Geometry::default();
    let mut diagonals: Vec<(usize, Rect, Scale, std::sync::OnceLock<Option<u32>>)> = Vec::new();
    for i in 0..columns.len() {
        for j in 0..columns.len() {
            if !shown(i, j) {
                continue;
            }
            let cell = grid.cell(i, j);
            if i == j && !density {
                diagonals.push((i, cell, grid.x[i].clone(), std::sync::OnceLock::new()));
            }
            if i != j {
                geometry.plots.push(Plot::xy(
                    cell,
                    PlotScale { field: columns[j].0.field.clone(), scale: grid.x[j].clone() },
                    PlotScale { field: columns[i].0.field.clone(), scale: grid.y[i].clone() },
                ));
            }
            items.push(Item::new(Role::Grid, Shape::Rect(cell), Style::stroke(theme.grid, 1.0)).labelled("cell"));
            if i == j {
                let counts = counted_cells.as_ref().and_then(|c| c.diagonals.get(i)).and_then(Option::as_deref);
                items.extend(diagonal_cell(
                    options,
                    cell,
                    &grid.x[i],
                    &columns[i].0,
                    (values[i], counts),
                    &paint,
                    &theme,
                ));
                continue;
            }
            items.extend(axis::grid(&grid.x[j], Side::Bottom, cell, &theme));
            items.extend(axis::grid(&grid.y[i], Side::Left, cell, &theme));
            if let Some(h) = highlight {
                items.extend(highlight::brush(
                    h,
                    cell,
                    (&columns[j].0.field, &grid.x[j]),
                    Some((&columns[i].0.field, &grid.y[i])),
                ));
            }
            match cells.remove(&(i, j)) {
                Some(CellMarks::Density(counts)) => items.push(counts.raster(&look, &scale)),
                Some(CellMarks::Points(marks)) => items.push(
                    Item::group(Role::DataMark, marks, Some(cell))
                        .labelled(format!("{} × {}", columns[j].0.field, columns[i].0.field)),
                ),
                None => {}
            }
        }
    }
    warnings.extend((frame::raster_note(&items)).into_iter().map(Warning::from));
    let fields: Vec<&str> = columns.iter().map(|(o, _)| o.field.as_str()).collect();
    items.extend(grid.axes(&axes, &fields, layout, &theme));
    if !diagonals.is_empty() {
        geometry.diagonals = Some(std::sync::Arc::new(Diagonals {
            options: options.clone(),
            cells: diagonals,
            channels: columns.iter().map(|(o, _)| o.clone()).collect(),
            colors: colors.clone(),
            radius,
            opacity,
            rows: rows.clone(),
            theme: theme.clone(),
        }));
    }

    let fields: Vec<&str> = columns.iter().map(|(o, _)| o.field.as_str()).collect();
    let mut derived = Derived::of_rows(rows, &fields);
    if let Some(c) = &options.color {
        derived.push(c.field(), DerivedColumn::Source(c.field().to_string()));
    }
    if let Some(h) = highlight {
        derived.push("selected", DerivedColumn::Selected(h.selected.clone()));
    }
    Ok(ChartOutput {
        scene: canvas.scene(chart, items, None),
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry,
    })
}

/// What it takes to draw a splom's diagonal cells again for another selection (the explorer
/// relights them as a brush moves, with the same code that drew them).
#[derive(Clone, Debug)]
pub struct Diagonals {
    options: SplomOptions,
    /// Column index, cell rectangle and scale of each diagonal cell drawn, and its histogram's
    /// bin count once known (it depends on every drawn row only, so a selection drawn again
    /// bins the same way without sorting the column again).
    cells: Vec<(usize, Rect, Scale, std::sync::OnceLock<Option<u32>>)>,
    channels: Vec<ChannelOptions>,
    colors: ColorEncoding,
    radius: f64,
    opacity: f64,
    rows: Vec<u32>,
    theme: Theme,
}

impl RedrawnCells for Diagonals {
    /// The diagonal cell containing `p`, by index into the cells drawn.
    fn cell_at(&self, p: Point) -> Option<usize> {
        self.cells.iter().position(|(_, r, _, _)| p.x >= r.x && p.x <= r.right() && p.y >= r.y && p.y <= r.bottom())
    }

    /// The data marks of every diagonal cell (in the order of [`Diagonals::cell_at`]) with the
    /// rows of `selected` (one flag per table row) lit: the grey distribution of every drawn row
    /// under the selected rows' coloured ones, as `draw` makes them for a selection. The cells
    /// are drawn in parallel.
    fn marks(&self, table: &Table, name: &str, selected: &[bool]) -> Vec<Vec<Item>> {
        let selection =
            crate::spec::Selection { data: String::new(), range: None, categories: None, combine: None, invert: None };
        let h = Highlight { name: name.to_string(), selection, selected: selected.to_vec() };
        let split = h.split(&self.rows);
        let paint = CellPaint {
            colors: &self.colors,
            radius: self.radius,
            opacity: self.opacity,
            highlight: Some(&h),
            split: Some(&split),
            rows: &self.rows,
        };
        self.cells
            .par_iter()
            .map(|(i, rect, scale, bins)| {
                let Some(channel) = self.channels.get(*i) else { return Vec::new() };
                let Some(values) = table.column(&channel.field).and_then(|c| c.numbers()) else { return Vec::new() };
                let bins = *bins.get_or_init(|| {
                    match (self.options.diagonal.unwrap_or(Diagonal::Histogram), self.options.bins) {
                        (Diagonal::Histogram, None) => {
                            let all: Vec<f64> =
                                self.rows.iter().filter_map(|&r| values.get(r as usize).copied()).collect();
                            let (lo, hi) = scale.domain();
                            u32::try_from(freedman_diaconis_bins(&all, lo, hi, 8, 50)).ok()
                        }
                        (_, bins) => bins,
                    }
                });
                let options = SplomOptions { bins, ..self.options.clone() };
                diagonal_cell(&options, *rect, scale, channel, (values, None), &paint, &self.theme)
                    .into_iter()
                    .filter(|item| item.role == Role::DataMark)
                    .collect()
            })
            .collect()
    }
}

/// What an off-diagonal cell draws.
enum CellMarks {
    /// Point batches (context, then selected or all rows).
    Points(Vec<Item>),
    /// Row counts in small bins.
    Density(DensityCounts),
}

/// The matrix layout: cell rectangles and one scale per column, across and up.
struct Grid {
    /// Left edge of each cell column.
    lefts: Vec<f64>,
    /// Top edge of each cell row.
    tops: Vec<f64>,
    cell_w: f64,
    cell_h: f64,
    gap: f64,
    /// Horizontal scale of each column (shared by its cell column).
    x: Vec<Scale>,
    /// Vertical scale of each column (shared by its cell row).
    y: Vec<Scale>,
}

impl Grid {
    /// Fit `axes.len()`² cells between the title, caption, outer axes and legends.
    fn lay_out(canvas: &frame::PanelCanvas, axes: &[PositionAxis]) -> Result<Grid, LayoutError> {
        let (width, height, theme) = (canvas.width, canvas.height, &canvas.theme);
        let m = theme.margin;
        let k = axes.len();
        let top = canvas.top();
        let bottom_reserved = m + canvas.caption_h;
        let right = m + canvas.legend_room();
        let gap = (theme.font_size * 0.8).round();
        let mut left = m + theme.font_size * 4.0;
        let mut bottom = bottom_reserved + theme.font_size * 3.0;
        for pass in 0..2 {
            let cell_w = ((width - left - right - gap * (k - 1) as f64) / k as f64).floor();
            let cell_h = ((height - top - bottom - gap * (k - 1) as f64) / k as f64).floor();
            if cell_w < MIN_PLOT_SIDE || cell_h < MIN_PLOT_SIDE {
                return Err(LayoutError::TooSmall { plot_width: cell_w.max(0.0), plot_height: cell_h.max(0.0) });
            }
            let lefts: Vec<f64> = (0..k).map(|j| left.ceil() + j as f64 * (cell_w + gap)).collect();
            let tops: Vec<f64> = (0..k).map(|i| top.ceil() + i as f64 * (cell_h + gap)).collect();
            let target_x = ((cell_w / (theme.font_size * 3.0)).round() as usize).clamp(3, 6);
            let target_y = ((cell_h / (theme.font_size * 3.0)).round() as usize).clamp(3, 6);
            let mut x = Vec::with_capacity(k);
            let mut y = Vec::with_capacity(k);
            for (c, axis) in axes.iter().enumerate() {
                let scale_x = build_scale(axis, (lefts[c], lefts[c] + cell_w), target_x)
                    .map_err(|error| LayoutError::Scale { axis: "x", error })?;
                let scale_y = build_scale(axis, (tops[c] + cell_h, tops[c]), target_y)
                    .map_err(|error| LayoutError::Scale { axis: "y", error })?;
                x.push(scale_x);
                y.push(scale_y);
            }
            if pass == 0 {
                let room = LabelRoom::unbounded(theme);
                let widest = |scales: &[Scale], side: Side| {
                    (0..k)
                        .map(|c| axis::thickness(&scales[c], side, Some(&axes[c].title), theme, &room))
                        .fold(0.0, f64::max)
                };
                left = m + widest(&y, Side::Left);
                bottom = bottom_reserved + widest(&x, Side::Bottom);
                continue;
            }
            return Ok(Grid { lefts, tops, cell_w, cell_h, gap, x, y });
        }
        unreachable!("the second pass returns")
    }

    /// The rectangle of cell (row `i`, column `j`).
    fn cell(&self, i: usize, j: usize) -> Rect {
        Rect::new(self.lefts[j], self.tops[i], self.cell_w, self.cell_h)
    }

    /// Outer axes: each cell column's x axis under its lowest drawn cell, each cell row's y axis
    /// left of its leftmost drawn cell (the outer edges for `full` and `lower`, the diagonal for
    /// `upper`). Each axis's items are labelled with its column: `x axis: FIELD`, `y axis: FIELD`.
    fn axes(&self, axes: &[PositionAxis], fields: &[&str], layout: MatrixLayout, theme: &Theme) -> Vec<Item> {
        let k = axes.len();
        let mut items = Vec::new();
        for (c, axis) in axes.iter().enumerate() {
            let (bottom_row, left_col) = match layout {
                MatrixLayout::Upper => (c, c),
                _ => (k - 1, 0),
            };
            let cell = self.cell(bottom_row, c);
            let title = truncate_to_width(&axis.title, self.cell_w + self.gap, theme.label_size);
            // Labels may reach past the outer edges, but never into a neighbouring cell's labels.
            let slack = |outer: bool| if outer { f64::INFINITY } else { self.gap * 0.3 };
            let span = (cell.x - slack(c == 0), cell.right() + slack(c == k - 1));
            let field = fields.get(c).copied().unwrap_or_default();
            let of_column = |side: &str, drawn: Vec<Item>| -> Vec<Item> {
                let (plain, named) = (format!("{side} axis"), format!("{side} axis: {field}"));
                drawn
                    .into_iter()
                    .map(|item| {
                        if item.label.as_deref() == Some(plain.as_str()) { item.labelled(named.clone()) } else { item }
                    })
                    .collect()
            };
            items.extend(of_column(
                "x",
                axis::draw_within(
                    &self.x[c],
                    Side::Bottom,
                    cell,
                    Some(&title),
                    theme,
                    &LabelRoom::unbounded(theme).within(span),
                ),
            ));
            let cell = self.cell(c, left_col);
            let title = truncate_to_width(&axis.title, self.cell_h + self.gap, theme.label_size);
            let span = (cell.y - slack(c == 0), cell.bottom() + slack(c == k - 1));
            items.extend(of_column(
                "y",
                axis::draw_within(
                    &self.y[c],
                    Side::Left,
                    cell,
                    Some(&title),
                    theme,
                    &LabelRoom::unbounded(theme).within(span),
                ),
            ));
        }
        items
    }
}

/// How the rows of an off-diagonal cell are painted.
struct CellPaint<'a> {
    colors: &'a ColorEncoding,
    radius: f64,
    opacity: f64,
    highlight: Option<&'a Highlight>,
    /// (context, selected) rows when a selection is drawn.
    split: Option<&'a (Vec<u32>, Vec<u32>)>,
    rows: &'a [u32],
}

impl CellPaint<'_> {
    /// Point batches of one cell: grey context first, then the selected or all rows in colour.
    fn points(&self, x: &Scale, y: &Scale, xs: &[f64], ys: &[f64]) -> Vec<Item> {
        let batch = |rows: &[u32], context: bool| {
            let centers: Vec<Point> =
                rows.iter().map(|&r| Point::new(x.map(xs[r as usize]), y.map(ys[r as usize]))).collect();
            let fill = highlight::point_fill(self.colors, rows, context, self.opacity);
            let stroke =
                (rows.len() <= 2_000 && self.radius >= 2.5).then(|| Stroke::solid(Color::WHITE.with_opacity(0.7), 0.5));
            let batch = PointBatch { centers, radius: PerPoint::Uniform(self.radius), fill, stroke };
            Item::new(Role::DataMark, Shape::Points(batch), Style::default()).with_rows(rows.to_vec())
        };
        match self.split {
            Some((context, selected)) => vec![batch(context, true), batch(selected, false)],
            None => vec![batch(self.rows, false)],
        }
    }

    /// The colour groups of the diagonal: (colour, rows), one group per category for a
    /// categorical colour, else one.
    fn groups(&self, rows: &[u32]) -> Vec<(Color, Vec<u32>)> {
        match self.colors {
            ColorEncoding::Categorical { categories, colors } => {
                let mut groups: Vec<Vec<u32>> = vec![Vec::new(); colors.len() + 1];
                for &r in rows {
                    let code = categories.codes.get(r as usize).copied().unwrap_or(u32::MAX) as usize;
                    groups[code.min(colors.len())].push(r);
                }
                groups
                    .into_iter()
                    .enumerate()
                    .filter(|(_, g)| !g.is_empty())
                    .map(|(k, g)| (colors.get(k).copied().unwrap_or(encode::MISSING_COLOR), g))
                    .collect()
            }
            ColorEncoding::Fixed(c) => vec![(*c, rows.to_vec())],
            ColorEncoding::Continuous { .. } => vec![(encode::DEFAULT_MARK_COLOR, rows.to_vec())],
        }
    }
}

/// A diagonal cell: the column's histogram or density (stacked by colour group, selected rows
/// over grey context), or just its name. `values`: the column, and its histogram's counts when
/// they were counted where the rows are (then the cell draws those, in one colour).
fn diagonal_cell(
    options: &SplomOptions,
    cell: Rect,
    scale: &Scale,
    channel: &ChannelOptions,
    (values, counted): (&[f64], Option<&[f64]>),
    paint: &CellPaint,
    theme: &Theme,
) -> Vec<Item> {
    let (lo, hi) = scale.domain();
    let mut items = Vec::new();
    if let Some(h) = paint.highlight {
        items.extend(highlight::brush(h, cell, (&channel.field, scale), None));
    }
    let (context, foreground): (&[u32], &[u32]) = match paint.split {
        Some((_, selected)) => (paint.rows, selected),
        None => (&[], paint.rows),
    };
    let groups = paint.groups(foreground);
    let kind = options.diagonal.unwrap_or(Diagonal::Histogram);
    let base = cell.bottom();
    // Leave room for the column name at the top of the cell.
    let height = (cell.h - theme.label_size * 1.6).max(cell.h * 0.5);
    match kind {
        Diagonal::Histogram => {
            let at = |rows: &[u32]| rows.iter().map(|&r| values[r as usize]).collect::<Vec<f64>>();
            let all = at(paint.rows);
            let bins = match counted {
                Some(counts) => counts.len(),
                None => options.bins.map_or_else(|| freedman_diaconis_bins(&all, lo, hi, 8, 50), |b| b as usize),
            };
            let count = |rows: &[u32]| match counted {
                Some(counts) => counts.to_vec(),
                None => bin_counts(rows.iter().map(|&r| values[r as usize]), lo, hi, bins),
            };
            let total = count(paint.rows);
            let max = total.iter().copied().fold(1.0, f64::max);
            let bar = |k: usize, from: f64, count: f64| {
                let x0 = scale.map(lo + (hi - lo) * k as f64 / bins as f64);
                let x1 = scale.map(lo + (hi - lo) * (k + 1) as f64 / bins as f64);
                let y0 = base - height * from / max;
                let y1 = base - height * (from + count) / max;
                // A hairline gap between bars, narrower for narrow bars so they stay solid.
                let gap = ((x1 - x0).abs() * 0.08).min(0.5);
                [x0 + gap, y1, x1 - gap, y0]
            };
            if !context.is_empty() {
                let rects: Vec<[f64; 4]> = total.iter().enumerate().map(|(k, &c)| bar(k, 0.0, c)).collect();
                items
                    .push(rect_path(&rects, highlight::CONTEXT, "histogram (all rows)").with_rows(paint.rows.to_vec()));
            }
            let mut stacked = vec![0.0; bins];
            for (color, rows) in &groups {
                let counts = count(rows);
                let rects: Vec<[f64; 4]> = counts
                    .iter()
                    .enumerate()
                    .filter(|(_, c)| **c > 0.0)
                    .map(|(k, &c)| {
                        let r = bar(k, stacked[k], c);
                        stacked[k] += c;
                        r
                    })
                    .collect();
                items.push(rect_path(&rects, *color, "histogram").with_rows(rows.clone()));
            }
        }
        Diagonal::Density => {
            let all: Vec<f64> = paint.rows.iter().map(|&r| values[r as usize]).collect();
            let h = silverman_bandwidth(&all).unwrap_or((hi - lo) / 20.0);
            let points = (cell.w as usize).clamp(32, 256);
            let curve = |rows: &[u32]| {
                let v: Vec<f64> = rows.iter().map(|&r| values[r as usize]).collect();
                // Each group's density weighted by its share, so the curves compare counts.
                let share = v.len() as f64 / all.len().max(1) as f64;
                kde(&v, h, lo, hi, points).into_iter().map(|d| d * share).collect::<Vec<f64>>()
            };
            let all_curve = curve(paint.rows);
            let curves: Vec<(Color, Vec<f64>, &Vec<u32>)> = groups.iter().map(|(c, r)| (*c, curve(r), r)).collect();
            let max = curves.iter().flat_map(|(_, c, _)| c.iter()).chain(&all_curve).copied().fold(1e-300, f64::max);
            let to_px = |k: usize, d: f64| {
                Point::new(scale.map(lo + (hi - lo) * k as f64 / (points - 1) as f64), base - height * d / max)
            };
            let area = |curve: &[f64]| {
                let mut cmds = vec![PathCmd::MoveTo(to_px(0, 0.0))];
                cmds.extend(curve.iter().enumerate().map(|(k, &d)| PathCmd::LineTo(to_px(k, d))));
                cmds.push(PathCmd::LineTo(to_px(points - 1, 0.0)));
                cmds.push(PathCmd::Close);
                cmds
            };
            if !context.is_empty() {
                items.push(
                    Item::new(Role::DataMark, Shape::Path(area(&all_curve)), Style::fill(highlight::CONTEXT))
                        .labelled("density (all rows)")
                        .with_rows(paint.rows.to_vec()),
                );
            }
            for (color, curve, rows) in curves {
                let style = Style { fill: Some(color.with_opacity(0.25)), stroke: Some(Stroke::solid(color, 1.5)) };
                items.push(
                    Item::new(Role::DataMark, Shape::Path(area(&curve)), style)
                        .with_rows(rows.clone())
                        .labelled("density"),
                );
            }
        }
        Diagonal::Label => {}
    }
    let name = truncate_to_width(channel.title.as_deref().unwrap_or(&channel.field), cell.w - 8.0, theme.label_size);
    let (at, anchor, baseline) = match kind {
        Diagonal::Label => (Point::new(cell.x + cell.w / 2.0, cell.y + cell.h / 2.0), Anchor::Middle, Baseline::Middle),
        _ => (Point::new(cell.x + 4.0, cell.y + 3.0), Anchor::Start, Baseline::Top),
    };
    items.push(
        Item::text(
            Role::Annotation,
            Text { at, content: name, size: theme.label_size, anchor, baseline, angle: 0.0, color: theme.text },
        )
        .labelled("column name"),
    );
    items
}

/// One path of axis-aligned rectangles `[x0, y0, x1, y1]`, filled.
fn rect_path(rects: &[[f64; 4]], color: Color, label: &str) -> Item {
    let mut cmds = Vec::with_capacity(rects.len() * 5);
    for &[x0, y0, x1, y1] in rects {
        cmds.push(PathCmd::MoveTo(Point::new(x0, y0)));
        cmds.push(PathCmd::LineTo(Point::new(x1, y0)));
        cmds.push(PathCmd::LineTo(Point::new(x1, y1)));
        cmds.push(PathCmd::LineTo(Point::new(x0, y1)));
        cmds.push(PathCmd::Close);
    }
    Item::new(Role::DataMark, Shape::Path(cmds), Style::fill(color)).labelled(label)
}

/// Row counts in small square bins of one cell: all rows, and the selected ones.
pub(super) struct DensityCounts {
    pub cell: Rect,
    pub nx: usize,
    pub ny: usize,
    pub all: Vec<u32>,
    pub selected: Option<Vec<u32>>,
}

impl DensityCounts {
    /// The counts drawn in colour: of the selected rows when a selection is drawn.
    fn shown(&self) -> &[u32] {
        self.selected.as_ref().unwrap_or(&self.all)
    }

    /// The cell as a raster: counts shaded by `scale` as `look` colours them; bins with only
    /// unselected rows in grey.
    fn raster(&self, look: &DensityLook, scale: &CountScale) -> Item {
        let mut rgba = vec![0u8; self.nx * self.ny * 4];
        let counts = self.shown();
        for k in 0..self.nx * self.ny {
            let color = if counts[k] > 0 {
                look.colours.at(scale.position(f64::from(counts[k])))
            } else if self.all[k] > 0 {
                highlight::CONTEXT
            } else {
                continue;
            };
            rgba[k * 4..k * 4 + 4].copy_from_slice(&[color.r, color.g, color.b, color.a]);
        }
        let raster = Raster {
            dest: self.cell,
            width: self.nx as u32,
            height: self.ny as u32,
            rgba: std::sync::Arc::new(rgba),
            smooth: false,
        };
        Item::new(Role::DataMark, Shape::Image(raster), Style::default()).labelled("density")
    }
}

/// Count rows into bins of about [`DENSITY_BIN_PX`] pixels over `cell`.
fn density_counts(
    cell: Rect,
    x: &Scale,
    y: &Scale,
    xs: &[f64],
    ys: &[f64],
    rows: &[u32],
    highlight: Option<&Highlight>,
) -> DensityCounts {
    let (nx, ny) = density_bins(cell);
    let mut all = vec![0u32; nx * ny];
    let mut selected = highlight.map(|_| vec![0u32; nx * ny]);
    for &r in rows {
        let Some(bin) = density_bin(cell, (nx, ny), (x, y), xs[r as usize], ys[r as usize]) else { continue };
        all[bin] += 1;
        if let (Some(sel), Some(h)) = (selected.as_mut(), highlight)
            && h.contains(r)
        {
            sel[bin] += 1;
        }
    }
    DensityCounts { cell, nx, ny, all, selected }
}

/// How many density bins of about [`DENSITY_BIN_PX`] pixels a cell has across and up.
pub(super) fn density_bins(cell: Rect) -> (usize, usize) {
    (((cell.w / DENSITY_BIN_PX).round() as usize).max(1), ((cell.h / DENSITY_BIN_PX).round() as usize).max(1))
}

/// The density bin (row-major from the cell's top left) of the point `(xv, yv)` placed by the
/// scales `x` and `y` in `cell` of `nx` × `ny` bins; `None` when it falls before the cell.
#[inline]
pub(super) fn density_bin(
    cell: Rect,
    (nx, ny): (usize, usize),
    (x, y): (&Scale, &Scale),
    xv: f64,
    yv: f64,
) -> Option<usize> {
    let px = (x.map(xv) - cell.x) / cell.w * nx as f64;
    let py = (y.map(yv) - cell.y) / cell.h * ny as f64;
    if !(px >= 0.0 && py >= 0.0) {
        return None;
    }
    Some((py as usize).min(ny - 1) * nx + (px as usize).min(nx - 1))
}

/// Every shown off-diagonal cell and diagonal histogram of a matrix over rows left in the plan,
/// counted in one scan.
fn count_cells(
    counted: &CountedRows,
    options: &SplomOptions,
    grid: &Grid,
    pairs: &[(usize, usize)],
    columns: usize,
) -> Result<CountedCells, MarkError> {
    let cells = pairs
        .iter()
        .map(|&(i, j)| {
            let cell = grid.cell(i, j);
            let (nx, ny) = density_bins(cell);
            CellBins { i, j, cell, nx, ny, x: grid.x[j].clone(), y: grid.y[i].clone() }
        })
        .collect();
    let mut diagonals = Vec::new();
    if options.diagonal.unwrap_or(Diagonal::Histogram) == Diagonal::Histogram {
        let domains: Vec<(f64, f64)> = (0..columns).map(|k| grid.x[k].domain()).collect();
        let bins = counted.diagonal_bins(options.bins, &domains)?;
        for (column, (&(lo, hi), bins)) in domains.iter().zip(bins).enumerate() {
            diagonals.push(DiagonalBins { column, lo, hi, bins });
        }
    }
    counted.count(columns, cells, diagonals)
}

/// `kind = "splom"`.
pub static KIND: KindInfo = KindInfo::new("splom", &["columns", "color"])
    .counting_rows(crate::mark::registry::RowCounting {
        modes: Some(&["density", "auto"]),
        unless: &["color", "diagonal", "highlight", "facet"],
        on_engine: false,
    })
    .sized(DEFAULT_SIZE)
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Canvas);

impl Technique for SplomOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.highlight, cx.plan)
    }

    crate::mark::registry::color_key!();
}
