//! Nested JSON trees (`format = "tree"`): an object with a `children` array, each child an
//! object of the same shape, as d3-hierarchy and many exporters write them. The tree is
//! flattened into a table with columns `id` (preorder number), `parent` (empty for top-level
//! nodes), `path` (names joined by `/`), `name`, `depth`, and one column per scalar field found
//! on any node (numbers, or text when any value is text).

use std::collections::BTreeMap;
use std::path::Path;

use serde_json::Value;

use super::LoadError;
use super::table::{Categories, ColumnValues, Table};
use crate::spec::DataFormat;

/// Key holding a node's children.
const CHILDREN: &str = "children";
/// Columns the flattening writes itself; fields with these names are not copied.
const OWN_COLUMNS: [&str; 5] = ["id", "parent", "path", "name", "depth"];

/// Read a nested JSON tree file into a flat id/parent table.
pub fn read_tree_json(path: &Path) -> Result<Table, LoadError> {
    let origin = format!("`{}`", path.display());
    let bytes = super::compressed::read_bytes(path)?;
    super::json_scan::check_depth(&bytes, super::json_scan::MAX_TREE_DEPTH).map_err(|error| LoadError::TooDeep {
        origin: origin.clone(),
        format: DataFormat::Tree,
        error,
    })?;
    let value: Value = serde_json::from_slice(&bytes).map_err(|e| LoadError::Parse {
        origin: origin.clone(),
        format: DataFormat::Tree,
        message: e.to_string(),
    })?;
    flatten(&value).map_err(|message| LoadError::Parse { origin, format: DataFormat::Tree, message })
}

/// One node met while walking the tree.
struct Flat<'v> {
    parent: Option<usize>,
    path: String,
    name: String,
    depth: usize,
    node: &'v serde_json::Map<String, Value>,
}

/// Flatten a parsed tree (an object, or an array of top-level objects) into a table.
pub fn flatten(root: &Value) -> Result<Table, String> {
    let tops: Vec<&Value> = match root {
        Value::Array(items) => items.iter().collect(),
        other => vec![other],
    };
    // A flat array of records linked by `parent` is a table, not a nested tree: flattening it
    // would drop those links and draw every record as a top-level leaf.
    let nested = tops.iter().any(|t| t.get(CHILDREN).is_some());
    if tops.len() > 1 && !nested && tops.iter().any(|t| t.get("parent").is_some()) {
        return Err("the file is a flat array of records with `parent` fields, not a nested tree with `children`; \
                    remove `format = \"tree\"` to read it as a table, whose `id` and `parent` columns give the tree"
            .to_owned());
    }
    let mut flat: Vec<Flat> = Vec::new();
    // Depth-first, children in order, without recursion (trees can be deep).
    let mut stack: Vec<(Option<usize>, &Value, usize)> = tops.iter().rev().map(|v| (None, *v, 0)).collect();
    while let Some((parent, value, depth)) = stack.pop() {
        let Value::Object(node) = value else {
            return Err(format!("a tree node must be a JSON object, found {}", kind_of(value)));
        };
        let own = flat.len();
        let name = match node.get("name") {
            Some(Value::String(s)) => s.clone(),
            Some(Value::Number(n)) => n.to_string(),
            _ => own.to_string(),
        };
        let path = match parent {
            Some(p) => format!("{}/{}", flat[p].path, name),
            None => name.clone(),
        };
        flat.push(Flat { parent, path, name, depth, node });
        match node.get(CHILDREN) {
            None | Some(Value::Null) => {}
            Some(Value::Array(children)) => stack.extend(children.iter().rev().map(|c| (Some(own), c, depth + 1))),
            Some(other) => return Err(format!("`children` must be an array, found {}", kind_of(other))),
        }
    }
    if flat.is_empty() {
        return Err("the tree has no nodes".into());
    }
    let mut columns: Vec<(String, ColumnValues)> = vec![
        ("id".into(), ColumnValues::Number((0..flat.len()).map(|i| i as f64).collect())),
        ("parent".into(), ColumnValues::Number(flat.iter().map(|f| f.parent.map_or(f64::NAN, |p| p as f64)).collect())),
        ("path".into(), text_column(flat.iter().map(|f| Some(f.path.as_str())))),
        ("name".into(), text_column(flat.iter().map(|f| Some(f.name.as_str())))),
        ("depth".into(), ColumnValues::Number(flat.iter().map(|f| f.depth as f64).collect())),
    ];
    columns.extend(field_columns(&flat));
    Ok(Table::from_columns(columns))
}

