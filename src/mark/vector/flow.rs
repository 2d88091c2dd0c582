//! `flow`: a 2-D vector field drawn as layers over one cartesian frame: speed as an image, line
//! integral convolution, arrows with a key, streamlines with direction marks, particle traces of
//! unsteady fields (pathlines, streaklines, timelines) and vector field topology (critical
//! points by the Jacobian's eigenvalues, separatrices, boundary switch points). The numerics live
//! in [`crate::enrich::flow`].

use std::sync::Arc;

use crate::data::{Column, Table};
use crate::enrich::flow::budget::{self, StepBudget};
use crate::enrich::flow::field::VectorField;
use crate::enrich::flow::integrate::Integrator;
use crate::enrich::flow::lic::{LicOptions, lic};
use crate::enrich::flow::seeding::{EvenlySpacedOptions, circle, evenly_spaced, grid_seeds, rake};
use crate::enrich::flow::streamline::{Direction, Streamline, StreamlineOptions, pathline, trace_within};
use crate::enrich::flow::topology::{CriticalKind, SwitchKind, boundary_points, critical_points, separatrices};
use crate::guide::axis::title_with_unit;
use crate::guide::color::ContinuousMap;
use crate::guide::format::format_value;
use crate::guide::layout::{Domain, Frame};
use crate::guide::legend::{Legend, Symbol};
use crate::guide::ticks::extended;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::gridded::grid_from_rows;
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Raster, Rect, Role, Shape, Stroke, Style, Text};
use crate::spec::{Channel, Chart, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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

/// Largest raster side for the speed image and LIC, in pixels.
const MAX_RASTER: usize = 2048;
/// Colour of streamlines.
const STREAMLINE: Color = Color::rgb(0x1a, 0x1a, 0x1a);
/// Colours of particle traces.
const PATHLINE: Color = Color::rgb(0xd5, 0x5e, 0x00);
const STREAKLINE: Color = Color::rgb(0x00, 0x72, 0xb2);
const TIMELINE: Color = Color::rgb(0x00, 0x9e, 0x73);
/// Colour of separatrices.
const SEPARATRIX: Color = Color::rgb(0xcc, 0x24, 0x24);
/// Particles released per seed for a streakline.
const STREAK_RELEASES: usize = 160;
/// Times at which a timeline is drawn.
const TIMELINE_STEPS: usize = 4;
/// `|Re λ| ≤ this × |Im λ|` counts as a centre.
const CENTRE_TOLERANCE: f64 = 1e-3;

/// Draw a flow chart.
pub fn draw(chart: &Chart, options: &FlowOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let (x_opts, y_opts) = (options.x.options(), options.y.options());
    let input = read_field(chart, options, table)?;
    let field = &input.field;
    let layers = options.layers.clone().unwrap_or_else(|| vec![FlowLayer::Speed, FlowLayer::Streamlines]);
    let has = |l: FlowLayer| layers.contains(&l);
    let unsteady = field.ts().len() > 1;
    for l in [FlowLayer::Pathlines, FlowLayer::Streaklines, FlowLayer::Timelines] {
        if has(l) && options.t.is_none() {
            return Err(MarkError::at(
                &["layers"],
                format!("particle traces need an unsteady field"),
                "name the time column with `t`, or draw `streamlines` of a steady field",
            ));
        }
    }
    let snapshot = snapshot(field, options.time).map_err(|e| field_error(&e))?;
    let speed_map = encode::continuous_map(&["scheme"], options.scheme.as_deref())?;
    let max_speed = snapshot.max_speed();
    let speed_title = title_with_unit("speed", options.unit.as_deref());
    let mut legends = Vec::new();
    if has(FlowLayer::Speed) || (has(FlowLayer::Arrows) && !has(FlowLayer::Lic)) {
        legends.push(Legend::ColorBar {
            title: speed_title.clone(),
            map: speed_map.clone(),
            domain: (0.0, max_speed.max(1e-300)),
        });
    }
    let budget = StepBudget::default();
    let topology = has(FlowLayer::Topology).then(|| Topology::find(&snapshot, &budget));
    if let Some(t) = &topology {
        legends.extend(t.legend());
    }
    let traces_legend: Vec<(String, Color)> = [
        (FlowLayer::Pathlines, "pathlines", PATHLINE),
        (FlowLayer::Streaklines, "streaklines", STREAKLINE),
        (FlowLayer::Timelines, "timelines", TIMELINE),
    ]
    .iter()
    .filter(|(l, _, _)| has(*l))
    .map(|(_, name, c)| (name.to_string(), *c))
    .collect();
    if !traces_legend.is_empty() {
        legends.push(Legend::Categorical { title: "traces".into(), entries: traces_legend, symbol: Symbol::Line });
    }

    let [x0, x1, y0, y1] = field.bounds();
    let mut x_axis = encode::position_axis("x", &x_opts, input.x_col, &input.rows)?;
    let mut y_axis = encode::position_axis("y", &y_opts, input.y_col, &input.rows)?;
    for (axis, lo, hi) in [(&mut x_axis, x0, x1), (&mut y_axis, y0, y1)] {
        axis.nice = false;
        axis.grid = false;
        axis.domain = Domain::Continuous(lo, hi);
    }
    let mut chart = chart.clone();
    chart.caption.get_or_insert_with(|| caption(options, &layers, field, options.time));
    let chart = &chart;
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, legends)?;
    let to_px = |p: [f64; 2]| Point::new(frame.x.map(p[0]), frame.y.map(p[1]));

    let mut marks = Vec::new();
    let mut derived = Traces::default();
    if has(FlowLayer::Speed) || has(FlowLayer::Lic) {
        let raster = speed_raster(&snapshot, &frame, &speed_map, has(FlowLayer::Speed), has(FlowLayer::Lic))
            .map_err(|e| MarkError::at(&["layers"], format!("{e}"), ""))?;
        marks.push(Item::new(Role::DataMark, Shape::Image(raster), Style::default()).with_rows(input.rows.clone()));
    }
    let density = options.density.unwrap_or(1.0);
    let on_raster = has(FlowLayer::Speed) || has(FlowLayer::Lic);
    if has(FlowLayer::Arrows) {
        let color = (!on_raster).then_some(&speed_map);
        let (items, placed) = arrows(&snapshot, &frame, density, color, max_speed);
        marks.extend(items);
        for (i, (p, speed)) in placed.into_iter().enumerate() {
            derived.push("arrow", i, p, speed, "", [f64::NAN; 4]);
        }
    }
    let mut trace_options = StreamlineOptions::for_field(field);
    trace_options.integrator = integrator(options.integrator);
    if has(FlowLayer::Streamlines) {
        let lines = streamlines(options, &snapshot, &trace_options, density, &budget)?;
        for line in &lines {
            marks.extend(polyline(&line.points, &to_px, STREAMLINE.with_opacity(0.85), 0.9));
            marks.extend(direction_mark(line, &to_px, STREAMLINE));
        }
        derived.add("streamline", &lines);
    }
    if unsteady {
        let seeds = trace_seeds(options, field, density)?;
        let end = options.time.unwrap_or(field.ts().last().copied().unwrap_or(0.0));
        let start = field.ts().first().copied().unwrap_or(0.0);
        let mut path_options = trace_options;
        path_options.direction = Direction::Forward;
        path_options.step = (end - start).abs() / 400.0;
        path_options.max_length = end - start;
        if has(FlowLayer::Pathlines) {
            let lines: Vec<Streamline> =
                seeds.iter().map(|&s| pathline(field, s, start, &path_options, &budget)).collect();
            for line in &lines {
                marks.extend(polyline(&line.points, &to_px, PATHLINE, 1.2));
            }
            derived.add("pathline", &lines);
        }
        if has(FlowLayer::Streaklines) {
            let lines = streaklines(field, &seeds, (start, end), &path_options, &budget);
            for line in &lines {
                marks.extend(polyline(line, &to_px, STREAKLINE, 1.4));
            }
            derived.add_points("streakline", &lines);
        }
        if has(FlowLayer::Timelines) {
            let lines = timelines(field, &seeds, (start, end), &path_options, &budget);
            for line in &lines {
                marks.extend(polyline(line, &to_px, TIMELINE, 1.4));
            }
            derived.add_points("timeline", &lines);
        }
    }
    if let Some(t) = &topology {
        marks.extend(t.draw(&to_px));
        derived.add("separatrix", &t.separatrices);
        derived.add_critical(t);
    }
    if has(FlowLayer::Arrows) {
        marks.extend(arrow_key(&frame, &theme, density, max_speed, options.unit.as_deref()));
    }
    let mut warnings = input.warnings;
    warnings.extend((budget.exhausted().then(|| budget_warning())).into_iter().map(Warning::from));
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);
    Ok(ChartOutput {
        scene,
        derived: derived.finish(),
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// The warning of a chart whose streamlines or separatrices stopped at the per-chart budget.
fn budget_warning() -> String {
    format!(
        "streamlines or particle traces stopped at the per-chart limit ({} integration steps, {} seeding \
         attempts, {} points examined for spacing); the lines traced so far are drawn. Resample the \
         field to a regular grid without tiny cells, lower `density`, or give fewer `seed_count` seeds",
        budget::MAX_STEPS,
        budget::MAX_SEED_ATTEMPTS,
        budget::MAX_EXAMINED
    )
}

/// The field read from the table, with the rows and columns the axes need.
struct FieldInput<'t> {
    field: VectorField,
    rows: Vec<u32>,
    x_col: &'t Column,
    y_col: &'t Column,
    warnings: Vec<Warning>,
}

fn field_error(e: &dyn std::fmt::Display) -> MarkError {
    MarkError::at(&["x"], format!("{e}"), "check the grid's coordinates and components")
}

/// Read the long-form table into a (steady or unsteady) vector field.
fn read_field<'t>(chart: &Chart, options: &FlowOptions, table: &'t Table) -> Result<FieldInput<'t>, MarkError> {
    let (x_opts, y_opts) = (options.x.options(), options.y.options());
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    let u_col = encode::column(chart, "u", &options.u, table)?;
    let v_col = encode::column(chart, "v", &options.v, table)?;
    let t_col = options.t.as_deref().map(|t| encode::column(chart, "t", t, table)).transpose()?;
    let mut numeric = vec![("x", x_opts.field.as_str(), x_col), ("y", y_opts.field.as_str(), y_col)];
    numeric.extend([("u", options.u.as_str(), u_col), ("v", options.v.as_str(), v_col)]);
    if let (Some(t), Some(col)) = (options.t.as_deref(), t_col) {
        numeric.push(("t", t, col));
    }
    for (key, field, col) in &numeric {
        encode::require_numeric(key, col, "a vector field", &format!("`{field}` must hold numbers"))?;
    }
    let mut placed = vec![(x_opts.field.as_str(), x_col), (y_opts.field.as_str(), y_col)];
    if let (Some(t), Some(col)) = (options.t.as_deref(), t_col) {
        placed.push((t, col));
    }
    let (rows, warning) = encode::finite_rows(&chart.name, table.rows, &placed);
    if rows.is_empty() {
        return Err(encode::no_rows(chart, table, warning.as_ref()));
    }
    let field = match t_col.and_then(Column::numbers) {
        None => {
            let u = grid_from_rows(x_col, y_col, u_col, &rows)?;
            let v = grid_from_rows(x_col, y_col, v_col, &rows)?;
            VectorField::new(u.xs().to_vec(), u.ys().to_vec(), u.values().to_vec(), v.values().to_vec())
        }
        Some(times) => {
            let mut ts: Vec<f64> = rows.iter().map(|&r| times[r as usize]).collect();
            ts.sort_by(f64::total_cmp);
            ts.dedup();
            let mut frames = Vec::with_capacity(ts.len());
            let mut axes: Option<(Vec<f64>, Vec<f64>)> = None;
            for &t in &ts {
                let at: Vec<u32> = rows.iter().copied().filter(|&r| times[r as usize] == t).collect();
                let u = grid_from_rows(x_col, y_col, u_col, &at)?;
                let v = grid_from_rows(x_col, y_col, v_col, &at)?;
                match &axes {
                    None => axes = Some((u.xs().to_vec(), u.ys().to_vec())),
                    Some((xs, ys)) if xs.as_slice() != u.xs() || ys.as_slice() != u.ys() => {
                        return Err(MarkError::at(
                            &["t"],
                            format!("the grid at t = {t} differs from the first time's grid"),
                            "every time needs the same x and y nodes",
                        ));
                    }
                    _ => {}
                }
                frames.push((u.values().to_vec(), v.values().to_vec()));
            }
            let (xs, ys) = axes.unwrap_or_default();
            VectorField::unsteady(xs, ys, ts, frames)
        }
    }
    .map_err(|e| field_error(&e))?;
    Ok(FieldInput { field, rows, x_col, y_col, warnings: warning.into_iter().collect() })
}

