//! Small multiples (`facet = ...`): a chart's rows split by the values of one or two columns,
//! each part drawn as a panel by the chart's own kind, on one canvas.
//!
//! A cartesian kind ([`Faceting::Frame`]) goes through each panel twice. The first pass records
//! each panel's axes and legends (through [`Panel`]) and stops before any mark is built; the union of the domains becomes the shared
//! scale of every channel that `resolve` does not make independent, and the legends are drawn
//! once beside the grid. The second pass draws each panel at its place on the whole canvas with
//! those scales, its tick labels only on the outer sides of the grid. Kinds with their own
//! layout ([`Faceting::Canvas`]) draw each panel as a small chart of its own, moved into place.

mod grid;
mod merge;
pub mod split;

use std::sync::Arc;

use rayon::prelude::*;

use crate::data::Table;
use crate::mark::panel::{Panel, PanelHandle, Seen};
use crate::mark::registry::{ChartContext, Faceting, names_where, technique};
use crate::mark::{ChartOutput, FRAME_SIZE, MarkError};
use crate::scene::{Item, Role, Scene};
use crate::selection::Highlight;
use crate::spec::{Chart, Facet, Sharing};

use split::Split;

/// Draw a faceted chart: one panel per value (or pair of values) of the facet columns.
pub fn draw(cx: &ChartContext<'_>, facet: &Facet) -> Result<ChartOutput, MarkError> {
    let kind = technique(&cx.chart.kind);
    let faceting = kind.info().faceting;
    if faceting == Faceting::Not {
        return Err(MarkError::at(
            &["facet"],
            format!("a `{}` chart cannot be faceted: it does not draw its rows one by one", kind.info().name),
            format!("remove `facet`; kinds that facet: {}", names_where(|k| k.faceting != Faceting::Not).join(", ")),
        ));
    }
    let split = split::split(facet, cx.table)?;
    if split.panels.is_empty() {
        return Err(MarkError::at(
            &["facet"],
            "no row has a value of the facet columns",
            "facet by a column with values",
        ));
    }
    let resolve = facet.options().resolve.unwrap_or_default();
    let mut base = cx.chart.clone();
    base.facet = None;
    base.panel = None;
    if let Some(shared) = kind.facet_shared(&base, cx.table)? {
        base.kind = shared;
    }
    let colour_order = crate::mark::categorical::fix_domain(&mut base, cx.table);
    let mut parts = Parts::new(cx, &split, base);
    parts.colour_order = colour_order.unwrap_or_default();
    match faceting {
        Faceting::Frame => {
            frame_panels(&parts, resolve.x == Some(Sharing::Independent), resolve.y == Some(Sharing::Independent))
        }
        _ => canvas_panels(&parts),
    }
}

/// The canvas of a faceted chart without `size`: room for its panels (from the facet columns'
/// values in `table`), their headers and, when the spec encodes colour or a selection, a legend.
pub fn default_size(chart: &Chart, facet: &Facet, table: &Table) -> Result<[f64; 2], MarkError> {
    Ok(sized_for(chart, &split::split(facet, table)?))
}

/// The default canvas of `chart` split as `split`: legend room when the spec encodes colour or
/// draws a selection.
fn sized_for(chart: &Chart, split: &Split) -> [f64; 2] {
    let kind = technique(&chart.kind);
    let legends = !kind.colour_encodings().is_empty() || chart.highlight.is_some();
    grid::default_size(split, kind.info().faceting == Faceting::Frame, legends)
}

/// A faceted chart split into its panels' tables, ready to draw.
struct Parts<'a> {
    /// The chart being faceted.
    cx: &'a ChartContext<'a>,
    /// The panels.
    split: &'a Split,
    /// The chart each panel draws (no facet, options shared across panels fixed).
    base: Chart,
    /// Each panel's rows as a table.
    tables: Vec<Table>,
    /// Each panel's part of the highlighted selection.
    highlights: Vec<Option<Highlight>>,
    /// The order of the colour categories (empty without categorical colours).
    colour_order: Vec<String>,
}

