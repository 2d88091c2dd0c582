//! The template engine set up for reports: minijinja with HTML auto-escaping forced for every
//! template whatever its file name, every printed value stripped of control and bidi characters,
//! the `safe` filter removed, `{% autoescape %}` blocks refused, and undefined values as errors
//! (so a misspelt variable in a user template is reported, not printed as nothing).

use minijinja::value::ValueKind;
use minijinja::{AutoEscape, Environment, ErrorKind, UndefinedBehavior, Value};

use super::ReportError;

/// The built-in HTML report template (`templates/report.html.jinja`).
pub const HTML: &str = include_str!("../../templates/report.html.jinja");

/// The built-in Markdown report template (`templates/report.md.jinja`), for CI job summaries.
pub const MARKDOWN: &str = include_str!("../../templates/report.md.jinja");

/// A template's name (used in error messages) and source text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TemplateSource {
    /// Shown in errors: the file path for user templates.
    pub name: String,
    /// The template text.
    pub text: String,
}

impl TemplateSource {
    /// A template from its name and text.
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> TemplateSource {
        TemplateSource { name: name.into(), text: text.into() }
    }

    /// Read a user template file.
    pub fn read(path: &std::path::Path) -> Result<TemplateSource, ReportError> {
        use crate::data::regular_file::{MAX_TEMPLATE_BYTES, read_capped};
        let text = read_capped(path, MAX_TEMPLATE_BYTES, "template")
            .and_then(|bytes| {
                String::from_utf8(bytes)
                    .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidData, "it is not UTF-8 text"))
            })
            .map_err(|source| ReportError::ReadTemplate { path: path.to_path_buf(), source })?;
        Ok(TemplateSource { name: path.display().to_string(), text })
    }
}

/// Fuel of one template render: minijinja takes about one unit per instruction and per 64 bytes
/// of data a template builds, so this bounds a runaway loop to seconds. The built-in templates
/// use a small fraction of it even for large reports.
pub const TEMPLATE_FUEL: u64 = 50_000_000;

/// The environment every report template renders in.
pub fn environment<'s>() -> Environment<'s> {
    let mut env = Environment::new();
    env.set_fuel(Some(TEMPLATE_FUEL));
    // Every template escapes for HTML, whatever its name says (`.md`, `.txt`, no extension):
    // Markdown renders entities as the characters they stand for, and raw HTML in a Markdown
    // job summary would be live.
    env.set_auto_escape_callback(|_| AutoEscape::Html);
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    // Our SVG arrives already marked safe; nothing else may be.
    env.remove_filter("safe");
    env.add_filter("md", md);
    env.set_formatter(|out, state, value| minijinja::escape_formatter(out, state, &shown(value)));
    env
}

/// A value as printed by `{{ ... }}`: its text with hidden characters removed
/// ([`crate::visible::multiline`]: no control or bidi characters), whether it is a plain string,
/// a safe one (the SVGs, `|e` output) or a list or map printed whole. Escaping comes after.
fn shown(value: &Value) -> Value {
    use crate::visible::multiline;
    use std::borrow::Cow;
    match value.kind() {
        ValueKind::String => match value.as_str().map(multiline) {
            Some(Cow::Owned(clean)) if value.is_safe() => Value::from_safe_string(clean),
            Some(Cow::Owned(clean)) => Value::from(clean),
            _ => value.clone(),
        },
        ValueKind::Seq | ValueKind::Map | ValueKind::Iterable | ValueKind::Plain => {
            Value::from(multiline(&value.to_string()).into_owned())
        }
        _ => value.clone(),
    }
}

/// Render `template` with `context`.
pub fn render(template: &TemplateSource, context: &Value) -> Result<String, ReportError> {
    if let Some(line) = autoescape_block_line(&template.text) {
        return Err(ReportError::TemplateDisablesEscaping { name: template.name.clone(), line });
    }
    let mut env = environment();
    let error = |e: minijinja::Error| ReportError::Template {
        name: template.name.clone(),
        message: e.to_string(),
        hint: template_hint(e.kind()),
    };
    env.add_template_owned(template.name.clone(), template.text.clone()).map_err(error)?;
    env.get_template(&template.name).and_then(|t| t.render(context)).map_err(error)
}

/// How to fix a template error of `kind`.
fn template_hint(kind: ErrorKind) -> &'static str {
    match kind {
        ErrorKind::UndefinedError => "check the name against the variables listed in templates/README.md",
        ErrorKind::UnknownFilter => {
            "use one of minijinja's built-in filters or `md`; `safe` is not available (values are always escaped)"
        }
        ErrorKind::OutOfFuel => {
            "the template ran over its work limit of 50,000,000 steps (see README, Limits): \
             loop over fewer items, or do not nest loops over the charts or rows"
        }
        ErrorKind::SyntaxError => {
            "fix the template syntax at that line (Jinja2 syntax: {{ value }}, {% for %}, {% if %})"
        }
        _ => "see templates/README.md for the variables and filters a report template can use",
    }
}

