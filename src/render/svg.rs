//! SVG 1.1 output.
//!
//! The document is self-contained and inspectable: every element carries `data-role`, data marks
//! drawn from one row carry `data-row`, labels become `data-label`. All user strings are
//! sanitized ([`crate::text::sanitize`]) and XML-escaped; no script or event attribute is ever
//! written. Coordinates are rounded to two decimals. Text is placed on its alphabetic baseline
//! computed from the embedded font's metrics, so browsers and resvg put it where the PNG does.

use std::fmt::Write as _;

use crate::scene::{
    Anchor, Color, Item, LineBatch, Mesh, PathCmd, PerPoint, Point, PointBatch, Raster, Scene, Shape, Style, Text,
};
use crate::text::{FONT_FAMILY, FONT_WEIGHT, baseline_shift, sanitize, sanitize_multiline};

use super::{clean_path, dash_pattern, finite_point, normalized_rect, role_name, visible_stroke};

/// Renders `scene` as a standalone SVG 1.1 document.
///
/// Items with non-finite geometry are left out; nothing else is dropped.
pub fn to_svg(scene: &Scene) -> String {
    let width = if scene.width.is_finite() && scene.width > 0.0 { scene.width } else { 0.0 };
    let height = if scene.height.is_finite() && scene.height > 0.0 { scene.height } else { 0.0 };
    let mut w = Writer { out: String::with_capacity(4096), next_clip: 0, canvas: (width, height) };
    let (ws, hs) = (num(width), num(height));
    w.out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        w.out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
         version=\"1.1\" width=\"{ws}\" height=\"{hs}\" viewBox=\"0 0 {ws} {hs}\">"
    );
    if let Some(title) = &scene.title {
        let _ = writeln!(w.out, "<title>{}</title>", escape(title));
    }
    if scene.background.a > 0 {
        let _ = writeln!(
            w.out,
            "<rect data-role=\"background\" x=\"0\" y=\"0\" width=\"{ws}\" height=\"{hs}\"{}/>",
            fill_attrs(Some(scene.background))
        );
    }
    for item in &scene.items {
        w.item(item);
    }
    w.out.push_str("</svg>\n");
    w.out
}

/// Output buffer plus a counter for unique clip-path ids.
struct Writer {
    out: String,
    next_clip: usize,
    /// Canvas width and height (for point batches embedded as rasters).
    canvas: (f64, f64),
}

/// Device pixels per canvas unit of a point batch (or a line batch or path above its vector
/// limit) embedded as a raster (sharp on high-DPI screens and when zoomed in twice).
pub const POINT_RASTER_SCALE: f64 = 2.0;

/// The box finite points cover, each with its reach.
struct Bounds {
    lo: [f64; 2],
    hi: [f64; 2],
}

impl Default for Bounds {
    fn default() -> Bounds {
        Bounds { lo: [f64::INFINITY; 2], hi: [f64::NEG_INFINITY; 2] }
    }
}

impl Bounds {
    fn add(&mut self, p: Point, reach: f64) {
        if finite_point(p) {
            (self.lo[0], self.lo[1]) = (self.lo[0].min(p.x - reach), self.lo[1].min(p.y - reach));
            (self.hi[0], self.hi[1]) = (self.hi[0].max(p.x + reach), self.hi[1].max(p.y + reach));
        }
    }
}

impl Writer {
    /// Writes one item (and, for groups, its children).
    fn item(&mut self, item: &Item) {
        let common = common_attrs(item);
        match &item.shape {
            Shape::Rect(r) => {
                let Some(r) = normalized_rect(*r) else { return };
                let _ = writeln!(
                    self.out,
                    "<rect{common} x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"{}{}",
                    num(r.x),
                    num(r.y),
                    num(r.w),
                    num(r.h),
                    style_attrs(&item.style),
                    end_tag("rect", item.tooltips.first())
                );
            }
            Shape::Circle { center, radius } => {
                if !finite_point(*center) || !radius.is_finite() || *radius <= 0.0 {
                    return;
                }
                let _ = writeln!(
                    self.out,
                    "<circle{common} cx=\"{}\" cy=\"{}\" r=\"{}\"{}{}",
                    num(center.x),
                    num(center.y),
                    num(*radius),
                    style_attrs(&item.style),
                    end_tag("circle", item.tooltips.first())
                );
            }
            Shape::Path(cmds) => {
                if cmds.len() > crate::scene::PATH_VECTOR_LIMIT {
                    let reach = item.style.stroke.as_ref().map_or(0.0, |s| s.width);
                    if let Some(raster) = self.raster_around(item, crate::scene::path_points(cmds), reach) {
                        self.image(&common, &raster);
                        return;
                    }
                }
                let Some(cmds) = clean_path(cmds) else { return };
                let _ = writeln!(
                    self.out,
                    "<path{common} d=\"{}\"{}{}",
                    path_data(&cmds),
                    style_attrs(&item.style),
                    end_tag("path", item.tooltips.first())
                );
            }
            Shape::Text(text) => self.text(&common, text, item.tooltips.first()),
            Shape::Image(raster) => self.image(&common, raster),
            Shape::Points(batch) => self.points(item, &common, batch),
            Shape::Lines(batch) => self.lines(item, &common, batch),
            Shape::Mesh(mesh) => self.mesh(item, &common, mesh),
            Shape::Group { items, clip } => {
                let clip = match clip {
                    Some(c) => match normalized_rect(*c) {
                        Some(c) => Some(c),
                        None => return,
                    },
                    None => None,
                };
                let clip_attr = match clip {
                    Some(c) => {
                        let id = format!("dataink-clip-{}", self.next_clip);
                        self.next_clip += 1;
                        let _ = writeln!(
                            self.out,
                            "<clipPath id=\"{id}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>",
                            num(c.x),
                            num(c.y),
                            num(c.w),
                            num(c.h)
                        );
                        format!(" clip-path=\"url(#{id})\"")
                    }
                    None => String::new(),
                };
                let _ = writeln!(self.out, "<g{common}{clip_attr}>");
                for child in items {
                    self.item(child);
                }
                self.out.push_str("</g>\n");
            }
        }
    }

