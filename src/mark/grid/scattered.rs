//! `scattered`: scattered measurements — the Delaunay triangulation of the points, the linear
//! interpolant inside each triangle as a colour fill, contour lines on the triangulation (no
//! resampling), an optional Voronoi (Dirichlet) overlay, and the points on top.

use std::sync::Arc;

use crate::data::Table;
use crate::enrich::contour::{clean_levels, nice_levels};
use crate::enrich::scattered::Triangulation;
use crate::guide::axis::title_with_unit;
use crate::guide::legend::Legend;
use crate::guide::scale::Scale;
use crate::mark::derived::Derived;
use crate::mark::level_labels::level_labels;
use crate::mark::registry::{AxisSpec, ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Color, Item, PathCmd, PerPoint, Point, PointBatch, Raster, Rect, Role, Shape, Stroke, Style};
use crate::spec::{Channel, Chart, ColorChannel, Levels, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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

/// Marker radius of the points.
const POINT_RADIUS: f64 = 3.0;

/// Draw a scattered-data chart.
pub fn draw(chart: &Chart, options: &ScatteredOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let z_opts = options.z.options();
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    let z_col = encode::column(chart, "z", &z_opts.field, table)?;
    for (key, field, col) in [("x", &x_opts.field, x_col), ("y", &y_opts.field, y_col), ("z", &z_opts.field, z_col)] {
        if col.numbers().is_none() || col.is_time() {
            return Err(MarkError::at(
                &[key],
                format!("column `{field}` holds {}; scattered data needs numbers", col.type_name()),
                "use numeric columns for x, y and z",
            ));
        }
    }
    let (rows, warning) = encode::finite_rows(
        &chart.name,
        table.rows,
        &[(x_opts.field.as_str(), x_col), (y_opts.field.as_str(), y_col), (z_opts.field.as_str(), z_col)],
    );
    let mut warnings: Vec<Warning> = warning.into_iter().collect();
    if rows.is_empty() {
        return Err(encode::no_rows(chart, table, warnings.first()));
    }
    let pick = |col: &crate::data::Column| encode::values_at(col, &rows);
    let (xs, ys, zs) = (pick(x_col), pick(y_col), pick(z_col));
    let points: Vec<(f64, f64)> = xs.iter().copied().zip(ys.iter().copied()).collect();
    let tin = Triangulation::new(&points, &zs)
        .map_err(|e| MarkError::at(&["x"], format!("{e}"), "check the point coordinates"))?;
    if tin.merged_duplicates() > 0 {
        warnings.push(Warning::from(format!(
            "merged {} points that repeat an earlier point's position (the first one's value is kept)",
            tin.merged_duplicates()
        )));
    }
    if tin.is_degenerate() {
        warnings.push(Warning::from(format!(
            "the points are fewer than three or all on one line, so there are no triangles; only the points are drawn"
        )));
    }

    let (zmin, zmax) = encode::extent(&zs, &(0..zs.len() as u32).collect::<Vec<_>>()).unwrap_or((0.0, 1.0));
    let map = encode::continuous_map(&["z", "scheme"], z_opts.scheme.as_deref())?;
    let (lo, hi) = encode::color_domain(&map, zmin, zmax, z_opts.midpoint);
    let color_of = |v: f64| map.at((v - lo) / (hi - lo));
    let title = title_with_unit(z_opts.title.as_deref().unwrap_or(&z_opts.field), z_opts.unit.as_deref());
    let legend = Legend::ColorBar { title, map: map.clone(), domain: (lo, hi) };
    let mut x_axis = encode::position_axis("x", &x_opts, x_col, &rows)?;
    let mut y_axis = encode::position_axis("y", &y_opts, y_col, &rows)?;
    x_axis.inset = POINT_RADIUS + 1.5;
    y_axis.inset = POINT_RADIUS + 1.5;
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, encode::shown_legends(legend, &z_opts))?;
    let to_px = |(x, y): (f64, f64)| Point::new(frame.x.map(x), frame.y.map(y));

    let mut marks = Vec::new();
    if options.fill.unwrap_or(true) && !tin.is_degenerate() {
        let raster = fill_raster(&tin, frame.plot, &frame.x, &frame.y, &color_of);
        marks.push(
            Item::new(Role::DataMark, Shape::Image(raster), Style::default())
                .with_rows(rows.clone())
                .labelled("interpolant"),
        );
    }
    if options.mesh.unwrap_or(true) && !tin.is_degenerate() {
        let mut cmds = Vec::with_capacity(tin.triangles().len() * 4);
        let pts = tin.points();
        for tri in tin.triangles() {
            let [a, b, c] = tri.map(|i| i as usize);
            let (Some(&a), Some(&b), Some(&c)) = (pts.get(a), pts.get(b), pts.get(c)) else { continue };
            cmds.extend([
                PathCmd::MoveTo(to_px(a)),
                PathCmd::LineTo(to_px(b)),
                PathCmd::LineTo(to_px(c)),
                PathCmd::Close,
            ]);
        }
        marks.push(
            Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(Color::WHITE.with_opacity(0.7), 0.6))
                .with_rows(rows.clone())
                .labelled("Delaunay triangles"),
        );
    }
    if options.voronoi.unwrap_or(false) {
        let clip = domain_rect(&frame.x, &frame.y, frame.plot);
        let cells = tin
            .voronoi_cells(clip)
            .map_err(|e| MarkError::at(&["voronoi"], format!("{e}"), "check the point coordinates"))?;
        let mut cmds = Vec::new();
        for cell in &cells {
            for (k, &p) in cell.iter().enumerate() {
                cmds.push(if k == 0 { PathCmd::MoveTo(to_px(p)) } else { PathCmd::LineTo(to_px(p)) });
            }
            if !cell.is_empty() {
                cmds.push(PathCmd::Close);
            }
        }
        if options.fill == Some(false) {
            // Without the interpolant, each tile takes its point's colour: nearest-neighbour
            // interpolation, the Dirichlet tessellation's own reading of the data.
            for ((cell, &z), input) in cells.iter().zip(tin.values()).zip(tin.rows()) {
                let mut cell_cmds = Vec::with_capacity(cell.len() + 1);
                for (k, &p) in cell.iter().enumerate() {
                    cell_cmds.push(if k == 0 { PathCmd::MoveTo(to_px(p)) } else { PathCmd::LineTo(to_px(p)) });
                }
                cell_cmds.push(PathCmd::Close);
                let mut style = Style::fill(color_of(z));
                style.stroke = Some(Stroke::solid(Color::WHITE, 0.8));
                let source: Vec<u32> = rows.get(input).copied().into_iter().collect();
                marks.push(
                    Item::new(Role::DataMark, Shape::Path(cell_cmds), style).with_rows(source).labelled("Voronoi tile"),
                );
            }
        } else {
            let style = Style::stroke(Color::rgb(0x20, 0x20, 0x20).with_opacity(0.6), 0.8);
            marks.push(
                Item::new(Role::DataMark, Shape::Path(cmds), style).with_rows(rows.clone()).labelled("Voronoi tiles"),
            );
        }
    }
    if let Some(levels) = &options.levels {
        let levels = match levels {
            Levels::Values(v) => v.clone(),
            Levels::Count(n) => nice_levels(zmin, zmax, (*n as usize).max(1)),
        };
        let levels =
            clean_levels(&levels).map_err(|e| MarkError::at(&["levels"], format!("{e}"), "give fewer levels"))?;
        let lines =
            tin.contour_lines(&levels).map_err(|e| MarkError::at(&["levels"], format!("{e}"), "give fewer levels"))?;
        for line in &lines {
            let cmds = frame::polyline(&line.points, line.closed, &to_px);
            marks.push(
                Item::new(
                    Role::DataMark,
                    Shape::Path(cmds),
                    Style::stroke(Color::rgb(0x20, 0x20, 0x20).with_opacity(0.7), 0.9),
                )
                .with_rows(rows.clone())
                .labelled(format!("z = {}", line.level)),
            );
        }
        let pairs = lines.iter().map(|l| (l.level, l.points.as_slice()));
        marks.extend(level_labels(pairs, &levels, &to_px, theme.font_size * 0.85));
    }
    if options.points.unwrap_or(true) {
        let centers = points.iter().map(|&p| to_px(p)).collect();
        let fill = PerPoint::Each(zs.iter().map(|&z| color_of(z)).collect());
        marks.push(
            Item::new(
                Role::DataMark,
                Shape::Points(PointBatch {
                    centers,
                    radius: PerPoint::Uniform(POINT_RADIUS),
                    fill,
                    stroke: Some(Stroke::solid(Color::rgb(0x22, 0x22, 0x22), 0.8)),
                }),
                Style::default(),
            )
            .with_rows(rows.clone())
            .labelled("points"),
        );
    }
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);
    let derived = Derived::of_rows(rows, &[&x_opts.field, &y_opts.field, &z_opts.field]);
    Ok(ChartOutput {
        scene,
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// The plot area in data coordinates `(xmin, ymin, xmax, ymax)`.
fn domain_rect(x: &Scale, y: &Scale, plot: Rect) -> (f64, f64, f64, f64) {
    let (x0, x1) = (x.invert(plot.x).unwrap_or(0.0), x.invert(plot.right()).unwrap_or(1.0));
    let (y0, y1) = (y.invert(plot.bottom()).unwrap_or(0.0), y.invert(plot.y).unwrap_or(1.0));
    (x0.min(x1), y0.min(y1), x0.max(x1), y0.max(y1))
}

/// The linear interpolant as a raster over the plot: each triangle is scan-converted in pixel
/// space and every pixel centre inside it gets the barycentric blend of its corner values, so
/// no point location is needed. Pixels outside the hull stay transparent.
fn fill_raster(tin: &Triangulation, plot: Rect, x: &Scale, y: &Scale, color_of: &impl Fn(f64) -> Color) -> Raster {
    let w = (plot.w.round().max(1.0) as usize).min(4096);
    let h = (plot.h.round().max(1.0) as usize).min(4096);
    let mut rgba = vec![0u8; w * h * 4];
    let (pts, vals) = (tin.points(), tin.values());
    // Pixel coordinates relative to the raster's top-left corner.
    let px = |p: (f64, f64)| ((x.map(p.0) - plot.x) * w as f64 / plot.w, (y.map(p.1) - plot.y) * h as f64 / plot.h);
    for tri in tin.triangles() {
        let [ia, ib, ic] = tri.map(|i| i as usize);
        let (Some(&a), Some(&b), Some(&c)) = (pts.get(ia), pts.get(ib), pts.get(ic)) else { continue };
        let (Some(&za), Some(&zb), Some(&zc)) = (vals.get(ia), vals.get(ib), vals.get(ic)) else {
            continue;
        };
        let (pa, pb, pc) = (px(a), px(b), px(c));
        let det = (pb.0 - pa.0) * (pc.1 - pa.1) - (pc.0 - pa.0) * (pb.1 - pa.1);
        if det.abs() < 1e-12 || !det.is_finite() {
            continue;
        }
        let xmin = pa.0.min(pb.0).min(pc.0).floor().max(0.0) as usize;
        let xmax = (pa.0.max(pb.0).max(pc.0).ceil().max(0.0) as usize).min(w);
        let ymin = pa.1.min(pb.1).min(pc.1).floor().max(0.0) as usize;
        let ymax = (pa.1.max(pb.1).max(pc.1).ceil().max(0.0) as usize).min(h);
        for j in ymin..ymax {
            let cy = j as f64 + 0.5;
            for i in xmin..xmax {
                let cx = i as f64 + 0.5;
                let l1 = ((pb.0 - cx) * (pc.1 - cy) - (pc.0 - cx) * (pb.1 - cy)) / det;
                let l2 = ((pc.0 - cx) * (pa.1 - cy) - (pa.0 - cx) * (pc.1 - cy)) / det;
                let l3 = 1.0 - l1 - l2;
                // Half-open edges (small tolerance) so shared edges are covered once, with no gaps.
                if l1 < -1e-9 || l2 < -1e-9 || l3 < -1e-9 {
                    continue;
                }
                let v = l1 * za + l2 * zb + l3 * zc;
                let c = color_of(v);
                if let Some(p) = rgba.get_mut((j * w + i) * 4..(j * w + i) * 4 + 4) {
                    p.copy_from_slice(&[c.r, c.g, c.b, 255]);
                }
            }
        }
    }
    Raster { dest: plot, width: w as u32, height: h as u32, rgba: Arc::new(rgba), smooth: false }
}

/// `kind = "scattered"`.
pub static KIND: KindInfo =
    KindInfo::new("scattered", &["x", "y", "z"]).conventions(defaults::GRID).taking_aspect().drawing_annotations();

impl Technique for ScatteredOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        AxisSpec::pair(&self.x, &self.y)
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        ColourSpec::z(&self.z)
    }
}
