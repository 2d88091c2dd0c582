//! Where facet panels go on the canvas: the plot area (or whole area) of every panel, which
//! panels label their axes, and the items around them — title, caption, panel headers, the one
//! x and y axis title of the grid, and the shared legends.

use crate::guide::Theme;
use crate::guide::axis::Side;
use crate::guide::layout::{MIN_PLOT_SIDE, PositionAxis, axis_room, labels_before, widest_tick_label};
use crate::guide::legend::{self, Legend, truncate_to_width};
use crate::mark::MarkError;
use crate::mark::frame::title_and_caption;
use crate::scene::{Anchor, Baseline, Item, Point, Rect, Role, Shape, Style, Text};
use crate::spec::Chart;

use super::split::Split;

/// The shared axes of cartesian panels, for the room their labels and titles take.
pub struct GridAxes<'a> {
    /// The x axis (its domain the union of the panels').
    pub x: &'a PositionAxis,
    /// The y axis.
    pub y: &'a PositionAxis,
    /// Whether every panel labels its own x axis (unshared x scales).
    pub x_independent: bool,
    /// Whether every panel labels its own y axis.
    pub y_independent: bool,
}

/// The panels placed on the canvas.
pub struct GridLayout {
    /// Each panel's area (the plot area of a cartesian panel, the whole chart area of another),
    /// in the order of [`Split::panels`].
    pub areas: Vec<Rect>,
    /// Whether each panel labels its x axis.
    pub x_labels: Vec<bool>,
    /// Whether each panel labels its y axis.
    pub y_labels: Vec<bool>,
    /// How far x and y tick labels may reach past a panel's plot and still leave a gap to the
    /// neighbour's labels.
    pub overhang: (f64, f64),
    /// The background, drawn first.
    pub under: Vec<Item>,
    /// Title, caption, headers, axis titles and legends, drawn after the panels.
    pub over: Vec<Item>,
}

