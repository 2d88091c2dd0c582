//! Density counts from a source's lazy plan, its rows never held: the plan (scan, transforms)
//! with only the two placed columns selected runs on polars' streaming engine, and each batch it
//! yields is counted into the grid ([`super::CountGrid::add`], the same arithmetic as for rows in
//! memory) and dropped. Memory is the grid plus a few batches, however many rows the file has.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use polars::prelude::*;

use super::{Bins, Coord, CountGrid, Extent};
use crate::data::contained::contain;

/// Rows scanned so far by the running density scans, and the rows those scans will read in all,
/// for a progress bar (both only grow, over the whole process).
pub static PROGRESS: ScanProgress = ScanProgress { scanned: AtomicU64::new(0), total: AtomicU64::new(0) };

/// Counters of the rows density scans have read and will read.
pub struct ScanProgress {
    scanned: AtomicU64,
    total: AtomicU64,
}

impl ScanProgress {
    /// Rows read so far, and rows to read in all.
    pub fn get(&self) -> (u64, u64) {
        (self.scanned.load(Ordering::Relaxed), self.total.load(Ordering::Relaxed))
    }
}

/// A source whose rows stay where they are (in its lazy plan, or on an engine), for charts
/// that only need them counted.
#[derive(Clone)]
pub struct PlanRows {
    source: String,
    schema: SchemaRef,
    rows: u64,
    backend: Backend,
}

/// Where the rows are counted.
#[derive(Clone)]
enum Backend {
    /// In this process, by polars' streaming engine.
    Lazy {
        frame: LazyFrame,
        /// The Parquet file the plan only scans (no transforms), whose footer may give the extent.
        parquet: Option<std::path::PathBuf>,
    },
    /// On a query engine, which sends back the counted bins.
    Engine {
        query: crate::data::engine::EngineQuery,
        /// The query's columns, with no rows.
        columns: DataFrame,
    },
}

impl std::fmt::Debug for PlanRows {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PlanRows").field("source", &self.source).field("rows", &self.rows).finish()
    }
}

/// Names for the two placed columns inside the scan (so `x` and `y` may be the same column).
const X: &str = "__dataink_x";
const Y: &str = "__dataink_y";

impl PlanRows {
    /// The rows of source `source` as `frame` yields them, counted (for a Parquet or IPC file
    /// from its metadata, for CSV by a scan of its lines).
    pub fn new(frame: LazyFrame, source: &str) -> Result<PlanRows, String> {
        let mut probe = frame.clone();
        let schema = contain(|| probe.collect_schema())?.map_err(|e| engine_error(source, &e))?;
        let counted =
            contain(|| frame.clone().select([len().alias("n")]).collect())?.map_err(|e| engine_error(source, &e))?;
        let rows = counted.column("n").ok().and_then(|c| c.get(0).ok()).and_then(|v| v.extract::<u64>()).unwrap_or(0);
        Ok(PlanRows { source: source.to_string(), schema, rows, backend: Backend::Lazy { frame, parquet: None } })
    }

    /// The rows of source `source` as an engine's query yields them (two queries: the columns,
    /// and the row count).
    pub fn on_engine(query: crate::data::engine::EngineQuery, source: &str) -> Result<PlanRows, String> {
        let columns = query.columns()?;
        let rows = query.rows()?;
        let schema = columns.schema().clone();
        Ok(PlanRows { source: source.to_string(), schema, rows, backend: Backend::Engine { query, columns } })
    }

    /// The same rows, known to be exactly those of the Parquet file at `path` (the plan scans it
    /// and does nothing else), so its footer's statistics can give the extent.
    pub fn scanning_only(mut self, path: std::path::PathBuf) -> PlanRows {
        if let Backend::Lazy { parquet, .. } = &mut self.backend {
            *parquet = Some(path);
        }
        self
    }

    /// The plan, when the rows are counted in this process.
    pub(super) fn frame(&self) -> Result<&LazyFrame, String> {
        match &self.backend {
            Backend::Lazy { frame, .. } => Ok(frame),
            Backend::Engine { .. } => Err(format!("data \"{}\": the rows are on the engine", self.source)),
        }
    }

