//! The JSON Schema of the spec (`dataink schema`), generated from the same types the validator uses.
//!
//! schemars' output is post-processed so that it describes TOML files exactly:
//! - `null` is dropped from optional fields (TOML has no null; leaving a key out is how to omit it);
//! - `Chart`, a struct with a `#[serde(flatten)]`ed, internally tagged `kind`, comes out of schemars
//!   as common `properties` plus a `oneOf` whose branches pair a `kind` const with a `$ref` to the
//!   kind's options. Such a schema cannot be closed (`additionalProperties` only sees sibling
//!   `properties`), so each branch is rebuilt as one closed object holding the common keys, `kind`
//!   and that kind's keys;
//! - every object schema with `properties` gets `additionalProperties: false`, so editors flag
//!   unknown keys the way the validator does;
//! - `$defs` no longer referenced (the inlined option structs) are dropped.

use std::collections::BTreeSet;
use std::sync::OnceLock;

use serde_json::{Map, Value};

use super::types::Spec;

/// The spec's JSON Schema (draft 2020-12), closed against unknown keys.
pub fn spec_schema() -> Value {
    schema_ref().clone()
}

/// The schema, built once.
pub(crate) fn schema_ref() -> &'static Value {
    static SCHEMA: OnceLock<Value> = OnceLock::new();
    SCHEMA.get_or_init(build)
}

fn build() -> Value {
    let mut schema = schemars::schema_for!(Spec).to_value();
    strip_null(&mut schema);
    merge_flattened_variants(&mut schema);
    close_objects(&mut schema);
    drop_unused_defs(&mut schema);
    schema
}

/// Calls `f` on every subschema directly inside `schema` (not on `schema` itself).
fn for_each_subschema(schema: &mut Value, f: &mut dyn FnMut(&mut Value)) {
    let Some(obj) = schema.as_object_mut() else { return };
    for (key, child) in obj.iter_mut() {
        match key.as_str() {
            "properties" | "$defs" | "definitions" | "patternProperties" => {
                if let Some(map) = child.as_object_mut() {
                    map.values_mut().for_each(&mut *f);
                }
            }
            "anyOf" | "oneOf" | "allOf" | "prefixItems" => {
                if let Some(list) = child.as_array_mut() {
                    list.iter_mut().for_each(&mut *f);
                }
            }
            "items" | "additionalProperties" | "not" | "if" | "then" | "else" | "contains" if child.is_object() => {
                f(child);
            }
            _ => {}
        }
    }
}

fn is_null_schema(v: &Value) -> bool {
    v.get("type").and_then(Value::as_str) == Some("null") && v.as_object().is_some_and(|o| o.len() == 1)
}

/// Removes `null` from types, `{type: null}` alternatives and `default: null`.
fn strip_null(schema: &mut Value) {
    if let Some(obj) = schema.as_object_mut() {
        if obj.get("default").is_some_and(Value::is_null) {
            obj.remove("default");
        }
        if let Some(Value::Array(types)) = obj.get_mut("type") {
            types.retain(|t| t.as_str() != Some("null"));
            if let [only] = types.as_slice() {
                let only = only.clone();
                obj.insert("type".to_owned(), only);
            }
        }
        for key in ["anyOf", "oneOf"] {
            let Some(Value::Array(branches)) = obj.get_mut(key) else { continue };
            let before = branches.len();
            branches.retain(|b| !is_null_schema(b));
            if branches.len() < before
                && branches.len() == 1
                && let Some(Value::Object(only)) = branches.pop()
            {
                obj.remove(key);
                for (k, v) in only {
                    obj.entry(k).or_insert(v);
                }
            }
        }
    }
    for_each_subschema(schema, &mut strip_null);
}

