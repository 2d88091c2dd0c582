//! Parsed expressions checked against a schema and turned into polars expressions.
//!
//! Every column is looked up (unknown ones get "did you mean"), every operator and function
//! checks the types of its operands, and errors keep the byte range of the offending part, so
//! problems are found before any data is read.

use std::ops::Range;

use polars::prelude::*;

use super::expr::{BinaryOp, Expr as Ast, Node};
use crate::spec::suggest;

/// The value types the expression language knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ty {
    /// Integers and floats.
    Number,
    /// Text.
    Text,
    /// Booleans.
    Bool,
    /// Dates and date-times.
    Time,
    /// Only nulls (fits anywhere).
    Null,
    /// Lists and other nested values.
    Other,
}

impl Ty {
    /// The type of a polars column.
    pub fn of(dtype: &DataType) -> Ty {
        match dtype {
            d if d.is_primitive_numeric() => Ty::Number,
            DataType::String => Ty::Text,
            DataType::Boolean => Ty::Bool,
            DataType::Date | DataType::Datetime(..) => Ty::Time,
            DataType::Null => Ty::Null,
            _ => Ty::Other,
        }
    }

    /// The type's name with an article.
    pub fn name(self) -> &'static str {
        match self {
            Ty::Number => "a number",
            Ty::Text => "text",
            Ty::Bool => "a boolean",
            Ty::Time => "a date",
            Ty::Null => "null",
            Ty::Other => "a nested value",
        }
    }

    fn fits(self, want: Ty) -> bool {
        self == want || self == Ty::Null
    }
}

/// A type or name error at a byte range of the expression.
#[derive(Clone, Debug, PartialEq)]
pub struct ExprError {
    /// What is wrong.
    pub message: String,
    /// How to fix it (may be empty).
    pub hint: String,
    /// Where in the expression.
    pub span: Range<usize>,
}

impl ExprError {
    fn new(span: &Range<usize>, message: impl Into<String>) -> Self {
        Self { message: message.into(), hint: String::new(), span: span.clone() }
    }

    fn hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = hint.into();
        self
    }
}

/// A checked expression: the polars expression and the type of its values.
pub struct Typed {
    /// The expression.
    pub expr: Expr,
    /// Its type.
    pub ty: Ty,
}

/// Check `ast` against `schema` and build its polars expression.
pub fn lower(ast: &Ast, schema: &Schema) -> Result<Typed, ExprError> {
    Lowerer { schema }.lower(ast)
}

/// The error for a column that is not in the schema, with "did you mean" or the list of columns.
pub fn unknown_column(name: &str, schema: &Schema, span: &Range<usize>) -> ExprError {
    let names: Vec<&str> = schema.iter_names().map(|n| n.as_str()).collect();
    let hint = suggest::hint(name, &names, "columns", true);
    ExprError::new(span, format!("no column `{name}`")).hint(hint)
}

const TIME_UNIT: TimeUnit = TimeUnit::Milliseconds;

/// A value as text; whole numbers without a fraction (`2015`, not `2015.0`).
pub fn to_text(expr: Expr, ty: Ty) -> Expr {
    match ty {
        Ty::Number => {
            let x = expr.cast(DataType::Float64);
            let whole = x.clone().eq(x.clone().floor()).and(x.clone().abs().lt(lit(1e15)));
            when(whole).then(x.clone().cast(DataType::Int64).cast(DataType::String)).otherwise(x.cast(DataType::String))
        }
        Ty::Text => expr,
        _ => expr.cast(DataType::String),
    }
}

/// `expr` as a date-time in milliseconds (dates become midnight UTC).
pub fn as_datetime(expr: Expr) -> Expr {
    expr.cast(DataType::Datetime(TIME_UNIT, None))
}

struct Lowerer<'a> {
    schema: &'a Schema,
}