    /// The column `field` and its type.
    fn typed<'a>(&'a self, field: &'a str) -> Result<(&'a str, &'a DataType), String> {
        let dtype =
            self.schema.get(field).ok_or_else(|| format!("data \"{}\" has no column `{field}`", self.source))?;
        Ok((field, dtype))
    }

    /// The type of column `field`.
    pub(super) fn dtype_of(&self, field: &str) -> Result<&DataType, String> {
        self.schema.get(field).ok_or_else(|| format!("data \"{}\" has no column `{field}`", self.source))
    }

    /// The source's name.
    pub(super) fn source(&self) -> &str {
        &self.source
    }

    /// How many rows the plan yields.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// The plan's columns, with no rows: what column checks and titles read.
    pub fn empty_frame(&self) -> Result<DataFrame, String> {
        match &self.backend {
            Backend::Lazy { frame, .. } => {
                contain(|| frame.clone().slice(0, 0).collect())?.map_err(|e| engine_error(&self.source, &e))
            }
            Backend::Engine { columns, .. } => Ok(columns.clone()),
        }
    }

    /// Whether `field` holds numbers or instants (what a table holds as numbers).
    pub fn is_number(&self, field: &str) -> bool {
        self.schema.get(field).is_some_and(|d| d.is_primitive_numeric() || d.is_temporal())
    }

    /// Whether `field` holds instants (a date or date-time column).
    pub fn is_time(&self, field: &str) -> bool {
        matches!(self.schema.get(field), Some(DataType::Date | DataType::Datetime(..)))
    }

    /// The extent of each axis (`log`: whether it is logarithmic), as [`Extent`] defines it:
    /// one streaming query of four minima and maxima.
    pub fn extent(&self, x: &str, y: &str, log: [bool; 2]) -> Result<Extent, String> {
        let parquet = match &self.backend {
            Backend::Engine { query, .. } => {
                return query.extent(self.typed(x)?, self.typed(y)?, log).map_err(|e| self.named(e));
            }
            Backend::Lazy { parquet, .. } => parquet,
        };
        if let Some(path) = parquet
            && let (Some(xr), Some(yr)) =
                (super::footer::float_range(path, x, log[0]), super::footer::float_range(path, y, log[1]))
        {
            return Ok(Extent { x: Some(xr), y: Some(yr) });
        }
        let range = |field: &str, log: bool| -> Result<[Expr; 2], String> {
            let v = self.number(field)?.cast(DataType::Float64);
            let keep = if log { v.clone().is_finite().and(v.clone().gt(lit(0.0))) } else { v.clone().is_finite() };
            let placed = v.filter(keep);
            Ok([placed.clone().min(), placed.max()])
        };
        let [x0, x1] = range(x, log[0])?;
        let [y0, y1] = range(y, log[1])?;
        let query = self.frame()?.clone().select([x0.alias("x0"), x1.alias("x1"), y0.alias("y0"), y1.alias("y1")]);
        let df = contain(|| query.collect_with_engine(Engine::Streaming))?
            .map_err(|e| engine_error(&self.source, &e))?
            .unwrap_single();
        let value = |name: &str| df.column(name).ok().and_then(|c| c.get(0).ok()).and_then(|v| v.extract::<f64>());
        let pair = |a, b| match (value(a), value(b)) {
            (Some(lo), Some(hi)) if lo <= hi => Some((lo, hi)),
            _ => None,
        };
        Ok(Extent { x: pair("x0", "x1"), y: pair("y0", "y1") })
    }

    /// The rows counted into a grid over `x` and `y`.
    pub fn count(&self, x_field: &str, y_field: &str, x: &Bins, y: &Bins) -> Result<CountGrid, String> {
        if let Backend::Engine { query, .. } = &self.backend {
            PROGRESS.total.fetch_add(self.rows, Ordering::Relaxed);
            let grid = query.count(self.typed(x_field)?, self.typed(y_field)?, x, y).map_err(|e| self.named(e))?;
            PROGRESS.scanned.fetch_add(self.rows, Ordering::Relaxed);
            return Ok(grid);
        }
        let threads = rayon::current_num_threads().max(1);
        let parts = vec![CountGrid::new(x.clone(), y.clone()); threads];
        let mut parts = self.scan(x_field, y_field, CountFold { parts })?.parts.into_iter();
        let mut grid = parts.next().unwrap_or_else(|| CountGrid::new(x.clone(), y.clone()));
        for part in parts {
            grid.merge(&part);
        }
        Ok(grid)
    }

    /// Run the plan with only `x` and `y` selected (`f32` and `f64` columns as stored, other
    /// numbers as `f64`, times in milliseconds since the epoch as tables hold them), folding each
    /// batch into `fold`.
    pub(super) fn scan<F: Fold>(&self, x: &str, y: &str, fold: F) -> Result<F, String> {
        let placed = self.frame()?.clone().select([self.number(x)?.alias(X), self.number(y)?.alias(Y)]);
        self.run_batches(placed, fold, |fold: &mut F, batch: &DataFrame| {
            let (xs, ys) = (Coords::of(batch.column(X)?)?, Coords::of(batch.column(Y)?)?);
            match (xs.values()?, ys.values()?) {
                (Values::F32(a), Values::F32(b)) => fold.fold(a, b),
                (Values::F32(a), Values::F64(b)) => fold.fold(a, b),
                (Values::F64(a), Values::F32(b)) => fold.fold(a, b),
                (Values::F64(a), Values::F64(b)) => fold.fold(a, b),
            }
            Ok(())
        })
    }

    /// Run `placed` (the plan with some columns selected) on the streaming engine, handing each
    /// batch it yields to `each` with `fold`, and counting the rows for the progress bar.
    fn run_batches<F: Send + 'static>(
        &self,
        placed: LazyFrame,
        fold: F,
        each: impl Fn(&mut F, &DataFrame) -> PolarsResult<()> + Send + Sync + 'static,
    ) -> Result<F, String> {
        let shared = Arc::new(Mutex::new(fold));
        let sink = Arc::clone(&shared);
        PROGRESS.total.fetch_add(self.rows, Ordering::Relaxed);
        let callback = PlanCallback::new(move |batch: DataFrame| {
            // A poisoned lock means an earlier batch panicked; that panic is reported instead.
            if let Ok(mut fold) = sink.lock() {
                each(&mut fold, &batch)?;
            }
            PROGRESS.scanned.fetch_add(batch.height() as u64, Ordering::Relaxed);
            Ok(false)
        });
        let source = &self.source;
        contain(|| placed.sink_batches(callback, false, None)?.collect_with_engine(Engine::Streaming))?
            .map_err(|e| engine_error(source, &e))?;
        let fold = Arc::try_unwrap(shared).map_err(|_| format!("data \"{source}\": the scan did not finish"))?;
        fold.into_inner().map_err(|_| format!("data \"{source}\": the scan failed part way"))
    }

    /// Run the plan with only `fields` selected, each as `f64` numbers (times in milliseconds
    /// since the epoch, missing cells NaN), folding each batch into `fold`: for views that count
    /// several columns at once.
    pub fn scan_columns<F: ColumnsFold>(&self, fields: &[&str], fold: F) -> Result<F, String> {
        let names: Vec<String> = (0..fields.len()).map(|i| format!("__dataink_c{i}")).collect();
        let mut selected = Vec::with_capacity(fields.len());
        for (field, name) in fields.iter().zip(&names) {
            selected.push(self.number(field)?.cast(DataType::Float64).alias(name.as_str()));
        }
        let placed = self.frame()?.clone().select(selected);
        self.run_batches(placed, fold, move |fold: &mut F, batch: &DataFrame| {
            let mut columns = Vec::with_capacity(names.len());
            for name in &names {
                let ca = batch.column(name)?.f64()?;
                let ca = if ca.null_count() > 0 { ca.fill_null_with_values(f64::NAN)? } else { ca.clone() };
                columns.push(ca.rechunk().into_owned());
            }
            let slices = columns.iter().map(|c| c.cont_slice()).collect::<PolarsResult<Vec<&[f64]>>>()?;
            fold.fold(&slices);
            Ok(())
        })
    }

    /// The same source with only the rows `keep` is true for, of which there are `rows`.
    pub(super) fn filtered(&self, keep: Expr, rows: u64) -> Result<PlanRows, String> {
        let frame = self.frame()?.clone().filter(keep);
        Ok(PlanRows {
            source: self.source.clone(),
            schema: self.schema.clone(),
            rows,
            backend: Backend::Lazy { frame, parquet: None },
        })
    }

    /// An engine's error, naming the source.
    fn named(&self, message: String) -> String {
        format!("data \"{}\": {message}", self.source)
    }

    /// Column `field` as numbers: `f32` and `f64` as they are, other numbers cast to `f64`,
    /// times in milliseconds since the epoch.
    pub(super) fn number(&self, field: &str) -> Result<Expr, String> {
        let dtype =
            self.schema.get(field).ok_or_else(|| format!("data \"{}\" has no column `{field}`", self.source))?;
        let column = col(field);
        Ok(match dtype {
            DataType::Float32 | DataType::Float64 => column,
            d if d.is_primitive_numeric() => column.cast(DataType::Float64),
            DataType::Datetime(unit, _) => {
                let per_ms = match unit {
                    TimeUnit::Milliseconds => 1.0,
                    TimeUnit::Microseconds => 1e3,
                    TimeUnit::Nanoseconds => 1e6,
                };
                column.cast(DataType::Int64).cast(DataType::Float64) / lit(per_ms)
            }
            DataType::Date => column.cast(DataType::Int32).cast(DataType::Float64) * lit(86_400_000.0),
            other => {
                return Err(format!(
                    "column `{field}` of data \"{}\" holds {other}, not numbers or times",
                    self.source
                ));
            }
        })
    }
}

