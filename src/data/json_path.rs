//! JSON files as people have them: an array of records (read by polars as it is), records one
//! per line, an array found inside the top-level object by a dotted `json_path`
//! (`"nodes"`, `"data.rows"`, `"items.0.values"`), or a grid stored as an object with exactly the
//! keys `width`, `height` and `values` (row-major numbers, `values[row * width + column]`), which
//! is read like a `.npy` grid into `x`, `y`, `value` columns.
//!
//! Nesting deeper than [`MAX_RECORD_DEPTH`] levels is refused before any parser runs, and
//! integers too wide for an `i64` are read as text ([`super::json_scan`]).

use std::io::Cursor;

use polars::prelude::*;
use serde_json::Value;

use super::json_scan::{MAX_RECORD_DEPTH, TooDeep, quote_wide_integers, scan};
use super::load::first_line;
use super::matrix::{MAX_CELLS, Matrix};
use crate::spec::suggest::did_you_mean;

/// The keys (all of them, no others) of an object read as a grid.
pub const GRID_KEYS: [&str; 3] = ["height", "values", "width"];

/// What a JSON file holds.
#[derive(Debug)]
pub enum JsonContent {
    /// Records, one row each.
    Frame(DataFrame),
    /// A `{ width, height, values }` grid.
    Grid(Matrix),
}

/// Why a JSON file could not be read.
#[derive(Debug, PartialEq)]
pub enum JsonError {
    /// The text is not JSON, or the records do not fit one table. The message says why.
    Syntax(String),
    /// A `json_path` step, or what it leads to, is wrong; `hint` lists what exists.
    Path {
        /// What is wrong.
        message: String,
        /// How to fix it (the keys that exist, a "did you mean").
        hint: String,
    },
    /// Arrays and objects nest deeper than [`MAX_RECORD_DEPTH`].
    TooDeep(TooDeep),
}

/// Read JSON bytes; `lines` for newline-delimited records (`.jsonl`, `.ndjson`).
pub fn read_json(bytes: &[u8], json_path: Option<&str>, lines: bool) -> Result<JsonContent, JsonError> {
    let long_integer = scan(bytes, MAX_RECORD_DEPTH).map_err(JsonError::TooDeep)?.long_integer;
    let first = bytes.iter().find(|b| !b.is_ascii_whitespace() && **b != 0xef && **b != 0xbb && **b != 0xbf);
    match (json_path, lines, first) {
        (None, true, _) => return records(bytes, JsonFormat::JsonLines, long_integer).map(JsonContent::Frame),
        (None, false, Some(b'[')) => return records(bytes, JsonFormat::Json, long_integer).map(JsonContent::Frame),
        (Some(_), true, _) => {
            return Err(JsonError::Path {
                message: "`json_path` needs one JSON document, not records one per line".into(),
                hint: "remove `json_path`, or store the file as a single JSON object".into(),
            });
        }
        _ => {}
    }
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let root: Value = match serde_json::from_slice(text) {
        Ok(v) => v,
        // Several objects one after another: records one per line in a `.json` file.
        Err(e) if json_path.is_none() && e.to_string().starts_with("trailing characters") => {
            return records(bytes, JsonFormat::JsonLines, long_integer).map(JsonContent::Frame);
        }
        Err(e) => return Err(JsonError::Syntax(e.to_string())),
    };
    let target = match json_path {
        Some(path) => select(&root, path)?,
        None => &root,
    };
    match target {
        Value::Array(_) => {
            let bytes = serde_json::to_vec(target).map_err(|e| JsonError::Syntax(e.to_string()))?;
            records(&bytes, JsonFormat::Json, long_integer).map(JsonContent::Frame)
        }
        Value::Object(map) if is_grid(map) => grid(map).map(JsonContent::Grid).map_err(JsonError::Syntax),
        Value::Object(map) => {
            let keys: Vec<&str> = map.keys().map(String::as_str).collect();
            let arrays: Vec<&str> = map.iter().filter(|(_, v)| v.is_array()).map(|(k, _)| k.as_str()).collect();
            let at = json_path.map_or("the file".to_string(), |p| format!("`json_path = \"{p}\"`"));
            let hint = match (arrays.first(), json_path) {
                (Some(first), None) => {
                    format!("name its array of records with json_path = \"{first}\"; {}", listing(&keys))
                }
                (Some(first), Some(p)) => {
                    format!("go one step further, e.g. json_path = \"{p}.{first}\"; {}", listing(&keys))
                }
                (None, _) => listing(&keys),
            };
            Err(JsonError::Path {
                message: format!("{at} holds an object, not an array of records or a {{ width, height, values }} grid"),
                hint,
            })
        }
        other => Err(JsonError::Path {
            message: format!(
                "{} holds {}, not an array of records",
                json_path.map_or("the file".to_string(), |p| format!("`json_path = \"{p}\"`")),
                kind_of(other)
            ),
            hint: "point json_path at an array of objects".into(),
        }),
    }
}

