//! The explorer's state without a window: every chart of a spec drawn into raster tiles, one row
//! set per data source shared by its charts, and the pointer actions (brush, hover, zoom, pan,
//! hyperbolic focus, save) as plain methods taking canvas coordinates.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use super::brush::{self, Brush, Mode, RowSet};
use super::counts::CountedTile;
use super::hyper::{FOCUS_SECONDS, FocusView};
use super::light;
use super::orbit::{self, Orbit};
use super::view;
use crate::data::Table;
use crate::enrich::volume::SpanSpace;
use crate::mark::geometry::Geometry;
use crate::mark::volume::isosurface::SurfaceCache;
use crate::mark::{ChartContext, ChartOutput};
use crate::pipeline::Loaded;
use crate::render::tiles::Tiles;
use crate::scene::{Item, Point, Rect, Shape};
use crate::selection::Highlight;
use crate::spec::Chart;

/// How near (canvas units) the pointer must be to a mark for hover to describe it.
pub const HOVER_REACH: f64 = 8.0;

/// What a drag started on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A cartesian plot (index into the chart's plots).
    Plot(usize),
    /// A parallel-coordinates axis (index into the chart's axes).
    Axis(usize),
    /// A hyperbolic tree's disk.
    Disk,
    /// A 3-D chart's drawing, turned by dragging.
    Scene,
}

/// One chart as shown: its drawing, tiles, geometry and view state.
#[derive(Debug)]
pub struct ChartView {
    /// Position among the spec's charts.
    pub index: usize,
    /// The chart's name.
    pub name: String,
    /// Its data source.
    pub data: String,
    /// Canvas size in canvas units.
    pub size: [f64; 2],
    /// The drawing (`None` when the chart failed to draw; see `error`).
    pub output: Option<ChartOutput>,
    /// Why the chart could not be drawn.
    pub error: Option<String>,
    /// Plots, axes or disk, for the pointer.
    pub geometry: Geometry,
    /// The drawing as raster tiles.
    pub tiles: Option<Tiles>,
    /// Axis domains set by zoom and pan, by column.
    pub domains: BTreeMap<String, [f64; 2]>,
    /// Hyperbolic tree view.
    pub focus: FocusView,
    /// Camera and iso value of a 3-D chart, as turned and moved.
    pub orbit: Orbit,
    /// An isosurface chart's surfaces, kept so a turn draws them without extracting them.
    pub surfaces: SurfaceCache,
    /// Lit and drawn rows (equal when nothing is selected).
    pub lit: (usize, usize),
    /// Bumped whenever `tiles` change.
    pub generation: u64,
    /// Count buffers of the large mark tiles, by tile index (relit by counting).
    counted: Vec<Option<CountedTile>>,
    /// The mask the count buffers show (`None`: every row lit).
    counted_mask: Option<Vec<bool>>,
}

impl ChartView {
    /// Whether a drag brushes this chart (it has plots or axes).
    pub fn brushable(&self) -> bool {
        !self.geometry.plots.is_empty() || !self.geometry.axes.is_empty()
    }
}

/// The explorer's state.
#[derive(Debug)]
pub struct Session {
    /// The spec, its tables and selections.
    pub loaded: Loaded,
    /// Every chart, in spec order.
    pub charts: Vec<ChartView>,
    /// The row set of every data source with a chart that draws a selection.
    pub sets: BTreeMap<String, RowSet>,
    /// Device pixels per canvas unit of the tiles.
    pub scale: f64,
    /// Span-space indexes of the volumes whose iso value was moved, by data source.
    indexes: BTreeMap<String, SpanSpace>,
}

/// Whether a chart kind draws a selection (`highlight`).
pub fn draws_selection(chart: &Chart) -> bool {
    crate::mark::technique(&chart.kind).info().draws_selection
}

impl Session {
    /// Draw every chart of `loaded` at `scale` device pixels per canvas unit. Each data source
    /// drawn by a selection-drawing chart gets a row set, starting from the spec selection its
    /// first such chart highlights, if any.
    pub fn new(loaded: Loaded, scale: f64) -> Session {
        let mut sets = BTreeMap::new();
        for chart in loaded.spec.chart.iter().filter(|c| draws_selection(c)) {
            let Some(table) = loaded.tables.get(&chart.data) else { continue };
            let spec = chart.highlight.as_ref().and_then(|h| loaded.highlights.get(h));
            let entry = sets.entry(chart.data.clone()).or_insert_with(|| RowSet::new(&chart.data, table.rows));
            if let (Some(h), false) = (spec, entry.is_active()) {
                *entry = RowSet::from_spec(&chart.data, &h.name, &h.selection, h.selected.clone());
            }
        }
        let charts = loaded
            .spec
            .chart
            .iter()
            .enumerate()
            .map(|(index, c)| ChartView {
                index,
                name: c.name.clone(),
                data: c.data.clone(),
                size: crate::mark::canvas_size(c),
                output: None,
                error: None,
                geometry: Geometry::default(),
                tiles: None,
                domains: BTreeMap::new(),
                focus: FocusView::default(),
                orbit: Orbit::default(),
                surfaces: SurfaceCache::default(),
                lit: (0, 0),
                generation: 0,
                counted: Vec::new(),
                counted_mask: None,
            })
            .collect();
        let mut session =
            Session { loaded, charts, sets, scale: if scale > 0.0 { scale } else { 1.0 }, indexes: BTreeMap::new() };
        let all: Vec<usize> = (0..session.charts.len()).collect();
        session.draw(&all);
        session
    }