impl Lowerer<'_> {
    fn lower(&self, ast: &Ast) -> Result<Typed, ExprError> {
        let span = &ast.span;
        Ok(match &ast.node {
            Node::Number(n) => Typed { expr: lit(*n), ty: Ty::Number },
            Node::Text(s) => Typed { expr: lit(s.clone()), ty: Ty::Text },
            Node::Bool(b) => Typed { expr: lit(*b), ty: Ty::Bool },
            Node::Null => Typed { expr: lit(NULL), ty: Ty::Null },
            Node::Column(name) => {
                let dtype = self.schema.get(name.as_str()).ok_or_else(|| unknown_column(name, self.schema, span))?;
                Typed { expr: col(name.as_str()), ty: Ty::of(dtype) }
            }
            Node::Negate(inner) => {
                let x = self.want(inner, Ty::Number, "`-`")?;
                Typed { expr: lit(0.0) - x, ty: Ty::Number }
            }
            Node::Not(inner) => {
                let x = self.want(inner, Ty::Bool, "`not`")?;
                Typed { expr: x.not(), ty: Ty::Bool }
            }
            Node::Binary(op, a, b) => self.binary(*op, a, b)?,
            Node::In { value, list, negated } => {
                let v = self.lower(value)?;
                let series = self.literal_list(list, v.ty)?;
                let test = if v.ty == Ty::Time { as_datetime(v.expr) } else { v.expr };
                let found = test.is_in(lit(series).implode(false), false);
                Typed { expr: if *negated { found.not() } else { found }, ty: Ty::Bool }
            }
            Node::IsNull { value, negated } => {
                let v = self.lower(value)?;
                let missing =
                    if v.ty == Ty::Number { v.expr.clone().is_null().or(v.expr.is_nan()) } else { v.expr.is_null() };
                Typed { expr: if *negated { missing.not() } else { missing }, ty: Ty::Bool }
            }
            Node::Call { name, args } => self.call(name, args, span)?,
        })
    }

    /// Lower `ast` and require its type.
    fn want(&self, ast: &Ast, want: Ty, what: &str) -> Result<Expr, ExprError> {
        let t = self.lower(ast)?;
        if t.ty.fits(want) { Ok(t.expr) } else { Err(mismatch(ast, t.ty, want, what)) }
    }

    fn binary(&self, op: BinaryOp, a: &Ast, b: &Ast) -> Result<Typed, ExprError> {
        let what = format!("`{}`", op.symbol());
        match op {
            BinaryOp::And | BinaryOp::Or => {
                let (x, y) = (self.want(a, Ty::Bool, &what)?, self.want(b, Ty::Bool, &what)?);
                let expr = if op == BinaryOp::And { x.and(y) } else { x.or(y) };
                Ok(Typed { expr, ty: Ty::Bool })
            }
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div | BinaryOp::Rem => {
                let left = self.lower(a)?;
                let right = self.lower(b)?;
                if op == BinaryOp::Sub && left.ty == Ty::Time && right.ty == Ty::Time {
                    // The difference of two dates, in milliseconds.
                    let ms = |e: Expr| as_datetime(e).cast(DataType::Int64).cast(DataType::Float64);
                    return Ok(Typed { expr: ms(left.expr) - ms(right.expr), ty: Ty::Number });
                }
                for (side, t) in [(a, left.ty), (b, right.ty)] {
                    if !t.fits(Ty::Number) {
                        let mut e = mismatch(side, t, Ty::Number, &what);
                        if op == BinaryOp::Add && t == Ty::Text {
                            e = e.hint("join text with concat(a, b)");
                        }
                        return Err(e);
                    }
                }
                // Arithmetic in floats, so 7 / 2 is 3.5 whatever the column types.
                let (x, y) = (left.expr.cast(DataType::Float64), right.expr.cast(DataType::Float64));
                let expr = match op {
                    BinaryOp::Add => x + y,
                    BinaryOp::Sub => x - y,
                    BinaryOp::Mul => x * y,
                    BinaryOp::Div => x / y,
                    _ => x % y,
                };
                Ok(Typed { expr, ty: Ty::Number })
            }
            _ => {
                let (x, y) = self.comparable(a, b, &what)?;
                let expr = match op {
                    BinaryOp::Eq => x.eq(y),
                    BinaryOp::NotEq => x.neq(y),
                    BinaryOp::Lt => x.lt(y),
                    BinaryOp::LtEq => x.lt_eq(y),
                    BinaryOp::Gt => x.gt(y),
                    _ => x.gt_eq(y),
                };
                Ok(Typed { expr, ty: Ty::Bool })
            }
        }
    }

    /// Both sides of a comparison, of one type; a date compared with text reads the text as an
    /// ISO date.
    fn comparable(&self, a: &Ast, b: &Ast, what: &str) -> Result<(Expr, Expr), ExprError> {
        let left = self.lower(a)?;
        let right = self.lower(b)?;
        let date = |side: &Ast, t: Typed| -> Result<Expr, ExprError> {
            match (&side.node, t.ty) {
                (Node::Text(s), _) => date_literal(s, &side.span),
                (_, Ty::Time | Ty::Null) => Ok(as_datetime(t.expr)),
                (_, other) => Err(mismatch(side, other, Ty::Time, what)),
            }
        };
        match (left.ty, right.ty) {
            (Ty::Time, _) | (_, Ty::Time) => Ok((date(a, left)?, date(b, right)?)),
            (l, r) if l == r || l == Ty::Null || r == Ty::Null => {
                if l == Ty::Other {
                    return Err(mismatch(a, l, Ty::Number, what));
                }
                Ok((left.expr, right.expr))
            }
            (l, r) => Err(ExprError::new(
                &(a.span.start..b.span.end),
                format!("{what} compares {} with {}", l.name(), r.name()),
            )
            .hint(match (l, r) {
                (Ty::Number, Ty::Text) | (Ty::Text, Ty::Number) => {
                    "numbers are written without quotes; to compare text, cast the column with { cast = { NAME = \"text\" } }"
                }
                _ => "compare values of one type",
            })),
        }
    }

    /// The literals of an `in` list as one series of the tested value's type.
    fn literal_list(&self, list: &[Ast], ty: Ty) -> Result<Series, ExprError> {
        let name = PlSmallStr::EMPTY;
        match ty {
            Ty::Number | Ty::Null => {
                let mut out = Vec::with_capacity(list.len());
                for item in list {
                    match &item.node {
                        Node::Number(n) => out.push(Some(*n)),
                        Node::Null => out.push(None),
                        _ => return Err(ExprError::new(&item.span, "the list of a number test holds numbers only")),
                    }
                }
                Ok(Series::new(name, out)
                    .cast(&DataType::Float64)
                    .unwrap_or_else(|_| Series::new_empty(PlSmallStr::EMPTY, &DataType::Float64)))
            }
            Ty::Text | Ty::Bool => {
                let mut out: Vec<Option<String>> = Vec::with_capacity(list.len());
                let mut bools = Vec::with_capacity(list.len());
                for item in list {
                    match (&item.node, ty) {
                        (Node::Text(s), Ty::Text) => out.push(Some(s.clone())),
                        (Node::Bool(b), Ty::Bool) => bools.push(Some(*b)),
                        (Node::Null, _) => {
                            out.push(None);
                            bools.push(None);
                        }
                        _ => {
                            return Err(ExprError::new(
                                &item.span,
                                format!("the list of this test holds {} only", ty.name()),
                            ));
                        }
                    }
                }
                Ok(if ty == Ty::Bool { Series::new(name, bools) } else { Series::new(name, out) })
            }
            Ty::Time => {
                let mut out = Vec::with_capacity(list.len());
                for item in list {
                    match &item.node {
                        Node::Text(s) => out.push(parse_date_ms(s, &item.span)?),
                        _ => {
                            return Err(ExprError::new(
                                &item.span,
                                "the list of a date test holds dates written as text, e.g. '2015-06-01'",
                            ));
                        }
                    }
                }
                Series::new(name, out)
                    .cast(&DataType::Datetime(TIME_UNIT, None))
                    .map_err(|e| ExprError::new(&list.first().map_or(0..0, |a| a.span.clone()), e.to_string()))
            }
            Ty::Other => Err(ExprError::new(
                &list.first().map_or(0..0, |a| a.span.clone()),
                "`in` tests numbers, text, booleans or dates",
            )),
        }
    }

    fn call(&self, name: &str, args: &[Ast], span: &Range<usize>) -> Result<Typed, ExprError> {
        let lower = name.to_ascii_lowercase();
        let Some(f) = FUNCTIONS.iter().find(|f| f.name == lower) else {
            let names: Vec<&str> = FUNCTIONS.iter().map(|f| f.name).collect();
            let mut e = ExprError::new(span, format!("no function `{name}`"));
            e.hint = if super::aggregate::is_aggregate(&lower) || super::window::is_window(&lower) {
                format!("`{lower}` summarises many rows: use it in an `aggregate` or `window` step")
            } else {
                suggest::hint(&lower, &names, "functions", false)
            };
            return Err(e);
        };
        let (lo, hi) = f.arity;
        if args.len() < lo || args.len() > hi {
            let want = if lo == hi { format!("{lo}") } else { format!("{lo} to {hi}") };
            return Err(ExprError::new(
                span,
                format!("`{}` takes {want} argument{}, found {}", f.name, if hi == 1 { "" } else { "s" }, args.len()),
            )
            .hint(format!("write {}", f.usage)));
        }
        (f.build)(self, args, span)
    }
}

