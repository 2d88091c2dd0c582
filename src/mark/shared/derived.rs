//! Derived geometry in data coordinates, written as CSV by `--format csv`.

use std::fmt::Write as _;

use crate::data::{Column, Table};
use crate::guide::time::format_timestamp;

/// One column of derived output.
#[derive(Clone, Debug, PartialEq)]
pub enum DerivedColumn {
    /// Numbers computed by the chart kind (written with full precision).
    Number(Vec<f64>),
    /// Text computed by the chart kind (quoted as CSV requires).
    Text(Vec<String>),
    /// A column of the chart's table, read at [`Derived::rows`] only when the CSV is written
    /// (so charts of millions of rows copy nothing unless `--format csv` asks for it).
    Source(String),
    /// The source row index of each output row.
    RowIndex,
    /// A flag per table row (e.g. whether a selection holds it), read at [`Derived::rows`] and
    /// written as `true` or `false`.
    Selected(Vec<bool>),
}

/// A small table of derived geometry in data coordinates: one output row per entry of `rows`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Derived {
    /// The source row of each output row.
    pub rows: Vec<u32>,
    /// Columns in output order.
    pub columns: Vec<(String, DerivedColumn)>,
}

impl Derived {
    /// An empty table whose output rows come from these source rows.
    pub fn over(rows: Vec<u32>) -> Derived {
        Derived { rows, columns: Vec::new() }
    }

    /// Output rows for `rows`: the row index, then each named table column read at those rows.
    pub fn of_rows(rows: Vec<u32>, fields: &[&str]) -> Derived {
        let mut d = Derived::over(rows);
        d.push("row", DerivedColumn::RowIndex);
        for field in fields {
            d.push(field, DerivedColumn::Source((*field).to_string()));
        }
        d
    }

    /// Add a column.
    pub fn push(&mut self, name: &str, column: DerivedColumn) {
        self.columns.push((name.to_string(), column));
    }

    /// The column named `name`, if there is one.
    pub fn column(&self, name: &str) -> Option<&DerivedColumn> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, c)| c)
    }

    /// Number of output rows: one per source row, or for purely computed tables (no source
    /// rows) the length of the longest computed column.
    pub fn len(&self) -> usize {
        if !self.rows.is_empty() {
            return self.rows.len();
        }
        self.columns
            .iter()
            .map(|(_, c)| match c {
                DerivedColumn::Number(v) => v.len(),
                DerivedColumn::Text(v) => v.len(),
                _ => 0,
            })
            .max()
            .unwrap_or(0)
    }

    /// Whether there are no output rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The table as CSV text with a header row, reading [`DerivedColumn::Source`] columns from
    /// `table`. Numbers use Rust's shortest round-trip form; non-finite numbers and missing
    /// cells are written as empty cells.
    pub fn to_csv(&self, table: &Table) -> String {
        let mut out = String::new();
        let header: Vec<String> = self.columns.iter().map(|(n, _)| csv_field(n)).collect();
        out.push_str(&header.join(","));
        out.push('\n');
        let sources: Vec<Option<&Column>> = self
            .columns
            .iter()
            .map(|(_, c)| match c {
                DerivedColumn::Source(name) => table.column(name),
                _ => None,
            })
            .collect();
        for k in 0..self.len() {
            let row = self.rows.get(k).copied().unwrap_or(u32::MAX);
            for (i, (_, column)) in self.columns.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                match column {
                    DerivedColumn::Number(v) => push_number(&mut out, v.get(k).copied()),
                    DerivedColumn::Text(v) => out.push_str(&csv_field(v.get(k).map(String::as_str).unwrap_or(""))),
                    DerivedColumn::RowIndex => {
                        let _ = write!(out, "{row}");
                    }
                    DerivedColumn::Selected(flags) => {
                        out.push_str(if flags.get(row as usize).copied().unwrap_or(false) { "true" } else { "false" });
                    }
                    DerivedColumn::Source(_) => {
                        if let Some(col) = sources.get(i).copied().flatten() {
                            match (col.categories(), col.numbers()) {
                                (Some(cats), _) => out.push_str(&csv_field(cats.value(row as usize).unwrap_or(""))),
                                (None, Some(nums)) if col.is_time() => {
                                    if let Some(ms) = nums.get(row as usize).filter(|v| v.is_finite()) {
                                        out.push_str(&format_timestamp(*ms));
                                    }
                                }
                                (None, Some(nums)) => push_number(&mut out, nums.get(row as usize).copied()),
                                _ => {}
                            }
                        }
                    }
                }
            }
            out.push('\n');
        }
        out
    }
}

/// Shortest round-trip form; exponent notation for very small or large magnitudes.
fn push_number(out: &mut String, v: Option<f64>) {
    if let Some(x) = v.filter(|x| x.is_finite()) {
        let a = x.abs();
        if a == 0.0 || (1e-5..1e16).contains(&a) {
            let _ = write!(out, "{x}");
        } else {
            let _ = write!(out, "{x:e}");
        }
    }
}

/// Quote a CSV field when it holds a separator, quote or line break; neutralise leading
/// spreadsheet formula characters.
fn csv_field(s: &str) -> String {
    let risky = s.starts_with(['=', '+', '-', '@']) && s.parse::<f64>().is_err();
    let body = if risky { format!("'{s}") } else { s.to_string() };
    if body.contains([',', '"', '\n', '\r']) { format!("\"{}\"", body.replace('"', "\"\"")) } else { body }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{Categories, ColumnValues};

    #[test]
    fn csv_quotes_round_trips_numbers_and_reads_source_columns() {
        let table = Table {
            columns: vec![
                Column { name: "v".into(), values: ColumnValues::Number(vec![10.0, 20.0, 30.0]) },
                Column {
                    name: "name".into(),
                    values: ColumnValues::Text(Categories::from_values([Some("a,b"), Some("c"), None])),
                },
            ],
            rows: 3,
        };
        let mut d = Derived::over(vec![2, 0, 1]);
        d.push("row", DerivedColumn::RowIndex);
        d.push("x", DerivedColumn::Number(vec![0.1, f64::NAN, 1e-300]));
        d.push("label", DerivedColumn::Text(vec!["say \"hi\"".into(), "=cmd()".into(), "-3".into()]));
        d.push("v", DerivedColumn::Source("v".into()));
        d.push("name", DerivedColumn::Source("name".into()));
        let csv = d.to_csv(&table);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "row,x,label,v,name");
        assert_eq!(lines[1], "2,0.1,\"say \"\"hi\"\"\",30,");
        assert_eq!(lines[2], "0,,'=cmd(),10,\"a,b\"");
        assert_eq!(lines[3], "1,1e-300,-3,20,c");
        assert_eq!(lines.len(), 4);
    }
}
