//! Warnings raised while drawing a chart, as data: lint reads their numbers, the CLI and the
//! report show their text (the same text either way).

use std::fmt;

/// A note raised while drawing a chart.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// Rows left out because a plotted column had no placeable value there (missing, NaN,
    /// infinite, or ≤ 0 on a log axis).
    DroppedRows {
        /// The chart's name.
        chart: String,
        /// Rows left out.
        dropped: usize,
        /// Rows the chart's table has.
        rows: usize,
        /// What each column lacked (columns lacking nothing are not listed).
        columns: Vec<ColumnLoss>,
    },
    /// Rows left out because their value lies outside a fixed axis domain, as counted by a chart
    /// whose rows stay in their source's plan (the lint reads the numbers; the reader the text).
    OutsideDomain {
        /// The axis' column.
        field: String,
        /// Rows left out.
        outside: usize,
        /// Rows with a value, inside the domain or not.
        rows: usize,
        /// The note as written for the reader.
        text: String,
    },
    /// Anything else, worded for the reader (it names its chart).
    Note(String),
}

/// What one column lacked in the rows a chart dropped.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ColumnLoss {
    /// The column.
    pub field: String,
    /// Missing or NaN cells.
    pub missing: usize,
    /// Infinite cells.
    pub infinite: usize,
    /// Finite values ≤ 0 on a log-scaled axis.
    pub non_positive: usize,
}

impl Warning {
    /// The note for `left_out` of `rows` rows whose `field` lies outside the domain `[lo, hi]`;
    /// `None` when no row was left out.
    pub fn outside_domain(field: &str, left_out: usize, rows: usize, [lo, hi]: [f64; 2]) -> Option<Warning> {
        (left_out > 0).then(|| Warning::OutsideDomain {
            field: field.to_string(),
            outside: left_out,
            rows,
            text: format!("left out {left_out} of {rows} rows whose `{field}` lies outside the domain [{lo}, {hi}]"),
        })
    }

    /// The rows dropped and the table's rows, for a [`Warning::DroppedRows`].
    pub fn dropped_rows(&self) -> Option<(usize, usize)> {
        match self {
            Warning::DroppedRows { dropped, rows, .. } => Some((*dropped, *rows)),
            Warning::OutsideDomain { .. } | Warning::Note(_) => None,
        }
    }

    /// The message without the chart's name in front (a note's text as it is).
    pub fn message(&self) -> String {
        match self {
            Warning::DroppedRows { dropped, rows, .. } => {
                format!("dropped {dropped} of {rows} rows with {}", self.what_rows_lack().unwrap_or_default())
            }
            Warning::OutsideDomain { text, .. } | Warning::Note(text) => text.clone(),
        }
    }

    /// What the dropped rows lacked, with the count per column ("missing or non-finite values
    /// (`x`: 2 missing or NaN)"), for a [`Warning::DroppedRows`].
    pub fn what_rows_lack(&self) -> Option<String> {
        let Warning::DroppedRows { columns, .. } = self else { return None };
        let log = columns.iter().any(|c| c.non_positive > 0);
        let details: Vec<String> = columns.iter().map(ColumnLoss::to_string).collect();
        Some(format!(
            "missing or non-finite values{} ({})",
            if log { " or values ≤ 0 on a log axis" } else { "" },
            details.join("; ")
        ))
    }
}

impl fmt::Display for ColumnLoss {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        if self.missing > 0 {
            parts.push(format!("{} missing or NaN", self.missing));
        }
        if self.infinite > 0 {
            parts.push(format!("{} infinite", self.infinite));
        }
        if self.non_positive > 0 {
            parts.push(format!("{} ≤ 0 on a log axis", self.non_positive));
        }
        write!(f, "`{}`: {}", self.field, parts.join(", "))
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::DroppedRows { chart, .. } => write!(f, "chart \"{chart}\": {}", self.message()),
            Warning::OutsideDomain { text, .. } | Warning::Note(text) => f.write_str(text),
        }
    }
}

impl From<String> for Warning {
    fn from(text: String) -> Warning {
        Warning::Note(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dropped_rows_read_as_numbers_and_word_as_before() {
        let w = Warning::DroppedRows {
            chart: "c".into(),
            dropped: 2,
            rows: 4,
            columns: vec![
                ColumnLoss { field: "y".into(), missing: 1, infinite: 1, non_positive: 0 },
                ColumnLoss { field: "x".into(), missing: 0, infinite: 0, non_positive: 1 },
            ],
        };
        assert_eq!(w.dropped_rows(), Some((2, 4)));
        assert_eq!(
            w.to_string(),
            "chart \"c\": dropped 2 of 4 rows with missing or non-finite values or values ≤ 0 on a log axis \
             (`y`: 1 missing or NaN, 1 infinite; `x`: 1 ≤ 0 on a log axis)"
        );
        assert!(w.message().starts_with("dropped 2 of 4 rows"));
        let note = Warning::from("chart \"c\": 3 node labels were left out".to_string());
        assert_eq!(note.dropped_rows(), None);
        assert_eq!(note.to_string(), "chart \"c\": 3 node labels were left out");
        assert_eq!(note.what_rows_lack(), None);
    }
}
