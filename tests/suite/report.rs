//! `dataink report`: provenance, exit codes, escaping of hostile user strings in every output,
//! user templates, and the page as a real browser draws it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use dataink::data::PathPolicy;
use dataink::pipeline;
use dataink::report::{self, ReportOptions};

use crate::common::{Fixture, assert_svg_parses, run_with_timeout};

fn dataink() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dataink"))
}

/// Four rows; its SHA-256 was computed separately (`sha256sum`).
const POINTS_CSV: &[u8] = b"x,y,group\n1,2,a\n2,3,b\n3,5,a\n4,4,b\n";
const POINTS_SHA256: &str = "a46f70036d91d1c3563674aadc470c05075af8ed80292c63c411aef47005952f";
/// SHA-256 of `[{"t":0,"v":1.5},{"t":1,"v":2.5}]`, the inline rows below as compact JSON.
const INLINE_SHA256: &str = "b37c8623eee2db70042c3e182251fce8c3b7bdcf95f1631a0defc33eb890d2b5";

/// A spec whose charts lint clean (titles, units, legends).
const CLEAN_SPEC: &str = r#"
title = "Points"

[data.points]
path = "data/points.csv"

[data.decay]
values = [{ t = 0, v = 1.5 }, { t = 1, v = 2.5 }]

[[chart]]
name = "points"
kind = "scatter"
data = "points"
title = "y grows with x in both groups"
x = { field = "x", title = "Distance", unit = "m" }
y = { field = "y", title = "Time", unit = "s" }
color = { field = "group", title = "Group" }
"#;

