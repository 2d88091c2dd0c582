//! Relighting drawn marks for a new row set without drawing the chart again.
//!
//! A brushable chart is drawn once with every row selected ([`all_lit`]), so its layout already
//! holds the selection legend and each data-mark batch holds every drawn row in its own colour.
//! [`split`] then turns one such batch into the two layers the kinds draw for a selection —
//! the other rows in the context grey first, the selected rows in their colours over them
//! (see `mark::highlight::layers`) — and [`count_text`] rewrites the legend's count. Drawing the
//! chart with the selection as a [`Highlight`] gives the same marks; only the brushed-range
//! bands, which the window draws itself while brushing, are left out.

use crate::mark::highlight::CONTEXT;
use crate::scene::{Color, Item, LineBatch, PerPoint, Point, PointBatch, Role, Shape, Text};
use crate::selection::Highlight;
use crate::spec::Selection;

/// Name of the selection the window draws: the legend reads "selected: K of N rows".
pub const LIT: &str = "selected";

/// A highlight over `rows` table rows of source `data` that selects every row: the base a
/// brushable chart is drawn with.
pub fn all_lit(data: &str, rows: usize) -> Highlight {
    let selection = Selection { data: data.to_string(), range: None, categories: None, combine: None, invert: None };
    Highlight { name: LIT.to_string(), selection, selected: vec![true; rows] }
}

/// Whether `item` is a data-mark batch with source rows (what a selection relights).
pub fn is_marks(item: &Item) -> bool {
    item.role == Role::DataMark && !item.rows.is_empty() && matches!(item.shape, Shape::Points(_) | Shape::Lines(_))
}

/// Whether `item` is the legend title counting the selected rows.
pub fn is_count(item: &Item) -> bool {
    item.role == Role::Legend
        && matches!(&item.shape, Shape::Text(t) if t.content.starts_with(&format!("{LIT}: ")) && t.content.ends_with(" rows"))
}

/// The lit and drawn rows of a marks batch under `mask` (`None`: every row lit).
pub fn lit_of(item: &Item, mask: Option<&[bool]>) -> (usize, usize) {
    let n = item.rows.len();
    let lit = match mask {
        None => n,
        Some(m) => item.rows.iter().filter(|&&r| m.get(r as usize).copied().unwrap_or(false)).count(),
    };
    (lit, n)
}

/// The count legend title for `lit` of `drawn` rows.
pub fn count_text(text: &Text, lit: usize, drawn: usize) -> Text {
    Text { content: format!("{LIT}: {lit} of {drawn} rows"), ..text.clone() }
}

/// A marks batch split by `mask` into grey context (rows not lit) and the lit rows in their own
/// colours, in that drawing order. Without a mask the batch is returned as it is. Other items
/// are returned unchanged.
pub fn split(item: &Item, mask: Option<&[bool]>) -> Vec<Item> {
    let Some(mask) = mask else { return vec![item.clone()] };
    let lit = |r: u32| mask.get(r as usize).copied().unwrap_or(false);
    let (context, selected): (Vec<usize>, Vec<usize>) = (0..item.rows.len()).partition(|&i| !lit(item.rows[i]));
    let rows_of = |idx: &[usize]| -> Vec<u32> { idx.iter().map(|&i| item.rows[i]).collect() };
    let layer = |shape: Shape, idx: &[usize]| Item { shape, rows: rows_of(idx), ..item.clone_empty() };
    match &item.shape {
        Shape::Points(b) => {
            let grey = PerPoint::Uniform(CONTEXT.with_opacity(alpha(b.fill.at(0))));
            let points = |idx: &[usize], fill: PerPoint<Color>| {
                Shape::Points(PointBatch {
                    centers: idx.iter().filter_map(|&i| b.centers.get(i).copied()).collect(),
                    radius: pick(&b.radius, idx),
                    fill,
                    stroke: b.stroke.clone(),
                })
            };
            vec![layer(points(&context, grey), &context), layer(points(&selected, pick(&b.fill, &selected)), &selected)]
        }
        Shape::Lines(b) => {
            let grey = PerPoint::Uniform(CONTEXT.with_opacity(alpha(b.color.at(0))));
            let lines = |idx: &[usize], color: PerPoint<Color>| {
                let mut points: Vec<Point> = Vec::with_capacity(idx.len() * b.stride);
                for &i in idx {
                    points.extend_from_slice(b.polyline(i).unwrap_or(&[]));
                }
                Shape::Lines(LineBatch { points, stride: b.stride, color, width: b.width })
            };
            vec![layer(lines(&context, grey), &context), layer(lines(&selected, pick(&b.color, &selected)), &selected)]
        }
        _ => vec![item.clone()],
    }
}

