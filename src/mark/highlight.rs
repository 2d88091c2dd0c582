//! Drawing a selection: grey context for unselected rows, a legend entry saying what is
//! selected, and translucent bands over the brushed ranges. Shared by every kind that draws
//! `highlight`.

use crate::guide::legend::{Legend, Symbol};
use crate::scene::{Color, Item, Rect, Role, Shape, Stroke, Style};
use crate::selection::Highlight;

/// Colour of rows outside the selection.
pub const CONTEXT: Color = Color::rgb(0xc8, 0xc8, 0xc8);
/// Colour of brushed ranges.
pub const BRUSH: Color = Color::rgb(0x33, 0x66, 0x99);

/// The legend of a highlight: how many rows are selected, and the grey of the others.
pub fn legend(highlight: &Highlight, selected: usize, total: usize, symbol: Symbol) -> Legend {
    Legend::Categorical {
        title: format!("{}: {selected} of {total} rows", highlight.name),
        entries: vec![("not selected".to_string(), CONTEXT)],
        symbol,
    }
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
