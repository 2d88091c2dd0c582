//! Derived geometry in data coordinates, written as CSV by `--format csv`.

use std::fmt::Write as _;

use crate::guide::format::format_value;

/// One column of derived output.
#[derive(Clone, Debug, PartialEq)]
pub enum DerivedColumn {
    /// Numbers (written with full precision).
    Number(Vec<f64>),
    /// Text (quoted as CSV requires).
    Text(Vec<String>),
}

impl DerivedColumn {
    fn len(&self) -> usize {
        match self {
            DerivedColumn::Number(v) => v.len(),
            DerivedColumn::Text(v) => v.len(),
        }
    }
}

/// A small table of derived geometry: named columns of equal length.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Derived {
    /// Columns in output order.
    pub columns: Vec<(String, DerivedColumn)>,
}

impl Derived {
    /// Add a column.
    pub fn push(&mut self, name: &str, column: DerivedColumn) {
        self.columns.push((name.to_string(), column));
    }

    /// Number of rows (the shortest column).
    pub fn rows(&self) -> usize {
        self.columns.iter().map(|(_, c)| c.len()).min().unwrap_or(0)
    }

    /// The table as CSV text with a header row. Numbers use Rust's shortest round-trip form;
    /// non-finite numbers are written as empty cells.
    pub fn to_csv(&self) -> String {
        let mut out = String::new();
        let header: Vec<String> = self.columns.iter().map(|(n, _)| csv_field(n)).collect();
        out.push_str(&header.join(","));
        out.push('\n');
        for row in 0..self.rows() {
            for (i, (_, column)) in self.columns.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                match column {
                    DerivedColumn::Number(v) => {
                        let x = v.get(row).copied().unwrap_or(f64::NAN);
                        if x.is_finite() {
                            let _ = write!(out, "{x}");
                        }
                    }
                    DerivedColumn::Text(v) => out.push_str(&csv_field(v.get(row).map(String::as_str).unwrap_or(""))),
                }
            }
            out.push('\n');
        }
        out
    }
}

/// Quote a CSV field when it holds a separator, quote or line break; neutralise leading
/// spreadsheet formula characters.
fn csv_field(s: &str) -> String {
    let risky = s.starts_with(['=', '+', '-', '@']) && s.parse::<f64>().is_err();
    let body = if risky { format!("'{s}") } else { s.to_string() };
    if body.contains([',', '"', '\n', '\r']) { format!("\"{}\"", body.replace('"', "\"\"")) } else { body }
}

/// A readable number for messages (re-exported for marks).
pub fn readable(v: f64) -> String {
    format_value(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_quotes_and_round_trips_numbers() {
        let mut d = Derived::default();
        d.push("x", DerivedColumn::Number(vec![0.1, f64::NAN, 1e-300]));
        d.push("label", DerivedColumn::Text(vec!["a,b".into(), "say \"hi\"".into(), "=cmd()".into()]));
        let csv = d.to_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "x,label");
        assert_eq!(lines[1], "0.1,\"a,b\"");
        assert_eq!(lines[2], ",\"say \"\"hi\"\"\"");
        assert_eq!(lines[3], "0.000...".replace("0.000...", &format!("{}", 1e-300)) + ",'=cmd()");
        assert_eq!(lines[3].split(',').next().and_then(|s| s.parse::<f64>().ok()), Some(1e-300));
    }
}
