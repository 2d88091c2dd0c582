//! Transform problems as spec diagnostics: at the step's key or value, or at the exact part of
//! an expression when the expression is written as a plain TOML string.

use std::ops::Range;

use super::TransformError;
use super::plan::PlanError;
use crate::spec::{Diagnostic, PathSeg, SpecDoc};

/// The diagnostic of a plan problem, pointing into the spec text `text`.
pub fn to_diagnostic(error: &PlanError, doc: &SpecDoc, text: &str) -> Diagnostic {
    match error {
        PlanError::Load { source, error } => {
            let key = ["path", "values"].into_iter().find(|k| doc.get(&super::plan::source_path(source, k)).is_some());
            let span = key.and_then(|k| doc.span_of(&super::plan::source_path(source, k)));
            Diagnostic::error(format!("data \"{source}\": {error}")).with_hint(error.hint()).at_opt(span)
        }
        PlanError::Transform(e) => transform_diagnostic(e, doc, text),
    }
}

fn transform_diagnostic(e: &TransformError, doc: &SpecDoc, text: &str) -> Diagnostic {
    let source = match e.path.get(1) {
        Some(PathSeg::Key(name)) => name.as_str(),
        _ => "?",
    };
    let mut d = Diagnostic::error(format!("data \"{source}\": {}", e.message));
    if !e.hint.is_empty() {
        d = d.with_hint(e.hint.clone());
    }
    // The deepest part of the path the spec has.
    let mut path = e.path.clone();
    while !path.is_empty() {
        let span = if e.at_key { doc.key_span_of(&path).or_else(|| doc.span_of(&path)) } else { doc.span_of(&path) };
        if let Some(span) = span {
            let exact = path.len() == e.path.len();
            let place = match (&e.inner, exact) {
                (Some(inner), true) => inside_string(text, &span, inner).unwrap_or(span),
                _ => span,
            };
            return d.at(place);
        }
        path.pop();
    }
    d
}

/// The byte range of `inner` (a range of the string's value) in the spec text, when the string
/// is written without escapes so its value is its text.
fn inside_string(text: &str, span: &Range<usize>, inner: &Range<usize>) -> Option<Range<usize>> {
    let written = text.get(span.clone())?;
    let quote = written.chars().next()?;
    let body = match quote {
        '\'' => written.strip_prefix('\'')?.strip_suffix('\'')?,
        '"' if !written.contains('\\') => written.strip_prefix('"')?.strip_suffix('"')?,
        _ => return None,
    };
    if inner.end > body.len() || written.starts_with("\"\"\"") || written.starts_with("'''") {
        return None;
    }
    let start = span.start + 1 + inner.start;
    let end = (span.start + 1 + inner.end).max(start + 1).min(span.start + 1 + body.len());
    Some(start..end.max(start))
}
