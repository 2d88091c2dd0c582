//! The frame of a cartesian chart: title, caption, axes and legends placed around a plot area
//! whose size is what remains of the canvas once every guide has room.

use std::fmt;

use super::Theme;
use super::axis::{self, AxisLabels, LabelRoom, Side};
use super::legend::{self, Legend, truncate_to_width};
use super::scale::{BandScale, LinearScale, LogScale, Scale, ScaleError, TimeScale};
use crate::scene::{Anchor, Baseline, Item, Point, Rect, Role, Shape, Style, Text};
use crate::spec::ScaleKind;
use crate::text::measure;

/// The smallest plot area (either side, in pixels) a chart may be left with.
pub const MIN_PLOT_SIDE: f64 = 24.0;

/// The data extent of a positional axis.
#[derive(Clone, Debug, PartialEq)]
pub enum Domain {
    /// Numbers or instants (ms since the epoch): the smallest and largest value.
    Continuous(f64, f64),
    /// Categories in display order.
    Categories(Vec<String>),
}

/// One positional axis of a cartesian chart, as resolved from the spec and the data.
#[derive(Clone, Debug, PartialEq)]
pub struct PositionAxis {
    /// Axis title including its unit.
    pub title: String,
    /// Scale type.
    pub kind: ScaleKind,
    /// Data extent.
    pub domain: Domain,
    /// Extend the domain to nice ticks.
    pub nice: bool,
    /// Requested tick count, if any.
    pub ticks: Option<u32>,
    /// Draw grid lines.
    pub grid: bool,
    /// Pixels kept free at both ends of the axis so marks at the extremes are not cut by the
    /// plot's clip (e.g. the largest marker radius). Ignored by band scales.
    pub inset: f64,
}

/// Everything a cartesian frame needs.
#[derive(Clone, Debug)]
pub struct FrameSpec {
    /// Canvas width.
    pub width: f64,
    /// Canvas height.
    pub height: f64,
    /// Chart title.
    pub title: Option<String>,
    /// Caption under the chart.
    pub caption: Option<String>,
    /// Horizontal axis.
    pub x: PositionAxis,
    /// Vertical axis.
    pub y: PositionAxis,
    /// Legends stacked on the right.
    pub legends: Vec<Legend>,
    /// Sizes and colours.
    pub theme: Theme,
    /// One data unit as long on x as on y: the plot shrinks along one axis, centred.
    pub equal_aspect: bool,
    /// A plot area placed by someone else (a facet panel's): no title, caption, legends or
    /// axis titles are drawn, and the axes are labelled only where asked.
    pub fixed: Option<FixedPlot>,
}

/// A facet panel's plot area, placed on the whole canvas by the facet layout.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedPlot {
    /// The plot area.
    pub plot: Rect,
    /// Whether the x axis has tick labels (else only its line and tick marks).
    pub x_labels: bool,
    /// Whether the y axis has tick labels (else only its line and tick marks).
    pub y_labels: bool,
    /// How far x and y tick labels may reach past the plot's ends (half the gap to the next
    /// panel across and along).
    pub overhang: (f64, f64),
}

/// A laid-out frame: the plot area, its scales, and the guide items to draw under and over the data.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The plot area.
    pub plot: Rect,
    /// Horizontal scale, mapping into the plot area.
    pub x: Scale,
    /// Vertical scale, mapping into the plot area (upwards).
    pub y: Scale,
    /// Background and grid, drawn before the data.
    pub under: Vec<Item>,
    /// Axes, titles, caption and legends, drawn after the data.
    pub over: Vec<Item>,
    /// The chart's annotations in pixels, drawn with the data (empty from [`cartesian`]; the
    /// kind's frame fills it).
    pub overlay: Overlay,
    /// What the reader should know about the frame, worded for the chart's warnings (category
    /// labels left out for lack of room).
    pub notes: Vec<String>,
    /// Where the legend column was drawn: its top-left corner and the height it had.
    pub legend_column: (Point, f64),
}

