//! `contour`: filled bands and contour lines of a scalar field on a regular grid, read from a
//! long-form table (one row per grid node), with level labels and a stepped colour bar.

use crate::data::Table;
use crate::enrich::contour::{self, Saddle};
use crate::guide::color::ContinuousMap;
use crate::guide::layout::Domain;
use crate::guide::legend::Legend;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::gridded::{self, GridInput};
use crate::mark::level_labels::level_labels;
use crate::mark::registry::{AxisSpec, ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Color, Item, PathCmd, Point, Role, Shape, Style};
use crate::spec::{Channel, Chart, ColorChannel, Levels, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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

/// Saddle-cell rules for contouring.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SaddleRule {
    /// Compare the level with the bilinear saddle value (f00·f11 − f01·f10)/(f00 + f11 − f01 − f10).
    Asymptotic,
    /// Compare the level with the mean of the cell's four corners.
    Center,
}

/// Default number of levels.
pub const DEFAULT_LEVELS: u32 = 10;

/// Draw a contour chart.
pub fn draw(chart: &Chart, options: &ContourOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let z_opts = options.z.options();
    let GridInput { grid, rows, mut warnings, x_col, y_col, zmin, zmax } =
        gridded::load_grid(chart, &x_opts, &y_opts, &z_opts, table)?;
    if grid.nx() < 2 || grid.ny() < 2 {
        return Err(MarkError::at(
            &["x"],
            format!("contours need at least 2 × 2 grid nodes, the grid has {} × {}", grid.nx(), grid.ny()),
            "give at least two distinct coordinates along each axis",
        ));
    }
    let levels = match &options.levels {
        Some(Levels::Values(v)) => v.clone(),
        Some(Levels::Count(n)) => contour::nice_levels(zmin, zmax, (*n as usize).max(1)),
        None => contour::nice_levels(zmin, zmax, DEFAULT_LEVELS as usize),
    };
    let levels =
        contour::clean_levels(&levels).map_err(|e| MarkError::at(&["levels"], format!("{e}"), "give fewer levels"))?;
    let saddle = match options.saddle.unwrap_or(SaddleRule::Asymptotic) {
        SaddleRule::Asymptotic => Saddle::Asymptotic,
        SaddleRule::Center => Saddle::Center,
    };
    let map = encode::continuous_map(&["z", "scheme"], z_opts.scheme.as_deref())?;
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
    let mut x_axis = encode::position_axis("x", &x_opts, x_col, &rows)?;
    let mut y_axis = encode::position_axis("y", &y_opts, y_col, &rows)?;
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
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, encode::shown_legends(legend, &z_opts))?;
    let to_px = |(x, y): (f64, f64)| Point::new(frame.x.map(x), frame.y.map(y));

    let mut marks = Vec::new();
    let bands = if fill {
        contour::contour_bands(&grid, &edges, saddle)
            .map_err(|e| MarkError::at(&["levels"], format!("{e}"), "give fewer levels"))?
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
    let lines = contour::contour_lines(&grid, &levels, saddle)
        .map_err(|e| MarkError::at(&["levels"], format!("{e}"), "give fewer levels"))?;
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
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

    let mut derived = Derived::default();
    derived.push("level", DerivedColumn::Number(derived_level));
    derived.push("line", DerivedColumn::Number(derived_line));
    derived.push(&x_opts.field, DerivedColumn::Number(derived_x));
    derived.push(&y_opts.field, DerivedColumn::Number(derived_y));
    Ok(ChartOutput {
        scene,
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: Some(crate::mark::geojson::ContourFeatures { lines, bands }),
        volume: None,
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

/// `kind = "contour"`.
pub static KIND: KindInfo =
    KindInfo::new("contour", &["x", "y", "z"]).conventions(defaults::GRID).taking_aspect().drawing_annotations();

impl Technique for ContourOptions {
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
