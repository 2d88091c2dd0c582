//! Trend lines drawn over a cartesian plot: the least-squares line (with its equation and R²
//! written in the plot) or a LOESS curve, through all drawn points or one per colour category.

use crate::data::Column;
use crate::enrich::regression::{LinearFit, linear_fit, loess};
use crate::guide::Theme;
use crate::guide::layout::Frame;
use crate::guide::scale::Scale;
use crate::mark::MarkError;
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Role, Shape, Stroke, Style, Text};
use crate::spec::{TrendMethod, TrendOptions};

/// Colour of a trend line through all points.
const TREND_INK: Color = Color::rgb(0x33, 0x33, 0x33);
/// Points at which a LOESS curve is evaluated.
const LOESS_POINTS: usize = 100;
/// Length of the line swatch before an equation, in pixels.
const SWATCH: f64 = 14.0;
/// The default LOESS span.
pub const DEFAULT_SPAN: f64 = 0.75;

/// The points a trend is fitted to.
pub struct Fitted<'a> {
    /// The x column.
    pub x: &'a Column,
    /// The y column.
    pub y: &'a Column,
    /// The drawn rows.
    pub rows: &'a [u32],
    /// With `groups`: each row's group and the groups' labels and colours.
    pub groups: Option<&'a (Vec<usize>, Vec<(String, Color)>)>,
}

/// The trend lines (and, for linear fits, their equations) over `frame`.
pub fn marks(
    options: &TrendOptions,
    fitted: &Fitted<'_>,
    frame: &Frame,
    theme: &Theme,
) -> Result<Vec<Item>, MarkError> {
    for (key, scale) in [("x", &frame.x), ("y", &frame.y)] {
        if matches!(scale, Scale::Log(_) | Scale::Band(_)) {
            return Err(MarkError::at(
                &["trend"],
                format!("a trend line is fitted on linear axes, but {key} is not linear"),
                "remove `scale = \"log\"` from the axis, or the trend",
            ));
        }
    }
    let (xv, yv) = (fitted.x.numbers().unwrap_or(&[]), fitted.y.numbers().unwrap_or(&[]));
    let sets: Vec<(String, Color, Vec<(f64, f64)>)> = match fitted.groups {
        Some((of_row, groups)) => groups
            .iter()
            .enumerate()
            .map(|(g, (label, color))| {
                let points = fitted
                    .rows
                    .iter()
                    .zip(of_row)
                    .filter(|(_, gr)| **gr == g)
                    .map(|(&r, _)| (xv[r as usize], yv[r as usize]))
                    .collect();
                (label.clone(), *color, points)
            })
            .collect(),
        None => {
            vec![(String::new(), TREND_INK, fitted.rows.iter().map(|&r| (xv[r as usize], yv[r as usize])).collect())]
        }
    };
    let show_equation =
        options.method == TrendMethod::Linear && options.equation.unwrap_or(true) && !fitted.x.is_time();
    let mut items = Vec::new();
    let mut equations = Vec::new();
    for (label, color, mut points) in sets {
        points.retain(|(x, y)| x.is_finite() && y.is_finite());
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (Some(first), Some(last)) = (points.first(), points.last()) else { continue };
        let (x0, x1) = (first.0, last.0);
        let name = if label.is_empty() { "trend".to_string() } else { format!("trend: {label}") };
        let curve: Vec<(f64, f64)> = match options.method {
            TrendMethod::Linear => {
                let Some(fit) = linear_fit(&points) else { continue };
                equations.push((equation(&label, &fit), color, fit.slope));
                vec![(x0, fit.at(x0)), (x1, fit.at(x1))]
            }
            TrendMethod::Loess => {
                let at: Vec<f64> =
                    (0..LOESS_POINTS).map(|i| x0 + (x1 - x0) * i as f64 / (LOESS_POINTS - 1) as f64).collect();
                let ys = loess(&points, options.span.unwrap_or(DEFAULT_SPAN), &at);
                at.into_iter().zip(ys).collect()
            }
        };
        let cmds: Vec<PathCmd> = curve
            .iter()
            .filter(|(_, y)| y.is_finite())
            .enumerate()
            .map(|(i, &(x, y))| {
                let p = Point::new(frame.x.map(x), frame.y.map(y));
                if i == 0 { PathCmd::MoveTo(p) } else { PathCmd::LineTo(p) }
            })
            .collect();
        if cmds.len() < 2 {
            continue;
        }
        let tooltip = match equations.last().filter(|_| options.method == TrendMethod::Linear) {
            Some((text, _, _)) => text.clone(),
            None => format!("{name} (LOESS, span {})", options.span.unwrap_or(DEFAULT_SPAN)),
        };
        // A white halo under the line keeps it visible over dense points.
        items.push(
            Item::new(
                Role::Annotation,
                Shape::Path(cmds.clone()),
                Style { fill: None, stroke: Some(Stroke::solid(Color::WHITE.with_opacity(0.8), 4.0)) },
            )
            .labelled(format!("{name} halo")),
        );
        items.push(
            Item::new(
                Role::Annotation,
                Shape::Path(cmds),
                Style { fill: None, stroke: Some(Stroke::solid(color, 2.0)) },
            )
            .labelled(name)
            .with_tooltip(tooltip),
        );
    }
    if show_equation {
        let size = theme.font_size;
        // Falling lines leave the top right emptier, rising ones the top left.
        let falling = equations.iter().all(|(_, _, slope)| *slope < 0.0);
        for (k, (text, color, _)) in equations.into_iter().enumerate() {
            // Text in the theme's ink (legible on the background); a swatch of the line's colour
            // before it says which line it describes.
            let width = crate::text::measure(&text, size).width;
            let left = if falling { frame.plot.right() - 6.0 - width - SWATCH - 4.0 } else { frame.plot.x + 6.0 };
            let y = frame.plot.y + 6.0 + k as f64 * (size * 1.3);
            let mid = y + size * 0.55;
            let swatch = vec![PathCmd::MoveTo(Point::new(left, mid)), PathCmd::LineTo(Point::new(left + SWATCH, mid))];
            items.push(
                Item::new(
                    Role::Annotation,
                    Shape::Path(swatch),
                    Style { fill: None, stroke: Some(Stroke::solid(color, 2.0)) },
                )
                .labelled("trend equation swatch"),
            );
            let at = Point::new(left + SWATCH + 4.0, y);
            let text = Text {
                at,
                content: text,
                size,
                anchor: Anchor::Start,
                baseline: Baseline::Top,
                angle: 0.0,
                color: theme.text,
            };
            items.push(Item::new(Role::Annotation, Shape::Text(text), Style::default()).labelled("trend equation"));
        }
    }
    Ok(items)
}