/// The steady field at `time` (linear between frames), or the first frame.
fn snapshot(field: &VectorField, time: Option<f64>) -> Result<VectorField, crate::enrich::flow::field::FieldError> {
    let (xs, ys) = (field.xs().to_vec(), field.ys().to_vec());
    let t = time.unwrap_or_else(|| field.ts().first().copied().unwrap_or(0.0));
    if field.ts().len() <= 1 {
        let (u, v) = (field.u(0).unwrap_or(&[]).to_vec(), field.v(0).unwrap_or(&[]).to_vec());
        return VectorField::new(xs, ys, u, v);
    }
    VectorField::from_fn(xs, ys, |x, y| field.velocity_at(x, y, t).unwrap_or([f64::NAN, f64::NAN]))
}

fn integrator(kind: Option<IntegratorKind>) -> Integrator {
    match kind.unwrap_or(IntegratorKind::Rk4) {
        IntegratorKind::Euler => Integrator::Euler,
        IntegratorKind::Rk2 => Integrator::Rk2,
        IntegratorKind::Rk4 => Integrator::Rk4,
        IntegratorKind::Rk45 => Integrator::Rk45,
    }
}

/// The default caption: the layers and how they were made.
fn caption(options: &FlowOptions, layers: &[FlowLayer], field: &VectorField, time: Option<f64>) -> String {
    let mut parts = vec![format!("{} × {} grid", field.nx(), field.ny())];
    if field.ts().len() > 1 {
        let (a, b) = (field.ts().first().copied().unwrap_or(0.0), field.ts().last().copied().unwrap_or(0.0));
        parts.push(format!("{} times from {} to {}", field.ts().len(), format_value(a), format_value(b)));
        parts.push(format!("snapshot at t = {}", format_value(time.unwrap_or(a))));
    }
    let traced = layers.iter().any(|l| !matches!(l, FlowLayer::Speed | FlowLayer::Lic | FlowLayer::Arrows));
    if traced {
        let name = match options.integrator.unwrap_or(IntegratorKind::Rk4) {
            IntegratorKind::Euler => "Euler",
            IntegratorKind::Rk2 => "RK2",
            IntegratorKind::Rk4 => "RK4",
            IntegratorKind::Rk45 => "adaptive RK45",
        };
        parts.push(format!("traces integrated with {name}"));
    }
    if layers.contains(&FlowLayer::Lic) {
        parts.push("texture: line integral convolution of white noise".into());
    }
    let mut text = parts.join("; ");
    text.push('.');
    text
}

