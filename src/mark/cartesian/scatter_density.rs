//! `scatter` in density mode: the rows counted in bins of a few pixels over the plot and each bin
//! shaded by its count, with a legend whose ticks are counts. The rows come from the chart's
//! table, or stay in the source's lazy plan and are counted as the engine streams them.

use super::scatter::ScatterOptions;
use crate::data::Table;
use crate::data::density::{CountGrid, Extent, count_by_category, count_columns, extent_of_columns, plan::PlanRows};
use crate::guide::layout::PositionAxis;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::density::{DensityLook, derived_bins};
use crate::mark::encode;
use crate::mark::encode::ColorEncoding;
use crate::mark::geometry::{Geometry, Plot, PlotScale};
use crate::mark::warning::{ColumnLoss, Warning};
use crate::mark::{ChartOutput, MarkError, frame};
use crate::scene::Color;
use crate::selection::Highlight;
use crate::spec::{ChannelOptions, Chart, ScaleKind};
use crate::timing::timed;

/// Where the chart's rows are.
pub enum Rows<'a> {
    /// In its table.
    Table(&'a Table),
    /// In its source's lazy plan, not read yet.
    Plan(&'a PlanRows),
}

/// The x and y of the rows, whichever way they are held.
enum Placed<'a> {
    Columns(&'a [f64], &'a [f64]),
    Plan(&'a PlanRows),
}

impl Placed<'_> {
    fn extent(&self, x: &ChannelOptions, y: &ChannelOptions, log: [bool; 2]) -> Result<Extent, MarkError> {
        match self {
            Placed::Columns(xs, ys) => Ok(extent_of_columns(xs, ys, log)),
            Placed::Plan(plan) => plan.extent(&x.field, &y.field, log).map_err(engine_error),
        }
    }

    fn count(
        &self,
        x: &ChannelOptions,
        y: &ChannelOptions,
        bins: &(crate::data::density::Bins, crate::data::density::Bins),
    ) -> Result<CountGrid, MarkError> {
        match self {
            Placed::Columns(xs, ys) => Ok(count_columns(xs, ys, None, &bins.0, &bins.1)),
            Placed::Plan(plan) => plan.count(&x.field, &y.field, &bins.0, &bins.1).map_err(engine_error),
        }
    }
}

fn engine_error(message: String) -> MarkError {
    MarkError::at(&["data"], message, "`dataink data SPEC NAME` shows the rows after the source's transforms")
}

