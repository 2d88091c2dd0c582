//! Brushes and the row set they make: rectangles and axis ranges drawn with the pointer, turned
//! into data ranges through the chart's scales, and composed (replace, add, subtract) into one
//! row set per data source. Every brush is a spec [`Selection`] evaluated by
//! [`crate::selection::evaluate`], so a saved brush selects exactly the rows the window lit.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::data::Table;
use crate::guide::scale::Scale;
use crate::mark::geometry::{ParallelAxis, Plot};
use crate::scene::Point;
use crate::selection::{self, SelectionError};
use crate::spec::{CategoryValue, Selection};

/// How a new brush combines with the rows already selected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The brush's rows replace the selection (plain drag).
    Replace,
    /// The brush's rows are added (shift).
    Add,
    /// The brush's rows are removed (alt).
    Subtract,
}

/// One brushed region: every range and category set must hold for a row to be in it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Brush {
    /// Inclusive numeric ranges by column.
    pub ranges: BTreeMap<String, [f64; 2]>,
    /// Category sets by column (brushes across band axes).
    pub categories: BTreeMap<String, Vec<String>>,
}

impl Brush {
    /// Whether the brush names no column.
    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty() && self.categories.is_empty()
    }

    /// The brush as a spec selection over data source `data`.
    pub fn selection(&self, data: &str) -> Selection {
        Selection {
            data: data.to_string(),
            range: (!self.ranges.is_empty()).then(|| self.ranges.clone()),
            categories: (!self.categories.is_empty()).then(|| {
                self.categories
                    .iter()
                    .map(|(k, v)| (k.clone(), v.iter().map(|s| CategoryValue::Text(s.clone())).collect()))
                    .collect()
            }),
            combine: None,
            invert: None,
        }
    }

    /// One flag per table row: whether the row lies in the brush.
    pub fn mask(&self, data: &str, table: &Table) -> Result<Vec<bool>, SelectionError> {
        selection::evaluate("brush", &self.selection(data), table).map(|h| h.selected)
    }
}

/// The data interval between two pixel positions on `scale`, rounded to a decimal step no
/// larger than one pixel (so the saved ranges are short numbers that select what was lit).
/// `None` for band scales and degenerate spans.
pub fn data_span(scale: &Scale, a: f64, b: f64) -> Option<[f64; 2]> {
    let (p0, p1) = (a.min(b), a.max(b));
    if !(p0.is_finite() && p1.is_finite()) {
        return None;
    }
    let v0 = scale.invert(p0)?;
    let v1 = scale.invert(p1)?;
    let round_at = |px: f64, v: f64| {
        let step = (scale.invert(px + 0.5)? - scale.invert(px - 0.5)?).abs();
        Some(round_to_step(v, step))
    };
    let (lo, hi) = (round_at(p0, v0)?, round_at(p1, v1)?);
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    (lo.is_finite() && hi.is_finite()).then_some([lo, hi])
}

/// `v` rounded to the largest power of ten not above `step` (unchanged for a bad step).
pub fn round_to_step(v: f64, step: f64) -> f64 {
    if !(step.is_finite() && step > 0.0 && v.is_finite()) {
        return v;
    }
    let e = step.log10().floor() as i32;
    // Divide by an exact power of ten (not multiply by its inexact inverse), so the result is
    // the double nearest the decimal and prints as the short number.
    if e < 0 {
        let k = 10f64.powi(-e);
        (v * k).round() / k
    } else {
        let k = 10f64.powi(e);
        (v / k).round() * k
    }
}

/// The categories of a band scale whose band centres lie between pixel positions `a` and `b`.
fn band_span(scale: &Scale, a: f64, b: f64) -> Option<Vec<String>> {
    let Scale::Band(band) = scale else { return None };
    let (p0, p1) = (a.min(b), a.max(b));
    let picked: Vec<String> = band
        .categories()
        .iter()
        .enumerate()
        .filter(|(i, _)| {
            let c = band.center(*i);
            c >= p0 && c <= p1
        })
        .map(|(_, name)| name.clone())
        .collect();
    Some(picked)
}

