//! Checks a parsed spec against its JSON Schema and the rules a schema cannot say, collecting every
//! problem as a [`Diagnostic`] that points at the offending key or value.
//!
//! The schema is walked generically (`$ref`, `type`, `properties`, `required`,
//! `additionalProperties`, `items`, `minItems`/`maxItems`, `minLength`/`maxLength`, `minimum`,
//! `maximum`, `exclusiveMinimum`, `exclusiveMaximum`, `const`/`enum`, `anyOf`/`oneOf`), so new spec
//! fields are checked as soon as they are added to the types. `oneOf` branches that all fix one
//! property to a constant (the chart's `kind`) are picked by that property; other alternatives are
//! picked by the value's type. `pattern` is not evaluated (chart names are checked by hand).

use std::collections::HashMap;
use std::ops::Range;

use serde_json::Value;

use super::annotation::Annotation;
use super::diagnostic::Diagnostic;
use super::schema::schema_ref;
use super::source::{PathSeg, SpannedValue, SpecDoc, TableEntry, ValueKind, display_key, display_path};
use super::suggest::did_you_mean;
use crate::mark::registry::KindInfo;

/// Deepest schema nesting followed; the spec's own schema is far shallower.
const MAX_SCHEMA_DEPTH: usize = 64;

/// Most charts one spec may hold; a larger spec is refused before any chart is checked.
pub const MAX_CHARTS: usize = 10_000;

/// Every problem in the spec: schema violations (types, unknown and missing keys, enum values,
/// number ranges) in file order, then the rules that need the whole spec (chart names and their
/// uniqueness, references from charts to data sources, `path` xor `values`, domain order).
pub fn validate(doc: &SpecDoc) -> Vec<Diagnostic> {
    walk(doc, Conventional::Required).0
}

/// [`validate`], except that chart keys with a conventional default column
/// ([`super::defaults`]) may be missing; the flag says whether any was.
pub(crate) fn validate_deferring(doc: &SpecDoc) -> (Vec<Diagnostic>, bool) {
    walk(doc, Conventional::Deferred)
}

/// [`validate`], with a note for the hint of each chart key still missing after the defaults
/// were filled, by chart index and key. Charts in `pending` (whose data did not load) may still
/// miss them; the flag says whether any did.
pub(crate) fn validate_noted(doc: &SpecDoc, filled: &super::defaults::Filled) -> (Vec<Diagnostic>, bool) {
    walk(doc, Conventional::Noted(filled.clone()))
}

fn walk(doc: &SpecDoc, conventional: Conventional) -> (Vec<Diagnostic>, bool) {
    if let Some(too_many) = too_many_charts(doc.root()) {
        return (vec![too_many], false);
    }
    let schema = schema_ref();
    let mut walker = Walker::new(schema, doc.root(), conventional);
    let mut path = Vec::new();
    walker.check(doc.root(), schema, &mut path, Field::default(), 0);
    walker.semantic(doc.root());
    (walker.diags, walker.deferred)
}

/// How chart keys with a conventional default column are checked.
enum Conventional {
    /// Like every other key.
    Required,
    /// Allowed to be missing (the data, not yet loaded, may have the column).
    Deferred,
    /// Required, with the fill's notes in the hint when missing, except in its `pending` charts,
    /// whose data did not load.
    Noted(super::defaults::Filled),
}

/// The error of a spec with more than [`MAX_CHARTS`] charts, pointing at the first one over.
fn too_many_charts(root: &SpannedValue) -> Option<Diagnostic> {
    let charts = root.get("chart").and_then(SpannedValue::as_array)?;
    let over = charts.get(MAX_CHARTS)?;
    let d = Diagnostic::error(format!("the spec has {} charts, over the limit of {MAX_CHARTS} per spec", charts.len()))
        .at(over.span.clone())
        .with_label(format!("chart #{} is one too many", MAX_CHARTS + 1))
        .with_hint("split the charts over several spec files and render each one");
    Some(d)
}

/// The schema property a value sits under: its name (for examples) and schema (for hints).
#[derive(Clone, Copy, Default)]
struct Field<'s> {
    key: Option<&'s str>,
    schema: Option<&'s Value>,
}

/// A required key a table lacks: its schema (for an example) and a note on its values.
struct Missing<'s> {
    key: &'s str,
    prop: Option<&'s Value>,
    note: Option<String>,
}

/// Chart names met so far: exactly, and folded to lower case.
#[derive(Default)]
struct SeenNames<'v> {
    exact: HashMap<&'v str, usize>,
    folded: HashMap<String, (usize, &'v str)>,
}

/// Where in the spec a path lies, for naming it in messages.
enum Ctx {
    Top,
    Data(String),
    Chart(usize),
}

struct Walker<'s> {
    root_schema: &'s Value,
    chart_names: Vec<Option<String>>,
    diags: Vec<Diagnostic>,
    conventional: Conventional,
    /// Whether a conventional key was let through missing.
    deferred: bool,
}

impl<'s> Walker<'s> {
    fn new(root_schema: &'s Value, root: &SpannedValue, conventional: Conventional) -> Self {
        let chart_names = root
            .get("chart")
            .and_then(SpannedValue::as_array)
            .unwrap_or(&[])
            .iter()
            .map(|c| c.get("name").and_then(SpannedValue::as_str).filter(|n| !n.is_empty()).map(str::to_owned))
            .collect();
        Self { root_schema, chart_names, diags: Vec::new(), conventional, deferred: false }
    }

    // ----- schema helpers -------------------------------------------------------------------

