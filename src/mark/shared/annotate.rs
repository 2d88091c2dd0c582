//! Annotations over a cartesian plot (a chart's `[[chart.annotate]]`): rules and shaded bands
//! across the plot, text at data points and arrows, written in the data's own values.
//!
//! [`widen`] stretches the axes' domains to take them in before the frame is laid out,
//! [`resolve`] places them through the frame's scales (a value an axis cannot place is an error
//! at `annotate[i]`), and [`draw`] turns them into the items drawn under the data (bands) and
//! over it (rules, arrows, labels), each label at the first of its candidate places that is
//! clear of other text and lines ([`place`]).

mod place;

use crate::data::time::parse_iso;
use crate::guide::Theme;
use crate::guide::color::parse_color;
use crate::guide::layout::{Domain, Frame, Overlay, PositionAxis};
use crate::guide::scale::Scale;
use crate::mark::{MarkError, technique};
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Rect, Role, Shape, Stroke, Style, Text};
use crate::spec::annotation::{AxisValue, Form, FormError, PlotAxis, TextAnchor};
use crate::spec::source::display_path;
use crate::spec::validate::shorten;
use crate::spec::{Chart, PathSeg, ScaleKind};

/// Lines, arrows and bands without a `color`.
const INK: Color = Color::rgb(0x4d, 0x4d, 0x4d);
/// A band's fill opacity without `opacity`.
const BAND_OPACITY: f64 = 0.15;
/// Width of rules and arrow shafts.
const LINE_WIDTH: f64 = 1.5;
/// Dash pattern of `dash = true`.
const DASH: [f64; 2] = [6.0, 4.0];
/// Between a line (or a band's edge, or an arrow's tail) and its label.
const GAP: f64 = 4.0;
/// Between the plot's edge and a label.
const INSET: f64 = 4.0;
/// Length of an arrowhead.
const HEAD: f64 = 9.0;
/// Opacity of the background-coloured patch under each label, which keeps it legible over data.
const BACKDROP_OPACITY: f64 = 0.75;
/// Most places tried along a line for its label, beyond its two ends.
const MAX_SLIDES: usize = 12;
/// Item labels of annotations start with this (`annotate[2] rule`).
const NAME: &str = "annotate[";

/// Widen the continuous x and y domains to take in every annotation value, so rules, bands, text
/// and arrows lie inside the plot. An axis whose channel fixes its `domain` keeps it (the spec's,
/// or the explorer's zoom), and what lies outside is cut off at the plot's edge like data; values
/// an axis cannot place are left to [`resolve`] to report.
pub fn widen(chart: &Chart, x: &mut PositionAxis, y: &mut PositionAxis) {
    if chart.annotate.is_empty() {
        return;
    }
    for (axis, position) in [(PlotAxis::X, x), (PlotAxis::Y, y)] {
        if fixed_domain(chart, axis).is_some() {
            continue;
        }
        let kind = position.kind;
        let Domain::Continuous(lo, hi) = &mut position.domain else { continue };
        let forms = chart.annotate.iter().filter_map(|a| a.form().ok());
        for v in forms.flat_map(|f| values_on(f, axis)).filter_map(|v| number(v, kind)) {
            (*lo, *hi) = (lo.min(v), hi.max(v));
        }
    }
}