/// Follow a dotted path (`a.b`, `items.0`) from the top-level value.
pub fn select<'v>(root: &'v Value, path: &str) -> Result<&'v Value, JsonError> {
    let mut here = root;
    let mut walked: Vec<&str> = Vec::new();
    for step in path.split('.') {
        let at = if walked.is_empty() { "the top level".to_string() } else { format!("`{}`", walked.join(".")) };
        here = match here {
            Value::Object(map) => match map.get(step) {
                Some(v) => v,
                None => {
                    let keys: Vec<&str> = map.keys().map(String::as_str).collect();
                    let hint = match did_you_mean(step, keys.iter().copied()) {
                        Some(best) => format!("did you mean `{}`? {}", crate::excerpt::quote(best), listing(&keys)),
                        None => listing(&keys),
                    };
                    return Err(JsonError::Path { message: format!("{at} has no key `{step}`"), hint });
                }
            },
            Value::Array(items) => match step.parse::<usize>().ok().and_then(|i| items.get(i)) {
                Some(v) => v,
                None => {
                    return Err(JsonError::Path {
                        message: format!("{at} is an array of {} items; `{step}` is not an index into it", items.len()),
                        hint: format!(
                            "use an index from 0 to {}, or end json_path before it",
                            items.len().saturating_sub(1)
                        ),
                    });
                }
            },
            other => {
                return Err(JsonError::Path {
                    message: format!("{at} holds {}, which has no key `{step}`", kind_of(other)),
                    hint: "end json_path before this step".into(),
                });
            }
        };
        walked.push(step);
    }
    Ok(here)
}

/// "keys: `a`, `b`", bounded by [`crate::excerpt::list`].
fn listing(keys: &[&str]) -> String {
    if keys.is_empty() {
        return "the object has no keys".into();
    }
    format!("keys: {}", crate::excerpt::list(keys.iter().copied(), true))
}

