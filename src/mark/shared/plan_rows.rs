//! What kinds read of rows left in their source's plan. A chart's groups ([`PlanRows::groups`]):
//! one table row per group (its keys as the source holds them, its row count and value
//! statistics), the groups that kept rows, and the dropped-rows warning the same rows in memory
//! give; kinds that draw one mark per group (bars, heatmap cells) read their categories from this
//! table with the same [`super::bands`] functions as from rows, so labels and orders come out
//! the same. And a column's quartiles (type 7) from tallies, for bin-width rules.

use super::encode;
use super::spread::Summary;
use super::warning::{ColumnLoss, Warning};
use crate::data::Table;
use crate::data::density::groups::{self, GroupQuery, Loss};
use crate::data::density::plan::PlanRows;
use crate::data::density::tally::Tally;
use crate::enrich::distribution::type7_position;
use crate::mark::MarkError;
use crate::spec::Chart;

/// The groups of a chart's rows.
pub struct PlanGroups {
    /// One row per group, in the order the groups' first rows appear in the source.
    pub table: Table,
    /// The groups with rows left after the non-finite policy (rows of `table`), in the order
    /// their first rows that count appear in the source.
    pub rows: Vec<u32>,
    /// The dropped-rows warning, when rows were dropped.
    pub warnings: Vec<Warning>,
}

/// The first and third quartiles (type 7, numpy's default) of the values `first` (a tally of
/// `field` in `plan`) placed.
pub fn quartiles(plan: &PlanRows, field: &str, first: &Tally) -> Result<(f64, f64), String> {
    let n = first.placed() as usize;
    let v = plan.at_ranks(field, first, &[type7_position(0.25, n), type7_position(0.75, n)])?;
    Ok((v[0], v[1]))
}

/// Whether the quartiles of the values `first` placed surely differ, from its bins alone:
/// q1 ≤ v[i1 + 1] ≤ v[i3] ≤ q3, so two values of those ranks in different bins separate them.
pub fn quartiles_differ(first: &Tally) -> bool {
    let n = first.placed() as usize;
    let ((i1, _), (i3, _)) = (type7_position(0.25, n), type7_position(0.75, n));
    n > 0 && first.ranks_differ(i1 as u64 + 1, i3 as u64)
}

/// The shared warning for `dropped` of `rows` rows left in a plan, dropped for the cells
/// counted in `losses`; `None` when none was dropped.
pub fn dropped_rows(chart: &Chart, dropped: u64, rows: u64, losses: &[Loss]) -> Option<Warning> {
    (dropped > 0).then(|| Warning::DroppedRows {
        chart: chart.name.clone(),
        dropped: dropped as usize,
        rows: rows as usize,
        columns: losses
            .iter()
            .map(|l| ColumnLoss {
                field: l.field.clone(),
                missing: l.missing as usize,
                infinite: l.infinite as usize,
                non_positive: 0,
            })
            .collect(),
    })
}

impl PlanGroups {
    /// Group the rows of `plan` as `query` says; the chart's no-rows error when no group kept any.
    pub fn of(chart: &Chart, plan: &PlanRows, query: GroupQuery<'_>) -> Result<PlanGroups, MarkError> {
        let scanned = |message: String| {
            MarkError::at(&["data"], message, "`dataink data SPEC NAME` shows the rows after the source's transforms")
        };
        let grouped = plan.groups(query).map_err(scanned)?;
        let table =
            crate::data::load::frame_to_table(&grouped.frame, &format!("the groups of chart \"{}\"", chart.name))
                .map_err(|e| scanned(e.to_string()))?;
        let counts = table.column(groups::N).and_then(|c| c.numbers()).unwrap_or(&[]);
        let mut rows: Vec<u32> =
            (0..table.rows as u32).filter(|&r| counts.get(r as usize).is_some_and(|&n| n > 0.0)).collect();
        let first = table.column(groups::FIRST_COUNTED).and_then(|c| c.numbers()).unwrap_or(&[]);
        rows.sort_by(|&a, &b| {
            let at = |r: u32| first.get(r as usize).copied().unwrap_or(f64::INFINITY);
            at(a).total_cmp(&at(b))
        });
        let warning = dropped_rows(chart, grouped.dropped, plan.rows(), &grouped.losses);
        if rows.is_empty() {
            return Err(encode::no_rows_of(chart, plan.rows() as usize, warning.as_ref()));
        }
        Ok(PlanGroups { table, rows, warnings: warning.into_iter().collect() })
    }

    /// The value statistics of group `row` (a row of `table`); `None` when it kept no rows. The
    /// median is NaN unless the query asked for it.
    pub fn summary(&self, row: u32) -> Option<Summary> {
        let at =
            |name: &str| self.table.column(name).and_then(|c| c.numbers()).and_then(|v| v.get(row as usize).copied());
        let n = at(groups::N)? as usize;
        if n == 0 {
            return None;
        }
        let sum = at(groups::SUM).unwrap_or(f64::NAN);
        Some(Summary {
            n,
            sum,
            mean: sum / n as f64,
            median: at(groups::MEDIAN).unwrap_or(f64::NAN),
            // One value has no spread (polars leaves it missing).
            stdev: at(groups::STDEV).filter(|s| s.is_finite()).unwrap_or(0.0),
            min: at(groups::MIN).unwrap_or(f64::NAN),
            max: at(groups::MAX).unwrap_or(f64::NAN),
        })
    }
}