/// The chart's annotations in the pixels of `frame`: bands under the data, rules and arrows over
/// it, and labels with the places each may take (none for a rule, note or arrow tail outside a
/// fixed domain, whose lines the plot's clip cuts off). A value an axis cannot place (a category
/// it does not show, text that is not a date on a time axis, text on a numeric axis) is an error
/// at its place in the spec, e.g. `annotate[2].x`.
pub fn resolve(chart: &Chart, frame: &Frame, theme: &Theme) -> Result<Overlay, MarkError> {
    let mut overlay = Overlay::default();
    for (i, note) in chart.annotate.iter().enumerate() {
        let here = Here { frame, index: i };
        let form = note.form().map_err(|e| here.form_error(e))?;
        let color = match &note.color {
            None => None,
            Some(c) => Some(parse_color(c).ok_or_else(|| {
                here.error(
                    &["color"],
                    format!("`{}` is not a colour", shorten(c)),
                    "use a CSS colour name such as \"firebrick\" or a hex colour such as \"#b22222\"",
                )
            })?),
        };
        let look = Look {
            name: format!("{NAME}{i}]"),
            line: color.unwrap_or(INK),
            // A label reads in the theme's ink whatever the colour of its line or band (a light
            // colour that shades a band well is too pale for text); a note is text in its colour.
            text: match form {
                Form::Text(..) => color.unwrap_or(theme.text),
                _ => theme.text,
            },
            dash: if note.dash == Some(true) { DASH.to_vec() } else { Vec::new() },
            size: theme.font_size,
        };
        let label = note.label.as_deref().filter(|l| !l.trim().is_empty());
        match form {
            Form::Rule(axis, v) => {
                let at = here.along(axis, v, &[PathSeg::from(axis.key())])?.mid;
                overlay.over.push(look.rule(axis, at, frame.plot));
                let shown = label.filter(|_| visible(frame.plot, axis, (at, at)).is_some());
                overlay.labels.extend(shown.map(|l| look.beside(l, axis, (at, at), frame.plot)));
            }
            Form::Band(axis, [a, b]) => {
                let key = PathSeg::from(axis.key());
                let (a, b) = (
                    here.along(axis, a, &[key.clone(), PathSeg::Index(0)])?,
                    here.along(axis, b, &[key, PathSeg::Index(1)])?,
                );
                let (lo, hi) = (a.lo.min(b.lo), a.hi.max(b.hi));
                let opacity = note.opacity.filter(|o| o.is_finite()).unwrap_or(BAND_OPACITY);
                overlay.under.push(look.band(axis, (lo, hi), frame.plot, opacity));
                if let (Some(l), Some(part)) = (label, visible(frame.plot, axis, (lo, hi))) {
                    overlay.labels.push(look.beside(l, axis, part, frame.plot));
                }
            }
            Form::Text(text, at) => {
                let point = here.point(at, &[PathSeg::from("at")])?;
                let anchor = match note.anchor.unwrap_or_default() {
                    TextAnchor::Start => Anchor::Start,
                    TextAnchor::Middle => Anchor::Middle,
                    TextAnchor::End => Anchor::End,
                };
                if contains(frame.plot, point) {
                    overlay.labels.push(vec![look.text(text, point, anchor, Baseline::Middle)]);
                }
            }
            Form::Arrow([from, to]) => {
                let arrow = |k: usize| [PathSeg::from("arrow"), PathSeg::Index(k)];
                let (tail, head) = (here.point(from, &arrow(0))?, here.point(to, &arrow(1))?);
                if (head.x - tail.x).hypot(head.y - tail.y) < 1.0 {
                    return Err(here.error(
                        &["arrow"],
                        "the arrow's two points are less than a pixel apart",
                        "give the tail (first point) and the head (second point) different values",
                    ));
                }
                overlay.over.extend(look.arrow(tail, head));
                let shown = label.filter(|_| contains(frame.plot, tail));
                overlay.labels.extend(shown.map(|l| look.at_tail(l, tail, head)));
            }
        }
    }
    Ok(overlay)
}

/// What annotations add to a chart's scene.
pub struct Layers {
    /// Drawn after the grid, before the data: the bands, clipped to the plot.
    pub under: Option<Item>,
    /// Drawn after the data: rules and arrows clipped to the plot, then the labels.
    pub over: Vec<Item>,
}

