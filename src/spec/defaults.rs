//! Conventional columns: a key a chart leaves out takes the column of the conventional name when
//! the chart's data has one — a grid's `x`, `y` and `value` (or `z`), a vector field's `x`, `y`,
//! `u`, `v` (and `t`), a tree's `id` and `parent` (or `path`) and `name` labels, a network's `source`, `target`
//! (and `weight` or `value`).
//!
//! The spec is first checked with these keys allowed to be missing ([`super::check_deferring`]);
//! once the data is loaded, [`fill`] writes the defaults into the spec, pointing at the chart's
//! header, and the spec is checked again in full, so a key whose column is missing too is reported
//! as missing with a note saying which column was looked for.

use std::collections::{BTreeMap, BTreeSet};

use super::source::{SpannedValue, SpecDoc, TableEntry, ValueKind};

/// What a conventional default fills in.
#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// A column name: the first of these the data has.
    Column(&'static [&'static str]),
    /// A tree's table: `{ id = "id", parent = "parent" }`, else `{ path = "path" }`.
    Tree,
}

/// One key of a kind with a conventional default (listed in the kind's
/// [`crate::mark::registry::KindInfo`]).
#[derive(Clone, Copy, Debug)]
pub struct Convention {
    /// The chart key.
    pub key: &'static str,
    /// What it takes.
    pub shape: Shape,
}

const fn column(key: &'static str, names: &'static [&'static str]) -> Convention {
    Convention { key, shape: Shape::Column(names) }
}

/// Kinds drawing a field on a grid (or on scattered points): what `.npy` and matrix sources hold.
pub const GRID: &[Convention] = &[column("x", &["x"]), column("y", &["y"]), column("z", &["value", "z"])];
/// Kinds drawing a field over more than two axes, which are always named.
pub const FIELD: &[Convention] = &[column("z", &["value", "z"])];
/// Vector fields.
pub const FLOW: &[Convention] =
    &[column("x", &["x"]), column("y", &["y"]), column("u", &["u"]), column("v", &["v"]), column("t", &["t"])];
/// Hierarchies.
pub const TREE: &[Convention] = &[Convention { key: "tree", shape: Shape::Tree }, column("label", &["name", "label"])];
/// Networks given as an edge table.
pub const NETWORK: &[Convention] =
    &[column("source", &["source"]), column("target", &["target"]), column("weight", &["weight", "value"])];

/// The keys of `kind` that default to conventional columns.
fn conventions(kind: &str) -> &'static [Convention] {
    crate::mark::registry::kind_info(kind).map_or(&[], |k| k.conventions)
}

/// Whether `key` of a `kind` chart may be left out for a conventional column.
pub fn has_convention(kind: &str, key: &str) -> bool {
    conventions(kind).iter().any(|c| c.key == key)
}

/// The column names a chart table would take by default, for reading them with the data: every
/// candidate of every conventional key the chart leaves out (a source need not have them all).
pub fn candidate_columns(chart: &serde_json::Value) -> Vec<&'static str> {
    let Some(kind) = chart.get("kind").and_then(serde_json::Value::as_str) else { return Vec::new() };
    let mut out = Vec::new();
    for c in conventions(kind).iter().filter(|c| chart.get(c.key).is_none()) {
        match c.shape {
            Shape::Column(names) => out.extend_from_slice(names),
            Shape::Tree => out.extend_from_slice(&["id", "parent", "path"]),
        }
    }
    out
}

/// A key one chart took by default.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Taken {
    /// The key, e.g. `u`.
    pub key: String,
    /// Its value as TOML, e.g. `"u"` or `{ id = "id", parent = "parent" }`.
    pub value: String,
}

/// What [`fill`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Filled {
    /// The defaults each chart took, by chart index.
    pub taken: BTreeMap<usize, Vec<Taken>>,
    /// For keys that stay missing because the data lacks the column too: a note for the missing
    /// key's hint, by chart index and key.
    pub notes: BTreeMap<(usize, String), String>,
    /// The columns of the data of each chart with such a note, as a line for the hint.
    pub columns: BTreeMap<usize, String>,
    /// Charts whose data did not load: their conventional keys stay unchecked (the load error is
    /// the one to report).
    pub pending: BTreeSet<usize>,
}

