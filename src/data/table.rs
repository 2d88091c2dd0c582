//! The columnar table that chart kinds read: numbers, times and categories, one row per record.
//! A grid source keeps its coordinate columns as [`GridAxis`]: its axis values, spread over the
//! rows only when something reads the column row by row.

use std::sync::OnceLock;

/// The values of one column.
#[derive(Clone, Debug, PartialEq)]
pub enum ColumnValues {
    /// Numbers as `f64`; missing cells are NaN.
    Number(Vec<f64>),
    /// Instants as milliseconds since the Unix epoch (UTC); missing cells are NaN.
    Time(Vec<f64>),
    /// Text (and booleans) as categories.
    Text(Categories),
    /// Numbers that are one coordinate of a row-major regular grid.
    Axis(GridAxis),
}

/// One coordinate of a regular grid stored row-major: row `r` holds
/// `coords[(r / repeat) % coords.len()]` (`x`: `repeat` 1; `y`: `repeat` = the number of x nodes).
/// The long form is made once, on first use of [`GridAxis::values`]; grid kinds read the
/// coordinates directly and never make it.
#[derive(Clone, Debug)]
pub struct GridAxis {
    coords: Vec<f64>,
    repeat: usize,
    len: usize,
    long: OnceLock<Vec<f64>>,
}

impl GridAxis {
    /// An axis of `len` rows whose coordinates are `coords`, each repeated `repeat` times in a row,
    /// the whole sequence cycling until `len` rows.
    pub fn new(coords: Vec<f64>, repeat: usize, len: usize) -> GridAxis {
        GridAxis { coords, repeat: repeat.max(1), len, long: OnceLock::new() }
    }

    /// The grid's coordinates along this axis.
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }

    /// How many consecutive rows share one coordinate.
    pub fn repeat(&self) -> usize {
        self.repeat
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the axis has no rows.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether the long form has been made (something read the column row by row).
    pub fn is_spread(&self) -> bool {
        self.long.get().is_some()
    }

    /// The value of every row (made on first call).
    pub fn values(&self) -> &[f64] {
        self.long.get_or_init(|| {
            let mut out = Vec::with_capacity(self.len);
            if !self.coords.is_empty() {
                while out.len() < self.len {
                    for &c in &self.coords {
                        let n = self.repeat.min(self.len - out.len());
                        out.extend(std::iter::repeat_n(c, n));
                        if out.len() == self.len {
                            break;
                        }
                    }
                }
            }
            out
        })
    }
}

impl PartialEq for GridAxis {
    fn eq(&self, other: &GridAxis) -> bool {
        self.len == other.len && self.values() == other.values()
    }
}

/// Text values stored as codes into a list of distinct levels (in order of first appearance).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Categories {
    /// Distinct values in order of first appearance.
    pub levels: Vec<String>,
    /// One code per row: an index into `levels`, or [`Categories::MISSING`].
    pub codes: Vec<u32>,
}

impl Categories {
    /// The code of a missing cell.
    pub const MISSING: u32 = u32::MAX;

    /// Build categories from optional strings.
    pub fn from_values<'a>(values: impl IntoIterator<Item = Option<&'a str>>) -> Categories {
        // A fast hash, seeded at random per process so crafted cells cannot collide on purpose.
        let mut index = std::collections::HashMap::<&'a str, u32, foldhash::fast::RandomState>::default();
        let mut cats = Categories::default();
        for value in values {
            let code = match value {
                None => Categories::MISSING,
                Some(s) => *index.entry(s).or_insert_with(|| {
                    cats.levels.push(s.to_string());
                    (cats.levels.len() - 1) as u32
                }),
            };
            cats.codes.push(code);
        }
        cats
    }

    /// The text of row `row`, if present.
    pub fn value(&self, row: usize) -> Option<&str> {
        let code = *self.codes.get(row)?;
        self.levels.get(code as usize).map(String::as_str)
    }
}

/// A named column.
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    /// Column name as in the source.
    pub name: String,
    /// Its values.
    pub values: ColumnValues,
}

impl Column {
    /// The cell at `row` as an identity key (node ids, tree paths): text trimmed, numbers in
    /// shortest form; `None` when the cell is missing, empty or not finite.
    pub fn key(&self, row: usize) -> Option<String> {
        if let Some(values) = self.numbers() {
            return values.get(row).filter(|v| v.is_finite()).map(|v| v.to_string());
        }
        let text = self.categories()?.value(row)?.trim();
        (!text.is_empty()).then(|| text.to_string())
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        match &self.values {
            ColumnValues::Number(v) | ColumnValues::Time(v) => v.len(),
            ColumnValues::Text(c) => c.codes.len(),
            ColumnValues::Axis(a) => a.len(),
        }
    }
    /// Whether the column has no rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The numeric values (numbers or times), if the column is numeric.
    pub fn numbers(&self) -> Option<&[f64]> {
        match &self.values {
            ColumnValues::Number(v) | ColumnValues::Time(v) => Some(v),
            ColumnValues::Axis(a) => Some(a.values()),
            ColumnValues::Text(_) => None,
        }
    }
    /// Whether the column holds numbers or times (asking does not spread a grid axis).
    pub fn is_numeric(&self) -> bool {
        !matches!(self.values, ColumnValues::Text(_))
    }
    /// The categories, if the column holds text.
    pub fn categories(&self) -> Option<&Categories> {
        match &self.values {
            ColumnValues::Text(c) => Some(c),
            _ => None,
        }
    }
    /// Whether the column holds instants.
    pub fn is_time(&self) -> bool {
        matches!(self.values, ColumnValues::Time(_))
    }
    /// A short name of the column's type for messages: "number", "time" or "text".
    pub fn type_name(&self) -> &'static str {
        match self.values {
            ColumnValues::Number(_) | ColumnValues::Axis(_) => "number",
            ColumnValues::Time(_) => "time",
            ColumnValues::Text(_) => "text",
        }
    }
}

