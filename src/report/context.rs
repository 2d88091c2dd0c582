//! The values a report template sees. Every string is plain text, escaped by the template
//! engine on output; only [`ChartEntry::svg`] is marked safe, because it is our own renderer's
//! output, which escapes every user string itself.

use minijinja::Value;
use serde::Serialize;

use super::provenance::Provenance;
use crate::lint::{Finding, Severity};
use crate::pipeline::{Linted, Loaded};

/// Everything a report template can use (documented in `templates/README.md`).
#[derive(Debug, Serialize)]
pub struct Context {
    /// The spec's `title`, or the spec file's name when it has none.
    pub title: String,
    /// The spec file.
    pub spec: SpecEntry,
    /// dataink's version.
    pub version: &'static str,
    /// When the report was made, UTC, RFC 3339 (`2025-01-31T12:00:00Z`).
    pub generated: String,
    /// Whether warnings fail the run (`--deny-warnings`).
    pub deny_warnings: bool,
    /// Totals over every chart.
    pub summary: Summary,
    /// Every reported chart, in spec order.
    pub charts: Vec<ChartEntry>,
    /// Every data source, in name order.
    pub data: Vec<Provenance>,
}

/// The spec file: its path and text.
#[derive(Debug, Serialize)]
pub struct SpecEntry {
    /// The path as given on the command line.
    pub path: String,
    /// The whole text.
    pub text: String,
    /// The text split into numbered lines (for line anchors).
    pub lines: Vec<Line>,
}

/// One numbered line of the spec.
#[derive(Debug, Serialize)]
pub struct Line {
    /// 1-based line number.
    pub number: usize,
    /// The line's text, without its line break.
    pub text: String,
}

/// Totals over every reported chart.
#[derive(Debug, Default, Serialize)]
pub struct Summary {
    /// Number of charts.
    pub charts: usize,
    /// Error findings.
    pub errors: usize,
    /// Warning findings.
    pub warnings: usize,
    /// Note findings.
    pub notes: usize,
    /// Findings dropped by `allow` entries.
    pub allowed: usize,
    /// Whether the run passes: no errors (and no warnings under `deny_warnings`).
    pub passed: bool,
}

/// One chart of the report.
#[derive(Debug, Serialize)]
pub struct ChartEntry {
    /// The chart's `name`.
    pub name: String,
    /// The HTML id of the chart's section (`chart-NAME`).
    pub anchor: String,
    /// The chart's `title`, if any.
    pub title: Option<String>,
    /// The chart's `kind`.
    pub kind: &'static str,
    /// 1-based spec line of the chart's `name` key, if found.
    pub line: Option<usize>,
    /// The chart as an inline SVG element (safe: escaped by the renderer).
    pub svg: Value,
    /// `"error"`, `"warning"`, `"note"` or `"clean"`: the most severe finding.
    pub status: &'static str,
    /// Error findings.
    pub errors: usize,
    /// Warning findings.
    pub warnings: usize,
    /// Note findings.
    pub notes: usize,
    /// Findings that stand, most severe first.
    pub findings: Vec<FindingEntry>,
    /// Findings dropped by an `allow` entry in the spec.
    pub allowed: Vec<FindingEntry>,
    /// Notes from drawing the chart (dropped rows, folded levels).
    pub drawing_notes: Vec<String>,
}

/// One lint finding as templates see it: every field of the finding (`severity`, `code`,
/// `rule`, `element`, `message`, `hint`, `path`, `line`, `column`) plus its `location`.
#[derive(Debug, Serialize)]
pub struct FindingEntry {
    /// The finding itself.
    #[serde(flatten)]
    pub finding: Finding,
    /// `line:column`, or empty when the finding has no place.
    pub location: String,
}

impl FindingEntry {
    fn new(f: &Finding) -> FindingEntry {
        FindingEntry {
            finding: f.clone(),
            location: match (f.line, f.column) {
                (Some(l), Some(c)) => format!("{l}:{c}"),
                (Some(l), None) => l.to_string(),
                _ => String::new(),
            },
        }
    }
}

