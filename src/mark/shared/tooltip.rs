//! Hover text for data marks: each mark drawn from one row gets that row's values of the chosen
//! columns ("species: setosa"), one line each; a mark drawn from several rows (a bar's sum, a
//! histogram bin, a contour) gets its label and its row count, unless its kind wrote a better
//! text while drawing (see [`Item::with_tooltip`]). The SVG renderer writes them as `<title>`
//! elements, which browsers show on hover.

use crate::data::{Column, ColumnValues, Table};
use crate::guide::time::format_timestamp;
use crate::mark::encode::MISSING_LABEL;
use crate::scene::{Item, Role, Scene, Shape};

/// Charts with more hover texts than this carry none unless the spec lists the columns: a
/// title per point would grow a large scatter's SVG by megabytes.
pub const TOOLTIP_LIMIT: usize = 5_000;

/// What the marks of a chart show on hover.
pub struct Tooltips<'a> {
    /// The table the marks' rows index.
    pub table: &'a Table,
    /// The columns a one-row mark lists, in order (missing ones are skipped).
    pub fields: Vec<String>,
    /// Whether the marks' rows index `table` (false for kinds whose marks index another table,
    /// such as a network's node table): then only labels and row counts are shown.
    pub rows_index_table: bool,
    /// Attach them however many there are (the spec listed the columns).
    pub unlimited: bool,
}

impl Tooltips<'_> {
    /// Attach hover texts to the data marks of `scene`; returns how many were attached (none
    /// when there would be more than [`TOOLTIP_LIMIT`] and the texts are not `unlimited`).
    pub fn attach(&self, scene: &mut Scene) -> usize {
        let needed: usize = count(&scene.items);
        if needed == 0 || (!self.unlimited && needed > TOOLTIP_LIMIT) {
            return 0;
        }
        let columns: Vec<(&str, &Column)> =
            self.fields.iter().filter_map(|f| self.table.column(f).map(|c| (f.as_str(), c))).collect();
        self.visit(&mut scene.items, &columns);
        needed
    }

    fn visit(&self, items: &mut [Item], columns: &[(&str, &Column)]) {
        for item in items {
            if let Shape::Group { items, .. } = &mut item.shape {
                self.visit(items, columns);
                continue;
            }
            // Kinds that know better (a bar's sum, a histogram's bin) write their own.
            if item.role != Role::DataMark || item.rows.is_empty() || !item.tooltips.is_empty() {
                continue;
            }
            item.tooltips = match (&item.shape, item.rows.as_slice()) {
                (Shape::Points(_) | Shape::Lines(_), rows) if per_element(item) => {
                    rows.iter().map(|&r| self.row_text(r, columns, item.label.as_deref())).collect()
                }
                (_, [row]) => vec![self.row_text(*row, columns, item.label.as_deref())],
                (_, rows) => vec![group_text(item.label.as_deref(), rows.len())],
            };
        }
    }

    /// The values of one row, one `column: value` line each; the label when the rows index
    /// another table or no column is listed.
    fn row_text(&self, row: u32, columns: &[(&str, &Column)], label: Option<&str>) -> String {
        if !self.rows_index_table || columns.is_empty() {
            return label.unwrap_or_default().to_string();
        }
        let lines: Vec<String> =
            columns.iter().map(|(name, column)| format!("{name}: {}", cell_text(column, row as usize))).collect();
        lines.join("\n")
    }
}

/// Whether a batch item carries one row per element (point or polyline).
fn per_element(item: &Item) -> bool {
    match &item.shape {
        Shape::Points(batch) => item.rows.len() == batch.centers.len(),
        Shape::Lines(batch) => item.rows.len() == batch.len(),
        _ => false,
    }
}

/// The hover texts the data marks of `items` need.
fn count(items: &[Item]) -> usize {
    items
        .iter()
        .map(|item| match &item.shape {
            Shape::Group { items, .. } => count(items),
            _ if item.role != Role::DataMark || item.rows.is_empty() || !item.tooltips.is_empty() => 0,
            _ if per_element(item) => item.rows.len(),
            _ => 1,
        })
        .sum()
}

/// The text of a mark drawn from several rows: its label and how many rows it stands for.
fn group_text(label: Option<&str>, rows: usize) -> String {
    let rows = if rows == 1 { "1 row".to_string() } else { format!("{rows} rows") };
    match label {
        Some(l) if !l.is_empty() => format!("{l}\n{rows}"),
        _ => rows,
    }
}