impl Frame {
    /// Draw `legends` in place of the ones drawn in the legend column (for a kind whose legend
    /// depends on the plot area, e.g. a density's counts; they must not be wider than those the
    /// frame was laid out with).
    pub fn redraw_legends(&mut self, legends: &[Legend], theme: &Theme) {
        self.over.retain(|item| item.role != Role::Legend);
        let (at, room) = self.legend_column;
        self.over.extend(legend::draw_stack(legends, at, theme, room));
    }
}

/// Notes drawn with the data (a chart's `annotate`), resolved to pixels: shapes under and over
/// the data, both clipped to the plot, and text labels, each given as the placements it may take,
/// best first (the drawing picks the first clear of other text).
#[derive(Clone, Debug, Default)]
pub struct Overlay {
    /// Drawn under the data (shaded bands).
    pub under: Vec<Item>,
    /// Drawn over the data (rules, arrows).
    pub over: Vec<Item>,
    /// Text items, each as its candidate placements in order of preference.
    pub labels: Vec<Vec<Item>>,
}

/// Why a frame could not be laid out.
#[derive(Debug, Clone, PartialEq)]
pub enum LayoutError {
    /// An axis' scale could not be built.
    Scale {
        /// "x" or "y".
        axis: &'static str,
        /// The scale's error.
        error: ScaleError,
    },
    /// `aspect = "equal"` over an axis that is not linear.
    AspectNeedsLinear,
    /// The guides leave no room for the plot.
    TooSmall {
        /// Plot width left.
        plot_width: f64,
        /// Plot height left.
        plot_height: f64,
    },
}

impl fmt::Display for LayoutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LayoutError::Scale { axis, error } => write!(f, "{axis} axis: {error}"),
            LayoutError::AspectNeedsLinear => {
                write!(f, "`aspect = \"equal\"` needs two linear axes (not log, time or categories)")
            }
            LayoutError::TooSmall { plot_width, plot_height } => write!(
                f,
                "the canvas is too small: titles, axes and legends leave a {plot_width:.0}×{plot_height:.0} px plot area (at least {MIN_PLOT_SIDE} px each way is needed)"
            ),
        }
    }
}

impl std::error::Error for LayoutError {}

/// Build a scale for an axis over a pixel range.
pub fn build_scale(axis: &PositionAxis, range: (f64, f64), target: usize) -> Result<Scale, ScaleError> {
    let target = axis.ticks.map(|t| t as usize).unwrap_or(target).clamp(2, 50);
    let inset = if axis.inset.is_finite() { axis.inset.clamp(0.0, (range.1 - range.0).abs() / 4.0) } else { 0.0 };
    let dir = if range.1 >= range.0 { 1.0 } else { -1.0 };
    let inner = (range.0 + dir * inset, range.1 - dir * inset);
    match (&axis.domain, axis.kind) {
        (Domain::Categories(cats), _) => Ok(Scale::Band(BandScale::new(cats.clone(), range, 0.2, 0.1)?)),
        (Domain::Continuous(lo, hi), ScaleKind::Log) => {
            Ok(Scale::Log(LogScale::new((*lo, *hi), inner, axis.nice)?.with_tick_target(target)))
        }
        (Domain::Continuous(lo, hi), ScaleKind::Time) => Ok(Scale::Time(TimeScale::new((*lo, *hi), inner, target)?)),
        (Domain::Continuous(lo, hi), _) => Ok(Scale::Linear(LinearScale::new((*lo, *hi), inner, axis.nice, target)?)),
    }
}

fn x_target(length: f64, theme: &Theme) -> usize {
    ((length / (theme.font_size * 7.0)).round() as usize).clamp(2, 10)
}

fn y_target(length: f64, theme: &Theme) -> usize {
    ((length / (theme.font_size * 4.0)).round() as usize).clamp(2, 10)
}

