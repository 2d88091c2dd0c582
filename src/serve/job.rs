//! One request's work, on a blocking thread: put the uploads in a private folder, load the spec
//! against them (or against the server's root), check the request's limits, draw, and write
//! the answer in the asked format.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use axum::http::StatusCode;

use super::Limits;
use super::cache::Input;
use super::reply::{Problem, Reply, diagnostics_json};
use super::submitted::Submitted;
use crate::data::PathPolicy;
use crate::pipeline::{self, Loaded};
use crate::spec::{Diagnostic, PathSeg, SourceFile, SpecDoc};

/// What a request asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// One chart as SVG.
    Svg,
    /// One chart as PNG.
    Png,
    /// One chart's derived table as CSV.
    Csv,
    /// Every chart's lint findings (or the one asked for) as JSON.
    Lint,
    /// The same as SARIF 2.1.0.
    Sarif,
    /// The report page (HTML).
    Report,
    /// Only the spec's diagnostics, as JSON.
    Check,
}

impl Format {
    /// The formats `render` answers in, as the query names them.
    pub const NAMES: &'static str = "svg, png, csv, lint, sarif or report";
}

/// The request's query, checked.
#[derive(Clone, Debug)]
pub struct Asked {
    /// The answer's format.
    pub format: Format,
    /// The chart, by name (the first chart when `None`, for one chart's formats).
    pub chart: Option<String>,
    /// Device pixels per CSS pixel for PNG.
    pub scale: f64,
}

impl Asked {
    /// Read `format`, `chart` and `scale` from the query (`check`: the check endpoint, which takes
    /// none of them).
    pub fn from_query(query: &HashMap<String, String>, check: bool) -> Result<Asked, Problem> {
        let bad = |message: String| Problem::new(StatusCode::BAD_REQUEST, message);
        if let Some(key) = query.keys().find(|k| !["format", "chart", "scale"].contains(&k.as_str())) {
            return Err(bad(format!("unknown query key `{}`; the keys are format, chart and scale", visible(key))));
        }
        let format = if check {
            Format::Check
        } else {
            match query.get("format").map(String::as_str).unwrap_or("svg") {
                "svg" => Format::Svg,
                "png" => Format::Png,
                "csv" => Format::Csv,
                "lint" | "json" => Format::Lint,
                "sarif" => Format::Sarif,
                "report" | "html" => Format::Report,
                other => return Err(bad(format!("unknown format `{}`; use {}", visible(other), Format::NAMES))),
            }
        };
        let scale = match query.get("scale") {
            None => 1.0,
            Some(text) => text
                .parse::<f64>()
                .ok()
                .filter(|s| s.is_finite() && (0.25..=8.0).contains(s))
                .ok_or_else(|| bad(format!("`scale` must be a number from 0.25 to 8, not `{}`", visible(text))))?,
        };
        Ok(Asked { format, chart: query.get("chart").cloned(), scale })
    }

    /// The request's parameters as one line, for its cache key.
    pub fn describe(&self) -> String {
        format!("{:?}|{:?}|{}", self.format, self.chart, self.scale)
    }
}

fn visible(text: &str) -> String {
    crate::visible::single_line(text).chars().take(80).collect()
}

/// A finished answer and the files under the root it was made from.
pub struct Answer {
    /// The reply.
    pub reply: Reply,
    /// Files under the root the spec read (none for uploads, which the cache key holds).
    pub inputs: Vec<Input>,
    /// Whether the answer may be kept: no input changed after the work began (a file rewritten
    /// during the render would otherwise keep the old answer under the new file's stamp).
    pub cacheable: bool,
}

/// Do the work `asked` and `submitted` describe, data paths resolving in `root` unless files
/// were uploaded.
pub fn run(root: &Path, limits: &Limits, asked: &Asked, submitted: Submitted) -> Result<Answer, Problem> {
    let started = std::time::SystemTime::now();
    refuse_engines(&submitted.spec)?;
    let uploads = Uploads::write(&submitted.files)?;
    let dir = uploads.as_ref().map_or(root, Uploads::path);
    let source = SourceFile { path: dir.join("request.toml"), text: submitted.spec };
    let loaded = match pipeline::load_source(source, dir, PathPolicy::InsideSpecFolder) {
        Ok(loaded) => loaded,
        Err(failed) => return Err(Problem::diagnostics(&failed.source, &failed.diagnostics)),
    };
    check_rows(&loaded, limits)?;
    let reply = answer(&loaded, limits, asked)?;
    let inputs: Vec<Input> = match uploads {
        Some(_) => Vec::new(),
        None => pipeline::input_files(&loaded).into_iter().skip(1).map(Input::now).collect(),
    };
    let cacheable = inputs.iter().all(|i| i.stamp.is_some_and(|(_, modified)| modified < started));
    Ok(Answer { reply, inputs, cacheable })
}