/// Write the conventional default of every key a chart leaves out into `doc`, when the chart's
/// data has the column. `columns(source)` gives a loaded source's column names (`None` when it
/// did not load; its charts are left alone).
pub fn fill(doc: &mut SpecDoc, columns: impl Fn(&str) -> Option<Vec<String>>) -> Filled {
    let mut filled = Filled::default();
    let Some(charts) = doc.root_mut().get_mut("chart").and_then(SpannedValue::as_array_mut) else { return filled };
    for (index, chart) in charts.iter_mut().enumerate() {
        let kind = chart.get("kind").and_then(SpannedValue::as_str).unwrap_or_default().to_owned();
        let Some(data) = chart.get("data").and_then(SpannedValue::as_str).map(str::to_owned) else { continue };
        let Some(names) = columns(&data) else {
            filled.pending.insert(index);
            continue;
        };
        let has = |name: &str| names.iter().any(|n| n == name);
        for convention in conventions(&kind) {
            if chart.get(convention.key).is_some() {
                continue;
            }
            let span = chart.span.clone();
            let value = match convention.shape {
                Shape::Column(candidates) => {
                    candidates.iter().find(|c| has(c)).map(|c| (SpannedValue::string(c, &span), format!("\"{c}\"")))
                }
                Shape::Tree => tree_default(&has).map(|pairs| {
                    let entries = pairs.iter().map(|(k, v)| entry(k, SpannedValue::string(v, &span), &span)).collect();
                    let text = pairs.iter().map(|(k, v)| format!("{k} = \"{v}\"")).collect::<Vec<_>>().join(", ");
                    (SpannedValue { span: span.clone(), kind: ValueKind::Table(entries) }, format!("{{ {text} }}"))
                }),
            };
            match value {
                Some((value, text)) => {
                    if let ValueKind::Table(entries) = &mut chart.kind {
                        entries.push(entry(convention.key, value, &span));
                    }
                    filled.taken.entry(index).or_default().push(Taken { key: convention.key.to_owned(), value: text });
                }
                None => {
                    filled.notes.insert((index, convention.key.to_owned()), missing_note(convention, &data));
                    filled.columns.entry(index).or_insert_with(|| columns_line(&data, &names));
                }
            }
        }
    }
    filled
}

/// A tree's columns by convention: `id` and `parent`, else `path`.
fn tree_default(has: &dyn Fn(&str) -> bool) -> Option<Vec<(&'static str, &'static str)>> {
    if has("id") && has("parent") {
        Some(vec![("id", "id"), ("parent", "parent")])
    } else if has("path") {
        Some(vec![("path", "path")])
    } else {
        None
    }
}

fn entry(key: &str, value: SpannedValue, span: &std::ops::Range<usize>) -> TableEntry {
    TableEntry { key: key.to_owned(), key_span: span.clone(), value }
}

/// Why a conventional key could not be filled: the columns looked for.
fn missing_note(convention: &Convention, data: &str) -> String {
    let looked_for = match convention.shape {
        Shape::Column(candidates) => {
            let quoted: Vec<String> = candidates.iter().map(|c| format!("`{c}`")).collect();
            format!("no column {}", quoted.join(" or "))
        }
        Shape::Tree => "no columns `id` and `parent`, or `path`,".to_owned(),
    };
    format!("data \"{data}\" has {looked_for} to take by default")
}

/// The columns a source has, for choosing among them.
fn columns_line(data: &str, names: &[String]) -> String {
    const SHOWN: usize = 12;
    let mut listed: Vec<String> = names.iter().take(SHOWN).map(|n| format!("`{n}`")).collect();
    if names.len() > SHOWN {
        listed.push(format!("… ({} in all)", names.len()));
    }
    format!("the columns of data \"{data}\" are {}", listed.join(", "))
}
