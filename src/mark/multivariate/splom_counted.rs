//! A scatter-plot matrix in density mode over rows left in its source's plan: one streaming query
//! finds the rows finite in every column and each column's extent over them; the diagonal
//! histograms' Freedman–Diaconis bins take exact quartiles from tallies of the narrowed plan;
//! then one scan of all the columns counts every cell's bins and every diagonal's histogram,
//! with the same placing arithmetic as rows in memory ([`super::splom`]'s `density_bin` and
//! [`bin_index`]), so the matrix is the one the rows held give.

use std::collections::HashMap;
use std::sync::Arc;

use rayon::prelude::*;

use super::splom::{DensityCounts, density_bin};
use crate::data::density::columns::FiniteRows;
use crate::data::density::plan::{ColumnsFold, PlanRows};
use crate::enrich::distribution::{bin_index, freedman_diaconis_bins_of, freedman_diaconis_saturates};
use crate::guide::layout::PositionAxis;
use crate::guide::scale::Scale;
use crate::mark::encode;
use crate::mark::plan_rows;
use crate::mark::warning::Warning;
use crate::mark::{MarkError, density::AUTO_DENSITY_ROWS};
use crate::scene::Rect;
use crate::spec::{ChannelOptions, Chart, ScaleKind};

/// The bins of one off-diagonal cell: column `j` across, column `i` up.
pub(super) struct CellBins {
    pub i: usize,
    pub j: usize,
    pub cell: Rect,
    pub nx: usize,
    pub ny: usize,
    pub x: Scale,
    pub y: Scale,
}

/// The histogram bins of one diagonal cell: `bins` equal bins over `[lo, hi]` of `column`.
pub(super) struct DiagonalBins {
    pub column: usize,
    pub lo: f64,
    pub hi: f64,
    pub bins: usize,
}

/// The counts of every cell and diagonal.
pub(super) struct CountedCells {
    /// By (row, column) of the matrix.
    pub cells: HashMap<(usize, usize), DensityCounts>,
    /// Each column's diagonal histogram, when it has one.
    pub diagonals: Vec<Option<Vec<f64>>>,
}

/// The rows of a splom's source left in its plan.
pub(super) struct CountedRows {
    finite: FiniteRows,
    kept: PlanRows,
    fields: Vec<String>,
    /// The dropped-rows warning, when rows were dropped.
    pub warnings: Vec<Warning>,
}

impl CountedRows {
    /// The rows of `plan` finite in every column of `fields`; the no-rows error when none is,
    /// and an error when too few are left for density mode (`mode = "auto"`).
    pub fn of(chart: &Chart, plan: &PlanRows, fields: &[&str], density_asked: bool) -> Result<CountedRows, MarkError> {
        let finite = plan.finite_rows(fields).map_err(scanned)?;
        let warning = plan_rows::dropped_rows(chart, finite.dropped, plan.rows(), &finite.losses);
        if finite.rows == 0 {
            return Err(encode::no_rows_of(chart, plan.rows() as usize, warning.as_ref()));
        }
        if !density_asked && finite.rows <= AUTO_DENSITY_ROWS {
            return Err(MarkError::at(
                &["mode"],
                format!(
                    "only {} of {} rows are finite in every column, too few for density mode, and the rows were left in the source's plan to be counted",
                    finite.rows,
                    plan.rows()
                ),
                "set `mode = \"density\"` to count them, or filter the source to the rows to draw as points",
            ));
        }
        let kept = plan.keeping_finite(fields, &finite).map_err(scanned)?;
        let fields = fields.iter().map(|f| f.to_string()).collect();
        Ok(CountedRows { finite, kept, fields, warnings: warning.into_iter().collect() })
    }

    /// How many rows are drawn.
    pub fn rows(&self) -> usize {
        self.finite.rows as usize
    }

    /// The axis of column `k` (`time`: it holds instants), over its extent.
    pub fn axis(&self, k: usize, options: &ChannelOptions, time: bool) -> Result<PositionAxis, MarkError> {
        let kind = match options.scale {
            Some(ScaleKind::Band) => {
                return Err(MarkError::at(
                    &["columns", "scale"],
                    format!("column `{}` cannot be counted in bins on a band scale", options.field),
                    "remove `scale = \"band\"`: a scatter-plot matrix places numbers",
                ));
            }
            Some(kind) => kind,
            None if time => ScaleKind::Time,
            None => ScaleKind::Linear,
        };
        encode::numeric_axis("columns", options, kind, self.finite.extents.get(k).copied().flatten())
    }