/// Speed colours, LIC greys, or speed colours shaded by the LIC texture, over the plot's pixels.
fn speed_raster(
    field: &VectorField,
    frame: &Frame,
    map: &ContinuousMap,
    speed: bool,
    texture: bool,
) -> Result<Raster, String> {
    let plot = frame.plot;
    let width = (plot.w.round().max(1.0) as usize).min(MAX_RASTER);
    let height = (plot.h.round().max(1.0) as usize).min(MAX_RASTER);
    let noise =
        if texture { Some(lic(field, &LicOptions::new(width, height)).map_err(|e| e.to_string())?) } else { None };
    let max = field.max_speed().max(1e-300);
    let xs: Vec<f64> = (0..width)
        .map(|col| frame.x.invert(plot.x + plot.w * (col as f64 + 0.5) / width as f64).unwrap_or(f64::NAN))
        .collect();
    let mut rgba = vec![0u8; width * height * 4];
    for row in 0..height {
        let y = frame.y.invert(plot.y + plot.h * (row as f64 + 0.5) / height as f64).unwrap_or(f64::NAN);
        for (col, &x) in xs.iter().enumerate() {
            // LIC rows run from the smallest y up.
            let shade = noise.as_ref().map(|n| n.data[(height - 1 - row) * width + col] as f64);
            let color = match (field.speed(x, y), shade) {
                (None, _) => Color::rgb(0xd9, 0xd9, 0xd9),
                (Some(_), Some(s)) if s.is_nan() => Color::rgb(0xd9, 0xd9, 0xd9),
                (Some(v), Some(s)) if speed => {
                    let c = map.at(v / max);
                    let k = 0.35 + 0.65 * s;
                    Color::rgb((c.r as f64 * k) as u8, (c.g as f64 * k) as u8, (c.b as f64 * k) as u8)
                }
                (Some(_), Some(s)) => {
                    let g = (30.0 + 225.0 * s) as u8;
                    Color::rgb(g, g, g)
                }
                (Some(v), None) => map.at(v / max),
            };
            let k = (row * width + col) * 4;
            rgba[k..k + 4].copy_from_slice(&[color.r, color.g, color.b, 255]);
        }
    }
    Ok(Raster { dest: plot, width: width as u32, height: height as u32, rgba: Arc::new(rgba), smooth: false })
}

