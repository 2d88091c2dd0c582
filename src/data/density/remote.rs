//! Density counts computed by a query engine: the source's query, with the two placed columns
//! bucketed and counted by one `GROUP BY` on the engine, so only the counted bins come back.
//!
//! The engine places a row by the arithmetic guess of [`Bins`]; a row whose guess lies within
//! [`NEAR_EDGE`] of a bin edge (or of the grid's border) comes back with its value instead of
//! its bin, grouped by value, and is binned here by [`Bins::index`]. So the grid is the one the
//! same rows give in-process bit for bit, whatever the engine's rounding of `log10` or of the
//! guess: a guess that far from an edge is the bin by any rounding a few units in the last place.

use polars::prelude::*;

use super::{Bins, CountGrid, Extent, Unplaced};
use crate::data::engine::EngineQuery;
use crate::data::engine::sql::{double, ident};

/// How near (in bins) to an edge a row's guess must be to come back as its value.
const NEAR_EDGE: f64 = 1e-6;

/// A column's dtype decides how its values become numbers.
enum Kind {
    Number,
    /// Timestamps with a time zone (Spark's `TIMESTAMP`): `unix_micros` over 1000, as in-process
    /// (milliseconds since the epoch).
    Instant,
    /// Timestamps without one (`TIMESTAMP_NTZ`): microseconds from the epoch's wall time, so no
    /// session time zone shifts them.
    Wall,
    /// Dates: days since the epoch times 86,400,000.
    Day,
}

/// The density queries of an engine source.
impl EngineQuery {
    /// The extent of each axis as [`Extent`] defines it: one query of four minima and maxima.
    pub fn extent(&self, x: (&str, &DataType), y: (&str, &DataType), log: [bool; 2]) -> Result<Extent, String> {
        let (vx, vy) = (value(x)?, value(y)?);
        let kept = |v: &str, log: bool| format!("CASE WHEN {} THEN {v} END", placeable(v, log));
        let sql = format!(
            "SELECT min(px) AS x0, max(px) AS x1, min(py) AS y0, max(py) AS y1 FROM \
             (SELECT {} AS px, {} AS py FROM (SELECT {vx} AS vx, {vy} AS vy FROM ({}) AS rows) AS v) AS p",
            kept("vx", log[0]),
            kept("vy", log[1]),
            self.query
        );
        let df = self.run(&sql)?;
        let get = |name: &str| df.column(name).ok().and_then(|c| c.get(0).ok()).and_then(|v| v.extract::<f64>());
        let pair = |a, b| match (get(a), get(b)) {
            (Some(lo), Some(hi)) if lo <= hi => Some((lo, hi)),
            _ => None,
        };
        Ok(Extent { x: pair("x0", "x1"), y: pair("y0", "y1") })
    }

