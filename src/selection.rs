//! Selections: named brushes (`[selection.NAME]`) evaluated to the set of rows they select.
//!
//! A selection is evaluated once per spec against its data source; every chart of that source
//! that names it in `highlight` receives the same row mask, which is what links the views.

use crate::data::{Column, Table};
use crate::guide::format::format_value;
use crate::spec::{CategoryValue, Combine, PathSeg, Selection};

/// A selection evaluated against its table: one flag per table row.
#[derive(Clone, Debug, PartialEq)]
pub struct Highlight {
    /// The selection's name.
    pub name: String,
    /// The selection as written.
    pub selection: Selection,
    /// `selected[row]` for every row of the table.
    pub selected: Vec<bool>,
}

impl Highlight {
    /// Whether table row `row` is selected.
    pub fn contains(&self, row: u32) -> bool {
        self.selected.get(row as usize).copied().unwrap_or(false)
    }

    /// Split `rows` into (context, selected), keeping their order.
    pub fn split(&self, rows: &[u32]) -> (Vec<u32>, Vec<u32>) {
        rows.iter().partition(|&&r| !self.contains(r))
    }

    /// The brushed numeric range on `column`, if the selection has one (`None` for `or`
    /// selections and inverted ones, whose ranges do not bound the selected rows on one axis).
    pub fn range_on(&self, column: &str) -> Option<(f64, f64)> {
        if !self.bounds_rows() {
            return None;
        }
        self.selection.range.as_ref()?.get(column).map(|r| (r[0], r[1]))
    }

    /// The brushed categories on `column`, if the selection has a set for it (`None` for `or`
    /// and inverted selections).
    pub fn categories_on(&self, column: &str) -> Option<Vec<String>> {
        if !self.bounds_rows() {
            return None;
        }
        let set = self.selection.categories.as_ref()?.get(column)?;
        Some(set.iter().map(category_text).collect())
    }

    /// Whether every condition bounds the selected rows on its own (an `and` selection, not
    /// inverted), so that its ranges and sets can be drawn on their axes.
    fn bounds_rows(&self) -> bool {
        self.selection.invert != Some(true) && self.selection.combine != Some(Combine::Or)
    }
}

/// Why a selection could not be evaluated, with the spec path it is about.
#[derive(Clone, Debug, PartialEq)]
pub struct SelectionError {
    /// What went wrong.
    pub message: String,
    /// How to fix it.
    pub hint: String,
    /// Where in the spec (e.g. `selection.small.range.petal_length`).
    pub path: Vec<PathSeg>,
}

/// Text of a category value as it is compared with a text column.
fn category_text(value: &CategoryValue) -> String {
    match value {
        CategoryValue::Text(s) => s.clone(),
        CategoryValue::Number(n) => format_value(*n),
    }
}

/// Evaluate selection `name` against `table`.
pub fn evaluate(name: &str, selection: &Selection, table: &Table) -> Result<Highlight, SelectionError> {
    let path = |kind: &str, column: &str| {
        vec![
            PathSeg::Key("selection".into()),
            PathSeg::Key(name.into()),
            PathSeg::Key(kind.into()),
            PathSeg::Key(column.into()),
        ]
    };
    let lookup = |kind: &str, column: &str| -> Result<&Column, SelectionError> {
        table.column(column).ok_or_else(|| {
            let hint = crate::spec::suggest::hint(column, &table.column_names(), "columns", true);
            SelectionError {
                message: format!("selection \"{name}\": data \"{}\" has no column `{column}`", selection.data),
                hint,
                path: path(kind, column),
            }
        })
    };

    let mut conditions: Vec<Vec<bool>> = Vec::new();
    for (column, [lo, hi]) in selection.range.iter().flatten() {
        let col = lookup("range", column)?;
        let Some(values) = col.numbers() else {
            return Err(SelectionError {
                message: format!("selection \"{name}\": `range` on `{column}`, which holds text"),
                hint: format!("select categories instead: `categories = {{ {column} = [\"...\"] }}`"),
                path: path("range", column),
            });
        };
        // NaN fails both comparisons, so missing values are never selected.
        conditions.push(values.iter().map(|v| *v >= *lo && *v <= *hi).collect());
    }
    for (column, set) in selection.categories.iter().flatten() {
        let col = lookup("categories", column)?;
        conditions.push(category_matches(col, set));
    }

    let combine = selection.combine.unwrap_or(Combine::And);
    let mut selected = match combine {
        Combine::And => vec![true; table.rows],
        Combine::Or => vec![false; table.rows],
    };
    for condition in &conditions {
        for (s, c) in selected.iter_mut().zip(condition) {
            *s = match combine {
                Combine::And => *s && *c,
                Combine::Or => *s || *c,
            };
        }
    }
    if conditions.is_empty() {
        selected.iter_mut().for_each(|s| *s = false);
    }
    if selection.invert == Some(true) {
        selected.iter_mut().for_each(|s| *s = !*s);
    }
    Ok(Highlight { name: name.to_string(), selection: selection.clone(), selected })
}

