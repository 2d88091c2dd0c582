//! The one embedded font: text measurement for layout and lint, and glyph outlines for the PNG
//! renderer.
//!
//! Every backend uses the same face — Ubuntu Light from `epaint_default_fonts`, the proportional
//! font the egui window uses too — so SVG, PNG and the window agree without any system font.
//! Text is a single line laid out left to right from advance widths (plus `kern` table pairs
//! when the font has them); there is no shaping, bidi reordering or font fallback. Characters
//! the font lacks are measured and drawn as its `.notdef` glyph.

use std::sync::OnceLock;

use ttf_parser::{Face, GlyphId, OutlineBuilder};

use crate::scene::{Anchor, Baseline, Point, Rect, Text};

/// CSS `font-family` list for SVG: the embedded face first, then generic fallbacks.
pub const FONT_FAMILY: &str = "Ubuntu Light, Ubuntu, DejaVu Sans, Helvetica Neue, Arial, sans-serif";

/// CSS `font-weight` of the embedded face (Light), written next to [`FONT_FAMILY`] in SVG.
pub const FONT_WEIGHT: u16 = 300;

/// Horizontal and vertical extent of a line of text at a given size, in canvas units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextMetrics {
    /// Advance width of the whole line.
    pub width: f64,
    /// Distance from the baseline up to the ascent line (positive).
    pub ascent: f64,
    /// Distance from the baseline down to the descent line (positive).
    pub descent: f64,
}

/// Font-unit metrics used when the embedded font cannot be parsed (never expected in practice).
const FALLBACK_ASCENT: f64 = 0.932;
const FALLBACK_DESCENT: f64 = 0.189;
const FALLBACK_ADVANCE: f64 = 0.5;

/// The parsed embedded face, or `None` if parsing failed.
fn face() -> Option<&'static Face<'static>> {
    static FACE: OnceLock<Option<Face<'static>>> = OnceLock::new();
    FACE.get_or_init(|| Face::parse(epaint_default_fonts::UBUNTU_LIGHT, 0).ok()).as_ref()
}

/// Units per em of the face (1000 for Ubuntu Light).
fn units_per_em(face: &Face<'_>) -> f64 {
    match face.units_per_em() {
        0 => 1000.0,
        u => f64::from(u),
    }
}

/// Ascent and descent of the face as fractions of the em, both positive.
fn vertical_em() -> (f64, f64) {
    match face() {
        Some(f) => {
            let upm = units_per_em(f);
            (f64::from(f.ascender()) / upm, -f64::from(f.descender()) / upm)
        }
        None => (FALLBACK_ASCENT, FALLBACK_DESCENT),
    }
}

/// The characters of `content` as drawn (see [`sanitize`]).
fn clean_chars(content: &str) -> impl Iterator<Item = char> + '_ {
    crate::visible::single_line_chars(content)
}

/// `content` with hidden characters removed, exactly as measured and drawn.
///
/// Tab, line feed and carriage return become a single space each (text is one line); control
/// characters, U+FFFE/U+FFFF and bidi controls are dropped ([`crate::visible`]). Both renderers
/// and [`measure`] apply this, so they agree on what is drawn.
pub fn sanitize(content: &str) -> String {
    crate::visible::single_line(content).into_owned()
}

/// `content` with hidden characters removed but line feeds kept: for text shown in several lines
/// by a viewer (an SVG `<title>`).
pub fn sanitize_multiline(content: &str) -> String {
    crate::visible::multiline(content).into_owned()
}

/// The glyph for `c`, or `.notdef` when the font has none.
fn glyph(face: &Face<'_>, c: char) -> GlyphId {
    face.glyph_index(c).unwrap_or(GlyphId(0))
}

/// Horizontal kerning between two glyphs, in font units (0 when the font has no `kern` table).
fn kerning(face: &Face<'_>, left: GlyphId, right: GlyphId) -> i32 {
    let Some(kern) = face.tables().kern else { return 0 };
    let mut total = 0i32;
    for sub in kern.subtables {
        if sub.horizontal
            && !sub.variable
            && !sub.has_cross_stream
            && let Some(k) = sub.glyphs_kerning(left, right)
        {
            total += i32::from(k);
        }
    }
    total
}