/// Height of a one-line text block at `size` with some breathing room.
fn line_block(size: f64) -> f64 {
    let m = measure("Ag", size);
    (m.ascent + m.descent) * 1.35
}

/// Shrink `plot` along one axis, centred, so one data unit has the same length on both. The
/// shrunk axis' scale is rebuilt for its new length (fewer ticks may give a different nice
/// domain) until the domains settle; the final scales keep those domains exactly.
fn equal_aspect(spec: &FrameSpec, full: Rect, x: Scale, y: Scale) -> Result<(Rect, Scale, Scale), LayoutError> {
    let linear = |a: &PositionAxis| matches!(a.domain, Domain::Continuous(..)) && a.kind == ScaleKind::Linear;
    if !linear(&spec.x) || !linear(&spec.y) {
        return Err(LayoutError::AspectNeedsLinear);
    }
    let theme = &spec.theme;
    let span = |s: &Scale| {
        let (lo, hi) = s.domain();
        (hi - lo).abs().max(f64::MIN_POSITIVE)
    };
    // The largest plot inside `full` with as many pixels per unit on x as on y (the insets
    // `build_scale` keeps free at both ends are not part of the data's length).
    let shrink = |x: &Scale, y: &Scale| {
        let inset =
            |a: &PositionAxis, length: f64| if a.inset.is_finite() { a.inset.clamp(0.0, length / 4.0) } else { 0.0 };
        let (ix, iy) = (inset(&spec.x, full.w), inset(&spec.y, full.h));
        let per_unit = ((full.w - 2.0 * ix) / span(x)).min((full.h - 2.0 * iy) / span(y));
        let (w, h) = ((per_unit * span(x) + 2.0 * ix).min(full.w), (per_unit * span(y) + 2.0 * iy).min(full.h));
        let plot = Rect::new((full.x + (full.w - w) / 2.0).round(), (full.y + (full.h - h) / 2.0).round(), w, h);
        match plot.w < MIN_PLOT_SIDE || plot.h < MIN_PLOT_SIDE {
            true => Err(LayoutError::TooSmall { plot_width: plot.w, plot_height: plot.h }),
            false => Ok(plot),
        }
    };
    let scales = |x: &PositionAxis, y: &PositionAxis, plot: Rect| {
        let sx = build_scale(x, (plot.x, plot.right()), x_target(plot.w, theme))
            .map_err(|error| LayoutError::Scale { axis: "x", error })?;
        let sy = build_scale(y, (plot.bottom(), plot.y), y_target(plot.h, theme))
            .map_err(|error| LayoutError::Scale { axis: "y", error })?;
        Ok::<_, LayoutError>((sx, sy))
    };
    let (mut x, mut y) = (x, y);
    for _ in 0..4 {
        let (nx, ny) = scales(&spec.x, &spec.y, shrink(&x, &y)?)?;
        let settled = nx.domain() == x.domain() && ny.domain() == y.domain();
        (x, y) = (nx, ny);
        if settled {
            break;
        }
    }
    // Size the plot for the domains the scales ended with and keep those domains exactly.
    let plot = shrink(&x, &y)?;
    let fixed = |a: &PositionAxis, s: &Scale| {
        let (lo, hi) = s.domain();
        PositionAxis { domain: Domain::Continuous(lo, hi), nice: false, ..a.clone() }
    };
    let (x, y) = scales(&fixed(&spec.x, &x), &fixed(&spec.y, &y), plot)?;
    Ok((plot, x, y))
}

/// The tick labels `axis` gets along a side `length` pixels long of a plot on a `canvas`
/// (width, height), placed as if the plot started at 0; `None` when its scale cannot be built.
fn side_labels(axis: &PositionAxis, side: Side, length: f64, theme: &Theme, canvas: [f64; 2]) -> Option<AxisLabels> {
    let target = match side {
        Side::Bottom => x_target(length, theme),
        Side::Left => y_target(length, theme),
    };
    let range = match side {
        Side::Bottom => (0.0, length.max(1.0)),
        Side::Left => (length.max(1.0), 0.0),
    };
    let scale = build_scale(axis, range, target).ok()?;
    Some(axis::labels(&scale, side, theme, &LabelRoom::on_canvas(side, canvas[0], canvas[1], theme)))
}

