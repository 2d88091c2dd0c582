//! Each transform step checked against the current schema and added to the lazy plan.

use std::collections::BTreeMap;

use polars::prelude::*;

use super::TransformError;
use super::aggregate::lower_aggregate;
use super::bin::Bins;
use super::expr::{self, Expr as Ast};
use super::lower::{ExprError, Ty, as_datetime, lower, unknown_column};
use super::window::{Frame, lower_window};
use crate::spec::suggest;
use crate::spec::{PathSeg, SpannedValue, ValueKind};

/// The step keys, each with the options it takes.
const STEPS: [(&str, &[&str]); 16] = [
    ("filter", &[]),
    ("calculate", &["as"]),
    ("cast", &[]),
    ("parse", &[]),
    ("bin", &["maxbins", "step", "extent", "as"]),
    ("aggregate", &["groupby"]),
    ("fold", &["as"]),
    ("pivot", &["value", "groupby", "op"]),
    ("sort", &[]),
    ("sample", &["seed"]),
    ("head", &[]),
    ("window", &["sort", "groupby"]),
    ("join", &["on", "how", "fields"]),
    ("lookup", &["on", "fields"]),
    ("flatten", &[]),
    ("sql", &[]),
];

/// Most distinct values a `pivot` turns into columns.
pub const MAX_PIVOT_COLUMNS: usize = 1000;

/// What a step may refer to besides its own rows.
pub struct Env<'a> {
    /// The data source's name (also a table name in `sql`).
    pub source: &'a str,
    /// The plans of the sources built so far (for `join`, `lookup` and `sql`).
    pub others: &'a BTreeMap<String, LazyFrame>,
    /// Every data source's name (for "did you mean").
    pub names: &'a [String],
}

