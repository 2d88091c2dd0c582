//! Lint: "good visualization" rules checked against what the reader will actually see.
//!
//! Each rule lives in its own file under [`rules`] and is a pure function over a [`Subject`]:
//! the chart's spec, its data table and the scene it drew (every mark, tick label, legend entry
//! and title, with glyph boxes measured by the same font that draws them). A rule returns
//! [`Issue`]s; [`lint_chart`] stamps them with the rule's stable code, its severity (after the
//! spec's `[lint]` configuration) and the chart's name, giving [`Finding`]s.
//!
//! Codes are grouped by what they protect:
//! - `SC` scale shown explicitly with good labelling (axes, ticks, units, legends);
//! - `LB` labelling (titles, overlapping, clipped, tiny or low-contrast text);
//! - `DI` data integrity (baselines, size encodings, log scales, hidden rows, aspect ratio);
//! - `CL` colour (rainbow maps, diverging midpoints, colour-vision deficiencies, too many hues);
//! - `CM` comparison (shared scales for small multiples, overplotting);
//! - `TQ` technique-specific checks (treemaps, graphs, contours, flow, faces).
//!
//! Configuration: `[lint] allow = [...]` drops findings of the named rules (codes or names),
//! `deny = [...]` raises them to errors; a chart's own `lint = { allow, deny }` applies on top.

pub mod chart_info;
pub mod geometry;
pub mod output;
pub mod rules;

use std::fmt;

use crate::data::Table;
use crate::mark::ChartOutput;
use crate::spec::{Chart, LintConfig, PathSeg};

/// How serious a finding is. Errors make `dataink lint` exit with code 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// Misleads the reader or hides data: the chart should not ship as it is.
    Error,
    /// Makes the chart harder to read correctly.
    Warning,
    /// Advice; worth a look.
    Note,
}

impl Severity {
    /// The lowercase name used in every output format.
    pub fn name(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The principle a rule protects.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Category {
    /// Show the scale explicitly, with good labelling.
    Scale,
    /// Label clearly and legibly.
    Labelling,
    /// Preserve the integrity of the data.
    Integrity,
    /// Use colour that encodes faithfully and reads for everyone.
    Colour,
    /// Enable comparison.
    Comparison,
    /// Checks particular to one technique.
    Technique,
}

impl Category {
    /// The lowercase name.
    pub fn name(self) -> &'static str {
        match self {
            Category::Scale => "scale",
            Category::Labelling => "labelling",
            Category::Integrity => "integrity",
            Category::Colour => "colour",
            Category::Comparison => "comparison",
            Category::Technique => "technique",
        }
    }
}

/// What a rule looks at: one drawn chart.
#[derive(Clone, Copy)]
pub struct Subject<'a> {
    /// The chart's spec.
    pub chart: &'a Chart,
    /// The chart's position among the spec's `[[chart]]` tables (0-based).
    pub index: usize,
    /// The chart's data table (edges for the network kinds).
    pub table: &'a Table,
    /// The node table of a network chart, when the spec names one.
    pub nodes: Option<&'a Table>,
    /// The drawn chart: scene, derived geometry and drawing warnings.
    pub output: &'a ChartOutput,
}

/// One problem a rule found, before the engine stamps it with the rule and chart.
#[derive(Clone, Debug, PartialEq)]
pub struct Issue {
    /// The element concerned, as a reader would name it (e.g. "x axis", "title", "legend").
    pub element: String,
    /// What is wrong, with the numbers that show it.
    pub message: String,
    /// How to fix it, naming the spec key to change where there is one.
    pub hint: String,
    /// The spec key the issue is about, relative to the chart (`"x.scale"`, `"title"`); empty
    /// for the chart table itself.
    pub key: String,
}

impl Issue {
    /// An issue about `element` at the chart key `key`.
    pub fn new(
        element: impl Into<String>,
        key: impl Into<String>,
        message: impl Into<String>,
        hint: impl Into<String>,
    ) -> Issue {
        Issue { element: element.into(), message: message.into(), hint: hint.into(), key: key.into() }
    }
}

/// A lint rule: a stable code, a name, a default severity and the check itself.
pub struct Rule {
    /// Stable code, e.g. `LB001`; never reused for another rule.
    pub code: &'static str,
    /// Short kebab-case name, e.g. `missing-title`; accepted wherever a code is.
    pub name: &'static str,
    /// The principle it protects.
    pub category: Category,
    /// Severity unless the spec's `deny` raises it.
    pub severity: Severity,
    /// One sentence saying what the rule checks (docs, SARIF rule descriptions).
    pub summary: &'static str,
    /// The check.
    pub check: fn(&Subject<'_>) -> Vec<Issue>,
}

impl fmt::Debug for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Rule({} {})", self.code, self.name)
    }
}

/// A finding: an issue stamped with its rule, chart and final severity.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Finding {
    /// The rule's code, e.g. `LB001`.
    pub code: &'static str,
    /// The rule's name, e.g. `missing-title`.
    pub rule: &'static str,
    /// Severity after the spec's configuration.
    pub severity: Severity,
    /// The chart's name.
    pub chart: String,
    /// The element concerned.
    pub element: String,
    /// What is wrong.
    pub message: String,
    /// How to fix it.
    pub hint: String,
    /// Where in the spec, as a dotted path (`chart[2].x.scale`).
    pub path: String,
    /// 1-based line in the spec file, when the path could be placed.
    pub line: Option<usize>,
    /// 1-based column in the spec file, when the path could be placed.
    pub column: Option<usize>,
    /// The spec path as segments (for placing it in the file).
    #[serde(skip)]
    pub segments: Vec<PathSeg>,
}

