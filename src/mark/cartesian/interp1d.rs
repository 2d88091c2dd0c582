//! `interp1d`: sample points (knots) and the curves that 1D interpolation methods draw through
//! them, overlaid with a legend so the reader sees what each method makes up between samples.

use crate::data::Table;
use crate::enrich::interp1d::{Interp1dError, Interpolant, Method, Slopes};
use crate::guide::layout::Domain;
use crate::guide::legend::{Legend, Symbol};
use crate::guide::scale::Scale;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::registry::{AxisSpec, ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Color, Item, PathCmd, PerPoint, Point, PointBatch, Role, Shape, Stroke, Style};
use crate::spec::{Channel, Chart};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "interp1d"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct Interp1dOptions {
    /// The knots' positions: a numeric column (rows are sorted by it; values must be distinct).
    pub x: Channel,
    /// The knots' values: a numeric column.
    pub y: Channel,
    /// Interpolation methods to overlay (default `["pchip"]`).
    #[serde(default)]
    pub methods: Option<Vec<InterpMethod>>,
    /// Column of slopes dy/dx at the knots, used by the `hermite` method.
    #[serde(default)]
    pub slopes: Option<String>,
    /// Keep `hermite` and `hermite-mean` curves within the range of neighbouring data.
    #[serde(default)]
    pub bounded: Option<bool>,
    /// Points per curve in the derived CSV and on non-linear scales (default 512).
    #[serde(default)]
    #[schemars(range(min = 2, max = 100000))]
    pub samples: Option<u32>,
    /// Draw the knots as points (default true).
    #[serde(default)]
    pub knots: Option<bool>,
    /// Line width in pixels, at most 100 (default 2).
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 100))]
    pub stroke_width: Option<f64>,
    /// Categorical colour scheme for the methods (default `okabe-ito`).
    #[serde(default)]
    pub scheme: Option<String>,
}

/// 1D interpolation methods.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum InterpMethod {
    /// Nearest neighbour: steps at the midpoints between knots.
    Nearest,
    /// Straight lines between knots.
    Linear,
    /// Cubic Hermite with the slopes given by the `slopes` column.
    Hermite,
    /// Cubic Hermite with slopes from the arithmetic mean of the adjacent chord slopes.
    HermiteMean,
    /// Cubic Hermite with harmonic-mean slopes (monotone; matches SciPy's PchipInterpolator).
    Pchip,
}

/// Default number of samples per curve.
pub const DEFAULT_SAMPLES: usize = 512;

/// The legend label of a method.
pub fn method_label(method: InterpMethod) -> &'static str {
    match method {
        InterpMethod::Nearest => "nearest neighbour",
        InterpMethod::Linear => "linear",
        InterpMethod::Hermite => "cubic, given slopes",
        InterpMethod::HermiteMean => "cubic, mean slopes",
        InterpMethod::Pchip => "PCHIP (monotone)",
    }
}

/// The spec name of a method (as written in `methods`).
pub fn method_name(method: InterpMethod) -> &'static str {
    match method {
        InterpMethod::Nearest => "nearest",
        InterpMethod::Linear => "linear",
        InterpMethod::Hermite => "hermite",
        InterpMethod::HermiteMean => "hermite-mean",
        InterpMethod::Pchip => "pchip",
    }
}