/// Add every step to `lf`; the first failing step ends the source's checks.
pub fn apply_steps(
    mut lf: LazyFrame,
    steps: &[SpannedValue],
    base: &[PathSeg],
    env: &Env<'_>,
) -> Result<LazyFrame, Vec<TransformError>> {
    // Every step's keys first, so misplaced options are all reported before anything runs.
    let mut compiled = Vec::with_capacity(steps.len());
    let mut errors = Vec::new();
    for (i, step) in steps.iter().enumerate() {
        let mut path = base.to_vec();
        path.push(PathSeg::Index(i));
        match Step::new(step, path) {
            Ok(s) => compiled.push(s),
            Err(e) => errors.extend(e),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    for step in compiled {
        let schema = lf.collect_schema().map_err(|e| vec![polars_error(&step.path, &e)])?;
        lf = step.apply(lf, &schema, env).map_err(|e| vec![e])?;
    }
    Ok(lf)
}

/// One step table: which step it is, and its values by key.
struct Step<'v> {
    kind: &'static str,
    value: &'v SpannedValue,
    path: Vec<PathSeg>,
}

impl<'v> Step<'v> {
    /// Work out the step key, and refuse options that belong to other steps.
    fn new(value: &'v SpannedValue, path: Vec<PathSeg>) -> Result<Self, Vec<TransformError>> {
        let step_names: Vec<&str> = STEPS.iter().map(|(k, _)| *k).collect();
        if !value.is_table() {
            return Err(vec![
                TransformError::at(path, format!("a transform step is a table, found {}", value.kind_name()))
                    .with_hint("write e.g. { filter = \"x > 0\" }"),
            ]);
        }
        let has_window = value.get("window").is_some();
        let found: Vec<&'static str> =
            STEPS.iter().map(|(k, _)| *k).filter(|k| value.get(k).is_some() && !(has_window && *k == "sort")).collect();
        let kind = match found.as_slice() {
            [one] => *one,
            [] => {
                return Err(vec![
                    TransformError::at(path, "this transform step has no step key")
                        .with_hint(format!("start it with one of: {}", step_names.join(", "))),
                ]);
            }
            [first, second, ..] => {
                let mut p = path;
                p.push(PathSeg::Key((*second).to_owned()));
                return Err(vec![
                    TransformError::at(p, format!("one step per table: this one has both `{first}` and `{second}`"))
                        .with_hint("write them as two steps, in the order they should run")
                        .on_key(),
                ]);
            }
        };
        let allowed = STEPS.iter().find(|(k, _)| *k == kind).map_or(&[][..], |(_, o)| *o);
        let mut errors = Vec::new();
        for entry in value.entries() {
            if entry.key != kind && !allowed.contains(&entry.key.as_str()) {
                let mut p = path.clone();
                p.push(PathSeg::Key(entry.key.clone()));
                let owners: Vec<&str> =
                    STEPS.iter().filter(|(_, o)| o.contains(&entry.key.as_str())).map(|(k, _)| *k).collect();
                let hint = if allowed.is_empty() {
                    format!("`{kind}` takes no options")
                } else {
                    format!(
                        "`{kind}` takes {}",
                        allowed.iter().map(|o| format!("`{o}`")).collect::<Vec<_>>().join(", ")
                    )
                };
                let message = if owners.is_empty() {
                    format!("`{}` is not an option of `{kind}`", entry.key)
                } else {
                    format!("`{}` belongs to {} steps, not `{kind}`", entry.key, owners.join(" and "))
                };
                errors.push(TransformError::at(p, message).with_hint(hint).on_key());
            }
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        Ok(Self { kind, value, path })
    }

    fn key_path(&self, key: &str) -> Vec<PathSeg> {
        let mut p = self.path.clone();
        p.push(PathSeg::Key(key.to_owned()));
        p
    }

    fn error(&self, key: &str, message: impl Into<String>) -> TransformError {
        TransformError::at(self.key_path(key), message)
    }

    fn text(&self, key: &str) -> Option<&'v str> {
        self.value.get(key).and_then(SpannedValue::as_str)
    }

    /// A string or a list of strings, as a list.
    fn names(&self, key: &str) -> Vec<String> {
        match self.value.get(key).map(|v| &v.kind) {
            Some(ValueKind::String(s)) => vec![s.clone()],
            Some(ValueKind::Array(items)) => items.iter().filter_map(|v| v.as_str().map(str::to_owned)).collect(),
            _ => Vec::new(),
        }
    }

    /// Parse the expression under `key` and hand it to `check`, placing its errors.
    fn expression<T>(&self, key: &str, check: impl FnOnce(&Ast) -> Result<T, ExprError>) -> Result<T, TransformError> {
        let text = self.text(key).unwrap_or("");
        self.expression_text(self.key_path(key), text, check)
    }

    fn expression_text<T>(
        &self,
        path: Vec<PathSeg>,
        text: &str,
        check: impl FnOnce(&Ast) -> Result<T, ExprError>,
    ) -> Result<T, TransformError> {
        let place = |message: String, hint: String, span: std::ops::Range<usize>| TransformError {
            path: path.clone(),
            inner: Some(span),
            message,
            hint,
            at_key: false,
        };
        let ast = expr::parse(text)
            .map_err(|e| place(format!("cannot read the expression: {}", e.message), String::new(), e.span))?;
        check(&ast).map_err(|e| place(e.message, e.hint, e.span))
    }

    /// Every named column must exist.
    fn columns_exist(&self, key: &str, names: &[String], schema: &Schema) -> Result<(), TransformError> {
        for (i, name) in names.iter().enumerate() {
            if schema.get(name.as_str()).is_none() {
                let mut p = self.key_path(key);
                if matches!(self.value.get(key).map(|v| &v.kind), Some(ValueKind::Array(_))) {
                    p.push(PathSeg::Index(i));
                }
                let e = unknown_column(name, schema, &(0..0));
                return Err(TransformError::at(p, e.message).with_hint(e.hint));
            }
        }
        Ok(())
    }

    fn apply(&self, lf: LazyFrame, schema: &Schema, env: &Env<'_>) -> Result<LazyFrame, TransformError> {
        match self.kind {
            "filter" => {
                let predicate = self.expression("filter", |ast| {
                    let t = lower(ast, schema)?;
                    if t.ty.fits_bool() {
                        Ok(t.expr)
                    } else {
                        Err(ExprError {
                            message: format!(
                                "a filter must be true or false for each row, but this is {}",
                                t.ty.name()
                            ),
                            hint: "compare it, e.g. `x > 0`".into(),
                            span: ast.span.clone(),
                        })
                    }
                })?;
                Ok(lf.filter(predicate))
            }
            "calculate" => {
                let name = self.output_name("calculate")?;
                let e = self.expression("calculate", |ast| lower(ast, schema))?;
                Ok(lf.with_column(e.expr.alias(name.as_str())))
            }
            "cast" | "parse" => self.cast(lf, schema),
            "bin" => self.bin(lf, schema),
            "aggregate" => {
                let groups = self.names("groupby");
                self.columns_exist("groupby", &groups, schema)?;
                let mut aggs = Vec::new();
                for entry in self.value.get("aggregate").map(SpannedValue::entries).unwrap_or(&[]) {
                    let mut p = self.key_path("aggregate");
                    p.push(PathSeg::Key(entry.key.clone()));
                    let text = entry.value.as_str().unwrap_or("");
                    aggs.push(self.expression_text(p, text, |ast| lower_aggregate(ast, schema, &entry.key))?);
                }
                if aggs.is_empty() {
                    return Err(self.error("aggregate", "`aggregate` names no output columns").with_hint(
                        "write e.g. aggregate = { n = \"count()\", mean_mpg = \"mean(Miles_per_Gallon)\" }",
                    ));
                }
                if groups.is_empty() {
                    return Ok(lf.select(aggs));
                }
                let by: Vec<Expr> = groups.iter().map(|g| col(g.as_str())).collect();
                Ok(lf.group_by_stable(by).agg(aggs))
            }
            "fold" => self.fold(lf, schema),
            "pivot" => self.pivot(lf, schema),
            "sort" => {
                let (exprs, descending) = self.sort_keys("sort", schema)?;
                Ok(sort(lf, exprs, descending))
            }
            "sample" => self.sample(lf),
            "head" => {
                let n = self.value.get("head").and_then(SpannedValue::as_f64).unwrap_or(0.0).max(0.0);
                Ok(lf.limit(n.min(IdxSize::MAX as f64) as IdxSize))
            }
            "window" => self.window(lf, schema),
            "join" | "lookup" => self.join(lf, schema, env),
            "flatten" => {
                let names = self.names("flatten");
                self.columns_exist("flatten", &names, schema)?;
                for name in &names {
                    if !matches!(schema.get(name.as_str()), Some(DataType::List(_))) {
                        return Err(self
                            .error("flatten", format!("column `{name}` holds single values, not lists"))
                            .with_hint("flatten unnests list columns such as [1, 2, 3] into one row per item"));
                    }
                }
                Ok(lf.explode(cols(names), ExplodeOptions { empty_as_null: true, keep_nulls: true }))
            }
            _ => self.sql(lf, env),
        }
    }

    /// The single output name under `as`.
    fn output_name(&self, step: &str) -> Result<String, TransformError> {
        match self.names("as").as_slice() {
            [one] if !one.is_empty() => Ok(one.clone()),
            [] => Err(TransformError::at(self.path.clone(), format!("`{step}` needs `as`, the new column's name"))
                .with_hint(format!("add as = \"NAME\" to the {step} step"))),
            _ => Err(self.error("as", format!("`{step}` makes one column: give `as` one name"))),
        }
    }

    fn cast(&self, lf: LazyFrame, schema: &Schema) -> Result<LazyFrame, TransformError> {
        let mut exprs = Vec::new();
        for entry in self.value.get(self.kind).map(SpannedValue::entries).unwrap_or(&[]) {
            let mut p = self.key_path(self.kind);
            p.push(PathSeg::Key(entry.key.clone()));
            let Some(dtype) = schema.get(entry.key.as_str()) else {
                let e = unknown_column(&entry.key, schema, &(0..0));
                return Err(TransformError::at(p, e.message).with_hint(e.hint).on_key());
            };
            let target = entry.value.as_str().unwrap_or("");
            let expr =
                cast_expr(&entry.key, Ty::of(dtype), target).map_err(|(m, h)| TransformError::at(p, m).with_hint(h))?;
            exprs.push(expr.alias(entry.key.as_str()));
        }
        Ok(lf.with_columns(exprs))
    }

    fn bin(&self, lf: LazyFrame, schema: &Schema) -> Result<LazyFrame, TransformError> {
        let field = self.text("bin").unwrap_or("").to_owned();
        self.columns_exist("bin", std::slice::from_ref(&field), schema)?;
        if !matches!(schema.get(field.as_str()).map(Ty::of), Some(Ty::Number)) {
            return Err(self
                .error("bin", format!("`bin` needs a numeric column, but `{field}` is not one"))
                .with_hint("cast it first with { cast = { NAME = \"number\" } }"));
        }
        let maxbins = self.value.get("maxbins").and_then(SpannedValue::as_f64).map_or(10, |m| m as u32);
        let step = self.value.get("step").and_then(SpannedValue::as_f64);
        let x = col(field.as_str()).cast(DataType::Float64);
        let (lo, hi) = match self.value.get("extent").and_then(SpannedValue::as_array) {
            Some([lo, hi]) => (lo.as_f64().unwrap_or(0.0), hi.as_f64().unwrap_or(0.0)),
            _ => {
                let finite = when(x.clone().is_finite()).then(x.clone()).otherwise(lit(NULL));
                let df = lf
                    .clone()
                    .select([finite.clone().min().alias("lo"), finite.max().alias("hi")])
                    .collect()
                    .map_err(|e| polars_error(&self.path, &e))?;
                let get =
                    |name: &str| df.column(name).ok().and_then(|c| c.get(0).ok()).and_then(|v| v.extract::<f64>());
                match (get("lo"), get("hi")) {
                    (Some(lo), Some(hi)) => (lo, hi),
                    _ => (0.0, 1.0),
                }
            }
        };
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(self.error("extent", "`extent` must be two finite numbers, the smaller first"));
        }
        let bins = Bins::nice(lo, hi, maxbins, step);
        let count = (bins.stop - bins.start) / bins.step;
        if count > 1e6 {
            return Err(self
                .error("step", format!("this step makes {count:.0} bins; at most 1000000 are allowed"))
                .with_hint("use a larger `step` or `maxbins`"));
        }
        let name = match self.names("as").first() {
            Some(n) => n.clone(),
            None => format!("{field}_bin"),
        };
        let last = bins.stop - bins.step;
        let clamped = when(x.clone().gt(lit(last))).then(lit(last)).otherwise(x.clone());
        let index = ((clamped - lit(bins.start)) / lit(bins.step) + lit(1e-14)).floor();
        let start = lit(bins.start) + lit(bins.step) * index;
        let inside = x.clone().gt_eq(lit(bins.start)).and(x.lt_eq(lit(bins.stop)));
        let start = when(inside).then(start).otherwise(lit(NULL).cast(DataType::Float64));
        let end_name = format!("{name}_end");
        Ok(lf.with_columns([start.clone().alias(name.as_str()), (start + lit(bins.step)).alias(end_name.as_str())]))
    }

    fn fold(&self, lf: LazyFrame, schema: &Schema) -> Result<LazyFrame, TransformError> {
        let folded: Vec<String> = self.names("fold");
        if folded.is_empty() {
            return Err(self
                .error("fold", "`fold` names no columns")
                .with_hint("write fold = [\"temp_max\", \"temp_min\"]"));
        }
        self.columns_exist("fold", &folded, schema)?;
        let types: Vec<Ty> = folded.iter().filter_map(|n| schema.get(n.as_str()).map(Ty::of)).collect();
        if types.windows(2).any(|w| w[0] != w[1] && w[0] != Ty::Null && w[1] != Ty::Null) {
            return Err(self
                .error("fold", "the folded columns hold values of different types")
                .with_hint("fold columns of one type (all numbers, say), or cast them first"));
        }
        let names = self.names("as");
        let (key, value) = match names.as_slice() {
            [] => ("key".to_owned(), "value".to_owned()),
            [k, v] => (k.clone(), v.clone()),
            _ => return Err(self.error("as", "`fold` makes two columns: as = [\"key\", \"value\"]")),
        };
        let index: Vec<String> = schema.iter_names().map(|n| n.to_string()).filter(|n| !folded.contains(n)).collect();
        Ok(lf.unpivot(UnpivotArgsDSL {
            on: Some(cols(folded)),
            index: cols(index),
            variable_name: Some(key.into()),
            value_name: Some(value.into()),
        }))
    }

    fn pivot(&self, lf: LazyFrame, schema: &Schema) -> Result<LazyFrame, TransformError> {
        let key = self.text("pivot").unwrap_or("").to_owned();
        self.columns_exist("pivot", std::slice::from_ref(&key), schema)?;
        let Some(value) = self.text("value").map(str::to_owned) else {
            return Err(TransformError::at(
                self.path.clone(),
                "`pivot` needs `value`, the column that fills the new columns",
            ));
        };
        self.columns_exist("value", std::slice::from_ref(&value), schema)?;
        let mut groups = self.names("groupby");
        if groups.is_empty() {
            groups = schema.iter_names().map(|n| n.to_string()).filter(|n| *n != key && *n != value).collect();
        }
        self.columns_exist("groupby", &groups, schema)?;
        let op = self.text("op").unwrap_or("sum");
        const OPS: [&str; 8] = ["sum", "mean", "median", "min", "max", "count", "first", "last"];
        if !OPS.contains(&op) {
            return Err(self
                .error("op", format!("no pivot op `{op}`"))
                .with_hint(suggest::hint(op, &OPS, "ops", true)));
        }
        let numeric = matches!(schema.get(value.as_str()).map(Ty::of), Some(Ty::Number | Ty::Null));
        if !numeric && matches!(op, "sum" | "mean" | "median") {
            return Err(self
                .error("op", format!("`{op}` needs numbers, but `{value}` is not numeric"))
                .with_hint("use op = \"first\" for text"));
        }
        let keys = lf
            .clone()
            .select([col(key.as_str()).cast(DataType::String).drop_nulls().unique_stable()])
            .limit((MAX_PIVOT_COLUMNS + 1) as IdxSize)
            .collect()
            .map_err(|e| polars_error(&self.path, &e))?;
        let keys: Vec<String> = keys
            .column(key.as_str())
            .ok()
            .and_then(|c| c.str().ok().map(|s| s.iter().flatten().map(str::to_owned).collect()))
            .unwrap_or_default();
        if keys.len() > MAX_PIVOT_COLUMNS {
            return Err(self
                .error(
                    "pivot",
                    format!("`{key}` has more than {MAX_PIVOT_COLUMNS} distinct values to turn into columns"),
                )
                .with_hint("pivot a column with fewer values, or filter first"));
        }
        let cell = |k: &str| col(value.as_str()).filter(col(key.as_str()).cast(DataType::String).eq(lit(k.to_owned())));
        let aggs: Vec<Expr> = keys
            .iter()
            .map(|k| {
                let x = cell(k);
                let e = match op {
                    "sum" => x.sum(),
                    "mean" => x.mean(),
                    "median" => x.median(),
                    "min" => x.min(),
                    "max" => x.max(),
                    "count" => x.count().cast(DataType::Float64),
                    "first" => x.first(),
                    _ => x.last(),
                };
                e.alias(k.as_str())
            })
            .collect();
        let by: Vec<Expr> = groups.iter().map(|g| col(g.as_str())).collect();
        Ok(lf.group_by_stable(by).agg(aggs))
    }

    /// Sort keys under `key`: names, `-name` for descending.
    fn sort_keys(&self, key: &str, schema: &Schema) -> Result<(Vec<Expr>, Vec<bool>), TransformError> {
        let mut exprs = Vec::new();
        let mut descending = Vec::new();
        let mut names = Vec::new();
        for raw in self.names(key) {
            let (name, desc) = match raw.strip_prefix('-') {
                Some(rest) if schema.get(raw.as_str()).is_none() => (rest.to_owned(), true),
                _ => (raw.clone(), false),
            };
            names.push(name.clone());
            exprs.push(col(name.as_str()));
            descending.push(desc);
        }
        self.columns_exist(key, &names, schema)?;
        Ok((exprs, descending))
    }

    fn sample(&self, lf: LazyFrame) -> Result<LazyFrame, TransformError> {
        let n = self.value.get("sample").and_then(SpannedValue::as_f64).unwrap_or(1.0).max(1.0) as usize;
        let seed = self.value.get("seed").and_then(SpannedValue::as_f64).map_or(0, |s| s.abs() as u64);
        const ROW: &str = "__dataink_sample_row";
        let df = lf.with_row_index(ROW, None).collect().map_err(|e| polars_error(&self.path, &e))?;
        let picked = if n >= df.height() {
            df
        } else {
            df.sample_n_literal(n, false, Some(false), Some(seed)).map_err(|e| polars_error(&self.path, &e))?
        };
        // The picked rows keep the order they had.
        Ok(picked.lazy().sort([ROW], SortMultipleOptions::default()).drop(cols([ROW])))
    }

    fn window(&self, lf: LazyFrame, schema: &Schema) -> Result<LazyFrame, TransformError> {
        let groups = self.names("groupby");
        self.columns_exist("groupby", &groups, schema)?;
        let (sort_exprs, descending) = self.sort_keys("sort", schema)?;
        let group_exprs: Vec<Expr> = groups.iter().map(|g| col(g.as_str())).collect();
        let mut keys = group_exprs.clone();
        keys.extend(sort_exprs.iter().cloned());
        let mut order = vec![false; group_exprs.len()];
        order.extend(descending);
        const ROW: &str = "__dataink_window_row";
        const NUMBER: &str = "__dataink_window_number";
        const RANK: &str = "__dataink_window_rank";
        let sorted = if keys.is_empty() { lf } else { sort(lf, keys, order) };
        let frame = Frame { groups: &group_exprs, number: NUMBER, rank: RANK };
        let mut exprs = Vec::new();
        for entry in self.value.get("window").map(SpannedValue::entries).unwrap_or(&[]) {
            let mut p = self.key_path("window");
            p.push(PathSeg::Key(entry.key.clone()));
            let text = entry.value.as_str().unwrap_or("");
            exprs.push(self.expression_text(p, text, |ast| lower_window(ast, schema, &entry.key, &frame))?);
        }
        if exprs.is_empty() {
            return Err(self
                .error("window", "`window` names no output columns")
                .with_hint("write e.g. window = { rank = \"rank()\", total = \"cumsum(x)\" }"));
        }
        let number = Frame::number_expr(&group_exprs, ROW).map_err(|e| polars_error(&self.path, &e))?;
        let rank = Frame::rank_expr(&group_exprs, &sort_exprs, NUMBER).map_err(|e| polars_error(&self.path, &e))?;
        Ok(sorted
            .with_row_index(ROW, None)
            .with_column(number.alias(NUMBER))
            .with_column(rank.alias(RANK))
            .with_columns(exprs)
            .drop(cols([ROW, NUMBER, RANK])))
    }

    fn join(&self, lf: LazyFrame, schema: &Schema, env: &Env<'_>) -> Result<LazyFrame, TransformError> {
        let other_name = self.text(self.kind).unwrap_or("");
        let Some(other) = env.others.get(other_name) else {
            let names: Vec<&str> = env.names.iter().map(String::as_str).filter(|n| *n != env.source).collect();
            let message = if env.names.iter().any(|n| n == other_name) {
                format!("data \"{other_name}\" could not be read, so it cannot be joined")
            } else {
                format!("no data source \"{other_name}\" to {}", self.kind)
            };
            return Err(self.error(self.kind, message).with_hint(suggest::hint(
                other_name,
                &names,
                "data sources",
                true,
            )));
        };
        let on = self.names("on");
        if on.is_empty() {
            return Err(TransformError::at(
                self.path.clone(),
                format!("`{}` needs `on`, the key column(s)", self.kind),
            )
            .with_hint("add on = \"id\" (the same name in both sources)"));
        }
        self.columns_exist("on", &on, schema)?;
        let mut other = other.clone();
        let other_schema = other.collect_schema().map_err(|e| polars_error(&self.path, &e))?;
        for name in &on {
            if other_schema.get(name.as_str()).is_none() {
                let e = unknown_column(name, &other_schema, &(0..0));
                return Err(self
                    .error(
                        "on",
                        format!("data \"{other_name}\" has {}", e.message.replace("no column", "no key column")),
                    )
                    .with_hint(e.hint));
            }
        }
        let fields = self.names("fields");
        self.columns_exist_in("fields", &fields, &other_schema, other_name)?;
        if !fields.is_empty() {
            let mut keep: Vec<Expr> = on.iter().map(|n| col(n.as_str())).collect();
            keep.extend(fields.iter().filter(|f| !on.contains(f)).map(|f| col(f.as_str())));
            other = other.select(keep);
        }
        let how = match (self.kind, self.text("how").unwrap_or("inner")) {
            ("lookup", _) | (_, "left") => JoinType::Left,
            (_, "inner") => JoinType::Inner,
            (_, "full") => JoinType::Full,
            (_, how) => {
                return Err(self.error("how", format!("no join `{how}`")).with_hint(suggest::hint(
                    how,
                    &["inner", "left", "full"],
                    "joins",
                    true,
                )));
            }
        };
        let keys: Vec<Expr> = on.iter().map(|n| col(n.as_str())).collect();
        let args = JoinArgs::new(how).with_coalesce(JoinCoalesce::CoalesceColumns);
        Ok(lf.join(other, keys.clone(), keys, args))
    }

    fn columns_exist_in(
        &self,
        key: &str,
        names: &[String],
        schema: &Schema,
        source: &str,
    ) -> Result<(), TransformError> {
        self.columns_exist(key, names, schema).map_err(|mut e| {
            e.message = format!("data \"{source}\" has {}", e.message);
            e
        })
    }

    fn sql(&self, lf: LazyFrame, env: &Env<'_>) -> Result<LazyFrame, TransformError> {
        let query = self.text("sql").unwrap_or("");
        if let Some(function) = super::sql_files::table_function(query) {
            return Err(self
                .error("sql", format!("the SQL query reads `{function}(...)`: a `sql` step reads only data sources"))
                .with_hint(
                    "name the file as a data source (`[data.NAME] path = ...`, which stays inside the spec's folder) \
                     and query it by its name",
                ));
        }
        let mut ctx = polars::sql::SQLContext::new();
        for (name, other) in env.others {
            ctx.register(name, other.clone());
        }
        ctx.register(env.source, lf.clone());
        ctx.register("source", lf);
        let mut out = ctx.execute(query).map_err(|e| {
            self.error("sql", format!("the SQL query fails: {}", first_line(&e)))
                .with_hint("the rows so far are the table `source`; other data sources are tables by their names")
        })?;
        out.collect_schema().map_err(|e| self.error("sql", format!("the SQL query fails: {}", first_line(&e))))?;
        Ok(out)
    }
}