/// Rebuilds every `$defs` entry that has both `properties` and a `oneOf` of tagged branches
/// (serde's `flatten` of an internally tagged enum) as a `oneOf` of closed, self-contained objects.
fn merge_flattened_variants(schema: &mut Value) {
    let Some(defs) = schema.get("$defs").and_then(Value::as_object).cloned() else { return };
    let mut rebuilt = Map::new();
    for (name, def) in &defs {
        let (Some(common), Some(branches)) =
            (def.get("properties").and_then(Value::as_object), def.get("oneOf").and_then(Value::as_array))
        else {
            continue;
        };
        let mut new_branches = Vec::with_capacity(branches.len());
        for branch in branches {
            let target = branch
                .get("$ref")
                .and_then(Value::as_str)
                .and_then(|r| r.strip_prefix("#/$defs/"))
                .and_then(|r| defs.get(r));
            let mut properties = common.clone();
            let mut required: Vec<Value> = Vec::new();
            let mut push_required = |list: Option<&Value>| {
                for r in list.and_then(Value::as_array).into_iter().flatten() {
                    if !required.contains(r) {
                        required.push(r.clone());
                    }
                }
            };
            push_required(def.get("required"));
            push_required(branch.get("required"));
            push_required(target.and_then(|t| t.get("required")));
            let description = branch.get("description").cloned();
            for (k, v) in branch.get("properties").and_then(Value::as_object).into_iter().flatten() {
                let mut v = v.clone();
                // The tag (`kind`) documents the variant it selects.
                if let (Some(obj), Some(d)) = (v.as_object_mut(), &description) {
                    obj.entry("description").or_insert(d.clone());
                }
                properties.insert(k.clone(), v);
            }
            for (k, v) in target.and_then(|t| t.get("properties")).and_then(Value::as_object).into_iter().flatten() {
                properties.insert(k.clone(), v.clone());
            }
            let mut new = Map::new();
            if let Some(d) = description {
                new.insert("description".to_owned(), d);
            }
            new.insert("type".to_owned(), "object".into());
            new.insert("properties".to_owned(), Value::Object(properties));
            new.insert("required".to_owned(), Value::Array(required));
            new.insert("additionalProperties".to_owned(), false.into());
            new_branches.push(Value::Object(new));
        }
        let mut new_def = def.as_object().cloned().unwrap_or_default();
        new_def.remove("properties");
        new_def.remove("required");
        new_def.insert("oneOf".to_owned(), Value::Array(new_branches));
        rebuilt.insert(name.clone(), Value::Object(new_def));
    }
    if let Some(defs) = schema.get_mut("$defs").and_then(Value::as_object_mut) {
        defs.extend(rebuilt);
    }
}

/// Adds `additionalProperties: false` to every object schema with `properties` that has none.
fn close_objects(schema: &mut Value) {
    if let Some(obj) = schema.as_object_mut()
        && obj.contains_key("properties")
        && !obj.contains_key("additionalProperties")
    {
        obj.insert("additionalProperties".to_owned(), false.into());
    }
    for_each_subschema(schema, &mut close_objects);
}

fn collect_refs(schema: &Value, out: &mut BTreeSet<String>) {
    match schema {
        Value::Object(obj) => {
            for (k, v) in obj {
                if k == "$ref" {
                    if let Some(name) = v.as_str().and_then(|r| r.strip_prefix("#/$defs/")) {
                        out.insert(name.to_owned());
                    }
                } else if k != "$defs" && k != "examples" && k != "default" && k != "const" {
                    collect_refs(v, out);
                }
            }
        }
        Value::Array(items) => items.iter().for_each(|v| collect_refs(v, out)),
        _ => {}
    }
}