/// The items of `overlay` for a chart whose plot is `plot` on `canvas`, each label placed clear of
/// the other labels, of the text in `drawn` (the marks and the guides) and of the annotation
/// lines, inside the plot when there is room. Notes written at a data point have one place and
/// are placed first, so the other labels keep clear of them.
pub fn draw(overlay: Overlay, plot: Rect, canvas: Rect, theme: &Theme, drawn: &[&[Item]]) -> Layers {
    if overlay.labels.is_empty() && overlay.under.is_empty() && overlay.over.is_empty() {
        return Layers { under: None, over: Vec::new() };
    }
    let mut obstacles = place::Obstacles::new(drawn, &overlay.over);
    let mut order: Vec<usize> = (0..overlay.labels.len()).collect();
    order.sort_by_key(|&k| overlay.labels[k].len() > 1);
    let mut placed: Vec<Option<Item>> = vec![None; overlay.labels.len()];
    for k in order {
        placed[k] = obstacles.place(&overlay.labels[k], plot, canvas);
    }
    let mut labels = Vec::new();
    for item in placed.into_iter().flatten() {
        if let Shape::Text(t) = &item.shape {
            let b = crate::text::bounds(t);
            let patch = Rect::new(b.x - 2.0, b.y - 1.0, b.w + 4.0, b.h + 2.0);
            let fill = Style::fill(theme.background.with_opacity(BACKDROP_OPACITY));
            let name = item.label.as_deref().map_or(String::new(), |l| l.replace(" label", " backdrop"));
            labels.push(Item::new(Role::Annotation, Shape::Rect(patch), fill).labelled(name));
        }
        labels.push(item);
    }
    let group = |items: Vec<Item>, clip, name: &str| Item::group(Role::Annotation, items, clip).labelled(name);
    let under = (!overlay.under.is_empty()).then(|| group(overlay.under, Some(plot), "annotations under the data"));
    let mut over = Vec::new();
    if !overlay.over.is_empty() {
        over.push(group(overlay.over, Some(plot), "annotations"));
    }
    if !labels.is_empty() {
        over.push(group(labels, None, "annotation labels"));
    }
    Layers { under, over }
}

/// Whether an item was drawn for a chart's `annotate` (and not by its kind).
pub fn is_note(item: &Item) -> bool {
    item.label.as_deref().is_some_and(|l| l.starts_with(NAME))
}

/// The part of pixels `lo..=hi` across `axis` that lies inside `plot` (half a pixel of slack),
/// if any.
fn visible(plot: Rect, axis: PlotAxis, (lo, hi): (f64, f64)) -> Option<(f64, f64)> {
    let (start, end) = match axis {
        PlotAxis::X => (plot.x, plot.right()),
        PlotAxis::Y => (plot.y, plot.bottom()),
    };
    let (lo, hi) = (lo.min(hi).max(start), lo.max(hi).min(end));
    (lo <= hi + 0.5).then_some((lo.min(hi), hi.max(lo)))
}

/// Whether `p` lies inside `plot` (half a pixel of slack).
fn contains(plot: Rect, p: Point) -> bool {
    plot.contains_rect(&Rect::new(p.x, p.y, 0.0, 0.0), 0.5)
}

/// The `domain` a chart's channel fixes for the plot's `axis`, if it fixes one.
fn fixed_domain(chart: &Chart, axis: PlotAxis) -> Option<[f64; 2]> {
    let name = match axis {
        PlotAxis::X => "x axis",
        PlotAxis::Y => "y axis",
    };
    technique(&chart.kind).cartesian_axes().into_iter().find(|a| a.name == name)?.options.domain
}

/// The values an annotation places along `axis`.
fn values_on(form: Form<'_>, axis: PlotAxis) -> Vec<&AxisValue> {
    let k = usize::from(axis == PlotAxis::Y);
    match form {
        Form::Rule(a, v) if a == axis => vec![v],
        Form::Band(a, [lo, hi]) if a == axis => vec![lo, hi],
        Form::Rule(..) | Form::Band(..) => Vec::new(),
        Form::Text(_, at) => at.get(k).into_iter().collect(),
        Form::Arrow(points) => points.iter().filter_map(|p| p.get(k)).collect(),
    }
}

/// A value as a number on a continuous axis of `kind` (a date in ms on a time axis), if it is one
/// that axis can show.
fn number(v: &AxisValue, kind: ScaleKind) -> Option<f64> {
    match (v, kind) {
        (AxisValue::Number(n), ScaleKind::Linear) => Some(*n),
        (AxisValue::Number(n), ScaleKind::Log) if *n > 0.0 => Some(*n),
        (AxisValue::Text(t), ScaleKind::Time) => parse_iso(t),
        _ => None,
    }
    .filter(|n| n.is_finite())
}