/// Counts of unusable cells found in a numeric column.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NonFinite {
    /// Missing (null) or NaN cells.
    pub nan: usize,
    /// +∞ or −∞ cells (including overflowing literals such as `1e999`).
    pub infinite: usize,
}

impl NonFinite {
    /// Count the non-finite values of a slice.
    pub fn count(values: &[f64]) -> NonFinite {
        let mut counts = NonFinite::default();
        for v in values {
            if v.is_nan() {
                counts.nan += 1;
            } else if v.is_infinite() {
                counts.infinite += 1;
            }
        }
        counts
    }
    /// Total unusable cells.
    pub fn total(&self) -> usize {
        self.nan + self.infinite
    }
}

/// A loaded data source: named columns of equal length.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Table {
    /// Columns in source order.
    pub columns: Vec<Column>,
    /// Number of rows.
    pub rows: usize,
}

impl Table {
    /// A table of named columns, which must all have the same length.
    pub fn from_columns(columns: impl IntoIterator<Item = (impl Into<String>, ColumnValues)>) -> Table {
        let columns: Vec<Column> =
            columns.into_iter().map(|(name, values)| Column { name: name.into(), values }).collect();
        let rows = columns.first().map_or(0, Column::len);
        debug_assert!(columns.iter().all(|c| c.len() == rows), "columns of different lengths");
        Table { columns, rows }
    }
    /// A column by exact name.
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|c| c.name == name)
    }
    /// The column names in source order.
    pub fn column_names(&self) -> Vec<&str> {
        self.columns.iter().map(|c| c.name.as_str()).collect()
    }

    /// The table of `rows` only, in that order (a facet panel's rows). Text columns keep every
    /// level of the whole table, so colours and category orders stay the same in every part;
    /// grid axes become plain numbers.
    pub fn take_rows(&self, rows: &[u32]) -> Table {
        let take = |values: &[f64]| rows.iter().map(|&r| values.get(r as usize).copied().unwrap_or(f64::NAN)).collect();
        let columns = self
            .columns
            .iter()
            .map(|c| {
                let values = match &c.values {
                    ColumnValues::Number(v) => ColumnValues::Number(take(v)),
                    ColumnValues::Time(v) => ColumnValues::Time(take(v)),
                    ColumnValues::Axis(a) => ColumnValues::Number(take(a.values())),
                    ColumnValues::Text(cats) => ColumnValues::Text(Categories {
                        levels: cats.levels.clone(),
                        codes: rows
                            .iter()
                            .map(|&r| cats.codes.get(r as usize).copied().unwrap_or(Categories::MISSING))
                            .collect(),
                    }),
                };
                Column { name: c.name.clone(), values }
            })
            .collect();
        Table { columns, rows: rows.len() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn categories_keep_first_appearance_order_and_missing() {
        let c = Categories::from_values([Some("b"), Some("a"), None, Some("b")]);
        assert_eq!(c.levels, vec!["b", "a"]);
        assert_eq!(c.codes, vec![0, 1, Categories::MISSING, 0]);
        assert_eq!(c.value(1), Some("a"));
        assert_eq!(c.value(2), None);
        assert_eq!(c.value(99), None);
    }

    #[test]
    fn grid_axes_spread_over_the_rows_as_the_long_form_would() {
        let x = GridAxis::new(vec![0.0, 1.0, 3.0], 1, 6);
        let y = GridAxis::new(vec![5.0, 7.0], 3, 6);
        assert_eq!(x.values(), [0.0, 1.0, 3.0, 0.0, 1.0, 3.0]);
        assert_eq!(y.values(), [5.0, 5.0, 5.0, 7.0, 7.0, 7.0]);
        let column = Column { name: "y".into(), values: ColumnValues::Axis(y.clone()) };
        assert_eq!(column.len(), 6);
        assert_eq!(column.type_name(), "number");
        assert_eq!(column.key(4), Some("7".into()));
        assert_eq!(GridAxis::new(Vec::new(), 1, 0).values(), [] as [f64; 0]);
        assert_eq!(y, GridAxis::new(vec![5.0, 7.0], 3, 6));
        assert_ne!(y, GridAxis::new(vec![5.0, 7.0], 2, 6));
    }

    #[test]
    fn non_finite_counts_nan_and_infinities() {
        let n = NonFinite::count(&[1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 2.0]);
        assert_eq!(n, NonFinite { nan: 1, infinite: 2 });
        assert_eq!(n.total(), 3);
    }

    #[test]
    fn take_rows_keeps_levels_and_order() {
        let table = Table::from_columns([
            ("v", ColumnValues::Number(vec![1.0, 2.0, 3.0])),
            ("g", ColumnValues::Text(Categories::from_values([Some("a"), Some("b"), None]))),
            ("x", ColumnValues::Axis(GridAxis::new(vec![5.0, 6.0, 7.0], 1, 3))),
        ]);
        let part = table.take_rows(&[2, 0]);
        assert_eq!(part.rows, 2);
        assert_eq!(part.column("v").and_then(Column::numbers), Some(&[3.0, 1.0][..]));
        let g = part.column("g").and_then(Column::categories).cloned().unwrap_or_default();
        assert_eq!(g.levels, ["a", "b"], "every level kept");
        assert_eq!(g.codes, [Categories::MISSING, 0]);
        assert_eq!(part.column("x").and_then(Column::numbers), Some(&[7.0, 5.0][..]));
    }
}
