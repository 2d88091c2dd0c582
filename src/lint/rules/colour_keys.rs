//! The categorical colour keys a chart shows, read back from its scene: the colour rules CL003
//! and CL004 judge the colours the reader actually sees, whichever kind drew them.
//!
//! A categorical legend is drawn (by `guide::legend`) as an optional title (legend text hung
//! from its top) followed by one row per entry: a swatch (an opaque filled circle or square
//! without outline, or a short horizontal stroked line) and, right of it on the same middle
//! line, the entry's label; a final "… and N more" label summarises entries past the shown
//! ones. Colour bars, stepped bars, size keys and notes never have that shape.

use crate::lint::chart_info::colour_encodings;
use crate::scene::{Baseline, Color, Item, PathCmd, Role, Scene, Shape};
use crate::spec::{Chart, ChartKind};

/// One categorical legend as drawn.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ColourKey {
    /// The legend's title, if it has one.
    pub title: Option<String>,
    /// The shown entries: label and swatch colour, top to bottom.
    pub entries: Vec<(String, Color)>,
    /// Entries summarised as "… and N more" (not drawn).
    pub more: usize,
}

impl ColourKey {
    /// Number of categories, shown or summarised.
    pub fn categories(&self) -> usize {
        self.entries.len() + self.more
    }

    /// How a message names the legend: `legend "Species"` or `legend`.
    pub fn element(&self) -> String {
        match &self.title {
            Some(t) => format!("legend \"{}\"", crate::spec::validate::shorten(t)),
            None => "legend".to_string(),
        }
    }
}

/// Where a chart's categorical colours are chosen, relative to the chart: the colour channel
/// (`"color"`, `"nodes.color"`; empty when the kind colours by a fixed rule) and the key of its
/// palette (`"color.scheme"`, or the chart-level `"scheme"` of kinds whose series or branches
/// take their colours from it).
pub fn palette_keys(chart: &Chart) -> (String, String) {
    if let Some(e) = colour_encodings(chart).first() {
        return (e.key.to_string(), format!("{}.scheme", e.key));
    }
    match &chart.kind {
        ChartKind::Line(_)
        | ChartKind::Interp1d(_)
        | ChartKind::Section(_)
        | ChartKind::Treemap(_)
        | ChartKind::Hypertree(_) => (String::new(), "scheme".to_string()),
        ChartKind::Graph(o) if o.nodes.as_ref().is_some_and(|n| n.color.is_some()) => {
            ("nodes.color".to_string(), "nodes.color.scheme".to_string())
        }
        _ => (String::new(), String::new()),
    }
}

/// The swatch colour and centre of a legend item that looks like a categorical swatch.
fn swatch(item: &Item) -> Option<(Color, f64, f64)> {
    let opaque = |c: Option<Color>| c.filter(|c| c.a == 255);
    match &item.shape {
        Shape::Circle { center, .. } if item.style.stroke.is_none() => {
            Some((opaque(item.style.fill)?, center.x, center.y))
        }
        Shape::Rect(r) if item.style.stroke.is_none() => {
            Some((opaque(item.style.fill)?, r.x + r.w / 2.0, r.y + r.h / 2.0))
        }
        Shape::Path(cmds) if item.style.fill.is_none() => match cmds.as_slice() {
            [PathCmd::MoveTo(a), PathCmd::LineTo(b)] if (a.y - b.y).abs() < 1e-9 => {
                let stroke = item.style.stroke.as_ref()?;
                Some((opaque(Some(stroke.color))?, (a.x + b.x) / 2.0, a.y))
            }
            _ => None,
        },
        _ => None,
    }
}

/// The label of an entry whose swatch is centred at (`x`, `y`): middle-aligned text on the
/// same line, to the right.
fn entry_label(item: &Item, x: f64, y: f64) -> Option<&str> {
    match &item.shape {
        Shape::Text(t) if t.baseline == Baseline::Middle && (t.at.y - y).abs() < 1.0 && t.at.x > x => Some(&t.content),
        _ => None,
    }
}

/// The count in a "… and N more" summary line.
fn more_count(item: &Item) -> Option<usize> {
    let Shape::Text(t) = &item.shape else { return None };
    t.content.strip_prefix("… and ")?.strip_suffix(" more")?.trim().parse().ok()
}

/// A legend being read: its key so far, its swatches' x, the last entry's y and the spacing of
/// its rows (known from the second entry on).
struct Open {
    key: ColourKey,
    x: f64,
    y: f64,
    step: Option<f64>,
}

impl Open {
    /// Whether a swatch at (`x`, `y`) continues this legend: same column, next row down, and
    /// (once known) the same row spacing, so that legends stacked without titles stay apart.
    fn continues(&self, x: f64, y: f64) -> bool {
        let dy = y - self.y;
        (self.x - x).abs() <= 1.0 && dy > 0.0 && self.step.is_none_or(|step| (dy - step).abs() <= 1.0)
    }
}