/// The 1-based line of the first `{% autoescape ... %}` tag, if any. Blocks are refused whatever
/// their argument: escaping is not the template's choice.
fn autoescape_block_line(text: &str) -> Option<usize> {
    let mut from = 0;
    while let Some(found) = text.get(from..).and_then(|rest| rest.find("{%")) {
        let start = from + found;
        let after = text.get(start + 2..).unwrap_or("");
        let tag = after.trim_start_matches(['-', '+', '~']).trim_start();
        if tag.starts_with("autoescape") {
            return Some(text.get(..start).map_or(1, |before| before.matches('\n').count() + 1));
        }
        from = start + 2;
    }
    None
}

/// The `md` filter: text made inert inside Markdown (table cells, list items). Characters that
/// start emphasis, links, images, code, tables or headings get a backslash; line breaks become
/// spaces. HTML escaping still applies after it (`<` becomes `&lt;`, which Markdown shows as
/// `<`).
pub fn md(value: Value) -> String {
    if value.is_none() || value.is_undefined() {
        return String::new();
    }
    let text = value.as_str().map_or_else(|| value.to_string(), str::to_string);
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        match c {
            '\\' | '`' | '*' | '_' | '[' | ']' | '(' | ')' | '{' | '}' | '#' | '+' | '!' | '|' | '~' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' | '\t' => out.push(' '),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use minijinja::value::Serde;

    fn render_str(text: &str, ctx: Value) -> Result<String, ReportError> {
        render(&TemplateSource::new("t.txt", text), &ctx)
    }

    #[test]
    fn every_template_escapes_html_whatever_its_name() {
        let ctx = Value::from(Serde(serde_json::json!({ "x": "</script><script>alert(1)</script>" })));
        for name in ["a.txt", "a.md", "noext", "a.html"] {
            let out = render(&TemplateSource::new(name, "{{ x }}"), &ctx).expect("renders");
            assert_eq!(out, "&lt;&#x2f;script&gt;&lt;script&gt;alert(1)&lt;&#x2f;script&gt;", "{name}");
        }
    }

    #[test]
    fn safe_strings_from_rust_pass_and_the_safe_filter_is_gone() {
        let ctx = Value::from(Serde(serde_json::json!({ "x": "<b>" })));
        let svg = Value::from_safe_string("<svg/>".into());
        let out = render_str("{{ svg }}", minijinja::context! { svg => svg }).expect("renders");
        assert_eq!(out, "<svg/>");
        let err = render_str("{{ x|safe }}", ctx).expect_err("no safe filter");
        assert!(err.to_string().contains("unknown filter"), "{err}");
    }

    #[test]
    fn autoescape_blocks_are_refused_with_their_line() {
        let err = render_str("a\nb\n{%- autoescape false %}{{ x }}{% endautoescape %}", Value::UNDEFINED)
            .expect_err("refused");
        assert!(matches!(&err, ReportError::TemplateDisablesEscaping { line: 3, .. }), "{err:?}");
        assert_eq!(autoescape_block_line("{% if x %}{% endif %}"), None);
    }

    #[test]
    fn undefined_variables_are_errors_naming_the_template() {
        let err = render_str("line one\n{{ chart.titel }}", minijinja::context! {}).expect_err("undefined");
        let text = err.to_string();
        assert!(text.contains("t.txt"), "{text}");
    }

    #[test]
    fn printed_values_lose_control_and_bidi_characters() {
        let hostile = "t\u{0}\u{7}\u{1b}[31m\u{202e}x\r\ny";
        let ctx = minijinja::context! {
            s => hostile,
            list => vec![hostile],
            svg => Value::from_safe_string(format!("<svg>{hostile}</svg>")),
        };
        let out =
            render_str("{{ s }}|{{ s|e }}|{{ s|md }}|{{ list }}|{{ list|join(',') }}|{{ svg }}", ctx).expect("renders");
        for c in ['\u{0}', '\u{7}', '\u{1b}', '\u{202e}', '\r'] {
            assert!(!out.contains(c), "{c:?} in {out:?}");
        }
        assert!(out.starts_with("t[31mx\ny|t[31mx\ny|t\\[31mx  y|"), "{out:?}");
        assert!(out.ends_with("|<svg>t[31mx\ny</svg>"), "{out:?}");
    }

    #[test]
    fn md_filter_neutralizes_markdown() {
        assert_eq!(md(Value::from("a|b ![x](http://e) *y*\nz")), "a\\|b \\!\\[x\\]\\(http://e\\) \\*y\\* z");
        assert_eq!(md(Value::from(())), "");
        assert_eq!(md(Value::from(3)), "3");
    }
}
