//! The spec's TOML text parsed into a small tree that keeps every key's and value's position.

use std::fmt;
use std::ops::Range;

use super::diagnostic::Diagnostic;

/// Deepest nesting of tables and arrays accepted (the TOML parser has its own, similar limit).
pub const MAX_DEPTH: usize = 128;

/// One step of a path into the spec: a table key or an array index (0-based).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum PathSeg {
    /// A key of a table.
    Key(String),
    /// A position in an array (0-based).
    Index(usize),
}

impl From<&str> for PathSeg {
    fn from(key: &str) -> Self {
        PathSeg::Key(key.to_owned())
    }
}

impl From<usize> for PathSeg {
    fn from(index: usize) -> Self {
        PathSeg::Index(index)
    }
}

/// Writes a path the way TOML readers think of it: `chart[2].x.field`.
pub fn display_path(path: &[PathSeg]) -> String {
    let mut out = String::new();
    for seg in path {
        match seg {
            PathSeg::Key(k) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(&display_key(k));
            }
            PathSeg::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// A key as written in TOML: bare when it can be, else quoted and escaped.
pub fn display_key(key: &str) -> String {
    let bare = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        return key.to_owned();
    }
    let mut out = String::with_capacity(key.len() + 2);
    out.push('"');
    for c in key.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => out.push_str(&format!("\\u{:04x}", u32::from(c))),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

impl fmt::Display for PathSeg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PathSeg::Key(k) => f.write_str(&display_key(k)),
            PathSeg::Index(i) => write!(f, "[{i}]"),
        }
    }
}

/// A TOML value with the byte range it occupies in the spec text.
#[derive(Clone, Debug, PartialEq)]
pub struct SpannedValue {
    /// Where the value is written. Tables written as `[header]` span the header; tables implied by
    /// dotted keys span the key.
    pub span: Range<usize>,
    /// The value itself.
    pub kind: ValueKind,
}

/// The kinds of TOML values.
#[derive(Clone, Debug, PartialEq)]
pub enum ValueKind {
    /// A table (`[header]`, `{ inline }` or implied by dotted keys), entries in file order.
    Table(Vec<TableEntry>),
    /// An array, including arrays of tables (`[[header]]`).
    Array(Vec<SpannedValue>),
    /// A string.
    String(String),
    /// An integer.
    Integer(i64),
    /// A float (may be `nan` or `inf`).
    Float(f64),
    /// `true` or `false`.
    Boolean(bool),
    /// An offset/local date-time, date or time, as written.
    Datetime(String),
}

/// One `key = value` of a table.
#[derive(Clone, Debug, PartialEq)]
pub struct TableEntry {
    /// The key, unquoted.
    pub key: String,
    /// Where the key is written.
    pub key_span: Range<usize>,
    /// The value.
    pub value: SpannedValue,
}

impl SpannedValue {
    /// The entries of a table (empty for other kinds).
    pub fn entries(&self) -> &[TableEntry] {
        match &self.kind {
            ValueKind::Table(entries) => entries,
            _ => &[],
        }
    }

    /// The entry for `key` if this is a table that has it.
    pub fn entry(&self, key: &str) -> Option<&TableEntry> {
        self.entries().iter().find(|e| e.key == key)
    }

    /// The value for `key` if this is a table that has it.
    pub fn get(&self, key: &str) -> Option<&SpannedValue> {
        self.entry(key).map(|e| &e.value)
    }

    /// The value for `key`, for changing it, if this is a table that has it.
    pub(crate) fn get_mut(&mut self, key: &str) -> Option<&mut SpannedValue> {
        match &mut self.kind {
            ValueKind::Table(entries) => entries.iter_mut().find(|e| e.key == key).map(|e| &mut e.value),
            _ => None,
        }
    }

    /// The items, for changing them, if this is an array.
    pub(crate) fn as_array_mut(&mut self) -> Option<&mut [SpannedValue]> {
        match &mut self.kind {
            ValueKind::Array(items) => Some(items),
            _ => None,
        }
    }

    /// A string value written at `span`.
    pub(crate) fn string(text: &str, span: &Range<usize>) -> SpannedValue {
        SpannedValue { span: span.clone(), kind: ValueKind::String(text.to_owned()) }
    }

    /// The items if this is an array.
    pub fn as_array(&self) -> Option<&[SpannedValue]> {
        match &self.kind {
            ValueKind::Array(items) => Some(items),
            _ => None,
        }
    }

    /// The string if this is one.
    pub fn as_str(&self) -> Option<&str> {
        match &self.kind {
            ValueKind::String(s) => Some(s),
            _ => None,
        }
    }

    /// The number if this is an integer or a float.
    pub fn as_f64(&self) -> Option<f64> {
        match self.kind {
            ValueKind::Integer(i) => Some(i as f64),
            ValueKind::Float(f) => Some(f),
            _ => None,
        }
    }