/// Removes `$defs` entries that nothing references any more.
fn drop_unused_defs(schema: &mut Value) {
    let Some(defs) = schema.get("$defs").and_then(Value::as_object).cloned() else { return };
    let mut used = BTreeSet::new();
    collect_refs(schema, &mut used);
    let mut queue: Vec<String> = used.iter().cloned().collect();
    while let Some(name) = queue.pop() {
        let mut more = BTreeSet::new();
        if let Some(def) = defs.get(&name) {
            collect_refs(def, &mut more);
        }
        for m in more {
            if used.insert(m.clone()) {
                queue.push(m);
            }
        }
    }
    if let Some(defs) = schema.get_mut("$defs").and_then(Value::as_object_mut) {
        defs.retain(|name, _| used.contains(name));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn def<'a>(schema: &'a Value, name: &str) -> &'a Value {
        &schema["$defs"][name]
    }

    #[test]
    fn chart_branches_are_closed_and_complete() {
        let schema = spec_schema();
        let chart = def(&schema, "Chart");
        assert!(chart.get("properties").is_none(), "common keys are merged into the branches");
        let branches = chart["oneOf"].as_array().cloned().unwrap_or_default();
        let names: Vec<&str> = crate::mark::registry::names().collect();
        assert_eq!(branches.len(), names.len());
        for (branch, kind) in branches.iter().zip(&names) {
            assert_eq!(branch["additionalProperties"], false);
            assert_eq!(branch["type"], "object");
            assert_eq!(branch["properties"]["kind"]["const"], *kind);
            for key in ["name", "data", "title", "caption", "size", "font_size", "kind"] {
                assert!(branch["properties"].get(key).is_some(), "{kind} lacks {key}");
            }
            let required: Vec<&str> =
                branch["required"].as_array().into_iter().flatten().filter_map(Value::as_str).collect();
            assert_eq!(required[..3], ["name", "data", "kind"], "{kind}");
            let own: &[&str] = match *kind {
                "hyperslice" => &["axes", "z"],
                "splom" | "parallel" | "daisy" | "segments" => &["columns"],
                "faces" | "slice" | "volume" => &[],
                "isosurface" => &["levels"],
                "box" | "violin" => &["y"],
                "histogram" => &["x"],
                "treemap" | "hypertree" => &["tree"],
                "graph" => &["source", "target"],
                "linkmap" => &["source", "target", "weight"],
                "flow" => &["x", "y", "u", "v"],
                "contour" | "image" | "section" | "scattered" | "surface" => &["x", "y", "z"],
                _ => &["x", "y"],
            };
            assert_eq!(required[3..], *own, "{kind}");
        }
        assert!(branches[0]["properties"].get("opacity").is_some());
        assert!(branches[0]["properties"].get("series").is_none());
        assert!(branches[1]["properties"].get("series").is_some());
        assert!(schema["$defs"].get("ScatterOptions").is_none(), "inlined defs are dropped");
    }

    #[test]
    fn every_object_with_properties_is_closed() {
        fn walk(schema: &Value, count: &mut usize) {
            if schema.get("properties").is_some() {
                *count += 1;
                assert_eq!(schema["additionalProperties"], false, "{schema}");
            }
            if let Some(obj) = schema.as_object() {
                for (k, v) in obj {
                    if k != "examples" {
                        match v {
                            Value::Object(m) if k == "properties" || k == "$defs" => {
                                m.values().for_each(|s| walk(s, count))
                            }
                            Value::Array(list) => list.iter().for_each(|s| walk(s, count)),
                            Value::Object(_) => walk(v, count),
                            _ => {}
                        }
                    }
                }
            }
        }
        let schema = spec_schema();
        let mut count = 0;
        walk(&schema, &mut count);
        // Spec, DataSource, Selection, LintConfig, ChannelOptions, ColorOptions, SizeOptions,
        // FaceFeatures, TreeSource, NodeTable, TransformStep, TrendOptions, LineBandOptions,
        // BarLabelOptions, FacetOptions, FacetResolve, Annotation, PlaneSpec, ValueColor,
        // ValueLabel, VolumeLabel and one branch per kind.
        assert_eq!(count, 21 + crate::mark::registry::KINDS.len());
        // Maps stay open: any data source name, any column in inline rows.
        assert_eq!(schema["properties"]["data"]["additionalProperties"]["$ref"], "#/$defs/DataSource");
        assert_eq!(def(&schema, "DataSource")["properties"]["values"]["items"]["additionalProperties"], true);
    }

    #[test]
    fn no_null_and_descriptions_from_doc_comments() {
        let schema = spec_schema();
        let text = schema.to_string();
        assert!(!text.contains("\"null\""), "TOML has no null");
        assert_eq!(schema["description"], "A whole spec file: named data sources and the charts drawn from them.");
        let scatter = &def(&schema, "Chart")["oneOf"][0];
        assert_eq!(
            scatter["properties"]["size"]["description"],
            "Canvas size `[width, height]` in CSS pixels, each at most 16384 (default: the kind's own, `[640, 420]` for one x/y frame)."
        );
        assert_eq!(scatter["properties"]["size"]["type"], "array");
        assert_eq!(
            scatter["properties"]["kind"]["description"],
            "Points at (x, y), optionally coloured and sized by columns."
        );
        assert_eq!(scatter["properties"]["color"]["$ref"], "#/$defs/ColorChannel");
        let scale = &def(&schema, "ChannelOptions")["properties"]["scale"];
        assert_eq!(scale["$ref"], "#/$defs/ScaleKind");
        assert!(scale.get("anyOf").is_none());
        assert_eq!(def(&schema, "Channel")["anyOf"][0]["type"], "string");
        assert_eq!(def(&schema, "Channel")["anyOf"][1]["$ref"], "#/$defs/ChannelOptions");
        assert_eq!(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
    }
}