/// Calls `f(glyph, pen)` for each glyph of the sanitized `content` with its pen position in
/// font units, and returns the total advance.
fn layout(face: &Face<'_>, content: &str, mut f: impl FnMut(GlyphId, f64)) -> f64 {
    let mut pen = 0.0f64;
    let mut prev: Option<GlyphId> = None;
    for c in clean_chars(content) {
        let g = glyph(face, c);
        if let Some(p) = prev {
            pen += f64::from(kerning(face, p, g));
        }
        f(g, pen);
        pen += f64::from(face.glyph_hor_advance(g).unwrap_or(0));
        prev = Some(g);
    }
    pen
}

/// Width, ascent and descent of `content` (sanitized) at font size `size`.
///
/// The width is the sum of advance widths plus kerning; ascent and descent come from the font
/// (they do not depend on the characters). A non-finite or non-positive size measures as zero.
pub fn measure(content: &str, size: f64) -> TextMetrics {
    if !size.is_finite() || size <= 0.0 {
        return TextMetrics { width: 0.0, ascent: 0.0, descent: 0.0 };
    }
    let (asc, desc) = vertical_em();
    let width = match face() {
        Some(f) => layout(f, content, |_, _| {}) / units_per_em(f) * size,
        None => clean_chars(content).count() as f64 * FALLBACK_ADVANCE * size,
    };
    TextMetrics { width, ascent: asc * size, descent: desc * size }
}

/// Vertical offset from the anchor position to the alphabetic baseline (before rotation),
/// positive downwards, for text of font size `size`.
///
/// Top puts the ascent line at the anchor, Middle the centre of ascent..descent, Alphabetic the
/// baseline itself and Bottom the descent line.
pub fn baseline_shift(baseline: Baseline, size: f64) -> f64 {
    if !size.is_finite() || size <= 0.0 {
        return 0.0;
    }
    let (asc, desc) = vertical_em();
    match baseline {
        Baseline::Top => asc * size,
        Baseline::Middle => (asc - desc) / 2.0 * size,
        Baseline::Alphabetic => 0.0,
        Baseline::Bottom => -desc * size,
    }
}

/// Horizontal offset from the anchor position to the start of the text (before rotation).
pub fn anchor_shift(anchor: Anchor, width: f64) -> f64 {
    match anchor {
        Anchor::Start => 0.0,
        Anchor::Middle => -width / 2.0,
        Anchor::End => -width,
    }
}

/// Rotates `(dx, dy)` clockwise (y down) by `angle` degrees and adds it to `at`.
fn rotate_about(at: Point, dx: f64, dy: f64, angle: f64) -> Point {
    let (s, c) = angle.to_radians().sin_cos();
    Point::new(at.x + dx * c - dy * s, at.y + dx * s + dy * c)
}

/// Axis-aligned bounding box of `text` as drawn: its advance width by its ascent..descent band,
/// with anchor, baseline and rotation applied.
///
/// Text with nothing to draw (empty after [`sanitize`], or a non-finite or non-positive size)
/// gives a zero-size box at its position; a non-finite position or angle gives a zero-size
/// box at the (possibly non-finite) position, which intersects nothing.
pub fn bounds(text: &Text) -> Rect {
    let empty = Rect::new(text.at.x, text.at.y, 0.0, 0.0);
    let Some(corners) = corners(text, 0.0) else { return empty };
    let (mut minx, mut miny, mut maxx, mut maxy) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
    for p in corners {
        minx = minx.min(p.x);
        miny = miny.min(p.y);
        maxx = maxx.max(p.x);
        maxy = maxy.max(p.y);
    }
    Rect::new(minx, miny, maxx - minx, maxy - miny)
}