    /// The table of a data source (empty if it is not loaded).
    pub fn table(&self, data: &str) -> &Table {
        static EMPTY: std::sync::OnceLock<Table> = std::sync::OnceLock::new();
        self.loaded.tables.get(data).unwrap_or_else(|| EMPTY.get_or_init(Table::default))
    }

    /// The lit rows of a data source; `None` when every row is lit.
    pub fn mask(&self, data: &str) -> Option<Vec<bool>> {
        self.sets.get(data).and_then(RowSet::mask)
    }

    /// Draw charts `which` again (after a view change), in parallel.
    pub fn draw(&mut self, which: &[usize]) {
        let masks: BTreeMap<String, Option<Vec<bool>>> = self.sets.iter().map(|(k, s)| (k.clone(), s.mask())).collect();
        let (loaded, scale, indexes) = (&self.loaded, self.scale, &self.indexes);
        let jobs: Vec<&mut ChartView> =
            self.charts.iter_mut().enumerate().filter(|(i, _)| which.contains(i)).map(|(_, v)| v).collect();
        jobs.into_par_iter().for_each(|v| {
            let mask = masks.get(&v.data).and_then(|m| m.as_deref());
            draw_view(loaded, indexes.get(&v.data), v, mask, scale);
        });
    }

    /// Relight every chart of data source `data` for its current row set.
    pub fn relight(&mut self, data: &str) {
        let mask = self.mask(data);
        let (loaded, scale) = (&self.loaded, self.scale);
        let jobs: Vec<&mut ChartView> = self.charts.iter_mut().filter(|v| v.data == data).collect();
        jobs.into_par_iter().for_each(|v| relight_view(loaded, v, mask.as_deref(), scale));
    }

    /// What a drag starting at `p` on chart `chart` would act on.
    pub fn target_at(&self, chart: usize, p: Point) -> Option<Target> {
        let v = self.charts.get(chart)?;
        if self.loaded.spec.chart.get(v.index).is_some_and(orbit::turns) {
            let inside = p.x >= 0.0 && p.y >= 0.0 && p.x <= v.size[0] && p.y <= v.size[1];
            return (inside && v.output.is_some()).then_some(Target::Scene);
        }
        if let Some(disk) = &v.geometry.disk {
            let d = disk.to_disk(p);
            return (d[0].hypot(d[1]) < 1.0).then_some(Target::Disk);
        }
        view::plot_at(&v.geometry, p).map(Target::Plot).or_else(|| view::axis_at(&v.geometry, p).map(Target::Axis))
    }

    /// The brush of a drag from `a` to `b` on `target` of chart `chart`.
    pub fn brush_for(&self, chart: usize, target: Target, a: Point, b: Point) -> Option<Brush> {
        let g = &self.charts.get(chart)?.geometry;
        match target {
            Target::Plot(i) => Some(brush::brush_in_plot(g.plots.get(i)?, a, b)),
            Target::Axis(i) => Some(brush::brush_on_axis(g.axes.get(i)?, a.y, b.y)),
            Target::Disk | Target::Scene => None,
        }
    }

    /// Show the brush of a drag from `a` to `b` live in every chart of the same data source.
    pub fn brush(&mut self, chart: usize, target: Target, a: Point, b: Point, mode: Mode) {
        let Some(brush) = self.brush_for(chart, target, a, b) else { return };
        let Some(data) = self.charts.get(chart).map(|v| v.data.clone()) else { return };
        let table = self.loaded.tables.get(&data);
        let (Some(set), Some(table)) = (self.sets.get_mut(&data), table) else { return };
        if set.preview(mode, brush, table).is_ok() {
            self.relight(&data);
        }
    }

    /// End the drag on chart `chart`: the live brush becomes part of the selection.
    pub fn end_brush(&mut self, chart: usize) {
        let Some(data) = self.charts.get(chart).map(|v| v.data.clone()) else { return };
        if let Some(set) = self.sets.get_mut(&data) {
            set.commit();
        }
        self.relight(&data);
    }

    /// Clear the selection of data source `data` (every row lit).
    pub fn clear(&mut self, data: &str) {
        if let Some(set) = self.sets.get_mut(data) {
            set.clear();
        }
        self.relight(data);
    }

