//! `contour`: filled bands and contour lines of a scalar field on a regular grid, read from a
//! long-form table (one row per grid node), with level labels and a stepped colour bar.

use super::derived::{Derived, DerivedColumn};
use super::gridded::{self, GridInput};
use super::registry::{AxisSpec, ChartContext, ColourSpec, KindInfo, Technique};
use super::{ChartOutput, MarkError, encode, frame};
use crate::data::Table;
use crate::enrich::contour::{self, Saddle};
use crate::guide::color::ContinuousMap;
use crate::guide::format::format_ticks;
use crate::guide::layout::Domain;
use crate::guide::legend::Legend;
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Role, Shape, Style, Text};
use crate::spec::defaults;
use crate::spec::{Chart, ContourOptions, Levels, SaddleRule};
use crate::text::measure;

/// Default number of levels.
pub const DEFAULT_LEVELS: u32 = 10;

/// Draw a contour chart.
pub fn draw(chart: &Chart, options: &ContourOptions, index: usize, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let z_opts = options.z.options();
    let GridInput { grid, rows, warnings, x_col, y_col, zmin, zmax } =
        gridded::load_grid(chart, index, &x_opts, &y_opts, &z_opts, table)?;
    if grid.nx() < 2 || grid.ny() < 2 {
        return Err(MarkError::at(
            index,
            &["x"],
            format!(
                "chart \"{}\": contours need at least 2 × 2 grid nodes, the grid has {} × {}",
                chart.name,
                grid.nx(),
                grid.ny()
            ),
            "give at least two distinct coordinates along each axis",
        ));
    }
    let levels = match &options.levels {
        Some(Levels::Values(v)) => v.clone(),
        Some(Levels::Count(n)) => contour::nice_levels(zmin, zmax, (*n as usize).max(1)),
        None => contour::nice_levels(zmin, zmax, DEFAULT_LEVELS as usize),
    };
    let levels = contour::clean_levels(&levels).map_err(|e| {
        MarkError::at(index, &["levels"], format!("chart \"{}\": {e}", chart.name), "give fewer levels")
    })?;
    let saddle = match options.saddle.unwrap_or(SaddleRule::Asymptotic) {
        SaddleRule::Asymptotic => Saddle::Asymptotic,
        SaddleRule::Center => Saddle::Center,
    };
    let map = encode::continuous_map(index, &["z", "scheme"], z_opts.scheme.as_deref())?;
    let fill = options.fill.unwrap_or(true);
    let draw_lines = options.lines.unwrap_or(true);

    // Bands fill everything: the outer edges are the field's extremes.
    let mut edges = vec![zmin];
    edges.extend(levels.iter().copied().filter(|l| *l > zmin && *l < zmax));
    edges.push(zmax);
    if zmin == zmax {
        // A constant field is one band around its value.
        edges = vec![zmin - 0.5, zmax + 0.5];
    }
    let (lo, hi) = encode::color_domain(&map, zmin, zmax, z_opts.midpoint);
    let band_colors = band_colors(&map, &edges, z_opts.midpoint);

    let z_title =
        crate::guide::axis::title_with_unit(z_opts.title.as_deref().unwrap_or(&z_opts.field), z_opts.unit.as_deref());
    let legend = if fill {
        Legend::Steps { title: z_title, edges: edges.clone(), colors: band_colors.clone() }
    } else {
        Legend::ColorBar { title: z_title, map: map.clone(), domain: (lo, hi) }
    };
    let mut x_axis = encode::position_axis(chart, index, "x", &x_opts, x_col, &rows)?;
    let mut y_axis = encode::position_axis(chart, index, "y", &y_opts, y_col, &rows)?;
    // The grid fills the plot exactly.
    for (axis, opts) in [(&mut x_axis, &x_opts), (&mut y_axis, &y_opts)] {
        axis.nice = opts.nice.unwrap_or(false) && opts.domain.is_none();
        axis.grid = opts.grid.unwrap_or(false);
    }
    if let (Some(&x0), Some(&x1)) = (grid.xs().first(), grid.xs().last()) {
        x_axis.domain = Domain::Continuous(x0, x1);
    }
    if let (Some(&y0), Some(&y1)) = (grid.ys().first(), grid.ys().last()) {
        y_axis.domain = Domain::Continuous(y0, y1);
    }
    let (frame, theme) = frame::cartesian(chart, index, x_axis, y_axis, encode::shown_legends(legend, &z_opts))?;
    let to_px = |(x, y): (f64, f64)| Point::new(frame.x.map(x), frame.y.map(y));

    let mut marks = Vec::new();
    let bands = if fill {
        contour::contour_bands(&grid, &edges, saddle).map_err(|e| {
            MarkError::at(index, &["levels"], format!("chart \"{}\": {e}", chart.name), "give fewer levels")
        })?
    } else {
        Vec::new()
    };
    {
        for (band, color) in bands.iter().zip(&band_colors) {
            let mut cmds = Vec::new();
            for ring in band.polygons.iter().flatten() {
                for (k, &p) in ring.iter().enumerate() {
                    cmds.push(if k == 0 { PathCmd::MoveTo(to_px(p)) } else { PathCmd::LineTo(to_px(p)) });
                }
                cmds.push(PathCmd::Close);
            }
            if !cmds.is_empty() {
                // A hairline of the same colour hides anti-aliasing seams between bands.
                let mut style = Style::fill(*color);
                style.stroke = Some(crate::scene::Stroke::solid(*color, 0.5));
                marks.push(
                    Item::new(Role::DataMark, Shape::Path(cmds), style)
                        .labelled(format!("{} ≤ z < {}", band.lower, band.upper)),
                );
            }
        }
    }
    let lines = contour::contour_lines(&grid, &levels, saddle).map_err(|e| {
        MarkError::at(index, &["levels"], format!("chart \"{}\": {e}", chart.name), "give fewer levels")
    })?;
    let mut derived_level = Vec::new();
    let mut derived_line = Vec::new();
    let mut derived_x = Vec::new();
    let mut derived_y = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        for &(x, y) in &line.points {
            derived_level.push(line.level);
            derived_line.push(k as f64);
            derived_x.push(x);
            derived_y.push(y);
        }
        if let Some(&first) = line.points.first().filter(|_| line.closed) {
            derived_level.push(line.level);
            derived_line.push(k as f64);
            derived_x.push(first.0);
            derived_y.push(first.1);
        }
    }
    if draw_lines {
        let line_color = if fill { Color::rgb(0x20, 0x20, 0x20).with_opacity(0.55) } else { Color::BLACK };
        // One path per level (its lines as subpaths): a noisy field has many small rings, and
        // a scene item each would cost far more than their points.
        for same_level in lines.chunk_by(|a, b| a.level == b.level) {
            let level = same_level[0].level;
            let cmds: Vec<PathCmd> =
                same_level.iter().flat_map(|line| frame::polyline(&line.points, line.closed, &to_px)).collect();
            let color = if fill { line_color } else { map.at((level - lo) / (hi - lo)) };
            marks.push(
                Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(color, if fill { 0.8 } else { 1.4 }))
                    .labelled(format!("z = {level}")),
            );
        }
        if options.labels.unwrap_or(true) {
            let pairs = lines.iter().map(|l| (l.level, l.points.as_slice()));
            marks.extend(level_labels(pairs, &levels, &to_px, theme.font_size * 0.85));
        }
    }
    let scene = frame::scene(chart, frame, &theme, marks);

    let mut derived = Derived::default();
    derived.push("level", DerivedColumn::Number(derived_level));
    derived.push("line", DerivedColumn::Number(derived_line));
    derived.push(&x_opts.field, DerivedColumn::Number(derived_x));
    derived.push(&y_opts.field, DerivedColumn::Number(derived_y));
    Ok(ChartOutput {
        scene,
        derived,
        warnings,
        geojson: Some(super::geojson::ContourFeatures { lines, bands }),
        geometry: Default::default(),
    })
}

