//! Drawing a selection: grey context for unselected rows, a legend entry saying what is
//! selected, and translucent bands over the brushed ranges. Shared by every kind that draws
//! `highlight`.

use crate::guide::legend::{Legend, Symbol};
use crate::guide::scale::Scale;
use crate::mark::encode::ColorEncoding;
use crate::scene::{Color, Item, PerPoint, Rect, Role, Shape, Stroke, Style};
use crate::selection::Highlight;

/// Colour of rows outside the selection.
pub const CONTEXT: Color = Color::rgb(0xc8, 0xc8, 0xc8);
/// Colour of brushed ranges.
pub const BRUSH: Color = Color::rgb(0x33, 0x66, 0x99);

/// The legend of a highlight: how many of the drawn `rows` are selected, and the grey of the
/// others.
pub fn legend(highlight: &Highlight, rows: &[u32], symbol: Symbol) -> Legend {
    let selected = rows.iter().filter(|&&r| highlight.contains(r)).count();
    Legend::Categorical {
        title: format!("{}: {selected} of {} rows", highlight.name, rows.len()),
        entries: vec![("not selected".to_string(), CONTEXT)],
        symbol,
    }
}

/// The marks of `rows` in drawing order: without a selection one layer of every row; with one,
/// the unselected rows as grey context first and the selected rows over them. `layer(rows,
/// context)` draws one layer.
pub fn layers(
    rows: &[u32],
    highlight: Option<&Highlight>,
    mut layer: impl FnMut(&[u32], bool) -> Vec<Item>,
) -> Vec<Item> {
    match highlight {
        Some(h) => {
            let (context, selected) = h.split(rows);
            let mut items = layer(&context, true);
            items.extend(layer(&selected, false));
            items
        }
        None => layer(rows, false),
    }
}

/// The colour of `row` at `opacity`: the context grey, or its encoded colour.
pub fn row_color(colors: &ColorEncoding, row: u32, context: bool, opacity: f64) -> Color {
    if context { CONTEXT.with_opacity(opacity) } else { colors.color_of(row).with_opacity(opacity) }
}

/// Fills of a point batch of `rows`: one colour when the layer is grey context or the colour is
/// fixed, else each row's colour.
pub fn point_fill(colors: &ColorEncoding, rows: &[u32], context: bool, opacity: f64) -> PerPoint<Color> {
    match (colors, context) {
        (_, true) => PerPoint::Uniform(CONTEXT.with_opacity(opacity)),
        (ColorEncoding::Fixed(c), false) => PerPoint::Uniform(c.with_opacity(opacity)),
        (other, false) => PerPoint::Each(rows.iter().map(|&r| other.color_of(r).with_opacity(opacity)).collect()),
    }
}

/// The brushed ranges over a plot or cell `rect`: across for the `x` column (name and scale),
/// up for the `y` column; a band spans the whole rect on a side without a range.
pub fn brush(h: &Highlight, rect: Rect, x: (&str, &Scale), y: Option<(&str, &Scale)>) -> Option<Item> {
    let xs = h.range_on(x.0).and_then(|r| pixel_span(r, |v| x.1.map(v), (rect.x, rect.right())));
    let ys = y
        .and_then(|(field, scale)| h.range_on(field).map(|r| (r, scale)))
        .and_then(|(r, scale)| pixel_span(r, |v| scale.map(v), (rect.y, rect.bottom())));
    if xs.is_none() && ys.is_none() {
        return None;
    }
    let (x0, x1) = xs.unwrap_or((rect.x, rect.right()));
    let (y0, y1) = ys.unwrap_or((rect.y, rect.bottom()));
    Some(brush_band(Rect::new(x0, y0, x1 - x0, y1 - y0)))
}

/// A translucent band over a brushed range (`rect` in canvas units).
pub fn brush_band(rect: Rect) -> Item {
    Item::new(
        Role::Annotation,
        Shape::Rect(rect),
        Style { fill: Some(BRUSH.with_opacity(0.10)), stroke: Some(Stroke::solid(BRUSH.with_opacity(0.55), 1.0)) },
    )
    .labelled("brushed range")
}

/// The pixel interval `[lo, hi]` of a brushed data range under `map`, clamped to `bounds`
/// (either order), or `None` when the range lies wholly outside.
pub fn pixel_span(range: (f64, f64), map: impl Fn(f64) -> f64, bounds: (f64, f64)) -> Option<(f64, f64)> {
    let (a, b) = (map(range.0), map(range.1));
    let (lo, hi) = (a.min(b), a.max(b));
    let (blo, bhi) = (bounds.0.min(bounds.1), bounds.0.max(bounds.1));
    let (lo, hi) = (lo.max(blo), hi.min(bhi));
    (lo.is_finite() && hi.is_finite() && lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_span_orders_and_clamps() {
        let map = |v: f64| 100.0 - 10.0 * v; // upward axis: larger values, smaller y
        assert_eq!(pixel_span((1.0, 2.0), map, (0.0, 100.0)), Some((80.0, 90.0)));
        assert_eq!(pixel_span((-5.0, 2.0), map, (100.0, 0.0)), Some((80.0, 100.0)));
        assert_eq!(pixel_span((20.0, 30.0), map, (0.0, 100.0)), None);
    }
}
