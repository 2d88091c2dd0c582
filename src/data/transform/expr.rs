//! The expression language of `filter`, `calculate`, `aggregate` and `window` steps, parsed
//! into a small tree whose every node keeps its byte range in the expression text.
//!
//! Grammar, loosest first:
//! `or` (also `||`) · `and` (`&&`) · `not` (`!`) · comparisons `== = != <> < <= > >=`,
//! `x in (a, b)`, `x not in [a, b]`, `x is null`, `x is not null` · `+ -` · `* / %` ·
//! unary `-` · literals (`1.5`, `'text'`, `"text"`, `true`, `false`, `null`), columns (`name`,
//! or `` `name with spaces` ``), calls `name(args)` and parentheses.

use std::ops::Range;

/// A parsed expression node and where it is written.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What the node is.
    pub node: Node,
    /// Byte range in the expression text.
    pub span: Range<usize>,
}

/// The kinds of expression nodes.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    /// A number literal.
    Number(f64),
    /// A text literal.
    Text(String),
    /// `true` or `false`.
    Bool(bool),
    /// `null`.
    Null,
    /// A column by name.
    Column(String),
    /// `-x`.
    Negate(Box<Expr>),
    /// `not x`.
    Not(Box<Expr>),
    /// A binary operator.
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    /// `x in (...)` or `x not in (...)`.
    In {
        /// The tested value.
        value: Box<Expr>,
        /// The list of literals.
        list: Vec<Expr>,
        /// `not in`.
        negated: bool,
    },
    /// `x is null` or `x is not null`.
    IsNull {
        /// The tested value.
        value: Box<Expr>,
        /// `is not null`.
        negated: bool,
    },
    /// A function call.
    Call {
        /// The function name as written (matched case-insensitively).
        name: String,
        /// The arguments.
        args: Vec<Expr>,
    },
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    /// `or`.
    Or,
    /// `and`.
    And,
    /// `==`.
    Eq,
    /// `!=`.
    NotEq,
    /// `<`.
    Lt,
    /// `<=`.
    LtEq,
    /// `>`.
    Gt,
    /// `>=`.
    GtEq,
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `%`.
    Rem,
}

impl BinaryOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Or => "or",
            BinaryOp::And => "and",
            BinaryOp::Eq => "==",
            BinaryOp::NotEq => "!=",
            BinaryOp::Lt => "<",
            BinaryOp::LtEq => "<=",
            BinaryOp::Gt => ">",
            BinaryOp::GtEq => ">=",
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Rem => "%",
        }
    }

    /// Whether the operator compares two values.
    pub fn is_comparison(self) -> bool {
        matches!(self, BinaryOp::Eq | BinaryOp::NotEq | BinaryOp::Lt | BinaryOp::LtEq | BinaryOp::Gt | BinaryOp::GtEq)
    }
}

/// A syntax error with its byte range in the expression text.
#[derive(Clone, Debug, PartialEq)]
pub struct SyntaxError {
    /// What is wrong.
    pub message: String,
    /// Where.
    pub span: Range<usize>,
}

/// Longest expression accepted, in bytes, and deepest nesting.
const MAX_LEN: usize = 64 * 1024;
const MAX_DEPTH: usize = 64;

