//! `hyperslice`: for gridded data of more than two dimensions, a lower-triangular matrix of 2D
//! slices through a focus point — panel (row r, column c) shows axis c across and axis r + 1 up,
//! every other axis held at the focus — sharing one colour scale, with the focus marked.

use crate::data::Table;
use crate::enrich::hyperslice::{NdGrid, slice_matrix};
use crate::guide::axis::{self, Side, title_with_unit};
use crate::guide::format::format_value;
use crate::guide::legend::Legend;
use crate::guide::scale::{LinearScale, Scale};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::raster::{NAN_COLOR, image_extent, raster_for};
use crate::mark::registry::{ChartContext, ColourSpec, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Color, Item, PathCmd, Point, Rect, Role, Shape, Stroke, Style};
use crate::spec::{Chart, ColorChannel, Resample, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "hyperslice"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct HypersliceOptions {
    /// The grid's coordinate columns, one per dimension (2 to 16), in a long-form table with one
    /// row per grid node.
    pub axes: Vec<String>,
    /// The value: a column name, or `{ field, title, unit, scheme, midpoint }`.
    pub z: ColorChannel,
    /// The focus point, one coordinate per axis (default: the middle node of each axis); each
    /// slice holds the other axes at the grid node nearest the focus.
    #[serde(default)]
    pub focus: Option<Vec<f64>>,
}

/// Draw a hyperslice matrix.
pub fn draw(chart: &Chart, options: &HypersliceOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let z_opts = options.z.options();
    if options.axes.len() < 2 {
        return Err(MarkError::at(
            &["axes"],
            format!("a hyperslice needs at least 2 axes, got {}", options.axes.len()),
            "list the grid's coordinate columns, e.g. axes = [\"x1\", \"x2\", \"x3\"]",
        ));
    }
    let mut columns = Vec::new();
    for (k, name) in options.axes.iter().enumerate() {
        let col = encode::column(chart, "axes", name, table).map_err(|mut e| {
            e.path.push(crate::spec::PathSeg::Index(k));
            e
        })?;
        if col.numbers().is_none() {
            let mut e =
                MarkError::at(&["axes"], format!("axis column `{name}` holds text"), "use numeric coordinate columns");
            e.path.push(crate::spec::PathSeg::Index(k));
            return Err(e);
        }
        columns.push((name.as_str(), col));
    }
    let z_col = encode::column(chart, "z", &z_opts.field, table)?;
    // Rows need finite coordinates; a non-finite value stays in the grid as a hole.
    let (rows, warning) = encode::finite_rows(&chart.name, table.rows, &columns);
    let warnings: Vec<Warning> = warning.into_iter().collect();
    if rows.is_empty() {
        return Err(encode::no_rows(chart, table, warnings.first()));
    }
    let pick = |col: &crate::data::Column| encode::values_at(col, &rows);
    let coords: Vec<Vec<f64>> = columns.iter().map(|(_, c)| pick(c)).collect();
    let coord_refs: Vec<&[f64]> = coords.iter().map(Vec::as_slice).collect();
    let values = pick(z_col);
    let grid = NdGrid::from_rows(&options.axes, &coord_refs, &values)
        .map_err(|e| MarkError::at(&["axes"], format!("{e}"), "hyperslice needs one row per node of a regular grid"))?;
    let dims = grid.dims();
    let focus_values: Vec<f64> = match &options.focus {
        Some(f) if f.len() == dims => f.clone(),
        Some(f) => {
            return Err(MarkError::at(
                &["focus"],
                format!("`focus` has {} coordinates for {dims} axes", f.len()),
                "give one coordinate per axis, in the order of `axes`",
            ));
        }
        None => (0..dims).map(|k| grid.axis(k).and_then(|(_, c)| c.get(c.len() / 2).copied()).unwrap_or(0.0)).collect(),
    };
    let focus = grid.nearest_index(&focus_values);
    let slices =
        slice_matrix(&grid, &focus).map_err(|e| MarkError::at(&["focus"], format!("{e}"), "check the focus point"))?;
    let Some((zmin, zmax)) = grid.range() else {
        return Err(MarkError::at(
            &["z"],
            format!("every value of `{}` is missing", z_opts.field),
            "check the z column",
        ));
    };
    let map = encode::continuous_map(&["z", "scheme"], z_opts.scheme.as_deref())?;
    let (lo, hi) = encode::color_domain(&map, zmin, zmax, z_opts.midpoint);

    let z_title = title_with_unit(z_opts.title.as_deref().unwrap_or(&z_opts.field), z_opts.unit.as_deref());
    let canvas = frame::PanelCanvas::new(
        chart,
        encode::shown_legends(Legend::ColorBar { title: z_title, map: map.clone(), domain: (lo, hi) }, &z_opts),
    );
    let (width, theme, title_h, caption_h, room, legend_w) =
        (canvas.width, canvas.theme.clone(), canvas.title_h, canvas.caption_h, canvas.room, canvas.legend_w);
    let m = theme.margin;
    let n = dims - 1;
    let (left, bottom) = (theme.font_size * 5.5, theme.font_size * 4.5 + caption_h.max(theme.caption_size * 1.8));
    let gap = theme.font_size * 0.8;
    let avail_w = width - 2.0 * m - legend_w - theme.font_size * 1.5 - left;
    let avail_h = room - bottom;
    let side = ((avail_w.min(avail_h) - gap * (n as f64 - 1.0)) / n as f64).floor();
    if side < 24.0 {
        return Err(MarkError::layout(crate::guide::layout::LayoutError::TooSmall {
            plot_width: side.max(0.0),
            plot_height: side.max(0.0),
        }));
    }
    let origin = Point::new(m + left, m + title_h);
    let mut items = vec![canvas.background()];
    let scale_for = |k: usize, range: (f64, f64)| -> Option<Scale> {
        let (_, c) = grid.axis(k)?;
        let extent = image_extent(c, Resample::Nearest)?;
        LinearScale::new(extent, range, false, 4).ok().map(Scale::Linear)
    };
    let focus_marker = Stroke { color: Color::WHITE, width: 1.0, dash: vec![3.0, 2.0] };
    for ((a, b), slice) in &slices {
        let (row, col) = (b - 1, *a);
        let plot = Rect::new(origin.x + col as f64 * (side + gap), origin.y + row as f64 * (side + gap), side, side);
        let (Some(x), Some(y)) = (scale_for(*a, (plot.x, plot.right())), scale_for(*b, (plot.bottom(), plot.y))) else {
            continue;
        };
        let image = raster_for(slice, plot, &x, &y, Resample::Nearest, |v| {
            if v.is_finite() { map.at((v - lo) / (hi - lo)) } else { NAN_COLOR }
        });
        items.push(
            Item::new(Role::DataMark, Shape::Image(image), Style::default())
                .labelled(format!("{} × {}", options.axes[*a], options.axes[*b])),
        );
        // The focus: where the other panels' slices cross this one.
        let (fx, fy) = (x.map(focus_values[*a]), y.map(focus_values[*b]));
        let cross = vec![
            PathCmd::MoveTo(Point::new(fx, plot.y)),
            PathCmd::LineTo(Point::new(fx, plot.bottom())),
            PathCmd::MoveTo(Point::new(plot.x, fy)),
            PathCmd::LineTo(Point::new(plot.right(), fy)),
        ];
        items.push(Item::group(
            Role::Annotation,
            vec![Item::new(
                Role::Annotation,
                Shape::Path(cross),
                Style { fill: None, stroke: Some(focus_marker.clone()) },
            )],
            Some(plot),
        ));
        items.push(Item::new(Role::Axis, Shape::Rect(plot), Style::stroke(theme.axis, 0.8)));
        if row == n - 1 {
            items.extend(axis::draw(&x, Side::Bottom, plot, Some(&options.axes[*a]), &theme));
        }
        if col == 0 {
            items.extend(axis::draw(&y, Side::Left, plot, Some(&options.axes[*b]), &theme));
        }
    }
    let focus_note: Vec<String> = options
        .axes
        .iter()
        .zip(&focus)
        .enumerate()
        .map(|(k, (name, &i))| {
            format!("{name} = {}", format_value(grid.axis(k).and_then(|(_, c)| c.get(i).copied()).unwrap_or(f64::NAN)))
        })
        .collect();
    let caption = match &chart.caption {
        Some(c) => format!("{c} — focus: {}", focus_note.join(", ")),
        None => format!("Focus: {}", focus_note.join(", ")),
    };
    let scene = canvas.scene(chart, items, Some(&caption));

    let mut derived = Derived::over(rows);
    derived.push("row", DerivedColumn::RowIndex);
    for name in &options.axes {
        derived.push(name, DerivedColumn::Source(name.clone()));
    }
    derived.push(&z_opts.field, DerivedColumn::Source(z_opts.field.clone()));
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

/// `kind = "hyperslice"`.
pub static KIND: KindInfo = KindInfo::new("hyperslice", &["axes", "z"]).conventions(defaults::FIELD);

impl Technique for HypersliceOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn colour_encodings(&self) -> Vec<ColourSpec> {
        ColourSpec::z(&self.z)
    }
}