/// Build the context of one report.
pub fn build(
    loaded: &Loaded,
    linted: &[Linted],
    data: Vec<Provenance>,
    deny_warnings: bool,
    generated: String,
) -> Context {
    let charts: Vec<ChartEntry> = linted.iter().map(|l| chart_entry(loaded, l)).collect();
    let total = |s: Severity| linted.iter().map(|l| l.lint.count(s)).sum::<usize>();
    let (errors, warnings) = (total(Severity::Error), total(Severity::Warning));
    let summary = Summary {
        charts: charts.len(),
        errors,
        warnings,
        notes: total(Severity::Note),
        allowed: linted.iter().map(|l| l.lint.allowed.len()).sum(),
        // The same rule as `lint::fails`.
        passed: errors == 0 && !(deny_warnings && warnings > 0),
    };
    let path = loaded.source.path.display().to_string();
    let title = match &loaded.spec.title {
        Some(t) if !t.trim().is_empty() => t.clone(),
        _ => loaded.source.path.file_name().map_or_else(|| path.clone(), |n| n.to_string_lossy().into_owned()),
    };
    let lines = loaded
        .source
        .text
        .lines()
        .enumerate()
        .map(|(i, text)| Line { number: i + 1, text: text.to_string() })
        .collect();
    Context {
        title,
        spec: SpecEntry { path, text: loaded.source.text.clone(), lines },
        version: env!("CARGO_PKG_VERSION"),
        generated,
        deny_warnings,
        summary,
        charts,
        data,
    }
}

/// One chart's entry: its SVG, counts and findings.
fn chart_entry(loaded: &Loaded, linted: &Linted) -> ChartEntry {
    let chart = loaded.spec.chart.get(linted.index);
    let name = linted.lint.chart.clone();
    let lint = &linted.lint;
    let (errors, warnings, notes) =
        (lint.count(Severity::Error), lint.count(Severity::Warning), lint.count(Severity::Note));
    let status = if errors > 0 {
        "error"
    } else if warnings > 0 {
        "warning"
    } else if notes > 0 {
        "note"
    } else {
        "clean"
    };
    let line = loaded
        .doc
        .key_span_of(&crate::spec::chart_path(linted.index, "name"))
        .map(|span| loaded.source.line_col(span.start).0);
    let svg = crate::render::svg::to_svg(&linted.output.scene);
    ChartEntry {
        anchor: format!("chart-{}", anchor_text(&name)),
        title: chart.and_then(|c| c.title.clone()),
        kind: chart.map_or("", |c| c.kind.name()),
        line,
        svg: Value::from_safe_string(inline_svg(&svg, linted.index)),
        status,
        errors,
        warnings,
        notes,
        findings: lint.findings.iter().map(FindingEntry::new).collect(),
        allowed: lint.allowed.iter().map(FindingEntry::new).collect(),
        drawing_notes: linted.output.warnings.iter().map(ToString::to_string).collect(),
        name,
    }
}

/// A chart name as an HTML id: names are already restricted to letters, digits, `-`, `_` and
/// `.`, but anything else is replaced so the id stays valid whatever the name.
fn anchor_text(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') { c } else { '_' }).collect()
}

/// Our renderer's standalone SVG document made fit to sit inside an HTML page: the XML
/// declaration is dropped, and the clip-path ids (numbered from 0 in every document) get the
/// chart's index so that charts on one page do not clip each other.
///
/// Only the renderer's own attribute spellings are rewritten; user text inside the SVG is
/// XML-escaped (no raw `"`), so it can never match them.
pub fn inline_svg(svg: &str, index: usize) -> String {
    let body = match svg.strip_prefix("<?xml") {
        Some(rest) => rest.split_once("?>").map_or(svg, |(_, after)| after.trim_start()),
        None => svg,
    };
    body.replace("id=\"dataink-clip-", &format!("id=\"dataink-c{index}-clip-"))
        .replace("clip-path=\"url(#dataink-clip-", &format!("clip-path=\"url(#dataink-c{index}-clip-"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inline_svg_drops_the_declaration_and_numbers_clip_ids_per_chart() {
        let svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg><clipPath id=\"dataink-clip-0\"><rect/></clipPath>\
                   <g clip-path=\"url(#dataink-clip-0)\"><text>id=&quot;dataink-clip-0</text></g></svg>\n";
        let out = inline_svg(svg, 3);
        assert!(out.starts_with("<svg>"), "{out}");
        assert!(out.contains("<clipPath id=\"dataink-c3-clip-0\">"), "{out}");
        assert!(out.contains("clip-path=\"url(#dataink-c3-clip-0)\""), "{out}");
        // Escaped user text is left alone.
        assert!(out.contains("<text>id=&quot;dataink-clip-0</text>"), "{out}");
        assert!(!out.contains("\"dataink-clip-"), "{out}");
    }

    #[test]
    fn anchors_are_valid_ids() {
        assert_eq!(anchor_text("iris-scatter.v2"), "iris-scatter.v2");
        assert_eq!(anchor_text("a b\"<c>"), "a_b__c_");
    }
}