/// A value written as in the spec, for messages: `50`, `"2014-13-01"`.
fn written(v: &AxisValue) -> String {
    match v {
        AxisValue::Number(n) => format!("{n}"),
        AxisValue::Text(t) => format!("\"{}\"", shorten(t)),
    }
}

/// The pixels a value covers along an axis: one pixel (`lo = mid = hi`), or a category's band.
#[derive(Clone, Copy, Debug)]
struct Along {
    lo: f64,
    mid: f64,
    hi: f64,
}

/// Annotation number `index`, placed in `frame`: where its errors point.
struct Here<'a> {
    frame: &'a Frame,
    index: usize,
}

impl Here<'_> {
    /// The spec path of `rest` inside this annotation.
    fn path(&self, rest: &[PathSeg]) -> Vec<PathSeg> {
        let mut path = vec![PathSeg::from("annotate"), PathSeg::Index(self.index)];
        path.extend_from_slice(rest);
        path
    }

    /// An error at `keys` inside this annotation, its message led by their path.
    fn error(&self, keys: &[&str], message: impl AsRef<str>, hint: impl Into<String>) -> MarkError {
        let rest: Vec<PathSeg> = keys.iter().map(|&k| PathSeg::from(k)).collect();
        self.error_at(&rest, message, hint)
    }

    fn error_at(&self, rest: &[PathSeg], message: impl AsRef<str>, hint: impl Into<String>) -> MarkError {
        let path = self.path(rest);
        MarkError::at_path(path.clone(), format!("{}: {}", display_path(&path), message.as_ref()), hint)
    }

    /// The annotation's keys make no one form.
    fn form_error(&self, e: FormError) -> MarkError {
        let rest: Vec<PathSeg> = e.key.map(PathSeg::from).into_iter().collect();
        let path = self.path(&rest);
        let shown = display_path(&self.path(&[]));
        MarkError::at_path(path, format!("{shown} {}", e.message), e.hint)
    }

    /// A data point `[x, y]` (at `rest`) in pixels.
    fn point(&self, at: &[AxisValue; 2], rest: &[PathSeg]) -> Result<Point, MarkError> {
        let key = |k: usize| {
            let mut path = rest.to_vec();
            path.push(PathSeg::Index(k));
            path
        };
        let [x, y] = at;
        Ok(Point::new(self.along(PlotAxis::X, x, &key(0))?.mid, self.along(PlotAxis::Y, y, &key(1))?.mid))
    }

    /// Where the value `v` (at `rest`) lies along `axis`, or why it cannot be placed there.
    fn along(&self, axis: PlotAxis, v: &AxisValue, rest: &[PathSeg]) -> Result<Along, MarkError> {
        let name = axis.key();
        let scale = match axis {
            PlotAxis::X => &self.frame.x,
            PlotAxis::Y => &self.frame.y,
        };
        let fail = |message: String, hint: String| Err(self.error_at(rest, message, hint));
        let shown = written(v);
        let n = match (scale, v) {
            (Scale::Band(bands), _) => {
                let category = match v {
                    AxisValue::Text(t) => t.clone(),
                    AxisValue::Number(n) => format!("{n}"),
                };
                let Some(i) = bands.band_of(&category) else {
                    let names: Vec<&str> = bands.categories().iter().map(String::as_str).collect();
                    let hint =
                        crate::spec::suggest::hint(&category, &names, &format!("categories on the {name} axis"), true);
                    return fail(format!("`{shown}` is not a category of the {name} axis"), hint);
                };
                let lo = bands.start(i);
                return Ok(Along { lo, mid: bands.center(i), hi: lo + bands.bandwidth() });
            }
            (Scale::Time(_), AxisValue::Text(t)) => match parse_iso(t) {
                Some(ms) => ms,
                None => {
                    let hint =
                        "write an ISO 8601 date such as \"2014-06-01\" or a date-time such as \"2014-06-01T12:00\"";
                    return fail(format!("`{shown}` is not a date"), hint.into());
                }
            },
            (Scale::Time(_), AxisValue::Number(_)) => {
                let hint = format!("write the date as text, e.g. `{name} = \"2014-06-01\"`");
                return fail(format!("`{shown}` is a number, but the {name} axis shows dates"), hint);
            }
            (_, AxisValue::Text(_)) => {
                let hint = format!("write a number, e.g. `{name} = 50`");
                return fail(format!("`{shown}` is text, but the {name} axis is numeric"), hint);
            }
            (Scale::Log(_), AxisValue::Number(n)) if *n <= 0.0 => {
                return fail(
                    format!("`{shown}` is not above 0, so the log {name} axis cannot show it"),
                    "move it above 0, or drop the annotation".into(),
                );
            }
            (_, AxisValue::Number(n)) => *n,
        };
        let px = scale.map(n);
        Ok(Along { lo: px, mid: px, hi: px })
    }
}

