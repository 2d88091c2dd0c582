//! The spec: what a `dataink` TOML file may say, and turning its text into a checked [`Spec`].
//!
//! [`parse_spec`] parses the text keeping positions ([`source`]), checks it against the JSON
//! Schema generated from the types ([`schema`], [`validate`]) and only then deserializes it. Every
//! problem found becomes a [`Diagnostic`] with a place in the file; all of them are reported at
//! once. The parsed [`SpecDoc`] is kept so later stages can point at the spec too
//! (see [`SpecDoc::span_of`] and [`chart_path`]).

pub mod annotation;
pub mod defaults;
pub mod diagnostic;
pub(crate) mod foreign;
pub mod schema;
pub mod source;
pub mod suggest;
pub mod transform;
pub mod types;
pub mod validate;

pub use annotation::{Annotation, AxisPlace, AxisValue, TextAnchor};
pub use diagnostic::{Diagnostic, Severity, SourceFile, render_all};
pub use schema::spec_schema;
pub use source::{PathSeg, SpannedValue, SpecDoc, TableEntry, ValueKind};
pub use transform::TransformStep;
pub use types::*;

/// A spec that passed every check, with its parsed text for pointing at places later.
#[derive(Clone, Debug, PartialEq)]
pub struct ParsedSpec {
    /// The typed spec.
    pub spec: Spec,
    /// The parsed text with positions, e.g. for `doc.span_of(&chart_path(2, "x"))`.
    pub doc: SpecDoc,
    /// Problems that do not stop the spec from working (e.g. chart names differing only in case).
    pub warnings: Vec<Diagnostic>,
}

/// Everything checking a spec found, for callers that go on despite errors (e.g. to check data
/// columns of the valid parts in the same run).
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    /// The typed spec, when there were no errors.
    pub spec: Option<Spec>,
    /// The parsed text with positions, when the TOML itself parsed.
    pub doc: Option<SpecDoc>,
    /// Every problem found, errors and warnings, in file order.
    pub diagnostics: Vec<Diagnostic>,
}

/// Parses and checks a spec, keeping whatever could be made of it.
pub fn check(source: &SourceFile) -> Checked {
    match SpecDoc::parse(&source.text) {
        Ok(doc) => {
            let diagnostics = validate::validate(&doc);
            typed(doc, diagnostics)
        }
        Err(d) => Checked { spec: None, doc: None, diagnostics: vec![d] },
    }
}

/// [`check`], except that chart keys with a conventional default column ([`defaults`]) may be
/// missing. When one is (the flag), the spec is not typed yet: fill the defaults once the data is
/// loaded ([`defaults::fill`]) and check it again with [`check_filled`].
pub fn check_deferring(source: &SourceFile) -> (Checked, bool) {
    match SpecDoc::parse(&source.text) {
        Ok(doc) => {
            let (diagnostics, deferred) = validate::validate_deferring(&doc);
            if deferred {
                let mut diagnostics = diagnostics;
                sort_by_position(&mut diagnostics);
                (Checked { spec: None, doc: Some(doc), diagnostics }, true)
            } else {
                (typed(doc, diagnostics), false)
            }
        }
        Err(d) => (Checked { spec: None, doc: None, diagnostics: vec![d] }, false),
    }
}

/// Checks a spec whose conventional defaults [`defaults::fill`] has written in, in full: keys
/// still missing are errors with the fill's notes in their hints (except in charts whose data did
/// not load, which stay untyped).
pub fn check_filled(doc: SpecDoc, filled: &defaults::Filled) -> Checked {
    let (mut diagnostics, pending) = validate::validate_noted(&doc, filled);
    if pending {
        sort_by_position(&mut diagnostics);
        return Checked { spec: None, doc: Some(doc), diagnostics };
    }
    typed(doc, diagnostics)
}

/// The typed spec of a checked document, unless `diagnostics` hold an error.
fn typed(doc: SpecDoc, mut diagnostics: Vec<Diagnostic>) -> Checked {
    sort_by_position(&mut diagnostics);
    if diagnostics.iter().any(Diagnostic::is_error) {
        return Checked { spec: None, doc: Some(doc), diagnostics };
    }
    match serde_json::from_value::<Spec>(doc.to_json()) {
        Ok(spec) => Checked { spec: Some(spec), doc: Some(doc), diagnostics },
        Err(e) => {
            diagnostics.push(
                Diagnostic::error(format!("the spec could not be read: {e}"))
                    .with_hint("the checks missed this; please report it to dataink with the spec"),
            );
            Checked { spec: None, doc: Some(doc), diagnostics }
        }
    }
}

/// Parses, checks and deserializes a spec; on failure returns every problem found, in file order.
pub fn parse_spec(source: &SourceFile) -> Result<ParsedSpec, Vec<Diagnostic>> {
    let checked = check(source);
    match (checked.spec, checked.doc) {
        (Some(spec), Some(doc)) => Ok(ParsedSpec { spec, doc, warnings: checked.diagnostics }),
        _ => Err(checked.diagnostics),
    }
}

/// Sorts diagnostics by where they point (those without a place last), keeping ties in order.
pub fn sort_by_position(diags: &mut [Diagnostic]) {
    diags.sort_by_key(|d| d.span.as_ref().map_or(usize::MAX, |s| s.start));
}