impl<'a> Parts<'a> {
    fn new(cx: &'a ChartContext<'a>, split: &'a Split, base: Chart) -> Parts<'a> {
        let tables = split.panels.par_iter().map(|p| cx.table.take_rows(&p.rows)).collect();
        let highlights = split
            .panels
            .iter()
            .map(|p| {
                cx.highlight.map(|h| Highlight {
                    name: h.name.clone(),
                    selection: h.selection.clone(),
                    selected: p.rows.iter().map(|&r| h.contains(r)).collect(),
                })
            })
            .collect();
        Parts { cx, split, base, tables, highlights, colour_order: Vec::new() }
    }

    /// Draw panel `i` at canvas size `size` with the instructions of `panel`; returns what it
    /// drew (`None` when the panel only measured) and what it saw.
    fn run(&self, i: usize, panel: Panel, size: [f64; 2]) -> Result<(Option<ChartOutput>, Seen), MarkError> {
        let handle = PanelHandle(Arc::new(panel));
        let mut chart = self.base.clone();
        chart.title = None;
        chart.caption = None;
        chart.size = Some(size);
        chart.panel = Some(handle.clone());
        let cx = ChartContext {
            chart,
            index: self.cx.index,
            table: &self.tables[i],
            highlight: self.highlights[i].as_ref(),
            nodes: self.cx.nodes,
            view: None,
            volume: None,
            span_space: None,
            surfaces: None,
            plan: None,
        };
        match technique(&cx.chart.kind).draw(&cx) {
            Ok(output) => Ok((Some(output), handle.seen())),
            Err(e) if e.is_measured() => Ok((None, handle.seen())),
            Err(mut e) => {
                e.message = format!("panel {}: {}", self.split.panel_name(&self.split.panels[i]), e.message);
                Err(e)
            }
        }
    }

    /// What every panel sees at the measuring size, in parallel. A cartesian panel stops once
    /// its frame has recorded its axes (`measuring`); other kinds draw in full.
    fn measure_all(&self, measuring: bool) -> Result<Vec<Seen>, MarkError> {
        (0..self.split.panels.len())
            .into_par_iter()
            .map(|i| Ok(self.run(i, Panel { measuring, ..Panel::default() }, FRAME_SIZE)?.1))
            .collect()
    }

    /// Draw every panel in parallel.
    fn draw_all(&self, panel: impl Fn(usize) -> (Panel, [f64; 2]) + Sync) -> Result<Vec<ChartOutput>, MarkError> {
        (0..self.split.panels.len())
            .into_par_iter()
            .map(|i| {
                let (p, size) = panel(i);
                let (output, _) = self.run(i, p, size)?;
                output.ok_or_else(|| MarkError::at(&["facet"], "a facet panel measured instead of drawing", ""))
            })
            .collect()
    }

    /// The canvas: the spec's `size`, else room for the panels ([`default_size`]).
    fn size(&self) -> [f64; 2] {
        self.cx.chart.size.unwrap_or_else(|| sized_for(&self.cx.chart, self.split))
    }
}

/// Panels that are one cartesian frame each, sharing their scales unless told otherwise.
fn frame_panels(parts: &Parts<'_>, x_independent: bool, y_independent: bool) -> Result<ChartOutput, MarkError> {
    let measured = parts.measure_all(true)?;
    let (Some(x), Some(y)) = (
        merge::union_axis(measured.iter().filter_map(|s| s.x.as_ref())),
        merge::union_axis(measured.iter().filter_map(|s| s.y.as_ref())),
    ) else {
        return Err(MarkError::at(&["facet"], "the chart's panels drew no axes to share", ""));
    };
    let mut legends = merge::union_legends(measured.iter().map(|s| s.legends.as_slice()), &parts.colour_order);
    let size_max = merge::share_size(&mut legends, &measured);
    let mut chart = parts.cx.chart.clone();
    chart.size = Some(parts.size());
    let axes = grid::GridAxes { x: &x, y: &y, x_independent, y_independent };
    let layout = grid::layout(&chart, parts.split, Some(&axes), &legends)?;
    let size = chart.size.unwrap_or(FRAME_SIZE);
    let color = merge::colour_range(&legends);
    let drawn = parts.draw_all(|i| {
        let panel = Panel {
            x: (!x_independent).then(|| x.domain.clone()),
            y: (!y_independent).then(|| y.domain.clone()),
            color,
            size_max,
            plot: Some(layout.areas[i]),
            x_labels: layout.x_labels[i],
            y_labels: layout.y_labels[i],
            overhang: layout.overhang,
            ..Panel::default()
        };
        (panel, size)
    })?;
    Ok(compose(parts, &chart, size, layout, drawn, |o| o.scene.items))
}

/// Panels that are whole charts of their own layout, moved into place.
fn canvas_panels(parts: &Parts<'_>) -> Result<ChartOutput, MarkError> {
    let measured = parts.measure_all(false)?;
    let legends = merge::union_legends(measured.iter().map(|s| s.legends.as_slice()), &parts.colour_order);
    let columns = merge::union_columns(measured.iter().map(|s| s.columns.as_slice()));
    let mut chart = parts.cx.chart.clone();
    chart.size = Some(parts.size());
    let layout = grid::layout(&chart, parts.split, None, &legends)?;
    let size = chart.size.unwrap_or(FRAME_SIZE);
    let areas = layout.areas.clone();
    let mut outputs =
        parts.draw_all(|i| (Panel { columns: columns.clone(), ..Panel::default() }, [areas[i].w, areas[i].h]))?;
    for (output, area) in outputs.iter_mut().zip(&areas) {
        // The panel's own interactive geometry is in its own coordinates; none is offered.
        output.geometry = Default::default();
        let items = std::mem::take(&mut output.scene.items);
        output.scene.items = items
            .into_iter()
            .filter(|item| item.role != Role::Background)
            .map(|item| item.translated(area.x, area.y))
            .collect();
    }
    Ok(compose(parts, &chart, size, layout, outputs, |o| o.scene.items))
}

/// One scene, derived table, warning list and geometry from the panels' outputs.
fn compose(
    parts: &Parts<'_>,
    chart: &Chart,
    size: [f64; 2],
    layout: grid::GridLayout,
    outputs: Vec<ChartOutput>,
    items_of: impl Fn(ChartOutput) -> Vec<Item>,
) -> ChartOutput {
    let split = parts.split;
    let derived = merge::concat_derived(&outputs, split, parts.cx.table.rows);
    let warnings = merge::merge_warnings(&outputs, split, &parts.cx.chart.name, parts.cx.table.rows);
    let mut geometry = crate::mark::geometry::Geometry::default();
    for o in &outputs {
        geometry.plots.extend(o.geometry.plots.iter().cloned());
        geometry.axes.extend(o.geometry.axes.iter().cloned());
    }
    let mut items = layout.under;
    for (i, output) in outputs.into_iter().enumerate() {
        let panel = &split.panels[i];
        let mut panel_items = items_of(output);
        merge::to_table_rows(&mut panel_items, &panel.rows);
        items.push(
            Item::group(Role::Background, panel_items, None).labelled(format!("panel: {}", split.panel_name(panel))),
        );
    }
    items.extend(layout.over);
    let theme_background = crate::guide::Theme::with_font_size(chart.font_size.unwrap_or(12.0)).background;
    ChartOutput {
        scene: Scene {
            width: size[0],
            height: size[1],
            background: theme_background,
            title: chart.title.clone(),
            items,
        },
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry,
    }
}