/// Draw an interp1d chart.
pub fn draw(chart: &Chart, options: &Interp1dOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let x_opts = options.x.options();
    let y_opts = options.y.options();
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    let methods = options.methods.clone().unwrap_or_else(|| vec![InterpMethod::Pchip]);
    if methods.is_empty() {
        return Err(MarkError::at(
            &["methods"],
            format!("`methods` is empty"),
            "name at least one method, e.g. methods = [\"linear\", \"pchip\"]",
        ));
    }
    let needs_slopes = methods.contains(&InterpMethod::Hermite);
    let slope_col = match (&options.slopes, needs_slopes) {
        (Some(field), _) => Some(encode::column(chart, "slopes", field, table)?),
        (None, true) => {
            return Err(MarkError::at(
                &["methods"],
                format!("method `hermite` needs the slopes at the knots"),
                "add `slopes = \"COLUMN\"` naming a column of dy/dx values, or use \"hermite-mean\" or \"pchip\"",
            ));
        }
        (None, false) => None,
    };
    for (key, field, col) in [("x", &x_opts.field, Some(x_col)), ("y", &y_opts.field, Some(y_col))]
        .into_iter()
        .chain(std::iter::once(("slopes", options.slopes.as_ref().unwrap_or(&y_opts.field), slope_col)))
    {
        if let Some(col) = col.filter(|c| c.numbers().is_none()) {
            return Err(MarkError::at(
                &[key],
                format!("column `{field}` holds {}; interpolation needs numbers", col.type_name()),
                "use a numeric column",
            ));
        }
    }

    let mut numeric = vec![(x_opts.field.as_str(), x_col), (y_opts.field.as_str(), y_col)];
    if let (Some(col), Some(field)) = (slope_col, &options.slopes) {
        numeric.push((field.as_str(), col));
    }
    let log = encode::log_fields(&[&x_opts, &y_opts]);
    let (rows, warning) = encode::placeable_rows(&chart.name, table.rows, &numeric, &log);
    let mut warnings: Vec<Warning> = warning.into_iter().collect();
    if rows.is_empty() {
        return Err(encode::no_rows(chart, table, warnings.first()));
    }
    let pick = |col: &crate::data::Column| encode::values_at(col, &rows);
    let xs = pick(x_col);
    let ys = pick(y_col);
    let given = slope_col.map(pick);
    let bounded = options.bounded.unwrap_or(false);

    let mut curves = Vec::new();
    for &m in &methods {
        let method = match m {
            InterpMethod::Nearest => Method::Nearest,
            InterpMethod::Linear => Method::Linear,
            InterpMethod::Hermite => Method::Hermite(Slopes::Given(given.clone().unwrap_or_default())),
            InterpMethod::HermiteMean => Method::Hermite(Slopes::ArithmeticMean),
            InterpMethod::Pchip => Method::Hermite(Slopes::HarmonicMean),
        };
        let interpolant = Interpolant::new(&xs, &ys, method, bounded).map_err(|e| interp_error(&e))?;
        curves.push((m, interpolant));
    }

    let samples = options.samples.map(|s| s as usize).unwrap_or(DEFAULT_SAMPLES).clamp(2, 100_000);
    let sampled: Vec<Vec<(f64, f64)>> = curves.iter().map(|(_, c)| c.sample(samples)).collect();
    // The y axis must show the curves' overshoot as well as the knots.
    let (mut lo, mut hi) = encode::extent(&ys, &(0..ys.len() as u32).collect::<Vec<_>>()).unwrap_or((0.0, 1.0));
    for (_, y) in sampled.iter().flatten() {
        if y.is_finite() {
            lo = lo.min(*y);
            hi = hi.max(*y);
        }
    }
    let palette = encode::palette(&["scheme"], options.scheme.as_deref())?;
    let colors: Vec<Color> =
        (0..curves.len()).map(|i| palette.get(i % palette.len().max(1)).copied().unwrap_or(Color::BLACK)).collect();
    let stroke_width = options.stroke_width.unwrap_or(2.0);
    let knot_radius = 3.5;

    let mut x_axis = encode::position_axis("x", &x_opts, x_col, &rows)?;
    let mut y_axis = encode::position_axis("y", &y_opts, y_col, &rows)?;
    if y_opts.domain.is_none() {
        y_axis.domain = Domain::Continuous(lo, hi);
    }
    x_axis.inset = knot_radius + 1.0;
    y_axis.inset = knot_radius + 1.0;
    let legend = Legend::Categorical {
        title: "Interpolation".into(),
        entries: curves.iter().zip(&colors).map(|((m, _), c)| (method_label(*m).to_string(), *c)).collect(),
        symbol: Symbol::Line,
    };
    let (frame, theme) = frame::cartesian(chart, x_axis, y_axis, vec![legend])?;

    let affine = is_affine(&frame.x) && is_affine(&frame.y);
    let to_px = |x: f64, y: f64| Point::new(frame.x.map(x), frame.y.map(y));
    let mut marks = Vec::new();
    for (((method, curve), color), samples) in curves.iter().zip(&colors).zip(&sampled) {
        let cmds = match method {
            InterpMethod::Nearest => steps(curve, &to_px),
            InterpMethod::Linear => polyline(curve.x().iter().copied().zip(curve.y().iter().copied()), &to_px),
            _ if affine => hermite_beziers(curve, &to_px),
            _ => polyline(samples.iter().copied(), &to_px),
        };
        marks.push(
            Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(*color, stroke_width))
                .with_rows(rows.clone())
                .labelled(method_label(*method)),
        );
    }
    if options.knots.unwrap_or(true) {
        let centers = xs.iter().zip(&ys).map(|(&x, &y)| to_px(x, y)).collect();
        marks.push(
            Item::new(
                Role::DataMark,
                Shape::Points(PointBatch {
                    centers,
                    radius: PerPoint::Uniform(knot_radius),
                    fill: PerPoint::Uniform(Color::rgb(0x22, 0x22, 0x22)),
                    stroke: Some(Stroke::solid(Color::WHITE, 1.0)),
                }),
                Style::default(),
            )
            .with_rows(rows.clone())
            .labelled("knots"),
        );
    }
    let scene = frame::scene(chart, frame, &theme, marks, &mut warnings);

    let mut derived = Derived::default();
    derived.push(
        "method",
        DerivedColumn::Text(
            curves
                .iter()
                .zip(&sampled)
                .flat_map(|((m, _), s)| std::iter::repeat_n(method_name(*m).to_string(), s.len()))
                .collect(),
        ),
    );
    derived.push(&x_opts.field, DerivedColumn::Number(sampled.iter().flatten().map(|p| p.0).collect()));
    derived.push(&y_opts.field, DerivedColumn::Number(sampled.iter().flatten().map(|p| p.1).collect()));
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