/// How far the tick labels (and the title, when given) of `axis` reach outside a plot side
/// `length` pixels long on a `canvas` (width, height): the room a facet layout keeps beside its
/// outer panels.
pub fn axis_room(
    axis: &PositionAxis,
    side: Side,
    length: f64,
    title: Option<&str>,
    theme: &Theme,
    canvas: [f64; 2],
) -> f64 {
    match side_labels(axis, side, length, theme, canvas) {
        Some(labels) => axis::labels_thickness(&labels, side, title, theme),
        None => theme.font_size * 3.0,
    }
}

/// How far before the start of a plot side `length` pixels long (left of the plot for a bottom
/// axis) the tick labels of `axis` reach: turned category labels lean left past the plot.
pub fn labels_before(axis: &PositionAxis, side: Side, length: f64, theme: &Theme, canvas: [f64; 2]) -> f64 {
    side_labels(axis, side, length, theme, canvas)
        .and_then(|labels| labels.along(side, theme))
        .map_or(0.0, |(lo, _)| (-lo).max(0.0))
}

/// The widest the tick labels of `axis` reach along a side `length` pixels long (see
/// [`AxisLabels::widest_along`]): the gap small multiples keep between panels so their end
/// labels do not meet.
pub fn widest_tick_label(axis: &PositionAxis, side: Side, length: f64, theme: &Theme, canvas: [f64; 2]) -> f64 {
    side_labels(axis, side, length, theme, canvas).map_or(0.0, |labels| labels.widest_along(side, theme))
}

/// The note for a chart whose category axis on `side` leaves labels out, if it does.
fn left_out_note(labels: &AxisLabels, side: Side, scale: &Scale, theme: &Theme) -> Option<String> {
    if labels.left_out == 0 {
        return None;
    }
    let (name, room) = match side {
        Side::Bottom => ("x", "`size` wider"),
        Side::Left => ("y", "`size` taller"),
    };
    let total = labels.left_out + labels.labels.len();
    let step = match scale {
        Scale::Band(b) => b.step(),
        _ => 0.0,
    };
    Some(format!(
        "{} of {total} category labels on the {name} axis are left out: the categories are {step:.1} px apart, \
         too close for {}-px labels even when turned upright; make {room}, `font_size` smaller, or show fewer categories",
        labels.left_out, theme.font_size
    ))
}