/// Streamlines from the chosen seeds.
fn streamlines(
    options: &FlowOptions,
    field: &VectorField,
    trace_options: &StreamlineOptions,
    density: f64,
    budget: &StepBudget,
) -> Result<Vec<Streamline>, MarkError> {
    let [x0, x1, ..] = field.bounds();
    if options.seeds.unwrap_or(SeedKind::Evenly) == SeedKind::Evenly {
        let mut evenly = EvenlySpacedOptions::new(field, (x1 - x0) / (30.0 * density));
        evenly.streamline.integrator = trace_options.integrator;
        return Ok(evenly_spaced(field, &evenly, budget));
    }
    let seeds = trace_seeds(options, field, density)?;
    Ok(seeds.iter().map(|&s| trace_within(field, s, trace_options, budget)).filter(|l| l.points.len() > 1).collect())
}

/// Seeds of traces: a rake, a circle or a grid (the grid also stands in for `evenly`).
fn trace_seeds(options: &FlowOptions, field: &VectorField, density: f64) -> Result<Vec<[f64; 2]>, MarkError> {
    let count = options.seed_count.unwrap_or(12) as usize;
    let missing = |key: &str, example: &str| {
        MarkError::at(&["seeds"], format!("`seeds = \"{key}\"` needs `{key}`"), format!("add e.g. `{key} = {example}`"))
    };
    Ok(match options.seeds.unwrap_or(SeedKind::Evenly) {
        SeedKind::Rake => {
            let [a, b] = options.rake.ok_or_else(|| missing("rake", "[[0.1, 0.1], [0.1, 0.9]]"))?;
            rake(a, b, count)
        }
        SeedKind::Circle => {
            let [cx, cy, r] = options.circle.ok_or_else(|| missing("circle", "[0.5, 0.5, 0.2]"))?;
            circle([cx, cy], r, count)
        }
        SeedKind::Grid | SeedKind::Evenly => {
            let [x0, x1, y0, y1] = field.bounds();
            let n = (12.0 * density).round().max(2.0) as usize;
            let ny = ((n as f64) * (y1 - y0) / (x1 - x0)).round().clamp(2.0, 400.0) as usize;
            grid_seeds(field.bounds(), n.min(400), ny)
        }
    })
}