fn answer(loaded: &Loaded, limits: &Limits, asked: &Asked) -> Result<Reply, Problem> {
    let failed = |diagnostics: Vec<Diagnostic>| Problem::diagnostics(&loaded.source, &diagnostics);
    let names: Vec<String> = asked.chart.iter().cloned().collect();
    match asked.format {
        Format::Check => {
            let charts: Vec<&str> = loaded.spec.chart.iter().map(|c| c.name.as_str()).collect();
            let body = serde_json::json!({
                "charts": charts,
                "diagnostics": diagnostics_json(&loaded.source, &loaded.warnings),
            });
            Ok(Reply::ok("application/json", serde_json::to_string_pretty(&body).unwrap_or_default()))
        }
        Format::Svg | Format::Png | Format::Csv => {
            let selected = pipeline::select_charts(&loaded.spec, &names).map_err(|d| failed(vec![d]))?;
            let Some(&(index, chart)) = selected.first() else {
                return Err(Problem::new(StatusCode::UNPROCESSABLE_ENTITY, "the spec has no chart"));
            };
            if asked.format == Format::Png {
                check_canvas(loaded, index, chart, asked.scale, limits).map_err(|d| failed(vec![d]))?;
            }
            let out = pipeline::draw_chart(loaded, index, chart)
                .map_err(|e| failed(vec![pipeline::mark_diagnostic(loaded, &e)]))?;
            Ok(match asked.format {
                Format::Svg => Reply::ok("image/svg+xml", crate::render::svg::to_svg(&out.scene)),
                Format::Png => {
                    let png = crate::render::png::to_png(&out.scene, asked.scale)
                        .map_err(|e| failed(vec![Diagnostic::error(format!("chart \"{}\": {e}", chart.name))]))?;
                    Reply::ok("image/png", png)
                }
                _ => {
                    let empty = crate::data::Table::default();
                    let csv = out.derived.to_csv(loaded.tables.get(&chart.data).unwrap_or(&empty));
                    Reply::ok("text/csv; charset=utf-8", csv)
                }
            })
        }
        Format::Lint | Format::Sarif | Format::Report => {
            let linted = pipeline::draw_and_lint(loaded, &names).map_err(failed)?;
            let results: Vec<_> = linted.iter().map(|l| l.lint.clone()).collect();
            Ok(match asked.format {
                Format::Lint => Reply::ok("application/json", crate::lint::output::json("request.toml", &results)),
                Format::Sarif => {
                    Reply::ok("application/sarif+json", crate::lint::output::sarif("request.toml", &results))
                }
                _ => {
                    let options = crate::report::ReportOptions {
                        policy: PathPolicy::InsideSpecFolder,
                        deny_warnings: false,
                        generated: chrono::Utc::now(),
                        html_template: None,
                    };
                    let report = crate::report::build(loaded, &linted, &options)
                        .map_err(|e| failed(vec![Diagnostic::error(e.to_string())]))?;
                    Reply::ok("text/html; charset=utf-8", report.html)
                }
            })
        }
    }
}

/// A served spec reads files only: a source on a query engine (`engine = "sc://..."`) would have
/// the server connect wherever the request says, so it is refused before anything is loaded.
fn refuse_engines(text: &str) -> Result<(), Problem> {
    let Ok(doc) = SpecDoc::parse(text) else { return Ok(()) };
    let json = doc.to_json();
    let Some(sources) = json.get("data").and_then(|d| d.as_object()) else { return Ok(()) };
    let diagnostics: Vec<Diagnostic> = sources
        .iter()
        .filter(|(_, source)| source.get("engine").is_some())
        .map(|(name, _)| {
            let path = [PathSeg::Key("data".into()), PathSeg::Key(name.clone()), PathSeg::Key("engine".into())];
            Diagnostic::error(format!("data \"{name}\": this server reads files only, not sources on a query engine"))
                .at_opt(doc.span_of(&path))
                .with_hint("run the spec with `dataink render`, or upload the data as a file")
        })
        .collect();
    if diagnostics.is_empty() {
        return Ok(());
    }
    let source = SourceFile { path: PathBuf::from("request.toml"), text: text.to_string() };
    Err(Problem::diagnostics(&source, &diagnostics))
}

/// Every data source within the row limit (a source left in its plan counts its plan's rows).
fn check_rows(loaded: &Loaded, limits: &Limits) -> Result<(), Problem> {
    let held = loaded.tables.iter().map(|(name, t)| (name, t.rows as u64));
    let planned = loaded.plans.iter().map(|(name, p)| (name, p.rows()));
    for (name, rows) in held.chain(planned) {
        if rows > limits.rows {
            return Err(Problem::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                format!("data \"{name}\" has {rows} rows; this server draws at most {} rows per source", limits.rows),
            ));
        }
    }
    Ok(())
}

/// The chart's PNG within the pixel limit (and a canvas the renderer accepts), checked as
/// `dataink render` checks it, before drawing.
fn check_canvas(
    loaded: &Loaded,
    index: usize,
    chart: &crate::spec::Chart,
    scale: f64,
    limits: &Limits,
) -> Result<(), Diagnostic> {
    let (pw, ph) = pipeline::png_canvas(loaded, index, chart, scale)?;
    let pixels = u64::from(pw) * u64::from(ph);
    if pixels > limits.pixels {
        let message =
            format!("the PNG would be {pw} × {ph} = {pixels} pixels; this server draws at most {}", limits.pixels);
        let error = crate::mark::MarkError::at(&["size"], message, "make `size` or `scale` smaller");
        return Err(pipeline::mark_diagnostic(loaded, &error.in_chart(index, &chart.name)));
    }
    Ok(())
}

/// A request's uploaded files in a folder of their own (readable by this user only, under an
/// unpredictable name), removed when done.
struct Uploads {
    dir: tempfile::TempDir,
}

impl Uploads {
    /// `None` when nothing was uploaded.
    fn write(files: &[(String, axum::body::Bytes)]) -> Result<Option<Uploads>, Problem> {
        if files.is_empty() {
            return Ok(None);
        }
        let failed = |e: std::io::Error| {
            Problem::new(StatusCode::INTERNAL_SERVER_ERROR, format!("cannot keep the uploaded files: {e}"))
        };
        let dir = tempfile::Builder::new().prefix("dataink-serve-").tempdir().map_err(failed)?;
        for (name, bytes) in files {
            let path = dir.path().join(name);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).map_err(failed)?;
            }
            std::fs::write(path, bytes).map_err(failed)?;
        }
        Ok(Some(Uploads { dir }))
    }

    fn path(&self) -> &Path {
        self.dir.path()
    }
}