/// The frame of a facet panel: scales over its fixed plot area, grid, and axes labelled only
/// on the sides asked for.
fn fixed_frame(spec: &FrameSpec, fixed: FixedPlot) -> Result<Frame, LayoutError> {
    let theme = &spec.theme;
    let mut plot = fixed.plot;
    if plot.w < MIN_PLOT_SIDE || plot.h < MIN_PLOT_SIDE {
        return Err(LayoutError::TooSmall { plot_width: plot.w.max(0.0), plot_height: plot.h.max(0.0) });
    }
    let mut x = build_scale(&spec.x, (plot.x, plot.right()), x_target(plot.w, theme))
        .map_err(|error| LayoutError::Scale { axis: "x", error })?;
    let mut y = build_scale(&spec.y, (plot.bottom(), plot.y), y_target(plot.h, theme))
        .map_err(|error| LayoutError::Scale { axis: "y", error })?;
    if spec.equal_aspect {
        (plot, x, y) = equal_aspect(spec, plot, x, y)?;
    }
    let mut under = vec![Item::new(Role::Background, Shape::Rect(plot), Style::fill(theme.background))];
    if spec.x.grid {
        under.extend(axis::grid(&x, Side::Bottom, plot, theme));
    }
    if spec.y.grid {
        under.extend(axis::grid(&y, Side::Left, plot, theme));
    }
    let mut over = Vec::new();
    let mut notes = Vec::new();
    let (ox, oy) = fixed.overhang;
    let spans = [(plot.x - ox, plot.right() + ox), (plot.y - oy, plot.bottom() + oy)];
    for ((scale, side, labelled), span) in
        [(&x, Side::Bottom, fixed.x_labels), (&y, Side::Left, fixed.y_labels)].into_iter().zip(spans)
    {
        if !labelled {
            over.extend(axis::draw_unlabelled(scale, side, plot, theme));
            continue;
        }
        let room = LabelRoom::on_canvas(side, spec.width, spec.height, theme).within(span);
        let labels = axis::labels(scale, side, theme, &room);
        notes.extend(left_out_note(&labels, side, scale, theme));
        over.extend(axis::draw_labels(&labels, side, plot, None, theme));
    }
    Ok(Frame {
        plot,
        x,
        y,
        under,
        over,
        overlay: Overlay::default(),
        notes,
        legend_column: (Point::new(0.0, 0.0), 0.0),
    })
}

