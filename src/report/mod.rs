//! Reports: one self-contained HTML page and a Markdown summary for a linted spec.
//!
//! The page shows every chart as inline SVG with its lint findings, a summary table, the data's
//! provenance (path, rows, columns, SHA-256 of the bytes read) and the spec text. It makes no
//! external request: no scripts, fonts or stylesheets are linked, and a Content-Security-Policy
//! forbids them. The Markdown file holds the summary table and the findings, for CI job
//! summaries.
//!
//! Templates are minijinja files embedded from `templates/` ([`templates`]); a user's own HTML
//! template may replace the built-in one. Every template escapes every value for HTML whatever
//! its file name; the only values passed through as they are are the SVG documents our own
//! renderer wrote, which escape user text themselves.
//!
//! - [`provenance`]: where each data source came from, with its content hash;
//! - [`context`]: the values a template sees;
//! - [`templates`]: the template environment and the built-in templates.

pub mod context;
pub mod provenance;
pub mod templates;

use std::fmt;
use std::path::{Path, PathBuf};

use minijinja::Value;
use minijinja::value::Serde;

use crate::data::{PathError, PathPolicy};
use crate::pipeline::{Linted, Loaded};

pub use templates::TemplateSource;

/// How to build a report.
#[derive(Clone, Debug)]
pub struct ReportOptions {
    /// The path policy the data was loaded under (for re-reading files to hash them).
    pub policy: PathPolicy,
    /// Whether warnings fail the run, as in `dataink lint --deny-warnings`.
    pub deny_warnings: bool,
    /// When the report is made (shown as UTC, RFC 3339).
    pub generated: chrono::DateTime<chrono::Utc>,
    /// A template replacing the built-in HTML one.
    pub html_template: Option<TemplateSource>,
}

/// A finished report.
#[derive(Clone, Debug)]
pub struct Report {
    /// The HTML page (`index.html`).
    pub html: String,
    /// The Markdown summary (`report.md`).
    pub markdown: String,
    /// Whether the run passes: no error findings (nor warnings under `deny_warnings`).
    pub passed: bool,
}

/// Why a report could not be made.
#[derive(Debug)]
pub enum ReportError {
    /// A data path the spec names is refused by the path policy.
    DataPath {
        /// The data source's name.
        name: String,
        /// Why the path was refused.
        error: PathError,
    },
    /// A data file could not be read to hash it.
    ReadData {
        /// The data source's name.
        name: String,
        /// The resolved file path.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A `--template` file could not be read.
    ReadTemplate {
        /// The file given.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A template has a syntax error or failed while rendering.
    Template {
        /// The template's name (its file path for user templates).
        name: String,
        /// minijinja's message, with the template line.
        message: String,
        /// How to fix it.
        hint: &'static str,
    },
    /// A template contains an `{% autoescape %}` block.
    TemplateDisablesEscaping {
        /// The template's name.
        name: String,
        /// 1-based line of the block.
        line: usize,
    },
    /// The output folder's lock could not be taken.
    Lock(crate::output::LockError),
    /// An output file would overwrite one of the run's inputs.
    OverwritesInput(crate::output::InputClash),
    /// An output file could not be written.
    Write {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

impl fmt::Display for ReportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReportError::DataPath { name, error } => write!(f, "data \"{name}\": {error}; {}", error.hint()),
            ReportError::ReadData { name, path, source } => write!(
                f,
                "data \"{name}\": cannot read `{}` to hash it: {source}; check that the file still exists and is readable",
                path.display()
            ),
            ReportError::ReadTemplate { path, source } => write!(
                f,
                "cannot read template `{}`: {source}; give the path of a minijinja template file (see templates/README.md)",
                path.display()
            ),
            ReportError::Template { name, message, hint } => write!(f, "template `{name}`: {message}; {hint}"),
            ReportError::TemplateDisablesEscaping { name, line } => write!(
                f,
                "template `{name}` line {line}: `{{% autoescape %}}` blocks are not allowed; report templates always \
                 escape HTML, so remove the block (the chart SVGs are already marked safe)"
            ),
            ReportError::Lock(e) => write!(f, "{e}"),
            ReportError::OverwritesInput(clash) => {
                write!(f, "{clash}; give another --out folder")
            }
            ReportError::Write { path, source } => {
                write!(f, "cannot write `{}`: {source}; check that the output folder is writable", path.display())
            }
        }
    }
}

impl std::error::Error for ReportError {}

/// Build the HTML page and the Markdown summary for charts drawn and linted from `loaded`.
pub fn build(loaded: &Loaded, linted: &[Linted], options: &ReportOptions) -> Result<Report, ReportError> {
    let spec_dir = provenance::spec_dir(&loaded.source.path);
    let data = provenance::collect(&loaded.spec.data, &loaded.tables, &spec_dir, options.policy)?;
    let generated = options.generated.to_rfc3339_opts(chrono::SecondsFormat::Secs, true);
    let context = context::build(loaded, linted, data, options.deny_warnings, generated);
    let passed = context.summary.passed;
    let value = Value::from(Serde(&context));
    let html_template = match &options.html_template {
        Some(t) => t.clone(),
        None => TemplateSource::new("report.html.jinja", templates::HTML),
    };
    let html = templates::render(&html_template, &value)?;
    let markdown = templates::render(&TemplateSource::new("report.md.jinja", templates::MARKDOWN), &value)?;
    Ok(Report { html, markdown, passed })
}

/// Write `index.html` and `report.md` into `dir` (created if missing), each atomically, holding
/// the folder's lock (`waiting` is called if another run holds it), and refusing to overwrite
/// any of `inputs` (the spec, its data files, the template); returns their paths.
pub fn write(
    report: &Report,
    dir: &Path,
    inputs: &[PathBuf],
    waiting: impl FnOnce(),
) -> Result<[PathBuf; 2], ReportError> {
    let _lock = crate::output::OutputLock::acquire(dir, waiting).map_err(ReportError::Lock)?;
    let html = dir.join("index.html");
    let markdown = dir.join("report.md");
    crate::output::refuse_inputs(&[html.clone(), markdown.clone()], inputs).map_err(ReportError::OverwritesInput)?;
    for (path, text) in [(&html, &report.html), (&markdown, &report.markdown)] {
        crate::output::write_file(path, text.as_bytes())
            .map_err(|source| ReportError::Write { path: path.clone(), source })?;
    }
    Ok([html, markdown])
}