/// Every categorical legend of `scene`, in drawing order; legends without entries are left out.
pub fn colour_keys(scene: &Scene) -> Vec<ColourKey> {
    let mut items: Vec<&Item> = Vec::new();
    scene.walk(|item| {
        if item.role == Role::Legend && !matches!(item.shape, Shape::Group { .. }) {
            items.push(item);
        }
    });
    let mut keys = Vec::new();
    let mut current: Option<Open> = None;
    let mut title: Option<String> = None;
    let close = |current: &mut Option<Open>, keys: &mut Vec<ColourKey>| {
        if let Some(open) = current.take()
            && open.key.categories() > 0
        {
            keys.push(open.key);
        }
    };
    let mut i = 0;
    while let Some(item) = items.get(i) {
        if let Some((color, x, y)) = swatch(item)
            && let Some(label) = items.get(i + 1).and_then(|next| entry_label(next, x, y))
        {
            if current.as_ref().is_some_and(|open| !open.continues(x, y)) {
                close(&mut current, &mut keys);
            }
            let open = current.get_or_insert_with(|| Open {
                key: ColourKey { title: title.take(), ..ColourKey::default() },
                x,
                y: f64::NAN,
                step: None,
            });
            if open.y.is_finite() {
                open.step = open.step.or(Some(y - open.y));
            }
            open.y = y;
            open.key.entries.push((label.to_string(), color));
            i += 2;
            continue;
        }
        match (&item.shape, more_count(item), current.as_mut()) {
            (_, Some(n), Some(open)) => open.key.more += n,
            // A legend too short to show any entry is only its summary line.
            (_, Some(n), None) => {
                let key = ColourKey { title: title.take(), entries: Vec::new(), more: n };
                current = Some(Open { key, x: f64::NAN, y: f64::NAN, step: None });
            }
            (Shape::Text(t), _, _) if t.baseline == Baseline::Top => {
                close(&mut current, &mut keys);
                title = Some(t.content.clone());
            }
            _ => {
                close(&mut current, &mut keys);
                title = None;
            }
        }
        i += 1;
    }
    close(&mut current, &mut keys);
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::guide::Theme;
    use crate::guide::color::continuous;
    use crate::guide::legend::{Legend, Symbol, draw_stack};
    use crate::scene::Point;

    fn scene_of(legends: &[Legend], height: f64) -> Scene {
        let theme = Theme::default();
        let items = draw_stack(legends, Point::new(500.0, 20.0), &theme, height);
        Scene { width: 640.0, height: 420.0, background: Color::WHITE, title: None, items }
    }

    fn entries(n: usize) -> Vec<(String, Color)> {
        (0..n).map(|i| (format!("c{i}"), Color::rgb((i * 8) as u8, 100, 200))).collect()
    }

    #[test]
    fn reads_back_every_categorical_legend_and_nothing_else() {
        let legends = vec![
            Legend::Categorical { title: "Species".into(), entries: entries(3), symbol: Symbol::Circle },
            Legend::ColorBar { title: "depth".into(), map: continuous("viridis").unwrap(), domain: (0.0, 1.0) },
            Legend::Steps { title: "z".into(), edges: vec![0.0, 1.0, 2.0, 3.0], colors: vec![Color::BLACK; 3] },
            Legend::Size {
                title: "size".into(),
                entries: vec![("1".into(), 3.0), ("10".into(), 9.0)],
                color: Color::BLACK,
            },
            Legend::Categorical { title: "series".into(), entries: entries(2), symbol: Symbol::Line },
            Legend::Categorical { title: String::new(), entries: entries(30), symbol: Symbol::Square },
        ];
        let keys = colour_keys(&scene_of(&legends, 2000.0));
        assert_eq!(keys.len(), 3, "{keys:?}");
        assert_eq!(keys[0].title.as_deref(), Some("Species"));
        assert_eq!(keys[0].entries, entries(3));
        assert_eq!(keys[0].element(), "legend \"Species\"");
        assert_eq!(keys[1].title.as_deref(), Some("series"));
        assert_eq!(keys[1].entries, entries(2));
        // 24 shown, 6 summarised.
        assert_eq!(keys[2].title, None);
        assert_eq!((keys[2].entries.len(), keys[2].more, keys[2].categories()), (24, 6, 30));
        assert_eq!(keys[2].element(), "legend");
    }

    #[test]
    fn a_legend_with_room_for_no_entry_still_counts() {
        let legends = vec![
            Legend::Categorical { title: "a".into(), entries: entries(3), symbol: Symbol::Circle },
            Legend::Categorical { title: "b".into(), entries: entries(30), symbol: Symbol::Circle },
        ];
        // Room for the first legend and the second's title and summary line only.
        let keys = colour_keys(&scene_of(&legends, 130.0));
        assert_eq!(keys.len(), 2, "{keys:?}");
        assert_eq!((keys[1].title.as_deref(), keys[1].categories()), (Some("b"), 30), "{keys:?}");
    }

    #[test]
    fn transparent_entries_have_no_swatch() {
        let mut e = entries(2);
        e.push(("none".into(), Color::TRANSPARENT));
        let legend = Legend::Categorical { title: "t".into(), entries: e, symbol: Symbol::Square };
        let keys = colour_keys(&scene_of(&[legend], 400.0));
        assert_eq!(keys.len(), 1);
        assert_eq!(keys[0].entries, entries(2));
    }
}