/// Where particles released at `seed` at evenly spaced times up to `end` are at `end`, youngest
/// first. The line is broken where a particle has left the domain or where neighbours are
/// further apart than a twentieth of the domain (the release spacing cannot resolve it there).
fn streaklines(
    field: &VectorField,
    seeds: &[[f64; 2]],
    (start, end): (f64, f64),
    options: &StreamlineOptions,
    budget: &StepBudget,
) -> Vec<Vec<[f64; 2]>> {
    let [x0, x1, y0, y1] = field.bounds();
    let gap = ((x1 - x0).hypot(y1 - y0)) / 20.0;
    let mut out = Vec::new();
    for &seed in seeds {
        let mut piece: Vec<[f64; 2]> = Vec::new();
        for k in (0..=STREAK_RELEASES).rev() {
            let release = start + (end - start) * k as f64 / STREAK_RELEASES as f64;
            let at = position_at(field, seed, (release, end), options, budget);
            let far = match (at, piece.last()) {
                (Some(p), Some(q)) => (p[0] - q[0]).hypot(p[1] - q[1]) > gap,
                _ => false,
            };
            if at.is_none() || far {
                if piece.len() > 1 {
                    out.push(std::mem::take(&mut piece));
                }
                piece.clear();
            }
            piece.extend(at);
        }
        if piece.len() > 1 {
            out.push(piece);
        }
    }
    out
}

/// The line through all seeds' particles, released together at `start`, at a few times.
fn timelines(
    field: &VectorField,
    seeds: &[[f64; 2]],
    (start, end): (f64, f64),
    options: &StreamlineOptions,
    budget: &StepBudget,
) -> Vec<Vec<[f64; 2]>> {
    (0..=TIMELINE_STEPS)
        .map(|m| {
            let t = start + (end - start) * m as f64 / TIMELINE_STEPS as f64;
            seeds.iter().filter_map(|&s| position_at(field, s, (start, t), options, budget)).collect::<Vec<_>>()
        })
        .filter(|l| l.len() > 1)
        .collect()
}

/// The position at time `t` of the particle released at `seed` at `release` (None when it left
/// the domain before then).
fn position_at(
    field: &VectorField,
    seed: [f64; 2],
    (release, t): (f64, f64),
    options: &StreamlineOptions,
    budget: &StepBudget,
) -> Option<[f64; 2]> {
    if t <= release {
        return field.contains(seed[0], seed[1]).then_some(seed);
    }
    let options = StreamlineOptions { max_length: t - release, ..*options };
    let line = pathline(field, seed, release, &options, budget);
    let (&last, &time) = (line.points.last()?, line.params.last()?);
    (time >= t - 1e-9 * (t - release).abs().max(1.0)).then_some(last)
}

