//! Lint results written for people and for CI: plain text, JSON, SARIF 2.1.0 (code-scanning
//! uploads) and JUnit XML (test-report widgets). Every user string is escaped for its format.

use serde_json::{Value, json};

use super::{ChartLint, Finding, Severity, rules};

/// Plain text, one finding per block:
/// `spec.toml:12:1: warning[LB001] chart "x": message` followed by the hint, then a summary line.
pub fn text(spec_path: &str, results: &[ChartLint]) -> String {
    let mut out = String::new();
    for f in results.iter().flat_map(|c| &c.findings) {
        out.push_str(&format!(
            "{}: {}[{} {}] chart \"{}\", {}: {}\n  hint: {}\n",
            place(spec_path, f),
            f.severity,
            f.code,
            f.rule,
            clean(&f.chart),
            clean(&f.element),
            clean(&f.message),
            clean(&f.hint)
        ));
    }
    out.push_str(&totals(results));
    out.push('\n');
    out
}

/// `file:line:col`, or just the file when the finding has no place.
fn place(spec_path: &str, f: &Finding) -> String {
    match (f.line, f.column) {
        (Some(l), Some(c)) => format!("{spec_path}:{l}:{c}"),
        _ => spec_path.to_string(),
    }
}

/// Hidden characters dropped ([`crate::visible`]), so user text cannot move a terminal's cursor
/// or reorder what it shows.
fn clean(s: &str) -> String {
    crate::visible::single_line(s).into_owned()
}

/// `3 charts linted: 1 error, 2 warnings, 0 notes (1 allowed)`.
pub fn totals(results: &[ChartLint]) -> String {
    let count = |s: Severity| results.iter().map(|c| c.count(s)).sum::<usize>();
    let allowed: usize = results.iter().map(|c| c.allowed.len()).sum();
    let plural = |n: usize, w: &str| format!("{n} {w}{}", if n == 1 { "" } else { "s" });
    format!(
        "{} linted: {}, {}, {}{}",
        plural(results.len(), "chart"),
        plural(count(Severity::Error), "error"),
        plural(count(Severity::Warning), "warning"),
        plural(count(Severity::Note), "note"),
        if allowed > 0 { format!(" ({allowed} allowed by the spec)") } else { String::new() }
    )
}

/// JSON: `{ "spec": ..., "charts": [{ "chart", "findings": [...], "allowed": [...] }], "errors", "warnings", "notes" }`.
pub fn json(spec_path: &str, results: &[ChartLint]) -> String {
    let count = |s: Severity| results.iter().map(|c| c.count(s)).sum::<usize>();
    let doc = json!({
        "spec": spec_path,
        "charts": results,
        "errors": count(Severity::Error),
        "warnings": count(Severity::Warning),
        "notes": count(Severity::Note),
    });
    serde_json::to_string_pretty(&doc).unwrap_or_default()
}

/// SARIF 2.1.0 with one run: every rule in the driver, one result per finding located in the
/// spec file (relative path as given), so code-scanning shows it on the spec's line.
pub fn sarif(spec_path: &str, results: &[ChartLint]) -> String {
    let rules: Vec<Value> = rules::ALL
        .iter()
        .map(|r| {
            json!({
                "id": r.code,
                "name": r.name,
                "shortDescription": { "text": r.summary },
                "defaultConfiguration": { "level": level(r.severity) },
                "properties": { "category": r.category.name() },
            })
        })
        .collect();
    let uri = spec_path.replace('\\', "/");
    let sarif_results: Vec<Value> = results
        .iter()
        .flat_map(|c| &c.findings)
        .map(|f| {
            let mut region = json!({});
            if let (Some(l), Some(c)) = (f.line, f.column) {
                region = json!({ "startLine": l, "startColumn": c });
            }
            json!({
                "ruleId": f.code,
                "ruleIndex": rules::ALL.iter().position(|r| r.code == f.code).unwrap_or(0),
                "level": level(f.severity),
                "message": { "text": format!("chart \"{}\", {}: {} Hint: {}", f.chart, f.element, f.message, f.hint) },
                "locations": [{
                    "physicalLocation": {
                        "artifactLocation": { "uri": uri },
                        "region": region,
                    },
                    "logicalLocations": [{ "name": f.chart, "fullyQualifiedName": f.path, "kind": "object" }],
                }],
            })
        })
        .collect();
    let doc = json!({
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [{
            "tool": { "driver": {
                "name": "dataink",
                "version": env!("CARGO_PKG_VERSION"),
                "informationUri": "https://crates.io/crates/dataink",
                "rules": rules,
            }},
            "results": sarif_results,
        }],
    });
    serde_json::to_string_pretty(&doc).unwrap_or_default()
}

/// SARIF's level for a severity.
fn level(s: Severity) -> &'static str {
    match s {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Note => "note",
    }
}