    /// The brushed ranges to outline on chart `chart`, in canvas units.
    pub fn brush_rects(&self, chart: usize) -> Vec<(Mode, Rect)> {
        let Some(v) = self.charts.get(chart) else { return Vec::new() };
        let Some(set) = self.sets.get(&v.data) else { return Vec::new() };
        let mut out = Vec::new();
        for (mode, b) in set.brushes() {
            for plot in &v.geometry.plots {
                let r = plot.rect;
                let xs = plot.x.as_ref().and_then(|x| span(b, &x.field, &x.scale, (r.x, r.right())));
                let ys = plot.y.as_ref().and_then(|y| span(b, &y.field, &y.scale, (r.y, r.bottom())));
                if xs.is_none() && ys.is_none() {
                    continue;
                }
                let (x0, x1) = xs.unwrap_or((r.x, r.right()));
                let (y0, y1) = ys.unwrap_or((r.y, r.bottom()));
                out.push((mode, Rect::new(x0, y0, x1 - x0, y1 - y0)));
            }
            for axis in &v.geometry.axes {
                if let Some((y0, y1)) = span(b, &axis.field, &axis.scale, (axis.top, axis.bottom)) {
                    out.push((mode, Rect::new(axis.x - 6.0, y0, 12.0, y1 - y0)));
                }
            }
        }
        out
    }

    /// A line describing the mark under `p` on chart `chart`, if any.
    pub fn hover(&self, chart: usize, p: Point) -> Option<String> {
        let v = self.charts.get(chart)?;
        let table = self.table(&v.data);
        let fields = self.fields_of(v);
        if let Some(disk) = &v.geometry.disk {
            let n = view::node_at(disk, p, 2.0)?;
            let node = disk.nodes.get(n)?;
            return Some(match node.row {
                Some(r) => format!("{} · {}", node.label, view::describe(table, r, &fields)),
                None => node.label.clone(),
            });
        }
        let row = match view::plot_at(&v.geometry, p) {
            Some(i) => view::nearest_point(v.geometry.plots.get(i)?, table, p, HOVER_REACH),
            None if !v.geometry.axes.is_empty() => view::nearest_line(&v.geometry.axes, table, p, HOVER_REACH / 2.0),
            None => None,
        }?;
        Some(view::describe(table, row, &fields))
    }

