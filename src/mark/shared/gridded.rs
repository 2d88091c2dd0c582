//! Gridded input shared by the grid chart kinds (`contour`, `image`, `section`): a regular grid
//! read from a long-form table with one row per node.

use crate::data::{Column, ColumnValues, Table};
use crate::enrich::grid::Grid;
use crate::mark::warning::Warning;
use crate::mark::{MarkError, encode};
use crate::spec::{ChannelOptions, Chart, ColorOptions};

/// Largest grid accepted (nodes).
pub const MAX_NODES: usize = 25_000_000;

/// A grid read from a table, with what the chart kinds need besides it.
pub struct GridInput<'t> {
    /// The grid (missing or non-finite z values are NaN holes).
    pub grid: Grid,
    /// Rows with finite coordinates.
    pub rows: Vec<u32>,
    /// Warnings from the non-finite policy.
    pub warnings: Vec<Warning>,
    /// The x column.
    pub x_col: &'t Column,
    /// The y column.
    pub y_col: &'t Column,
    /// Smallest finite z.
    pub zmin: f64,
    /// Largest finite z.
    pub zmax: f64,
}

/// Read the grid named by the x, y and z channels of chart `index`.
pub fn load_grid<'t>(
    chart: &Chart,
    x_opts: &ChannelOptions,
    y_opts: &ChannelOptions,
    z_opts: &ColorOptions,
    table: &'t Table,
) -> Result<GridInput<'t>, MarkError> {
    let x_col = encode::column(chart, "x", &x_opts.field, table)?;
    let y_col = encode::column(chart, "y", &y_opts.field, table)?;
    let z_col = encode::column(chart, "z", &z_opts.field, table)?;
    for (key, field, col) in [("x", &x_opts.field, x_col), ("y", &y_opts.field, y_col), ("z", &z_opts.field, z_col)] {
        if !col.is_numeric() {
            return Err(MarkError::at(
                &[key],
                format!("column `{field}` holds {}; a grid needs numbers", col.type_name()),
                "use numeric columns for x, y and z",
            ));
        }
    }
    if let Some(grid) = grid_of_axes(x_col, y_col, z_col) {
        // A grid source's own coordinates: every row is a node, every coordinate finite.
        let Some((zmin, zmax)) = grid.range() else {
            return Err(all_missing(z_opts));
        };
        let rows = (0..table.rows as u32).collect();
        return Ok(GridInput { grid, rows, warnings: Vec::new(), x_col, y_col, zmin, zmax });
    }
    // Rows without finite coordinates cannot be placed; a non-finite z is a hole in the grid.
    let (rows, warning) =
        encode::finite_rows(&chart.name, table.rows, &[(x_opts.field.as_str(), x_col), (y_opts.field.as_str(), y_col)]);
    let warnings: Vec<Warning> = warning.into_iter().collect();
    if rows.is_empty() {
        return Err(encode::no_rows(chart, table, warnings.first()));
    }
    let grid = grid_from_rows(x_col, y_col, z_col, &rows)?;
    let Some((zmin, zmax)) = grid.range() else {
        return Err(all_missing(z_opts));
    };
    Ok(GridInput { grid, rows, warnings, x_col, y_col, zmin, zmax })
}

fn all_missing(z_opts: &ColorOptions) -> MarkError {
    MarkError::at(&["z"], format!("every value of `{}` is missing or non-finite", z_opts.field), "check the z column")
}

/// The grid of a grid source read directly: `x` and `y` are its coordinate columns
/// ([`ColumnValues::Axis`], x fastest, both increasing and finite) and `z` has a value per node.
/// `None` for anything else, which goes through the rows.
fn grid_of_axes(x_col: &Column, y_col: &Column, z_col: &Column) -> Option<Grid> {
    let (ColumnValues::Axis(x), ColumnValues::Axis(y)) = (&x_col.values, &y_col.values) else { return None };
    let (xs, ys) = (x.coords(), y.coords());
    let nodes = xs.len().checked_mul(ys.len())?;
    let increasing = |c: &[f64]| c.iter().all(|v| v.is_finite()) && c.windows(2).all(|w| w[0] < w[1]);
    let z = z_col.numbers()?;
    let fits = x.repeat() == 1 && y.repeat() == xs.len() && x.len() == nodes && y.len() == nodes && z.len() == nodes;
    if !fits || !increasing(xs) || !increasing(ys) {
        return None;
    }
    Grid::new(xs.to_vec(), ys.to_vec(), z.to_vec()).ok()
}