/// How one annotation is drawn: its name (the items' label prefix), colours, dash and text size.
struct Look {
    name: String,
    line: Color,
    text: Color,
    dash: Vec<f64>,
    size: f64,
}

/// Which side of a coordinate a label lies on: towards smaller pixels or larger ones.
#[derive(Clone, Copy)]
enum Side {
    Before,
    After,
}

impl Side {
    fn anchor(self) -> Anchor {
        match self {
            Side::Before => Anchor::End,
            Side::After => Anchor::Start,
        }
    }

    fn baseline(self) -> Baseline {
        match self {
            Side::Before => Baseline::Bottom,
            Side::After => Baseline::Top,
        }
    }
}

impl Look {
    fn stroke(&self) -> Stroke {
        Stroke { color: self.line, width: LINE_WIDTH, dash: self.dash.clone() }
    }

    /// A line across the plot at pixel `at` of `axis` (a rule at y = v runs horizontally).
    fn rule(&self, axis: PlotAxis, at: f64, plot: Rect) -> Item {
        let (a, b) = match axis {
            PlotAxis::Y => (Point::new(plot.x, at), Point::new(plot.right(), at)),
            PlotAxis::X => (Point::new(at, plot.y), Point::new(at, plot.bottom())),
        };
        let style = Style { fill: None, stroke: Some(self.stroke()) };
        Item::new(Role::Annotation, Shape::Path(vec![PathCmd::MoveTo(a), PathCmd::LineTo(b)]), style)
            .labelled(format!("{} rule", self.name))
    }

    /// A band across the plot over pixels `lo..hi` of `axis`.
    fn band(&self, axis: PlotAxis, (lo, hi): (f64, f64), plot: Rect, opacity: f64) -> Item {
        let rect = match axis {
            PlotAxis::Y => Rect::new(plot.x, lo.min(hi), plot.w, (hi - lo).abs()),
            PlotAxis::X => Rect::new(lo.min(hi), plot.y, (hi - lo).abs(), plot.h),
        };
        Item::new(Role::Annotation, Shape::Rect(rect), Style::fill(self.line.with_opacity(opacity)))
            .labelled(format!("{} band", self.name))
    }

    /// A shaft from `tail` to just short of `head`, and a filled arrowhead at `head`.
    fn arrow(&self, tail: Point, head: Point) -> Vec<Item> {
        let len = (head.x - tail.x).hypot(head.y - tail.y);
        let (ux, uy) = ((head.x - tail.x) / len, (head.y - tail.y) / len);
        let h = HEAD.min(len / 1.5);
        let base = Point::new(head.x - ux * h, head.y - uy * h);
        let (nx, ny) = (-uy * h * 0.45, ux * h * 0.45);
        let shaft = vec![PathCmd::MoveTo(tail), PathCmd::LineTo(base)];
        let tip = vec![
            PathCmd::MoveTo(head),
            PathCmd::LineTo(Point::new(base.x + nx, base.y + ny)),
            PathCmd::LineTo(Point::new(base.x - nx, base.y - ny)),
            PathCmd::Close,
        ];
        vec![
            Item::new(Role::Annotation, Shape::Path(shaft), Style { fill: None, stroke: Some(self.stroke()) })
                .labelled(format!("{} arrow", self.name)),
            Item::new(Role::Annotation, Shape::Path(tip), Style::fill(self.line))
                .labelled(format!("{} arrowhead", self.name)),
        ]
    }