    /// Whether this is a table.
    pub fn is_table(&self) -> bool {
        matches!(self.kind, ValueKind::Table(_))
    }

    /// What kind of value this is, with an article: "a string", "an array", ...
    pub fn kind_name(&self) -> &'static str {
        match self.kind {
            ValueKind::Table(_) => "a table",
            ValueKind::Array(_) => "an array",
            ValueKind::String(_) => "a string",
            ValueKind::Integer(_) => "an integer",
            ValueKind::Float(_) => "a float",
            ValueKind::Boolean(_) => "a boolean",
            ValueKind::Datetime(_) => "a date-time",
        }
    }

    /// The value as JSON: date-times become strings, `nan` and `±inf` become `null`.
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::Value;
        match &self.kind {
            ValueKind::Table(entries) => {
                Value::Object(entries.iter().map(|e| (e.key.clone(), e.value.to_json())).collect())
            }
            ValueKind::Array(items) => Value::Array(items.iter().map(SpannedValue::to_json).collect()),
            ValueKind::String(s) => Value::String(s.clone()),
            ValueKind::Integer(i) => Value::from(*i),
            ValueKind::Float(f) => serde_json::Number::from_f64(*f).map_or(Value::Null, Value::Number),
            ValueKind::Boolean(b) => Value::Bool(*b),
            ValueKind::Datetime(d) => Value::String(d.clone()),
        }
    }

    /// The value at `path` below this one.
    pub fn at_path(&self, path: &[PathSeg]) -> Option<&SpannedValue> {
        let mut here = self;
        for seg in path {
            here = match seg {
                PathSeg::Key(k) => here.get(k)?,
                PathSeg::Index(i) => here.as_array()?.get(*i)?,
            };
        }
        Some(here)
    }
}

/// A parsed spec file: its values with their positions, before any checking.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecDoc {
    root: SpannedValue,
}

impl SpecDoc {
    /// Parses TOML text; a syntax error (or absurd nesting) becomes one diagnostic with its place.
    pub fn parse(text: &str) -> Result<Self, Diagnostic> {
        let doc = toml_edit::Document::parse(text).map_err(|e| syntax_error(&e))?;
        let table = doc.as_table();
        let span = 0..0;
        let root = convert_table(table, span, 0)?;
        Ok(Self { root })
    }

    /// The root table.
    pub fn root(&self) -> &SpannedValue {
        &self.root
    }

    /// The root table, for filling in defaults.
    pub(crate) fn root_mut(&mut self) -> &mut SpannedValue {
        &mut self.root
    }

    /// The value at `path`, e.g. `[Key("chart"), Index(2), Key("x")]` for `chart[2].x`.
    pub fn get(&self, path: &[PathSeg]) -> Option<&SpannedValue> {
        self.root.at_path(path)
    }

    /// Byte range of the value at `path` (a table's header, or its key when it has no header).
    pub fn span_of(&self, path: &[PathSeg]) -> Option<Range<usize>> {
        self.get(path).map(|v| v.span.clone())
    }

    /// Byte range of the key of the entry at `path`; `None` when the path ends in an index.
    pub fn key_span_of(&self, path: &[PathSeg]) -> Option<Range<usize>> {
        let (last, parent) = path.split_last()?;
        match last {
            PathSeg::Key(k) => self.get(parent)?.entry(k).map(|e| e.key_span.clone()),
            PathSeg::Index(_) => None,
        }
    }

    /// The whole spec as JSON (see [`SpannedValue::to_json`]).
    pub fn to_json(&self) -> serde_json::Value {
        self.root.to_json()
    }
}

fn syntax_error(e: &toml_edit::TomlError) -> Diagnostic {
    let message = e.message().trim();
    let first = message.lines().next().unwrap_or("");
    let diag = Diagnostic::error(format!("invalid TOML: {first}")).at_opt(e.span());
    if message.starts_with("duplicate key") {
        diag.with_hint("each key may appear only once in a table")
    } else if message.contains("recurs") {
        diag.with_hint(format!("nest tables and arrays at most {MAX_DEPTH} levels deep"))
    } else {
        diag
    }
}

fn too_deep(span: Range<usize>) -> Diagnostic {
    Diagnostic::error(format!("the spec nests tables and arrays more than {MAX_DEPTH} levels deep"))
        .at(span)
        .with_hint("flatten the structure")
}