    /// Columns to show when hovering a row of chart `v`: its positional columns, then the
    /// others its spec names.
    fn fields_of<'a>(&self, v: &'a ChartView) -> Vec<&'a str> {
        let mut out: Vec<&str> = Vec::new();
        for p in &v.geometry.plots {
            out.extend(p.scales().map(|s| s.field.as_str()));
        }
        out.extend(v.geometry.axes.iter().map(|a| a.field.as_str()));
        out
    }

    /// Whether zoom and pan act at `p` on chart `chart` (a plot or an axis is there).
    pub fn zoomable_at(&self, chart: usize, p: Point) -> bool {
        self.charts
            .get(chart)
            .is_some_and(|v| view::plot_at(&v.geometry, p).is_some() || view::axis_at(&v.geometry, p).is_some())
    }

    /// Zoom chart `chart` by `factor` (below 1 zooms in) about `p`: the plot's two columns, or
    /// the axis' column, get new domains and every chart view using them is redrawn.
    pub fn zoom(&mut self, chart: usize, p: Point, factor: f64) {
        let Some(v) = self.charts.get(chart) else { return };
        let mut changes = Vec::new();
        if let Some(plot) = view::plot_at(&v.geometry, p).and_then(|i| v.geometry.plots.get(i)) {
            for (s, at) in plot.x.iter().map(|s| (s, p.x)).chain(plot.y.iter().map(|s| (s, p.y))) {
                changes.extend(view::zoomed(&s.scale, at, factor).map(|d| (s.field.clone(), d)));
            }
        } else if let Some(axis) = view::axis_at(&v.geometry, p).and_then(|i| v.geometry.axes.get(i)) {
            changes.extend(view::zoomed(&axis.scale, p.y, factor).map(|d| (axis.field.clone(), d)));
        }
        self.set_domains(chart, changes);
    }

    /// Pan chart `chart` by a drag from `from` to `to`.
    pub fn pan(&mut self, chart: usize, from: Point, to: Point) {
        let Some(v) = self.charts.get(chart) else { return };
        let mut changes = Vec::new();
        if let Some(plot) = view::plot_at(&v.geometry, from).and_then(|i| v.geometry.plots.get(i)) {
            let moves = plot.x.iter().map(|s| (s, from.x, to.x)).chain(plot.y.iter().map(|s| (s, from.y, to.y)));
            for (s, a, b) in moves {
                changes.extend(view::panned(&s.scale, a, b).map(|d| (s.field.clone(), d)));
            }
        } else if let Some(axis) = view::axis_at(&v.geometry, from).and_then(|i| v.geometry.axes.get(i)) {
            changes.extend(view::panned(&axis.scale, from.y, to.y).map(|d| (axis.field.clone(), d)));
        }
        self.set_domains(chart, changes);
    }

    /// Give chart `chart` new column domains and redraw it.
    fn set_domains(&mut self, chart: usize, changes: Vec<(String, [f64; 2])>) {
        let Some(v) = self.charts.get_mut(chart) else { return };
        if changes.is_empty() {
            return;
        }
        v.domains.extend(changes);
        self.draw(&[chart]);
    }

    /// Undo zoom, pan and hyperbolic focus on chart `chart`.
    pub fn reset_view(&mut self, chart: usize) {
        let Some(v) = self.charts.get_mut(chart) else { return };
        v.domains.clear();
        v.focus.reset();
        v.orbit = Orbit::default();
        self.draw(&[chart]);
    }

    /// Drag a hyperbolic tree's view so that the point under `from` follows the pointer to `to`.
    pub fn hyper_drag(&mut self, chart: usize, from: Point, to: Point) {
        let Some(v) = self.charts.get_mut(chart) else { return };
        let Some(disk) = &v.geometry.disk else { return };
        let (a, b) = (disk.to_disk(from), disk.to_disk(to));
        v.focus.drag(a, b);
        self.draw(&[chart]);
    }

    /// Turn a 3-D chart's camera for a drag from `from` to `to`, drawing it as a quick preview
    /// (fewer rays for a volume rendering) until [`Session::end_turn`].
    pub fn turn(&mut self, chart: usize, from: Point, to: Point) {
        let Some(v) = self.charts.get_mut(chart) else { return };
        let Some(spec) = self.loaded.spec.chart.get(v.index).filter(|c| orbit::turns(c)) else { return };
        v.orbit.turn(spec, to.x - from.x, to.y - from.y);
        v.orbit.preview = true;
        self.draw(&[chart]);
    }

    /// End a turn: draw the chart at full resolution.
    pub fn end_turn(&mut self, chart: usize) {
        let Some(v) = self.charts.get_mut(chart) else { return };
        if std::mem::take(&mut v.orbit.preview) {
            self.draw(&[chart]);
        }
    }

    /// The value of an isosurface chart's first surface as drawn, and the range of its
    /// volume's values (what a slider moves it over); `None` for other charts.
    pub fn level(&self, chart: usize) -> Option<(f64, [f64; 2])> {
        let v = self.charts.get(chart)?;
        let spec = self.loaded.spec.chart.get(v.index)?;
        let level = v.orbit.level(spec)?;
        let (lo, hi) = self.loaded.volumes.get(&spec.data)?.range().0?;
        Some((level, [lo, hi]))
    }

    /// Where a one-plane slice chart's plane crosses its axis as drawn, the world range of the
    /// volume along that axis, and the axis (0, 1, 2 for x, y, z); `None` for other charts.
    pub fn plane(&self, chart: usize) -> Option<(f64, [f64; 2], usize)> {
        let v = self.charts.get(chart)?;
        let spec = self.loaded.spec.chart.get(v.index)?;
        let axis = orbit::sliding_axis(spec)?;
        let volume = self.loaded.volumes.get(&spec.data)?;
        let [nx, ny, nz] = volume.dims().map(|n| n.saturating_sub(1) as f64);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for c in 0..8 {
            let bit = |b: usize, n: f64| if c >> b & 1 == 1 { n } else { 0.0 };
            let w = volume.world(bit(0, nx), bit(1, ny), bit(2, nz))[axis];
            (lo, hi) = (lo.min(w), hi.max(w));
        }
        let name = ["point_x", "point_y", "point_z"][axis];
        let drawn = v.output.as_ref().and_then(|o| match o.derived.column(name) {
            Some(crate::mark::derived::DerivedColumn::Number(at)) => at.first().copied(),
            _ => None,
        });
        Some((v.orbit.plane.or(drawn).unwrap_or(0.5 * (lo + hi)), [lo, hi], axis))
    }

    /// Move a one-plane slice chart's plane to `at` along its axis and draw it again.
    pub fn set_plane(&mut self, chart: usize, at: f64) {
        let Some(v) = self.charts.get_mut(chart) else { return };
        if !at.is_finite() || self.loaded.spec.chart.get(v.index).and_then(orbit::sliding_axis).is_none() {
            return;
        }
        v.orbit.plane = Some(at);
        self.draw(&[chart]);
    }

    /// Move an isosurface chart's first surface to `value` and draw it again. The first move
    /// builds a span-space index of the chart's volume, which finds the cells of every later
    /// value without scanning them all.
    pub fn set_level(&mut self, chart: usize, value: f64) {
        let Some(v) = self.charts.get_mut(chart) else { return };
        if !value.is_finite() || self.loaded.spec.chart.get(v.index).is_none_or(|c| c.kind.name() != "isosurface") {
            return;
        }
        v.orbit.level = Some(value);
        if let Some(volume) = self.loaded.volumes.get(&v.data) {
            self.indexes.entry(v.data.clone()).or_insert_with(|| SpanSpace::build(volume));
        }
        self.draw(&[chart]);
    }

    /// Start bringing the node under `p` to the centre of a hyperbolic tree; returns whether a
    /// node was hit. `seconds` is the animation's length (0 for at once).
    pub fn hyper_focus(&mut self, chart: usize, p: Point, seconds: Option<f64>) -> bool {
        let Some(v) = self.charts.get_mut(chart) else { return false };
        let Some(disk) = &v.geometry.disk else { return false };
        let Some(node) = view::node_at(disk, p, 3.0).and_then(|n| disk.nodes.get(n)) else { return false };
        v.focus.focus(node.position, seconds.unwrap_or(FOCUS_SECONDS));
        self.draw(&[chart]);
        true
    }

    /// Advance running focus animations by `dt` seconds, redrawing their charts; returns whether
    /// any is still running.
    pub fn advance(&mut self, dt: f64) -> bool {
        let mut moving = Vec::new();
        let mut running = false;
        for (i, v) in self.charts.iter_mut().enumerate() {
            if v.focus.is_animating() {
                running |= v.focus.advance(dt);
                moving.push(i);
            }
        }
        if !moving.is_empty() {
            self.draw(&moving);
        }
        running
    }

    /// The name a data source's saved selection gets.
    pub fn selection_name(data: &str) -> String {
        format!("{data}-brush")
    }

    /// Write the selections as spec TOML (`DIR/selection.toml`) and charts `which` as drawn
    /// now (zoom, pan and focus kept) with the selection, as `DIR/NAME.svg` and `DIR/NAME.png`.
    /// Returns the files written.
    pub fn save(&self, dir: &Path, which: &[usize]) -> Result<Vec<PathBuf>, String> {
        std::fs::create_dir_all(dir).map_err(|e| format!("cannot create `{}`: {e}", dir.display()))?;
        let mut files = Vec::new();
        let mut toml = String::new();
        for (data, set) in &self.sets {
            if let Some(t) = set.to_toml(&Session::selection_name(data)) {
                toml.push_str(&t);
                toml.push('\n');
            }
        }
        if !toml.is_empty() {
            let names: Vec<String> = which
                .iter()
                .filter_map(|&i| self.charts.get(i))
                .filter(|v| self.sets.get(&v.data).is_some_and(RowSet::is_active))
                .map(|v| v.name.clone())
                .collect();
            let header = format!(
                "# Paste into the spec, and draw it on a chart with `highlight = \"NAME\"`{}.\n",
                if names.is_empty() { String::new() } else { format!(" (saved: {})", names.join(", ")) }
            );
            let path = dir.join("selection.toml");
            crate::output::write_file(&path, (header + &toml).as_bytes())
                .map_err(|e| format!("cannot write `{}`: {e}", path.display()))?;
            files.push(path);
        }
        for &i in which {
            let Some(v) = self.charts.get(i) else { continue };
            let Some(output) = self.saved_output(v) else { continue };
            let svg = dir.join(format!("{}.svg", v.name));
            crate::output::write_file(&svg, crate::render::to_svg(&output.scene).as_bytes())
                .map_err(|e| format!("cannot write `{}`: {e}", svg.display()))?;
            files.push(svg);
            let png = dir.join(format!("{}.png", v.name));
            let bytes = crate::render::to_png(&output.scene, self.scale).map_err(|e| format!("{}: {e}", v.name))?;
            crate::output::write_file(&png, &bytes).map_err(|e| format!("cannot write `{}`: {e}", png.display()))?;
            files.push(png);
        }
        Ok(files)
    }

    /// Chart `v` drawn for saving: its view, and its data source's selection as a highlight
    /// (with the brushed ranges when one brush makes it).
    pub fn saved_output(&self, v: &ChartView) -> Option<ChartOutput> {
        let chart = self.loaded.spec.chart.get(v.index)?;
        let table = table_of(&self.loaded, &chart.data)?;
        let chart = Orbit { preview: false, ..v.orbit }.apply(&view::with_domains(chart, &v.domains));
        let highlight = self.sets.get(&v.data).and_then(|set| {
            let mask = set.mask()?;
            let brushes = set.brushes();
            let selection = match brushes.as_slice() {
                [(Mode::Replace, b)] => b.selection(&v.data),
                _ => Brush::default().selection(&v.data),
            };
            Some(Highlight { name: Session::selection_name(&v.data), selection, selected: mask })
        });
        let highlight = highlight.filter(|_| draws_selection(&chart));
        let index = self.indexes.get(&v.data);
        crate::mark::draw_in(&view_context(&self.loaded, index, v, &chart, table).with_highlight(highlight.as_ref()))
            .ok()
    }
}

