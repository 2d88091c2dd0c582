//! A source's query as Spark SQL text: the relation it reads (a table, or a Parquet, ORC or
//! JSON path the cluster reads), then its transform steps, each a query over the one before, so
//! the engine runs scan, steps and the chart's aggregation as one query.
//!
//! `filter` and `calculate` expressions are printed from their parsed form (the same parser the
//! in-process steps use); `sql` steps are Spark SQL already. Other steps say they do not run on
//! an engine, rather than run differently there.

use crate::data::transform::expr::{self, BinaryOp, Expr, Node};
use crate::spec::transform::TransformStep;

/// A column or table name quoted for Spark SQL: `` `name` ``, backticks doubled.
pub fn ident(name: &str) -> String {
    format!("`{}`", name.replace('`', "``"))
}

/// A number as a Spark SQL `DOUBLE` literal that reads back as exactly `v`: the shortest
/// round-trip digits with an exponent (`2.5e-1`), which Spark takes as a double (a plain
/// `0.25` would be a decimal); NaN and the infinities by name.
pub fn double(v: f64) -> String {
    if v.is_nan() {
        "CAST('NaN' AS DOUBLE)".to_string()
    } else if v.is_infinite() {
        format!("CAST('{}Infinity' AS DOUBLE)", if v < 0.0 { "-" } else { "" })
    } else {
        format!("({v:e})")
    }
}

/// A text as a Spark SQL string literal (quotes and backslashes escaped).
pub fn text(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('\'');
    for c in s.chars() {
        match c {
            '\'' => out.push_str("\\'"),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c => out.push(c),
        }
    }
    out.push('\'');
    out
}

/// The relation a source reads: a table of the engine's catalog (`db.name` allowed), or a file
/// path the cluster reads, its format from `format` or the path's extension.
pub fn relation(table: Option<&str>, path: Option<&str>, format: Option<&str>) -> Result<String, String> {
    if let Some(table) = table {
        let parts: Vec<String> = table.split('.').map(ident).collect();
        return Ok(format!("SELECT * FROM {}", parts.join(".")));
    }
    let Some(path) = path else {
        return Err("an engine source names a `table` or a `path` the cluster reads".to_string());
    };
    let lower = path.to_ascii_lowercase();
    let reader = match format {
        Some(f) => f,
        None if lower.ends_with(".parquet") || lower.ends_with(".pq") || !lower.contains('.') => "parquet",
        None if lower.ends_with(".orc") => "orc",
        None if lower.ends_with(".json") || lower.ends_with(".jsonl") => "json",
        None => {
            return Err(format!(
                "the engine reads Parquet, ORC or JSON paths, not `{path}`; register the file as a table and name it with `table`"
            ));
        }
    };
    if !matches!(reader, "parquet" | "orc" | "json") {
        return Err(format!("the engine reads Parquet, ORC or JSON paths, not {reader}"));
    }
    Ok(format!("SELECT * FROM {reader}.{}", ident(path)))
}

/// The query `base` followed by the transform `steps` of source `name`; on a step that cannot
/// run on the engine, its index and why.
pub fn with_steps(base: String, steps: &[TransformStep], name: &str) -> Result<String, (usize, String)> {
    let mut query = base;
    for (i, step) in steps.iter().enumerate() {
        query = step_query(&query, step, name).map_err(|e| (i, e))?;
    }
    Ok(query)
}

fn step_query(rows: &str, step: &TransformStep, name: &str) -> Result<String, String> {
    if let Some(filter) = &step.filter {
        return Ok(format!("SELECT * FROM ({rows}) AS rows WHERE {}", expression(filter)?));
    }
    if let Some(calculate) = &step.calculate {
        let Some(target) = step.as_.as_ref().and_then(|a| a.as_slice().first()) else {
            return Err("`calculate` names its column with `as`".to_string());
        };
        return Ok(format!("SELECT *, {} AS {} FROM ({rows}) AS rows", expression(calculate)?, ident(target)));
    }
    if let Some(sql) = &step.sql {
        // The rows so far are the table `source` and the source's own name, as in-process.
        let own = if name == "source" { String::new() } else { format!(", {} AS (SELECT * FROM source)", ident(name)) };
        return Ok(format!("WITH source AS ({rows}){own} SELECT * FROM ({sql}) AS rows"));
    }
    Err("this step does not run on an engine source; `filter`, `calculate` and `sql` (Spark SQL) steps do".to_string())
}

/// A `filter` or `calculate` expression as Spark SQL.
pub fn expression(text: &str) -> Result<String, String> {
    let ast = expr::parse(text).map_err(|e| e.message)?;
    print(&ast)
}