/// A cell as text: the full number (shortest round-trip form), the date and time, or the
/// category; `(missing)` for a missing or non-finite cell.
pub fn cell_text(column: &Column, row: usize) -> String {
    let number = |v: Option<&f64>| match v {
        Some(v) if v.is_finite() => {
            if column.is_time() {
                let t = format_timestamp(*v);
                t.strip_suffix(" 00:00:00").map(str::to_string).unwrap_or(t)
            } else {
                // −0 + 0 = +0: the two zeros are one value, written "0".
                format!("{}", v + 0.0)
            }
        }
        _ => MISSING_LABEL.to_string(),
    };
    match &column.values {
        ColumnValues::Axis(axis) => {
            number(axis.coords().get((row / axis.repeat().max(1)) % axis.coords().len().max(1)))
        }
        _ => match (column.numbers(), column.categories()) {
            (Some(values), _) => number(values.get(row)),
            (None, Some(cats)) => cats.value(row).unwrap_or(MISSING_LABEL).to_string(),
            (None, None) => MISSING_LABEL.to_string(),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::Categories;
    use crate::scene::{Color, PerPoint, Point, PointBatch, Rect, Style};

    fn table() -> Table {
        Table::from_columns([
            ("x", ColumnValues::Number(vec![1.5, f64::NAN, 3.0])),
            ("kind", ColumnValues::Text(Categories::from_values([Some("a"), None, Some("c")]))),
        ])
    }

    fn points(rows: Vec<u32>) -> Item {
        let centers = rows.iter().map(|&r| Point::new(f64::from(r), 0.0)).collect();
        let batch =
            PointBatch { centers, radius: PerPoint::Uniform(2.0), fill: PerPoint::Uniform(Color::BLACK), stroke: None };
        Item::new(Role::DataMark, Shape::Points(batch), Style::default()).with_rows(rows)
    }

    fn scene(items: Vec<Item>) -> Scene {
        Scene { width: 10.0, height: 10.0, background: Color::WHITE, title: None, items }
    }

    #[test]
    fn one_row_marks_list_their_values_and_group_marks_their_label_and_count() {
        let table = table();
        let tips = Tooltips {
            table: &table,
            fields: vec!["x".into(), "kind".into(), "nope".into()],
            rows_index_table: true,
            unlimited: false,
        };
        let bar = Item::new(Role::DataMark, Shape::Rect(Rect::new(0.0, 0.0, 1.0, 1.0)), Style::default())
            .with_rows(vec![0, 2])
            .labelled("a, c");
        let axis =
            Item::new(Role::Axis, Shape::Rect(Rect::new(0.0, 0.0, 1.0, 1.0)), Style::default()).with_rows(vec![0]);
        let mut s = scene(vec![Item::group(Role::DataMark, vec![points(vec![0, 1, 2]), bar], None), axis]);
        assert_eq!(tips.attach(&mut s), 4);
        let Shape::Group { items, .. } = &s.items[0].shape else { panic!() };
        assert_eq!(items[0].tooltips, ["x: 1.5\nkind: a", "x: (missing)\nkind: (missing)", "x: 3\nkind: c"]);
        assert_eq!(items[1].tooltips, ["a, c\n2 rows"]);
        assert!(s.items[1].tooltips.is_empty(), "only data marks get hover text");
    }

    #[test]
    fn too_many_marks_get_none_unless_the_columns_are_listed() {
        let table = Table::from_columns([("x", ColumnValues::Number(vec![0.0; TOOLTIP_LIMIT + 1]))]);
        let rows: Vec<u32> = (0..=TOOLTIP_LIMIT as u32).collect();
        let mut tips = Tooltips { table: &table, fields: vec!["x".into()], rows_index_table: true, unlimited: false };
        let mut s = scene(vec![points(rows.clone())]);
        assert_eq!(tips.attach(&mut s), 0);
        assert!(s.items[0].tooltips.is_empty());
        tips.unlimited = true;
        assert_eq!(tips.attach(&mut s), TOOLTIP_LIMIT + 1);
        assert_eq!(s.items[0].tooltips.len(), TOOLTIP_LIMIT + 1);
    }

    #[test]
    fn marks_indexing_another_table_show_their_label_only() {
        let table = table();
        let tips = Tooltips { table: &table, fields: vec!["x".into()], rows_index_table: false, unlimited: false };
        let node =
            Item::new(Role::DataMark, Shape::Circle { center: Point::new(0.0, 0.0), radius: 1.0 }, Style::default())
                .with_rows(vec![1])
                .labelled("Valjean");
        let mut s = scene(vec![node]);
        tips.attach(&mut s);
        assert_eq!(s.items[0].tooltips, ["Valjean"]);
    }
}