fn polyline(points: &[[f64; 2]], to_px: &impl Fn([f64; 2]) -> Point, color: Color, width: f64) -> Option<Item> {
    if points.len() < 2 {
        return None;
    }
    let cmds = points
        .iter()
        .enumerate()
        .map(|(i, &p)| if i == 0 { PathCmd::MoveTo(to_px(p)) } else { PathCmd::LineTo(to_px(p)) })
        .collect();
    Some(Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(color, width)))
}

/// A small arrowhead halfway along a streamline, pointing downstream.
fn direction_mark(line: &Streamline, to_px: &impl Fn([f64; 2]) -> Point, color: Color) -> Option<Item> {
    let px: Vec<Point> = line.points.iter().map(|&p| to_px(p)).collect();
    let lengths: Vec<f64> = px.windows(2).map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y)).collect();
    let total: f64 = lengths.iter().sum();
    if total < 24.0 {
        return None;
    }
    let mut walked = 0.0;
    let k = lengths.iter().position(|l| {
        walked += l;
        walked >= total / 2.0
    })?;
    let (a, b) = (px[k], px[k + 1]);
    let len = (b.x - a.x).hypot(b.y - a.y).max(1e-9);
    let (ux, uy) = ((b.x - a.x) / len, (b.y - a.y) / len);
    Some(triangle(Point::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0), ux, uy, 6.0, color))
}

/// A filled arrowhead with its tip at `tip + size/2` along (ux, uy).
fn triangle(at: Point, ux: f64, uy: f64, size: f64, color: Color) -> Item {
    let tip = Point::new(at.x + ux * size / 2.0, at.y + uy * size / 2.0);
    let base = Point::new(at.x - ux * size / 2.0, at.y - uy * size / 2.0);
    let half = size * 0.42;
    let cmds = vec![
        PathCmd::MoveTo(tip),
        PathCmd::LineTo(Point::new(base.x - uy * half, base.y + ux * half)),
        PathCmd::LineTo(Point::new(base.x + uy * half, base.y - ux * half)),
        PathCmd::Close,
    ];
    Item::new(Role::DataMark, Shape::Path(cmds), Style::fill(color))
}

/// Grid spacing of arrows in pixels.
fn arrow_spacing(frame: &Frame, density: f64) -> f64 {
    (frame.plot.w.max(frame.plot.h) / (25.0 * density)).max(6.0)
}

/// Arrows on a regular grid; the fastest is 0.9 grid spacings long. Also returns each arrow's
/// position and speed.
fn arrows(
    field: &VectorField,
    frame: &Frame,
    density: f64,
    color: Option<&ContinuousMap>,
    max_speed: f64,
) -> (Vec<Item>, Vec<([f64; 2], f64)>) {
    let spacing = arrow_spacing(frame, density);
    let scale = 0.9 * spacing / max_speed.max(1e-300);
    let (nx, ny) = ((frame.plot.w / spacing).floor() as usize, (frame.plot.h / spacing).floor() as usize);
    let mut items = Vec::new();
    let mut placed = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let c = Point::new(frame.plot.x + spacing * (i as f64 + 0.5), frame.plot.y + spacing * (j as f64 + 0.5));
            let (Some(x), Some(y)) = (frame.x.invert(c.x), frame.y.invert(c.y)) else { continue };
            let Some([u, v]) = field.velocity(x, y) else { continue };
            let speed = u.hypot(v);
            let fill = color.map_or(Color::rgb(0x1a, 0x1a, 0x1a), |m| m.at(speed / max_speed.max(1e-300)));
            items.extend(arrow(c, u * scale, -v * scale, fill));
            placed.push(([x, y], speed));
        }
    }
    (items, placed)
}

/// An arrow centred on `c` with pixel components (dx, dy).
fn arrow(c: Point, dx: f64, dy: f64, color: Color) -> Option<Item> {
    let len = dx.hypot(dy);
    if len < 1.0 {
        return None;
    }
    let (ux, uy) = (dx / len, dy / len);
    let head = (len * 0.35).min(6.0);
    let (a, b) = (Point::new(c.x - dx / 2.0, c.y - dy / 2.0), Point::new(c.x + dx / 2.0, c.y + dy / 2.0));
    let base = Point::new(b.x - ux * head, b.y - uy * head);
    let half = head * 0.45;
    let cmds = vec![
        PathCmd::MoveTo(a),
        PathCmd::LineTo(base),
        PathCmd::MoveTo(b),
        PathCmd::LineTo(Point::new(base.x - uy * half, base.y + ux * half)),
        PathCmd::LineTo(Point::new(base.x + uy * half, base.y - ux * half)),
        PathCmd::Close,
    ];
    let mut style = Style::fill(color);
    style.stroke = Some(Stroke::solid(color, 1.1));
    Some(Item::new(Role::DataMark, Shape::Path(cmds), style))
}

