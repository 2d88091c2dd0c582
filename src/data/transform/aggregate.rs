//! Aggregate calls (`count()`, `mean(x)`, `quantile(x, 0.9)`, ...) of `aggregate` steps.

use polars::prelude::*;

use super::expr::{Expr as Ast, Node};
use super::lower::{ExprError, Ty, lower};
use crate::spec::suggest;

/// The aggregate functions, with how each is written.
const AGGREGATES: [(&str, &str); 13] = [
    ("count", "count() (rows) or count(x) (values that are not null)"),
    ("sum", "sum(x)"),
    ("mean", "mean(x)"),
    ("median", "median(x)"),
    ("min", "min(x)"),
    ("max", "max(x)"),
    ("quantile", "quantile(x, 0.9)"),
    ("stdev", "stdev(x) (sample standard deviation)"),
    ("variance", "variance(x) (sample variance)"),
    ("distinct", "distinct(x) (number of distinct values)"),
    ("first", "first(x)"),
    ("last", "last(x)"),
    ("values", "values(x) (the list of values)"),
];

/// Whether `name` is an aggregate function.
pub fn is_aggregate(name: &str) -> bool {
    AGGREGATES.iter().any(|(n, _)| *n == name)
}

/// One aggregate call checked against the schema: its polars expression, named `output`.
pub fn lower_aggregate(ast: &Ast, schema: &Schema, output: &str) -> Result<Expr, ExprError> {
    let Node::Call { name, args } = &ast.node else {
        return Err(error(ast, "an aggregate is a call such as `mean(x)` or `count()`"));
    };
    let lower_name = name.to_ascii_lowercase();
    let Some((_, usage)) = AGGREGATES.iter().find(|(n, _)| *n == lower_name) else {
        let names: Vec<&str> = AGGREGATES.iter().map(|(n, _)| *n).collect();
        let mut e = error(ast, &format!("no aggregate `{name}`"));
        e.hint = suggest::hint(&lower_name, &names, "aggregates", true);
        return Err(e);
    };
    let arity_error = || {
        let mut e = error(ast, &format!("`{lower_name}` takes other arguments"));
        e.hint = format!("write {usage}");
        e
    };
    if lower_name == "count" && args.is_empty() {
        return Ok(len().cast(DataType::Float64).alias(output));
    }
    let expected = if lower_name == "quantile" { 2 } else { 1 };
    if args.len() != expected {
        return Err(arity_error());
    }
    let value = lower(&args[0], schema)?;
    let numeric = matches!(lower_name.as_str(), "sum" | "mean" | "quantile" | "stdev" | "variance");
    let ordered = matches!(lower_name.as_str(), "median" | "min" | "max");
    let fits = match value.ty {
        Ty::Null | Ty::Number => true,
        Ty::Time => !numeric,
        Ty::Text | Ty::Bool => !numeric && !ordered,
        Ty::Other => lower_name == "count" || lower_name == "first" || lower_name == "last",
    };
    if !fits {
        let what = if numeric { "numbers" } else { "numbers or dates" };
        return Err(error(&args[0], &format!("`{lower_name}` needs {what}, but this is {}", value.ty.name())));
    }
    let x = if numeric && value.ty == Ty::Number { value.expr.cast(DataType::Float64) } else { value.expr };
    // NaN counts as missing, as it does everywhere in dataink.
    let x = if value.ty == Ty::Number { when(x.clone().is_nan()).then(lit(NULL)).otherwise(x) } else { x };
    let out = match lower_name.as_str() {
        "count" => x.count().cast(DataType::Float64),
        "sum" => x.sum(),
        "mean" => x.mean(),
        "median" => x.median(),
        "min" => x.min(),
        "max" => x.max(),
        "stdev" => x.std(1),
        "variance" => x.var(1),
        "distinct" => x.drop_nulls().n_unique().cast(DataType::Float64),
        "first" => x.first(),
        "last" => x.last(),
        "values" => x.implode(true),
        _ => {
            let q = match args[1].node {
                Node::Number(q) if (0.0..=1.0).contains(&q) => q,
                _ => return Err(error(&args[1], "the quantile is a number from 0 to 1")),
            };
            x.quantile(lit(q), QuantileMethod::Linear)
        }
    };
    Ok(out.alias(output))
}

fn error(ast: &Ast, message: &str) -> ExprError {
    ExprError { message: message.to_owned(), hint: String::new(), span: ast.span.clone() }
}
