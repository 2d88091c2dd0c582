//! Command-line interface: argument parsing and exit codes. Thin: all work is in the library.

mod output;
mod serve;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use dataink::data::PathPolicy;
use dataink::pipeline::{self, Formats, RenderOptions};
use output::{errln, errs, outln};

const EXIT_CODES: &str = "Exit codes:\n  0  success\n  1  lint errors found (`dataink lint`, `dataink report`; with --deny-warnings, warnings too)\n  2  bad input (spec, data) or failure";

/// Declarative visualization: render the charts of a TOML spec to SVG and PNG.
#[derive(Parser, Debug)]
#[command(name = "dataink", version, about, after_help = format!(
    "Examples:\n  dataink render examples/gallery.toml --out out\n  dataink render spec.toml --chart iris-scatter --format png --scale 2\n  dataink schema > dataink.schema.json\n\n{EXIT_CODES}"
))]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render every chart of a spec to files in an output folder.
    #[command(after_help = format!(
        "Examples:\n  dataink render examples/gallery.toml --out out\n  dataink render examples/gallery.toml --chart iris-scatter --format svg,png,csv\n  dataink render spec.toml --format png --scale 2   # high-DPI PNG\n\n{EXIT_CODES}"
    ))]
    Render {
        /// The spec file (TOML).
        spec: PathBuf,
        /// Output folder; created if missing.
        #[arg(long, short, default_value = "out")]
        out: PathBuf,
        /// Output formats, comma-separated.
        #[arg(long, short, value_delimiter = ',', default_value = "svg,png")]
        format: Vec<Format>,
        /// Render only this chart (repeat for several).
        #[arg(long)]
        chart: Vec<String>,
        /// Device pixels per CSS pixel in PNG output (2 for high-DPI screens).
        #[arg(long, default_value_t = 1.0)]
        scale: f64,
        /// Allow data paths outside the spec's folder (absolute, or climbing out with `..`).
        #[arg(long)]
        allow_outside_paths: bool,
        /// Print nothing but errors.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Check every chart of a spec against the good-visualization rules.
    #[command(after_help = format!(
        "Examples:\n  dataink lint examples/gallery.toml\n  dataink lint spec.toml --format sarif > lint.sarif\n  dataink lint spec.toml --format junit --deny-warnings > lint.xml\n  dataink lint --rules   # list every rule\n\n{EXIT_CODES}"
    ))]
    Lint {
        /// The spec file (TOML).
        #[arg(required_unless_present = "rules")]
        spec: Option<PathBuf>,
        /// Output format, written to standard output.
        #[arg(long, short, default_value = "text")]
        format: LintFormat,
        /// Fail (exit code 1) on warnings too, not only on errors.
        #[arg(long)]
        deny_warnings: bool,
        /// Lint only this chart (repeat for several).
        #[arg(long)]
        chart: Vec<String>,
        /// Allow data paths outside the spec's folder (absolute, or climbing out with `..`).
        #[arg(long)]
        allow_outside_paths: bool,
        /// List every rule (code, name, severity, what it checks) and exit.
        #[arg(long)]
        rules: bool,
    },
    /// Build an HTML report (charts, lint findings, data provenance, the spec) and a Markdown
    /// summary for CI.
    #[command(after_help = format!(
        "Writes DIR/index.html (one self-contained page) and DIR/report.md (summary table and findings).\n\nExamples:\n  dataink report examples/gallery.toml --out report\n  dataink report spec.toml --out report --deny-warnings\n  dataink report spec.toml --out report --template my-report.html.jinja\n\n{EXIT_CODES}"
    ))]
    Report {
        /// The spec file (TOML).
        spec: PathBuf,
        /// Output folder for index.html and report.md; created if missing.
        #[arg(long, short)]
        out: PathBuf,
        /// A minijinja template replacing the built-in HTML one (see templates/README.md).
        #[arg(long)]
        template: Option<PathBuf>,
        /// Report only this chart (repeat for several).
        #[arg(long)]
        chart: Vec<String>,
        /// Fail (exit code 1) on warnings too, not only on errors.
        #[arg(long)]
        deny_warnings: bool,
        /// Allow data paths outside the spec's folder (absolute, or climbing out with `..`).
        #[arg(long)]
        allow_outside_paths: bool,
    },
    /// Open a window with every chart of a spec: brush to select rows (linked across the charts
    /// of a data source), hover, zoom and pan, refocus hyperbolic trees, save the selection.
    #[command(after_help = format!(
        "Keys: drag brushes (shift adds, alt removes, Esc or a click clears), scroll zooms, right-drag pans,\n\
         double-click resets; in a hyperbolic tree drag moves the focus and a click centres a node.\n\
         Save writes DIR/selection.toml ([selection.NAME] tables) and the open tab's charts as SVG and PNG.\n\n\
         Needs a build with the `explore` feature: cargo run --release --features explore -- explore SPEC\n\n\
         Examples:\n  dataink explore examples/gallery.toml\n  dataink explore spec.toml --out picked\n\n{EXIT_CODES}"
    ))]
    Explore {
        /// The spec file (TOML).
        spec: PathBuf,
        /// Folder Save writes into; created when saving.
        #[arg(long, short, default_value = "explore-out")]
        out: PathBuf,
        /// Allow data paths outside the spec's folder (absolute, or climbing out with `..`).
        #[arg(long)]
        allow_outside_paths: bool,
    },
    /// Print each data source of a spec as its charts see it: the columns and their types, the
    /// number of rows and the first rows, after the source's transforms.
    #[command(after_help = format!(
        "Only the spec's [data] tables need to be valid; charts are not checked.\n\nExamples:\n  dataink data examples/gallery.toml\n  dataink data spec.toml cars --rows 20\n\n{EXIT_CODES}"
    ))]
    Data {
        /// The spec file (TOML).
        spec: PathBuf,
        /// Only this data source.
        source: Option<String>,
        /// How many rows to show.
        #[arg(long, default_value_t = 10)]
        rows: usize,
        /// Allow data paths outside the spec's folder (absolute, or climbing out with `..`).
        #[arg(long)]
        allow_outside_paths: bool,
    },
    /// Serve the pipeline over HTTP: post a spec (and its data files) and get a chart as SVG, PNG
    /// or CSV, the lint findings (JSON, SARIF), the report page or the spec's diagnostics.
    #[command(after_help = format!(
        "Data paths resolve under --root (symlinks must stay inside it) unless the request uploads the files.\n\
         GET /api/openapi.json describes the API. Needs a build with the `serve` feature:\n  \
         cargo run --release --features serve -- serve --root examples\n\n\
         Examples:\n  dataink serve --root examples\n  \
         curl --data-binary @examples/gallery.toml 'http://127.0.0.1:8700/api/render?chart=iris-scatter&format=png' -o iris.png\n\n{EXIT_CODES}"
    ))]
    Serve(serve::ServeArgs),
    /// Print the JSON Schema of the spec format (for editor completion and validation).
    #[command(after_help = "Example:\n  dataink schema > dataink.schema.json")]
    Schema,
}