/// Add the span between pixel positions `a` and `b` on `scale` (column `field`) to `brush`.
fn add_span(brush: &mut Brush, field: &str, scale: &Scale, a: f64, b: f64) {
    if let Some(cats) = band_span(scale, a, b) {
        brush.categories.insert(field.to_string(), cats);
    } else if let Some(range) = data_span(scale, a, b) {
        brush.ranges.insert(field.to_string(), range);
    }
}

/// The brush of a rectangle dragged from `a` to `b` in a plot (clamped to the plot area), over
/// the plot's columns (only x on a histogram: its heights are counts, not a column).
pub fn brush_in_plot(plot: &Plot, a: Point, b: Point) -> Brush {
    let r = plot.rect;
    let cx = |x: f64| x.clamp(r.x, r.right());
    let cy = |y: f64| y.clamp(r.y, r.bottom());
    let mut brush = Brush::default();
    if let Some(x) = &plot.x {
        add_span(&mut brush, &x.field, &x.scale, cx(a.x), cx(b.x));
    }
    if let Some(y) = &plot.y {
        add_span(&mut brush, &y.field, &y.scale, cy(a.y), cy(b.y));
    }
    brush
}

/// The brush of a range dragged from `y0` to `y1` along a parallel-coordinates axis (clamped
/// to the axis).
pub fn brush_on_axis(axis: &ParallelAxis, y0: f64, y1: f64) -> Brush {
    let c = |y: f64| y.clamp(axis.top, axis.bottom);
    let mut brush = Brush::default();
    add_span(&mut brush, &axis.field, &axis.scale, c(y0), c(y1));
    brush
}

/// The selected rows of one data source: a base (a spec selection the window opened with, or
/// nothing) and the brushes applied since, with the rows they select.
#[derive(Clone, Debug)]
pub struct RowSet {
    /// The data source.
    pub data: String,
    /// Rows of the source's table.
    rows: usize,
    /// The spec selection the set started from: its name, and its ranges when they bound the
    /// selected rows (to outline them).
    base: Option<(String, Option<Brush>)>,
    /// Brushes applied after the base, in order.
    terms: Vec<(Mode, Brush)>,
    /// Rows selected by base and terms; `None` when nothing is selected (every row lit).
    committed: Option<Vec<bool>>,
    /// The brush being dragged, shown live on top of `committed`.
    live: Option<(Mode, Brush, Vec<bool>)>,
}

impl RowSet {
    /// No selection over a table of `rows` rows: every row lit.
    pub fn new(data: &str, rows: usize) -> RowSet {
        RowSet { data: data.to_string(), rows, base: None, terms: Vec::new(), committed: None, live: None }
    }

    /// A set starting from a spec selection (`name`, the selection, its row flags).
    pub fn from_spec(data: &str, name: &str, selection: &Selection, selected: Vec<bool>) -> RowSet {
        let rows = selected.len();
        let bounds = selection.invert != Some(true) && selection.combine != Some(crate::spec::Combine::Or);
        let brush = bounds.then(|| Brush {
            ranges: selection.range.clone().unwrap_or_default(),
            categories: selection
                .categories
                .iter()
                .flatten()
                .map(|(k, v)| {
                    let names = v
                        .iter()
                        .map(|c| match c {
                            CategoryValue::Text(t) => t.clone(),
                            CategoryValue::Number(n) => crate::guide::format::format_value(*n),
                        })
                        .collect();
                    (k.clone(), names)
                })
                .collect(),
        });
        RowSet {
            data: data.to_string(),
            rows,
            base: Some((name.to_string(), brush)),
            terms: Vec::new(),
            committed: Some(selected),
            live: None,
        }
    }

    /// Show `brush` live while it is dragged (replacing any earlier live brush).
    pub fn preview(&mut self, mode: Mode, brush: Brush, table: &Table) -> Result<(), SelectionError> {
        let mask = brush.mask(&self.data, table)?;
        self.live = Some((mode, brush, mask));
        Ok(())
    }