    /// The diagonal histograms' bin counts over `domains` (each column's axis): `bins` when
    /// given, else Freedman–Diaconis between 8 and 50. Its quartiles come from a first tally of
    /// every column (one scan), narrowed to the exact values only where the tally cannot tell
    /// the outcome: with many rows the rule gives 50 bins whenever the quartiles differ.
    pub fn diagonal_bins(&self, bins: Option<u32>, domains: &[(f64, f64)]) -> Result<Vec<usize>, MarkError> {
        if let Some(b) = bins {
            return Ok(vec![b as usize; domains.len()]);
        }
        let n = self.rows();
        let fields: Vec<&str> = self.fields.iter().map(String::as_str).collect();
        let extents: Vec<(f64, f64)> = self.finite.extents.iter().map(|e| e.unwrap_or((0.0, 0.0))).collect();
        let tallies = self.kept.opening_tallies(&fields, &extents).map_err(scanned)?;
        let mut counts = Vec::with_capacity(domains.len());
        for (k, &domain) in domains.iter().enumerate() {
            let (first, (a, b)) = (&tallies[k], extents[k]);
            if freedman_diaconis_saturates(n, b - a, domain, 50) && plan_rows::quartiles_differ(first) {
                counts.push(50);
                continue;
            }
            let mut failed = None;
            let quartiles = || match plan_rows::quartiles(&self.kept, fields[k], first) {
                Ok(q) => Some(q),
                Err(e) => {
                    failed = Some(e);
                    None
                }
            };
            let bins = freedman_diaconis_bins_of(n, quartiles, domain, (8, 50));
            if let Some(e) = failed {
                return Err(scanned(e));
            }
            counts.push(bins);
        }
        Ok(counts)
    }

    /// Count every cell of `cells` and histogram of `diagonals` in one scan (`columns`: how many
    /// columns the matrix has).
    pub fn count(
        &self,
        columns: usize,
        cells: Vec<CellBins>,
        diagonals: Vec<DiagonalBins>,
    ) -> Result<CountedCells, MarkError> {
        let fields: Vec<&str> = self.fields.iter().map(String::as_str).collect();
        let fold = MatrixFold {
            counts: cells.iter().map(|c| vec![0u32; c.nx * c.ny]).collect(),
            histograms: diagonals.iter().map(|d| vec![0.0; d.bins]).collect(),
            cells: Arc::new(cells),
            diagonals: Arc::new(diagonals),
        };
        let label = format!("matrix counts of {} columns", fields.len());
        let fold = crate::timing::timed(&label, || self.kept.scan_columns(&fields, fold)).map_err(scanned)?;
        let mut diagonal_counts = vec![None; columns];
        for (d, h) in fold.diagonals.iter().zip(fold.histograms) {
            if let Some(slot) = diagonal_counts.get_mut(d.column) {
                *slot = Some(h);
            }
        }
        let cells = fold
            .cells
            .iter()
            .zip(fold.counts)
            .map(|(c, all)| ((c.i, c.j), DensityCounts { cell: c.cell, nx: c.nx, ny: c.ny, all, selected: None }))
            .collect();
        Ok(CountedCells { cells, diagonals: diagonal_counts })
    }
}

/// A scan's error, with where to look.
fn scanned(message: String) -> MarkError {
    MarkError::at(&["data"], message, "`dataink data SPEC NAME` shows the rows after the source's transforms")
}

/// Every cell's counts and every diagonal's histogram, filled batch by batch.
struct MatrixFold {
    cells: Arc<Vec<CellBins>>,
    diagonals: Arc<Vec<DiagonalBins>>,
    counts: Vec<Vec<u32>>,
    histograms: Vec<Vec<f64>>,
}

/// Rows counted by one task of a batch.
const ROWS_PER_TASK: usize = 1 << 15;

impl ColumnsFold for MatrixFold {
    fn fold(&mut self, columns: &[&[f64]]) {
        let n = columns.first().map_or(0, |c| c.len());
        let (cells, diagonals) = (&self.cells, &self.diagonals);
        let parts: Vec<(Vec<Vec<u32>>, Vec<Vec<f64>>)> = (0..n.div_ceil(ROWS_PER_TASK))
            .into_par_iter()
            .map(|task| {
                let rows = task * ROWS_PER_TASK..((task + 1) * ROWS_PER_TASK).min(n);
                let mut counts: Vec<Vec<u32>> = cells.iter().map(|c| vec![0u32; c.nx * c.ny]).collect();
                let mut histograms: Vec<Vec<f64>> = diagonals.iter().map(|d| vec![0.0; d.bins]).collect();
                for (c, counts) in cells.iter().zip(&mut counts) {
                    let (xs, ys) = (&columns[c.j][rows.clone()], &columns[c.i][rows.clone()]);
                    for (&xv, &yv) in xs.iter().zip(ys) {
                        if let Some(b) = density_bin(c.cell, (c.nx, c.ny), (&c.x, &c.y), xv, yv) {
                            counts[b] += 1;
                        }
                    }
                }
                for (d, histogram) in diagonals.iter().zip(&mut histograms) {
                    // `bin_counts` counts nothing in an empty range.
                    if d.bins == 0 || d.hi <= d.lo {
                        continue;
                    }
                    let scale = d.bins as f64 / (d.hi - d.lo);
                    for &v in &columns[d.column][rows.clone()] {
                        if let Some(b) = bin_index(v, (d.lo, d.hi), scale, d.bins) {
                            histogram[b] += 1.0;
                        }
                    }
                }
                (counts, histograms)
            })
            .collect();
        for (counts, histograms) in parts {
            for (total, part) in self.counts.iter_mut().zip(counts) {
                total.iter_mut().zip(part).for_each(|(t, p)| *t += p);
            }
            for (total, part) in self.histograms.iter_mut().zip(histograms) {
                total.iter_mut().zip(part).for_each(|(t, p)| *t += p);
            }
        }
    }
}