/// The corners of the glyph box of `text` (as [`bounds`] measures it, moved `inset` inwards
/// on every side), with anchor, baseline and rotation applied, in order around the box.
/// `None` when there is nothing to draw or a value is not finite.
pub fn corners(text: &Text, inset: f64) -> Option<[Point; 4]> {
    let at = text.at;
    if !at.x.is_finite() || !at.y.is_finite() || !text.angle.is_finite() {
        return None;
    }
    let m = measure(&text.content, text.size);
    if m.ascent <= 0.0 || clean_chars(&text.content).next().is_none() {
        return None;
    }
    let x0 = anchor_shift(text.anchor, m.width);
    let base = baseline_shift(text.baseline, text.size);
    let (left, right) = (x0 + inset, (x0 + m.width - inset).max(x0 + inset));
    let (top, bottom) = (base - m.ascent + inset, (base + m.descent - inset).max(base - m.ascent + inset));
    let p = [(left, top), (right, top), (right, bottom), (left, bottom)]
        .map(|(dx, dy)| rotate_about(at, dx, dy, text.angle));
    p.iter().all(|q| q.x.is_finite() && q.y.is_finite()).then_some(p)
}

/// Whether two convex quadrilaterals share area (separating axis test over their edges).
fn quads_overlap(a: &[Point; 4], b: &[Point; 4]) -> bool {
    let separated_along = |poly: &[Point; 4]| {
        (0..4).any(|i| {
            let (p, q) = (poly[i], poly[(i + 1) % 4]);
            let (nx, ny) = (q.y - p.y, p.x - q.x);
            if nx == 0.0 && ny == 0.0 {
                return false;
            }
            let project = |s: &[Point; 4]| {
                s.iter()
                    .map(|v| v.x * nx + v.y * ny)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)))
            };
            let ((a0, a1), (b0, b1)) = (project(a), project(b));
            a1 <= b0 || b1 <= a0
        })
    };
    !separated_along(a) && !separated_along(b)
}

/// Whether the glyph boxes of two texts overlap enough to hurt reading (by more than half a
/// pixel inwards from every side), measured on the turned boxes themselves: the axis-aligned
/// [`bounds`] of two neighbouring labels turned −45° overlap although their glyphs do not.
pub fn texts_overlap(a: &Text, b: &Text) -> bool {
    if !boxes_overlap(&bounds(a), &bounds(b)) {
        return false;
    }
    let square = |t: &Text| t.angle.rem_euclid(90.0) == 0.0;
    if square(a) && square(b) {
        return true;
    }
    match (corners(a, 0.5), corners(b, 0.5)) {
        (Some(p), Some(q)) => quads_overlap(&p, &q),
        _ => false,
    }
}

/// Whether two glyph boxes overlap enough to hurt reading: by more than half a pixel inwards
/// from every side (lint rule LB002 reports such pairs; label placement keeps clear of them).
pub fn boxes_overlap(a: &Rect, b: &Rect) -> bool {
    let shrink = |r: &Rect| Rect::new(r.x + 0.5, r.y + 0.5, (r.w - 1.0).max(0.0), (r.h - 1.0).max(0.0));
    let (a, b) = (shrink(a), shrink(b));
    a.w > 0.0 && b.w > 0.0 && a.intersects(&b)
}

/// Collects a glyph outline into a tiny-skia path, mapping font units to canvas units.
struct Outline<'a> {
    builder: &'a mut tiny_skia::PathBuilder,
    /// Canvas x of the glyph origin.
    ox: f64,
    /// Canvas y of the baseline.
    oy: f64,
    /// Canvas units per font unit.
    k: f64,
}

impl Outline<'_> {
    fn map(&self, x: f32, y: f32) -> (f32, f32) {
        ((self.ox + f64::from(x) * self.k) as f32, (self.oy - f64::from(y) * self.k) as f32)
    }
}

impl OutlineBuilder for Outline<'_> {
    fn move_to(&mut self, x: f32, y: f32) {
        let (x, y) = self.map(x, y);
        self.builder.move_to(x, y);
    }
    fn line_to(&mut self, x: f32, y: f32) {
        let (x, y) = self.map(x, y);
        self.builder.line_to(x, y);
    }
    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        let (x1, y1) = self.map(x1, y1);
        let (x, y) = self.map(x, y);
        self.builder.quad_to(x1, y1, x, y);
    }
    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        let (x1, y1) = self.map(x1, y1);
        let (x2, y2) = self.map(x2, y2);
        let (x, y) = self.map(x, y);
        self.builder.cubic_to(x1, y1, x2, y2, x, y);
    }
    fn close(&mut self) {
        self.builder.close();
    }
}