/// Whether the scale maps data to pixels by an affine function (so Bézier curves map exactly).
fn is_affine(scale: &Scale) -> bool {
    matches!(scale, Scale::Linear(_) | Scale::Time(_))
}

fn interp_error(e: &Interp1dError) -> MarkError {
    let key = match e {
        Interp1dError::SlopesLength { .. } => "slopes",
        Interp1dError::NonFinite { column, .. } if column.contains("slope") => "slopes",
        _ => "x",
    };
    MarkError::at(&[key], format!("{e}"), "check the knots: x values must be distinct and there must be at least two")
}

fn polyline(points: impl Iterator<Item = (f64, f64)>, to_px: &impl Fn(f64, f64) -> Point) -> Vec<PathCmd> {
    let mut cmds = Vec::new();
    for (i, (x, y)) in points.filter(|(x, y)| x.is_finite() && y.is_finite()).enumerate() {
        let p = to_px(x, y);
        cmds.push(if i == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) });
    }
    cmds
}

/// Nearest neighbour as exact steps: each knot's value holds out to the midpoints.
fn steps(curve: &Interpolant, to_px: &impl Fn(f64, f64) -> Point) -> Vec<PathCmd> {
    let (x, y) = (curve.x(), curve.y());
    let mut cmds = Vec::new();
    for i in 0..x.len() {
        let start = if i == 0 { x[0] } else { (x[i - 1] + x[i]) / 2.0 };
        let end = if i + 1 == x.len() { x[i] } else { (x[i] + x[i + 1]) / 2.0 };
        let a = to_px(start, y[i]);
        cmds.push(if i == 0 { PathCmd::MoveTo(a) } else { PathCmd::LineTo(a) });
        cmds.push(PathCmd::LineTo(to_px(end, y[i])));
    }
    cmds
}