/// The pixel span of `b`'s range on column `field` under `scale`, clamped to `bounds`.
fn span(b: &Brush, field: &str, scale: &crate::guide::scale::Scale, bounds: (f64, f64)) -> Option<(f64, f64)> {
    let r = b.ranges.get(field)?;
    crate::mark::highlight::pixel_span((r[0], r[1]), |v| scale.map(v), bounds)
}

/// Table rows lit in one mask and not the other (`None`: every row lit).
fn changed_rows(before: Option<&[bool]>, after: Option<&[bool]>) -> Vec<u32> {
    let flag = |m: Option<&[bool]>, r: usize| m.is_none_or(|m| m.get(r).copied().unwrap_or(false));
    let n = before.map_or(0, <[bool]>::len).max(after.map_or(0, <[bool]>::len));
    (0..n).filter(|&r| flag(before, r) != flag(after, r)).map(|r| r as u32).collect()
}

/// Whether `item` is one of a splom diagonal's distributions (drawn again for a selection).
fn is_distribution(item: &Item) -> bool {
    item.role == crate::scene::Role::DataMark && !item.rows.is_empty() && matches!(item.shape, Shape::Path(_))
}

/// Chart view `v` bound to its table, node table and hyperbolic view.
/// The table of data source `data`: its own, or no rows for a volume (read from the context's
/// volume instead).
fn table_of<'a>(loaded: &'a Loaded, data: &str) -> Option<&'a Table> {
    static NO_ROWS: std::sync::OnceLock<Table> = std::sync::OnceLock::new();
    loaded.tables.get(data).or_else(|| loaded.volumes.contains_key(data).then(|| NO_ROWS.get_or_init(Table::default)))
}