    /// Writes a `<text>` element with its baseline computed from the embedded font. Hover text
    /// (a shortened category label's full name) goes in a `<g>` around it, as that group's
    /// `<title>`: text content stays just the text drawn.
    fn text(&mut self, common: &str, text: &Text, tooltip: Option<&String>) {
        let content = sanitize(&text.content);
        if content.is_empty()
            || !finite_point(text.at)
            || !text.size.is_finite()
            || text.size <= 0.0
            || !text.angle.is_finite()
            || text.color.a == 0
        {
            return;
        }
        let y = text.at.y + baseline_shift(text.baseline, text.size);
        let anchor = match text.anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let angle = text.angle.rem_euclid(360.0);
        let transform = if num(angle) == "0" || num(angle) == "360" {
            String::new()
        } else {
            format!(" transform=\"rotate({} {} {})\"", num(angle), num(text.at.x), num(text.at.y))
        };
        let title = title_element(tooltip);
        if !title.is_empty() {
            let _ = write!(self.out, "<g>{title}");
        }
        let _ = write!(
            self.out,
            "<text{common} x=\"{}\" y=\"{}\" font-family=\"{}\" font-size=\"{}\" font-weight=\"{FONT_WEIGHT}\" \
             text-anchor=\"{anchor}\"{}{transform} xml:space=\"preserve\" \
             style=\"font-kerning:none;font-variant-ligatures:none\">{}</text>",
            num(text.at.x),
            num(y),
            escape(FONT_FAMILY),
            num(text.size),
            fill_attrs(Some(text.color)),
            escape(&content)
        );
        self.out.push_str(if title.is_empty() { "\n" } else { "</g>\n" });
    }

    /// Writes an `<image>` with the raster as a base64 PNG data URI.
    fn image(&mut self, common: &str, raster: &Raster) {
        let Some(dest) = normalized_rect(raster.dest) else { return };
        if dest.w <= 0.0 || dest.h <= 0.0 {
            return;
        }
        let Ok(png) = super::png::encode_raster(raster) else { return };
        let rendering =
            if raster.smooth { "" } else { " image-rendering=\"optimizeSpeed\" style=\"image-rendering:pixelated\"" };
        let _ = writeln!(
            self.out,
            "<image{common} x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\"{rendering} \
             xlink:href=\"data:image/png;base64,{}\"/>",
            num(dest.x),
            num(dest.y),
            num(dest.w),
            num(dest.h),
            base64(&png)
        );
    }

    /// Writes a point batch as one `<g>` carrying the shared style and one `<circle>` per point,
    /// or, above [`PointBatch::VECTOR_LIMIT`] points, as one embedded image drawn by the PNG
    /// renderer's point blitter (circles again if the canvas is too large to rasterize).
    fn points(&mut self, item: &Item, common: &str, batch: &PointBatch) {
        if batch.drawn_as_raster()
            && let Some(raster) = self.point_raster(item, batch)
        {
            self.image(common, &raster);
            return;
        }
        let shared_fill = match &batch.fill {
            PerPoint::Uniform(c) => fill_attrs(Some(*c)),
            PerPoint::Each(_) => String::new(),
        };
        let stroke = stroke_attrs(&batch.stroke);
        let _ = writeln!(self.out, "<g{common}{shared_fill}{stroke}>");
        let per_point_rows = item.rows.len() == batch.centers.len() && item.rows.len() > 1;
        let per_point_tips = item.tooltips.len() == batch.centers.len();
        for (i, c) in batch.centers.iter().enumerate() {
            let r = batch.radius.at(i).unwrap_or(0.0);
            if !finite_point(*c) || !r.is_finite() || r <= 0.0 {
                continue;
            }
            let fill = match &batch.fill {
                PerPoint::Uniform(_) => String::new(),
                PerPoint::Each(_) => fill_attrs(batch.fill.at(i)),
            };
            let row = match item.rows.get(i) {
                Some(row) if per_point_rows => format!(" data-row=\"{row}\""),
                _ => String::new(),
            };
            let end = end_tag("circle", item.tooltips.get(i).filter(|_| per_point_tips));
            let _ =
                writeln!(self.out, "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{fill}{row}{end}", num(c.x), num(c.y), num(r));
        }
        self.out.push_str("</g>\n");
    }

    /// The batch drawn alone at [`POINT_RASTER_SCALE`], cut to the device pixels its points cover.
    fn point_raster(&self, item: &Item, batch: &PointBatch) -> Option<Raster> {
        let outline = batch.stroke.as_ref().map_or(0.0, |s| s.width);
        let reach = |i: usize| batch.radius.at(i).filter(|r| r.is_finite() && *r > 0.0).map(|r| r + outline);
        let mut bounds = Bounds::default();
        for (i, c) in batch.centers.iter().enumerate() {
            if let Some(r) = reach(i) {
                bounds.add(*c, r);
            }
        }
        self.raster_of(item, bounds)
    }