/// The error for an operand of the wrong type.
fn mismatch(ast: &Ast, found: Ty, want: Ty, what: &str) -> ExprError {
    let shown = match &ast.node {
        Node::Column(c) => format!("column `{c}` is {}", found.name()),
        _ => format!("this is {}", found.name()),
    };
    let mut e = ExprError::new(&ast.span, format!("{what} needs {}, but {shown}", want.name()));
    if let (Node::Column(c), Ty::Text, Ty::Number | Ty::Time) = (&ast.node, found, want) {
        let to = if want == Ty::Number { "number" } else { "date" };
        e = e.hint(format!("cast it first: {{ cast = {{ {} = \"{to}\" }} }}", crate::spec::source::display_key(c)));
    }
    e
}

fn parse_date_ms(text: &str, span: &Range<usize>) -> Result<i64, ExprError> {
    crate::data::time::parse_iso(text).map(|ms| ms as i64).ok_or_else(|| {
        ExprError::new(span, format!("'{text}' is not an ISO date"))
            .hint("write dates as '2015-06-01' or '2015-06-01T12:00:00'")
    })
}

fn date_literal(text: &str, span: &Range<usize>) -> Result<Expr, ExprError> {
    Ok(lit(parse_date_ms(text, span)?).cast(DataType::Datetime(TIME_UNIT, None)))
}