/// Glyph outlines of `content` (sanitized) at font size `size`, with the pen starting at
/// (0, 0) on the alphabetic baseline, y down. Fill with the non-zero rule.
///
/// `None` when there is nothing to draw (empty text, only spaces, bad size, or no font).
pub fn glyph_path(content: &str, size: f64) -> Option<tiny_skia::Path> {
    glyph_path_at(content, size, 0.0, 0.0)
}

/// Glyph outlines with the pen starting at `(x, y)` on the baseline.
fn glyph_path_at(content: &str, size: f64, x: f64, y: f64) -> Option<tiny_skia::Path> {
    if !size.is_finite() || size <= 0.0 || !x.is_finite() || !y.is_finite() {
        return None;
    }
    let f = face()?;
    let k = size / units_per_em(f);
    let mut builder = tiny_skia::PathBuilder::new();
    layout(f, content, |g, pen| {
        let mut outline = Outline { builder: &mut builder, ox: x + pen * k, oy: y, k };
        // Glyphs without an outline (spaces) draw nothing; that is not an error.
        let _ = f.outline_glyph(g, &mut outline);
    });
    builder.finish()
}

/// Glyph outlines of `text` in canvas coordinates, placed exactly as [`bounds`] describes
/// (anchor, baseline and clockwise rotation about `text.at` applied).
///
/// `None` when there is nothing to draw or the position, size or angle is not finite.
pub fn text_path(text: &Text) -> Option<tiny_skia::Path> {
    let at = text.at;
    if !at.x.is_finite() || !at.y.is_finite() || !text.angle.is_finite() {
        return None;
    }
    let m = measure(&text.content, text.size);
    let x = at.x + anchor_shift(text.anchor, m.width);
    let y = at.y + baseline_shift(text.baseline, text.size);
    let path = glyph_path_at(&text.content, text.size, x, y)?;
    let angle = text.angle.rem_euclid(360.0);
    if angle == 0.0 {
        return Some(path);
    }
    path.transform(tiny_skia::Transform::from_rotate_at(angle as f32, at.x as f32, at.y as f32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Color;

    fn t(content: &str, anchor: Anchor, baseline: Baseline, angle: f64) -> Text {
        Text {
            at: Point::new(100.0, 50.0),
            content: content.to_string(),
            size: 20.0,
            anchor,
            baseline,
            angle,
            color: Color::BLACK,
        }
    }

    #[test]
    fn font_parses_and_measures() {
        assert!(face().is_some());
        assert_eq!(measure("", 12.0).width, 0.0);
        let a = measure("a", 12.0).width;
        let ab = measure("ab", 12.0).width;
        let abc = measure("abc", 12.0).width;
        assert!(a > 0.0 && ab > a && abc > ab);
        // Width scales linearly with size.
        assert!((measure("abc", 24.0).width - 2.0 * abc).abs() < 1e-9);
        let m = measure("x", 10.0);
        assert!(m.ascent > 5.0 && m.descent > 0.5 && m.descent < m.ascent);
        assert_eq!(measure("abc", f64::NAN).width, 0.0);
        assert_eq!(measure("abc", -3.0).width, 0.0);
    }

    #[test]
    fn sanitize_drops_controls() {
        assert_eq!(sanitize("a\u{7}b\u{0}c\u{1b}d"), "abcd");
        assert_eq!(sanitize("a\nb\tc"), "a b c");
        assert_eq!(sanitize("x\u{FFFF}"), "x");
        assert_eq!(sanitize("\u{202e}evil\u{2069}"), "evil");
        assert_eq!(measure("ab\u{7}", 10.0).width, measure("ab", 10.0).width);
        // Missing glyphs (Hebrew) still advance.
        assert!(measure("שלום", 10.0).width > 0.0);
    }

    #[test]
    fn bounds_follow_anchor_and_baseline() {
        let m = measure("Hello", 20.0);
        let b = bounds(&t("Hello", Anchor::Start, Baseline::Alphabetic, 0.0));
        assert!((b.x - 100.0).abs() < 1e-9 && (b.w - m.width).abs() < 1e-9);
        assert!((b.y - (50.0 - m.ascent)).abs() < 1e-9 && (b.h - (m.ascent + m.descent)).abs() < 1e-9);
        let b = bounds(&t("Hello", Anchor::Middle, Baseline::Top, 0.0));
        assert!((b.x - (100.0 - m.width / 2.0)).abs() < 1e-9 && (b.y - 50.0).abs() < 1e-9);
        let b = bounds(&t("Hello", Anchor::End, Baseline::Bottom, 0.0));
        assert!((b.right() - 100.0).abs() < 1e-9 && (b.bottom() - 50.0).abs() < 1e-9);
        let b = bounds(&t("Hello", Anchor::Start, Baseline::Middle, 0.0));
        assert!((b.y + b.h / 2.0 - 50.0).abs() < 1e-9);
    }

    #[test]
    fn bounds_rotate_clockwise() {
        let m = measure("Axis title", 20.0);
        // -90°: reads bottom to top, so the text extends upwards from the anchor.
        let b = bounds(&t("Axis title", Anchor::Start, Baseline::Alphabetic, -90.0));
        assert!((b.h - m.width).abs() < 1e-9);
        assert!((b.bottom() - 50.0).abs() < 1e-9);
        assert!((b.x - (100.0 - m.ascent)).abs() < 1e-9);
        // +90°: extends downwards, ascent to the right of the anchor.
        let b = bounds(&t("Axis title", Anchor::Start, Baseline::Alphabetic, 90.0));
        assert!((b.y - 50.0).abs() < 1e-9 && (b.right() - (100.0 + m.ascent)).abs() < 1e-9);
    }

    #[test]
    fn turned_neighbours_do_not_overlap_though_their_bounds_do() {
        let label = |x: f64, angle: f64| Text {
            at: Point::new(x, 50.0),
            content: "A long category name".to_string(),
            size: 12.0,
            anchor: Anchor::End,
            baseline: Baseline::Middle,
            angle,
            color: Color::BLACK,
        };
        // −45°: 13.5 px tall lines 20 px apart along x are 14.1 px apart across them.
        let (a, b) = (label(100.0, -45.0), label(120.0, -45.0));
        assert!(bounds(&a).intersects(&bounds(&b)), "the axis-aligned boxes overlap");
        assert!(!texts_overlap(&a, &b));
        // 10 px apart they do overlap.
        assert!(texts_overlap(&a, &label(110.0, -45.0)));
        // Upright neighbours: exact boxes.
        assert!(!texts_overlap(&label(100.0, -90.0), &label(114.0, -90.0)));
        assert!(texts_overlap(&label(100.0, -90.0), &label(110.0, -90.0)));
        // A flat label crossing a turned one.
        let flat = Text { angle: 0.0, anchor: Anchor::Middle, ..label(80.0, 0.0) };
        assert!(texts_overlap(&flat, &label(110.0, -45.0)));
        let Some(c) = corners(&a, 0.0) else { panic!("corners") };
        let b = bounds(&a);
        for p in c {
            assert!(p.x >= b.x - 1e-9 && p.x <= b.right() + 1e-9 && p.y >= b.y - 1e-9 && p.y <= b.bottom() + 1e-9);
        }
    }

    #[test]
    fn bounds_survive_bad_input() {
        let mut x = t("Hi", Anchor::Start, Baseline::Top, f64::NAN);
        assert_eq!(bounds(&x).w, 0.0);
        x.angle = 0.0;
        x.at.x = f64::INFINITY;
        assert_eq!(bounds(&x).w, 0.0);
        assert!(text_path(&x).is_none());
        let e = bounds(&t("\u{7}", Anchor::Middle, Baseline::Middle, 0.0));
        assert_eq!((e.w, e.h), (0.0, 0.0));
    }

    #[test]
    fn outlines_lie_inside_bounds() {
        for angle in [0.0, -90.0, 30.0] {
            let text = t("Typography gjq", Anchor::Middle, Baseline::Middle, angle);
            let b = bounds(&text);
            let Some(p) = text_path(&text) else { panic!("no path") };
            let pb = p.bounds();
            let eps = 1.5;
            assert!(f64::from(pb.left()) >= b.x - eps && f64::from(pb.right()) <= b.right() + eps, "{angle}");
            assert!(f64::from(pb.top()) >= b.y - eps && f64::from(pb.bottom()) <= b.bottom() + eps, "{angle}");
        }
        assert!(glyph_path("   ", 12.0).is_none());
    }
}