/// Build the grid from long-form rows: the distinct x and y values are the grid's axes.
pub fn grid_from_rows(x_col: &Column, y_col: &Column, z_col: &Column, rows: &[u32]) -> Result<Grid, MarkError> {
    let (xv, yv, zv) = (x_col.numbers().unwrap_or(&[]), y_col.numbers().unwrap_or(&[]), z_col.numbers().unwrap_or(&[]));
    if rows.len() == xv.len()
        && let Some((xs, ys)) = row_major_axes(xv, yv)
    {
        let nodes = xs.len() * ys.len();
        if nodes <= MAX_NODES {
            return Grid::new(xs, ys, zv[..nodes].to_vec())
                .map_err(|e| MarkError::at(&["x"], format!("{e}"), "check the grid coordinates"));
        }
    }
    let distinct = |v: &[f64]| {
        let mut d: Vec<f64> = rows.iter().filter_map(|&r| v.get(r as usize).copied()).collect();
        d.sort_by(f64::total_cmp);
        d.dedup();
        d
    };
    let xs = distinct(xv);
    let ys = distinct(yv);
    let nodes = xs.len().saturating_mul(ys.len());
    if nodes > MAX_NODES {
        return Err(MarkError::at(
            &["x"],
            format!("the grid would have {} × {} = {nodes} nodes (at most {MAX_NODES})", xs.len(), ys.len()),
            "resample the field to a coarser grid",
        ));
    }
    if rows.len() * 2 < nodes {
        return Err(MarkError::at(
            &["x"],
            format!(
                "x and y do not form a regular grid: {} rows for {} distinct x × {} distinct y values",
                rows.len(),
                xs.len(),
                ys.len()
            ),
            "contour needs one row per node of a rectangular grid (long form: x, y, z)",
        ));
    }
    let mut values = vec![f64::NAN; nodes];
    let mut seen = vec![false; nodes];
    for &r in rows {
        let (Some(&x), Some(&y)) = (xv.get(r as usize), yv.get(r as usize)) else { continue };
        let (Ok(i), Ok(j)) = (xs.binary_search_by(|v| v.total_cmp(&x)), ys.binary_search_by(|v| v.total_cmp(&y)))
        else {
            continue;
        };
        let k = j * xs.len() + i;
        if seen.get(k).copied().unwrap_or(true) {
            return Err(MarkError::at(
                &["x"],
                format!("the grid node ({x}, {y}) appears in more than one row (row {r})"),
                "each (x, y) pair must appear once; aggregate duplicates first",
            ));
        }
        seen[k] = true;
        values[k] = zv.get(r as usize).copied().unwrap_or(f64::NAN);
    }
    Grid::new(xs, ys, values).map_err(|e| MarkError::at(&["x"], format!("{e}"), "check the grid coordinates"))
}

/// The axes of a table whose rows already are a grid in row-major order — x increasing fastest,
/// then y increasing, every node once — as grid files (`.npy`, matrices) and most exporters
/// write them; `None` for any other order, which [`grid_from_rows`] then sorts out. One pass
/// over the rows, no sorting.
fn row_major_axes(xv: &[f64], yv: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
    let y0 = *yv.first()?;
    let nx = yv.iter().position(|&y| y != y0).unwrap_or(yv.len());
    if nx < 2 || !yv.len().is_multiple_of(nx) || yv.len() != xv.len() {
        return None;
    }
    let xs = &xv[..nx];
    if !xs.windows(2).all(|w| w[0] < w[1]) {
        return None;
    }
    let mut ys = Vec::with_capacity(yv.len() / nx);
    for (xrow, yrow) in xv.chunks_exact(nx).zip(yv.chunks_exact(nx)) {
        let y = yrow[0];
        if ys.last().is_some_and(|&last| last >= y) || xrow != xs || yrow.iter().any(|&v| v != y) {
            return None;
        }
        ys.push(y);
    }
    Some((xs.to_vec(), ys))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid of (x, y, z) rows through the general path (sorting) and through whatever path
    /// `grid_from_rows` takes.
    fn both(xv: &[f64], yv: &[f64], zv: &[f64]) -> (Option<(Vec<f64>, Vec<f64>)>, Grid) {
        let col =
            |name: &str, v: &[f64]| Column { name: name.into(), values: crate::data::ColumnValues::Number(v.to_vec()) };
        let rows: Vec<u32> = (0..xv.len() as u32).collect();
        let grid = grid_from_rows(&col("x", xv), &col("y", yv), &col("z", zv), &rows).unwrap();
        (row_major_axes(xv, yv), grid)
    }

    #[test]
    fn rows_already_in_grid_order_skip_the_sort_and_give_the_same_grid() {
        let (xv, yv, zv) =
            ([0.0, 1.0, 3.0, 0.0, 1.0, 3.0], [5.0, 5.0, 5.0, 7.0, 7.0, 7.0], [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        let (fast, grid) = both(&xv, &yv, &zv);
        assert_eq!(fast, Some((vec![0.0, 1.0, 3.0], vec![5.0, 7.0])));
        // The same rows shuffled go through the sort: the same grid.
        let order = [4, 0, 5, 2, 1, 3];
        let pick = |v: &[f64]| order.iter().map(|&i| v[i]).collect::<Vec<f64>>();
        let (slow, shuffled) = both(&pick(&xv), &pick(&yv), &pick(&zv));
        assert_eq!(slow, None);
        assert_eq!(grid, shuffled);
    }

    #[test]
    fn other_orders_are_not_taken_for_a_row_major_grid() {
        // y fastest (column-major), x decreasing, y decreasing, a ragged row, a repeated x.
        assert_eq!(row_major_axes(&[0.0, 0.0, 1.0, 1.0], &[0.0, 1.0, 0.0, 1.0]), None);
        assert_eq!(row_major_axes(&[1.0, 0.0, 1.0, 0.0], &[0.0, 0.0, 1.0, 1.0]), None);
        assert_eq!(row_major_axes(&[0.0, 1.0, 0.0, 1.0], &[1.0, 1.0, 0.0, 0.0]), None);
        assert_eq!(row_major_axes(&[0.0, 1.0, 0.0, 2.0], &[0.0, 0.0, 1.0, 1.0]), None);
        assert_eq!(row_major_axes(&[0.0, 1.0, 0.0, 1.0], &[0.0, 0.0, 1.0, 2.0]), None);
        assert_eq!(row_major_axes(&[0.0, 1.0, 1.0], &[0.0, 0.0, 0.0]), None);
        assert_eq!(row_major_axes(&[0.0, 1.0, 0.0], &[0.0, 0.0, 1.0]), None);
    }
}