/// Parse an expression.
pub fn parse(text: &str) -> Result<Expr, SyntaxError> {
    if text.len() > MAX_LEN {
        return Err(SyntaxError { message: format!("the expression is longer than {MAX_LEN} bytes"), span: 0..0 });
    }
    let tokens = lex(text)?;
    let mut parser = Parser { tokens, pos: 0, end: text.len(), depth: 0 };
    let expr = parser.or()?;
    match parser.peek() {
        None => Ok(expr),
        Some(t) => Err(SyntaxError { message: format!("unexpected {}", t.tok.describe()), span: t.span.clone() }),
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Number(f64),
    Text(String),
    Ident(String),
    Quoted(String),
    Op(&'static str),
}

impl Tok {
    fn describe(&self) -> String {
        match self {
            Tok::Number(n) => format!("number `{n}`"),
            Tok::Text(_) => "text".into(),
            Tok::Ident(s) | Tok::Quoted(s) => format!("`{s}`"),
            Tok::Op(o) => format!("`{o}`"),
        }
    }
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    span: Range<usize>,
}

const OPERATORS: [&str; 20] =
    ["==", "!=", "<>", "<=", ">=", "&&", "||", "<", ">", "=", "!", "+", "-", "*", "/", "%", "(", ")", ",", "["];

fn lex(text: &str) -> Result<Vec<Token>, SyntaxError> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let start = i;
        if c.is_ascii_digit() || (c == b'.' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit)) {
            while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
                i += 1;
            }
            if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
                let mut j = i + 1;
                if j < bytes.len() && (bytes[j] == b'+' || bytes[j] == b'-') {
                    j += 1;
                }
                if j < bytes.len() && bytes[j].is_ascii_digit() {
                    i = j;
                    while i < bytes.len() && bytes[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let literal = &text[start..i];
            let value = literal
                .parse::<f64>()
                .map_err(|_| SyntaxError { message: format!("`{literal}` is not a number"), span: start..i })?;
            out.push(Token { tok: Tok::Number(value), span: start..i });
        } else if c == b'\'' || c == b'"' || c == b'`' {
            let mut value = String::new();
            i += 1;
            let mut closed = false;
            while i < bytes.len() {
                let Some(ch) = text[i..].chars().next() else { break };
                if ch as u32 == u32::from(c) {
                    // A doubled quote stands for one quote character.
                    if bytes.get(i + 1) == Some(&c) {
                        value.push(ch);
                        i += 2;
                        continue;
                    }
                    i += 1;
                    closed = true;
                    break;
                }
                value.push(ch);
                i += ch.len_utf8();
            }
            if !closed {
                let what = if c == b'`' { "column name" } else { "text" };
                return Err(SyntaxError {
                    message: format!("the {what} starting here is not closed with {}", c as char),
                    span: start..text.len(),
                });
            }
            let tok = if c == b'`' { Tok::Quoted(value) } else { Tok::Text(value) };
            out.push(Token { tok, span: start..i });
        } else if c.is_ascii_alphabetic() || c == b'_' || c >= 0x80 {
            while i < bytes.len() {
                let Some(ch) = text[i..].chars().next() else { break };
                if ch.is_alphanumeric() || ch == '_' || ch == '.' {
                    i += ch.len_utf8();
                } else {
                    break;
                }
            }
            out.push(Token { tok: Tok::Ident(text[start..i].to_owned()), span: start..i });
        } else if c == b']' {
            i += 1;
            out.push(Token { tok: Tok::Op("]"), span: start..i });
        } else {
            let rest = &text[i..];
            let Some(op) = OPERATORS.iter().find(|op| rest.starts_with(**op)) else {
                let ch = rest.chars().next().unwrap_or('?');
                return Err(SyntaxError {
                    message: format!("unexpected character `{ch}`"),
                    span: start..start + ch.len_utf8(),
                });
            };
            i += op.len();
            out.push(Token { tok: Tok::Op(op), span: start..i });
        }
    }
    Ok(out)
}

struct Parser {
    tokens: Vec<Token>,
    pos: usize,
    end: usize,
    depth: usize,
}