/// What [`PlanRows::scan_columns`] folds its batches into.
pub trait ColumnsFold: Send + 'static {
    /// Count one batch: `columns[k][r]` is row `r`'s value of the `k`-th field.
    fn fold(&mut self, columns: &[&[f64]]);
}

/// What a scan folds its batches into.
pub(super) trait Fold: Send + 'static {
    /// Count one batch's rows `(xs[r], ys[r])`.
    fn fold<X: Coord, Y: Coord>(&mut self, xs: &[X], ys: &[Y]);
}

/// The counts, one grid per thread.
struct CountFold {
    parts: Vec<CountGrid>,
}

impl Fold for CountFold {
    fn fold<X: Coord, Y: Coord>(&mut self, xs: &[X], ys: &[Y]) {
        CountGrid::add_in_parts(&mut self.parts, xs, ys);
    }
}

/// A batch's column as stored, missing cells NaN, in one piece.
enum Coords {
    F32(Float32Chunked),
    F64(Float64Chunked),
}

/// The values of a [`Coords`].
enum Values<'a> {
    F32(&'a [f32]),
    F64(&'a [f64]),
}

impl Coords {
    fn of(column: &Column) -> PolarsResult<Coords> {
        Ok(if column.dtype() == &DataType::Float32 {
            let ca = column.f32()?;
            let ca = if ca.null_count() > 0 { ca.fill_null_with_values(f32::NAN)? } else { ca.clone() };
            Coords::F32(ca.rechunk().into_owned())
        } else {
            let ca = column.f64()?;
            let ca = if ca.null_count() > 0 { ca.fill_null_with_values(f64::NAN)? } else { ca.clone() };
            Coords::F64(ca.rechunk().into_owned())
        })
    }

    fn values(&self) -> PolarsResult<Values<'_>> {
        Ok(match self {
            Coords::F32(ca) => Values::F32(ca.cont_slice()?),
            Coords::F64(ca) => Values::F64(ca.cont_slice()?),
        })
    }
}