/// Which rows of `column` are in the category set.
fn category_matches(column: &Column, set: &[CategoryValue]) -> Vec<bool> {
    if let Some(values) = column.numbers() {
        let wanted: Vec<f64> = set
            .iter()
            .filter_map(|v| match v {
                CategoryValue::Number(n) => Some(*n),
                CategoryValue::Text(s) => s.trim().parse().ok(),
            })
            .collect();
        return values.iter().map(|v| wanted.contains(v)).collect();
    }
    let Some(cats) = column.categories() else { return vec![false; column.len()] };
    let wanted: Vec<String> = set.iter().map(category_text).collect();
    (0..column.len()).map(|row| cats.value(row).is_some_and(|v| wanted.iter().any(|w| w == v))).collect()
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::data::{Categories, ColumnValues};

    fn table() -> Table {
        Table::from_columns([
            ("x", ColumnValues::Number(vec![0.0, 1.0, 2.0, f64::NAN, 4.0])),
            ("cyl", ColumnValues::Number(vec![4.0, 6.0, 8.0, 4.0, 6.0])),
            ("kind", ColumnValues::Text(Categories::from_values([Some("a"), Some("b"), None, Some("a"), Some("c")]))),
        ])
    }

    fn selection(range: &[(&str, [f64; 2])], cats: &[(&str, Vec<CategoryValue>)], combine: Combine) -> Selection {
        Selection {
            data: "t".into(),
            range: Some(range.iter().map(|(k, v)| (k.to_string(), *v)).collect::<BTreeMap<_, _>>()),
            categories: Some(cats.iter().map(|(k, v)| (k.to_string(), v.clone())).collect()),
            combine: Some(combine),
            invert: None,
        }
    }

    fn text(s: &str) -> CategoryValue {
        CategoryValue::Text(s.into())
    }

    #[test]
    fn ranges_are_inclusive_and_skip_missing_values() {
        let h = evaluate("s", &selection(&[("x", [1.0, 4.0])], &[], Combine::And), &table()).unwrap();
        assert_eq!(h.selected, vec![false, true, true, false, true]);
        assert_eq!(h.split(&[0, 1, 2, 3, 4]), (vec![0, 3], vec![1, 2, 4]));
        assert_eq!(h.range_on("x"), Some((1.0, 4.0)));
    }

    #[test]
    fn and_or_and_invert_combine_conditions() {
        let t = table();
        let conds = |c| selection(&[("x", [0.0, 1.0])], &[("kind", vec![text("a"), text("c")])], c);
        assert_eq!(evaluate("s", &conds(Combine::And), &t).unwrap().selected, vec![true, false, false, false, false]);
        assert_eq!(evaluate("s", &conds(Combine::Or), &t).unwrap().selected, vec![true, true, false, true, true]);
        let mut inverted = conds(Combine::And);
        inverted.invert = Some(true);
        let h = evaluate("s", &inverted, &t).unwrap();
        assert_eq!(h.selected, vec![false, true, true, true, true]);
        // An inverted brush does not bound the selected rows, so no range is drawn.
        assert_eq!(h.range_on("x"), None);
    }

    #[test]
    fn numeric_codes_match_numeric_columns() {
        let s = selection(&[], &[("cyl", vec![CategoryValue::Number(4.0), text("8")])], Combine::And);
        assert_eq!(evaluate("s", &s, &table()).unwrap().selected, vec![true, false, true, true, false]);
    }

    #[test]
    fn unknown_columns_and_text_ranges_are_errors_with_paths() {
        let e = evaluate("s", &selection(&[("kindd", [0.0, 1.0])], &[], Combine::And), &table()).unwrap_err();
        assert!(e.message.contains("no column `kindd`"), "{}", e.message);
        assert!(e.hint.contains("did you mean `kind`"), "{}", e.hint);
        assert_eq!(e.path[0], PathSeg::Key("selection".into()));
        assert_eq!(e.path[3], PathSeg::Key("kindd".into()));
        let e = evaluate("s", &selection(&[("kind", [0.0, 1.0])], &[], Combine::And), &table()).unwrap_err();
        assert!(e.message.contains("holds text"), "{}", e.message);
    }
}