    /// Text at `at`.
    fn text(&self, content: &str, at: Point, anchor: Anchor, baseline: Baseline) -> Item {
        let text =
            Text { at, content: content.to_owned(), size: self.size, anchor, baseline, angle: 0.0, color: self.text };
        Item::text(Role::Annotation, text).labelled(format!("{} label", self.name))
    }

    /// The places of the label of a rule (`lo == hi`) or band over pixels `lo..hi` of `axis`,
    /// best first: at the right end of a horizontal line, then its left end, then along it; at
    /// the top of a vertical line, then its bottom, then down it.
    fn beside(&self, content: &str, axis: PlotAxis, (lo, hi): (f64, f64), plot: Rect) -> Vec<Item> {
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        // A rule's label goes above it (horizontal) or to its right (vertical), else across it;
        // a band's inside its edges, else outside them.
        // Places across the line, in groups tried along the whole line one after the other: a
        // rule's label above it (horizontal) or right of it (vertical), else across it; a band's
        // inside its edges anywhere along it before outside them.
        let across = match (hi - lo < 1.0, axis) {
            (true, PlotAxis::Y) => vec![vec![(lo - GAP, Side::Before), (hi + GAP, Side::After)]],
            (true, PlotAxis::X) => vec![vec![(hi + GAP, Side::After), (lo - GAP, Side::Before)]],
            (false, _) => vec![
                vec![(lo + GAP, Side::After), (hi - GAP, Side::Before)],
                vec![(lo - GAP, Side::Before), (hi + GAP, Side::After)],
            ],
        };
        let m = crate::text::measure(content, self.size);
        let along: Vec<(f64, Side)> = match axis {
            PlotAxis::Y => {
                let step = m.width + 2.0 * INSET;
                let slides = (1..=MAX_SLIDES)
                    .map(|k| plot.right() - INSET - k as f64 * step)
                    .take_while(|x| x - m.width >= plot.x + INSET)
                    .map(|x| (x, Side::Before));
                [(plot.right() - INSET, Side::Before), (plot.x + INSET, Side::After)]
                    .into_iter()
                    .chain(slides)
                    .collect()
            }
            PlotAxis::X => {
                let step = (m.ascent + m.descent) * 1.2;
                let rows = (1..=MAX_SLIDES)
                    .map(|k| plot.y + INSET + k as f64 * step)
                    .take_while(|y| y + step <= plot.bottom() - INSET)
                    .map(|y| (y, Side::After));
                [(plot.y + INSET, Side::After), (plot.bottom() - INSET, Side::Before)].into_iter().chain(rows).collect()
            }
        };
        let place = |(a, a_side): (f64, Side), (c, c_side): (f64, Side)| match axis {
            PlotAxis::Y => self.text(content, Point::new(a, c), a_side.anchor(), c_side.baseline()),
            PlotAxis::X => self.text(content, Point::new(c, a), c_side.anchor(), a_side.baseline()),
        };
        across
            .iter()
            .flat_map(|group| along.iter().flat_map(move |&a| group.iter().map(move |&c| place(a, c))))
            .collect()
    }

