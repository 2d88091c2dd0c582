//! Statistics per group of rows left in a source's plan: one `group_by` over the plan, run by
//! polars' streaming engine, gives each group's row count and the sum, spread, range (and, when
//! asked, median) of one value column, so a bar chart or a heatmap of 10⁹ rows needs memory for
//! its groups only.
//!
//! A row counts in its group when its value and every other `required` column are finite (the
//! drawing policy for rows in memory); the rows that are not are counted per column, so the
//! chart's dropped-rows warning is the one its rows in memory give. Groups keep the order in
//! which their first row appears ([`FIRST`]; [`FIRST_COUNTED`] is the first that counts), and
//! keys of floating-point columns are normalized so that −0 and 0 are one group, and NaN, ±∞
//! and missing another, as they are one category.

use polars::prelude::*;

use super::plan::{PlanRows, engine_error};
use crate::data::contained::contain;

/// The first row of each group (0-based, in the plan's order).
pub const FIRST: &str = "__dataink_first";
/// The first of the group's rows that counts (missing when none does).
pub const FIRST_COUNTED: &str = "__dataink_first_counted";
/// Rows of the group whose required columns are all finite.
pub const N: &str = "__dataink_n";
/// Their values' sum, sample standard deviation, minimum, maximum and median.
pub const SUM: &str = "__dataink_sum";
/// See [`SUM`].
pub const STDEV: &str = "__dataink_stdev";
/// See [`SUM`].
pub const MIN: &str = "__dataink_min";
/// See [`SUM`].
pub const MAX: &str = "__dataink_max";
/// See [`SUM`].
pub const MEDIAN: &str = "__dataink_median";
/// Rows of the group dropped for a non-finite required column.
const DROPPED: &str = "__dataink_dropped";
/// The row index column inside the query.
const ROW: &str = "__dataink_row";

/// What to group and summarize.
#[derive(Clone, Copy, Debug)]
pub struct GroupQuery<'a> {
    /// The columns whose distinct values make the groups, as they are (text, numbers, times).
    pub keys: &'a [&'a str],
    /// The numeric column summarized (`None`: rows are only counted).
    pub value: Option<&'a str>,
    /// Numeric columns (the value among them, when it must be finite) a row needs finite to count.
    pub required: &'a [&'a str],
    /// Whether each group's median is wanted (it holds the group's values while it is found).
    pub median: bool,
}

/// One required column's non-finite cells over all rows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Loss {
    /// The column.
    pub field: String,
    /// Missing or NaN cells.
    pub missing: u64,
    /// Infinite cells.
    pub infinite: u64,
}

/// The groups of a [`GroupQuery`].
#[derive(Debug)]
pub struct Groups {
    /// One row per group in the order their first rows appear: the keys, [`FIRST`],
    /// [`FIRST_COUNTED`], [`N`] and,
    /// with a value, [`SUM`], [`STDEV`], [`MIN`], [`MAX`] (and [`MEDIAN`] when asked); a group
    /// whose rows were all dropped has `N` = 0 and no statistics.
    pub frame: DataFrame,
    /// Rows dropped for a non-finite required column.
    pub dropped: u64,
    /// The required columns with non-finite cells.
    pub losses: Vec<Loss>,
}