/// The key arrow: a nice speed's length, labelled, in the plot's top-right corner on a halo.
fn arrow_key(
    frame: &Frame,
    theme: &crate::guide::Theme,
    density: f64,
    max_speed: f64,
    unit: Option<&str>,
) -> Vec<Item> {
    if max_speed <= 0.0 {
        return Vec::new();
    }
    let spacing = arrow_spacing(frame, density);
    let scale = 0.9 * spacing / max_speed;
    let ticks = extended(0.0, max_speed, 3, false);
    let value = ticks.values.iter().copied().filter(|v| *v > 0.0 && *v <= max_speed).fold(max_speed, |_, v| v);
    let len = value * scale;
    let label = match unit {
        Some(u) => format!("{} {u}", format_value(value)),
        None => format_value(value),
    };
    let size = theme.label_size;
    let w = len + 8.0 + crate::text::measure(&label, size).width;
    let box_ = Rect::new(frame.plot.right() - w - 12.0, frame.plot.y + 4.0, w + 8.0, size * 1.6);
    let mid = box_.y + box_.h / 2.0;
    let mut items = vec![Item::new(Role::Legend, Shape::Rect(box_), Style::fill(theme.background.with_opacity(0.85)))];
    let start = box_.x + 4.0;
    items.extend(arrow(Point::new(start + len / 2.0, mid), len, 0.0, theme.text).map(|mut a| {
        a.role = Role::Legend;
        a
    }));
    items.push(Item::text(
        Role::Legend,
        Text {
            at: Point::new(start + len + 4.0, mid),
            content: label,
            size,
            anchor: Anchor::Start,
            baseline: Baseline::Middle,
            angle: 0.0,
            color: theme.text,
        },
    ));
    items
}

/// Critical points, separatrices and boundary switch points of a steady field.
struct Topology {
    points: Vec<crate::enrich::flow::topology::CriticalPoint>,
    separatrices: Vec<Streamline>,
    boundary: Vec<crate::enrich::flow::topology::BoundaryPoint>,
}

/// Glyph colour of each critical kind.
fn kind_style(kind: CriticalKind) -> (&'static str, Color, bool) {
    match kind {
        CriticalKind::Saddle => ("saddle", Color::rgb(0xcc, 0x24, 0x24), true),
        CriticalKind::AttractingNode => ("attracting node", Color::rgb(0x00, 0x72, 0xb2), true),
        CriticalKind::RepellingNode => ("repelling node", Color::rgb(0xe6, 0x9f, 0x00), true),
        CriticalKind::AttractingFocus => ("attracting focus", Color::rgb(0x56, 0xb4, 0xe9), false),
        CriticalKind::RepellingFocus => ("repelling focus", Color::rgb(0xd5, 0x5e, 0x00), false),
        CriticalKind::Centre => ("centre", Color::rgb(0x00, 0x9e, 0x73), false),
        CriticalKind::Degenerate => ("degenerate", Color::rgb(0x7f, 0x7f, 0x7f), true),
    }
}

impl Topology {
    fn find(field: &VectorField, budget: &StepBudget) -> Topology {
        let points = critical_points(field, CENTRE_TOLERANCE);
        let options = StreamlineOptions::for_field(field);
        let lines = separatrices(field, &points, 0.5 * field.min_cell(), &options, budget);
        Topology { points, separatrices: lines.into_iter().map(|s| s.line).collect(), boundary: boundary_points(field) }
    }

    /// The key: critical and boundary points as swatches, separatrices as a line of their own.
    fn legend(&self) -> Vec<Legend> {
        let mut entries: Vec<(String, Color)> = Vec::new();
        for p in &self.points {
            let (name, color, _) = kind_style(p.kind);
            if !entries.iter().any(|(n, _)| n == name) {
                entries.push((name.to_string(), color));
            }
        }
        if self.boundary.iter().any(|b| b.kind == SwitchKind::Attachment) {
            entries.push(("attachment".into(), Color::rgb(0x33, 0x33, 0x33)));
        }
        if self.boundary.iter().any(|b| b.kind == SwitchKind::Detachment) {
            entries.push(("detachment".into(), Color::rgb(0x99, 0x99, 0x99)));
        }
        let mut legends = Vec::new();
        if !entries.is_empty() {
            legends.push(Legend::Categorical { title: "topology".into(), entries, symbol: Symbol::Square });
        }
        if !self.separatrices.is_empty() {
            legends.push(Legend::Categorical {
                title: "from saddles".into(),
                entries: vec![("separatrix".into(), SEPARATRIX)],
                symbol: Symbol::Line,
            });
        }
        legends
    }