    /// The rows counted into a grid over `x` and `y` by the engine (see the module's doc).
    pub fn count(&self, x: (&str, &DataType), y: (&str, &DataType), bx: &Bins, by: &Bins) -> Result<CountGrid, String> {
        let (vx, vy) = (value(x)?, value(y)?);
        let (fx, fy) = (guess("vx", bx), guess("vy", by));
        let (nx, ny) = (bx.len() as f64, by.len() as f64);
        let inside = |f: &str, n: f64| format!("({f} > {} AND {f} < {})", double(-NEAR_EDGE), double(n + NEAR_EDGE));
        let border = |f: &str, n: f64| {
            format!("(abs({f}) < {eps} OR abs({f} - {n}) < {eps})", eps = double(NEAR_EDGE), n = double(n))
        };
        let near = |f: &str, n: f64| {
            format!(
                "({f} < {eps} OR {f} > {top} OR {f} - floor({f}) < {eps} OR {f} - floor({f}) > {one})",
                eps = double(NEAR_EDGE),
                top = double(n - NEAR_EDGE),
                one = double(1.0 - NEAR_EDGE)
            )
        };
        // One grouping key per row: its cell (`j · nx + i`) when the engine placed it, else
        // `LACKING − (4 · why x + why y)` (a value that cannot be placed, see `why`),
        // `OUTSIDE − (2 · x outside + y outside)`, or `NEAR` (near an edge or the border: its
        // values come back as `ex`, `ey`). Rows near the border are sent back before the outside
        // ones, so "outside" per axis is exact.
        let sql = format!(
            "SELECT cell, ex, ey, count(*) AS n FROM (\
               SELECT CASE cls WHEN 2 THEN CAST(floor(fy) AS BIGINT) * {nx_int} + CAST(floor(fx) AS BIGINT) \
                        WHEN 0 THEN {LACKING} - (4 * {why_x} + {why_y}) \
                        WHEN 1 THEN {OUTSIDE} - (2 * (CASE WHEN {in_x} THEN 0 ELSE 1 END) \
                                                + (CASE WHEN {in_y} THEN 0 ELSE 1 END)) \
                        ELSE {NEAR} END AS cell, \
                 CASE WHEN cls = 3 THEN vx END AS ex, \
                 CASE WHEN cls = 3 THEN vy END AS ey \
               FROM (\
                 SELECT vx, vy, fx, fy, \
                   CASE WHEN NOT ({px} AND {py}) THEN 0 WHEN {border_x} OR {border_y} THEN 3 \
                        WHEN NOT ({in_x} AND {in_y}) THEN 1 \
                        WHEN {near_x} OR {near_y} THEN 3 ELSE 2 END AS cls \
                 FROM (SELECT vx, vy, {fx} AS fx, {fy} AS fy FROM \
                   (SELECT {vx} AS vx, {vy} AS vy FROM ({query}) AS rows) AS v) AS f) AS c) AS b \
             GROUP BY cell, ex, ey",
            nx_int = bx.len(),
            why_x = why("vx", bx.is_log()),
            why_y = why("vy", by.is_log()),
            border_x = border("fx", nx),
            border_y = border("fy", ny),
            near_x = near("fx", nx),
            near_y = near("fy", ny),
            px = placeable("vx", bx.is_log()),
            py = placeable("vy", by.is_log()),
            in_x = inside("fx", nx),
            in_y = inside("fy", ny),
            query = self.query,
        );
        let df = self.run(&sql)?;
        grid_of(&df, bx, by).map_err(|e| format!("engine {}: unreadable counts: {e}", self.url))
    }
}

/// Column `field` as a `DOUBLE` the way tables hold it (numbers as they are, instants in
/// milliseconds since the epoch).
fn value((field, dtype): (&str, &DataType)) -> Result<String, String> {
    let kind = match dtype {
        DataType::Datetime(_, None) => Kind::Wall,
        DataType::Datetime(..) => Kind::Instant,
        DataType::Date => Kind::Day,
        d if d.is_primitive_numeric() => Kind::Number,
        other => return Err(format!("column `{field}` holds {other}; a density view places numbers or times")),
    };
    let column = ident(field);
    Ok(match kind {
        Kind::Number => format!("CAST({column} AS DOUBLE)"),
        Kind::Instant => format!("(CAST(unix_micros({column}) AS DOUBLE) / {})", double(1e3)),
        Kind::Wall => format!(
            "(CAST(timestampdiff(MICROSECOND, TIMESTAMP_NTZ'1970-01-01 00:00:00', {column}) AS DOUBLE) / {})",
            double(1e3)
        ),
        Kind::Day => format!("(CAST(unix_date({column}) AS DOUBLE) * {})", double(86_400_000.0)),
    })
}

/// Why `v` cannot be placed on an axis, as a code: 0 it can, 1 missing or NaN, 2 infinite,
/// 3 ≤ 0 on a log axis (the order of [`Unplaced`]).
fn why(v: &str, log: bool) -> String {
    let non_positive = if log { format!(" WHEN {v} <= {} THEN 3", double(0.0)) } else { String::new() };
    format!(
        "(CASE WHEN {v} IS NULL OR isnan({v}) THEN 1 WHEN abs({v}) = CAST('Infinity' AS DOUBLE) THEN 2{non_positive} ELSE 0 END)"
    )
}

/// The reason a [`why`] code stands for.
fn unplaced(code: i64) -> Option<Unplaced> {
    match code {
        1 => Some(Unplaced::Missing),
        2 => Some(Unplaced::Infinite),
        3 => Some(Unplaced::NonPositive),
        _ => None,
    }
}

/// Group keys below the cells: rows lacking a value, rows outside, rows sent back by value.
const LACKING: i64 = -100;
const OUTSIDE: i64 = -200;
const NEAR: i64 = -4;

/// Whether `v` can be placed on an axis: present, finite, and positive on a log axis.
fn placeable(v: &str, log: bool) -> String {
    let finite = format!("({v} IS NOT NULL AND NOT isnan({v}) AND abs({v}) <> CAST('Infinity' AS DOUBLE))");
    if log { format!("({finite} AND {v} > {})", double(0.0)) } else { finite }
}