fn view_context<'a>(
    loaded: &'a Loaded,
    index: Option<&'a SpanSpace>,
    v: &'a ChartView,
    chart: &Chart,
    table: &'a Table,
) -> ChartContext<'a> {
    ChartContext::new(chart, v.index, table)
        .with_nodes(crate::pipeline::node_table(loaded, chart))
        .with_view(Some(&v.focus.transform))
        .with_volume(loaded.volumes.get(&chart.data))
        .with_span_space(index)
        .with_surfaces(Some(&v.surfaces))
}

/// Draw chart view `v` for its view state and relight it for `mask`.
fn draw_view(loaded: &Loaded, index: Option<&SpanSpace>, v: &mut ChartView, mask: Option<&[bool]>, scale: f64) {
    let Some(chart) = loaded.spec.chart.get(v.index) else { return };
    let Some(table) = table_of(loaded, &chart.data) else {
        v.error = Some(format!("data \"{}\" was not loaded", chart.data));
        return;
    };
    let chart = v.orbit.apply(&view::with_domains(chart, &v.domains));
    let base = draws_selection(&chart).then(|| light::all_lit(&chart.data, table.rows));
    match crate::mark::draw_in(&view_context(loaded, index, v, &chart, table).with_highlight(base.as_ref())) {
        Ok(mut output) => {
            let geometry = std::mem::take(&mut output.geometry);
            let selectable = base.is_some();
            let diagonal = geometry.diagonals.is_some();
            let tiles = Tiles::new(&output.scene, scale, |i| {
                selectable && (light::is_marks(i) || light::is_count(i) || (diagonal && is_distribution(i)))
            });
            v.counted = (0..tiles.tiles.len())
                .into_par_iter()
                .map(|k| {
                    let (item, clip) = tiles.single_item(k).filter(|(i, _)| light::is_marks(i))?;
                    CountedTile::new(item, clip, tiles.tiles.get(k)?, scale)
                })
                .collect();
            v.tiles = Some(tiles);
            v.counted_mask = None;
            v.size = [output.scene.width, output.scene.height];
            v.output = Some(output);
            v.geometry = geometry;
            v.error = None;
            relight_view(loaded, v, mask, scale);
        }
        Err(e) => {
            v.error = Some(e.message);
            v.output = None;
            v.tiles = None;
            v.geometry = Geometry::default();
        }
    }
    v.generation += 1;
}