/// One column per scalar field (other than `children` and the flattening's own columns), in
/// the order fields are first met.
fn field_columns(flat: &[Flat]) -> Vec<(String, ColumnValues)> {
    let mut order: Vec<&str> = Vec::new();
    let mut is_text: BTreeMap<&str, bool> = BTreeMap::new();
    for f in flat {
        for (key, value) in f.node {
            if key == CHILDREN || OWN_COLUMNS.contains(&key.as_str()) {
                continue;
            }
            let text = matches!(value, Value::String(_) | Value::Bool(_));
            let scalar = text || value.is_number() || value.is_null();
            if !scalar {
                continue;
            }
            match is_text.get_mut(key.as_str()) {
                Some(t) => *t |= text,
                None => {
                    order.push(key);
                    is_text.insert(key, text);
                }
            }
        }
    }
    order
        .into_iter()
        .map(|key| {
            let values = if is_text.get(key).copied().unwrap_or(false) {
                let cells: Vec<Option<String>> = flat.iter().map(|f| f.node.get(key).and_then(scalar_text)).collect();
                text_column(cells.iter().map(Option::as_deref))
            } else {
                ColumnValues::Number(
                    flat.iter().map(|f| f.node.get(key).and_then(Value::as_f64).unwrap_or(f64::NAN)).collect(),
                )
            };
            (key.to_string(), values)
        })
        .collect()
}

fn scalar_text(value: &Value) -> Option<String> {
    match value {
        Value::String(s) => Some(s.clone()),
        Value::Number(n) => Some(n.to_string()),
        Value::Bool(b) => Some(b.to_string()),
        _ => None,
    }
}

fn text_column<'a>(cells: impl IntoIterator<Item = Option<&'a str>>) -> ColumnValues {
    ColumnValues::Text(Categories::from_values(cells))
}

fn kind_of(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nested_tree_flattens_in_preorder_with_its_fields() {
        let json: Value = serde_json::from_str(
            r#"{"name": "flare", "children": [
                 {"name": "vis", "children": [{"name": "axis", "size": 10}, {"name": "legend", "size": 4, "kind": "ui"}]},
                 {"name": "util", "size": 7}]}"#,
        )
        .unwrap();
        let table = flatten(&json).unwrap();
        assert_eq!(table.rows, 5);
        assert_eq!(table.column_names(), vec!["id", "parent", "path", "name", "depth", "size", "kind"]);
        let parent = table.column("parent").unwrap().numbers().unwrap();
        assert!(parent[0].is_nan());
        assert_eq!(&parent[1..], &[0.0, 1.0, 1.0, 0.0]);
        let path = table.column("path").unwrap().categories().unwrap();
        assert_eq!(path.value(3), Some("flare/vis/legend"));
        let size = table.column("size").unwrap().numbers().unwrap();
        assert!(size[0].is_nan() && size[2] == 10.0 && size[4] == 7.0);
        assert_eq!(table.column("depth").unwrap().numbers().unwrap(), &[0.0, 1.0, 2.0, 2.0, 1.0]);
        assert_eq!(table.column("kind").unwrap().categories().unwrap().value(3), Some("ui"));
    }

    #[test]
    fn malformed_trees_say_what_is_wrong() {
        let bad: Value = serde_json::from_str(r#"{"name": "a", "children": 3}"#).unwrap();
        assert!(flatten(&bad).unwrap_err().contains("`children` must be an array"));
        let bad: Value = serde_json::from_str(r#"{"name": "a", "children": [1]}"#).unwrap();
        assert!(flatten(&bad).unwrap_err().contains("must be a JSON object, found a number"));
        let empty: Value = serde_json::from_str("[]").unwrap();
        assert!(flatten(&empty).is_err());
        // vega-datasets' flare.json: records linked by `parent`, not nested.
        let flat: Value =
            serde_json::from_str(r#"[{"id": 1, "name": "flare"}, {"id": 2, "name": "vis", "parent": 1}]"#).unwrap();
        assert!(flatten(&flat).unwrap_err().contains("remove `format = \"tree\"`"));
        // Several top-level trees are still trees.
        let forest: Value = serde_json::from_str(r#"[{"name": "a", "children": []}, {"name": "b"}]"#).unwrap();
        assert_eq!(flatten(&forest).unwrap().rows, 2);
    }
}