/// The arithmetic position of `v` along `bins`, in bins from the lower edge.
fn guess(v: &str, bins: &Bins) -> String {
    let lo = bins.edges[0];
    let term =
        if bins.is_log() { format!("log10(CASE WHEN {v} > {} THEN {v} END)", double(0.0)) } else { v.to_string() };
    format!("(({term} - {}) * {})", double(lo), double(bins.per_unit))
}

/// The grid the engine's groups make: cells it placed, rows near an edge placed here.
fn grid_of(df: &DataFrame, bx: &Bins, by: &Bins) -> PolarsResult<CountGrid> {
    let mut grid = CountGrid::new(bx.clone(), by.clone());
    let int = |name: &str| -> PolarsResult<Int64Chunked> { df.column(name)?.cast(&DataType::Int64)?.i64().cloned() };
    let float =
        |name: &str| -> PolarsResult<Float64Chunked> { df.column(name)?.cast(&DataType::Float64)?.f64().cloned() };
    let (cell, n) = (int("cell")?, int("n")?);
    let (ex, ey) = (float("ex")?, float("ey")?);
    let nx = bx.len();
    for r in 0..df.height() {
        let count = n.get(r).unwrap_or(0).max(0) as u64;
        match cell.get(r) {
            Some(k) if k >= 0 => match grid.counts.get_mut(k as usize) {
                Some(c) => *c += count,
                None => grid.outside += count,
            },
            Some(NEAR) => match (ex.get(r), ey.get(r)) {
                (Some(vx), Some(vy)) => match (bx.index(vx), by.index(vy)) {
                    (Some(i), Some(j)) => grid.counts[j * nx + i] += count,
                    _ => grid.not_placed_times(vx, vy, count),
                },
                _ => grid.outside += count,
            },
            Some(k) if (LACKING - 15..=LACKING).contains(&k) => {
                let code = LACKING - k;
                grid.missing += count;
                for (axis, why) in [code / 4, code % 4].into_iter().enumerate() {
                    if let Some(why) = unplaced(why) {
                        grid.losses.lack(axis, why, count);
                    }
                }
            }
            Some(k) if (OUTSIDE - 3..=OUTSIDE).contains(&k) => {
                let code = OUTSIDE - k;
                grid.outside += count;
                grid.losses.outside[0] += count * (code / 2) as u64;
                grid.losses.outside[1] += count * (code % 2) as u64;
            }
            _ => grid.outside += count,
        }
    }
    Ok(grid)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_are_placed_by_bin_or_by_value() {
        let (bx, by) = (Bins::new(0.0, 10.0, 10, false).unwrap(), Bins::new(1.0, 1000.0, 3, true).unwrap());
        let df = df!(
            "cell" => [3i64, NEAR, NEAR, LACKING - 4, OUTSIDE - 3, 11],
            "ex" => [None, Some(5.0), Some(9.99), None, None, None],
            "ey" => [None, Some(500.0), Some(1000.0), None, None, None],
            "n" => [4i64, 2, 7, 5, 6, 1],
        )
        .unwrap();
        let grid = grid_of(&df, &bx, &by).unwrap();
        assert_eq!(grid.counts[3], 4);
        assert_eq!(grid.counts[2 * 10 + 5], 2, "x = 5 is the lower edge of bin 5");
        assert_eq!(grid.counts[2 * 10 + 9], 7, "y = 1000 is the top of the last log bin");
        assert_eq!(grid.counts[10 + 1], 1);
        assert_eq!((grid.missing, grid.outside, grid.placed()), (5, 6, 14));
        assert_eq!(grid.losses.missing, [5, 0], "code 4 · 1 + 0: x missing, y placeable");
        assert_eq!(grid.losses.outside, [6, 6], "code 2 · 1 + 1: outside on both axes");
    }

    #[test]
    fn values_become_doubles_as_tables_hold_them() {
        assert_eq!(value(("a", &DataType::Float32)).unwrap(), "CAST(`a` AS DOUBLE)");
        let utc = DataType::Datetime(TimeUnit::Microseconds, Some(TimeZone::UTC));
        assert!(value(("t", &utc)).unwrap().contains("unix_micros(`t`)"));
        assert!(value(("t", &DataType::Datetime(TimeUnit::Microseconds, None))).unwrap().contains("TIMESTAMP_NTZ"));
        assert!(value(("s", &DataType::String)).unwrap_err().contains("column `s`"));
    }
}