    /// `item` drawn alone at [`POINT_RASTER_SCALE`], cut to the device pixels that `points`
    /// (each reaching `reach` around it) cover.
    fn raster_around(&self, item: &Item, points: impl Iterator<Item = Point>, reach: f64) -> Option<Raster> {
        let reach = if reach.is_finite() { reach.max(0.0) + 1.0 } else { 1.0 };
        let mut bounds = Bounds::default();
        for p in points {
            bounds.add(p, reach);
        }
        self.raster_of(item, bounds)
    }

    /// `item` drawn alone at [`POINT_RASTER_SCALE`], cut to `bounds` (in canvas units).
    fn raster_of(&self, item: &Item, Bounds { lo, hi }: Bounds) -> Option<Raster> {
        if !(lo[0] <= hi[0] && lo[1] <= hi[1]) {
            return None;
        }
        let s = POINT_RASTER_SCALE;
        let (w, h) = self.canvas;
        let px = |v: f64, max: f64| (v * s).clamp(0.0, max * s);
        let bounds = (
            px(lo[0], w).floor() as u32,
            px(lo[1], h).floor() as u32,
            px(hi[0], w).ceil() as u32,
            px(hi[1], h).ceil() as u32,
        );
        super::png::item_raster(item, self.canvas, s, bounds).ok()
    }

    /// Writes a line batch as one `<g>` carrying the shared style and one `<path>` per polyline
    /// (with `data-row` when the item has one row per polyline). A non-finite vertex ends its
    /// subpath; polylines with nothing to draw are left out.
    fn lines(&mut self, item: &Item, common: &str, batch: &LineBatch) {
        if batch.drawn_as_raster()
            && let Some(raster) = self.raster_around(item, batch.points.iter().copied(), batch.width)
        {
            self.image(common, &raster);
            return;
        }
        let visible_width = batch.width.is_finite() && batch.width > 0.0;
        let stroke_color = |c: Option<Color>| match c {
            Some(c) if visible_width => stroke_color_attrs(c),
            _ => String::new(),
        };
        let shared_color = match &batch.color {
            PerPoint::Uniform(c) => stroke_color(Some(*c)),
            PerPoint::Each(_) => String::new(),
        };
        let width = if visible_width { format!(" stroke-width=\"{}\"", num(batch.width)) } else { String::new() };
        let _ = writeln!(self.out, "<g{common} fill=\"none\"{shared_color}{width} stroke-linejoin=\"round\">");
        let per_line_rows = item.rows.len() == batch.len() && item.rows.len() > 1;
        let per_line_tips = item.tooltips.len() == batch.len();
        for k in 0..batch.len() {
            let Some(line) = batch.polyline(k) else { break };
            let d = polyline_data(line);
            if d.is_empty() {
                continue;
            }
            let color = match &batch.color {
                PerPoint::Uniform(_) => String::new(),
                PerPoint::Each(_) => stroke_color(batch.color.at(k)),
            };
            let row = match item.rows.get(k) {
                Some(row) if per_line_rows => format!(" data-row=\"{row}\""),
                _ => String::new(),
            };
            let end = end_tag("path", item.tooltips.get(k).filter(|_| per_line_tips));
            let _ = writeln!(self.out, "<path d=\"{d}\"{color}{row}{end}");
        }
        self.out.push_str("</g>\n");
    }
}

impl Writer {
    /// Writes a mesh as one `<g>` of triangles back to front (by mean depth, ties in mesh order),
    /// each a `<path>` filled and outlined with a hairline in the mean colour of its vertices (the
    /// outline closes anti-aliasing seams between neighbours); or, above
    /// [`Mesh::VECTOR_LIMIT`] triangles, as one embedded image drawn by the PNG renderer's
    /// z-buffer.
    fn mesh(&mut self, item: &Item, common: &str, mesh: &Mesh) {
        if mesh.drawn_as_raster() {
            let points = mesh.positions.iter().map(|p| Point::new(f64::from(p[0]), f64::from(p[1])));
            if let Some(raster) = self.raster_around(item, points, 0.0) {
                self.image(common, &raster);
                return;
            }
        }
        let mut tris: Vec<(f64, [[f32; 3]; 3], Color)> = (0..mesh.indices.len())
            .filter_map(|i| mesh.triangle(i))
            .map(|(p, c)| {
                let depth = (f64::from(p[0][2]) + f64::from(p[1][2]) + f64::from(p[2][2])) / 3.0;
                (depth, p, mean_colour(c))
            })
            .collect();
        // Larger depth is nearer: ascending depth is back to front (the sort is stable).
        tris.sort_by(|a, b| a.0.total_cmp(&b.0));
        let _ = writeln!(self.out, "<g{common} stroke-width=\"{}\" stroke-linejoin=\"round\">", num(MESH_SEAM_WIDTH));
        for (_, p, c) in &tris {
            if c.a == 0 {
                continue;
            }
            let [a, b, d] = p.map(|q| (num(f64::from(q[0])), num(f64::from(q[1]))));
            let stroke = stroke_color_attrs(*c);
            let _ = writeln!(
                self.out,
                "<path d=\"M{} {}L{} {}L{} {}Z\"{}{stroke}/>",
                a.0,
                a.1,
                b.0,
                b.1,
                d.0,
                d.1,
                fill_attrs(Some(*c))
            );
        }
        self.out.push_str("</g>\n");
    }
}