/// `dataink explore`: the window, in builds with the `explore` feature.
#[cfg(feature = "explore")]
fn explore(spec: &std::path::Path, out: PathBuf, policy: PathPolicy) -> ExitCode {
    let loaded = match load_or_report(spec, policy) {
        Ok(l) => l,
        Err(code) => return code,
    };
    for w in &loaded.warnings {
        errs!("{}", loaded.source.render(w));
    }
    let title = format!("dataink explore — {}", spec.display());
    let session = dataink::explore::Session::new(loaded, 1.0);
    match dataink::explore::app::run(session, out, &title) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            errln!("error: cannot open the window: {e}");
            errln!("hint: `dataink explore` needs a display (X11) with OpenGL; `dataink render` works without one");
            ExitCode::from(2)
        }
    }
}

/// `dataink explore` in a build without the window: say how to get it.
#[cfg(not(feature = "explore"))]
fn explore(_spec: &std::path::Path, _out: PathBuf, _policy: PathPolicy) -> ExitCode {
    errln!("error: this dataink was built without the interactive window");
    errln!("hint: build it with the `explore` feature:");
    errln!("  cargo run --release --features explore -- explore SPEC");
    errln!("  cargo install --path . --features explore");
    ExitCode::from(2)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Format {
    /// Scalable vector graphics.
    Svg,
    /// Raster image.
    Png,
    /// Derived geometry in data coordinates.
    Csv,
    /// Derived geometry as GeoJSON (contour lines and bands).
    Geojson,
    /// 3-D surfaces as glTF 2.0 binary (isosurfaces).
    Glb,
    /// 3-D surfaces as PLY (isosurfaces).
    Ply,
    /// 3-D surfaces as Wavefront OBJ (isosurfaces).
    Obj,
}

/// Output formats of `dataink lint`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum LintFormat {
    /// Human-readable findings with hints.
    Text,
    /// Machine-readable findings.
    Json,
    /// SARIF 2.1.0, for code-scanning uploads.
    Sarif,
    /// JUnit XML, one test case per chart.
    Junit,
}