/// Lay out the panels of `split` on the canvas of `chart` (its `size` filled in).
pub fn layout(
    chart: &Chart,
    split: &Split,
    axes: Option<&GridAxes<'_>>,
    legends: &[Legend],
) -> Result<GridLayout, MarkError> {
    let [width, height] = chart.size.unwrap_or(crate::mark::FRAME_SIZE);
    let theme = Theme::with_font_size(chart.font_size.unwrap_or(12.0));
    let m = theme.margin;
    let (nr, nc) = split.grid;
    let header = theme.label_size * 1.7;
    let title_h = chart.title.as_ref().map_or(0.0, |_| theme.title_size * 1.8);
    let caption_h = chart.caption.as_ref().map_or(0.0, |_| theme.caption_size * 1.8);
    let top = m + title_h;
    let room = (height - top - caption_h - m).max(0.0);
    let legend_w = legend::stack_width(legends, &theme, room);
    let legend_room = legend::stack_room(legends, &theme, room);
    let row_strip = if split.row_field.is_some() && !split.wrapped { header } else { 0.0 };
    // Headers above every grid row when wrapped, above the first only in a grid.
    let header_above = |i: usize| match (split.wrapped, split.column_field.is_some()) {
        (true, _) => header,
        (false, true) if i == 0 => header,
        _ => 0.0,
    };
    let headers_total: f64 = (0..nr).map(header_above).sum();

    // The axes' room depends on the panel size and the panel size on the room: two passes.
    let mut panel = (width / nc as f64, height / nr as f64);
    let (mut left, mut bottom, mut hgap, mut vgap) = (m, m + caption_h, theme.font_size, theme.font_size);
    for _ in 0..2 {
        if let Some(a) = axes {
            let canvas = [width, height];
            left = m + axis_room(a.y, Side::Left, panel.1, Some(&a.y.title), &theme, canvas);
            // Turned category labels under the first panel lean left past it.
            left = left.max(m + labels_before(a.x, Side::Bottom, panel.0, &theme, canvas));
            bottom = m + caption_h + axis_room(a.x, Side::Bottom, panel.0, Some(&a.x.title), &theme, canvas);
            let y_labels = axis_room(a.y, Side::Left, panel.1, None, &theme, canvas);
            let x_labels = axis_room(a.x, Side::Bottom, panel.0, None, &theme, canvas);
            // End labels of neighbouring x axes meet in the gap: it is as wide as the widest label.
            let x_label = widest_tick_label(a.x, Side::Bottom, panel.0, &theme, canvas) + theme.font_size;
            hgap = if a.y_independent { y_labels + theme.font_size * 1.5 } else { theme.font_size * 2.0 };
            hgap = hgap.max(x_label);
            vgap = if a.x_independent { x_labels + theme.font_size * 0.5 } else { theme.font_size * 1.3 };
        }
        let free_w = width - left - m - legend_room - row_strip - (nc - 1) as f64 * hgap;
        let free_h = height - top - bottom - headers_total - (nr - 1) as f64 * vgap;
        panel = (free_w / nc as f64, free_h / nr as f64);
    }
    let (pw, ph) = (panel.0.floor(), panel.1.floor());
    if pw < MIN_PLOT_SIDE * 2.0 || ph < MIN_PLOT_SIDE * 2.0 {
        return Err(MarkError::at(
            &["size"],
            format!(
                "the canvas is too small for {nr} × {nc} facet panels: each would have a {:.0}×{:.0} px plot",
                pw.max(0.0),
                ph.max(0.0)
            ),
            "make `size` larger (or leave it out to fit the panels), or facet by a column with fewer values",
        ));
    }

    let mut row_tops = Vec::with_capacity(nr);
    let mut y = top;
    for i in 0..nr {
        y += header_above(i);
        row_tops.push(y.round());
        y += ph + vgap;
    }
    let col_left = |j: usize| (left + j as f64 * (pw + hgap)).round();
    let areas: Vec<Rect> =
        split.panels.iter().map(|p| Rect::new(col_left(p.cell.1), row_tops[p.cell.0], pw, ph)).collect();
    // Outer axes: the lowest panel of each grid column labels x, the first of each grid row y.
    let lowest = |c: usize| split.panels.iter().filter(|p| p.cell.1 == c).map(|p| p.cell.0).max();
    let first = |r: usize| split.panels.iter().filter(|p| p.cell.0 == r).map(|p| p.cell.1).min();
    let independent = |f: fn(&GridAxes<'_>) -> bool| axes.is_some_and(f);
    let x_labels =
        split.panels.iter().map(|p| independent(|a| a.x_independent) || lowest(p.cell.1) == Some(p.cell.0)).collect();
    let y_labels =
        split.panels.iter().map(|p| independent(|a| a.y_independent) || first(p.cell.0) == Some(p.cell.1)).collect();

    let under = vec![Item::new(
        Role::Background,
        Shape::Rect(Rect::new(0.0, 0.0, width, height)),
        Style::fill(theme.background),
    )];
    let mut over = title_and_caption(chart, &theme, m, None);
    let text = |at: Point, content: String, anchor: Anchor, angle: f64| Text {
        at,
        content,
        size: theme.label_size,
        anchor,
        baseline: Baseline::Bottom,
        angle,
        color: theme.text,
    };
    let header_item = |t: Text| Item::text(Role::Annotation, t).labelled("facet header");
    let mut column_header = |p: &super::split::PanelRows, x: f64, y: f64| {
        if let Some(h) = split.column_header(p) {
            let content = truncate_to_width(&h, pw, theme.label_size);
            over.push(header_item(text(Point::new(x + pw / 2.0, y - header * 0.3), content, Anchor::Middle, 0.0)));
        }
    };
    if split.wrapped {
        for (p, area) in split.panels.iter().zip(&areas) {
            column_header(p, area.x, area.y);
        }
    } else {
        for j in 0..nc {
            if let Some(p) = split.panels.iter().find(|p| p.cell.1 == j) {
                column_header(p, col_left(j), row_tops[0]);
            }
        }
    }
    if row_strip > 0.0 {
        let right = col_left(nc - 1) + pw;
        for (i, &row_top) in row_tops.iter().enumerate() {
            let Some(p) = split.panels.iter().find(|p| p.cell.0 == i) else { continue };
            let Some(h) = split.row_header(p) else { continue };
            let content = truncate_to_width(&h, ph, theme.label_size);
            let at = Point::new(right + header * 0.3, row_top + ph / 2.0);
            over.push(header_item(text(at, content, Anchor::Middle, 90.0)));
        }
    }
    if let Some(a) = axes {
        let grid_left = left;
        let grid_right = col_left(nc - 1) + pw;
        let grid_top = row_tops[0];
        let grid_bottom = row_tops[nr - 1] + ph;
        let x_title = Text {
            at: Point::new((grid_left + grid_right) / 2.0, height - m - caption_h),
            baseline: Baseline::Bottom,
            ..text(Point::new(0.0, 0.0), a.x.title.clone(), Anchor::Middle, 0.0)
        };
        let y_title = Text {
            at: Point::new(m, (grid_top + grid_bottom) / 2.0),
            baseline: Baseline::Top,
            ..text(Point::new(0.0, 0.0), a.y.title.clone(), Anchor::Middle, -90.0)
        };
        for (t, name) in [(x_title, "x axis"), (y_title, "y axis")] {
            if !t.content.trim().is_empty() {
                over.push(Item::text(Role::AxisTitle, t).labelled(name));
            }
        }
    }
    over.extend(legend::draw_stack(legends, Point::new(width - m - legend_w, top), &theme, room));
    Ok(GridLayout {
        areas,
        x_labels,
        y_labels,
        overhang: (hgap / 2.0 - theme.font_size * 0.3, vgap / 2.0 - theme.font_size * 0.1),
        under,
        over,
    })
}

/// The canvas size of a faceted chart when the spec gives none: room for each panel, the
/// headers and the legends.
pub fn default_size(split: &Split, cartesian: bool, legends: bool) -> [f64; 2] {
    let (nr, nc) = split.grid;
    let (panel_w, panel_h) = if cartesian { (250.0, 220.0) } else { (320.0, 320.0) };
    let legend_w = if legends { 140.0 } else { 0.0 };
    let row_headers = if split.row_field.is_some() && !split.wrapped { 24.0 } else { 0.0 };
    let width = 100.0 + nc as f64 * panel_w + legend_w + row_headers;
    let height = 120.0 + nr as f64 * (panel_h + 24.0);
    [width.min(4000.0), height.min(4000.0)]
}
