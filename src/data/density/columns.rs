//! Several numeric columns of a source's plan over the rows finite in all of them (what a
//! scatter-plot matrix draws): how many such rows there are, each column's extent over them and
//! the cells that made the others drop, from one streaming query; and the plan narrowed to those
//! rows, for the scans that count them.

use polars::prelude::*;

use super::groups::Loss;
use super::plan::{PlanRows, engine_error};
use crate::data::contained::contain;

/// The rows of a plan finite in every one of some columns.
#[derive(Clone, Debug, PartialEq)]
pub struct FiniteRows {
    /// How many rows are finite in every column.
    pub rows: u64,
    /// Each column's smallest and largest value over those rows (`None` when there are none).
    pub extents: Vec<Option<(f64, f64)>>,
    /// Rows with a missing or non-finite value in some column.
    pub dropped: u64,
    /// The columns with missing or non-finite cells, over all rows.
    pub losses: Vec<Loss>,
}

impl PlanRows {
    /// The rows finite in every column of `fields` (numbers or times), in one streaming query.
    pub fn finite_rows(&self, fields: &[&str]) -> Result<FiniteRows, String> {
        let values: Vec<Expr> =
            fields.iter().map(|f| Ok(self.number(f)?.cast(DataType::Float64))).collect::<Result<_, String>>()?;
        let keep = all_finite(&values);
        let mut query = vec![keep.clone().sum().alias("kept")];
        for (i, v) in values.iter().enumerate() {
            let kept = v.clone().filter(keep.clone());
            query.push(kept.clone().min().alias(format!("lo{i}")));
            query.push(kept.max().alias(format!("hi{i}")));
            let missing = v.clone().is_null().or(v.clone().is_nan().fill_null(lit(false)));
            query.push(missing.sum().alias(format!("missing{i}")));
            query.push(v.clone().is_infinite().fill_null(lit(false)).sum().alias(format!("infinite{i}")));
        }
        let frame = self.frame()?.clone();
        let df = contain(|| frame.select(query).collect_with_engine(Engine::Streaming))?
            .map_err(|e| engine_error(self.source(), &e))?
            .unwrap_single();
        let number = |name: &str| df.column(name).ok().and_then(|c| c.get(0).ok()).and_then(|v| v.extract::<f64>());
        let count = |name: &str| number(name).unwrap_or(0.0) as u64;
        let rows = count("kept");
        let extents = (0..fields.len())
            .map(|i| match (number(&format!("lo{i}")), number(&format!("hi{i}"))) {
                (Some(lo), Some(hi)) if lo <= hi => Some((lo, hi)),
                _ => None,
            })
            .collect();
        let losses = fields
            .iter()
            .enumerate()
            .map(|(i, f)| Loss {
                field: f.to_string(),
                missing: count(&format!("missing{i}")),
                infinite: count(&format!("infinite{i}")),
            })
            .filter(|l| l.missing + l.infinite > 0)
            .collect();
        Ok(FiniteRows { rows, extents, dropped: self.rows().saturating_sub(rows), losses })
    }

    /// The plan narrowed to the rows finite in every column of `fields` (`finite`: what
    /// [`PlanRows::finite_rows`] said of them).
    pub fn keeping_finite(&self, fields: &[&str], finite: &FiniteRows) -> Result<PlanRows, String> {
        let values: Vec<Expr> =
            fields.iter().map(|f| Ok(self.number(f)?.cast(DataType::Float64))).collect::<Result<_, String>>()?;
        self.filtered(all_finite(&values), finite.rows)
    }
}

/// True where every one of `values` is finite (a missing value is not).
fn all_finite(values: &[Expr]) -> Expr {
    values.iter().map(|v| v.clone().is_finite().fill_null(lit(false))).reduce(|a, b| a.and(b)).unwrap_or(lit(true))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finite_rows_are_counted_and_measured_over_every_column_at_once() {
        let a = [Some(1.0), Some(5.0), None, Some(-2.0), Some(f64::INFINITY), Some(3.0)];
        let b = [Some(10.0), Some(f64::NAN), Some(7.0), Some(20.0), Some(1.0), Some(-4.0)];
        let plan = PlanRows::new(df!("a" => a, "b" => b).unwrap().lazy(), "t").unwrap();
        let finite = plan.finite_rows(&["a", "b"]).unwrap();
        // Rows 0, 3 and 5 are finite in both.
        assert_eq!(finite.rows, 3);
        assert_eq!(finite.extents, [Some((-2.0, 3.0)), Some((-4.0, 20.0))]);
        assert_eq!(finite.dropped, 3);
        assert_eq!(
            finite.losses,
            [Loss { field: "a".into(), missing: 1, infinite: 1 }, Loss { field: "b".into(), missing: 1, infinite: 0 }]
        );
        let kept = plan.keeping_finite(&["a", "b"], &finite).unwrap();
        assert_eq!(kept.rows(), 3);
        let first = kept.finite_rows(&["a"]).unwrap();
        assert_eq!((first.rows, first.extents[0]), (3, Some((-2.0, 3.0))));
    }
}