impl Ty {
    fn fits_bool(self) -> bool {
        matches!(self, Ty::Bool | Ty::Null)
    }
}

fn sort(lf: LazyFrame, exprs: Vec<Expr>, descending: Vec<bool>) -> LazyFrame {
    let options = SortMultipleOptions::default()
        .with_order_descending_multi(descending)
        .with_nulls_last(true)
        .with_maintain_order(true);
    lf.sort_by_exprs(exprs, options)
}

/// The expression casting column `name` (of type `from`) to a `cast`/`parse` target.
fn cast_expr(name: &str, from: Ty, target: &str) -> Result<Expr, (String, String)> {
    let x = col(name);
    let (kind, format) = match target.split_once(':') {
        Some((k, f)) => (k.trim(), Some(f)),
        None => (target.trim(), None),
    };
    const TARGETS: [&str; 5] = ["number", "text", "boolean", "category", "date"];
    if format.is_some() && kind != "date" {
        return Err((format!("only `date` takes a format, found `{target}`"), "write e.g. \"date:%d/%m/%Y\"".into()));
    }
    Ok(match (kind, from) {
        ("number", Ty::Text) => x.str().strip_chars(lit(NULL)).strict_cast(DataType::Float64),
        ("number", Ty::Time) => as_datetime(x).cast(DataType::Int64).cast(DataType::Float64),
        ("number", _) => x.strict_cast(DataType::Float64),
        ("text" | "category", Ty::Time) => as_datetime(x).dt().to_string("%Y-%m-%dT%H:%M:%S%.3f"),
        ("text" | "category", from) => super::lower::to_text(x, from),
        ("boolean", Ty::Text) => {
            let t = x.str().strip_chars(lit(NULL)).str().to_lowercase();
            let yes = t
                .clone()
                .is_in(lit(Series::new(PlSmallStr::EMPTY, ["true", "yes", "1", "t", "y"])).implode(false), false);
            let no = t.is_in(lit(Series::new(PlSmallStr::EMPTY, ["false", "no", "0", "f", "n"])).implode(false), false);
            when(yes).then(lit(true)).when(no).then(lit(false)).otherwise(lit(NULL).cast(DataType::Boolean))
        }
        ("boolean", Ty::Number) => x.neq(lit(0.0)),
        ("boolean", _) => x.strict_cast(DataType::Boolean),
        ("date", Ty::Time) => as_datetime(x),
        ("date", Ty::Text) => {
            let options = |format: Option<&str>| StrptimeOptions {
                format: format.map(PlSmallStr::from),
                strict: true,
                exact: true,
                cache: true,
            };
            match format {
                Some(f) if !has_time_of_day(f) => as_datetime(x.str().to_date(options(Some(f)))),
                Some(f) => x.str().to_datetime(Some(TimeUnit::Milliseconds), None, options(Some(f)), lit("raise")),
                None => x.str().to_datetime(Some(TimeUnit::Milliseconds), None, options(None), lit("raise")),
            }
        }
        ("date", other) => {
            return Err((
                format!("column `{name}` is {}; only text can be parsed as dates", other.name()),
                "numbers such as years can become dates with calculate, e.g. concat(year, '-01-01') then cast".into(),
            ));
        }
        _ => {
            let hint = suggest::hint(kind, &TARGETS, "types", true);
            return Err((
                format!("no type `{target}` to cast to"),
                format!("{hint} (dates may take a format: \"date:%d/%m/%Y\")"),
            ));
        }
    })
}

/// Whether a strftime format reads a time of day.
fn has_time_of_day(format: &str) -> bool {
    ["%H", "%I", "%M", "%S", "%T", "%R", "%s", "%p", "%c", "%+"].iter().any(|d| format.contains(d))
}

fn first_line(e: &PolarsError) -> String {
    super::first_line(&e.to_string())
}

/// A polars failure while planning, at the step.
pub fn polars_error(path: &[PathSeg], e: &PolarsError) -> TransformError {
    TransformError::at(path.to_vec(), format!("this step fails: {}", first_line(e)))
}