/// One function of the expression language.
struct Function {
    name: &'static str,
    arity: (usize, usize),
    usage: &'static str,
    build: fn(&Lowerer<'_>, &[Ast], &Range<usize>) -> Result<Typed, ExprError>,
}

fn arg<'a>(args: &'a [Ast], i: usize) -> &'a Ast {
    &args[i.min(args.len().saturating_sub(1))]
}

fn number(l: &Lowerer<'_>, args: &[Ast], i: usize, what: &str) -> Result<Expr, ExprError> {
    Ok(l.want(arg(args, i), Ty::Number, what)?.cast(DataType::Float64))
}

fn text(l: &Lowerer<'_>, args: &[Ast], i: usize, what: &str) -> Result<Expr, ExprError> {
    l.want(arg(args, i), Ty::Text, what)
}

fn time(l: &Lowerer<'_>, args: &[Ast], what: &str) -> Result<Expr, ExprError> {
    Ok(as_datetime(l.want(arg(args, 0), Ty::Time, what)?))
}

/// A whole non-negative number literal (digits of `round`).
fn count_literal(args: &[Ast], i: usize, what: &str) -> Result<u32, ExprError> {
    let a = arg(args, i);
    match a.node {
        Node::Number(n) if n >= 0.0 && n.fract() == 0.0 && n <= 15.0 => Ok(n as u32),
        _ => Err(ExprError::new(&a.span, format!("{what} takes a whole number from 0 to 15 here"))),
    }
}

macro_rules! num1 {
    ($name:literal, $method:ident) => {
        Function {
            name: $name,
            arity: (1, 1),
            usage: concat!($name, "(x)"),
            build: |l, a, _| Ok(Typed { expr: number(l, a, 0, concat!("`", $name, "`"))?.$method(), ty: Ty::Number }),
        }
    };
}

macro_rules! date_part {
    ($name:literal, $method:ident) => {
        Function {
            name: $name,
            arity: (1, 1),
            usage: concat!($name, "(date)"),
            build: |l, a, _| {
                Ok(Typed {
                    expr: time(l, a, concat!("`", $name, "`"))?.dt().$method().cast(DataType::Float64),
                    ty: Ty::Number,
                })
            },
        }
    };
}

macro_rules! text_test {
    ($name:literal, $method:ident) => {
        Function {
            name: $name,
            arity: (2, 2),
            usage: concat!($name, "(text, 'part')"),
            build: |l, a, _| {
                let what = concat!("`", $name, "`");
                Ok(Typed { expr: text(l, a, 0, what)?.str().$method(text(l, a, 1, what)?), ty: Ty::Bool })
            },
        }
    };
}

