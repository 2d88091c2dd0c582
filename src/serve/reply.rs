//! What the server answers: a finished body with its type, a problem as JSON (with the spec's
//! diagnostics at their lines and columns), and the headers every response carries.

use axum::body::Body;
use axum::http::header::{self, HeaderValue};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use serde_json::{Value, json};

use super::Limits;
use crate::spec::{Diagnostic, SourceFile};

/// The Content-Security-Policy of every response: nothing from elsewhere, no inline script, no
/// framing. (Pages the server sends later load their own script and style from the server.)
pub const CONTENT_SECURITY_POLICY: &str = "default-src 'none'; script-src 'self'; style-src 'self' 'unsafe-inline'; \
     img-src 'self' data: blob:; font-src 'self' data:; connect-src 'self'; base-uri 'none'; form-action 'self'; \
     frame-ancestors 'none'";

/// A finished answer: status, content type and body.
#[derive(Clone, Debug)]
pub struct Reply {
    /// The HTTP status.
    pub status: StatusCode,
    /// The body's media type.
    pub content_type: &'static str,
    /// The body.
    pub body: axum::body::Bytes,
}

impl Reply {
    /// A 200 answer.
    pub fn ok(content_type: &'static str, body: impl Into<axum::body::Bytes>) -> Reply {
        Reply { status: StatusCode::OK, content_type, body: body.into() }
    }

    /// The response, saying whether it came from the cache.
    pub fn into_response_marked(self, cached: bool) -> Response {
        let mut response =
            (self.status, [(header::CONTENT_TYPE, self.content_type)], Body::from(self.body)).into_response();
        let mark = if cached { "hit" } else { "miss" };
        response.headers_mut().insert("x-dataink-cache", HeaderValue::from_static(mark));
        response
    }
}

/// A request the server will not or cannot answer as asked, with the reason as JSON.
#[derive(Debug)]
pub struct Problem {
    /// The HTTP status.
    pub status: StatusCode,
    /// The JSON body.
    pub body: Value,
}

impl Problem {
    /// A problem with one message.
    pub fn new(status: StatusCode, message: impl Into<String>) -> Problem {
        Problem { status, body: json!({ "error": message.into() }) }
    }

    /// A spec that failed its checks (422): every diagnostic with its place in `source`.
    pub fn diagnostics(source: &SourceFile, diagnostics: &[Diagnostic]) -> Problem {
        let first = diagnostics.iter().find(|d| d.is_error()).or(diagnostics.first());
        let message = first.map_or_else(|| "the spec has errors".to_string(), |d| d.message.clone());
        Problem {
            status: StatusCode::UNPROCESSABLE_ENTITY,
            body: json!({ "error": message, "diagnostics": diagnostics_json(source, diagnostics) }),
        }
    }

    /// No render slot came free in time (503).
    pub fn busy(limits: &Limits) -> Problem {
        Problem::new(
            StatusCode::SERVICE_UNAVAILABLE,
            format!(
                "the server is busy: no render slot came free within {} s; try again",
                limits.render_time.as_secs_f64()
            ),
        )
    }

    /// The render ran past its time (503).
    pub fn too_slow(limits: &Limits) -> Problem {
        Problem::new(
            StatusCode::SERVICE_UNAVAILABLE,
            format!(
                "the render took longer than the server's limit of {} s and was abandoned; draw fewer rows or a smaller chart",
                limits.render_time.as_secs_f64()
            ),
        )
    }
}

impl IntoResponse for Problem {
    fn into_response(self) -> Response {
        json(self.status, &self.body)
    }
}

/// A JSON response.
pub fn json(status: StatusCode, value: &Value) -> Response {
    let text = serde_json::to_string_pretty(value).unwrap_or_default();
    (status, [(header::CONTENT_TYPE, "application/json")], text).into_response()
}

/// A JSON error response with one message.
pub fn error_json(status: StatusCode, message: &str) -> Response {
    Problem::new(status, message).into_response()
}

/// Diagnostics as JSON: severity, message, the place (1-based line and column of the start and
/// end, when the problem has one), label and hint.
pub fn diagnostics_json(source: &SourceFile, diagnostics: &[Diagnostic]) -> Vec<Value> {
    diagnostics
        .iter()
        .map(|d| {
            let mut entry = json!({
                "severity": if d.is_error() { "error" } else { "warning" },
                "message": d.message,
            });
            if let Some(span) = &d.span {
                let (line, column) = source.line_col(span.start);
                let (end_line, end_column) = source.line_col(span.end);
                entry["line"] = json!(line);
                entry["column"] = json!(column);
                entry["end_line"] = json!(end_line);
                entry["end_column"] = json!(end_column);
            }
            if let Some(label) = &d.label {
                entry["label"] = json!(label);
            }
            if let Some(hint) = &d.hint {
                entry["hint"] = json!(hint);
            }
            entry
        })
        .collect()
}

/// Add the headers every response carries: the content security policy, no sniffing of types,
/// no referrer, and no caching by browsers of answers that depend on what was posted.
pub async fn secure(mut response: Response) -> Response {
    let headers: &mut HeaderMap = response.headers_mut();
    headers.insert(header::CONTENT_SECURITY_POLICY, HeaderValue::from_static(CONTENT_SECURITY_POLICY));
    headers.insert(header::X_CONTENT_TYPE_OPTIONS, HeaderValue::from_static("nosniff"));
    headers.insert(header::REFERRER_POLICY, HeaderValue::from_static("no-referrer"));
    headers.insert(header::X_FRAME_OPTIONS, HeaderValue::from_static("DENY"));
    headers.entry(header::CACHE_CONTROL).or_insert(HeaderValue::from_static("no-store"));
    response
}