impl PlanRows {
    /// Group the rows as `query` says, in one streaming query.
    pub fn groups(&self, query: GroupQuery<'_>) -> Result<Groups, String> {
        let frame = self.frame()?.clone();
        let mut keys = Vec::with_capacity(query.keys.len());
        for &key in query.keys {
            let dtype = self.dtype_of(key)?;
            // −0 + 0 = +0: the two zeros make one group; NaN and ±∞ join the missing values, as
            // all of them are the category "(missing)".
            keys.push(if dtype.is_float() {
                when(col(key).is_finite()).then(col(key) + lit(0.0)).otherwise(lit(NULL).cast(dtype.clone())).alias(key)
            } else {
                col(key)
            });
        }
        let mut ok: Option<Expr> = None;
        let mut aggregates = vec![col(ROW).min().alias(FIRST)];
        for (i, &field) in query.required.iter().enumerate() {
            let v = self.number(field)?.cast(DataType::Float64);
            let finite = v.clone().is_finite().fill_null(lit(false));
            ok = Some(match ok {
                Some(ok) => ok.and(finite),
                None => finite,
            });
            let missing = v.clone().is_null().or(v.clone().is_nan().fill_null(lit(false)));
            aggregates.push(missing.sum().alias(format!("__dataink_missing_{i}")));
            aggregates.push(v.is_infinite().fill_null(lit(false)).sum().alias(format!("__dataink_infinite_{i}")));
        }
        // A literal `true` would be one value per group, not one per row: without required
        // columns every row counts.
        match &ok {
            Some(ok) => {
                aggregates.push(col(ROW).filter(ok.clone()).min().alias(FIRST_COUNTED));
                aggregates.push(ok.clone().sum().alias(N));
                aggregates.push(ok.clone().not().sum().alias(DROPPED));
            }
            None => {
                aggregates.push(col(ROW).min().alias(FIRST_COUNTED));
                aggregates.push(len().alias(N));
            }
        }
        if let Some(field) = query.value {
            let v = self.number(field)?.cast(DataType::Float64);
            let v = match ok {
                Some(ok) => v.filter(ok),
                None => v,
            };
            aggregates.push(v.clone().sum().alias(SUM));
            aggregates.push(v.clone().std(1).alias(STDEV));
            aggregates.push(v.clone().min().alias(MIN));
            aggregates.push(v.clone().max().alias(MAX));
            if query.median {
                aggregates.push(v.median().alias(MEDIAN));
            }
        }
        let grouped = frame
            .with_row_index(ROW, None)
            .group_by(keys)
            .agg(aggregates)
            .sort([FIRST], SortMultipleOptions::default());
        let label = format!("groups by {} of {} rows", query.keys.join(", "), self.rows());
        let mut frame = crate::timing::timed(&label, || contain(|| grouped.collect_with_engine(Engine::Streaming)))?
            .map_err(|e| engine_error(self.source(), &e))?
            .unwrap_single();
        let total = |frame: &DataFrame, name: &str| -> u64 {
            frame.column(name).ok().and_then(|c| c.as_materialized_series().sum::<u64>().ok()).unwrap_or(0)
        };
        let dropped = total(&frame, DROPPED);
        let mut losses = Vec::new();
        for (i, &field) in query.required.iter().enumerate() {
            let (missing, infinite) = (format!("__dataink_missing_{i}"), format!("__dataink_infinite_{i}"));
            let loss =
                Loss { field: field.to_string(), missing: total(&frame, &missing), infinite: total(&frame, &infinite) };
            if loss.missing + loss.infinite > 0 {
                losses.push(loss);
            }
            for name in [missing, infinite] {
                let _ = frame.drop_in_place(&name);
            }
        }
        let _ = frame.drop_in_place(DROPPED);
        Ok(Groups { frame, dropped, losses })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbers(frame: &DataFrame, name: &str) -> Vec<Option<f64>> {
        let c = frame.column(name).unwrap().cast(&DataType::Float64).unwrap();
        c.f64().unwrap().iter().collect()
    }

    #[test]
    fn groups_count_and_summarize_their_finite_rows_in_order_of_appearance() {
        let lf = df!(
            "k" => [Some("b"), Some("a"), Some("b"), None, Some("a"), Some("c"), Some("b")],
            "v" => [Some(1.0), Some(f64::NAN), Some(3.0), Some(4.0), Some(10.0), None, Some(f64::INFINITY)]
        )
        .unwrap()
        .lazy();
        let plan = PlanRows::new(lf, "t").unwrap();
        let query = GroupQuery { keys: &["k"], value: Some("v"), required: &["v"], median: true };
        let groups = plan.groups(query).unwrap();
        let keys: Vec<Option<&str>> = groups.frame.column("k").unwrap().str().unwrap().iter().collect();
        assert_eq!(keys, [Some("b"), Some("a"), None, Some("c")]);
        assert_eq!(numbers(&groups.frame, N), [Some(2.0), Some(1.0), Some(1.0), Some(0.0)]);
        assert_eq!(numbers(&groups.frame, SUM), [Some(4.0), Some(10.0), Some(4.0), Some(0.0)]);
        assert_eq!(numbers(&groups.frame, MEDIAN), [Some(2.0), Some(10.0), Some(4.0), None]);
        assert_eq!(numbers(&groups.frame, MIN), [Some(1.0), Some(10.0), Some(4.0), None]);
        let sd = numbers(&groups.frame, STDEV);
        assert!((sd[0].unwrap() - 2f64.sqrt()).abs() < 1e-12, "{sd:?}");
        assert_eq!(numbers(&groups.frame, FIRST_COUNTED), [Some(0.0), Some(4.0), Some(3.0), None]);
        assert_eq!(groups.dropped, 3);
        assert_eq!(groups.losses, [Loss { field: "v".into(), missing: 2, infinite: 1 }]);
    }

    #[test]
    fn the_two_zeros_are_one_group_and_counting_needs_no_value() {
        let x = [Some(0.0), Some(-0.0), Some(f64::NAN), Some(1.5), None, Some(0.0), Some(f64::INFINITY)];
        let lf = df!("x" => x).unwrap().lazy();
        let plan = PlanRows::new(lf, "t").unwrap();
        let groups = plan.groups(GroupQuery { keys: &["x"], value: None, required: &[], median: false }).unwrap();
        assert_eq!(numbers(&groups.frame, "x"), [Some(0.0), None, Some(1.5)]);
        assert_eq!(numbers(&groups.frame, N), [Some(3.0), Some(3.0), Some(1.0)]);
        assert_eq!(numbers(&groups.frame, FIRST_COUNTED), [Some(0.0), Some(2.0), Some(3.0)]);
        assert_eq!(groups.dropped, 0);
        assert!(groups.losses.is_empty());
    }
}