/// JUnit XML: one test suite per spec, one test case per chart; a chart with error findings
/// (or, with `deny_warnings`, warnings) fails, and every finding is listed in its output.
pub fn junit(spec_path: &str, results: &[ChartLint], deny_warnings: bool) -> String {
    let failing = |f: &Finding| f.severity == Severity::Error || (deny_warnings && f.severity == Severity::Warning);
    let failures = results.iter().filter(|c| c.findings.iter().any(failing)).count();
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    out.push_str(&format!("<testsuites name=\"dataink lint\" tests=\"{}\" failures=\"{failures}\">\n", results.len()));
    out.push_str(&format!(
        "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failures}\" errors=\"0\" skipped=\"0\">\n",
        xml(spec_path),
        results.len()
    ));
    for c in results {
        out.push_str(&format!("    <testcase classname=\"{}\" name=\"{}\"", xml(spec_path), xml(&c.chart)));
        if c.findings.is_empty() {
            out.push_str("/>\n");
            continue;
        }
        out.push_str(">\n");
        let lines: Vec<String> = c
            .findings
            .iter()
            .map(|f| {
                format!(
                    "{}: {}[{} {}] {}: {} (hint: {})",
                    place(spec_path, f),
                    f.severity,
                    f.code,
                    f.rule,
                    f.element,
                    f.message,
                    f.hint
                )
            })
            .collect();
        let failed: Vec<&Finding> = c.findings.iter().filter(|f| failing(f)).collect();
        if let Some(first) = failed.first() {
            out.push_str(&format!(
                "      <failure type=\"{}\" message=\"{}\">{}</failure>\n",
                first.code,
                xml(&format!("{} finding(s) fail the lint; first: {}", failed.len(), first.message)),
                xml_lines(&lines)
            ));
        } else {
            out.push_str(&format!("      <system-out>{}</system-out>\n", xml_lines(&lines)));
        }
        out.push_str("    </testcase>\n");
    }
    out.push_str("  </testsuite>\n</testsuites>\n");
    out
}

/// Text escaped for XML attributes and content (control characters dropped).
fn xml(s: &str) -> String {
    crate::render::svg::escape(s)
}

/// Lines escaped one by one and joined with newlines, for element content.
fn xml_lines(lines: &[String]) -> String {
    lines.iter().map(|l| xml(l)).collect::<Vec<_>>().join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn finding(severity: Severity, chart: &str, message: &str) -> Finding {
        Finding {
            code: "LB001",
            rule: "missing-title",
            severity,
            chart: chart.to_string(),
            element: "title".into(),
            message: message.into(),
            hint: "add `title`".into(),
            path: "chart[0]".into(),
            line: Some(3),
            column: Some(1),
            segments: Vec::new(),
        }
    }

    fn results() -> Vec<ChartLint> {
        vec![
            ChartLint {
                chart: "a".into(),
                findings: vec![finding(Severity::Error, "a", "x < y & \"z\"")],
                allowed: vec![],
            },
            ChartLint {
                chart: "b<'>".into(),
                findings: vec![finding(Severity::Warning, "b<'>", "w")],
                allowed: vec![],
            },
            ChartLint { chart: "c".into(), findings: vec![], allowed: vec![] },
        ]
    }

    #[test]
    fn junit_counts_failing_charts_and_escapes_names() {
        let x = junit("spec.toml", &results(), false);
        assert!(x.contains("tests=\"3\" failures=\"1\""), "{x}");
        assert!(x.contains("name=\"b&lt;&apos;&gt;\""), "{x}");
        assert!(x.contains("x &lt; y &amp; &quot;z&quot;"), "{x}");
        assert!(!x.contains("x < y"), "{x}");
        let strict = junit("spec.toml", &results(), true);
        assert!(strict.contains("failures=\"2\""), "{strict}");
    }

    #[test]
    fn sarif_places_results_on_the_spec_line() {
        let doc: Value = serde_json::from_str(&sarif("dir/spec.toml", &results())).expect("valid JSON");
        assert_eq!(doc["version"], "2.1.0");
        let res = &doc["runs"][0]["results"];
        assert_eq!(res.as_array().map(Vec::len), Some(2));
        assert_eq!(res[0]["level"], "error");
        assert_eq!(res[1]["level"], "warning");
        assert_eq!(res[0]["locations"][0]["physicalLocation"]["region"]["startLine"], 3);
        assert_eq!(res[0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"], "dir/spec.toml");
        let rules = doc["runs"][0]["tool"]["driver"]["rules"].as_array().cloned().unwrap_or_default();
        assert_eq!(rules.len(), rules::ALL.len());
    }

    #[test]
    fn text_ends_with_totals() {
        let t = text("spec.toml", &results());
        assert!(t.starts_with("spec.toml:3:1: error[LB001 missing-title] chart \"a\""), "{t}");
        assert!(t.trim_end().ends_with("3 charts linted: 1 error, 1 warning, 0 notes"), "{t}");
    }
}