/// Relight chart view `v` for `mask`: split its mark tiles (charts whose marks carry rows), or
/// draw it again with the mask as its highlight (other selection-drawing kinds).
fn relight_view(loaded: &Loaded, v: &mut ChartView, mask: Option<&[bool]>, scale: f64) {
    if !loaded.spec.chart.get(v.index).is_some_and(draws_selection) {
        return;
    }
    let Some(tiles) = &mut v.tiles else { return };
    let first = tiles.dynamic_items().find(|i| light::is_marks(i)).map(|i| light::lit_of(i, mask));
    match first {
        Some((lit, drawn)) => {
            let counted: Vec<bool> = v.counted.iter().map(Option::is_some).collect();
            let exact = |k: usize| !counted.get(k).copied().unwrap_or(false);
            let table = loaded.tables.get(&v.data);
            let all;
            let selected = match mask {
                Some(m) => m,
                None => {
                    all = vec![true; table.map_or(0, |t| t.rows)];
                    &all
                }
            };
            let diagonals: Vec<Vec<Item>> = match (&v.geometry.diagonals, table) {
                (Some(d), Some(t)) => d.marks(t, light::LIT, selected),
                _ => Vec::new(),
            };
            let cell_at = |p: Point| v.geometry.diagonals.as_ref().and_then(|d| d.cell_at(p));
            tiles.redraw_dynamic_where(exact, |item| match &item.shape {
                Shape::Text(t) => vec![crate::scene::Item::text(item.role, light::count_text(t, lit, drawn))],
                Shape::Path(cmds) => {
                    // A splom diagonal: the grey distribution of all rows stands for the cell,
                    // drawn again with the selection; the coloured ones it replaces go.
                    let all_rows = item.label.as_deref().is_some_and(|l| l.ends_with("(all rows)"));
                    let at = cmds.iter().find_map(|c| match c {
                        crate::scene::PathCmd::MoveTo(p) => Some(*p),
                        _ => None,
                    });
                    match (all_rows, at.and_then(cell_at)) {
                        (true, Some(c)) => diagonals.get(c).cloned().unwrap_or_default(),
                        _ => Vec::new(),
                    }
                }
                _ => light::split(item, mask),
            });
            let changed = changed_rows(v.counted_mask.as_deref(), mask);
            tiles.tiles.par_iter_mut().zip(v.counted.par_iter_mut()).for_each(|(t, c)| {
                if let Some(c) = c {
                    c.update_rows(mask, Some(&changed), t);
                }
            });
            v.counted_mask = mask.map(<[bool]>::to_vec);
            v.lit = (lit, drawn);
        }
        None => {
            let Some(chart) = loaded.spec.chart.get(v.index).filter(|c| draws_selection(c)) else { return };
            let Some(table) = loaded.tables.get(&chart.data) else { return };
            let chart = view::with_domains(chart, &v.domains);
            let selected = mask.map_or_else(|| vec![true; table.rows], <[bool]>::to_vec);
            let lit = selected.iter().filter(|&&s| s).count();
            let h = Highlight { selected, ..light::all_lit(&chart.data, table.rows) };
            if let Ok(output) = crate::mark::draw(&chart, v.index, table, Some(&h)) {
                *tiles = Tiles::new(&output.scene, scale, |_| false);
                v.output = Some(output);
            }
            v.lit = (lit, table.rows);
        }
    }
    v.generation += 1;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::PathPolicy;

    /// A spec with a scatter, a splom and parallel coordinates over one inline table.
    fn session() -> Session {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("spec.toml");
        let rows: Vec<String> = (0..40)
            .map(|i| {
                let (a, b, c) = (i as f64, ((i * 7) % 40) as f64, ((i * 13) % 40) as f64);
                format!("{{ a = {a}, b = {b}, c = {c}, k = \"{}\" }}", if i % 2 == 0 { "even" } else { "odd" })
            })
            .collect();
        let spec = format!(
            "[data.t]\nvalues = [{}]\n\n[[chart]]\nname = \"s\"\nkind = \"scatter\"\ndata = \"t\"\nx = \"a\"\ny = \"b\"\ncolor = \"k\"\n\n[[chart]]\nname = \"m\"\nkind = \"splom\"\ndata = \"t\"\ncolumns = [\"a\", \"b\", \"c\"]\n\n[[chart]]\nname = \"p\"\nkind = \"parallel\"\ndata = \"t\"\ncolumns = [\"a\", \"b\", \"c\"]\n",
            rows.join(", ")
        );
        std::fs::write(&path, spec).unwrap();
        let loaded = crate::pipeline::load(&path, PathPolicy::InsideSpecFolder).unwrap();
        Session::new(loaded, 1.0)
    }

    #[test]
    fn a_brush_in_one_chart_lights_the_same_rows_everywhere() {
        let mut s = session();
        assert!(s.charts.iter().all(|v| v.error.is_none() && v.lit == (40, 40)), "{:?}", s.charts[0].error);
        let plot = s.charts[0].geometry.plots[0].clone();
        // a in [5, 35] and b in [0, 30]: rows 5..=35 whose b = 7i mod 40 is at most 30.
        let (x0, x1) = (plot.x.as_ref().unwrap().scale.map(5.0), plot.x.as_ref().unwrap().scale.map(35.0));
        let (y0, y1) = (plot.y.as_ref().unwrap().scale.map(0.0), plot.y.as_ref().unwrap().scale.map(30.0));
        s.brush(0, Target::Plot(0), Point::new(x0, y0), Point::new(x1, y1), Mode::Replace);
        s.end_brush(0);
        let expected: Vec<bool> = (0..40).map(|i| (5..=35).contains(&i) && (i * 7) % 40 <= 30).collect();
        let want = expected.iter().filter(|&&e| e).count();
        // Two digits, like the 40 the layout was made for: the legend keeps its width.
        assert!(want >= 10, "{want}");
        assert_eq!(s.mask("t"), Some(expected));
        for v in &s.charts {
            assert_eq!(v.lit, (want, 40), "chart {}", v.name);
        }
        // The relit tiles equal the chart drawn with the selection as its highlight (one
        // without ranges: the window outlines brushes itself instead of drawing bands). The
        // window keeps the layout made for "N of N rows", so a count of other width would
        // shift the legend column by a few pixels in a saved file.
        // Both the splom (its diagonal histograms too) and the parallel coordinates.
        for k in [1, 2] {
            let mask = s.mask("t").unwrap();
            let h = Highlight { selected: mask, ..light::all_lit("t", 40) };
            let chart = &s.loaded.spec.chart[k];
            let direct = crate::mark::draw(chart, k, s.table("t"), Some(&h)).unwrap();
            let png = crate::render::to_pixmap(&direct.scene, 1.0).unwrap();
            let (_, _, window) = s.charts[k].tiles.as_ref().unwrap().composite();
            let worst = window.iter().zip(png.data()).map(|(a, b)| a.abs_diff(*b)).max().unwrap();
            // Overlapping translucent marks blended on a transparent tile and then over the
            // background round differently from blending straight onto it: a few levels at most.
            assert!(worst <= 6, "relit chart {k} differs from the drawn chart by {worst}");
        }
        s.clear("t");
        assert!(s.charts.iter().all(|v| v.lit == (40, 40)));
    }

    #[test]
    fn large_batches_relit_by_counting_look_like_the_exact_drawing() {
        let dir = tempfile::tempdir().unwrap();
        let mut csv = String::from("a,b,c,k\n");
        for i in 0..24_000u64 {
            let h = |k: u64| ((i.wrapping_mul(2_654_435_761).wrapping_add(k * 40_503)) % 1000) as f64 / 100.0;
            csv.push_str(&format!(
                "{},{},{},{}\n",
                h(1),
                h(2) * 0.5 + h(1) * 0.5,
                h(3),
                if i % 2 == 0 { "x" } else { "y" }
            ));
        }
        std::fs::write(dir.path().join("t.csv"), csv).unwrap();
        let spec = "[data.t]\npath = \"t.csv\"\n\n[[chart]]\nname = \"p\"\nkind = \"parallel\"\ndata = \"t\"\ncolumns = [\"a\", \"b\", \"c\"]\ncolor = \"k\"\n";
        std::fs::write(dir.path().join("spec.toml"), spec).unwrap();
        let loaded = crate::pipeline::load(&dir.path().join("spec.toml"), PathPolicy::InsideSpecFolder).unwrap();
        let mut s = Session::new(loaded, 1.0);
        assert!(s.charts[0].counted.iter().flatten().count() == 1, "the line batch is counted");
        let (_, _, before) = s.charts[0].tiles.as_ref().unwrap().composite();
        let axis = s.charts[0].geometry.axes[0].clone();
        let (y0, y1) = (axis.scale.map(6.0), axis.scale.map(2.0));
        s.brush(0, Target::Axis(0), Point::new(axis.x, y0), Point::new(axis.x, y1), Mode::Replace);
        s.end_brush(0);
        let mask = s.mask("t").unwrap();
        let lit = mask.iter().filter(|&&m| m).count();
        assert!(lit > 6_000 && lit < 12_000, "{lit}");
        assert_eq!(s.charts[0].lit, (lit, 24_000));
        let h = Highlight { selected: mask, ..light::all_lit("t", 24_000) };
        let direct = crate::mark::draw(&s.loaded.spec.chart[0], 0, s.table("t"), Some(&h)).unwrap();
        let png = crate::render::to_pixmap(&direct.scene, 1.0).unwrap();
        let (_, _, window) = s.charts[0].tiles.as_ref().unwrap().composite();
        let mean =
            window.iter().zip(png.data()).map(|(a, b)| f64::from(a.abs_diff(*b))).sum::<f64>() / window.len() as f64;
        // Same picture; the counted lines are not anti-aliased and mix overlapping colours, so
        // pixels differ a little (relighting without the selection would be ~20 levels off).
        assert!(mean < 8.0, "counted relight is {mean} levels from the exact drawing on average");
        // Clearing brings back the exact pixels of the chart with every row lit.
        s.clear("t");
        let (_, _, cleared) = s.charts[0].tiles.as_ref().unwrap().composite();
        assert!(cleared == before, "the pixels before the brush come back");
    }

    #[test]
    fn zoom_pan_and_reset_change_the_domains() {
        let mut s = session();
        let plot = s.charts[0].geometry.plots[0].clone();
        let c = Point::new(plot.rect.x + plot.rect.w / 2.0, plot.rect.y + plot.rect.h / 2.0);
        let before = plot.x.as_ref().unwrap().scale.domain();
        s.zoom(0, c, 0.5);
        let after = s.charts[0].geometry.plots[0].x.as_ref().unwrap().scale.domain();
        assert!((after.1 - after.0) < 0.6 * (before.1 - before.0), "{before:?} → {after:?}");
        s.pan(0, c, Point::new(c.x + 20.0, c.y));
        assert!(s.charts[0].geometry.plots[0].x.as_ref().unwrap().scale.domain().0 < after.0);
        s.reset_view(0);
        assert_eq!(s.charts[0].geometry.plots[0].x.as_ref().unwrap().scale.domain(), before);
        assert!(s.hover(0, Point::new(-5.0, -5.0)).is_none());
    }
}