/// Load a spec, printing every problem on failure.
fn load_or_report(spec: &std::path::Path, policy: PathPolicy) -> Result<pipeline::Loaded, ExitCode> {
    pipeline::load(spec, policy).map_err(|failed| {
        errs!("{}", failed.render());
        let errors = failed.diagnostics.iter().filter(|d| d.is_error()).count();
        errln!("error: {} problem{} in `{}`", errors, if errors == 1 { "" } else { "s" }, spec.display());
        ExitCode::from(2)
    })
}

/// Draw and lint the charts, printing every problem on failure.
fn draw_and_lint_or_report(loaded: &pipeline::Loaded, charts: &[String]) -> Result<Vec<pipeline::Linted>, ExitCode> {
    pipeline::draw_and_lint(loaded, charts).map_err(|diagnostics| {
        for d in &diagnostics {
            errs!("{}", loaded.source.render(d));
        }
        ExitCode::from(2)
    })
}

/// `dataink lint`.
fn lint(
    spec: &std::path::Path,
    format: LintFormat,
    deny_warnings: bool,
    charts: &[String],
    policy: PathPolicy,
) -> ExitCode {
    let loaded = match load_or_report(spec, policy) {
        Ok(l) => l,
        Err(code) => return code,
    };
    let linted = match draw_and_lint_or_report(&loaded, charts) {
        Ok(l) => l,
        Err(code) => return code,
    };
    let results: Vec<dataink::lint::ChartLint> = linted.into_iter().map(|l| l.lint).collect();
    let path = spec.display().to_string();
    let text = match format {
        LintFormat::Text => dataink::lint::output::text(&path, &results),
        LintFormat::Json => dataink::lint::output::json(&path, &results),
        LintFormat::Sarif => dataink::lint::output::sarif(&path, &results),
        LintFormat::Junit => dataink::lint::output::junit(&path, &results, deny_warnings),
    };
    outln!("{}", text.trim_end());
    if dataink::lint::fails(&results, deny_warnings) { ExitCode::from(1) } else { ExitCode::SUCCESS }
}