/// One colour per band, by the band's rank rather than its value, so that unevenly spaced
/// levels still get evenly spaced, distinguishable colours. Diverging maps put the bands below
/// the midpoint (default: the middle of the range) in the lower half of the map and the bands
/// above it in the upper half.
pub fn band_colors(map: &ContinuousMap, edges: &[f64], midpoint: Option<f64>) -> Vec<Color> {
    let n = edges.len().saturating_sub(1);
    if n == 0 {
        return Vec::new();
    }
    if !map.is_diverging() {
        return (0..n).map(|k| map.at((k as f64 + 0.5) / n as f64)).collect();
    }
    let (first, last) = (edges[0], edges[n]);
    let mid = midpoint.unwrap_or((first + last) / 2.0);
    let centre = |k: usize| (edges[k] + edges[k + 1]) / 2.0;
    let below = (0..n).filter(|&k| centre(k) < mid).count();
    let above = n - below;
    (0..n)
        .map(|k| {
            if k < below {
                // The band nearest the midpoint is lightest: rank from the midpoint outwards.
                map.at(0.5 - 0.5 * (below - k) as f64 / below as f64 + 0.25 / below as f64)
            } else {
                map.at(0.5 + 0.5 * (k - below + 1) as f64 / above as f64 - 0.25 / above as f64)
            }
        })
        .collect()
}