/// Draw a scatter chart as a density.
pub fn draw(
    chart: &Chart,
    options: &ScatterOptions,
    rows: Rows<'_>,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let (x_opts, y_opts) = (options.x.options(), options.y.options());
    let mut warnings = Vec::new();
    for (given, key, why) in [
        (options.point_size.is_some(), "point_size", "bins count rows, not sizes"),
        (options.trend.is_some(), "trend", "a density view draws no trend line yet"),
        (highlight.is_some(), "highlight", "a density view does not mark a selection yet"),
    ] {
        if given {
            warnings.push(Warning::from(format!("`{key}` is not drawn in density mode: {why}")));
        }
    }
    let (placed, times, total) = match rows {
        Rows::Table(table) => {
            let mut columns = Vec::new();
            for (key, opts) in [("x", &x_opts), ("y", &y_opts)] {
                let column = encode::column(chart, key, &opts.field, table)?;
                let values = column.numbers().ok_or_else(|| {
                    MarkError::at(
                        &[key],
                        format!("column `{}` holds text; a density view places numbers or times", opts.field),
                        "use mode = \"points\" to place categories in bands",
                    )
                })?;
                columns.push((values, column.is_time()));
            }
            (Placed::Columns(columns[0].0, columns[1].0), [columns[0].1, columns[1].1], table.rows as u64)
        }
        Rows::Plan(plan) => {
            (Placed::Plan(plan), [plan.is_time(&x_opts.field), plan.is_time(&y_opts.field)], plan.rows())
        }
    };
    let mixed = match (&rows, &options.color) {
        (Rows::Table(table), Some(channel)) => {
            let all: Vec<u32> = (0..table.rows as u32).collect();
            match encode::color_encoding(chart, Some(channel), None, table, &all, Symbol::Square)? {
                (ColorEncoding::Categorical { categories, colors }, legend) => Some((categories, colors, legend)),
                _ => {
                    warnings.push(Warning::from(
                        "`color` by numbers is not drawn in density mode: bins count rows, and a bin's rows have many values"
                            .to_string(),
                    ));
                    None
                }
            }
        }
        _ => None,
    };
    let log = [x_opts.scale == Some(ScaleKind::Log), y_opts.scale == Some(ScaleKind::Log)];
    let extent = timed("density extent", || placed.extent(&x_opts, &y_opts, log))?;
    let (Some(x_extent), Some(y_extent)) = (extent.x, extent.y) else {
        return Err(MarkError::at(
            &["data"],
            format!("data \"{}\" has no row with both `{}` and `{}` placeable", chart.data, x_opts.field, y_opts.field),
            "check the columns' contents; missing and non-finite cells are not drawn",
        ));
    };
    let mut look = DensityLook::new(options.shading, options.bin, options.min_alpha, options.spread);
    if mixed.is_some() {
        look = look.by_category();
    }
    let category_legend: Vec<Legend> = mixed.as_ref().and_then(|m| m.2.clone()).into_iter().collect();
    let x_axis = axis("x", &x_opts, x_extent, times[0])?;
    let y_axis = axis("y", &y_opts, y_extent, times[1])?;
    let legends = [vec![look.provisional_legend(total)], category_legend.clone()].concat();
    let (mut frame, theme) = frame::cartesian(chart, x_axis, y_axis, legends)?;
    let bins = look
        .bins(frame.plot, &frame.x, &frame.y)
        .ok_or_else(|| MarkError::at(&["size"], "the plot has no room for density bins", "make the chart larger"))?;
    let split = match (&mixed, &placed) {
        (Some((categories, colors, _)), Placed::Columns(xs, ys)) => Some(timed("density counts by category", || {
            count_by_category(xs, ys, &categories.codes, colors.len(), &bins.0, &bins.1)
        })),
        _ => None,
    };
    let counted;
    let grid = match &split {
        Some(split) => &split.totals,
        None => {
            counted = timed("density counts", || placed.count(&x_opts, &y_opts, &bins))?;
            &counted
        }
    };
    warnings.extend(left_out(chart, grid, total, [&x_opts, &y_opts]));
    let (raster, scale) = match (&split, &mixed) {
        (Some(split), Some((_, colors, _))) => {
            let with_missing: Vec<Color> = colors.iter().copied().chain([crate::guide::color::MISSING]).collect();
            look.mixed_raster(split, &with_missing, frame.plot, &chart.name)
        }
        _ => look.raster(grid, frame.plot, &chart.name),
    };
    frame.redraw_legends(&[vec![look.legend(scale)], category_legend].concat(), &theme);
    let plot = Plot::xy(
        frame.plot,
        PlotScale { field: x_opts.field.clone(), scale: frame.x.clone() },
        PlotScale { field: y_opts.field.clone(), scale: frame.y.clone() },
    );
    let scene = frame::scene(chart, frame, &theme, vec![raster], &mut warnings);
    let derived = derived_bins(grid, &x_opts.field, &y_opts.field);
    let geometry = Geometry { plots: vec![plot], ..Geometry::default() };
    Ok(ChartOutput { scene, derived, warnings, meshes: Vec::new(), geojson: None, volume: None, geometry })
}

/// The warnings for the rows the grid left out: those lacking a placeable value (per column, as
/// every chart reports dropped rows) and, per axis with a fixed `domain`, those outside it.
fn left_out(chart: &Chart, grid: &CountGrid, total: u64, axes: [&ChannelOptions; 2]) -> Vec<Warning> {
    let losses = &grid.losses;
    let columns: Vec<ColumnLoss> = (0..2)
        .map(|a| ColumnLoss {
            field: axes[a].field.clone(),
            missing: losses.missing[a] as usize,
            infinite: losses.infinite[a] as usize,
            non_positive: losses.non_positive[a] as usize,
        })
        .filter(|c| c.missing + c.infinite + c.non_positive > 0)
        .collect();
    let mut warnings = Vec::new();
    if grid.missing > 0 {
        warnings.push(Warning::DroppedRows {
            chart: chart.name.clone(),
            dropped: grid.missing as usize,
            rows: total as usize,
            columns,
        });
    }
    let placeable = (grid.placed() + grid.outside) as usize;
    for (a, options) in axes.into_iter().enumerate() {
        if let Some([lo, hi]) = options.domain {
            let outside = losses.outside[a] as usize;
            warnings.extend(Warning::outside_domain(&options.field, outside, placeable, [lo.min(hi), lo.max(hi)]));
        }
    }
    warnings
}

/// A position axis over the placed rows' extent (or the channel's `domain`).
fn axis(key: &str, options: &ChannelOptions, extent: (f64, f64), time: bool) -> Result<PositionAxis, MarkError> {
    let kind = match options.scale {
        Some(ScaleKind::Band) => {
            return Err(MarkError::at(
                &[key, "scale"],
                "a density view places numbers or times, not bands",
                "use mode = \"points\" for a band scale",
            ));
        }
        Some(kind) => kind,
        None if time => ScaleKind::Time,
        None => ScaleKind::Linear,
    };
    encode::numeric_axis(key, options, kind, Some(extent))
}