/// Width of the outline a mesh triangle gets in SVG, in canvas units.
const MESH_SEAM_WIDTH: f64 = 0.5;

/// The mean of three colours, channel by channel.
fn mean_colour(c: [Color; 3]) -> Color {
    let mean = |f: fn(&Color) -> u8| ((c.iter().map(|x| u32::from(f(x))).sum::<u32>() + 1) / 3) as u8;
    Color { r: mean(|c| c.r), g: mean(|c| c.g), b: mean(|c| c.b), a: mean(|c| c.a) }
}

/// The end of an element `tag`: self-closing, or holding its hover text as a `<title>`.
fn end_tag(tag: &str, tooltip: Option<&String>) -> String {
    match title_element(tooltip) {
        title if title.is_empty() => "/>".to_string(),
        title => format!(">{title}</{tag}>"),
    }
}

/// A `<title>` child holding `tooltip` (lines kept as `&#10;`), or nothing.
fn title_element(tooltip: Option<&String>) -> String {
    match tooltip.map(|t| sanitize_multiline(t)).filter(|t| !t.is_empty()) {
        Some(text) => {
            let lines: Vec<String> = text.split('\n').map(escape).collect();
            format!("<title>{}</title>", lines.join("&#10;"))
        }
        None => String::new(),
    }
}

/// `data-role`, `data-row` (single-row items) and `data-label` attributes.
fn common_attrs(item: &Item) -> String {
    let mut s = format!(" data-role=\"{}\"", role_name(item.role));
    if let [row] = item.rows.as_slice() {
        let _ = write!(s, " data-row=\"{row}\"");
    }
    if let Some(label) = &item.label {
        let _ = write!(s, " data-label=\"{}\"", escape(label));
    }
    s
}

/// `fill` and `fill-opacity` attributes (`fill="none"` when absent).
fn fill_attrs(fill: Option<Color>) -> String {
    match fill {
        Some(c) if c.a > 0 => {
            if c.a < 255 {
                format!(" fill=\"{}\" fill-opacity=\"{}\"", c.hex(), opacity(c))
            } else {
                format!(" fill=\"{}\"", c.hex())
            }
        }
        _ => " fill=\"none\"".to_string(),
    }
}

/// Stroke attributes (nothing when there is no visible stroke; SVG's default is no stroke).
fn stroke_attrs(stroke: &Option<crate::scene::Stroke>) -> String {
    let Some(s) = visible_stroke(stroke) else { return String::new() };
    let mut out = format!(" stroke=\"{}\" stroke-width=\"{}\"", s.color.hex(), num(s.width));
    if s.color.a < 255 {
        let _ = write!(out, " stroke-opacity=\"{}\"", opacity(s.color));
    }
    if let Some(d) = dash_pattern(&s.dash) {
        let list: Vec<String> = d.iter().map(|v| num(*v)).collect();
        let _ = write!(out, " stroke-dasharray=\"{}\"", list.join(" "));
    }
    out
}

/// `stroke` and `stroke-opacity` attributes of a colour (nothing when it is fully transparent:
/// SVG's default is no stroke).
fn stroke_color_attrs(c: Color) -> String {
    match c.a {
        0 => String::new(),
        255 => format!(" stroke=\"{}\"", c.hex()),
        _ => format!(" stroke=\"{}\" stroke-opacity=\"{}\"", c.hex(), opacity(c)),
    }
}

/// Fill and stroke attributes of a shape.
fn style_attrs(style: &Style) -> String {
    let mut s = fill_attrs(style.fill);
    s.push_str(&stroke_attrs(&style.stroke));
    s
}

/// Alpha as a 0..1 number with three decimals.
fn opacity(c: Color) -> String {
    let v = (c.alpha() * 1000.0).round() / 1000.0;
    let s = format!("{v:.3}");
    trim_zeros(s)
}

/// A coordinate rounded to two decimals without trailing zeros (`-0` becomes `0`).
fn num(v: f64) -> String {
    if !v.is_finite() {
        return "0".to_string();
    }
    let r = (v * 100.0).round() / 100.0;
    if r == 0.0 {
        return "0".to_string();
    }
    trim_zeros(format!("{r:.2}"))
}

/// Strips trailing zeros (and a trailing dot) after a decimal point.
fn trim_zeros(s: String) -> String {
    if s.contains('.') {
        let t = s.trim_end_matches('0').trim_end_matches('.');
        if t == "-0" { "0".to_string() } else { t.to_string() }
    } else {
        s
    }
}

/// SVG path data for cleaned commands.
fn path_data(cmds: &[PathCmd]) -> String {
    let mut d = String::with_capacity(cmds.len() * 16);
    for cmd in cmds {
        if !d.is_empty() {
            d.push(' ');
        }
        let _ = match cmd {
            PathCmd::MoveTo(p) => write!(d, "M{} {}", num(p.x), num(p.y)),
            PathCmd::LineTo(p) => write!(d, "L{} {}", num(p.x), num(p.y)),
            PathCmd::QuadTo(a, p) => write!(d, "Q{} {} {} {}", num(a.x), num(a.y), num(p.x), num(p.y)),
            PathCmd::CubicTo(a, b, p) => {
                write!(d, "C{} {} {} {} {} {}", num(a.x), num(a.y), num(b.x), num(b.y), num(p.x), num(p.y))
            }
            PathCmd::Close => write!(d, "Z"),
        };
    }
    d
}