/// One label per level, on that level's longest line, rotated along it, over a white halo.
/// `lines` are `(level, points in data coordinates)`; labels that would collide with one placed
/// before are moved along their line or dropped.
pub fn level_labels<'a>(
    lines: impl Iterator<Item = (f64, &'a [(f64, f64)])> + Clone,
    levels: &[f64],
    to_px: &impl Fn((f64, f64)) -> Point,
    size: f64,
) -> Vec<Item> {
    let step = levels.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
    let texts = format_ticks(levels, if step.is_finite() { step } else { 1.0 });
    let mut items = Vec::new();
    let mut placed: Vec<crate::scene::Rect> = Vec::new();
    for (level, label) in levels.iter().zip(texts) {
        let best = lines
            .clone()
            .filter(|(l, _)| *l == *level)
            .map(|(_, points)| {
                let px: Vec<Point> = points.iter().map(|&p| to_px(p)).collect();
                let len: f64 = px.windows(2).map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y)).sum();
                (len, px)
            })
            .max_by(|a, b| a.0.total_cmp(&b.0));
        let Some((len, px)) = best else { continue };
        let width = measure(&label, size).width;
        if len < width * 3.0 {
            continue;
        }
        // Try points along the line (half, quarter, three quarters, ...) until the label's box
        // clears every label placed so far.
        let m = measure(&label, size);
        let (hw, hh) = (m.width / 2.0 + 2.0, (m.ascent + m.descent) / 2.0 + 1.0);
        let mut at = None;
        for fraction in [0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875] {
            let Some((p, angle)) = point_along(&px, len * fraction) else { continue };
            let r = hw.max(hh);
            let bounds = crate::scene::Rect::new(p.x - r, p.y - r, 2.0 * r, 2.0 * r);
            if placed.iter().all(|b: &crate::scene::Rect| !b.intersects(&bounds)) {
                placed.push(bounds);
                at = Some((p, angle));
                break;
            }
        }
        let Some((p, angle)) = at else { continue };
        let (s, c) = angle.to_radians().sin_cos();
        let corner = |dx: f64, dy: f64| Point::new(p.x + dx * c - dy * s, p.y + dx * s + dy * c);
        items.push(Item::new(
            Role::Annotation,
            Shape::Path(vec![
                PathCmd::MoveTo(corner(-hw, -hh)),
                PathCmd::LineTo(corner(hw, -hh)),
                PathCmd::LineTo(corner(hw, hh)),
                PathCmd::LineTo(corner(-hw, hh)),
                PathCmd::Close,
            ]),
            Style::fill(Color::WHITE.with_opacity(0.8)),
        ));
        items.push(Item::text(
            Role::Annotation,
            Text {
                at: p,
                content: label,
                size,
                anchor: Anchor::Middle,
                baseline: Baseline::Middle,
                angle,
                color: Color::rgb(0x22, 0x22, 0x22),
            },
        ));
    }
    items
}

/// The point at arc length `distance` along a polyline and the direction there in degrees,
/// turned to read left to right.
fn point_along(px: &[Point], distance: f64) -> Option<(Point, f64)> {
    let mut walked = 0.0;
    for w in px.windows(2) {
        let seg = (w[1].x - w[0].x).hypot(w[1].y - w[0].y);
        if walked + seg >= distance && seg > 0.0 {
            let t = (distance - walked) / seg;
            let p = Point::new(w[0].x + t * (w[1].x - w[0].x), w[0].y + t * (w[1].y - w[0].y));
            let mut angle = (w[1].y - w[0].y).atan2(w[1].x - w[0].x).to_degrees();
            if angle > 90.0 {
                angle -= 180.0;
            } else if angle < -90.0 {
                angle += 180.0;
            }
            return Some((p, angle));
        }
        walked += seg;
    }
    None
}

/// `kind = "contour"`.
pub static KIND: KindInfo = KindInfo::new("contour", &["x", "y", "z"]).conventions(defaults::GRID).taking_aspect();

impl Technique for ContourOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.index, cx.table)
    }

    fn cartesian_axes(&self) -> Vec<AxisSpec> {
        AxisSpec::pair(&self.x, &self.y)
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        ColourSpec::z(&self.z)
    }
}