/// An engine error's first line, naming the source.
pub(super) fn engine_error(source: &str, error: &PolarsError) -> String {
    format!("data \"{source}\": {}", crate::data::transform::first_line(&error.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(xs: Vec<Option<f64>>, ys: Vec<Option<f32>>) -> LazyFrame {
        df!("a" => xs, "b" => ys).expect("frame").lazy()
    }

    #[test]
    fn the_plan_counts_the_grid_the_columns_give() {
        let n = 250_000;
        let xs: Vec<Option<f64>> =
            (0..n).map(|i| if i % 997 == 0 { None } else { Some(((i * 7919) % 1000) as f64 / 100.0) }).collect();
        let ys: Vec<Option<f32>> = (0..n).map(|i| Some(((i * 104_729) % 4001) as f32 / 400.0)).collect();
        let rows = PlanRows::new(frame(xs.clone(), ys.clone()).filter(col("b").lt(lit(9.5f32))), "points").unwrap();
        let kept: Vec<usize> = (0..n).filter(|&i| ys[i].unwrap() < 9.5).collect();
        assert_eq!(rows.rows(), kept.len() as u64);
        let (x, y) = (Bins::new(0.0, 10.0, 37, false).unwrap(), Bins::new(0.0, 9.0, 23, false).unwrap());
        let counted = rows.count("a", "b", &x, &y).unwrap();
        let mem_x: Vec<f64> = kept.iter().map(|&i| xs[i].unwrap_or(f64::NAN)).collect();
        let mem_y: Vec<f64> = kept.iter().map(|&i| ys[i].map_or(f64::NAN, f64::from)).collect();
        assert_eq!(counted, super::super::count_columns(&mem_x, &mem_y, None, &x, &y));
        assert!(counted.missing > 0 && counted.outside > 0);
        let extent = rows.extent("a", "b", [false, false]).unwrap();
        assert_eq!(extent, super::super::extent_of_columns(&mem_x, &mem_y, [false, false]));
    }

    #[test]
    fn text_columns_and_unknown_names_are_refused_by_name() {
        let lf = df!("t" => ["a", "b"], "v" => [1.0, 2.0]).unwrap().lazy();
        let rows = PlanRows::new(lf, "words").unwrap();
        let err = rows.extent("t", "v", [false, false]).unwrap_err();
        assert!(err.contains("column `t`") && err.contains("\"words\""), "{err}");
        let err = rows.extent("nope", "v", [false, false]).unwrap_err();
        assert!(err.contains("no column `nope`"), "{err}");
    }
}