/// Lay out a cartesian chart.
pub fn cartesian(spec: &FrameSpec) -> Result<Frame, LayoutError> {
    if let Some(fixed) = spec.fixed {
        return fixed_frame(spec, fixed);
    }
    let theme = &spec.theme;
    let m = theme.margin;
    let title = spec.title.as_deref().filter(|t| !t.trim().is_empty());
    let caption = spec.caption.as_deref().filter(|t| !t.trim().is_empty());
    let top = m + title.map(|_| line_block(theme.title_size) + theme.font_size * 0.4).unwrap_or(theme.font_size * 0.5);
    let bottom_reserved = m + caption.map(|_| line_block(theme.caption_size)).unwrap_or(0.0);
    let legend_room = (spec.height - top - bottom_reserved).max(0.0);
    let legend_width = legend::stack_width(&spec.legends, theme, legend_room);
    let right = m + legend::stack_room(&spec.legends, theme, legend_room);

    let x_title = Some(spec.x.title.as_str());
    let y_title = Some(spec.y.title.as_str());
    let x_room = LabelRoom::on_canvas(Side::Bottom, spec.width, spec.height, theme);
    let y_room = LabelRoom::on_canvas(Side::Left, spec.width, spec.height, theme);
    // Two passes: tick labels depend on the scale, the scale on the space left by the labels.
    let mut left = m + theme.font_size * 4.0;
    let mut bottom = bottom_reserved + theme.font_size * 3.0;
    let mut right_overhang = 0.0;
    let mut plot = Rect::new(0.0, 0.0, 0.0, 0.0);
    let mut scales = None;
    for _ in 0..3 {
        plot = Rect::new(left, top, spec.width - left - right - right_overhang, spec.height - top - bottom);
        if plot.w < MIN_PLOT_SIDE || plot.h < MIN_PLOT_SIDE {
            return Err(LayoutError::TooSmall { plot_width: plot.w.max(0.0), plot_height: plot.h.max(0.0) });
        }
        let x = build_scale(&spec.x, (plot.x, plot.right()), x_target(plot.w, theme))
            .map_err(|error| LayoutError::Scale { axis: "x", error })?;
        let y = build_scale(&spec.y, (plot.bottom(), plot.y), y_target(plot.h, theme))
            .map_err(|error| LayoutError::Scale { axis: "y", error })?;
        let x_labels = axis::labels(&x, Side::Bottom, theme, &x_room);
        left = m + axis::thickness(&y, Side::Left, y_title, theme, &y_room);
        bottom = bottom_reserved + axis::labels_thickness(&x_labels, Side::Bottom, x_title, theme);
        let (before, after) = match x_labels.along(Side::Bottom, theme) {
            Some((lo, hi)) => ((plot.x - lo).max(0.0), (hi - plot.right()).max(0.0)),
            None => (0.0, 0.0),
        };
        // Turned category labels lean left of the plot: keep them on the canvas.
        left = left.max(m + before);
        right_overhang = match x_labels.labels.last() {
            Some(l) if x_labels.angle == 0.0 => {
                let widest = l.lines.iter().map(|s| measure(s, theme.font_size).width).fold(0.0, f64::max);
                (widest / 2.0 - (plot.right() - l.tick.position)).max(0.0)
            }
            _ => after,
        };
        scales = Some((x, y));
    }
    // Whole-pixel edges: crisp axis lines, and clipping to the plot is a plain bounds check.
    let (x0, y0) = (left.ceil(), top.ceil());
    let (x1, y1) = ((spec.width - right - right_overhang).floor(), (spec.height - bottom).floor());
    let final_plot = Rect::new(x0, y0, x1 - x0, y1 - y0);
    if final_plot.w < MIN_PLOT_SIDE || final_plot.h < MIN_PLOT_SIDE {
        return Err(LayoutError::TooSmall { plot_width: final_plot.w.max(0.0), plot_height: final_plot.h.max(0.0) });
    }
    if final_plot != plot || scales.is_none() {
        plot = final_plot;
        let x = build_scale(&spec.x, (plot.x, plot.right()), x_target(plot.w, theme))
            .map_err(|error| LayoutError::Scale { axis: "x", error })?;
        let y = build_scale(&spec.y, (plot.bottom(), plot.y), y_target(plot.h, theme))
            .map_err(|error| LayoutError::Scale { axis: "y", error })?;
        scales = Some((x, y));
    }
    let Some((mut x, mut y)) = scales else {
        return Err(LayoutError::TooSmall { plot_width: 0.0, plot_height: 0.0 });
    };
    if spec.equal_aspect {
        (plot, x, y) = equal_aspect(spec, plot, x, y)?;
    }

    let mut under = vec![Item::new(
        Role::Background,
        Shape::Rect(Rect::new(0.0, 0.0, spec.width, spec.height)),
        Style::fill(theme.background),
    )];
    if spec.x.grid {
        under.extend(axis::grid(&x, Side::Bottom, plot, theme));
    }
    if spec.y.grid {
        under.extend(axis::grid(&y, Side::Left, plot, theme));
    }

    let mut over = Vec::new();
    let mut notes = Vec::new();
    for (scale, side, title, room) in [(&x, Side::Bottom, x_title, &x_room), (&y, Side::Left, y_title, &y_room)] {
        let labels = axis::labels(scale, side, theme, room);
        notes.extend(left_out_note(&labels, side, scale, theme));
        over.extend(axis::draw_labels(&labels, side, plot, title, theme));
    }
    if let Some(t) = title {
        over.push(Item::text(
            Role::Title,
            Text {
                at: Point::new(m, m),
                content: truncate_to_width(t, spec.width - 2.0 * m, theme.title_size),
                size: theme.title_size,
                anchor: Anchor::Start,
                baseline: Baseline::Top,
                angle: 0.0,
                color: theme.text,
            },
        ));
    }
    if let Some(c) = caption {
        over.push(Item::text(
            Role::Caption,
            Text {
                at: Point::new(m, spec.height - m),
                content: truncate_to_width(c, spec.width - 2.0 * m, theme.caption_size),
                size: theme.caption_size,
                anchor: Anchor::Start,
                baseline: Baseline::Bottom,
                angle: 0.0,
                color: theme.muted_text,
            },
        ));
    }
    let legend_at = Point::new(spec.width - m - legend_width, top);
    over.extend(legend::draw_stack(&spec.legends, legend_at, theme, legend_room));
    Ok(Frame { plot, x, y, under, over, overlay: Overlay::default(), notes, legend_column: (legend_at, legend_room) })
}
