//! Command-line interface: argument parsing and exit codes. Thin: all work is in the library.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use dataink::data::PathPolicy;
use dataink::pipeline::{self, Formats, RenderOptions};

const EXIT_CODES: &str = "Exit codes:\n  0  success\n  1  lint errors found (reserved for `dataink lint`)\n  2  bad input (spec, data) or failure";

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
    /// Print the JSON Schema of the spec format (for editor completion and validation).
    #[command(after_help = "Example:\n  dataink schema > dataink.schema.json")]
    Schema,
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
}

/// Run the tool; returns the process exit code.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Schema => match serde_json::to_string_pretty(&dataink::spec::spec_schema()) {
            Ok(text) => {
                println!("{text}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Render { spec, out, format, chart, scale, allow_outside_paths, quiet } => {
            if !scale.is_finite() || scale <= 0.0 || scale > 16.0 {
                eprintln!("error: --scale must be a number in (0, 16], got {scale}");
                return ExitCode::from(2);
            }
            let policy = if allow_outside_paths { PathPolicy::AllowOutside } else { PathPolicy::InsideSpecFolder };
            let loaded = match pipeline::load(&spec, policy) {
                Ok(l) => l,
                Err(failed) => {
                    eprint!("{}", failed.render());
                    let errors = failed.diagnostics.iter().filter(|d| d.is_error()).count();
                    eprintln!(
                        "error: {} problem{} in `{}`",
                        errors,
                        if errors == 1 { "" } else { "s" },
                        spec.display()
                    );
                    return ExitCode::from(2);
                }
            };
            if !quiet {
                for w in &loaded.warnings {
                    eprint!("{}", loaded.source.render(w));
                }
            }
            let formats = Formats {
                svg: format.contains(&Format::Svg),
                png: format.contains(&Format::Png),
                csv: format.contains(&Format::Csv),
                geojson: format.contains(&Format::Geojson),
            };
            let options = RenderOptions { out_dir: out, formats, charts: chart, scale };
            let bar = progress_bar(loaded.spec.chart.len(), quiet);
            let result = pipeline::render_all(&loaded, &options, &|name| {
                bar.set_message(name.to_string());
                bar.inc(1);
            });
            bar.finish_and_clear();
            match result {
                Ok(rendered) => {
                    for r in &rendered {
                        if !quiet {
                            for w in &r.warnings {
                                eprintln!("warning: {w}");
                            }
                            let files: Vec<String> = r.files.iter().map(|f| f.display().to_string()).collect();
                            eprintln!("wrote {}", files.join(", "));
                        }
                    }
                    ExitCode::SUCCESS
                }
                Err(diagnostics) => {
                    for d in &diagnostics {
                        eprint!("{}", loaded.source.render(d));
                    }
                    ExitCode::from(2)
                }
            }
        }
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