    fn draw(&self, to_px: &impl Fn([f64; 2]) -> Point) -> Vec<Item> {
        let mut items: Vec<Item> =
            self.separatrices.iter().filter_map(|l| polyline(&l.points, to_px, SEPARATRIX, 1.6)).collect();
        for b in &self.boundary {
            let c = to_px(b.position);
            let color = if b.kind == SwitchKind::Attachment {
                Color::rgb(0x33, 0x33, 0x33)
            } else {
                Color::rgb(0x99, 0x99, 0x99)
            };
            let d = 5.0;
            let cmds = vec![
                PathCmd::MoveTo(Point::new(c.x, c.y - d)),
                PathCmd::LineTo(Point::new(c.x + d, c.y)),
                PathCmd::LineTo(Point::new(c.x, c.y + d)),
                PathCmd::LineTo(Point::new(c.x - d, c.y)),
                PathCmd::Close,
            ];
            items.push(Item::new(Role::DataMark, Shape::Path(cmds), Style::fill(color)));
        }
        for p in &self.points {
            let (_, color, filled) = kind_style(p.kind);
            let c = to_px(p.position);
            let mut style = if filled { Style::fill(color) } else { Style::fill(Color::rgb(255, 255, 255)) };
            style.stroke = Some(Stroke::solid(if filled { Color::rgb(255, 255, 255) } else { color }, 2.0));
            let shape = if p.kind == CriticalKind::Saddle {
                Shape::Rect(Rect::new(c.x - 5.0, c.y - 5.0, 10.0, 10.0))
            } else {
                Shape::Circle { center: c, radius: 5.5 }
            };
            items.push(Item::new(Role::DataMark, shape, style));
        }
        items
    }
}

/// Derived output: one row per point of every traced line, and one per critical point.
#[derive(Default)]
struct Traces {
    element: Vec<String>,
    line: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    param: Vec<f64>,
    class: Vec<String>,
    eigen: [Vec<f64>; 4],
}

impl Traces {
    fn push(&mut self, element: &str, line: usize, p: [f64; 2], param: f64, class: &str, eigen: [f64; 4]) {
        self.element.push(element.to_string());
        self.line.push(line as f64);
        self.x.push(p[0]);
        self.y.push(p[1]);
        self.param.push(param);
        self.class.push(class.to_string());
        for (k, e) in eigen.iter().enumerate() {
            self.eigen[k].push(*e);
        }
    }

    fn add(&mut self, element: &str, lines: &[Streamline]) {
        for (i, l) in lines.iter().enumerate() {
            for (p, t) in l.points.iter().zip(&l.params) {
                self.push(element, i, *p, *t, "", [f64::NAN; 4]);
            }
        }
    }

    fn add_points(&mut self, element: &str, lines: &[Vec<[f64; 2]>]) {
        for (i, l) in lines.iter().enumerate() {
            for p in l {
                self.push(element, i, *p, f64::NAN, "", [f64::NAN; 4]);
            }
        }
    }

    fn add_critical(&mut self, t: &Topology) {
        for (i, p) in t.points.iter().enumerate() {
            let [(a, b), (c, d)] = p.eigenvalues;
            self.push("critical point", i, p.position, f64::NAN, kind_style(p.kind).0, [a, b, c, d]);
        }
        for (i, b) in t.boundary.iter().enumerate() {
            let class = if b.kind == SwitchKind::Attachment { "attachment" } else { "detachment" };
            self.push("boundary point", i, b.position, f64::NAN, class, [f64::NAN; 4]);
        }
    }

    fn finish(self) -> Derived {
        let mut d = Derived::default();
        d.push("element", DerivedColumn::Text(self.element));
        d.push("line", DerivedColumn::Number(self.line));
        d.push("x", DerivedColumn::Number(self.x));
        d.push("y", DerivedColumn::Number(self.y));
        d.push("param", DerivedColumn::Number(self.param));
        d.push("class", DerivedColumn::Text(self.class));
        let [a, b, c, e] = self.eigen;
        d.push("eigen1_re", DerivedColumn::Number(a));
        d.push("eigen1_im", DerivedColumn::Number(b));
        d.push("eigen2_re", DerivedColumn::Number(c));
        d.push("eigen2_im", DerivedColumn::Number(e));
        d
    }
}

/// `kind = "flow"`.
pub static KIND: KindInfo =
    KindInfo::new("flow", &["x", "y", "u", "v", "t"]).conventions(defaults::FLOW).taking_aspect().drawing_annotations();

impl Technique for FlowOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        AxisSpec::pair(&self.x, &self.y)
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }
}