/// `dataink report`.
fn report(
    spec: &std::path::Path,
    out: &std::path::Path,
    template: Option<&std::path::Path>,
    charts: &[String],
    deny_warnings: bool,
    policy: PathPolicy,
) -> ExitCode {
    let html_template = match template.map(dataink::report::TemplateSource::read).transpose() {
        Ok(t) => t,
        Err(e) => {
            errln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let loaded = match load_or_report(spec, policy) {
        Ok(l) => l,
        Err(code) => return code,
    };
    for w in &loaded.warnings {
        errs!("{}", loaded.source.render(w));
    }
    let linted = match draw_and_lint_or_report(&loaded, charts) {
        Ok(l) => l,
        Err(code) => return code,
    };
    let options =
        dataink::report::ReportOptions { policy, deny_warnings, generated: chrono::Utc::now(), html_template };
    let written = dataink::report::build(&loaded, &linted, &options).and_then(|report| {
        let mut inputs = pipeline::input_files(&loaded);
        inputs.extend(template.map(std::path::Path::to_path_buf));
        dataink::report::write(&report, out, &inputs, || say_waiting(out)).map(|files| (report.passed, files))
    });
    match written {
        Ok((passed, files)) => {
            let files: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
            errln!("wrote {}", files.join(", "));
            if passed { ExitCode::SUCCESS } else { ExitCode::from(1) }
        }
        Err(e) => {
            errln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// " (by convention: u = \"u\", v = \"v\")" for a chart that took conventional defaults, else "".
fn defaults_note(loaded: &pipeline::Loaded, chart: &str) -> String {
    match loaded.defaults.get(chart) {
        Some(taken) if !taken.is_empty() => {
            let keys: Vec<String> = taken.iter().map(|t| format!("{} = {}", t.key, t.value)).collect();
            format!(" (by convention: {})", keys.join(", "))
        }
        _ => String::new(),
    }
}

/// `dataink lint --rules`: every rule, one per line.
/// `dataink data`: each source's schema and first rows after its transforms.
fn data_preview(spec: &std::path::Path, only: Option<&str>, rows: usize, policy: PathPolicy) -> ExitCode {
    match pipeline::preview_sources(spec, policy, only, rows.min(10_000)) {
        Ok(previews) => {
            let mut text = String::new();
            for p in previews {
                if let Some(summary) = &p.volume {
                    text.push_str(&format!("data \"{}\": {}\n{summary}\n", p.name, p.head));
                    continue;
                }
                text.push_str(&format!("data \"{}\": {} rows, {} columns\n", p.name, p.rows, p.schema.len()));
                for (name, dtype) in &p.schema {
                    text.push_str(&format!("  {name}: {dtype}\n"));
                }
                text.push_str(&p.head);
                text.push_str("\n\n");
            }
            output::out(format_args!("{text}"));
            ExitCode::SUCCESS
        }
        Err(failed) => {
            errs!("{}", failed.render());
            ExitCode::from(2)
        }
    }
}

fn list_rules() -> ExitCode {
    for r in dataink::lint::rules::ALL {
        outln!("{}  {:<28} {:<8} {:<11} {}", r.code, r.name, r.severity.name(), r.category.name(), r.summary);
    }
    ExitCode::SUCCESS
}

/// Run the tool; returns the process exit code.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Schema => match serde_json::to_string_pretty(&dataink::spec::spec_schema()) {
            Ok(text) => {
                outln!("{text}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                errln!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Lint { rules: true, .. } => list_rules(),
        Command::Data { spec, source, rows, allow_outside_paths } => {
            let policy = if allow_outside_paths { PathPolicy::AllowOutside } else { PathPolicy::InsideSpecFolder };
            data_preview(&spec, source.as_deref(), rows, policy)
        }
        Command::Serve(args) => serve::serve(args),
        Command::Explore { spec, out, allow_outside_paths } => {
            let policy = if allow_outside_paths { PathPolicy::AllowOutside } else { PathPolicy::InsideSpecFolder };
            explore(&spec, out, policy)
        }
        Command::Lint { spec: Some(spec), format, deny_warnings, chart, allow_outside_paths, rules: false } => {
            let policy = if allow_outside_paths { PathPolicy::AllowOutside } else { PathPolicy::InsideSpecFolder };
            lint(&spec, format, deny_warnings, &chart, policy)
        }
        Command::Report { spec, out, template, chart, deny_warnings, allow_outside_paths } => {
            let policy = if allow_outside_paths { PathPolicy::AllowOutside } else { PathPolicy::InsideSpecFolder };
            report(&spec, &out, template.as_deref(), &chart, deny_warnings, policy)
        }
        Command::Lint { spec: None, .. } => {
            errln!("error: give a spec file to lint, or --rules");
            ExitCode::from(2)
        }
        Command::Render { spec, out, format, chart, scale, allow_outside_paths, quiet } => {
            if !scale.is_finite() || scale <= 0.0 || scale > 16.0 {
                errln!("error: --scale must be a number in (0, 16], got {scale}");
                return ExitCode::from(2);
            }
            let policy = if allow_outside_paths { PathPolicy::AllowOutside } else { PathPolicy::InsideSpecFolder };
            let loaded = match load_or_report(&spec, policy) {
                Ok(l) => l,
                Err(code) => return code,
            };
            if !quiet {
                for w in &loaded.warnings {
                    errs!("{}", loaded.source.render(w));
                }
            }
            let formats = Formats {
                svg: format.contains(&Format::Svg),
                png: format.contains(&Format::Png),
                csv: format.contains(&Format::Csv),
                geojson: format.contains(&Format::Geojson),
                glb: format.contains(&Format::Glb),
                ply: format.contains(&Format::Ply),
                obj: format.contains(&Format::Obj),
            };
            let waiting = if quiet { None } else { Some(say_waiting as fn(&std::path::Path)) };
            let options = RenderOptions { out_dir: out, formats, charts: chart, scale, waiting };
            let bar = progress_bar(loaded.spec.chart.len(), quiet);
            let scans = (!loaded.plans.is_empty()).then(|| ScanBar::start(quiet));
            let result = pipeline::render_all(&loaded, &options, &|name| {
                bar.set_message(name.to_string());
                bar.inc(1);
            });
            bar.finish_and_clear();
            if let Some(scans) = scans {
                scans.finish();
            }
            let (rendered, diagnostics) = match result {
                Ok(rendered) => (rendered, Vec::new()),
                Err(failure) => (failure.rendered, failure.diagnostics),
            };
            if !quiet {
                for r in &rendered {
                    for w in &r.warnings {
                        errln!("warning: {w}");
                    }
                    let files: Vec<String> = r.files.iter().map(|f| f.display().to_string()).collect();
                    if files.is_empty() {
                        // E.g. `--format glb` for a chart with no surface.
                        errln!("wrote nothing for chart \"{}\": it has nothing in the formats asked for", r.name);
                    } else {
                        errln!("wrote {}{}", files.join(", "), defaults_note(&loaded, &r.name));
                    }
                    errln!("lint {}", r.lint.summary_line());
                }
            }
            for d in &diagnostics {
                errs!("{}", loaded.source.render(d));
            }
            if diagnostics.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(2) }
        }
    }
}

/// Tell the user that another run is writing into `dir` and this one waits for it.
fn say_waiting(dir: &std::path::Path) {
    errln!("waiting for another dataink run writing into `{}` to finish", dir.display());
}

/// A bar of the rows the density charts' scans have read, while they stream a source's rows
/// through its plan (on an interactive terminal only, like [`progress_bar`]).
struct ScanBar {
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    watcher: std::thread::JoinHandle<()>,
}

impl ScanBar {
    fn start(quiet: bool) -> ScanBar {
        use std::sync::atomic::Ordering;
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let bar = progress_bar(usize::MAX, quiet);
        if let Ok(style) = indicatif::ProgressStyle::with_template("{bar:30} {human_pos}/{human_len} rows scanned") {
            bar.set_style(style);
        }
        let stopping = std::sync::Arc::clone(&stop);
        let watcher = std::thread::spawn(move || {
            while !stopping.load(Ordering::Relaxed) {
                let (scanned, total) = dataink::data::density::plan::PROGRESS.get();
                bar.set_length(total.max(1));
                bar.set_position(scanned.min(total));
                std::thread::sleep(std::time::Duration::from_millis(100));
            }
            bar.finish_and_clear();
        });
        ScanBar { stop, watcher }
    }

    fn finish(self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        let _ = self.watcher.join();
    }
}

/// A progress bar on an interactive terminal; hidden otherwise (CI logs stay quiet).
fn progress_bar(len: usize, quiet: bool) -> indicatif::ProgressBar {
    if quiet || !std::io::stderr().is_terminal() || len < 2 {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} charts {msg}") {
        bar.set_style(style);
    }
    bar
}