/// Run `dataink report` on a fixture's spec into `out`, with extra arguments.
fn run_report(fixture: &Fixture, out: &Path, extra: &[&str]) -> Output {
    dataink().arg("report").arg(&fixture.spec).arg("--out").arg(out).args(extra).output().expect("run dataink")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn read(path: PathBuf) -> String {
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A start or end tag of an HTML document.
#[derive(Debug)]
struct Tag {
    name: String,
    attributes: Vec<String>,
    end: bool,
    self_closing: bool,
}

/// Every tag of `html`, panicking on a `<` that starts no tag or comment (escaped text never
/// holds a raw `<`).
fn tags(html: &str) -> Vec<Tag> {
    let bytes = html.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(found) = html[i..].find('<') {
        let start = i + found;
        let rest = &html[start..];
        if rest.starts_with("<!--") {
            i = start + rest.find("-->").expect("comment closes") + 3;
            continue;
        }
        if rest.starts_with("<!") {
            i = start + rest.find('>').expect("declaration closes") + 1;
            continue;
        }
        let end = rest.starts_with("</");
        let name_start = start + if end { 2 } else { 1 };
        let mut j = name_start;
        while j < bytes.len() && (bytes[j].is_ascii_alphanumeric() || bytes[j] == b'-' || bytes[j] == b':') {
            j += 1;
        }
        let name = &html[name_start..j];
        assert!(
            !name.is_empty() && bytes[name_start].is_ascii_alphabetic(),
            "raw `<` in text at byte {start}: {:?}",
            html[start..].chars().take(60).collect::<String>()
        );
        // Attributes up to the closing `>`, honouring quotes.
        let mut attributes = Vec::new();
        let mut quote: Option<u8> = None;
        let mut current = String::new();
        let mut in_name = true;
        let mut k = j;
        loop {
            assert!(k < bytes.len(), "tag `{name}` at byte {start} never closes");
            let b = bytes[k];
            match quote {
                Some(q) if b == q => quote = None,
                Some(_) => {}
                None if b == b'"' || b == b'\'' => quote = Some(b),
                None if b == b'>' => break,
                None if b.is_ascii_whitespace() || b == b'/' => {
                    if !current.is_empty() {
                        attributes.push(std::mem::take(&mut current));
                    }
                    in_name = true;
                }
                None if b == b'=' => {
                    if !current.is_empty() {
                        attributes.push(std::mem::take(&mut current));
                    }
                    in_name = false;
                }
                None if in_name => current.push(b as char),
                None => {}
            }
            k += 1;
        }
        if !current.is_empty() {
            attributes.push(current);
        }
        let self_closing = bytes[k - 1] == b'/';
        out.push(Tag { name: name.to_string(), attributes, end, self_closing });
        i = k + 1;
        // Raw-text elements: skip to their end tag.
        if !end && (name.eq_ignore_ascii_case("style") || name.eq_ignore_ascii_case("script")) {
            let close = format!("</{name}");
            i += html[i..].find(&close).expect("raw text element closes");
        }
    }
    out
}

const VOID: &[&str] =
    &["area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"];

/// Assert that `html` is well-formed enough: every tag closes in order, and no element or
/// attribute can run script.
fn assert_inert_and_balanced(html: &str, what: &str) {
    assert!(!html.to_ascii_lowercase().contains("<script"), "{what} has a script tag");
    let mut stack: Vec<String> = Vec::new();
    for tag in tags(html) {
        for a in &tag.attributes {
            let a = a.to_ascii_lowercase();
            assert!(!a.starts_with("on"), "{what}: <{}> has an event attribute `{a}`", tag.name);
        }
        assert!(!tag.name.eq_ignore_ascii_case("script"), "{what} has a script element");
        if tag.end {
            let open = stack.pop().unwrap_or_else(|| panic!("{what}: </{}> closes nothing", tag.name));
            assert_eq!(open, tag.name, "{what}: <{open}> closed by </{}>", tag.name);
        } else if !tag.self_closing && !VOID.contains(&tag.name.to_ascii_lowercase().as_str()) {
            stack.push(tag.name);
        }
    }
    assert!(stack.is_empty(), "{what}: unclosed elements {stack:?}");
}

/// The inline `<svg>…</svg>` documents of a page.
fn inline_svgs(html: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = html;
    while let Some(start) = rest.find("<svg") {
        let end = rest[start..].find("</svg>").expect("svg closes") + start + "</svg>".len();
        out.push(&rest[start..end]);
        rest = &rest[end..];
    }
    out
}

#[test]
fn provenance_has_rows_columns_and_sha256_of_the_bytes() {
    let fixture = Fixture::new(CLEAN_SPEC, &[("data/points.csv", POINTS_CSV)]);
    let loaded = fixture.load().unwrap_or_else(|e| panic!("{e}"));
    let dir = report::provenance::spec_dir(&fixture.spec);
    let data = report::provenance::collect(&loaded.spec.data, &loaded.tables, &dir, PathPolicy::InsideSpecFolder)
        .expect("provenance");
    assert_eq!(data.len(), 2);
    // Sources in name order: decay (inline), points (file).
    let (decay, points) = (&data[0], &data[1]);
    assert_eq!((points.name.as_str(), points.origin, points.path.as_str()), ("points", "file", "data/points.csv"));
    assert_eq!(points.format, "csv");
    assert_eq!(points.rows, 4);
    assert_eq!(points.columns, ["x", "y", "group"]);
    assert_eq!(points.bytes, POINTS_CSV.len() as u64);
    assert_eq!(points.sha256, POINTS_SHA256);
    assert_eq!((decay.origin, decay.path.as_str(), decay.rows), ("inline", "", 2));
    assert_eq!(decay.columns, ["t", "v"]);
    assert_eq!(decay.sha256, INLINE_SHA256);

    // The page shows them.
    let linted = pipeline::draw_and_lint(&loaded, &[]).expect("draws");
    let generated = chrono::DateTime::parse_from_rfc3339("2025-03-04T05:06:07Z").expect("time").to_utc();
    let options =
        ReportOptions { policy: PathPolicy::InsideSpecFolder, deny_warnings: false, generated, html_template: None };
    let built = report::build(&loaded, &linted, &options).expect("report");
    for needle in
        [POINTS_SHA256, INLINE_SHA256, "data&#x2f;points.csv", "2025-03-04T05:06:07Z", env!("CARGO_PKG_VERSION")]
    {
        assert!(built.html.contains(needle), "index.html lacks {needle}");
    }
    assert!(built.markdown.contains("2025-03-04T05:06:07Z"), "{}", built.markdown);
}

#[test]
fn exit_codes_follow_lint() {
    let out = tempfile::tempdir().expect("temp dir");
    let dir = out.path().join("report");

    // Clean: 0, both files written and named on stderr.
    let clean = Fixture::new(CLEAN_SPEC, &[("data/points.csv", POINTS_CSV)]);
    let run = run_report(&clean, &dir, &[]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let expected = format!("wrote {}, {}", dir.join("index.html").display(), dir.join("report.md").display());
    assert!(stderr(&run).contains(&expected), "{}", stderr(&run));
    let md = read(dir.join("report.md"));
    assert!(md.contains("**Passed**") && md.contains("No findings."), "{md}");

    // A warning only (no title): 0, but 1 with --deny-warnings.
    let untitled = CLEAN_SPEC.replace("title = \"y grows with x in both groups\"\n", "");
    let warned = Fixture::new(&untitled, &[("data/points.csv", POINTS_CSV)]);
    let run = run_report(&warned, &dir, &[]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert!(read(dir.join("report.md")).contains("LB001"), "the warning is listed");
    let run = run_report(&warned, &dir, &["--deny-warnings"]);
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    assert!(read(dir.join("report.md")).contains("**Failed**"));

    // The same finding made an error by the spec: 1, and the page still written.
    let denied = format!("{untitled}\n[lint]\ndeny = [\"missing-title\"]\n");
    let run = run_report(&Fixture::new(&denied, &[("data/points.csv", POINTS_CSV)]), &dir, &[]);
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    let html = read(dir.join("index.html"));
    assert!(html.contains("class=\"verdict fail\"") && html.contains("LB001"), "failed page");

    // Bad input: 2.
    let run = run_report(&clean, &dir, &["--chart", "pionts"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("did you mean `points`?"), "{}", stderr(&run));
    let run = run_report(&clean, &dir, &["--template", "no/such/template.html"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("cannot read template `no/such/template.html`"), "{}", stderr(&run));
    let broken = Fixture::new("[[chart]]\nname = 3\n", &[]);
    assert_eq!(run_report(&broken, &dir, &[]).status.code(), Some(2));
    let outside = CLEAN_SPEC.replace("data/points.csv", "../points.csv");
    let run = run_report(&Fixture::new(&outside, &[]), &dir, &[]);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
}

const SCRIPT: &str = "</script><script>alert(1)</script>";
const ONLOAD: &str = "\"><svg onload=alert(1)>";

/// A spec with hostile text in every user string that reaches a report.
fn hostile_fixture() -> Fixture {
    // TOML basic strings: escape the double quotes.
    let onload = ONLOAD.replace('"', "\\\"");
    let spec = format!(
        r#"# {SCRIPT} {ONLOAD}
title = "{SCRIPT}"

[data.evil]
path = "evil.csv"

[[chart]]
name = "evil"
kind = "scatter"
data = "evil"
title = "{onload}"
caption = "{SCRIPT}"
x = {{ field = "x", title = "{SCRIPT}", unit = "{onload}" }}
y = {{ field = "y", title = "{onload}" }}
color = {{ field = "who", title = "{SCRIPT}" }}

[[chart]]
name = "plain"
kind = "line"
data = "evil"
x = "x"
y = "y"
"#
    );
    // CSV: quotes doubled inside a quoted field.
    let csv =
        format!("x,y,who\n1,2,{SCRIPT}\n2,3,\"{}\"\n3,1,<img src=x onerror=alert(1)>\n", ONLOAD.replace('"', "\"\""));
    Fixture::new(&spec, &[("evil.csv", csv.as_bytes())])
}

#[test]
fn hostile_strings_never_become_markup() {
    let fixture = hostile_fixture();
    let out = tempfile::tempdir().expect("temp dir");
    let run = run_report(&fixture, out.path(), &[]);
    assert!(matches!(run.status.code(), Some(0 | 1)), "{}", stderr(&run));
    let html = read(out.path().join("index.html"));
    let md = read(out.path().join("report.md"));

    assert_inert_and_balanced(&html, "index.html");
    let svgs = inline_svgs(&html);
    assert_eq!(svgs.len(), 2, "one SVG per chart");
    for svg in &svgs {
        assert_svg_parses(svg);
        assert_inert_and_balanced(svg, "inline SVG");
    }
    // The text is there, escaped: by the template engine in the page, by the renderer in the SVG.
    assert!(html.contains("<h1>&lt;&#x2f;script&gt;&lt;script&gt;alert(1)&lt;&#x2f;script&gt;</h1>"), "spec title");
    assert!(html.contains("&quot;&gt;&lt;svg onload=alert(1)&gt;"), "chart title in the page");
    assert!(svgs[0].contains("&lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt;"), "legend entry in the SVG");
    assert!(svgs[0].contains("&lt;img src=x onerror=alert(1)&gt;"), "category in the SVG");
    assert!(html.contains("<span class=\"ln\">1</span># &lt;&#x2f;script&gt;"), "spec text");

    // Markdown: no markup at all, and the title's text is still there, escaped.
    assert!(!md.contains('<'), "report.md holds a raw `<`:\n{md}");
    assert!(md.contains("&lt;&#x2f;script&gt;"), "{md}");
    // The untitled second chart's finding names it.
    assert!(md.contains("LB001"), "{md}");
}

#[test]
fn user_templates_are_escaped_too() {
    let fixture = hostile_fixture();
    let out = tempfile::tempdir().expect("temp dir");
    // A `.txt` name: escaping does not depend on the extension.
    let template = fixture.dir.path().join("mine.txt");
    std::fs::write(
        &template,
        "<!DOCTYPE html><html><head><title>{{ title }}</title></head><body><h1>{{ title }}</h1>\
         {% for c in charts %}<h2 id=\"{{ c.anchor }}\">{{ c.title }}</h2>{{ c.svg }}\
         {% for f in c.findings %}<p>{{ f.code }} {{ f.message }}</p>{% endfor %}{% endfor %}\
         {% for d in data %}<p>{{ d.path }} {{ d.sha256 }}</p>{% endfor %}<pre>{{ spec.text }}</pre></body></html>",
    )
    .expect("write template");
    let run = run_report(&fixture, out.path(), &["--template", template.to_str().expect("utf-8 path")]);
    assert!(matches!(run.status.code(), Some(0 | 1)), "{}", stderr(&run));
    let html = read(out.path().join("index.html"));
    assert!(html.starts_with("<!DOCTYPE html><html><head><title>&lt;&#x2f;script&gt;"), "the user's template");
    assert_inert_and_balanced(&html, "user template output");
    assert_eq!(inline_svgs(&html).len(), 2, "SVGs pass through unescaped");
    assert!(html.contains("<pre># &lt;&#x2f;script&gt;"), "spec text escaped");

    // Ways to switch escaping off are refused, naming the template and line.
    std::fs::write(&template, "<h1>{{ title|safe }}</h1>").expect("write template");
    let run = run_report(&fixture, out.path(), &["--template", template.to_str().expect("utf-8 path")]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("unknown filter"), "{}", stderr(&run));
    std::fs::write(&template, "ok\n{% autoescape false %}{{ title }}{% endautoescape %}").expect("write template");
    let run = run_report(&fixture, out.path(), &["--template", template.to_str().expect("utf-8 path")]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("mine.txt` line 2: `{% autoescape %}` blocks are not allowed"), "{}", stderr(&run));
    // A misspelt variable is an error, not an empty string.
    std::fs::write(&template, "{{ titel }}").expect("write template");
    let run = run_report(&fixture, out.path(), &["--template", template.to_str().expect("utf-8 path")]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("undefined"), "{}", stderr(&run));
}

fn chromium(profile: &Path) -> Command {
    let mut c = Command::new(CHROMIUM);
    c.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--no-first-run",
    ]);
    c.arg(format!("--user-data-dir={}", profile.display()));
    c
}

const CHROMIUM: &str = "/usr/bin/chromium";

#[test]
fn a_browser_draws_the_page_with_every_chart_and_no_script() {
    if !Path::new(CHROMIUM).exists() {
        crate::common::skip_outside_ci(
            &format!("{CHROMIUM} is missing but CI is set: install chromium (see .ci/run)"),
            &format!("note: {CHROMIUM} not found; skipping the browser check (install chromium to run it)"),
        );
        return;
    }
    let fixture = hostile_fixture();
    let out = tempfile::tempdir().expect("temp dir");
    let run = run_report(&fixture, out.path(), &[]);
    assert!(matches!(run.status.code(), Some(0 | 1)), "{}", stderr(&run));
    let page = format!("file://{}", out.path().join("index.html").display());

    // The DOM as the browser parsed it.
    let profile = tempfile::tempdir().expect("profile dir");
    let mut dump = chromium(profile.path());
    dump.arg("--dump-dom").arg(&page);
    let dom = run_with_timeout(dump, 120).expect("chromium --dump-dom finishes within 2 minutes");
    let dom = String::from_utf8_lossy(&dom.stdout).into_owned();
    assert!(dom.contains("<body>"), "a DOM was dumped: {dom:.300}");
    assert_inert_and_balanced(&dom, "the browser's DOM");
    for anchor in ["chart-evil", "chart-plain"] {
        let at = dom.find(&format!("id=\"{anchor}\"")).unwrap_or_else(|| panic!("section {anchor} in the DOM"));
        let section = &dom[at..];
        let section = &section[..section.find("</section>").expect("section closes")];
        assert!(section.contains("<svg") && section.contains("</svg>"), "{anchor} holds its SVG");
        assert!(section.contains("data-role=\"data-mark\""), "{anchor} has data marks");
    }

    // A screenshot that is not blank.
    let shot = out.path().join("shot.png");
    let profile = tempfile::tempdir().expect("profile dir");
    let mut screenshot = chromium(profile.path());
    screenshot.arg(format!("--screenshot={}", shot.display())).arg("--window-size=1200,1800").arg(&page);
    run_with_timeout(screenshot, 120).expect("chromium --screenshot finishes within 2 minutes");
    let bytes = std::fs::read(&shot).expect("screenshot written");
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("png header");
    let mut buf = vec![0; reader.output_buffer_size().expect("buffer size")];
    let info = reader.next_frame(&mut buf).expect("png frame");
    assert_eq!((info.width, info.height), (1200, 1800));
    let channels = info.color_type.samples();
    let luma: Vec<f64> = buf[..info.buffer_size()]
        .chunks_exact(channels)
        .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
        .collect();
    let mean = luma.iter().sum::<f64>() / luma.len() as f64;
    let variance = luma.iter().map(|l| (l - mean) * (l - mean)).sum::<f64>() / luma.len() as f64;
    let dark = luma.iter().filter(|l| **l < 128.0).count();
    // A white page with text, tables and two charts: mostly light, with real ink.
    assert!(variance > 100.0, "screenshot looks blank: luma variance {variance:.1}");
    assert!(dark > 2_000, "screenshot has only {dark} dark pixels");
    assert!(mean > 150.0, "the page is light: mean luma {mean:.1}");
}
