//! The OpenAPI 3.1 description of the server's API, served at `/api/openapi.json`.

use serde_json::{Value, json};

/// The API's description.
pub fn document() -> Value {
    let body = json!({
        "required": true,
        "content": {
            "application/toml": { "schema": { "type": "string", "description": "the spec; data paths resolve under the server's root" } },
            "multipart/form-data": { "schema": {
                "type": "object",
                "required": ["spec"],
                "properties": { "spec": { "type": "string", "description": "the spec (TOML)" } },
                "additionalProperties": { "type": "string", "format": "binary", "description": "a data file; its file name is the path the spec gives (a plain name)" }
            } }
        }
    });
    let problem = json!({ "application/json": { "schema": { "$ref": "#/components/schemas/Problem" } } });
    let errors = json!({
        "400": { "description": "the request is malformed (query, form, file name, text encoding)", "content": problem },
        "413": { "description": "the body, the spec or the number of files is over the server's limit", "content": problem },
        "422": { "description": "the spec has errors, or asks for more rows or pixels than the server draws", "content": problem },
        "503": { "description": "no render slot came free in time, or the render ran past the time limit", "content": problem }
    });
    json!({
        "openapi": "3.1.0",
        "info": { "title": "dataink serve", "version": env!("CARGO_PKG_VERSION"),
                  "description": "Declarative charts over HTTP: post a spec, get the chart, its lint findings or its diagnostics." },
        "paths": {
            "/api/render": { "post": {
                "summary": "Draw one chart (or lint every chart, or build the report page)",
                "parameters": [
                    { "name": "format", "in": "query", "schema": { "type": "string", "enum": ["svg", "png", "csv", "lint", "sarif", "report"], "default": "svg" } },
                    { "name": "chart", "in": "query", "description": "the chart's name; the first chart when absent (every chart for lint, sarif and report)", "schema": { "type": "string" } },
                    { "name": "scale", "in": "query", "description": "device pixels per CSS pixel for PNG", "schema": { "type": "number", "minimum": 0.25, "maximum": 8, "default": 1 } }
                ],
                "requestBody": body,
                "responses": merge(json!({
                    "200": { "description": "the answer; header X-Dataink-Cache says hit or miss", "content": {
                        "image/svg+xml": {}, "image/png": {}, "text/csv": {}, "application/json": {}, "application/sarif+json": {}, "text/html": {} } }
                }), &errors)
            } },
            "/api/check": { "post": {
                "summary": "Check a spec and load its data: the diagnostics (warnings on success, errors with 422)",
                "requestBody": body,
                "responses": merge(json!({
                    "200": { "description": "the spec is valid", "content": { "application/json": { "schema": {
                        "type": "object", "properties": { "charts": { "type": "array", "items": { "type": "string" }, "description": "the spec's charts by name, in order" }, "diagnostics": { "type": "array", "items": { "$ref": "#/components/schemas/Diagnostic" } } } } } } }
                }), &errors)
            } },
            "/api/openapi.json": { "get": { "summary": "This description", "responses": { "200": { "description": "OpenAPI 3.1" } } } },
            "/": { "get": { "summary": "The browser page: a spec editor with the chart drawn as you type", "responses": { "200": { "description": "HTML", "content": { "text/html": {} } } } } }
        },
        "components": { "schemas": {
            "Diagnostic": { "type": "object", "required": ["severity", "message"], "properties": {
                "severity": { "type": "string", "enum": ["error", "warning"] },
                "message": { "type": "string" },
                "line": { "type": "integer", "description": "1-based" },
                "column": { "type": "integer", "description": "1-based, in characters" },
                "end_line": { "type": "integer" }, "end_column": { "type": "integer" },
                "label": { "type": "string" }, "hint": { "type": "string" } } },
            "Problem": { "type": "object", "required": ["error"], "properties": {
                "error": { "type": "string" },
                "diagnostics": { "type": "array", "items": { "$ref": "#/components/schemas/Diagnostic" } } } }
        } }
    })
}

fn merge(mut a: Value, b: &Value) -> Value {
    if let (Some(a), Some(b)) = (a.as_object_mut(), b.as_object()) {
        for (k, v) in b {
            a.insert(k.clone(), v.clone());
        }
    }
    a
}