const FUNCTIONS: &[Function] = &[
    num1!("abs", abs),
    num1!("sqrt", sqrt),
    num1!("exp", exp),
    num1!("floor", floor),
    num1!("ceil", ceil),
    num1!("sign", sign),
    num1!("sin", sin),
    num1!("cos", cos),
    num1!("tan", tan),
    Function {
        name: "log",
        arity: (1, 2),
        usage: "log(x) (natural) or log(x, base)",
        build: |l, a, _| {
            let base = if a.len() > 1 { number(l, a, 1, "`log`")? } else { lit(std::f64::consts::E) };
            Ok(Typed { expr: number(l, a, 0, "`log`")?.log(base), ty: Ty::Number })
        },
    },
    Function {
        name: "log10",
        arity: (1, 1),
        usage: "log10(x)",
        build: |l, a, _| Ok(Typed { expr: number(l, a, 0, "`log10`")?.log(lit(10.0)), ty: Ty::Number }),
    },
    Function {
        name: "log2",
        arity: (1, 1),
        usage: "log2(x)",
        build: |l, a, _| Ok(Typed { expr: number(l, a, 0, "`log2`")?.log(lit(2.0)), ty: Ty::Number }),
    },
    Function {
        name: "pow",
        arity: (2, 2),
        usage: "pow(x, y)",
        build: |l, a, _| Ok(Typed { expr: number(l, a, 0, "`pow`")?.pow(number(l, a, 1, "`pow`")?), ty: Ty::Number }),
    },
    Function {
        name: "round",
        arity: (1, 2),
        usage: "round(x) or round(x, digits)",
        build: |l, a, _| {
            let digits = if a.len() > 1 { count_literal(a, 1, "`round`")? } else { 0 };
            Ok(Typed { expr: number(l, a, 0, "`round`")?.round(digits, RoundMode::HalfAwayFromZero), ty: Ty::Number })
        },
    },
    Function {
        name: "if",
        arity: (3, 3),
        usage: "if(condition, then, otherwise)",
        build: |l, a, span| {
            let cond = l.want(&a[0], Ty::Bool, "the condition of `if`")?;
            let then = l.lower(&a[1])?;
            let other = l.lower(&a[2])?;
            let ty = if then.ty == Ty::Null { other.ty } else { then.ty };
            if !other.ty.fits(ty) {
                return Err(ExprError::new(
                    span,
                    format!("`if` gives {} or {}: both branches need one type", then.ty.name(), other.ty.name()),
                ));
            }
            Ok(Typed { expr: when(cond).then(then.expr).otherwise(other.expr), ty })
        },
    },
    Function {
        name: "coalesce",
        arity: (2, 16),
        usage: "coalesce(a, b, ...)",
        build: |l, a, span| {
            let mut out: Option<(Expr, Ty)> = None;
            for item in a.iter().rev() {
                let t = l.lower(item)?;
                out = Some(match out {
                    None => (t.expr, t.ty),
                    Some((rest, ty)) => {
                        if !t.ty.fits(ty) && ty != Ty::Null {
                            return Err(ExprError::new(span, "`coalesce` needs values of one type"));
                        }
                        let ty = if ty == Ty::Null { t.ty } else { ty };
                        (when(t.expr.clone().is_not_null()).then(t.expr).otherwise(rest), ty)
                    }
                });
            }
            let (expr, ty) = out.unwrap_or((lit(NULL), Ty::Null));
            Ok(Typed { expr, ty })
        },
    },
    text_test!("contains", contains_literal),
    text_test!("starts_with", starts_with),
    text_test!("ends_with", ends_with),
    Function {
        name: "lower",
        arity: (1, 1),
        usage: "lower(text)",
        build: |l, a, _| Ok(Typed { expr: text(l, a, 0, "`lower`")?.str().to_lowercase(), ty: Ty::Text }),
    },
    Function {
        name: "upper",
        arity: (1, 1),
        usage: "upper(text)",
        build: |l, a, _| Ok(Typed { expr: text(l, a, 0, "`upper`")?.str().to_uppercase(), ty: Ty::Text }),
    },
    Function {
        name: "trim",
        arity: (1, 1),
        usage: "trim(text)",
        build: |l, a, _| Ok(Typed { expr: text(l, a, 0, "`trim`")?.str().strip_chars(lit(NULL)), ty: Ty::Text }),
    },
    Function {
        name: "length",
        arity: (1, 1),
        usage: "length(text)",
        build: |l, a, _| {
            Ok(Typed { expr: text(l, a, 0, "`length`")?.str().len_chars().cast(DataType::Float64), ty: Ty::Number })
        },
    },
    Function {
        name: "concat",
        arity: (1, 32),
        usage: "concat(a, b, ...)",
        build: |l, a, _| {
            let mut parts = Vec::with_capacity(a.len());
            for item in a {
                let t = l.lower(item)?;
                parts.push(to_text(t.expr, t.ty));
            }
            Ok(Typed { expr: concat_str(parts, "", false), ty: Ty::Text })
        },
    },
    Function {
        name: "text",
        arity: (1, 1),
        usage: "text(x)",
        build: |l, a, _| {
            let t = l.lower(&a[0])?;
            Ok(Typed { expr: to_text(t.expr, t.ty), ty: Ty::Text })
        },
    },
    Function {
        name: "number",
        arity: (1, 1),
        usage: "number(x) (text that is not a number becomes null)",
        build: |l, a, _| Ok(Typed { expr: l.lower(&a[0])?.expr.cast(DataType::Float64), ty: Ty::Number }),
    },
    date_part!("year", year),
    date_part!("quarter", quarter),
    date_part!("month", month),
    date_part!("day", day),
    date_part!("weekday", weekday),
    date_part!("dayofyear", ordinal_day),
    date_part!("hour", hour),
    date_part!("minute", minute),
    date_part!("second", second),
];