fn print(e: &Expr) -> Result<String, String> {
    Ok(match &e.node {
        Node::Number(v) => double(*v),
        Node::Text(s) => self::text(s),
        Node::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        Node::Null => "NULL".to_string(),
        Node::Column(name) => ident(name),
        Node::Negate(x) => format!("(-{})", print(x)?),
        Node::Not(x) => format!("(NOT {})", print(x)?),
        Node::Binary(op, a, b) => {
            let symbol = match op {
                BinaryOp::Or => "OR",
                BinaryOp::And => "AND",
                BinaryOp::Eq => "=",
                BinaryOp::NotEq => "<>",
                other => other.symbol(),
            };
            format!("({} {symbol} {})", print(a)?, print(b)?)
        }
        Node::In { value, list, negated } => {
            let items: Result<Vec<String>, String> = list.iter().map(print).collect();
            format!("({} {}IN ({}))", print(value)?, if *negated { "NOT " } else { "" }, items?.join(", "))
        }
        Node::IsNull { value, negated } => {
            format!("({} IS {}NULL)", print(value)?, if *negated { "NOT " } else { "" })
        }
        Node::Call { name, args } => call(name, args)?,
    })
}

/// Functions whose Spark SQL namesake computes the same thing.
const SAME_NAME: &[&str] =
    &["abs", "sqrt", "exp", "floor", "ceil", "log10", "log2", "pow", "lower", "upper", "trim", "length", "coalesce"];

fn call(name: &str, args: &[Expr]) -> Result<String, String> {
    let lower = name.to_ascii_lowercase();
    let printed: Vec<String> = args.iter().map(print).collect::<Result<_, _>>()?;
    Ok(match (lower.as_str(), printed.as_slice()) {
        (f, _) if SAME_NAME.contains(&f) => format!("{f}({})", printed.join(", ")),
        ("log", [x]) => format!("ln({x})"),
        // Spark's two-argument log takes the base first.
        ("log", [x, base]) => format!("log({base}, {x})"),
        ("round", [x]) => format!("round({x})"),
        ("round", [x, digits]) => format!("round({x}, CAST({digits} AS INT))"),
        ("if", [c, a, b]) => format!("(CASE WHEN {c} THEN {a} ELSE {b} END)"),
        ("concat", _) => format!("concat({})", printed.join(", ")),
        ("text", [x]) => format!("CAST({x} AS STRING)"),
        ("number", [x]) => format!("CAST({x} AS DOUBLE)"),
        _ => {
            return Err(format!(
                "`{lower}` is not translated for an engine source; write the step as a `sql` step in Spark SQL"
            ));
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doubles_read_back_exactly_and_are_never_decimals() {
        for v in [0.1, -2.5, 1e-300, 123456789.0, f64::MAX, f64::MIN_POSITIVE, 1.0 / 3.0] {
            let lit = double(v);
            assert!(lit.contains('e'), "{lit}");
            let inner = lit.trim_start_matches('(').trim_end_matches(')');
            assert_eq!(inner.parse::<f64>().unwrap(), v);
        }
        assert_eq!(double(f64::NEG_INFINITY), "CAST('-Infinity' AS DOUBLE)");
    }

    #[test]
    fn expressions_print_as_spark_sql() {
        let got = expression("Horsepower > 100 and Origin != 'Japan''s' or not (x in (1, 2))").unwrap();
        assert_eq!(got, "(((`Horsepower` > (1e2)) AND (`Origin` <> 'Japan\\'s')) OR (NOT (`x` IN ((1e0), (2e0)))))");
        assert_eq!(
            expression("log(x, 2) + if(y is null, 0, y)").unwrap(),
            "(log((2e0), `x`) + (CASE WHEN (`y` IS NULL) THEN (0e0) ELSE `y` END))"
        );
        let err = expression("year(t)").unwrap_err();
        assert!(err.contains("`year`") && err.contains("`sql` step"), "{err}");
    }

    #[test]
    fn relations_and_steps_nest_into_one_query() {
        assert_eq!(relation(Some("db.trips"), None, None).unwrap(), "SELECT * FROM `db`.`trips`");
        assert_eq!(relation(None, Some("/d/p`q.parquet"), None).unwrap(), "SELECT * FROM parquet.`/d/p``q.parquet`");
        assert!(relation(None, Some("/d/a.csv"), None).unwrap_err().contains("`table`"));
        let steps: Vec<TransformStep> = vec![
            TransformStep { filter: Some("x > 0".into()), ..Default::default() },
            TransformStep { sql: Some("SELECT x FROM pts".into()), ..Default::default() },
        ];
        let q = with_steps("SELECT * FROM t".into(), &steps, "pts").unwrap();
        assert_eq!(
            q,
            "WITH source AS (SELECT * FROM (SELECT * FROM t) AS rows WHERE (`x` > (0e0))), `pts` AS (SELECT * FROM source) \
             SELECT * FROM (SELECT x FROM pts) AS rows"
        );
        let bad = vec![TransformStep { sample: Some(3), ..Default::default() }];
        assert_eq!(with_steps("SELECT 1".into(), &bad, "p").unwrap_err().0, 0);
    }
}