/// The findings of one chart.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct ChartLint {
    /// The chart's name.
    pub chart: String,
    /// Findings that stand, most severe first.
    pub findings: Vec<Finding>,
    /// Findings dropped by an `allow` entry (kept for reports).
    pub allowed: Vec<Finding>,
}

impl ChartLint {
    /// Number of findings of `severity`.
    pub fn count(&self, severity: Severity) -> usize {
        self.findings.iter().filter(|f| f.severity == severity).count()
    }

    /// One line: `name: 1 error, 2 warnings (LB001, SC004)` or `name: clean`.
    pub fn summary_line(&self) -> String {
        let (e, w, n) = (self.count(Severity::Error), self.count(Severity::Warning), self.count(Severity::Note));
        if self.findings.is_empty() {
            return match self.allowed.len() {
                0 => format!("{}: clean", self.chart),
                n => format!("{}: clean ({n} allowed by the spec)", self.chart),
            };
        }
        let mut codes: Vec<&str> = self.findings.iter().map(|f| f.code).collect();
        codes.dedup();
        let plural = |n: usize, word: &str| format!("{n} {word}{}", if n == 1 { "" } else { "s" });
        format!(
            "{}: {}, {}, {} ({})",
            self.chart,
            plural(e, "error"),
            plural(w, "warning"),
            plural(n, "note"),
            codes.join(", ")
        )
    }
}

/// The rule with code or name `key` (case-insensitive).
pub fn find_rule(key: &str) -> Option<&'static Rule> {
    let key = key.trim();
    rules::ALL.iter().copied().find(|r| r.code.eq_ignore_ascii_case(key) || r.name.eq_ignore_ascii_case(key))
}

/// Every code and name, for "did you mean" hints.
pub fn rule_keys() -> Vec<&'static str> {
    rules::ALL.iter().flat_map(|r| [r.code, r.name]).collect()
}

/// What the configuration does to a rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Verdict {
    /// Findings are dropped (kept as allowed).
    Allow,
    /// Findings become errors.
    Deny,
    /// Default severity.
    Default,
}

/// The verdict of the spec-wide then the chart's configuration for `rule`: the chart's own entry
/// wins over the spec's.
fn verdict(rule: &Rule, spec: Option<&LintConfig>, chart: Option<&LintConfig>) -> Verdict {
    let named = |list: &Option<Vec<String>>| {
        list.as_ref().is_some_and(|l| l.iter().any(|k| find_rule(k).is_some_and(|r| r.code == rule.code)))
    };
    let mut v = Verdict::Default;
    for config in [spec, chart].into_iter().flatten() {
        if named(&config.allow) {
            v = Verdict::Allow;
        }
        if named(&config.deny) {
            v = Verdict::Deny;
        }
    }
    v
}

/// Run every rule on one chart under the spec-wide configuration `spec_config` (the chart's own
/// `lint` table is read from the chart).
pub fn lint_chart(subject: &Subject<'_>, spec_config: Option<&LintConfig>) -> ChartLint {
    let mut out = ChartLint { chart: subject.chart.name.clone(), ..ChartLint::default() };
    for rule in rules::ALL {
        let issues = (rule.check)(subject);
        if issues.is_empty() {
            continue;
        }
        let v = verdict(rule, spec_config, subject.chart.lint.as_ref());
        for issue in issues {
            let segments = crate::spec::chart_path(subject.index, &issue.key);
            let finding = Finding {
                code: rule.code,
                rule: rule.name,
                severity: if v == Verdict::Deny { Severity::Error } else { rule.severity },
                chart: subject.chart.name.clone(),
                element: issue.element,
                message: issue.message,
                hint: issue.hint,
                path: crate::spec::source::display_path(&segments),
                line: None,
                column: None,
                segments,
            };
            if v == Verdict::Allow { out.allowed.push(finding) } else { out.findings.push(finding) }
        }
    }
    out.findings.sort_by(|a, b| a.severity.cmp(&b.severity).then(a.code.cmp(b.code)));
    out
}

/// Whether a run with these results fails: any error, or with `deny_warnings` any warning.
pub fn fails(results: &[ChartLint], deny_warnings: bool) -> bool {
    results
        .iter()
        .flat_map(|c| &c.findings)
        .any(|f| f.severity == Severity::Error || (deny_warnings && f.severity == Severity::Warning))
}

#[cfg(test)]
pub(crate) mod test_support {
    //! Subjects built from a hand-made scene, for rules whose trigger dataink itself never draws
    //! (its layout prevents it), so the rule is checked on the geometry it reads.

    use crate::data::Table;
    use crate::mark::ChartOutput;
    use crate::scene::Scene;
    use crate::spec::{Chart, SourceFile, parse_spec};

    /// A minimal scatter chart spec (title "T").
    pub fn chart() -> Chart {
        let text = "[data.d]\nvalues = [{ x = 1, y = 2 }]\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\ntitle = \"T\"\nx = \"x\"\ny = \"y\"\n";
        let parsed = parse_spec(&SourceFile::new("t.toml", text)).expect("a valid spec");
        parsed.spec.chart.into_iter().next().expect("one chart")
    }

    /// The chart's output with `scene`.
    pub fn output(scene: Scene) -> ChartOutput {
        ChartOutput {
            scene,
            derived: Default::default(),
            warnings: Vec::new(),
            meshes: Vec::new(),
            geojson: None,
            volume: None,
            geometry: Default::default(),
        }
    }

    /// Run `check` on `scene` under [`chart`] with an empty table.
    pub fn issues(check: fn(&super::Subject<'_>) -> Vec<super::Issue>, scene: Scene) -> Vec<super::Issue> {
        let chart = chart();
        let table = Table::default();
        let out = output(scene);
        check(&super::Subject { chart: &chart, index: 0, table: &table, nodes: None, output: &out })
    }
}