    /// Make the live brush part of the selection (the drag ended). An empty brush (a click)
    /// with `Replace` clears the selection.
    pub fn commit(&mut self) {
        let Some((mode, brush, mask)) = self.live.take() else { return };
        if brush.is_empty() {
            if mode == Mode::Replace {
                self.clear();
            }
            return;
        }
        self.committed = Some(combine(self.committed.as_deref(), mode, &mask));
        if mode == Mode::Replace {
            self.base = None;
            self.terms.clear();
        }
        self.terms.push((mode, brush));
    }

    /// Drop the live brush without applying it.
    pub fn cancel(&mut self) {
        self.live = None;
    }

    /// Clear the selection: every row lit again.
    pub fn clear(&mut self) {
        *self = RowSet::new(&self.data, self.rows);
    }

    /// Whether any row is selected out (a brush or a spec selection is in force).
    pub fn is_active(&self) -> bool {
        self.committed.is_some() || self.live.is_some()
    }

    /// The lit rows, one flag per table row; `None` when nothing is selected (every row lit).
    pub fn mask(&self) -> Option<Vec<bool>> {
        match &self.live {
            Some((mode, _, mask)) => Some(combine(self.committed.as_deref(), *mode, mask)),
            None => self.committed.clone(),
        }
    }

    /// How many rows are lit.
    pub fn count(&self) -> usize {
        self.mask().map_or(self.rows, |m| m.iter().filter(|&&s| s).count())
    }

    /// Rows of the table.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The brushes in force (live one included), for drawing their ranges.
    pub fn brushes(&self) -> Vec<(Mode, &Brush)> {
        let base = self.base.as_ref().and_then(|(_, b)| b.as_ref()).map(|b| (Mode::Replace, b));
        let mut out: Vec<(Mode, &Brush)> = base.into_iter().chain(self.terms.iter().map(|(m, b)| (*m, b))).collect();
        if let Some((m, b, _)) = &self.live {
            if *m == Mode::Replace {
                out.clear();
            }
            out.push((*m, b));
        }
        out
    }

    /// The selection as spec TOML: one `[selection.NAME]` table with the brushed ranges when
    /// one brush (or one spec selection) makes it; when brushes were added or subtracted, one
    /// table per brush (`NAME-1`, `NAME-2`, ...) with a comment saying how they combine, since a
    /// spec selection holds one rectangle. `None` when nothing is selected.
    pub fn to_toml(&self, name: &str) -> Option<String> {
        self.committed.as_ref()?;
        let count = self.count();
        let mut out = format!("# {count} of {} rows of \"{}\" selected in `dataink explore`\n", self.rows, self.data);
        match (&self.base, self.terms.as_slice()) {
            (None, [(Mode::Replace, brush)]) => {
                write_table(&mut out, name, &self.data, brush);
            }
            (Some((spec, _)), []) => {
                let _ = writeln!(out, "# the spec's own [selection.{spec}], unchanged");
            }
            _ => {
                let mut formula = match &self.base {
                    Some((spec, _)) => spec.clone(),
                    None => String::new(),
                };
                for (k, (mode, _)) in self.terms.iter().enumerate() {
                    let op = match mode {
                        Mode::Replace => "",
                        Mode::Add => " + ",
                        Mode::Subtract => " - ",
                    };
                    let _ = write!(formula, "{op}{name}-{}", k + 1);
                }
                let _ = writeln!(
                    out,
                    "# the rows are {formula} (+ adds rows, - removes them); a selection holds one\n\
                     # rectangle, so each brush is its own selection"
                );
                for (k, (_, brush)) in self.terms.iter().enumerate() {
                    write_table(&mut out, &format!("{name}-{}", k + 1), &self.data, brush);
                }
            }
        }
        Some(out)
    }
}

/// `committed` combined with a brush's rows under `mode` (nothing committed: every row lit for
/// subtracting, no row for adding).
fn combine(committed: Option<&[bool]>, mode: Mode, brush: &[bool]) -> Vec<bool> {
    match (mode, committed) {
        (Mode::Replace, _) | (Mode::Add, None) => brush.to_vec(),
        (Mode::Subtract, None) => brush.iter().map(|b| !b).collect(),
        (Mode::Add, Some(c)) => c.iter().zip(brush).map(|(a, b)| *a || *b).collect(),
        (Mode::Subtract, Some(c)) => c.iter().zip(brush).map(|(a, b)| *a && !*b).collect(),
    }
}