/// SVG path data of a polyline: one `M…L…` subpath per run of at least two finite vertices.
fn polyline_data(line: &[Point]) -> String {
    let mut d = String::with_capacity(line.len() * 16);
    for (k, p) in line.iter().enumerate() {
        if !finite_point(*p) {
            continue;
        }
        let prev = k > 0 && line.get(k - 1).is_some_and(|q| finite_point(*q));
        let next = line.get(k + 1).is_some_and(|q| finite_point(*q));
        if !prev && !next {
            continue;
        }
        if !d.is_empty() {
            d.push(' ');
        }
        let _ = write!(d, "{}{} {}", if prev { 'L' } else { 'M' }, num(p.x), num(p.y));
    }
    d
}

/// Sanitizes and XML-escapes a user string for element content or an attribute value.
pub fn escape(s: &str) -> String {
    let clean = sanitize(s);
    let mut out = String::with_capacity(clean.len() + 8);
    for c in clean.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// Standard base64 (RFC 4648, with padding).
pub fn base64(data: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let sym = |v: u32| char::from(ALPHABET[(v & 63) as usize]);
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    let mut chunks = data.chunks_exact(3);
    for c in &mut chunks {
        let n = (u32::from(c[0]) << 16) | (u32::from(c[1]) << 8) | u32::from(c[2]);
        out.extend([sym(n >> 18), sym(n >> 12), sym(n >> 6), sym(n)]);
    }
    match *chunks.remainder() {
        [a] => {
            let n = u32::from(a) << 16;
            out.extend([sym(n >> 18), sym(n >> 12), '=', '=']);
        }
        [a, b] => {
            let n = (u32::from(a) << 16) | (u32::from(b) << 8);
            out.extend([sym(n >> 18), sym(n >> 12), sym(n >> 6), '=']);
        }
        _ => {}
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::scene::{Baseline, Point, Rect, Role, Stroke};

    /// A scene with every shape kind and hostile strings.
    pub(crate) fn kitchen_sink() -> Scene {
        let hostile = "<script>alert(1)</script> & \" ' \u{0007} שלום עולם";
        let t = |at: Point, content: &str, anchor, baseline, angle| Text {
            at,
            content: content.to_string(),
            size: 14.0,
            anchor,
            baseline,
            angle,
            color: Color::rgb(20, 20, 20),
        };
        let dashed = Stroke { color: Color::rgb(200, 0, 0).with_opacity(0.5), width: 2.0, dash: vec![6.0, 3.0] };
        let mut rgba = Vec::new();
        for y in 0..4u8 {
            for x in 0..4u8 {
                rgba.extend_from_slice(&[x * 60, y * 60, 128, 255]);
            }
        }
        let points = PointBatch {
            centers: vec![
                Point::new(250.0, 150.0),
                Point::new(270.0, 160.0),
                Point::new(f64::NAN, 1.0),
                Point::new(290.0, 140.0),
            ],
            radius: PerPoint::Each(vec![3.0, 4.0, 5.0, 6.0]),
            fill: PerPoint::Each(vec![
                Color::rgb(0, 0, 255),
                Color::rgb(0, 128, 0).with_opacity(0.5),
                Color::BLACK,
                Color::rgb(255, 128, 0),
            ]),
            stroke: Some(Stroke::solid(Color::WHITE, 1.0)),
        };
        Scene {
            width: 400.0,
            height: 300.0,
            background: Color::WHITE,
            title: Some(hostile.to_string()),
            items: vec![
                Item::new(
                    Role::DataMark,
                    Shape::Rect(Rect::new(10.123456, 20.0, 50.0, 30.0)),
                    Style::fill(Color::rgb(255, 0, 0)),
                )
                .with_rows(vec![7])
                .labelled(hostile),
                Item::new(
                    Role::DataMark,
                    Shape::Circle { center: Point::new(100.0, 100.0), radius: 10.0 },
                    Style { fill: Some(Color::rgb(0, 0, 255).with_opacity(0.4)), stroke: Some(dashed.clone()) },
                ),
                Item::new(
                    Role::Annotation,
                    Shape::Path(vec![
                        PathCmd::MoveTo(Point::new(10.0, 200.0)),
                        PathCmd::LineTo(Point::new(60.0, 180.0)),
                        PathCmd::QuadTo(Point::new(80.0, 150.0), Point::new(100.0, 200.0)),
                        PathCmd::CubicTo(Point::new(120.0, 250.0), Point::new(140.0, 150.0), Point::new(160.0, 200.0)),
                        PathCmd::Close,
                    ]),
                    Style { fill: None, stroke: Some(dashed) },
                ),
                Item::new(Role::DataMark, Shape::Rect(Rect::new(f64::NAN, 0.0, 1.0, 1.0)), Style::fill(Color::BLACK)),
                Item::group(
                    Role::DataMark,
                    vec![
                        Item::new(Role::DataMark, Shape::Points(points), Style::default()).with_rows(vec![0, 1, 2, 3]),
                        Item::new(
                            Role::DataMark,
                            Shape::Image(Raster {
                                dest: Rect::new(300.0, 200.0, 80.0, 80.0),
                                width: 4,
                                height: 4,
                                rgba: Arc::new(rgba),
                                smooth: false,
                            }),
                            Style::default(),
                        ),
                    ],
                    Some(Rect::new(200.0, 100.0, 190.0, 190.0)),
                ),
                Item::new(
                    Role::DataMark,
                    Shape::Lines(LineBatch {
                        points: vec![
                            Point::new(20.0, 60.0),
                            Point::new(60.0, 90.0),
                            Point::new(100.0, 70.0),
                            Point::new(20.0, 80.0),
                            Point::new(f64::NAN, 90.0),
                            Point::new(100.0, 95.0),
                        ],
                        stride: 3,
                        color: PerPoint::Uniform(Color::rgb(120, 0, 160).with_opacity(0.3)),
                        width: 1.5,
                    }),
                    Style::default(),
                )
                .with_rows(vec![4, 5]),
                Item::new(
                    Role::DataMark,
                    Shape::Mesh(Mesh {
                        positions: Arc::new(vec![
                            [120.0, 200.0, 0.0],
                            [180.0, 210.0, 1.0],
                            [140.0, 260.0, 0.5],
                            [f32::NAN, 0.0, 0.0],
                        ]),
                        indices: Arc::new(vec![[0, 1, 2], [0, 1, 3], [0, 2, 9]]),
                        colors: Arc::new(vec![
                            Color::rgb(200, 30, 30),
                            Color::rgb(30, 200, 30),
                            Color::rgb(30, 30, 200),
                        ]),
                        normals: None,
                    }),
                    Style::default(),
                ),
                Item::text(Role::Title, t(Point::new(200.0, 10.0), hostile, Anchor::Middle, Baseline::Top, 0.0)),
                Item::text(
                    Role::AxisTitle,
                    t(Point::new(20.0, 150.0), "Value (units)", Anchor::Middle, Baseline::Middle, -90.0),
                ),
                Item::text(Role::TickLabel, t(Point::new(380.0, 290.0), "1,000", Anchor::End, Baseline::Bottom, 0.0)),
                Item::text(
                    Role::Caption,
                    t(Point::new(10.0, 280.0), "مرحبا بالعالم", Anchor::Start, Baseline::Alphabetic, 0.0),
                ),
            ],
        }
    }

    #[test]
    fn svg_parses_with_usvg() {
        let svg = to_svg(&kitchen_sink());
        let tree = usvg::Tree::from_str(&svg, &usvg::Options::default());
        assert!(tree.is_ok(), "{:?}\n{svg}", tree.err());
        if let Ok(tree) = tree {
            assert_eq!(tree.size().width(), 400.0);
        }
    }

    #[test]
    fn hostile_strings_are_escaped() {
        let svg = to_svg(&kitchen_sink());
        assert!(!svg.contains("<script"));
        assert!(!svg.to_lowercase().contains("onload") && !svg.contains("onclick"));
        assert!(svg.contains("&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot; &apos;"));
        assert!(!svg.contains('\u{7}'));
        assert!(svg.contains("<title>&lt;script&gt;"));
        assert!(svg.contains("שלום עולם") && svg.contains("مرحبا بالعالم"));
        assert!(svg.contains("data-label=\"&lt;script&gt;"));
    }

    #[test]
    fn attributes_and_rounding() {
        let svg = to_svg(&kitchen_sink());
        assert!(svg.contains("x=\"10.12\" y=\"20\" width=\"50\" height=\"30\""), "{svg}");
        assert!(svg.contains("data-role=\"data-mark\" data-row=\"7\""));
        assert!(svg.contains("data-role=\"tick-label\""));
        assert!(svg.contains("fill=\"#0000ff\" fill-opacity=\"0.4\""));
        assert!(svg.contains("stroke-opacity=\"0.502\"") && svg.contains("stroke-dasharray=\"6 3\""));
        assert!(svg.contains("clip-path=\"url(#dataink-clip-0)\""));
        assert!(svg.contains("transform=\"rotate(270 20 150)\""));
        assert!(svg.contains("data:image/png;base64,iVBORw0KGgo"));
        // The NaN rect and the NaN point are skipped; three valid points remain.
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
        assert_eq!(svg.matches("<circle cx").count(), 3);
        assert!(svg.contains("data-row=\"3\""));
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(1.005e3), "1005");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(-12.34567), "-12.35");
    }

    #[test]
    fn point_batches_above_the_limit_become_one_image_of_the_points_bounds() {
        let svg_of = |n: usize| {
            // Points on a 10 × 10 px patch from (20, 30): the raster covers only that patch.
            let centers =
                (0..n).map(|i| Point::new(20.0 + (i % 100) as f64 * 0.1, 30.0 + (i / 100 % 100) as f64 * 0.1));
            let batch = PointBatch {
                centers: centers.collect(),
                radius: PerPoint::Uniform(1.0),
                fill: PerPoint::Uniform(Color::rgb(0, 0, 255)),
                stroke: None,
            };
            let item = Item::new(Role::DataMark, Shape::Points(batch), Style::default());
            to_svg(&Scene { width: 200.0, height: 100.0, background: Color::WHITE, title: None, items: vec![item] })
        };
        let vector = svg_of(PointBatch::VECTOR_LIMIT);
        assert_eq!(vector.matches("<circle").count(), PointBatch::VECTOR_LIMIT);
        assert!(!vector.contains("<image"));
        let raster = svg_of(PointBatch::VECTOR_LIMIT + 1);
        assert_eq!(raster.matches("<circle").count(), 0);
        assert_eq!(raster.matches("<image").count(), 1);
        // Bounds 19..30.9 × 29..40.9 at 2 device pixels per unit: 38..62 × 58..82.
        assert!(raster.contains("x=\"19\" y=\"29\" width=\"12\" height=\"12\""), "{}", &raster[..600]);
        assert!(raster.contains("data-role=\"data-mark\""));
    }

    #[test]
    fn line_batches_and_paths_above_their_limits_become_one_image_of_their_bounds() {
        let scene = |item: Item| Scene {
            width: 200.0,
            height: 100.0,
            background: Color::WHITE,
            title: None,
            items: vec![item],
        };
        // Zig-zags between x = 20 and 40 inside y = 30..50: the raster covers that box and the stroke width + 1 around it.
        let at = |i: usize| Point::new(20.0 + (i % 2) as f64 * 20.0, 30.0 + (i % 21) as f64);
        let lines = |n: usize| {
            let batch = LineBatch {
                points: (0..n).map(at).collect(),
                stride: 2,
                color: PerPoint::Uniform(Color::BLACK),
                width: 2.0,
            };
            to_svg(&scene(Item::new(Role::DataMark, Shape::Lines(batch), Style::default())))
        };
        let vector = lines(LineBatch::VECTOR_LIMIT);
        assert_eq!(vector.matches("<path d").count(), LineBatch::VECTOR_LIMIT / 2);
        let raster = lines(LineBatch::VECTOR_LIMIT + 2);
        assert_eq!((raster.matches("<path").count(), raster.matches("<image").count()), (0, 1));
        assert!(raster.contains("x=\"17\" y=\"27\" width=\"26\" height=\"26\""), "{}", &raster[..600]);
        // The path goes once round the same box (a zig-zag of this many segments across a few
        // pixels is the rasterizer's worst case, minutes in a debug build).
        let around = |i: usize, n: usize| {
            let t = 80.0 * i as f64 / (n - 1) as f64;
            match t {
                t if t < 20.0 => Point::new(20.0 + t, 30.0),
                t if t < 40.0 => Point::new(40.0, 30.0 + (t - 20.0)),
                t if t < 60.0 => Point::new(40.0 - (t - 40.0), 50.0),
                t => Point::new(20.0, 50.0 - (t - 60.0)),
            }
        };
        let path = |n: usize| {
            let cmds = (0..n)
                .map(|i| if i == 0 { PathCmd::MoveTo(around(i, n)) } else { PathCmd::LineTo(around(i, n)) })
                .collect();
            let style = Style::stroke(Color::BLACK, 2.0);
            to_svg(&scene(Item::new(Role::DataMark, Shape::Path(cmds), style)))
        };
        let vector = path(crate::scene::PATH_VECTOR_LIMIT);
        assert_eq!((vector.matches("<path").count(), vector.matches("<image").count()), (1, 0));
        let raster = path(crate::scene::PATH_VECTOR_LIMIT + 1);
        assert_eq!((raster.matches("<path").count(), raster.matches("<image").count()), (0, 1));
        assert!(raster.contains("x=\"17\" y=\"27\" width=\"26\" height=\"26\""), "{}", &raster[..600]);
    }

    /// A 200 × 100 white scene of one item.
    fn scene(item: Item) -> Scene {
        Scene { width: 200.0, height: 100.0, background: Color::WHITE, title: None, items: vec![item] }
    }

    /// A mesh of `n` flat triangles, triangle `k` at depth `depths[k % depths.len()]` in colour
    /// `(k % 256, 0, 0)`, all over one spot.
    fn stacked_mesh(n: usize, depths: &[f32]) -> Mesh {
        let mut positions = Vec::new();
        let mut colors = Vec::new();
        for k in 0..n {
            let z = depths[k % depths.len()];
            let dx = (k % 7) as f32;
            positions.extend([[10.0 + dx, 10.0, z], [40.0 + dx, 12.0, z], [20.0, 40.0 + dx, z]]);
            colors.extend([Color::rgb((k % 256) as u8, 0, 0); 3]);
        }
        let indices = (0..n as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        Mesh { positions: Arc::new(positions), indices: Arc::new(indices), colors: Arc::new(colors), normals: None }
    }

    #[test]
    fn mesh_triangles_are_written_back_to_front() {
        // Given near first: the far triangles must come first in the file.
        let m = stacked_mesh(4, &[3.0, 1.0, 2.0, 0.0]);
        let svg = to_svg(&scene(Item::new(Role::DataMark, Shape::Mesh(m), Style::default()).labelled("f")));
        assert!(usvg::Tree::from_str(&svg, &usvg::Options::default()).is_ok(), "{svg}");
        let fills: Vec<&str> = svg
            .match_indices("<path d=")
            .map(|(i, _)| &svg[i..])
            .filter_map(|s| s.split("fill=\"").nth(1))
            .map(|s| &s[..7])
            .collect();
        // Depths 0, 1, 2, 3 are triangles 3, 1, 2, 0.
        assert_eq!(fills, ["#030000", "#010000", "#020000", "#000000"]);
        assert!(svg.contains("<g data-role=\"data-mark\" data-label=\"f\""), "{svg}");
        // Colours are the mean of the vertices'; broken triangles are left out.
        let m = Mesh {
            positions: Arc::new(vec![[10.0, 10.0, 0.0], [40.0, 10.0, 0.0], [10.0, 40.0, f32::INFINITY]]),
            indices: Arc::new(vec![[0, 1, 2], [0, 1, 7]]),
            colors: Arc::new(vec![Color::rgb(255, 0, 0), Color::rgb(0, 255, 0), Color::rgb(0, 0, 255)]),
            normals: None,
        };
        let svg = to_svg(&scene(Item::new(Role::DataMark, Shape::Mesh(m), Style::default())));
        assert_eq!(svg.matches("<path").count(), 0, "{svg}");
        let m = Mesh {
            positions: Arc::new(vec![[10.0, 10.0, 0.0], [40.0, 10.0, 0.0], [10.0, 40.0, 0.0]]),
            indices: Arc::new(vec![[0, 1, 2]]),
            colors: Arc::new(vec![Color::rgb(255, 0, 0), Color::rgb(0, 255, 0), Color::rgb(0, 0, 255)]),
            normals: None,
        };
        let svg = to_svg(&scene(Item::new(Role::DataMark, Shape::Mesh(m), Style::default())));
        assert!(svg.contains("<path d=\"M10 10L40 10L10 40Z\" fill=\"#555555\" stroke=\"#555555\"/>"), "{svg}");
    }

    #[test]
    fn a_mesh_over_the_cap_becomes_one_image() {
        let at_cap = stacked_mesh(Mesh::VECTOR_LIMIT, &[0.0]);
        let svg = to_svg(&scene(Item::new(Role::DataMark, Shape::Mesh(at_cap), Style::default())));
        assert_eq!((svg.matches("<path").count(), svg.matches("<image").count()), (Mesh::VECTOR_LIMIT, 0));
        let over = stacked_mesh(Mesh::VECTOR_LIMIT + 1, &[0.0, 1.0]);
        let svg = to_svg(&scene(Item::new(Role::DataMark, Shape::Mesh(over), Style::default())));
        assert_eq!((svg.matches("<path").count(), svg.matches("<image").count()), (0, 1));
        assert!(usvg::Tree::from_str(&svg, &usvg::Options::default()).is_ok());
        // The image covers the mesh's vertices (x 10..46, y 10..46) plus a pixel around.
        assert!(svg.contains("x=\"9\" y=\"9\" width=\"38\" height=\"38\""), "{}", &svg[..600]);
    }

    #[test]
    fn line_batches_write_one_path_per_polyline() {
        let p = Point::new;
        let lines = |color, rows: Vec<u32>| {
            let batch = LineBatch {
                points: vec![
                    p(10.0, 10.0),
                    p(20.0, 15.555),
                    p(30.0, 10.0),
                    p(40.0, 12.0),
                    p(10.0, 30.0),
                    p(20.0, 35.0),
                    p(f64::NAN, 1.0),
                    p(40.0, 30.0),
                ],
                stride: 4,
                color,
                width: 1.25,
            };
            let item = Item::new(Role::DataMark, Shape::Lines(batch), Style::default()).with_rows(rows);
            to_svg(&Scene { width: 50.0, height: 50.0, background: Color::WHITE, title: None, items: vec![item] })
        };
        let svg = lines(PerPoint::Uniform(Color::rgb(0, 0, 255).with_opacity(0.2)), vec![3, 8]);
        assert!(usvg::Tree::from_str(&svg, &usvg::Options::default()).is_ok(), "{svg}");
        assert!(
            svg.contains(
                "<g data-role=\"data-mark\" fill=\"none\" stroke=\"#0000ff\" stroke-opacity=\"0.2\" \
                 stroke-width=\"1.25\" stroke-linejoin=\"round\">"
            ),
            "{svg}"
        );
        assert_eq!(svg.matches("<path").count(), 2, "{svg}");
        assert!(svg.contains("<path d=\"M10 10 L20 15.56 L30 10 L40 12\" data-row=\"3\"/>"), "{svg}");
        // The NaN vertex splits the second polyline: two subpaths, and the lone vertex after it
        // (a run of one) is dropped.
        let second = svg.lines().find(|l| l.contains("data-row=\"8\"")).unwrap_or_default();
        assert_eq!(second.matches('M').count(), 1, "{second}");
        let svg = lines(PerPoint::Uniform(Color::BLACK), vec![]);
        assert!(svg.contains("<path d=\"M10 30 L20 35\"/>"), "{svg}");
        // A vertex that is finite on both sides of a break starts a second subpath.
        let batch = LineBatch {
            points: vec![p(1.0, 1.0), p(2.0, 2.0), p(f64::NAN, 3.0), p(4.0, 4.0), p(5.0, 5.0)],
            stride: 5,
            color: PerPoint::Each(vec![Color::rgb(255, 0, 0)]),
            width: 1.0,
        };
        let item = Item::new(Role::DataMark, Shape::Lines(batch), Style::default());
        let svg =
            to_svg(&Scene { width: 10.0, height: 10.0, background: Color::WHITE, title: None, items: vec![item] });
        assert!(svg.contains("<path d=\"M1 1 L2 2 M4 4 L5 5\" stroke=\"#ff0000\"/>"), "{svg}");
        assert_eq!(svg.matches('M').count(), 2, "{svg}");
    }

    #[test]
    fn text_baseline_matches_font_metrics() {
        let m = crate::text::measure("x", 14.0);
        let svg = to_svg(&kitchen_sink());
        // The title is Top-anchored at y = 10: its baseline sits one ascent lower.
        assert!(svg.contains(&format!("y=\"{}\" font-family", num(10.0 + m.ascent))));
    }

    #[test]
    fn base64_known_vectors() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }

    #[test]
    fn empty_and_degenerate_scenes() {
        let s = Scene { width: f64::NAN, height: -1.0, background: Color::TRANSPARENT, title: None, items: vec![] };
        let svg = to_svg(&s);
        assert!(usvg::Tree::from_str(&svg, &usvg::Options::default()).is_err() || svg.contains("width=\"0\""));
    }
}