/// Names of the row functions, for error hints elsewhere.
pub fn function_names() -> Vec<&'static str> {
    FUNCTIONS.iter().map(|f| f.name).collect()
}

#[cfg(test)]
mod tests {
    use super::super::expr::parse;
    use super::*;

    fn schema() -> Schema {
        Schema::from_iter([
            Field::new("Horsepower".into(), DataType::Int64),
            Field::new("Origin".into(), DataType::String),
            Field::new("when".into(), DataType::Date),
            Field::new("ok".into(), DataType::Boolean),
        ])
    }

    fn err(text: &str) -> (String, String, Range<usize>) {
        let ast = parse(text).expect("parses");
        match lower(&ast, &schema()) {
            Ok(_) => panic!("`{text}` should not type-check"),
            Err(e) => (e.message, e.hint, e.span),
        }
    }

    fn ty(text: &str) -> Ty {
        let ast = parse(text).expect("parses");
        lower(&ast, &schema()).map(|t| t.ty).unwrap_or_else(|e| panic!("{text}: {}", e.message))
    }

    #[test]
    fn types_of_well_formed_expressions() {
        assert_eq!(ty("Horsepower > 100 and Origin != 'Japan'"), Ty::Bool);
        assert_eq!(ty("Horsepower / 2.2 + 1"), Ty::Number);
        assert_eq!(ty("when >= '2015-06-01'"), Ty::Bool);
        assert_eq!(ty("year(when) * 1"), Ty::Number);
        assert_eq!(ty("if(ok, 'yes', 'no')"), Ty::Text);
        assert_eq!(ty("Origin in ('USA', 'Japan') or Origin is null"), Ty::Bool);
        assert_eq!(ty("concat(Origin, '-', Horsepower)"), Ty::Text);
        assert_eq!(ty("contains(lower(Origin), 'us')"), Ty::Bool);
        assert_eq!(ty("text(year(when))"), Ty::Text);
    }

    #[test]
    fn unknown_columns_get_did_you_mean_at_their_place() {
        let (message, hint, span) = err("Horsepowr > 100");
        assert_eq!(message, "no column `Horsepowr`");
        assert!(hint.contains("did you mean `Horsepower`?"), "{hint}");
        assert_eq!(span, 0..9);
    }

    #[test]
    fn type_errors_name_both_sides() {
        let (message, hint, span) = err("Origin > 3");
        assert_eq!(message, "`>` compares text with a number");
        assert!(hint.contains("cast"), "{hint}");
        assert_eq!(span, 0..10);
        let (message, hint, _) = err("year(Origin)");
        assert_eq!(message, "`year` needs a date, but column `Origin` is text");
        assert_eq!(hint, "cast it first: { cast = { Origin = \"date\" } }");
        let (message, _, span) = err("Horsepower and ok");
        assert_eq!(message, "`and` needs a boolean, but column `Horsepower` is a number");
        assert_eq!(span, 0..10);
        let (message, _, _) = err("when > 'June'");
        assert_eq!(message, "'June' is not an ISO date");
        let (message, hint, _) = err("mean(Horsepower)");
        assert_eq!(message, "no function `mean`");
        assert!(hint.contains("aggregate"), "{hint}");
        let (message, _, _) = err("round(Horsepower, 1, 2)");
        assert_eq!(message, "`round` takes 1 to 2 arguments, found 3");
        let (message, _, _) = err("Origin in (1, 2)");
        assert_eq!(message, "the list of this test holds text only");
    }
}