/// A cubic Hermite piece on [x0, x1] is a cubic Bézier with control points at thirds of the
/// interval along the end tangents; under affine scales the drawn curve is exact.
fn hermite_beziers(curve: &Interpolant, to_px: &impl Fn(f64, f64) -> Point) -> Vec<PathCmd> {
    let (x, y, d) = (curve.x(), curve.y(), curve.slopes());
    let mut cmds = Vec::with_capacity(x.len());
    if let (Some(&x0), Some(&y0)) = (x.first(), y.first()) {
        cmds.push(PathCmd::MoveTo(to_px(x0, y0)));
    }
    for i in 0..x.len().saturating_sub(1) {
        let (Some(&d0), Some(&d1)) = (d.get(i), d.get(i + 1)) else { break };
        let h = x[i + 1] - x[i];
        cmds.push(PathCmd::CubicTo(
            to_px(x[i] + h / 3.0, y[i] + d0 * h / 3.0),
            to_px(x[i + 1] - h / 3.0, y[i + 1] - d1 * h / 3.0),
            to_px(x[i + 1], y[i + 1]),
        ));
    }
    cmds
}

/// `kind = "interp1d"`.
pub static KIND: KindInfo = KindInfo::new("interp1d", &["x", "y", "slopes"]).taking_aspect().drawing_annotations();

impl Technique for Interp1dOptions {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bezier_control_points_reproduce_the_hermite_cubic() {
        // A cubic Bézier with these control points equals the Hermite piece at every t.
        let xs = [0.0, 1.0, 3.0];
        let ys = [0.0, 2.0, 1.0];
        let c = Interpolant::new(&xs, &ys, Method::Hermite(Slopes::HarmonicMean), false).expect("pchip");
        let id = |x: f64, y: f64| Point::new(x, y);
        let cmds = hermite_beziers(&c, &id);
        let mut start = Point::new(0.0, 0.0);
        for cmd in &cmds {
            match *cmd {
                PathCmd::MoveTo(p) => start = p,
                PathCmd::CubicTo(p1, p2, p3) => {
                    for k in 0..=10 {
                        let t = k as f64 / 10.0;
                        let u = 1.0 - t;
                        let bx =
                            u * u * u * start.x + 3.0 * u * u * t * p1.x + 3.0 * u * t * t * p2.x + t * t * t * p3.x;
                        let by =
                            u * u * u * start.y + 3.0 * u * u * t * p1.y + 3.0 * u * t * t * p2.y + t * t * t * p3.y;
                        assert!((c.eval(bx) - by).abs() < 1e-12, "t={t}: {} vs {by}", c.eval(bx));
                    }
                    start = p3;
                }
                _ => panic!("unexpected command"),
            }
        }
    }

    #[test]
    fn nearest_steps_jump_at_midpoints() {
        let c = Interpolant::new(&[0.0, 2.0, 4.0], &[1.0, 3.0, 2.0], Method::Nearest, false).expect("nearest");
        let cmds = steps(&c, &|x, y| Point::new(x, y));
        let pts: Vec<Point> = cmds
            .iter()
            .map(|c| match *c {
                PathCmd::MoveTo(p) | PathCmd::LineTo(p) => p,
                _ => Point::new(f64::NAN, f64::NAN),
            })
            .collect();
        let expect = [(0.0, 1.0), (1.0, 1.0), (1.0, 3.0), (3.0, 3.0), (3.0, 2.0), (4.0, 2.0)];
        assert_eq!(pts.len(), expect.len());
        for (p, e) in pts.iter().zip(expect) {
            assert_eq!((p.x, p.y), e);
        }
    }
}