/// Opacity of a colour (1 when absent).
fn alpha(c: Option<Color>) -> f64 {
    c.map_or(1.0, Color::alpha)
}

/// The values of `idx` from a per-point value.
fn pick<T: Copy>(values: &PerPoint<T>, idx: &[usize]) -> PerPoint<T> {
    match values {
        PerPoint::Uniform(v) => PerPoint::Uniform(*v),
        PerPoint::Each(vs) => PerPoint::Each(idx.iter().filter_map(|&i| vs.get(i).copied()).collect()),
    }
}

/// An item's role, style and label without its geometry and rows (cheap to clone).
trait CloneEmpty {
    fn clone_empty(&self) -> Item;
}

impl CloneEmpty for Item {
    fn clone_empty(&self) -> Item {
        Item {
            role: self.role,
            shape: Shape::Group { items: Vec::new(), clip: None },
            style: self.style.clone(),
            rows: Vec::new(),
            label: self.label.clone(),
            tooltips: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Style;

    #[test]
    fn split_puts_grey_context_under_the_lit_rows_in_their_colours() {
        let red = Color::rgb(200, 0, 0).with_opacity(0.5);
        let blue = Color::rgb(0, 0, 200).with_opacity(0.5);
        let batch = PointBatch {
            centers: (0..4).map(|i| Point::new(i as f64, 0.0)).collect(),
            radius: PerPoint::Each(vec![1.0, 2.0, 3.0, 4.0]),
            fill: PerPoint::Each(vec![red, blue, red, blue]),
            stroke: None,
        };
        let item = Item::new(Role::DataMark, Shape::Points(batch), Style::default()).with_rows(vec![7, 3, 5, 1]);
        assert!(is_marks(&item));
        let mut mask = vec![false; 8];
        mask[3] = true;
        mask[5] = true;
        let layers = split(&item, Some(&mask));
        assert_eq!(layers.len(), 2);
        assert_eq!((layers[0].rows.clone(), layers[1].rows.clone()), (vec![7, 1], vec![3, 5]));
        let (Shape::Points(grey), Shape::Points(lit)) = (&layers[0].shape, &layers[1].shape) else { panic!("points") };
        assert_eq!(grey.fill, PerPoint::Uniform(CONTEXT.with_opacity(0.5)));
        assert_eq!(grey.radius, PerPoint::Each(vec![1.0, 4.0]));
        assert_eq!(lit.fill, PerPoint::Each(vec![blue, red]));
        assert_eq!(lit.centers, vec![Point::new(1.0, 0.0), Point::new(2.0, 0.0)]);
        assert_eq!(lit_of(&item, Some(&mask)), (2, 4));
        assert_eq!(split(&item, None), vec![item.clone()]);
    }

    #[test]
    fn split_lines_keeps_whole_polylines() {
        let batch = LineBatch {
            points: (0..6).map(|i| Point::new(i as f64, i as f64)).collect(),
            stride: 2,
            color: PerPoint::Uniform(Color::BLACK.with_opacity(0.1)),
            width: 1.0,
        };
        let item = Item::new(Role::DataMark, Shape::Lines(batch), Style::default()).with_rows(vec![0, 1, 2]);
        let layers = split(&item, Some(&[true, false, true]));
        let (Shape::Lines(grey), Shape::Lines(lit)) = (&layers[0].shape, &layers[1].shape) else { panic!("lines") };
        assert_eq!(grey.points, vec![Point::new(2.0, 2.0), Point::new(3.0, 3.0)]);
        assert_eq!(lit.len(), 2);
        assert_eq!(grey.color, PerPoint::Uniform(CONTEXT.with_opacity(Color::BLACK.with_opacity(0.1).alpha())));
    }
}
