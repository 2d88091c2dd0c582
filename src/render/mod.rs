//! Renderers: turn a [`Scene`](crate::scene::Scene) into SVG text or a PNG raster; [`tiles`]
//! cuts a scene into raster tiles for the explorer window, and `egui` (feature `explore`)
//! paints them.
//!
//! Both backends draw text with the embedded font of [`crate::text`], skip items whose
//! coordinates are not finite, and never fail on a valid scene — the only error is a PNG canvas
//! that is non-finite, empty or over [`MAX_CANVAS_PIXELS`], caught before any allocation.

#[cfg(feature = "explore")]
pub mod egui;
mod lines;
pub mod mesh;
pub mod meshfile;
pub mod png;
mod points;
pub mod svg;
pub mod tiles;

pub use self::png::{MAX_CANVAS_PIXELS, RenderError, check_canvas, to_pixmap, to_png};
pub use self::svg::to_svg;

use crate::scene::{PathCmd, Point, Rect, Role, Stroke};

/// The stable name of a role, as written in SVG `data-role` attributes.
pub fn role_name(role: Role) -> &'static str {
    match role {
        Role::Background => "background",
        Role::DataMark => "data-mark",
        Role::Axis => "axis",
        Role::TickLabel => "tick-label",
        Role::AxisTitle => "axis-title",
        Role::Grid => "grid",
        Role::Legend => "legend",
        Role::Title => "title",
        Role::Caption => "caption",
        Role::Annotation => "annotation",
    }
}

/// Whether both coordinates are finite.
pub(crate) fn finite_point(p: Point) -> bool {
    p.x.is_finite() && p.y.is_finite()
}

/// A rectangle with non-negative size, or `None` if any field is not finite.
pub(crate) fn normalized_rect(r: Rect) -> Option<Rect> {
    if !(r.x.is_finite() && r.y.is_finite() && r.w.is_finite() && r.h.is_finite()) {
        return None;
    }
    let (x, w) = if r.w < 0.0 { (r.x + r.w, -r.w) } else { (r.x, r.w) };
    let (y, h) = if r.h < 0.0 { (r.y + r.h, -r.h) } else { (r.y, r.h) };
    Some(Rect::new(x, y, w, h))
}

/// Intersection of two rectangles (possibly empty, never negative).
pub(crate) fn intersect(a: Rect, b: Rect) -> Rect {
    let x0 = a.x.max(b.x);
    let y0 = a.y.max(b.y);
    let x1 = a.right().min(b.right());
    let y1 = a.bottom().min(b.bottom());
    Rect::new(x0, y0, (x1 - x0).max(0.0), (y1 - y0).max(0.0))
}

/// Path commands ready to draw: `None` if any coordinate is not finite or nothing is drawn.
///
/// A segment that arrives without a current point starts a new subpath at its end point, and
/// a `Close` without an open subpath is dropped, so both backends see the same geometry.
pub(crate) fn clean_path(cmds: &[PathCmd]) -> Option<Vec<PathCmd>> {
    let mut out = Vec::with_capacity(cmds.len());
    let mut open = false;
    let mut segments = 0usize;
    for cmd in cmds {
        let ok = match *cmd {
            PathCmd::MoveTo(p) | PathCmd::LineTo(p) => finite_point(p),
            PathCmd::QuadTo(a, p) => finite_point(a) && finite_point(p),
            PathCmd::CubicTo(a, b, p) => finite_point(a) && finite_point(b) && finite_point(p),
            PathCmd::Close => true,
        };
        if !ok {
            return None;
        }
        match *cmd {
            PathCmd::MoveTo(_) => {
                out.push(*cmd);
                open = true;
            }
            PathCmd::Close => {
                if open {
                    out.push(*cmd);
                    open = false;
                }
            }
            PathCmd::LineTo(p) | PathCmd::QuadTo(_, p) | PathCmd::CubicTo(_, _, p) => {
                if open {
                    out.push(*cmd);
                    segments += 1;
                } else if matches!(out.last(), Some(PathCmd::Close)) {
                    // After a close the pen is back at the subpath start: SVG continues from there.
                    let start = out.iter().rev().find_map(|c| match c {
                        PathCmd::MoveTo(s) => Some(*s),
                        _ => None,
                    });
                    match start {
                        Some(s) => {
                            out.push(PathCmd::MoveTo(s));
                            out.push(*cmd);
                            segments += 1;
                        }
                        None => out.push(PathCmd::MoveTo(p)),
                    }
                    open = true;
                } else {
                    out.push(PathCmd::MoveTo(p));
                    open = true;
                }
            }
        }
    }
    if segments == 0 { None } else { Some(out) }
}

/// The stroke to draw, if any: width finite and positive, colour not fully transparent.
pub(crate) fn visible_stroke(stroke: &Option<Stroke>) -> Option<&Stroke> {
    stroke.as_ref().filter(|s| s.width.is_finite() && s.width > 0.0 && s.color.a > 0)
}

/// The dash pattern to use: even-length (an odd list is repeated, as SVG does), all finite and
/// non-negative with a positive sum; `None` for a solid line.
pub(crate) fn dash_pattern(dash: &[f64]) -> Option<Vec<f64>> {
    if dash.is_empty() || dash.iter().any(|d| !d.is_finite() || *d < 0.0) {
        return None;
    }
    let sum: f64 = dash.iter().sum();
    if !sum.is_finite() || sum <= 0.0 {
        return None;
    }
    let mut v = dash.to_vec();
    if v.len() % 2 == 1 {
        v.extend_from_slice(dash);
    }
    Some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clean_path_handles_odd_input() {
        let p = |x, y| Point::new(x, y);
        assert!(clean_path(&[]).is_none());
        assert!(clean_path(&[PathCmd::MoveTo(p(0.0, 0.0))]).is_none());
        assert!(clean_path(&[PathCmd::MoveTo(p(0.0, 0.0)), PathCmd::LineTo(p(f64::NAN, 1.0))]).is_none());
        let c = clean_path(&[PathCmd::LineTo(p(1.0, 1.0)), PathCmd::LineTo(p(2.0, 2.0))]);
        assert_eq!(c, Some(vec![PathCmd::MoveTo(p(1.0, 1.0)), PathCmd::LineTo(p(2.0, 2.0))]));
        let c = clean_path(&[
            PathCmd::Close,
            PathCmd::MoveTo(p(0.0, 0.0)),
            PathCmd::LineTo(p(1.0, 0.0)),
            PathCmd::Close,
            PathCmd::LineTo(p(1.0, 1.0)),
        ]);
        assert_eq!(c.map(|v| v.len()), Some(5));
    }

    #[test]
    fn dash_patterns() {
        assert_eq!(dash_pattern(&[]), None);
        assert_eq!(dash_pattern(&[0.0, 0.0]), None);
        assert_eq!(dash_pattern(&[1.0, f64::NAN]), None);
        assert_eq!(dash_pattern(&[3.0]), Some(vec![3.0, 3.0]));
        assert_eq!(dash_pattern(&[4.0, 2.0, 1.0]), Some(vec![4.0, 2.0, 1.0, 4.0, 2.0, 1.0]));
    }
}