impl Parser {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.pos)
    }

    fn peek_keyword(&self, word: &str) -> bool {
        matches!(self.peek(), Some(Token { tok: Tok::Ident(s), .. }) if s.eq_ignore_ascii_case(word))
    }

    fn peek_op(&self, ops: &[&str]) -> Option<&'static str> {
        match self.peek() {
            Some(Token { tok: Tok::Op(o), .. }) if ops.contains(o) => Some(o),
            _ => None,
        }
    }

    fn bump(&mut self) -> Option<Token> {
        let t = self.tokens.get(self.pos).cloned();
        self.pos += 1;
        t
    }

    fn here(&self) -> Range<usize> {
        self.peek().map_or(self.end..self.end, |t| t.span.clone())
    }

    fn expect_op(&mut self, op: &str) -> Result<Range<usize>, SyntaxError> {
        match self.peek() {
            Some(Token { tok: Tok::Op(o), span }) if *o == op => {
                let span = span.clone();
                self.pos += 1;
                Ok(span)
            }
            Some(t) => Err(SyntaxError {
                message: format!("expected `{op}`, found {}", t.tok.describe()),
                span: t.span.clone(),
            }),
            None => Err(SyntaxError { message: format!("expected `{op}` at the end"), span: self.end..self.end }),
        }
    }

    fn binary(
        &mut self,
        op: BinaryOp,
        left: Expr,
        next: fn(&mut Self) -> Result<Expr, SyntaxError>,
    ) -> Result<Expr, SyntaxError> {
        let right = next(self)?;
        let span = left.span.start..right.span.end;
        Ok(Expr { node: Node::Binary(op, Box::new(left), Box::new(right)), span })
    }

    fn or(&mut self) -> Result<Expr, SyntaxError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(SyntaxError {
                message: format!("the expression nests more than {MAX_DEPTH} levels deep"),
                span: self.here(),
            });
        }
        let mut left = self.and()?;
        while self.peek_keyword("or") || self.peek_op(&["||"]).is_some() {
            self.pos += 1;
            left = self.binary(BinaryOp::Or, left, Self::and)?;
        }
        self.depth -= 1;
        Ok(left)
    }

    fn and(&mut self) -> Result<Expr, SyntaxError> {
        let mut left = self.not()?;
        while self.peek_keyword("and") || self.peek_op(&["&&"]).is_some() {
            self.pos += 1;
            left = self.binary(BinaryOp::And, left, Self::not)?;
        }
        Ok(left)
    }

    fn not(&mut self) -> Result<Expr, SyntaxError> {
        if self.peek_keyword("not") || self.peek_op(&["!"]).is_some() {
            let start = self.here().start;
            self.pos += 1;
            let inner = self.not()?;
            let span = start..inner.span.end;
            return Ok(Expr { node: Node::Not(Box::new(inner)), span });
        }
        self.comparison()
    }

    fn comparison(&mut self) -> Result<Expr, SyntaxError> {
        let left = self.additive()?;
        if let Some(op) = self.peek_op(&["==", "=", "!=", "<>", "<", "<=", ">", ">="]) {
            self.pos += 1;
            let op = match op {
                "==" | "=" => BinaryOp::Eq,
                "!=" | "<>" => BinaryOp::NotEq,
                "<" => BinaryOp::Lt,
                "<=" => BinaryOp::LtEq,
                ">" => BinaryOp::Gt,
                _ => BinaryOp::GtEq,
            };
            return self.binary(op, left, Self::additive);
        }
        if self.peek_keyword("is") {
            self.pos += 1;
            let negated = self.peek_keyword("not");
            if negated {
                self.pos += 1;
            }
            if !self.peek_keyword("null") {
                return Err(SyntaxError { message: "expected `null` after `is`".into(), span: self.here() });
            }
            let end = self.here().end;
            self.pos += 1;
            let span = left.span.start..end;
            return Ok(Expr { node: Node::IsNull { value: Box::new(left), negated }, span });
        }
        let negated = self.peek_keyword("not")
            && matches!(self.tokens.get(self.pos + 1), Some(Token { tok: Tok::Ident(s), .. }) if s.eq_ignore_ascii_case("in"));
        if negated {
            self.pos += 1;
        }
        if self.peek_keyword("in") {
            self.pos += 1;
            let close = match self.peek_op(&["(", "["]) {
                Some("(") => ")",
                Some(_) => "]",
                None => {
                    return Err(SyntaxError {
                        message: "expected a list after `in`, e.g. in ('a', 'b')".into(),
                        span: self.here(),
                    });
                }
            };
            self.pos += 1;
            let mut list = Vec::new();
            if self.peek_op(&[close]).is_none() {
                loop {
                    list.push(self.additive()?);
                    if self.peek_op(&[","]).is_some() {
                        self.pos += 1;
                        continue;
                    }
                    break;
                }
            }
            let end = self.expect_op(close)?.end;
            let span = left.span.start..end;
            return Ok(Expr { node: Node::In { value: Box::new(left), list, negated }, span });
        }
        Ok(left)
    }

    fn additive(&mut self) -> Result<Expr, SyntaxError> {
        let mut left = self.multiplicative()?;
        while let Some(op) = self.peek_op(&["+", "-"]) {
            self.pos += 1;
            let op = if op == "+" { BinaryOp::Add } else { BinaryOp::Sub };
            left = self.binary(op, left, Self::multiplicative)?;
        }
        Ok(left)
    }

    fn multiplicative(&mut self) -> Result<Expr, SyntaxError> {
        let mut left = self.unary()?;
        while let Some(op) = self.peek_op(&["*", "/", "%"]) {
            self.pos += 1;
            let op = match op {
                "*" => BinaryOp::Mul,
                "/" => BinaryOp::Div,
                _ => BinaryOp::Rem,
            };
            left = self.binary(op, left, Self::unary)?;
        }
        Ok(left)
    }

    fn unary(&mut self) -> Result<Expr, SyntaxError> {
        if self.peek_op(&["-"]).is_some() {
            let start = self.here().start;
            self.pos += 1;
            let inner = self.unary()?;
            let span = start..inner.span.end;
            if let Node::Number(n) = inner.node {
                return Ok(Expr { node: Node::Number(-n), span });
            }
            return Ok(Expr { node: Node::Negate(Box::new(inner)), span });
        }
        self.primary()
    }

    fn primary(&mut self) -> Result<Expr, SyntaxError> {
        let Some(token) = self.bump() else {
            return Err(SyntaxError { message: "the expression ends too early".into(), span: self.end..self.end });
        };
        let span = token.span.clone();
        let node = match token.tok {
            Tok::Number(n) => Node::Number(n),
            Tok::Text(s) => Node::Text(s),
            Tok::Quoted(s) => Node::Column(s),
            Tok::Op("(") => {
                let mut inner = self.or()?;
                let end = self.expect_op(")")?.end;
                inner.span = span.start..end;
                return Ok(inner);
            }
            Tok::Op(o) => return Err(SyntaxError { message: format!("unexpected `{o}`"), span }),
            Tok::Ident(word) => {
                if self.peek_op(&["("]).is_some() {
                    self.pos += 1;
                    let mut args = Vec::new();
                    if self.peek_op(&[")"]).is_none() {
                        loop {
                            args.push(self.or()?);
                            if self.peek_op(&[","]).is_some() {
                                self.pos += 1;
                                continue;
                            }
                            break;
                        }
                    }
                    let end = self.expect_op(")")?.end;
                    return Ok(Expr { node: Node::Call { name: word, args }, span: span.start..end });
                }
                match word.to_ascii_lowercase().as_str() {
                    "true" => Node::Bool(true),
                    "false" => Node::Bool(false),
                    "null" => Node::Null,
                    "and" | "or" | "not" | "in" | "is" => {
                        return Err(SyntaxError { message: format!("`{word}` needs a value before it"), span });
                    }
                    _ => Node::Column(word),
                }
            }
        };
        Ok(Expr { node, span })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn show(e: &Expr) -> String {
        match &e.node {
            Node::Number(n) => format!("{n}"),
            Node::Text(s) => format!("'{s}'"),
            Node::Bool(b) => format!("{b}"),
            Node::Null => "null".into(),
            Node::Column(c) => format!("${c}"),
            Node::Negate(x) => format!("(- {})", show(x)),
            Node::Not(x) => format!("(not {})", show(x)),
            Node::Binary(op, a, b) => format!("({} {} {})", show(a), op.symbol(), show(b)),
            Node::In { value, list, negated } => {
                let items: Vec<String> = list.iter().map(show).collect();
                format!("({} {}in [{}])", show(value), if *negated { "not " } else { "" }, items.join(", "))
            }
            Node::IsNull { value, negated } => {
                format!("({} is {}null)", show(value), if *negated { "not " } else { "" })
            }
            Node::Call { name, args } => {
                let items: Vec<String> = args.iter().map(show).collect();
                format!("{name}({})", items.join(", "))
            }
        }
    }

    fn p(text: &str) -> String {
        parse(text).map(|e| show(&e)).unwrap_or_else(|e| format!("error {:?}: {}", e.span, e.message))
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(p("a + b * c - d"), "(($a + ($b * $c)) - $d)");
        assert_eq!(p("a > 1 and b < 2 or not c == 3"), "((($a > 1) and ($b < 2)) or (not ($c == 3)))");
        assert_eq!(p("-x * 2"), "((- $x) * 2)");
        assert_eq!(p("-2.5e3 + .5"), "(-2500 + 0.5)");
        assert_eq!(p("(a + b) * c"), "(($a + $b) * $c)");
        assert_eq!(p("a && b || !c"), "(($a and $b) or (not $c))");
        assert_eq!(p("x = 'it''s'"), "($x == 'it's')");
    }

    #[test]
    fn lists_nulls_calls_and_quoted_columns() {
        assert_eq!(p("Origin in ('USA', \"Japan\")"), "($Origin in ['USA', 'Japan'])");
        assert_eq!(p("n not in [1, 2]"), "($n not in [1, 2])");
        assert_eq!(p("`Release Date` is not null"), "($Release Date is not null)");
        assert_eq!(p("x IS NULL"), "($x is null)");
        assert_eq!(p("if(a > 1, 'big', 'small')"), "if(($a > 1), 'big', 'small')");
        assert_eq!(p("count()"), "count()");
        assert_eq!(p("quantile(x, 0.9)"), "quantile($x, 0.9)");
    }

    #[test]
    fn errors_point_at_the_problem() {
        assert_eq!(p("a >"), "error 3..3: the expression ends too early");
        assert_eq!(p("a > 1 b"), "error 6..7: unexpected `b`");
        assert_eq!(p("name == 'x"), "error 8..10: the text starting here is not closed with '");
        assert_eq!(p("a ? b"), "error 2..3: unexpected character `?`");
        assert_eq!(p("f(a, b"), "error 6..6: expected `)` at the end");
        assert_eq!(p("x is 3"), "error 5..6: expected `null` after `is`");
        assert_eq!(p("x in 3"), "error 5..6: expected a list after `in`, e.g. in ('a', 'b')");
        let deep = format!("{}1{}", "(".repeat(100), ")".repeat(100));
        assert!(p(&deep).contains("nests more than 64"), "{}", p(&deep));
    }
}