    fn deref_once(&self, s: &'s Value) -> Option<&'s Value> {
        let name = s.get("$ref")?.as_str()?.strip_prefix("#/$defs/")?;
        self.root_schema.get("$defs")?.get(name)
    }

    fn resolve(&self, mut s: &'s Value) -> &'s Value {
        for _ in 0..MAX_SCHEMA_DEPTH {
            match self.deref_once(s) {
                Some(t) => s = t,
                None => break,
            }
        }
        s
    }

    /// A keyword from the schema itself or, failing that, from what its `$ref` points at.
    fn keyword(&self, mut s: &'s Value, key: &str) -> Option<&'s Value> {
        for _ in 0..MAX_SCHEMA_DEPTH {
            if let Some(v) = s.get(key) {
                return Some(v);
            }
            s = self.deref_once(s)?;
        }
        None
    }

    /// The allowed strings if the schema is a `const`, an `enum` or alternatives of those.
    fn enum_values(&self, s: &'s Value) -> Option<Vec<&'s str>> {
        let s = self.resolve(s);
        if let Some(c) = s.get("const") {
            return Some(vec![c.as_str()?]);
        }
        if let Some(list) = s.get("enum").and_then(Value::as_array) {
            return list.iter().map(Value::as_str).collect();
        }
        let branches = alternatives(s)?;
        let mut out = Vec::new();
        for b in branches {
            let b = self.resolve(b);
            if b.get("const").is_none() && b.get("enum").is_none() {
                return None;
            }
            out.extend(self.enum_values(b)?);
        }
        Some(out)
    }

    /// The property every branch fixes to a different constant (`kind`), if there is one.
    fn tag_of(&self, branches: &'s [Value]) -> Option<&'s str> {
        let first = self.resolve(branches.first()?);
        first.get("properties")?.as_object()?.iter().find_map(|(key, _)| {
            let all = branches.iter().all(|b| self.tag_value(self.resolve(b), key).is_some());
            all.then_some(key.as_str())
        })
    }

    fn tag_value(&self, branch: &'s Value, tag: &str) -> Option<&'s str> {
        branch.get("properties")?.get(tag)?.get("const")?.as_str()
    }

    /// Whether a value's type fits a schema (ignoring everything but types), for picking
    /// among untagged alternatives.
    fn accepts(&self, s: &'s Value, v: &SpannedValue, depth: usize) -> bool {
        if depth > MAX_SCHEMA_DEPTH {
            return false;
        }
        let s = self.resolve(s);
        if self.enum_values(s).is_some() {
            return matches!(v.kind, ValueKind::String(_));
        }
        if let Some(branches) = alternatives(s) {
            return branches.iter().any(|b| self.accepts(b, v, depth + 1));
        }
        s.get("type").is_none_or(|t| type_matches(t, v))
    }

    /// What a schema accepts, in words: "an array of 2 numbers", "a string or a table", ...
    fn describe(&self, s: &'s Value, plural: bool, depth: usize) -> String {
        let mut parts = Vec::new();
        self.describe_parts(s, plural, depth, &mut parts);
        parts.dedup();
        join_or(&parts)
    }

    fn describe_parts(&self, s: &'s Value, plural: bool, depth: usize, out: &mut Vec<String>) {
        let s = self.resolve(s);
        if depth > MAX_SCHEMA_DEPTH {
            out.push(pick(plural, "a value", "values"));
            return;
        }
        if let Some(values) = self.enum_values(s) {
            if plural {
                out.push("strings".to_owned());
            } else {
                let quoted: Vec<String> = values.iter().map(|v| format!("`{v}`")).collect();
                out.push(if quoted.len() == 1 { quoted.concat() } else { format!("one of {}", join_or(&quoted)) });
            }
            return;
        }
        if let Some(branches) = alternatives(s) {
            if self.tag_of(branches).is_some() {
                out.push(pick(plural, "a table", "tables"));
            } else {
                for b in branches {
                    self.describe_parts(b, plural, depth + 1, out);
                }
            }
            return;
        }
        let types: Vec<&str> = match s.get("type") {
            Some(Value::String(t)) => vec![t.as_str()],
            Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).collect(),
            _ => Vec::new(),
        };
        if types.is_empty() {
            out.push(pick(plural, "a value", "values"));
        }
        for t in types {
            out.push(match t {
                "string" => pick(plural, "a string", "strings"),
                "integer" => pick(plural, "an integer", "integers"),
                "number" => pick(plural, "a number", "numbers"),
                "boolean" => pick(plural, "`true` or `false`", "booleans"),
                "object" => pick(plural, "a table", "tables"),
                "array" => {
                    let items =
                        s.get("items").map_or_else(|| "values".to_owned(), |i| self.describe(i, true, depth + 1));
                    let min = s.get("minItems").and_then(Value::as_u64);
                    let max = s.get("maxItems").and_then(Value::as_u64);
                    let (a, arrays) = match (min, max) {
                        (Some(n), Some(m)) if n == m => {
                            (format!("an array of {n} {items}"), format!("arrays of {n} {items}"))
                        }
                        _ => (format!("an array of {items}"), format!("arrays of {items}")),
                    };
                    if plural { arrays } else { a }
                }
                _ => pick(plural, "a value", "values"),
            });
        }
    }

    /// An example value for a schema, written as TOML.
    fn example(&self, s: &'s Value) -> Option<String> {
        if let Some(first) = self.keyword(s, "examples").and_then(Value::as_array).and_then(|e| e.first()) {
            return Some(toml_inline(first));
        }
        self.enum_values(s)?.first().map(|v| toml_inline(&Value::from(*v)))
    }

    fn description(&self, s: &'s Value) -> Option<String> {
        let d = self.keyword(s, "description")?.as_str()?;
        let d = d.split_whitespace().collect::<Vec<_>>().join(" ");
        let d = match d.strip_suffix('.') {
            Some(rest) if !rest.ends_with('.') => rest,
            _ => d.as_str(),
        };
        Some(lowercase_first(d))
    }

    /// "description; for example `key = value`".
    fn field_hint(&self, field: Field<'s>) -> Option<String> {
        let schema = field.schema?;
        let mut parts = Vec::new();
        if let Some(d) = self.description(schema) {
            parts.push(d);
        }
        if let (Some(key), Some(ex)) = (field.key, self.example(schema)) {
            parts.push(format!("for example `{} = {ex}`", display_key(key)));
        }
        (!parts.is_empty()).then(|| parts.join("; "))
    }

    /// Keys of an object schema: required ones in order, then the rest alphabetically.
    fn ordered_keys(&self, s: &'s Value) -> Vec<&'s str> {
        let mut keys: Vec<&str> =
            s.get("required").and_then(Value::as_array).into_iter().flatten().filter_map(Value::as_str).collect();
        let mut rest: Vec<&str> = s
            .get("properties")
            .and_then(Value::as_object)
            .into_iter()
            .flatten()
            .map(|(k, _)| k.as_str())
            .filter(|k| !keys.contains(k))
            .collect();
        rest.sort_unstable();
        keys.extend(rest);
        keys
    }

    // ----- naming places --------------------------------------------------------------------

    fn ctx(&self, path: &[PathSeg]) -> (Ctx, usize) {
        match path {
            [PathSeg::Key(c), PathSeg::Index(i), ..] if c == "chart" => (Ctx::Chart(*i), 2),
            [PathSeg::Key(d), PathSeg::Key(name), ..] if d == "data" => (Ctx::Data(name.clone()), 2),
            _ => (Ctx::Top, 0),
        }
    }

    fn chart_label(&self, i: usize) -> String {
        match self.chart_names.get(i).and_then(Option::as_deref) {
            Some(name) => format!("chart \"{}\"", shorten(name)),
            None => format!("chart #{}", i + 1),
        }
    }

    fn ctx_name(&self, ctx: &Ctx) -> String {
        match ctx {
            Ctx::Top => "the spec".to_owned(),
            Ctx::Data(name) => format!("`data.{}`", shorten(&display_key(name))),
            Ctx::Chart(i) => self.chart_label(*i),
        }
    }

    /// The local part of a path, e.g. `x.domain` inside a chart.
    fn local(&self, path: &[PathSeg]) -> (Ctx, String) {
        let (ctx, depth) = self.ctx(path);
        let local = path.get(depth..).map(display_path).unwrap_or_default();
        (ctx, shorten(&local))
    }

    /// What a value is called as the subject of a sentence: "`size`", "chart #3", "`data.iris`".
    fn subject(&self, path: &[PathSeg]) -> String {
        let (ctx, local) = self.local(path);
        if local.is_empty() { self.ctx_name(&ctx) } else { format!("`{local}`") }
    }

    /// A table named as owner: "chart \"a\"", "`x` of chart \"a\"", "`data.iris`".
    fn owner(&self, path: &[PathSeg]) -> String {
        let (ctx, local) = self.local(path);
        match (local.is_empty(), &ctx) {
            (true, _) => self.ctx_name(&ctx),
            (false, Ctx::Top) => format!("`{local}`"),
            (false, _) => format!("`{local}` of {}", self.ctx_name(&ctx)),
        }
    }

    /// Where a key of the table at `path` is: "in chart \"a\"", "at the top level", ...
    fn inside(&self, path: &[PathSeg]) -> String {
        let (ctx, local) = self.local(path);
        match (local.is_empty(), &ctx) {
            (true, Ctx::Top) => "at the top level".to_owned(),
            _ => format!("in {}", self.owner(path)),
        }
    }

    /// What an enum value is called: "chart kind", "scale", "color type".
    fn enum_noun(&self, path: &[PathSeg]) -> String {
        let mut keys = path.iter().rev().filter_map(|s| match s {
            PathSeg::Key(k) => Some(k.as_str()),
            PathSeg::Index(_) => None,
        });
        let last = keys.next().unwrap_or("value");
        if (last == "kind" || last == "type")
            && let Some(parent) = keys.next()
        {
            return format!("{parent} {last}").replace('_', " ");
        }
        last.replace('_', " ")
    }

    // ----- the walk -------------------------------------------------------------------------

    fn check(&mut self, v: &SpannedValue, schema: &'s Value, path: &mut Vec<PathSeg>, field: Field<'s>, depth: usize) {
        if depth > MAX_SCHEMA_DEPTH {
            return;
        }
        let s = self.resolve(schema);
        if let Some(values) = self.enum_values(s) {
            self.check_enum(v, schema, &values, path, field);
            return;
        }
        if let Some(branches) = alternatives(s) {
            match self.tag_of(branches) {
                Some(tag) => self.check_tagged(v, s, branches, tag, path, field, depth),
                None => match branches.iter().find(|b| self.accepts(b, v, 0)) {
                    Some(b) => self.check(v, b, path, field, depth + 1),
                    None => self.type_error(v, schema, path, field),
                },
            }
            return;
        }
        if let Some(t) = s.get("type")
            && !type_matches(t, v)
        {
            self.type_error(v, schema, path, field);
            return;
        }
        match &v.kind {
            ValueKind::Integer(_) | ValueKind::Float(_) => self.check_number(v, s, path, field),
            ValueKind::String(text) => self.check_string(v, text, s, path, field),
            ValueKind::Array(items) => self.check_array(v, items, s, path, field, depth),
            ValueKind::Table(entries) => self.check_table(v, entries, s, path, depth, &[], None),
            ValueKind::Boolean(_) | ValueKind::Datetime(_) => {}
        }
    }

    fn type_error(&mut self, v: &SpannedValue, schema: &'s Value, path: &[PathSeg], field: Field<'s>) {
        let expected = self.describe(schema, false, 0);
        let found = match &v.kind {
            ValueKind::Float(f) if !f.is_finite() => format!("{} ({})", v.kind_name(), fmt_f64(*f)),
            _ => v.kind_name().to_owned(),
        };
        let mut d =
            Diagnostic::error(format!("{} must be {expected}, found {found}", self.subject(path))).at(v.span.clone());
        if let Some(h) = self.field_hint(field) {
            d = d.with_hint(h);
        }
        self.diags.push(d);
    }

    fn check_enum(
        &mut self,
        v: &SpannedValue,
        schema: &'s Value,
        values: &[&'s str],
        path: &[PathSeg],
        field: Field<'s>,
    ) {
        let Some(text) = v.as_str() else {
            self.type_error(v, schema, path, field);
            return;
        };
        if values.contains(&text) {
            return;
        }
        let mut message = format!("unknown {} `{}`", self.enum_noun(path), shorten(text));
        if let Some(best) = did_you_mean(text, values.iter().copied()) {
            message.push_str(&format!("; did you mean `{best}`?"));
        }
        let list: Vec<String> = values.iter().map(|v| format!("`{v}`")).collect();
        let mut hint = format!("expected one of: {}", list.join(", "));
        if let Some(note) = super::foreign::value(text) {
            hint = format!("{note}; {hint}");
        }
        self.diags.push(Diagnostic::error(message).at(v.span.clone()).with_hint(hint));
    }

    fn check_number(&mut self, v: &SpannedValue, s: &'s Value, path: &[PathSeg], field: Field<'s>) {
        let (x, shown) = match v.kind {
            ValueKind::Integer(i) => (i as f64, i.to_string()),
            ValueKind::Float(f) => (f, fmt_f64(f)),
            _ => return,
        };
        let hint = self.field_hint(field);
        if !x.is_finite() {
            let d = Diagnostic::error(format!("{} must be a finite number, found {shown}", self.subject(path)))
                .at(v.span.clone());
            self.diags.push(match hint {
                Some(h) => d.with_hint(h),
                None => d,
            });
            return;
        }
        let num = |k: &str| s.get(k).and_then(Value::as_f64);
        let (mut min, mut max) = (num("minimum"), num("maximum"));
        let (xmin, xmax) = (num("exclusiveMinimum"), num("exclusiveMaximum"));
        let fmt_bounds: Option<(f64, f64)> = match s.get("format").and_then(Value::as_str) {
            Some("uint8") => Some((0.0, f64::from(u8::MAX))),
            Some("uint16") => Some((0.0, f64::from(u16::MAX))),
            Some("uint32") => Some((0.0, f64::from(u32::MAX))),
            Some("int8") => Some((f64::from(i8::MIN), f64::from(i8::MAX))),
            Some("int16") => Some((f64::from(i16::MIN), f64::from(i16::MAX))),
            Some("int32") => Some((f64::from(i32::MIN), f64::from(i32::MAX))),
            Some("uint" | "uint64") => Some((0.0, f64::INFINITY)),
            _ => None,
        };
        if let Some((lo, hi)) = fmt_bounds {
            min = Some(min.map_or(lo, |m| m.max(lo)));
            if hi.is_finite() {
                max = Some(max.map_or(hi, |m| m.min(hi)));
            }
        }
        let bad = min.is_some_and(|m| x < m)
            || max.is_some_and(|m| x > m)
            || xmin.is_some_and(|m| x <= m)
            || xmax.is_some_and(|m| x >= m);
        if !bad {
            return;
        }
        let mut parts = Vec::new();
        match (min, max, xmin, xmax) {
            (Some(lo), Some(hi), None, None) => parts.push(format!("between {} and {}", fmt_f64(lo), fmt_f64(hi))),
            _ => {
                if let Some(m) = xmin {
                    parts.push(format!("greater than {}", fmt_f64(m)));
                } else if let Some(m) = min {
                    parts.push(format!("at least {}", fmt_f64(m)));
                }
                if let Some(m) = xmax {
                    parts.push(format!("less than {}", fmt_f64(m)));
                } else if let Some(m) = max {
                    parts.push(format!("at most {}", fmt_f64(m)));
                }
            }
        }
        let d = Diagnostic::error(format!("{} must be {}, found {shown}", self.subject(path), parts.join(" and ")))
            .at(v.span.clone());
        self.diags.push(match hint {
            Some(h) => d.with_hint(h),
            None => d,
        });
    }

    fn check_string(&mut self, v: &SpannedValue, text: &str, s: &'s Value, path: &[PathSeg], field: Field<'s>) {
        let n = text.chars().count() as u64;
        let min = s.get("minLength").and_then(Value::as_u64);
        let max = s.get("maxLength").and_then(Value::as_u64);
        if min.is_none_or(|m| n >= m) && max.is_none_or(|m| n <= m) {
            return;
        }
        let chars = |k: u64| if k == 1 { "1 character".to_owned() } else { format!("{k} characters") };
        let expected = match (min, max) {
            (Some(a), Some(b)) if a == b => format!("exactly {}", chars(a)),
            (Some(a), Some(b)) => format!("{a} to {}", chars(b)),
            (Some(a), None) => format!("at least {}", chars(a)),
            (None, Some(b)) => format!("at most {}", chars(b)),
            (None, None) => return,
        };
        let found = if n == 0 { "an empty string".to_owned() } else { chars(n) };
        let mut d =
            Diagnostic::error(format!("{} must be {expected}, found {found}", self.subject(path))).at(v.span.clone());
        if let Some(h) = self.field_hint(field) {
            d = d.with_hint(h);
        }
        self.diags.push(d);
    }

    fn check_array(
        &mut self,
        v: &SpannedValue,
        items: &[SpannedValue],
        s: &'s Value,
        path: &mut Vec<PathSeg>,
        field: Field<'s>,
        depth: usize,
    ) {
        let n = items.len() as u64;
        let min = s.get("minItems").and_then(Value::as_u64);
        let max = s.get("maxItems").and_then(Value::as_u64);
        if min.is_some_and(|m| n < m) || max.is_some_and(|m| n > m) {
            let expected = self.describe(s, false, 0);
            let found = match n {
                0 => "an empty array".to_owned(),
                1 => "an array of 1 item".to_owned(),
                _ => format!("an array of {n} items"),
            };
            let mut d = Diagnostic::error(format!("{} must be {expected}, found {found}", self.subject(path)))
                .at(v.span.clone());
            if let Some(h) = self.field_hint(field) {
                d = d.with_hint(h);
            }
            self.diags.push(d);
        }
        if let Some(item_schema) = s.get("items").filter(|i| i.is_object()) {
            for (i, item) in items.iter().enumerate() {
                path.push(PathSeg::Index(i));
                self.check(item, item_schema, path, field, depth + 1);
                path.pop();
            }
        }
    }

    /// Checks a table's keys against an object schema. `elsewhere` lists the other branches of a
    /// tagged choice (to say "only for kind = ..."); `tag` is the already checked tag key.
    #[allow(clippy::too_many_arguments)]
    fn check_table(
        &mut self,
        v: &SpannedValue,
        entries: &[TableEntry],
        s: &'s Value,
        path: &mut Vec<PathSeg>,
        depth: usize,
        elsewhere: &[(&'s str, &'s Value)],
        tag: Option<&'s str>,
    ) {
        let props = s.get("properties").and_then(Value::as_object);
        let additional = s.get("additionalProperties");
        for e in entries {
            if Some(e.key.as_str()) == tag {
                continue;
            }
            if let Some((key, prop)) = props.and_then(|p| p.get_key_value(&e.key)) {
                path.push(PathSeg::Key(e.key.clone()));
                self.check(&e.value, prop, path, Field { key: Some(key), schema: Some(prop) }, depth + 1);
                path.pop();
                continue;
            }
            match additional {
                Some(extra @ Value::Object(_)) => {
                    path.push(PathSeg::Key(e.key.clone()));
                    self.check(&e.value, extra, path, Field { key: None, schema: Some(extra) }, depth + 1);
                    path.pop();
                }
                Some(Value::Bool(true)) => {}
                None if props.is_none() => {}
                _ => {
                    let allowed = self.ordered_keys(s);
                    self.unknown_key(v, e, &allowed, path, elsewhere, tag);
                }
            }
        }
        self.check_required(v, s, path, tag);
    }

    fn check_required(&mut self, v: &SpannedValue, s: &'s Value, path: &[PathSeg], tag: Option<&str>) {
        let props = s.get("properties");
        let mut missing = Vec::new();
        // A chart's own table: its index and kind, for keys with a conventional default.
        let chart = match path {
            [PathSeg::Key(c), PathSeg::Index(i)] if c == "chart" => {
                v.get("kind").and_then(SpannedValue::as_str).map(|kind| (*i, kind))
            }
            _ => None,
        };
        for key in s.get("required").and_then(Value::as_array).into_iter().flatten().filter_map(Value::as_str) {
            if Some(key) == tag || v.entry(key).is_some() {
                continue;
            }
            let conventional = chart.filter(|(_, kind)| super::defaults::has_convention(kind, key));
            let note = match (&self.conventional, conventional) {
                (Conventional::Deferred, Some(_)) => {
                    self.deferred = true;
                    continue;
                }
                (Conventional::Noted(filled), Some((i, _))) if filled.pending.contains(&i) => {
                    self.deferred = true;
                    continue;
                }
                (Conventional::Noted(filled), Some((i, _))) => filled.notes.get(&(i, key.to_owned())).cloned(),
                _ => None,
            };
            missing.push(Missing { key, prop: props.and_then(|p| p.get(key)), note });
        }
        let noted = missing.iter().any(|m| m.note.is_some());
        self.report_missing(v, path, &missing);
        // The columns to choose from, once, after the notes.
        if let (true, Conventional::Noted(filled), Some((i, _))) = (noted, &self.conventional, chart)
            && let (Some(line), Some(d)) = (filled.columns.get(&i), self.diags.last_mut())
        {
            d.hint = Some(format!("{}\n{line}", d.hint.take().unwrap_or_default()));
        }
    }

    /// One diagnostic for all required keys a table lacks, at the table's header.
    fn report_missing(&mut self, v: &SpannedValue, path: &[PathSeg], missing: &[Missing<'s>]) {
        let owner = self.owner(path);
        let example = |m: &Missing<'s>| m.prop.and_then(|p| self.example(p));
        let diag = match missing {
            [] => return,
            [m] => {
                let mut hint = match example(m) {
                    Some(ex) => format!("add `{} = {ex}`", display_key(m.key)),
                    None => format!("add `{}`", display_key(m.key)),
                };
                if let Some(note) = &m.note {
                    hint.push_str("; ");
                    hint.push_str(note);
                } else if let Some(d) = m.prop.and_then(|p| self.description(p)) {
                    hint.push_str(": ");
                    hint.push_str(&d);
                }
                Diagnostic::error(format!("{owner} has no `{}`", display_key(m.key))).with_hint(hint)
            }
            many => {
                let keys: Vec<String> = many.iter().map(|m| format!("`{}`", display_key(m.key))).collect();
                let mut keys_and = keys.clone();
                let last = keys_and.pop().unwrap_or_default();
                let listed = format!("{} and {last}", keys_and.join(", "));
                let mut hint = "add them, for example:".to_owned();
                for m in many {
                    let ex = example(m).unwrap_or_else(|| "…".to_owned());
                    hint.push_str(&format!("\n{} = {ex}", display_key(m.key)));
                    if let Some(note) = &m.note {
                        hint.push_str(&format!("  # {note}"));
                    }
                }
                Diagnostic::error(format!("{owner} is missing {listed}")).with_hint(hint)
            }
        };
        self.diags.push(diag.at(v.span.clone()));
    }

    /// An unknown key `e` of the table `table`.
    fn unknown_key(
        &mut self,
        table: &SpannedValue,
        e: &TableEntry,
        allowed: &[&str],
        path: &[PathSeg],
        elsewhere: &[(&'s str, &'s Value)],
        tag: Option<&str>,
    ) {
        let key = shorten(&display_key(&e.key));
        let mut d = Diagnostic::error(format!("unknown key `{key}` {}", self.inside(path))).at(e.key_span.clone());
        let owners: Vec<String> = elsewhere
            .iter()
            .filter(|(_, b)| b.get("properties").and_then(|p| p.get(&e.key)).is_some())
            .map(|(k, _)| format!("{} = \"{k}\"", tag.unwrap_or("kind")))
            .collect();
        let translation = super::foreign::key(&e.key).filter(|t| allowed.contains(&t.key));
        if !owners.is_empty() {
            d = d.with_label(format!("only for {}", owners.join(" or ")));
        } else if let Some(translation) = translation {
            // The chart's own column for the channel, written as a name or as `{ field = ... }`.
            let channel = table.get(translation.key);
            let column = channel.and_then(|c| c.as_str().or_else(|| c.get("field").and_then(SpannedValue::as_str)));
            self.diags.push(d.with_label(translation.label).with_hint(translation.hint_for(column)));
            return;
        } else if let Some(best) = did_you_mean(&e.key, allowed.iter().copied()) {
            d = d.with_label(format!("did you mean `{best}`?"));
        }
        let mut hint = format!("keys allowed here: {}", allowed.join(", "));
        if allowed.is_empty() {
            hint = "no keys are allowed here".to_owned();
        }
        self.diags.push(d.with_hint(hint));
    }

    /// A table chosen among `oneOf` branches by its `tag` key (the chart's `kind`).
    #[allow(clippy::too_many_arguments)]
    fn check_tagged(
        &mut self,
        v: &SpannedValue,
        s: &'s Value,
        branches: &'s [Value],
        tag: &'s str,
        path: &mut Vec<PathSeg>,
        field: Field<'s>,
        depth: usize,
    ) {
        let ValueKind::Table(entries) = &v.kind else {
            self.type_error(v, s, path, field);
            return;
        };
        let options: Vec<(&'s str, &'s Value)> = branches
            .iter()
            .filter_map(|b| {
                let b = self.resolve(b);
                Some((self.tag_value(b, tag)?, b))
            })
            .collect();
        let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
        let listed: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
        path.push(PathSeg::Key(tag.to_owned()));
        let noun = self.enum_noun(path);
        path.pop();
        match v.entry(tag) {
            Some(e) => match e.value.as_str() {
                Some(k) => {
                    if let Some((_, branch)) = options.iter().find(|(n, _)| *n == k) {
                        let others: Vec<(&'s str, &'s Value)> =
                            options.iter().filter(|(n, _)| *n != k).copied().collect();
                        self.check_table(v, entries, branch, path, depth, &others, Some(tag));
                        return;
                    }
                    let mut message = format!("unknown {noun} `{}`", shorten(k));
                    if let Some(best) = did_you_mean(k, names.iter().copied()) {
                        message.push_str(&format!("; did you mean `{best}`?"));
                    }
                    self.diags.push(
                        Diagnostic::error(message)
                            .at(e.value.span.clone())
                            .with_hint(format!("expected one of: {}", listed.join(", "))),
                    );
                }
                None => {
                    path.push(PathSeg::Key(tag.to_owned()));
                    let message = format!(
                        "{} must be one of {}, found {}",
                        self.subject(path),
                        join_or(&listed),
                        e.value.kind_name()
                    );
                    path.pop();
                    self.diags.push(Diagnostic::error(message).at(e.value.span.clone()));
                }
            },
            None => {
                let note = format!("{noun}s: {}", names.join(", "));
                self.check_any_branch(v, entries, &options, tag, Some(note), path, depth);
                return;
            }
        }
        self.check_any_branch(v, entries, &options, tag, None, path, depth);
    }

    /// Without a usable tag: check what every branch agrees on, and flag keys no branch knows.
    /// `tag_note` is set when the tag itself is missing (and says which values it may take).
    #[allow(clippy::too_many_arguments)]
    fn check_any_branch(
        &mut self,
        v: &SpannedValue,
        entries: &[TableEntry],
        options: &[(&'s str, &'s Value)],
        tag: &'s str,
        tag_note: Option<String>,
        path: &mut Vec<PathSeg>,
        depth: usize,
    ) {
        let mut union: Vec<&'s str> = Vec::new();
        for (_, b) in options {
            for k in self.ordered_keys(b) {
                if !union.contains(&k) {
                    union.push(k);
                }
            }
        }
        for e in entries {
            if e.key == tag {
                continue;
            }
            let schemas: Vec<Option<(&'s String, &'s Value)>> = options
                .iter()
                .map(|(_, b)| b.get("properties").and_then(Value::as_object).and_then(|p| p.get_key_value(&e.key)))
                .collect();
            let first = schemas.first().copied().flatten();
            let agreed = first.filter(|(_, f)| schemas.iter().all(|s| s.is_some_and(|(_, x)| x == *f)));
            if let Some((key, prop)) = agreed {
                path.push(PathSeg::Key(e.key.clone()));
                self.check(&e.value, prop, path, Field { key: Some(key), schema: Some(prop) }, depth + 1);
                path.pop();
            } else if schemas.iter().all(Option::is_none) {
                self.unknown_key(v, e, &union, path, &[], Some(tag));
            }
        }
        let required_by_all = options.first().map(|(_, b)| self.ordered_keys(b)).unwrap_or_default();
        let mut missing = Vec::new();
        for key in required_by_all {
            let everywhere = options.iter().all(|(_, b)| {
                b.get("required").and_then(Value::as_array).is_some_and(|r| r.iter().any(|x| x.as_str() == Some(key)))
            });
            let wanted = if key == tag { tag_note.is_some() } else { v.entry(key).is_none() };
            if everywhere && wanted {
                let prop = options.first().and_then(|(_, b)| b.get("properties")).and_then(|p| p.get(key));
                let note = if key == tag { tag_note.clone() } else { None };
                missing.push(Missing { key, prop, note });
            }
        }
        self.report_missing(v, path, &missing);
    }

    // ----- rules the schema cannot say ------------------------------------------------------

    fn semantic(&mut self, root: &SpannedValue) {
        let data = root.get("data");
        let data_names: Option<Vec<&str>> = match data {
            None => Some(Vec::new()),
            Some(d) if d.is_table() => Some(d.entries().iter().map(|e| e.key.as_str()).collect()),
            Some(_) => None,
        };
        for e in data.map(SpannedValue::entries).unwrap_or(&[]) {
            self.check_data_source(e);
        }
        let selections: Vec<(&str, &SpannedValue)> = root
            .get("selection")
            .map(SpannedValue::entries)
            .unwrap_or(&[])
            .iter()
            .filter(|e| e.value.is_table())
            .map(|e| (e.key.as_str(), &e.value))
            .collect();
        for (name, selection) in &selections {
            self.check_selection(name, selection, data_names.as_deref());
        }
        match root.get("chart") {
            None => self.no_charts(None),
            Some(c) => match c.as_array() {
                Some([]) => self.no_charts(Some(c)),
                Some(charts) => {
                    let mut seen = SeenNames::default();
                    for (i, chart) in charts.iter().enumerate() {
                        if chart.is_table() {
                            self.check_chart(i, chart, data_names.as_deref(), &selections, &mut seen);
                        }
                    }
                }
                None => {}
            },
        }
    }

    fn no_charts(&mut self, chart: Option<&SpannedValue>) {
        let d = Diagnostic::error("the spec has no charts").at_opt(chart.map(|c| c.span.clone())).with_hint(
            "add one, for example:\n[[chart]]\nname = \"iris-scatter\"\ndata = \"iris\"\nkind = \"scatter\"\nx = \"sepal_length\"\ny = \"petal_length\"",
        );
        self.diags.push(d);
    }

    fn check_data_source(&mut self, e: &TableEntry) {
        let source = &e.value;
        if !source.is_table() {
            return;
        }
        let name = format!("`data.{}`", shorten(&display_key(&e.key)));
        if source.entry("engine").is_some() {
            self.check_engine_source(&name, source);
            return;
        }
        if let Some(table) = source.entry("table") {
            self.diags.push(
                Diagnostic::error(format!("{name} names a `table` but no `engine`"))
                    .at(table.key_span.clone())
                    .with_hint("`table` is a table on a query engine: add `engine = \"sc://HOST:PORT\"`, or read a file with `path`"),
            );
        }
        self.exactly_one(
            &name,
            source,
            &["path", "values", "from"],
            Diagnostic::error(format!("{name} has none of `path`, `values` or `from`"))
                .with_hint("add `path = \"data/iris.csv\"` (a file next to the spec), inline rows `values = [{ x = 1, y = 2 }]` or `from = \"OTHER\"` (another source, then its own `transform`)"),
            Some("a data source reads a file (`path`), holds inline rows (`values`) or derives from another source (`from`): exactly one"),
        );
        if let Some(delim) = source.get("delimiter")
            && let Some(text) = delim.as_str()
            && text.chars().count() == 1
            && !text.is_ascii()
        {
            self.diags.push(
                Diagnostic::error(format!("`delimiter` must be an ASCII character, found `{}`", shorten(text)))
                    .at(delim.span.clone())
                    .with_hint("CSV readers split on single bytes; use e.g. `,`, `;`, `|` or `\\t`"),
            );
        }
    }

    /// An engine source reads exactly one of `path` and `table`, on the cluster.
    fn check_engine_source(&mut self, name: &str, source: &SpannedValue) {
        for key in ["values", "from"] {
            if let Some(entry) = source.entry(key) {
                self.diags.push(
                    Diagnostic::error(format!("{name} is on an engine and cannot take `{key}`"))
                        .at(entry.key_span.clone())
                        .with_hint("an engine source reads a `path` or a `table` the cluster holds; another source cannot start from it yet"),
                );
            }
        }
        self.exactly_one(
            name,
            source,
            &["path", "table"],
            Diagnostic::error(format!("{name} has an `engine` but neither `path` nor `table`"))
                .with_hint("name what the cluster reads: `path = \"/data/trips.parquet\"` or `table = \"trips\"`"),
            None,
        );
    }

    /// Exactly one of the origin `keys` in a data source: `none` (placed at the source) when it
    /// has none, "has both" at the second when it has two.
    fn exactly_one(
        &mut self,
        name: &str,
        source: &SpannedValue,
        keys: &[&str],
        none: Diagnostic,
        both_hint: Option<&str>,
    ) {
        let origins: Vec<&TableEntry> = keys.iter().filter_map(|k| source.entry(k)).collect();
        match origins.as_slice() {
            [] => self.diags.push(none.at(source.span.clone())),
            [first, second, ..] => {
                let mut d = Diagnostic::error(format!("{name} has both `{}` and `{}`", first.key, second.key))
                    .at(second.key_span.clone())
                    .with_label(format!("remove this or `{}`", first.key));
                if let Some(hint) = both_hint {
                    d = d.with_hint(hint);
                }
                self.diags.push(d);
            }
            _ => {}
        }
    }

    fn check_chart<'v>(
        &mut self,
        i: usize,
        chart: &'v SpannedValue,
        data_names: Option<&[&str]>,
        selections: &[(&str, &SpannedValue)],
        seen: &mut SeenNames<'v>,
    ) {
        let name_hint = "use ASCII letters, digits, `-`, `_` and `.` (the name is the output file stem)";
        if let Some(name_value) = chart.get("name")
            && let Some(name) = name_value.as_str()
        {
            let span = name_value.span.clone();
            let bad = name.chars().find(|c| !(c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.')));
            if name.is_empty() {
                self.diags.push(
                    Diagnostic::error(format!("chart #{} has an empty name", i + 1))
                        .at(span)
                        .with_hint("the name is the output file stem, e.g. `name = \"iris-scatter\"`"),
                );
            } else if let Some(c) = bad {
                self.diags.push(
                    Diagnostic::error(format!("invalid chart name `{}`", shorten(name)))
                        .at(span)
                        .with_label(format!("`{}` is not allowed", c.escape_debug()))
                        .with_hint(name_hint),
                );
            } else if name.chars().all(|c| c == '.') {
                self.diags.push(
                    Diagnostic::error(format!("invalid chart name `{name}`"))
                        .at(span)
                        .with_label("not a usable file name")
                        .with_hint(name_hint),
                );
            } else if let Some(first) = seen.exact.get(name) {
                self.diags.push(
                    Diagnostic::error(format!("duplicate chart name `{name}`"))
                        .at(span)
                        .with_label(format!("chart #{} has the same name", first + 1))
                        .with_hint("each chart is written to `<name>.svg`; give every chart its own name"),
                );
            } else {
                seen.exact.insert(name, i);
                match seen.folded.get(&name.to_ascii_lowercase()) {
                    Some((first, other)) => self.diags.push(
                        Diagnostic::warning(format!("chart names `{other}` and `{name}` differ only in case"))
                            .at(span)
                            .with_label(format!("like chart #{}", first + 1))
                            .with_hint(
                                "on case-insensitive file systems (macOS, Windows) both charts write the same file",
                            ),
                    ),
                    None => {
                        seen.folded.insert(name.to_ascii_lowercase(), (i, name));
                    }
                }
            }
        }
        if let (Some(names), Some(data)) = (data_names, chart.get("data")) {
            self.check_reference(data, names, Reference::Data);
        }
        if let (Some(names), Some(data)) = (data_names, chart.get("nodes").and_then(|n| n.get("data"))) {
            self.check_reference(data, names, Reference::Data);
        }
        if let Some(tree) = chart.get("tree") {
            self.check_tree_source(tree);
        }
        if let Some(highlight) = chart.get("highlight") {
            self.check_highlight(chart, highlight, selections);
        }
        self.check_aspect(chart);
        self.check_annotate(i, chart);
        for e in chart.entries() {
            let tables: Vec<(String, &SpannedValue)> = match &e.value.kind {
                ValueKind::Table(_) => vec![(display_key(&e.key), &e.value)],
                ValueKind::Array(items) => items
                    .iter()
                    .enumerate()
                    .filter(|(_, t)| t.is_table())
                    .map(|(j, t)| (format!("{}[{j}]", display_key(&e.key)), t))
                    .collect(),
                _ => Vec::new(),
            };
            for (local, t) in tables {
                self.check_domain(&local, t);
            }
        }
    }

    /// A tree's columns: `path`, or `id` with `parent`.
    fn check_tree_source(&mut self, tree: &SpannedValue) {
        if !tree.is_table() {
            return;
        }
        let (id, parent, path) = (tree.get("id"), tree.get("parent"), tree.get("path"));
        let problem = match (id.is_some(), parent.is_some(), path.is_some()) {
            (_, _, true) if id.is_some() || parent.is_some() => Some("`tree` has both `path` and `id`/`parent`"),
            (false, false, false) => Some("`tree` names no columns"),
            (true, false, false) => Some("`tree` has `id` but no `parent`"),
            (false, true, false) => Some("`tree` has `parent` but no `id`"),
            _ => None,
        };
        if let Some(message) = problem {
            self.diags.push(Diagnostic::error(message).at(tree.span.clone()).with_hint(
                "write `tree = { id = \"id\", parent = \"parent\" }` (a parent id per row) or `tree = { path = \"path\" }` (paths such as a/b/c)",
            ));
        }
    }

    /// A reference by name to a data source or a selection that must exist.
    fn check_reference(&mut self, value: &SpannedValue, names: &[&str], what: Reference) {
        let Some(wanted) = value.as_str() else { return };
        if names.contains(&wanted) {
            return;
        }
        let noun = match what {
            Reference::Data => "data source",
            Reference::Selection => "selection",
        };
        let mut message = format!("unknown {noun} `{}`", shorten(wanted));
        if let Some(best) = did_you_mean(wanted, names.iter().copied()) {
            message.push_str(&format!("; did you mean `{best}`?"));
        }
        let hint = if names.is_empty() {
            match what {
                Reference::Data => format!(
                    "no data sources are defined; add a `[data.{}]` table with `path` or `values`",
                    shorten(&display_key(wanted))
                ),
                Reference::Selection => format!(
                    "no selections are defined; add a `[selection.{}]` table with `data` and `range` or `categories`",
                    shorten(&display_key(wanted))
                ),
            }
        } else {
            let listed: Vec<String> = names.iter().map(|n| format!("`{}`", shorten(n))).collect();
            format!("{noun}s defined: {}", listed.join(", "))
        };
        self.diags.push(Diagnostic::error(message).at(value.span.clone()).with_hint(hint));
    }

    fn check_selection(&mut self, name: &str, selection: &SpannedValue, data_names: Option<&[&str]>) {
        let label = format!("`selection.{}`", shorten(&display_key(name)));
        if let (Some(names), Some(data)) = (data_names, selection.get("data")) {
            self.check_reference(data, names, Reference::Data);
        }
        if selection.get("range").is_none() && selection.get("categories").is_none() {
            self.diags.push(
                Diagnostic::error(format!("{label} selects nothing: it has neither `range` nor `categories`"))
                    .at(selection.span.clone())
                    .with_hint(
                        "add e.g. `range = { petal_length = [1.0, 2.5] }` or `categories = { species = [\"setosa\"] }`",
                    ),
            );
        }
        for e in selection.get("range").map(SpannedValue::entries).unwrap_or(&[]) {
            let Some([a, b]) = e.value.as_array() else { continue };
            let (Some(lo), Some(hi)) = (a.as_f64(), b.as_f64()) else { continue };
            if lo.is_finite() && hi.is_finite() && lo > hi {
                self.diags.push(
                    Diagnostic::error(format!(
                        "{label}: range of `{}` must be `[min, max]` with min ≤ max, found `[{}, {}]`",
                        shorten(&display_key(&e.key)),
                        fmt_f64(lo),
                        fmt_f64(hi)
                    ))
                    .at(e.value.span.clone())
                    .with_hint("swap the two numbers"),
                );
            }
        }
    }

    /// An error at `span` when the chart's kind does not take a key (`takes` says which kinds
    /// do): "{what} `KIND` charts", with the kinds that take it (`takers`) in the hint. Whether
    /// the kind refused it.
    fn refused_by_kind(
        &mut self,
        chart: &SpannedValue,
        span: Range<usize>,
        what: &str,
        takes: fn(&KindInfo) -> bool,
        takers: &str,
    ) -> bool {
        let Some(kind) = chart.get("kind").and_then(SpannedValue::as_str) else { return false };
        if crate::mark::registry::kind_info(kind).is_none_or(takes) {
            return false;
        }
        let kinds = crate::mark::registry::names_where(takes).join(", ");
        self.diags.push(
            Diagnostic::error(format!("{what} `{kind}` charts")).at(span).with_hint(format!("{takers}: {kinds}")),
        );
        true
    }

    /// `aspect = "equal"` only where one x/y frame (or given node positions) is drawn.
    fn check_aspect(&mut self, chart: &SpannedValue) {
        let Some(entry) = chart.entry("aspect") else { return };
        if entry.value.as_str() == Some("equal") {
            let what = "`aspect = \"equal\"` is not applied by";
            self.refused_by_kind(chart, entry.key_span.clone(), what, |k| k.applies_aspect, "charts with one x/y plot");
        }
    }

    /// `annotate` only where one x/y frame is drawn, each of its tables one form of annotation
    /// (the chart's `i`-th).
    fn check_annotate(&mut self, i: usize, chart: &SpannedValue) {
        let Some(entry) = chart.entry("annotate") else { return };
        let takers = "charts with one x/y plot, which draw annotations";
        if self.refused_by_kind(
            chart,
            entry.key_span.clone(),
            "`annotate` is not drawn by",
            |k| k.draws_annotations,
            takers,
        ) {
            return;
        }
        for (j, table) in entry.value.as_array().unwrap_or(&[]).iter().enumerate() {
            // A table whose keys or values the schema refused is reported already.
            let Ok(note) = serde_json::from_value::<Annotation>(table.to_json()) else { continue };
            let Err(e) = note.form() else { continue };
            let span = e.key.and_then(|k| table.entry(k)).map_or(table.span.clone(), |k| k.key_span.clone());
            let path =
                [PathSeg::Key("chart".into()), PathSeg::Index(i), PathSeg::Key("annotate".into()), PathSeg::Index(j)];
            let message = format!("{} {}", self.owner(&path), e.message);
            self.diags.push(Diagnostic::error(message).at(span).with_hint(e.hint));
        }
    }

    /// `highlight` must name a selection over the chart's own data, on a kind that draws it.
    fn check_highlight(
        &mut self,
        chart: &SpannedValue,
        highlight: &SpannedValue,
        selections: &[(&str, &SpannedValue)],
    ) {
        let names: Vec<&str> = selections.iter().map(|(n, _)| *n).collect();
        let Some(wanted) = highlight.as_str() else { return };
        let key_span = chart.entry("highlight").map_or(highlight.span.clone(), |e| e.key_span.clone());
        let what = "`highlight` is not drawn by";
        if self.refused_by_kind(chart, key_span, what, |k| k.draws_selection, "charts that draw selections") {
            return;
        }
        if !names.contains(&wanted) {
            self.check_reference(highlight, &names, Reference::Selection);
            return;
        }
        let selection_data = selections.iter().find(|(n, _)| *n == wanted).and_then(|(_, s)| s.get("data"));
        let chart_data = chart.get("data").and_then(SpannedValue::as_str);
        if let (Some(sel_data), Some(chart_data)) = (selection_data.and_then(SpannedValue::as_str), chart_data)
            && sel_data != chart_data
        {
            self.diags.push(
                Diagnostic::error(format!(
                    "selection `{}` is over data `{}`, but this chart draws `{}`",
                    shorten(wanted),
                    shorten(sel_data),
                    shorten(chart_data)
                ))
                .at(highlight.span.clone())
                .with_label("rows are linked only within one data source")
                .with_hint("highlight a selection made over the chart's own data source"),
            );
        }
    }

    fn check_domain(&mut self, local: &str, channel: &SpannedValue) {
        // A colour `domain` lists categories in colour order, not an extent.
        if local == "color" {
            return;
        }
        let Some(domain) = channel.get("domain") else { return };
        let Some([a, b]) = domain.as_array() else { return };
        let (Some(lo), Some(hi)) = (a.as_f64(), b.as_f64()) else { return };
        if lo.is_finite() && hi.is_finite() && lo >= hi {
            self.diags.push(
                Diagnostic::error(format!(
                    "`{}.domain` must be `[min, max]` with min < max, found `[{}, {}]`",
                    shorten(local),
                    fmt_f64(lo),
                    fmt_f64(hi)
                ))
                .at(domain.span.clone())
                .with_hint("give a smaller first number, or leave `domain` out to use the data's extent"),
            );
        }
    }
}

/// What a name refers to.
#[derive(Clone, Copy)]
enum Reference {
    /// A `[data.NAME]` table.
    Data,
    /// A `[selection.NAME]` table.
    Selection,
}

fn alternatives(s: &Value) -> Option<&[Value]> {
    s.get("oneOf").or_else(|| s.get("anyOf")).and_then(Value::as_array).map(Vec::as_slice)
}

fn type_matches(t: &Value, v: &SpannedValue) -> bool {
    let one = |name: &str| {
        matches!(
            (name, &v.kind),
            ("string", ValueKind::String(_))
                | ("boolean", ValueKind::Boolean(_))
                | ("object", ValueKind::Table(_))
                | ("array", ValueKind::Array(_))
                | ("integer", ValueKind::Integer(_))
                | ("number", ValueKind::Integer(_) | ValueKind::Float(_))
        )
    };
    match t {
        Value::String(name) => one(name),
        Value::Array(names) => names.iter().filter_map(Value::as_str).any(one),
        _ => true,
    }
}

fn pick(plural: bool, one: &str, many: &str) -> String {
    if plural { many.to_owned() } else { one.to_owned() }
}

/// "a", "a or b", "a, b or c".
fn join_or(parts: &[String]) -> String {
    match parts {
        [] => String::new(),
        [only] => only.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

fn lowercase_first(text: &str) -> String {
    let mut chars = text.chars();
    let (Some(first), second) = (chars.next(), chars.next()) else { return text.to_owned() };
    if second.is_some_and(char::is_uppercase) {
        return text.to_owned();
    }
    first.to_lowercase().chain(text.chars().skip(1)).collect()
}

/// User text for a message: control characters escaped, at most 40 characters (spec errors and
/// lint findings).
pub(crate) fn shorten(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars().take(40) {
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    if text.chars().count() > 40 {
        out.push('…');
    }
    out
}

fn fmt_f64(x: f64) -> String {
    if x.is_nan() {
        "nan".to_owned()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".to_owned() } else { "-inf".to_owned() }
    } else if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{x:.0}")
    } else if x.abs() >= 1e15 || x.abs() < 1e-4 {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// A JSON value written as an inline TOML value.
fn toml_inline(v: &Value) -> String {
    match v {
        Value::Null => "\"\"".to_owned(),
        Value::Bool(b) => b.to_string(),
        Value::Number(n) => n.to_string(),
        Value::String(s) => format!("{s:?}"),
        Value::Array(items) => format!("[{}]", items.iter().map(toml_inline).collect::<Vec<_>>().join(", ")),
        Value::Object(map) => {
            let inner: Vec<String> =
                map.iter().map(|(k, v)| format!("{} = {}", display_key(k), toml_inline(v))).collect();
            format!("{{ {} }}", inner.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn helpers() {
        assert_eq!(join_or(&["a".into(), "b".into(), "c".into()]), "a, b or c");
        assert_eq!(fmt_f64(800.0), "800");
        assert_eq!(fmt_f64(0.5), "0.5");
        assert_eq!(fmt_f64(1e300), "1e300");
        assert_eq!(fmt_f64(f64::NEG_INFINITY), "-inf");
        assert_eq!(lowercase_first("Canvas size"), "canvas size");
        assert_eq!(lowercase_first("CSV field"), "CSV field");
        assert_eq!(shorten("a\u{1b}b"), "a\\u{1b}b");
        assert_eq!(shorten(&"x".repeat(50)), format!("{}…", "x".repeat(40)));
        assert_eq!(toml_inline(&serde_json::json!([800, 600])), "[800, 600]");
        assert_eq!(toml_inline(&serde_json::json!({"a b": "x"})), "{ \"a b\" = \"x\" }");
    }
}