    /// The places of an arrow's label in the eight directions around its tail, the one facing
    /// most directly away from the head first.
    fn at_tail(&self, content: &str, tail: Point, head: Point) -> Vec<Item> {
        let (dx, dy) = (head.x - tail.x, head.y - tail.y);
        let toward_head = |&(ux, uy): &(f64, f64)| (ux * dx + uy * dy) / ux.hypot(uy);
        let units = [-1.0, 0.0, 1.0];
        let mut around: Vec<(f64, f64)> =
            units.iter().flat_map(|&ux| units.map(|uy| (ux, uy))).filter(|&u| u != (0.0, 0.0)).collect();
        around.sort_by(|a, b| toward_head(a).total_cmp(&toward_head(b)));
        let sign = |v: f64| if v < 0.0 { Side::Before } else { Side::After };
        around
            .iter()
            .map(|&(ux, uy)| {
                let n = ux.hypot(uy);
                let at = Point::new(tail.x + ux / n * GAP, tail.y + uy / n * GAP);
                let anchor = if ux == 0.0 { Anchor::Middle } else { sign(ux).anchor() };
                let baseline = if uy == 0.0 { Baseline::Middle } else { sign(uy).baseline() };
                self.text(content, at, anchor, baseline)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart(annotate: serde_json::Value) -> Chart {
        let spec = serde_json::json!({
            "name": "c", "data": "d", "kind": "scatter", "x": "x",
            "y": { "field": "y", "domain": [0, 10] }, "annotate": annotate,
        });
        serde_json::from_value(spec).expect("a scatter chart")
    }

    fn axis(kind: ScaleKind, domain: Domain) -> PositionAxis {
        PositionAxis { title: "t".into(), kind, domain, nice: true, ticks: None, grid: true, inset: 0.0 }
    }

    #[test]
    fn domains_widen_to_the_values_they_can_show() {
        let c = chart(serde_json::json!([
            { "x": [-5, 2] },
            { "text": "a", "at": [40, 99] },
            { "arrow": [[3, 4], [60, 5]] },
            { "x": "not a number" },
        ]));
        let mut x = axis(ScaleKind::Linear, Domain::Continuous(0.0, 10.0));
        let mut y = axis(ScaleKind::Linear, Domain::Continuous(0.0, 10.0));
        widen(&c, &mut x, &mut y);
        assert_eq!(x.domain, Domain::Continuous(-5.0, 60.0));
        assert_eq!(y.domain, Domain::Continuous(0.0, 10.0), "y fixes its domain");
        let mut cats = axis(ScaleKind::Band, Domain::Categories(vec!["a".into()]));
        let mut time = axis(ScaleKind::Time, Domain::Continuous(0.0, 1.0));
        let c = chart(serde_json::json!([{ "x": "1970-01-02" }, { "x": "someday" }]));
        widen(&c, &mut time, &mut cats);
        assert_eq!(time.domain, Domain::Continuous(0.0, 86_400_000.0));
        let mut log = axis(ScaleKind::Log, Domain::Continuous(1.0, 10.0));
        widen(&chart(serde_json::json!([{ "x": 0 }, { "x": 1000 }])), &mut log, &mut cats);
        assert_eq!(log.domain, Domain::Continuous(1.0, 1000.0), "a log axis cannot take 0 in");
    }

    #[test]
    fn rule_labels_start_at_the_right_end_above_the_line() {
        let look = Look { name: "annotate[0]".into(), line: INK, text: INK, dash: Vec::new(), size: 12.0 };
        let plot = Rect::new(50.0, 20.0, 400.0, 300.0);
        let choices = look.beside("target", PlotAxis::Y, (100.0, 100.0), plot);
        let Shape::Text(first) = &choices[0].shape else { panic!("text") };
        assert_eq!((first.at, first.anchor, first.baseline), (Point::new(446.0, 96.0), Anchor::End, Baseline::Bottom));
        let Shape::Text(second) = &choices[1].shape else { panic!("text") };
        assert_eq!((second.at.y, second.baseline), (104.0, Baseline::Top), "then below");
        assert!(choices.len() > 4, "then along the line");
        let vertical = look.beside("then", PlotAxis::X, (200.0, 200.0), plot);
        let Shape::Text(top) = &vertical[0].shape else { panic!("text") };
        assert_eq!((top.at, top.anchor, top.baseline), (Point::new(204.0, 24.0), Anchor::Start, Baseline::Top));
        let arrow = look.at_tail("from here", Point::new(100.0, 100.0), Point::new(200.0, 120.0));
        let Shape::Text(away) = &arrow[0].shape else { panic!("text") };
        assert_eq!((away.at, away.anchor), (Point::new(96.0, 100.0), Anchor::End), "left of a tail pointing right");
    }
}