fn kind_of(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "text",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Records (an array of objects, or objects one per line) into a frame through polars; integers
/// wider than an `i64` are read as text.
fn records(bytes: &[u8], format: JsonFormat, long_integer: bool) -> Result<DataFrame, JsonError> {
    let bytes = if long_integer { quote_wide_integers(bytes) } else { std::borrow::Cow::Borrowed(bytes) };
    JsonReader::new(Cursor::new(&*bytes))
        .with_json_format(format)
        .infer_schema_len(None)
        .finish()
        .map_err(|e| JsonError::Syntax(first_line(&e)))
}

fn is_grid(map: &serde_json::Map<String, Value>) -> bool {
    map.len() == GRID_KEYS.len() && GRID_KEYS.iter().all(|k| map.contains_key(*k))
}

/// A `{ width, height, values }` object as a matrix (`height` rows of `width` columns).
fn grid(map: &serde_json::Map<String, Value>) -> Result<Matrix, String> {
    let size = |key: &str| -> Result<usize, String> {
        map.get(key)
            .and_then(Value::as_u64)
            .filter(|&n| n > 0)
            .and_then(|n| usize::try_from(n).ok())
            .ok_or_else(|| format!("grid `{key}` must be a whole number above 0"))
    };
    let (cols, rows) = (size("width")?, size("height")?);
    let cells = cols
        .checked_mul(rows)
        .filter(|&n| n <= MAX_CELLS)
        .ok_or_else(|| format!("the grid has {cols} × {rows} cells, more than {MAX_CELLS}"))?;
    let Some(Value::Array(items)) = map.get("values") else {
        return Err("grid `values` must be an array of numbers".into());
    };
    if items.len() != cells {
        return Err(format!("grid `values` has {} numbers; width {cols} × height {rows} needs {cells}", items.len()));
    }
    let mut values = Vec::with_capacity(cells);
    for (i, item) in items.iter().enumerate() {
        values.push(match item {
            Value::Number(n) => n.as_f64().unwrap_or(f64::NAN),
            Value::Null => f64::NAN,
            other => return Err(format!("grid `values` item {i} is {}, not a number", kind_of(other))),
        });
    }
    Ok(Matrix { rows, cols, values })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(content: Result<JsonContent, JsonError>) -> DataFrame {
        match content {
            Ok(JsonContent::Frame(df)) => df,
            other => panic!("expected records, got {other:?}"),
        }
    }

    const GRAPH: &str = r#"{"nodes": [{"name": "a", "group": 1}, {"name": "b", "group": 2}],
        "links": [{"source": 0, "target": 1, "value": 3}],
        "meta": {"deep": {"rows": [{"v": 1}, {"v": 2}, {"v": 3}]}}}"#;

    #[test]
    fn a_path_selects_an_array_inside_the_object() {
        let nodes = frame(read_json(GRAPH.as_bytes(), Some("nodes"), false));
        assert_eq!(nodes.height(), 2);
        assert_eq!(nodes.get_column_names(), ["name", "group"]);
        let links = frame(read_json(GRAPH.as_bytes(), Some("links"), false));
        assert_eq!(links.height(), 1);
        let deep = frame(read_json(GRAPH.as_bytes(), Some("meta.deep.rows"), false));
        assert_eq!(
            deep.column("v").expect("v").as_materialized_series().i64().expect("ints").to_vec(),
            [Some(1), Some(2), Some(3)]
        );
        let graph: serde_json::Value = serde_json::from_str(GRAPH).expect("json");
        let second = select(&graph, "nodes.1.name").expect("index");
        assert_eq!(second, "b");
    }

    #[test]
    fn an_unknown_key_lists_the_keys_that_exist() {
        let err = read_json(GRAPH.as_bytes(), Some("node"), false).expect_err("no such key");
        assert_eq!(
            err,
            JsonError::Path {
                message: "the top level has no key `node`".into(),
                hint: "did you mean `nodes`? keys: `nodes`, `links`, `meta`".into(),
            }
        );
        let JsonError::Path { message, .. } = read_json(GRAPH.as_bytes(), Some("meta.deep.cols"), false).expect_err("")
        else {
            panic!("a path error")
        };
        assert_eq!(message, "`meta.deep` has no key `cols`");
        let JsonError::Path { message, .. } = read_json(GRAPH.as_bytes(), Some("nodes.7"), false).expect_err("") else {
            panic!("a path error")
        };
        assert_eq!(message, "`nodes` is an array of 2 items; `7` is not an index into it");
    }

    #[test]
    fn an_object_without_a_path_says_which_array_to_name() {
        let JsonError::Path { message, hint } = read_json(GRAPH.as_bytes(), None, false).expect_err("an object") else {
            panic!("a path error")
        };
        assert_eq!(message, "the file holds an object, not an array of records or a { width, height, values } grid");
        assert_eq!(hint, "name its array of records with json_path = \"nodes\"; keys: `nodes`, `links`, `meta`");
        let JsonError::Path { message, .. } = read_json(GRAPH.as_bytes(), Some("links.0.value"), false).expect_err("")
        else {
            panic!("a path error")
        };
        assert_eq!(message, "`json_path = \"links.0.value\"` holds a number, not an array of records");
    }

    #[test]
    fn a_width_height_values_object_is_a_grid() {
        let text = r#"{"width": 3, "height": 2, "values": [1, 2, 3, 4, null, 6.5]}"#;
        let Ok(JsonContent::Grid(m)) = read_json(text.as_bytes(), None, false) else { panic!("a grid") };
        assert_eq!((m.rows, m.cols), (2, 3));
        assert_eq!(m.values[..4], [1.0, 2.0, 3.0, 4.0]);
        assert!(m.values[4].is_nan());
        let table = m.to_table(None);
        // Row-major: the fourth value lies at x = 0 on the second row.
        assert_eq!(table.column("x").and_then(|c| c.numbers()).map(|v| v[3]), Some(0.0));
        assert_eq!(table.column("y").and_then(|c| c.numbers()).map(|v| v[3]), Some(1.0));
        let nested = r#"{"grid": {"width": 2, "height": 1, "values": [5, 6]}}"#;
        assert!(matches!(read_json(nested.as_bytes(), Some("grid"), false), Ok(JsonContent::Grid(_))));
    }

    #[test]
    fn bad_grids_and_bad_json_are_errors() {
        let short = r#"{"width": 3, "height": 2, "values": [1, 2, 3]}"#;
        assert_eq!(
            read_json(short.as_bytes(), None, false).expect_err("short"),
            JsonError::Syntax("grid `values` has 3 numbers; width 3 × height 2 needs 6".into())
        );
        let zero = r#"{"width": 0, "height": 2, "values": []}"#;
        assert_eq!(
            read_json(zero.as_bytes(), None, false).expect_err("zero"),
            JsonError::Syntax("grid `width` must be a whole number above 0".into())
        );
        let truncated = r#"{"nodes": [{"name": "a"}, {"na"#;
        let JsonError::Syntax(m) = read_json(truncated.as_bytes(), Some("nodes"), false).expect_err("cut") else {
            panic!("a syntax error")
        };
        assert!(m.starts_with("EOF while parsing"), "{m}");
        let deep = format!("{}{}", "[".repeat(200), "]".repeat(200));
        let JsonError::TooDeep(e) = read_json(format!("{{\"a\": {deep}}}").as_bytes(), Some("a"), false).expect_err("")
        else {
            panic!("a depth error")
        };
        assert_eq!((e.depth, e.offset, e.limit), (201, 69, MAX_RECORD_DEPTH));
    }

    #[test]
    fn records_one_per_line_read_with_or_without_the_extension() {
        let text = "{\"x\": 1}\n{\"x\": 2}\n";
        assert_eq!(frame(read_json(text.as_bytes(), None, true)).height(), 2);
        assert_eq!(frame(read_json(text.as_bytes(), None, false)).height(), 2);
    }
}