/// "y = 0.500x + 3.00, R² = 0.667", prefixed by the group's label.
fn equation(label: &str, fit: &LinearFit) -> String {
    let sign = if fit.intercept < 0.0 { "−" } else { "+" };
    let prefix = if label.is_empty() { String::new() } else { format!("{label}: ") };
    format!(
        "{prefix}y = {}x {sign} {}, R² = {:.3} (n = {})",
        significant(fit.slope),
        significant(fit.intercept.abs()),
        fit.r2,
        fit.n
    )
}

/// `v` to three significant digits, without an exponent for everyday magnitudes, with a true
/// minus sign.
fn significant(v: f64) -> String {
    let text = if v == 0.0 || !v.is_finite() {
        format!("{v}")
    } else {
        let magnitude = v.abs().log10().floor() as i32;
        if (-4..=6).contains(&magnitude) {
            let decimals = (2 - magnitude).max(0) as usize;
            format!("{v:.decimals$}")
        } else {
            format!("{v:.2e}")
        }
    };
    text.replacen('-', "−", 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equations_read_as_written_by_hand() {
        let fit = LinearFit { slope: 0.50009, intercept: 3.00009, r2: 0.66654, n: 11 };
        assert_eq!(equation("", &fit), "y = 0.500x + 3.00, R² = 0.667 (n = 11)");
        let down = LinearFit { slope: -1234.4, intercept: -0.000123456, r2: 0.5, n: 3 };
        assert_eq!(equation("a", &down), "a: y = −1234x − 0.000123, R² = 0.500 (n = 3)");
        assert_eq!(significant(1.5e9), "1.50e9");
    }
}