/// The path of a key in the chart at `index` (0-based): `chart_path(2, "x")` is `chart[2].x`.
///
/// `key` may be dotted (`"x.field"`); an empty `key` gives the chart table itself.
pub fn chart_path(index: usize, key: &str) -> Vec<PathSeg> {
    let mut path = vec![PathSeg::Key("chart".to_owned()), PathSeg::Index(index)];
    path.extend(key.split('.').filter(|k| !k.is_empty()).map(|k| PathSeg::Key(k.to_owned())));
    path
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use serde_json::{Value, json};

    use super::*;

    fn source(text: &str) -> SourceFile {
        SourceFile::new("spec.toml", text)
    }

    fn errors(text: &str) -> Vec<Diagnostic> {
        match parse_spec(&source(text)) {
            Ok(parsed) => panic!("expected errors, got {:?}", parsed.spec),
            Err(diags) => diags,
        }
    }

    fn parse_ok(text: &str) -> ParsedSpec {
        match parse_spec(&source(text)) {
            Ok(parsed) => parsed,
            Err(diags) => panic!("{}", render_all(&source(text), &diags)),
        }
    }

    /// (message, line, column, underlined text, label) of each diagnostic.
    fn summary(text: &str, diags: &[Diagnostic]) -> Vec<(String, usize, usize, String, Option<String>)> {
        let src = source(text);
        diags
            .iter()
            .map(|d| {
                let span = d.span.clone().unwrap_or(0..0);
                let (line, col) = src.line_col(span.start);
                let marked = text.get(span).unwrap_or("").to_owned();
                (d.message.clone(), line, col, marked, d.label.clone())
            })
            .collect()
    }

    const THREE_MISTAKES: &str = r#"title = "Iris"

[data.iris]
path = "data/iris.csv"

[[chart]]
name = "iris-scatter"
data = "iris"
kind = "scatter"
x = "sepal_length"
y = "petal_length"
colour = "species"
size = "big"

[[chart]]
name = "petals"
data = "iris"
kind = "scater"
x = "petal_length"
y = "petal_width"
"#;

    #[test]
    fn three_mistakes_reported_in_one_run() {
        let diags = errors(THREE_MISTAKES);
        assert_eq!(
            summary(THREE_MISTAKES, &diags),
            vec![
                (
                    "unknown key `colour` in chart \"iris-scatter\"".to_owned(),
                    12,
                    1,
                    "colour".to_owned(),
                    Some("did you mean `color`?".to_owned())
                ),
                ("`size` must be an array of 2 numbers, found a string".to_owned(), 13, 8, "\"big\"".to_owned(), None),
                (
                    "unknown chart kind `scater`; did you mean `scatter`?".to_owned(),
                    18,
                    8,
                    "\"scater\"".to_owned(),
                    None
                ),
            ]
        );
        assert!(diags.iter().all(Diagnostic::is_error));
        assert_eq!(
            diags[0].hint.as_deref(),
            Some(
                "keys allowed here: name, data, kind, x, y, annotate, aspect, bin, caption, color, facet, font_size, highlight, lint, mark_color, min_alpha, mode, opacity, point_size, radius, shading, size, spread, title, tooltip, trend"
            )
        );
        assert_eq!(
            diags[1].hint.as_deref(),
            Some(
                "canvas size `[width, height]` in CSS pixels, each at most 16384 (default: the kind's own, `[640, 420]` for one x/y frame); for example `size = [800, 600]`"
            )
        );
        let kinds: Vec<String> = crate::mark::registry::names().map(|k| format!("`{k}`")).collect();
        assert_eq!(diags[2].hint.as_deref(), Some(format!("expected one of: {}", kinds.join(", ")).as_str()));

        let rendered = render_all(&source(THREE_MISTAKES), &diags);
        let expected = format!(
            r#"error: unknown key `colour` in chart "iris-scatter"
  --> spec.toml:12:1
   |
12 | colour = "species"
   | ^^^^^^ did you mean `color`?
   = hint: keys allowed here: name, data, kind, x, y, annotate, aspect, bin, caption, color, facet, font_size, highlight, lint, mark_color, min_alpha, mode, opacity, point_size, radius, shading, size, spread, title, tooltip, trend

error: `size` must be an array of 2 numbers, found a string
  --> spec.toml:13:8
   |
13 | size = "big"
   |        ^^^^^
   = hint: canvas size `[width, height]` in CSS pixels, each at most 16384 (default: the kind's own, `[640, 420]` for one x/y frame); for example `size = [800, 600]`

error: unknown chart kind `scater`; did you mean `scatter`?
  --> spec.toml:18:8
   |
18 | kind = "scater"
   |        ^^^^^^^^
   = hint: expected one of: {}
"#,
            kinds.join(", ")
        );
        assert_eq!(rendered, expected);
    }

    #[test]
    fn check_keeps_the_doc_when_the_spec_has_errors() {
        let source = source(THREE_MISTAKES);
        let checked = check(&source);
        let diagnostics = checked.diagnostics;
        assert_eq!(diagnostics.len(), 3);
        let Some(doc) = checked.doc else { panic!("the TOML parsed, so the doc is kept") };
        assert_eq!(doc.span_of(&chart_path(0, "size")).and_then(|s| THREE_MISTAKES.get(s)), Some("\"big\""));
        assert_eq!(checked.spec, None);
        let broken = check(&SourceFile::new("s.toml", "[[chart"));
        assert_eq!((broken.doc.is_none(), broken.spec.is_none(), broken.diagnostics.len()), (true, true, 1));
    }

    #[test]
    fn syntax_error_has_line_and_column() {
        let text = "title = \"x\"\n[[chart]\nname = \"a\"\n";
        let diags = errors(text);
        assert_eq!(diags.len(), 1);
        assert_eq!(summary(text, &diags)[0].0, "invalid TOML: unclosed array table, expected `]`");
        assert_eq!(source(text).line_col(diags[0].span.clone().unwrap_or(0..0).start), (2, 9));
        let rendered = source(text).render(&diags[0]);
        assert!(rendered.contains(" --> spec.toml:2:9\n  |\n2 | [[chart]\n  |         ^\n"), "{rendered}");
    }

    #[test]
    fn unknown_data_reference_suggests_closest_name() {
        let text = "[data.iris]\npath = \"iris.csv\"\n[data.penguins]\npath = \"p.csv\"\n[[chart]]\nname = \"a\"\ndata = \"pengiuns\"\nkind = \"scatter\"\nx = \"a\"\ny = \"b\"\n";
        let diags = errors(text);
        assert_eq!(
            summary(text, &diags),
            vec![(
                "unknown data source `pengiuns`; did you mean `penguins`?".to_owned(),
                7,
                8,
                "\"pengiuns\"".to_owned(),
                None
            )]
        );
        assert_eq!(diags[0].hint.as_deref(), Some("data sources defined: `iris`, `penguins`"));
    }

    #[test]
    fn missing_keys_point_at_the_header() {
        let text = "[data.d]\nvalues = []\n[[chart]]\nname = \"a\"\ndata = \"d\"\nkind = \"line\"\ny = \"v\"\n[[chart]]\nkind = \"scatter\"\nx = { title = \"t\" }\n";
        let diags = errors(text);
        let got = summary(text, &diags);
        let messages: Vec<&str> = got.iter().map(|g| g.0.as_str()).collect();
        assert_eq!(
            messages,
            ["chart \"a\" has no `x`", "chart #2 is missing `name`, `data` and `y`", "`x` of chart #2 has no `field`"]
        );
        assert_eq!((got[0].1, got[0].2, got[0].3.as_str()), (3, 1, "[[chart]]"));
        assert_eq!((got[1].1, got[1].2, got[1].3.as_str()), (8, 1, "[[chart]]"));
        assert_eq!(got[2].3, "{ title = \"t\" }");
        assert_eq!(
            diags[0].hint.as_deref(),
            Some(
                "add `x = \"date\"`: horizontal position: a column name or a table with `field`, `title`, `unit`, `scale`, ..."
            )
        );
        assert_eq!(
            diags[1].hint.as_deref(),
            Some("add them, for example:\nname = \"iris-scatter\"\ndata = \"iris\"\ny = \"petal_length\"")
        );
    }

    #[test]
    fn semantic_rules_all_reported() {
        let text = r#"[data.a]
[data.b]
path = "b.csv"
values = []
delimiter = "ab"
[[chart]]
name = "a b"
data = "b"
kind = "scatter"
x = { field = "x", domain = [3, 3], ticks = 51 }
y = "y"
size = [0, 20000]
font_size = 0.5
opacity = -0.1
radius = 0
[[chart]]
name = "A"
data = "b"
kind = "line"
x = "x"
y = [{ field = "y", domain = [2, 1] }]
stroke_width = 0
[[chart]]
name = "A"
data = "b"
kind = "scatter"
x = "x"
y = "y"
point_size = { field = "s", max_radius = -2 }
[[chart]]
name = "a"
data = "b"
kind = "line"
x = "x"
y = "y"
"#;
        let diags = errors(text);
        let messages: Vec<String> = diags.iter().map(|d| format!("{}: {}", d.severity, d.message)).collect();
        assert_eq!(
            messages,
            [
                "error: `data.a` has none of `path`, `values` or `from`",
                "error: `data.b` has both `path` and `values`",
                "error: `delimiter` must be exactly 1 character, found 2 characters",
                "error: invalid chart name `a b`",
                "error: `x.domain` must be `[min, max]` with min < max, found `[3, 3]`",
                "error: `x.ticks` must be between 2 and 50, found 51",
                "error: `size[0]` must be greater than 0 and at most 16384, found 0",
                "error: `size[1]` must be greater than 0 and at most 16384, found 20000",
                "error: `font_size` must be between 1 and 200, found 0.5",
                "error: `opacity` must be between 0 and 1, found -0.1",
                "error: `radius` must be greater than 0 and at most 100, found 0",
                "error: `y[0].domain` must be `[min, max]` with min < max, found `[2, 1]`",
                "error: `stroke_width` must be greater than 0 and at most 100, found 0",
                "error: duplicate chart name `A`",
                "error: `point_size.max_radius` must be greater than 0 and at most 200, found -2",
                "warning: chart names `A` and `a` differ only in case",
            ]
        );
        assert_eq!(diags[3].label.as_deref(), Some("` ` is not allowed"));
        assert_eq!(diags[13].label.as_deref(), Some("chart #2 has the same name"));
    }

    #[test]
    fn case_only_duplicates_are_warnings() {
        let text = "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"Iris\"\ndata = \"d\"\nkind = \"line\"\nx = \"x\"\ny = \"y\"\n[[chart]]\nname = \"iris\"\ndata = \"d\"\nkind = \"line\"\nx = \"x\"\ny = \"y\"\n";
        let parsed = parse_ok(text);
        assert_eq!(parsed.spec.chart.len(), 2);
        assert_eq!(parsed.warnings.len(), 1);
        assert_eq!(parsed.warnings[0].severity, Severity::Warning);
    }

    #[test]
    fn unknown_keys_everywhere_with_context() {
        let text = "titel = \"x\"\n[data.d]\npth = \"d.csv\"\npath = \"d.csv\"\n[[chart]]\ndata = \"d\"\nkind = \"scatter\"\nx = { field = \"a\", Scale = \"log\" }\ny = \"b\"\nseries = \"s\"\n";
        let got = summary(text, &errors(text));
        let rows: Vec<(&str, Option<&str>)> = got.iter().map(|g| (g.0.as_str(), g.4.as_deref())).collect();
        assert_eq!(
            rows,
            [
                ("unknown key `titel` at the top level", Some("did you mean `title`?")),
                ("unknown key `pth` in `data.d`", Some("did you mean `path`?")),
                ("chart #1 has no `name`", None),
                ("unknown key `Scale` in `x` of chart #1", Some("did you mean `scale`?")),
                ("unknown key `series` in chart #1", Some("only for kind = \"line\"")),
            ]
        );
    }

    #[test]
    fn enum_values_and_untagged_choices() {
        let text = "[data.d]\npath = \"d.csv\"\nformat = \"CSV\"\n[[chart]]\nname = \"c\"\ndata = \"d\"\nkind = \"line\"\nx = { field = \"a\", scale = \"logarithmic\" }\ny = [\"b\", 3, true]\n";
        let got = summary(text, &errors(text));
        let messages: Vec<&str> = got.iter().map(|g| g.0.as_str()).collect();
        assert_eq!(
            messages,
            [
                "unknown format `CSV`; did you mean `csv`?",
                "unknown scale `logarithmic`; did you mean `log`?",
                "`y[1]` must be a string or a table, found an integer",
                "`y[2]` must be a string or a table, found a boolean",
            ]
        );
        let text =
            "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"c\"\ndata = \"d\"\nkind = \"line\"\nx = \"a\"\ny = 5\n";
        assert_eq!(
            errors(text)[0].message,
            "`y` must be an array of strings or tables, a string or a table, found an integer"
        );
    }

    const FULL: &str = r##"title = "Iris"

[data.iris]
path = "data/iris.csv"
format = "csv"
delimiter = ";"
null_values = ["-999"]

[data.rows]
values = [{ x = 1, y = 2.5, when = 1979-05-27 }, { x = 2, y = 3.0, label = "b" }]

[selection.short]
data = "iris"
range = { petal_length = [1, 2.5] }
categories = { species = ["setosa", 3] }
combine = "or"
invert = true

[lint]
allow = ["DI006"]

[[chart]]
name = "iris-scatter"
data = "iris"
title = "Petals"
caption = "Source: Fisher (1936)"
size = [800, 600.5]
font_size = 12
aspect = "equal"
highlight = "short"
lint = { allow = ["LB001"], deny = ["tick-count"] }
kind = "scatter"
x = { field = "sepal_length", title = "Sepal length", unit = "cm", scale = "linear", domain = [4, 8], zero = false, nice = true, ticks = 5, grid = true }
y = "petal_length"
color = { field = "species", title = "Species", unit = "", scheme = "viridis_r", type = "categorical", midpoint = 0.5, legend = true }
point_size = { field = "petal_width", title = "Width", unit = "cm", max_radius = 10 }
radius = 3.5
mark_color = "#336699"
opacity = 0.7
tooltip = ["species", "petal_length"]
facet = { row = "sex", column = "island", resolve = { y = "independent" }, sort = "data" }
trend = { method = "loess", span = 0.5, groups = true, equation = false }
mode = "points"
shading = "log"
bin = 3
min_alpha = 0.5
spread = 1
annotate = [{ y = 2.5, label = "target", color = "firebrick", dash = true }, { x = [5, 6.5], opacity = 0.2 }, { text = "note", at = [5, 1], anchor = "start" }, { arrow = [[4, 1], [5, 2]] }]

[[chart]]
name = "prices.v2"
data = "rows"
kind = "line"
x = "x"
y = ["y", { field = "y", scale = "log" }]
series = "label"
markers = true
stroke_width = 1.5
scheme = "okabe-ito"
mark_color = "black"

[[chart]]
name = "simple_line"
data = "rows"
kind = "line"

[chart.x]
field = "x"
scale = "time"

[chart.y]
field = "y"
scale = "band"

[[chart]]
name = "plain"
data = "iris"
kind = "scatter"
x = "a"
y = "b"
color = { field = "c", type = "continuous" }
point_size = "d"
"##;

    fn expected_full() -> Spec {
        let row = |pairs: &[(&str, Value)]| -> BTreeMap<String, Value> {
            pairs.iter().map(|(k, v)| ((*k).to_owned(), v.clone())).collect()
        };
        let mut data = BTreeMap::new();
        data.insert(
            "iris".to_owned(),
            DataSource {
                path: Some("data/iris.csv".to_owned()),
                format: Some(DataFormat::Csv),
                values: None,
                extent: None,
                delimiter: Some(";".to_owned()),
                from: None,
                transform: None,
                json_path: None,
                parse: None,
                null_values: Some(vec!["-999".to_owned()]),
                ..DataSource::default()
            },
        );
        data.insert(
            "rows".to_owned(),
            DataSource {
                path: None,
                format: None,
                values: Some(vec![
                    row(&[("x", json!(1)), ("y", json!(2.5)), ("when", json!("1979-05-27"))]),
                    row(&[("x", json!(2)), ("y", json!(3.0)), ("label", json!("b"))]),
                ]),
                extent: None,
                delimiter: None,
                from: None,
                transform: None,
                json_path: None,
                parse: None,
                null_values: None,
                ..DataSource::default()
            },
        );
        let field = |f: &str| Channel::Field(f.to_owned());
        Spec {
            title: Some("Iris".to_owned()),
            data,
            selection: BTreeMap::from([(
                "short".to_owned(),
                Selection {
                    data: "iris".to_owned(),
                    range: Some(BTreeMap::from([("petal_length".to_owned(), [1.0, 2.5])])),
                    categories: Some(BTreeMap::from([(
                        "species".to_owned(),
                        vec![CategoryValue::Text("setosa".to_owned()), CategoryValue::Number(3.0)],
                    )])),
                    combine: Some(Combine::Or),
                    invert: Some(true),
                },
            )]),
            lint: Some(LintConfig { allow: Some(vec!["DI006".to_owned()]), deny: None }),
            chart: vec![
                Chart {
                    name: "iris-scatter".to_owned(),
                    data: "iris".to_owned(),
                    title: Some("Petals".to_owned()),
                    highlight: Some("short".to_owned()),
                    lint: Some(LintConfig {
                        allow: Some(vec!["LB001".to_owned()]),
                        deny: Some(vec!["tick-count".to_owned()]),
                    }),
                    caption: Some("Source: Fisher (1936)".to_owned()),
                    size: Some([800.0, 600.5]),
                    font_size: Some(12.0),
                    aspect: Some(Aspect::Equal),
                    tooltip: Some(Tooltip::Fields(vec!["species".to_owned(), "petal_length".to_owned()])),
                    annotate: vec![
                        Annotation {
                            y: Some(AxisPlace::At(AxisValue::Number(2.5))),
                            label: Some("target".to_owned()),
                            color: Some("firebrick".to_owned()),
                            dash: Some(true),
                            ..Annotation::default()
                        },
                        Annotation {
                            x: Some(AxisPlace::Range([AxisValue::Number(5.0), AxisValue::Number(6.5)])),
                            opacity: Some(0.2),
                            ..Annotation::default()
                        },
                        Annotation {
                            text: Some("note".to_owned()),
                            at: Some([AxisValue::Number(5.0), AxisValue::Number(1.0)]),
                            anchor: Some(TextAnchor::Start),
                            ..Annotation::default()
                        },
                        Annotation {
                            arrow: Some([
                                [AxisValue::Number(4.0), AxisValue::Number(1.0)],
                                [AxisValue::Number(5.0), AxisValue::Number(2.0)],
                            ]),
                            ..Annotation::default()
                        },
                    ],
                    facet: Some(Facet::Detailed(FacetOptions {
                        row: Some("sex".to_owned()),
                        column: Some("island".to_owned()),
                        wrap: None,
                        resolve: Some(FacetResolve { x: None, y: Some(Sharing::Independent) }),
                        sort: Some(FacetSort::Data),
                    })),
                    panel: None,
                    kind: ChartKind::Scatter(ScatterOptions {
                        x: Channel::Detailed(ChannelOptions {
                            field: "sepal_length".to_owned(),
                            title: Some("Sepal length".to_owned()),
                            unit: Some("cm".to_owned()),
                            scale: Some(ScaleKind::Linear),
                            domain: Some([4.0, 8.0]),
                            zero: Some(false),
                            nice: Some(true),
                            ticks: Some(5),
                            grid: Some(true),
                        }),
                        y: field("petal_length"),
                        color: Some(ColorChannel::Detailed(ColorOptions {
                            field: "species".to_owned(),
                            title: Some("Species".to_owned()),
                            unit: Some(String::new()),
                            scheme: Some("viridis_r".to_owned()),
                            r#type: Some(ColorType::Categorical),
                            midpoint: Some(0.5),
                            legend: Some(true),
                            domain: None,
                            range: None,
                        })),
                        point_size: Some(SizeChannel::Detailed(SizeOptions {
                            field: "petal_width".to_owned(),
                            title: Some("Width".to_owned()),
                            unit: Some("cm".to_owned()),
                            max_radius: Some(10.0),
                            mapping: None,
                        })),
                        radius: Some(3.5),
                        mark_color: Some("#336699".to_owned()),
                        opacity: Some(0.7),
                        trend: Some(Trend::Detailed(TrendOptions {
                            method: TrendMethod::Loess,
                            span: Some(0.5),
                            groups: Some(true),
                            equation: Some(false),
                        })),
                        mode: Some(crate::mark::density::PointMode::Points),
                        shading: Some(crate::mark::density::ShadingOption::Log),
                        bin: Some(3.0),
                        min_alpha: Some(0.5),
                        spread: Some(1),
                    }),
                },
                Chart {
                    name: "prices.v2".to_owned(),
                    data: "rows".to_owned(),
                    title: None,
                    caption: None,
                    size: None,
                    font_size: None,
                    aspect: None,
                    highlight: None,
                    lint: None,
                    tooltip: None,
                    annotate: Vec::new(),
                    facet: None,
                    panel: None,
                    kind: ChartKind::Line(LineOptions {
                        x: field("x"),
                        y: OneOrMany::Many(vec![
                            field("y"),
                            Channel::Detailed(ChannelOptions {
                                field: "y".to_owned(),
                                scale: Some(ScaleKind::Log),
                                ..ChannelOptions::default()
                            }),
                        ]),
                        series: Some("label".to_owned()),
                        color: None,
                        y_title: None,
                        markers: Some(true),
                        stroke_width: Some(1.5),
                        scheme: Some("okabe-ito".to_owned()),
                        mark_color: Some("black".to_owned()),
                        band: None,
                    }),
                },
                Chart {
                    name: "simple_line".to_owned(),
                    data: "rows".to_owned(),
                    title: None,
                    caption: None,
                    size: None,
                    font_size: None,
                    aspect: None,
                    highlight: None,
                    lint: None,
                    tooltip: None,
                    annotate: Vec::new(),
                    facet: None,
                    panel: None,
                    kind: ChartKind::Line(LineOptions {
                        x: Channel::Detailed(ChannelOptions {
                            field: "x".to_owned(),
                            scale: Some(ScaleKind::Time),
                            ..ChannelOptions::default()
                        }),
                        y: OneOrMany::One(Channel::Detailed(ChannelOptions {
                            field: "y".to_owned(),
                            scale: Some(ScaleKind::Band),
                            ..ChannelOptions::default()
                        })),
                        series: None,
                        color: None,
                        y_title: None,
                        markers: None,
                        stroke_width: None,
                        scheme: None,
                        mark_color: None,
                        band: None,
                    }),
                },
                Chart {
                    name: "plain".to_owned(),
                    data: "iris".to_owned(),
                    title: None,
                    caption: None,
                    size: None,
                    font_size: None,
                    aspect: None,
                    highlight: None,
                    lint: None,
                    tooltip: None,
                    annotate: Vec::new(),
                    facet: None,
                    panel: None,
                    kind: ChartKind::Scatter(ScatterOptions {
                        x: field("a"),
                        y: field("b"),
                        color: Some(ColorChannel::Detailed(ColorOptions {
                            field: "c".to_owned(),
                            r#type: Some(ColorType::Continuous),
                            ..ColorOptions::default()
                        })),
                        point_size: Some(SizeChannel::Field("d".to_owned())),
                        radius: None,
                        mark_color: None,
                        opacity: None,
                        trend: None,
                        mode: None,
                        shading: None,
                        bin: None,
                        min_alpha: None,
                        spread: None,
                    }),
                },
            ],
        }
    }

    /// Writes a spec (as serialized JSON) back as TOML: test-only, enough for these types.
    fn to_toml(spec: &Spec) -> String {
        fn inline(v: &Value) -> String {
            match v {
                Value::Object(map) => {
                    let parts: Vec<String> = map
                        .iter()
                        .filter(|(_, v)| !v.is_null())
                        .map(|(k, v)| format!("{k:?} = {}", inline(v)))
                        .collect();
                    format!("{{ {} }}", parts.join(", "))
                }
                Value::Array(items) => format!("[{}]", items.iter().map(inline).collect::<Vec<_>>().join(", ")),
                other => other.to_string(),
            }
        }
        fn entries(map: &serde_json::Map<String, Value>) -> String {
            map.iter().filter(|(_, v)| !v.is_null()).map(|(k, v)| format!("{k:?} = {}\n", inline(v))).collect()
        }
        let json = serde_json::to_value(spec).unwrap_or_default();
        let mut out = String::new();
        if let Some(title) = json.get("title").filter(|t| !t.is_null()) {
            out.push_str(&format!("title = {title}\n"));
        }
        for (name, source) in json.get("data").and_then(Value::as_object).into_iter().flatten() {
            out.push_str(&format!("[data.{name:?}]\n"));
            out.push_str(&entries(source.as_object().unwrap_or(&serde_json::Map::new())));
        }
        for (name, selection) in json.get("selection").and_then(Value::as_object).into_iter().flatten() {
            out.push_str(&format!("[selection.{name:?}]\n"));
            out.push_str(&entries(selection.as_object().unwrap_or(&serde_json::Map::new())));
        }
        if let Some(lint) = json.get("lint").and_then(Value::as_object) {
            out.push_str("[lint]\n");
            out.push_str(&entries(lint));
        }
        for chart in json.get("chart").and_then(Value::as_array).into_iter().flatten() {
            out.push_str("[[chart]]\n");
            out.push_str(&entries(chart.as_object().unwrap_or(&serde_json::Map::new())));
        }
        out
    }

    #[test]
    fn valid_spec_with_every_field_round_trips() {
        let parsed = parse_ok(FULL);
        assert!(parsed.warnings.is_empty());
        let expected = expected_full();
        assert_eq!(parsed.spec, expected);
        // Spec → TOML → Spec gives the same spec.
        let again = parse_ok(&to_toml(&expected));
        assert_eq!(again.spec, expected);
        // The doc keeps positions for later stages.
        let span = parsed.doc.span_of(&chart_path(1, "y"));
        assert_eq!(span.and_then(|s| FULL.get(s)), Some("[\"y\", { field = \"y\", scale = \"log\" }]"));
        let mut field = chart_path(2, "x");
        field.push(PathSeg::Key("field".to_owned()));
        assert_eq!(parsed.doc.span_of(&field).and_then(|s| FULL.get(s)), Some("\"x\""));
        assert_eq!(chart_path(2, "x.field"), field);
        assert_eq!(parsed.doc.key_span_of(&field).and_then(|s| FULL.get(s)), Some("field"));
        assert_eq!(parsed.doc.span_of(&chart_path(2, "x")).and_then(|s| FULL.get(s)), Some("[chart.x]"));
        assert_eq!(parsed.doc.span_of(&chart_path(3, "")).and_then(|s| FULL.get(s)), Some("[[chart]]"));
    }

    #[test]
    fn schema_and_validator_agree_on_chart_keys() {
        let schema = spec_schema();
        let branches = schema["$defs"]["Chart"]["oneOf"].as_array().cloned().unwrap_or_default();
        // Every key the validator accepts for a scatter chart is in the closed schema branch.
        let scatter = branches.iter().find(|b| b["properties"]["kind"]["const"] == "scatter");
        let keys: Vec<&str> = scatter
            .and_then(|b| b["properties"].as_object())
            .map(|p| p.keys().map(String::as_str).collect())
            .unwrap_or_default();
        for key in keys {
            assert!(FULL.contains(&format!("\n{key} = ")) || FULL.contains(&format!("{key} = ")), "{key}");
        }
        assert_eq!(scatter.map(|b| b["additionalProperties"].clone()), Some(Value::Bool(false)));
        assert_eq!(schema["additionalProperties"], false);
    }

    #[test]
    fn odd_inputs_give_diagnostics_and_never_panic() {
        let deep_array = format!("a = {}{}\n", "[".repeat(5000), "]".repeat(5000));
        let deep_table = format!("a = {}1{}\n", "{b = ".repeat(500), "}".repeat(500));
        let deep_keys = format!("a{} = 1\n", ".b".repeat(300));
        let long_line = format!("title = \"{}\"\n", "x".repeat(100_000));
        let many_charts = "[[chart]]\n".repeat(2000);
        let cases: Vec<(&str, String)> = vec![
            ("empty", String::new()),
            ("comments", "# only a comment\n\n   # another\n".to_owned()),
            ("huge int", "[[chart]]\nsize = [99999999999999999999, 1]\n".to_owned()),
            ("huge float", "[[chart]]\nsize = [1e999, 1]\n".to_owned()),
            ("big float", "[data.d]\npath = \"d\"\n[[chart]]\nname = \"c\"\ndata = \"d\"\nkind = \"line\"\nx = \"a\"\ny = \"b\"\nsize = [1e300, -1e300]\nfont_size = 1e-300\n".to_owned()),
            ("nan inf", "[data.d]\npath = \"d\"\n[[chart]]\nname = \"c\"\ndata = \"d\"\nkind = \"line\"\nx = \"a\"\ny = \"b\"\nsize = [nan, inf]\nfont_size = -inf\n".to_owned()),
            ("deep array", deep_array),
            ("deep table", deep_table),
            ("deep keys", deep_keys),
            ("non-ascii keys", "\"größe\" = 1\n\"名前\" = 2\n[[chart]]\n\"ключ\" = 3\n".to_owned()),
            ("bare non-ascii key", "größe = 1\n".to_owned()),
            ("chart = 3", "chart = 3\n".to_owned()),
            ("chart table", "[chart]\nname = \"a\"\n".to_owned()),
            ("chart list of ints", "chart = [1, \"two\", [3]]\n".to_owned()),
            ("data = 3", "data = 3\n[[chart]]\nname = \"a\"\ndata = \"x\"\nkind = \"line\"\nx = \"a\"\ny = \"b\"\n".to_owned()),
            ("nul and escapes", "title = \"a\\u0000b\"\n\"\\u001b[31m\" = 1\n".to_owned()),
            ("bom", "\u{feff}[[chart]]\n".to_owned()),
            ("crlf", "[[chart]]\r\nname = 3\r\n".to_owned()),
            ("long line", long_line),
            ("many charts", many_charts),
            ("datetimes", "title = 1979-05-27T07:32:00Z\n[[chart]]\nname = 07:32:00\n".to_owned()),
            ("empty name", "[data.d]\npath = \"d\"\n[[chart]]\nname = \"\"\ndata = \"d\"\nkind = \"line\"\nx = \"\"\ny = \"b\"\n".to_owned()),
            ("dots name", "[data.d]\npath = \"d\"\n[[chart]]\nname = \"..\"\ndata = \"d\"\nkind = \"line\"\nx = \"a\"\ny = \"b\"\n".to_owned()),
            ("garbage", "\u{0}\u{1}\u{7f}=[{\n".to_owned()),
        ];
        for (what, text) in cases {
            let src = source(&text);
            let result = parse_spec(&src);
            let Err(diags) = result else { panic!("{what}: expected diagnostics") };
            assert!(!diags.is_empty(), "{what}");
            for d in &diags {
                if let Some(span) = &d.span {
                    assert!(span.start <= span.end && span.end <= text.len(), "{what}: {d:?}");
                }
                assert!(!d.message.contains("could not be read"), "{what}: {d:?}");
            }
            let rendered = render_all(&src, &diags);
            assert!(rendered.starts_with("error") || rendered.starts_with("warning"), "{what}");
        }
        let nan = errors(
            "[data.d]\npath = \"d\"\n[[chart]]\nname = \"c\"\ndata = \"d\"\nkind = \"line\"\nx = \"a\"\ny = \"b\"\nsize = [nan, inf]\n",
        );
        let messages: Vec<&str> = nan.iter().map(|d| d.message.as_str()).collect();
        assert_eq!(
            messages,
            ["`size[0]` must be a finite number, found nan", "`size[1]` must be a finite number, found inf"]
        );
        assert_eq!(errors("chart = 3\n")[0].message, "`chart` must be an array of tables, found an integer");
        assert_eq!(errors("")[0].message, "the spec has no charts");
        assert_eq!(errors("# nothing\n")[0].span, None);
    }

    /// A small deterministic generator (xorshift) for the fuzz test.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn below(&mut self, n: usize) -> usize {
            (self.next() % n.max(1) as u64) as usize
        }
    }

    #[test]
    fn fuzz_parse_spec_never_panics_and_agrees_with_serde() {
        const PIECES: &[&str] = &[
            "[[chart]]\n",
            "[data.d]\n",
            "[chart.x]\n",
            "name = \"c\"\n",
            "data = \"d\"\n",
            "kind = \"line\"\n",
            "kind = \"scatter\"\n",
            "x = \"a\"\n",
            "y = [\"b\", { field = \"c\" }]\n",
            "path = \"p.csv\"\n",
            "values = [{ a = 1 }]\n",
            "size = [",
            "nan",
            "inf",
            "1e308",
            "-0.0",
            "0",
            "]",
            "{",
            "}",
            "\"",
            "'",
            "=",
            ".",
            ",",
            "\n",
            " ",
            "#",
            "ticks = 5\n",
            "domain = [1, 2]\n",
            "field = \"f\"\n",
            "color = { field = \"c\", type = \"continuous\" }\n",
            "opacity = 1\n",
            "é",
            "名",
            "\u{0}",
            "\t",
            "\r\n",
            "[[",
            "]]",
            "[",
            "1979-05-27",
            "true",
            "\"\"\"",
            "\\u0041",
            "delimiter = \";\"\n",
            "font_size = 12\n",
        ];
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut ok = 0;
        for _ in 0..3000 {
            let mut text = String::new();
            for _ in 0..rng.below(40) {
                text.push_str(PIECES[rng.below(PIECES.len())]);
            }
            match parse_spec(&source(&text)) {
                Ok(_) => ok += 1,
                Err(diags) => {
                    assert!(!diags.is_empty());
                    for d in &diags {
                        assert!(!d.message.contains("could not be read"), "{text:?}: {d:?}");
                        assert!(d.span.as_ref().is_none_or(|s| s.end <= text.len()), "{text:?}: {d:?}");
                    }
                    let _ = render_all(&source(&text), &diags);
                }
            }
        }
        // Mutations of a valid spec: drop, duplicate or insert characters.
        let base: Vec<char> = FULL.chars().collect();
        for _ in 0..1500 {
            let mut chars = base.clone();
            for _ in 0..1 + rng.below(3) {
                let at = rng.below(chars.len());
                match rng.below(3) {
                    0 => {
                        chars.remove(at);
                    }
                    1 => chars.insert(at, chars[at]),
                    _ => chars.insert(at, ['"', '[', ']', '=', '\n', 'x', '1', '.', '{', ','][rng.below(10)]),
                }
            }
            let text: String = chars.into_iter().collect();
            match parse_spec(&source(&text)) {
                Ok(_) => ok += 1,
                Err(diags) => {
                    for d in &diags {
                        assert!(!d.message.contains("could not be read"), "{text}: {d:?}");
                    }
                    let _ = render_all(&source(&text), &diags);
                }
            }
        }
        assert!(ok > 0, "some mutated specs stay valid");
    }
}