fn convert_table(table: &toml_edit::Table, fallback: Range<usize>, depth: usize) -> Result<SpannedValue, Diagnostic> {
    let span = table.span().unwrap_or(fallback);
    if depth > MAX_DEPTH {
        return Err(too_deep(span));
    }
    let mut entries = Vec::with_capacity(table.len());
    for (key, item) in table.iter() {
        let key_span = table.key(key).and_then(toml_edit::Key::span).unwrap_or_else(|| span.clone());
        let value = match item {
            toml_edit::Item::None => continue,
            toml_edit::Item::Value(v) => convert_value(v, key_span.clone(), depth + 1)?,
            toml_edit::Item::Table(t) => convert_table(t, key_span.clone(), depth + 1)?,
            toml_edit::Item::ArrayOfTables(a) => {
                let a_span = a.span().unwrap_or_else(|| key_span.clone());
                let mut items = Vec::with_capacity(a.len());
                for t in a.iter() {
                    items.push(convert_table(t, a_span.clone(), depth + 2)?);
                }
                SpannedValue { span: a_span, kind: ValueKind::Array(items) }
            }
        };
        entries.push(TableEntry { key: key.to_owned(), key_span, value });
    }
    Ok(SpannedValue { span, kind: ValueKind::Table(entries) })
}

fn convert_value(value: &toml_edit::Value, fallback: Range<usize>, depth: usize) -> Result<SpannedValue, Diagnostic> {
    use toml_edit::Value as V;
    let span = value.span().unwrap_or(fallback);
    if depth > MAX_DEPTH {
        return Err(too_deep(span));
    }
    let kind = match value {
        V::String(s) => ValueKind::String(s.value().clone()),
        V::Integer(i) => ValueKind::Integer(*i.value()),
        V::Float(f) => ValueKind::Float(*f.value()),
        V::Boolean(b) => ValueKind::Boolean(*b.value()),
        V::Datetime(d) => ValueKind::Datetime(d.value().to_string()),
        V::Array(a) => {
            let mut items = Vec::with_capacity(a.len());
            for v in a.iter() {
                items.push(convert_value(v, span.clone(), depth + 1)?);
            }
            ValueKind::Array(items)
        }
        V::InlineTable(t) => {
            let mut entries = Vec::with_capacity(t.len());
            for (key, v) in t.iter() {
                let key_span = t.key(key).and_then(toml_edit::Key::span).unwrap_or_else(|| span.clone());
                let value = convert_value(v, key_span.clone(), depth + 1)?;
                entries.push(TableEntry { key: key.to_owned(), key_span, value });
            }
            ValueKind::Table(entries)
        }
    };
    Ok(SpannedValue { span, kind })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "title = \"t\"\n[data.iris]\npath = \"iris.csv\"\n[[chart]]\nname = \"a\"\nx = { field = \"f\", domain = [0, 1.5] }\n[[chart]]\nname = \"b\"\nwhen = 1979-05-27T07:32:00Z\nsize = [nan, inf]\n";

    fn slice(range: Option<Range<usize>>) -> &'static str {
        range.and_then(|r| TEXT.get(r)).unwrap_or("<none>")
    }

    fn path(segs: &[PathSeg]) -> Vec<PathSeg> {
        segs.to_vec()
    }

    #[test]
    fn spans_of_values_and_keys() -> Result<(), Diagnostic> {
        let doc = SpecDoc::parse(TEXT)?;
        let x = path(&["chart".into(), 0.into(), "x".into()]);
        assert_eq!(slice(doc.span_of(&x)), "{ field = \"f\", domain = [0, 1.5] }");
        assert_eq!(slice(doc.key_span_of(&x)), "x");
        let field = path(&["chart".into(), 0.into(), "x".into(), "field".into()]);
        assert_eq!(slice(doc.span_of(&field)), "\"f\"");
        assert_eq!(slice(doc.key_span_of(&field)), "field");
        assert_eq!(slice(doc.span_of(&["chart".into(), 1.into()])), "[[chart]]");
        assert_eq!(slice(doc.span_of(&["data".into(), "iris".into()])), "[data.iris]");
        assert_eq!(slice(doc.span_of(&["chart".into(), 1.into(), "when".into()])), "1979-05-27T07:32:00Z");
        assert_eq!(doc.span_of(&["chart".into(), 5.into()]), None);
        assert_eq!(doc.key_span_of(&["chart".into(), 1.into()]), None);
        assert_eq!(display_path(&field), "chart[0].x.field");
        assert_eq!(display_path(&["data".into(), "a b".into()]), "data.\"a b\"");
        Ok(())
    }

    #[test]
    fn json_conversion() -> Result<(), Diagnostic> {
        let doc = SpecDoc::parse(TEXT)?;
        let json = doc.to_json();
        assert_eq!(json["chart"][1]["when"], "1979-05-27T07:32:00Z");
        assert_eq!(json["chart"][1]["size"], serde_json::json!([null, null]));
        assert_eq!(json["chart"][0]["x"]["domain"], serde_json::json!([0, 1.5]));
        assert_eq!(json["data"]["iris"]["path"], "iris.csv");
        Ok(())
    }

    #[test]
    fn syntax_errors_have_spans() {
        let err = SpecDoc::parse("a = 1\nb = \n").err();
        let span = err.as_ref().and_then(|d| d.span.clone());
        assert!(err.as_ref().is_some_and(|d| d.message.starts_with("invalid TOML: ")), "{err:?}");
        assert!(span.is_some_and(|s| s.start >= 6), "{err:?}");
    }
}