/// One `[selection.NAME]` table.
fn write_table(out: &mut String, name: &str, data: &str, brush: &Brush) {
    let _ = writeln!(out, "\n[selection.{}]\ndata = {}", toml_key(name), toml_string(data));
    if !brush.ranges.is_empty() {
        let ranges: Vec<String> =
            brush.ranges.iter().map(|(k, [lo, hi])| format!("{} = [{lo:?}, {hi:?}]", toml_key(k))).collect();
        let _ = writeln!(out, "range = {{ {} }}", ranges.join(", "));
    }
    if !brush.categories.is_empty() {
        let sets: Vec<String> = brush
            .categories
            .iter()
            .map(|(k, v)| {
                let items: Vec<String> = v.iter().map(|s| toml_string(s)).collect();
                format!("{} = [{}]", toml_key(k), items.join(", "))
            })
            .collect();
        let _ = writeln!(out, "categories = {{ {} }}", sets.join(", "));
    }
}

/// A TOML key: bare when it is only letters, digits, `-` and `_`, else quoted.
fn toml_key(key: &str) -> String {
    if !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
        key.to_string()
    } else {
        toml_string(key)
    }
}

/// A TOML basic string with the needed escapes.
fn toml_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{Categories, ColumnValues};
    use crate::guide::scale::LinearScale;
    use crate::mark::geometry::PlotScale;
    use crate::scene::Rect;

    fn table() -> Table {
        Table::from_columns([
            ("a", ColumnValues::Number(vec![0.0, 1.0, 2.0, 3.0, 4.0, f64::NAN])),
            ("b", ColumnValues::Number(vec![10.0, 30.0, 20.0, 40.0, 0.0, 5.0])),
            (
                "k",
                ColumnValues::Text(Categories::from_values([
                    Some("x"),
                    Some("y"),
                    Some("x"),
                    None,
                    Some("y"),
                    Some("x"),
                ])),
            ),
        ])
    }

    /// A 100 × 100 plot: `a` from 0 to 4 across, `b` from 0 to 40 up.
    fn plot() -> Plot {
        Plot {
            rect: Rect::new(0.0, 0.0, 100.0, 100.0),
            x: Some(PlotScale {
                field: "a".into(),
                scale: Scale::Linear(LinearScale::new((0.0, 4.0), (0.0, 100.0), false, 0).unwrap()),
            }),
            y: Some(PlotScale {
                field: "b".into(),
                scale: Scale::Linear(LinearScale::new((0.0, 40.0), (100.0, 0.0), false, 0).unwrap()),
            }),
        }
    }

    #[test]
    fn rectangles_become_rounded_ranges_through_the_scales() {
        // x 25..75 px → a 1..3; y 10..60 px → b 16..36 (upward axis).
        let b = brush_in_plot(&plot(), Point::new(75.0, 10.0), Point::new(25.0, 60.0));
        assert_eq!(b.ranges["a"], [1.0, 3.0]);
        assert_eq!(b.ranges["b"], [16.0, 36.0]);
        // Odd pixels give values rounded to a step below one pixel (0.04 a, 0.4 b).
        let b = brush_in_plot(&plot(), Point::new(33.3, 0.0), Point::new(66.7, 100.0));
        assert_eq!(b.ranges["a"], [1.33, 2.67]);
        assert_eq!(format!("{:?}", b.ranges["a"][0]), "1.33");
        // Outside the plot the rectangle is clamped to it.
        let b = brush_in_plot(&plot(), Point::new(-50.0, -50.0), Point::new(500.0, 500.0));
        assert_eq!(b.ranges["a"], [0.0, 4.0]);
    }

    #[test]
    fn masks_compose_replace_add_subtract_and_clear() {
        let t = table();
        let mut set = RowSet::new("t", t.rows);
        assert_eq!((set.mask(), set.count()), (None, 6));
        let wide = Brush { ranges: [("a".to_string(), [1.0, 3.0])].into(), ..Brush::default() };
        set.preview(Mode::Replace, wide.clone(), &t).unwrap();
        assert_eq!(set.mask().unwrap(), vec![false, true, true, true, false, false]);
        set.commit();
        let high_b = Brush { ranges: [("b".to_string(), [25.0, 100.0])].into(), ..Brush::default() };
        set.preview(Mode::Subtract, high_b.clone(), &t).unwrap();
        assert_eq!(set.mask().unwrap(), vec![false, false, true, false, false, false]);
        set.commit();
        let first = Brush { ranges: [("a".to_string(), [0.0, 0.5])].into(), ..Brush::default() };
        set.preview(Mode::Add, first, &t).unwrap();
        set.commit();
        assert_eq!(set.mask().unwrap(), vec![true, false, true, false, false, false]);
        assert_eq!(set.count(), 2);
        let toml = set.to_toml("pick").unwrap();
        assert!(toml.contains("pick-1 - pick-2 + pick-3"), "{toml}");
        set.clear();
        assert_eq!((set.mask(), set.count()), (None, 6));
        // Subtracting from nothing selected removes from all rows; a click (empty brush) clears.
        set.preview(Mode::Subtract, high_b, &t).unwrap();
        assert_eq!(set.mask().unwrap(), vec![true, false, true, false, true, true]);
        set.commit();
        set.preview(Mode::Replace, Brush::default(), &t).unwrap();
        set.commit();
        assert!(!set.is_active());
    }

    #[test]
    fn one_brush_saves_as_a_selection_that_selects_the_same_rows() {
        let t = table();
        let mut set = RowSet::new("t", t.rows);
        let brush = brush_in_plot(&plot(), Point::new(20.0, 20.0), Point::new(90.0, 95.0));
        set.preview(Mode::Replace, brush, &t).unwrap();
        set.commit();
        let toml = set.to_toml("t-brush").unwrap();
        assert!(
            toml.contains("[selection.t-brush]\ndata = \"t\"\nrange = { a = [0.8, 3.6], b = [2.0, 32.0] }"),
            "{toml}"
        );
        let doc = toml_edit::Document::parse(toml.as_str()).unwrap();
        let range = doc.as_table()["selection"]["t-brush"]["range"].as_inline_table().unwrap();
        let get = |k: &str| -> [f64; 2] {
            let a = range.get(k).unwrap().as_array().unwrap();
            [a.get(0).unwrap().as_float().unwrap(), a.get(1).unwrap().as_float().unwrap()]
        };
        let saved = Selection {
            data: "t".into(),
            range: Some([("a".to_string(), get("a")), ("b".to_string(), get("b"))].into()),
            categories: None,
            combine: None,
            invert: None,
        };
        let again = selection::evaluate("t-brush", &saved, &t).unwrap().selected;
        assert_eq!(Some(again), set.mask());
        assert_eq!(set.mask().unwrap(), vec![false, true, true, false, false, false]);
    }

    #[test]
    fn band_axes_brush_categories_and_keys_are_quoted() {
        let band = crate::guide::scale::BandScale::new(vec!["x".into(), "y".into()], (0.0, 100.0), 0.1, 0.1);
        let Ok(band) = band else { panic!("band scale") };
        let axis = ParallelAxis { field: "k k".into(), x: 0.0, top: 0.0, bottom: 100.0, scale: Scale::Band(band) };
        let b = brush_on_axis(&axis, 0.0, 40.0);
        assert_eq!(b.categories["k k"], vec!["x".to_string()]);
        let mut out = String::new();
        write_table(&mut out, "s", "d\"q", &b);
        assert!(out.contains("data = \"d\\\"q\"\ncategories = { \"k k\" = [\"x\"] }"), "{out}");
        assert_eq!(round_to_step(1234.5, 20.0), 1230.0);
        assert!(round_to_step(f64::NAN, 1.0).is_nan());
    }
}
