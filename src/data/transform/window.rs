//! Window functions (`rank()`, `cumsum(x)`, `rolling_mean(x, 7)`, ...) of `window` steps.
//!
//! The step sorts the rows by its `groupby` and `sort` columns and numbers them; every function
//! then runs over the rows of one group in that order.

use polars::prelude::*;

use super::expr::{Expr as Ast, Node};
use super::lower::{ExprError, Ty, lower};
use crate::spec::suggest;

const WINDOWS: [(&str, &str); 13] = [
    ("row_number", "row_number() (1, 2, 3, ... within the group)"),
    ("rank", "rank() (1, 1, 3: ties share a rank, gaps follow)"),
    ("dense_rank", "dense_rank() (1, 1, 2: no gaps)"),
    ("cumcount", "cumcount() (rows so far)"),
    ("cumsum", "cumsum(x)"),
    ("cummax", "cummax(x)"),
    ("cummin", "cummin(x)"),
    ("rolling_mean", "rolling_mean(x, 7) (this row and the 6 before it)"),
    ("rolling_sum", "rolling_sum(x, 7)"),
    ("rolling_min", "rolling_min(x, 7)"),
    ("rolling_max", "rolling_max(x, 7)"),
    ("lag", "lag(x) or lag(x, n) (the value n rows before)"),
    ("lead", "lead(x) or lead(x, n) (the value n rows after)"),
];

/// Whether `name` is a window function.
pub fn is_window(name: &str) -> bool {
    WINDOWS.iter().any(|(n, _)| *n == name)
}

/// What a window function sees: the groups, and the columns the step adds before the functions
/// run (in three passes, so no window expression nests inside another).
pub struct Frame<'a> {
    /// The `groupby` columns.
    pub groups: &'a [Expr],
    /// The column numbering the rows 1, 2, 3, ... within their group.
    pub number: &'a str,
    /// The column holding the number of the first row with the same group and sort keys.
    pub rank: &'a str,
}

impl Frame<'_> {
    fn over(&self, e: Expr) -> PolarsResult<Expr> {
        if self.groups.is_empty() { Ok(e) } else { e.over(self.groups) }
    }

    /// The row numbers within the group, from a column numbering all rows 0, 1, 2, ...
    pub fn number_expr(groups: &[Expr], row: &str) -> PolarsResult<Expr> {
        let first = if groups.is_empty() { col(row).min() } else { col(row).min().over(groups)? };
        Ok((col(row) - first).cast(DataType::Float64) + lit(1.0))
    }

    /// The rank (ties share the first row number) from the row-number column.
    pub fn rank_expr(groups: &[Expr], sort_keys: &[Expr], number: &str) -> PolarsResult<Expr> {
        let mut by: Vec<Expr> = groups.to_vec();
        by.extend(sort_keys.iter().cloned());
        if sort_keys.is_empty() { Ok(col(number)) } else { col(number).min().over(by) }
    }
}

/// One window call, named `output`.
pub fn lower_window(ast: &Ast, schema: &Schema, output: &str, frame: &Frame<'_>) -> Result<Expr, ExprError> {
    let Node::Call { name, args } = &ast.node else {
        return Err(error(ast, "a window function is a call such as `rank()` or `cumsum(x)`"));
    };
    let lower_name = name.to_ascii_lowercase();
    let Some((_, usage)) = WINDOWS.iter().find(|(n, _)| *n == lower_name) else {
        let names: Vec<&str> = WINDOWS.iter().map(|(n, _)| *n).collect();
        let mut e = error(ast, &format!("no window function `{name}`"));
        e.hint = suggest::hint(&lower_name, &names, "window functions", true);
        return Err(e);
    };
    let (lo, hi) = match lower_name.as_str() {
        "row_number" | "rank" | "dense_rank" | "cumcount" => (0, 0),
        "cumsum" | "cummax" | "cummin" => (1, 1),
        "lag" | "lead" => (1, 2),
        _ => (2, 2),
    };
    if args.len() < lo || args.len() > hi {
        let mut e = error(ast, &format!("`{lower_name}` takes other arguments"));
        e.hint = format!("write {usage}");
        return Err(e);
    }
    let value = |i: usize| -> Result<Expr, ExprError> {
        let t = lower(&args[i], schema)?;
        if !matches!(t.ty, Ty::Number | Ty::Null) && lower_name != "lag" && lower_name != "lead" {
            return Err(error(&args[i], &format!("`{lower_name}` needs numbers, but this is {}", t.ty.name())));
        }
        Ok(if t.ty == Ty::Number { t.expr.cast(DataType::Float64) } else { t.expr })
    };
    let rows = |i: usize, most: f64| -> Result<usize, ExprError> {
        match args.get(i).map(|a| &a.node) {
            None => Ok(1),
            Some(Node::Number(n)) if *n >= 1.0 && n.fract() == 0.0 && *n <= most => Ok(*n as usize),
            _ => Err(error(&args[i], &format!("the number of rows is a whole number from 1 to {most}"))),
        }
    };
    let windowed = match lower_name.as_str() {
        "row_number" | "cumcount" => Ok(col(frame.number)),
        "rank" => Ok(col(frame.rank)),
        "dense_rank" => {
            // A new sort-key value starts where the row number equals the rank.
            let starts = col(frame.number).eq(col(frame.rank)).cast(DataType::Float64);
            frame.over(starts.cum_sum(false))
        }
        "cumsum" => frame.over(value(0)?.cum_sum(false)),
        "cummax" => frame.over(value(0)?.cum_max(false)),
        "cummin" => frame.over(value(0)?.cum_min(false)),
        "lag" => frame.over(value(0)?.shift(lit(rows(1, 1e6)? as i64))),
        "lead" => frame.over(value(0)?.shift(lit(-(rows(1, 1e6)? as i64)))),
        _ => {
            let options =
                RollingOptionsFixedWindow { window_size: rows(1, 1e6)?, min_periods: 1, ..Default::default() };
            let x = value(0)?;
            frame.over(match lower_name.as_str() {
                "rolling_mean" => x.rolling_mean(options),
                "rolling_sum" => x.rolling_sum(options),
                "rolling_min" => x.rolling_min(options),
                _ => x.rolling_max(options),
            })
        }
    };
    let out = windowed.map_err(|e| error(ast, &format!("this window cannot be computed: {e}")))?;
    Ok(out.alias(output))
}

fn error(ast: &Ast, message: &str) -> ExprError {
    ExprError { message: message.to_owned(), hint: String::new(), span: ast.span.clone() }
}
