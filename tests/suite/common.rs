//! Helpers shared by the integration tests: write a spec and its data into a temporary folder,
//! run the pipeline, and return the outputs or the rendered diagnostics.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use dataink::data::PathPolicy;
use dataink::lint::{ChartLint, Finding};
use dataink::mark::{ChartOutput, DerivedColumn};
use dataink::pipeline::{self, Loaded};
use dataink::scene::{Item, PathCmd, Rect, Role, Shape};

/// A temporary folder holding a spec file and its data files.
pub struct Fixture {
    pub dir: tempfile::TempDir,
    pub spec: PathBuf,
}

impl Fixture {
    /// Write `spec.toml` with `text` and each `(name, bytes)` data file beside it.
    pub fn new(text: &str, files: &[(&str, &[u8])]) -> Fixture {
        let dir = tempfile::tempdir().expect("temp dir");
        for (name, bytes) in files {
            let path = dir.path().join(name);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).expect("mkdir");
            }
            std::fs::write(path, bytes).expect("write data");
        }
        let spec = dir.path().join("spec.toml");
        std::fs::write(&spec, text).expect("write spec");
        Fixture { dir, spec }
    }

    /// Load and check the spec; on failure, the rendered diagnostics.
    pub fn load(&self) -> Result<Loaded, String> {
        self.load_with(PathPolicy::InsideSpecFolder)
    }

    /// Load with a path policy.
    pub fn load_with(&self, policy: PathPolicy) -> Result<Loaded, String> {
        pipeline::load(&self.spec, policy).map_err(|f| f.render())
    }

    /// Load and draw every chart; on failure, the rendered diagnostics.
    pub fn draw(&self) -> Result<Vec<ChartOutput>, String> {
        let loaded = self.load()?;
        let mut out = Vec::new();
        for (i, chart) in loaded.spec.chart.iter().enumerate() {
            match pipeline::draw_chart(&loaded, i, chart) {
                Ok(o) => out.push(o),
                Err(e) => return Err(loaded.source.render(&pipeline::mark_diagnostic(&loaded, &e))),
            }
        }
        Ok(out)
    }

    /// Load, draw and lint every chart; on failure, the rendered diagnostics.
    pub fn lint(&self) -> Result<Vec<ChartLint>, String> {
        let loaded = self.load()?;
        pipeline::draw_and_lint(&loaded, &[])
            .map(|l| l.into_iter().map(|l| l.lint).collect())
            .map_err(|ds| ds.iter().map(|d| loaded.source.render(d)).collect())
    }
}

/// Lint a spec with its data files and return the codes found (every chart, sorted, repeated
/// once per finding); panics with the diagnostics if the spec does not load or draw.
pub fn lint_codes(spec: &str, files: &[(&str, &[u8])]) -> Vec<&'static str> {
    let results = Fixture::new(spec, files).lint().unwrap_or_else(|e| panic!("{e}"));
    let mut codes: Vec<&'static str> = results.iter().flat_map(|c| c.findings.iter().map(|f| f.code)).collect();
    codes.sort_unstable();
    codes
}

/// The findings of one rule in a spec, for asserting on messages.
pub fn lint_findings(spec: &str, files: &[(&str, &[u8])], code: &str) -> Vec<Finding> {
    let results = Fixture::new(spec, files).lint().unwrap_or_else(|e| panic!("{e}"));
    results.into_iter().flat_map(|c| c.findings).filter(|f| f.code == code).collect()
}

/// The plot area of a chart in one cartesian frame: the clip of the data-mark group.
pub fn plot(out: &ChartOutput) -> Rect {
    let mut plot = None;
    out.scene.walk(|item: &Item| {
        if let (Role::DataMark, Shape::Group { clip: Some(c), .. }) = (&item.role, &item.shape) {
            plot = Some(*c);
        }
    });
    plot.expect("a clipped data group")
}

/// Tick label texts of one axis (`"x axis"` or `"y axis"`).
pub fn tick_labels(out: &ChartOutput, axis: &str) -> Vec<String> {
    let mut labels = Vec::new();
    out.scene.walk(|item: &Item| {
        if item.role == Role::TickLabel
            && item.label.as_deref() == Some(axis)
            && let Shape::Text(t) = &item.shape
        {
            labels.push(t.content.clone());
        }
    });
    labels
}

/// The repository root.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The policy for a test whose tool or data comes from outside the repository (installed by
/// `.ci/run`): outside CI print `note` (why the test skips and how to install what it needs)
/// and return, so the caller skips; with `CI` set, fail with `in_ci` instead.
pub fn skip_outside_ci(in_ci: &str, note: &str) {
    assert!(std::env::var_os("CI").is_none(), "{in_ci}");
    eprintln!("{note}");
}

/// Assert that an SVG document parses with usvg.
pub fn assert_svg_parses(svg: &str) {
    if let Err(e) = usvg::Tree::from_str(svg, &usvg::Options::default()) {
        panic!("SVG does not parse: {e}\n{}", &svg[..svg.len().min(2000)]);
    }
}

/// Run a command with a time limit, reading stdout and stderr on threads so a full pipe cannot
/// stall it; `None` when it does not finish within `seconds` (it is then killed).
pub fn run_with_timeout(mut command: std::process::Command, seconds: u64) -> Option<std::process::Output> {
    use std::process::Stdio;
    let mut child = command.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("start the command");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(seconds);
    let drain = |pipe: Option<Box<dyn std::io::Read + Send>>| {
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            if let Some(mut pipe) = pipe {
                let _ = pipe.read_to_end(&mut buf);
            }
            buf
        })
    };
    let stdout = drain(child.stdout.take().map(|p| Box::new(p) as Box<dyn std::io::Read + Send>));
    let stderr = drain(child.stderr.take().map(|p| Box::new(p) as Box<dyn std::io::Read + Send>));
    loop {
        match child.try_wait().expect("poll the command") {
            Some(status) => {
                let stdout = stdout.join().unwrap_or_default();
                let stderr = stderr.join().unwrap_or_default();
                return Some(std::process::Output { status, stdout, stderr });
            }
            None if std::time::Instant::now() > deadline => {
                let _ = child.kill();
                let _ = child.wait();
                return None;
            }
            None => std::thread::sleep(std::time::Duration::from_millis(50)),
        }
    }
}

/// Run `dataink ARGS` in `dir` with a time limit (see [`run_with_timeout`]).
pub fn run_dataink(dir: &Path, args: &[&str], seconds: u64) -> Option<std::process::Output> {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_dataink"));
    command.current_dir(dir).args(args);
    run_with_timeout(command, seconds)
}

/// A NumPy `.npy` file (version 1) of `rows × cols` little-endian f8 values in C order.
pub fn npy_f8(rows: usize, cols: usize, values: &[f64]) -> Vec<u8> {
    let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    npy("<f8", &format!("({rows}, {cols})"), &data)
}

/// A NumPy `.npy` file (version 1, C order) of `descr` cells (`<f4`, `>u2`, ...) of `shape`
/// (`"(2, 3, 4)"`) with the given raw cell bytes.
pub fn npy(descr: &str, shape: &str, data: &[u8]) -> Vec<u8> {
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    while !(10 + header.len() + 1).is_multiple_of(64) {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

/// The drawn bars (rectangular data marks): (label, rectangle, source rows), in drawing order.
pub fn bars(out: &ChartOutput) -> Vec<(String, Rect, Vec<u32>)> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if item.role == Role::DataMark
            && let Shape::Rect(r) = &item.shape
        {
            found.push((item.label.clone().unwrap_or_default(), *r, item.rows.clone()));
        }
    });
    found
}

pub fn derived_column<'a>(out: &'a ChartOutput, name: &str) -> &'a DerivedColumn {
    &out.derived.columns.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no column {name}")).1
}

/// A numeric column of a chart's derived table.
pub fn numbers(out: &ChartOutput, name: &str) -> Vec<f64> {
    match derived_column(out, name) {
        DerivedColumn::Number(v) => v.clone(),
        other => panic!("derived column {name} is not numeric: {other:?}"),
    }
}

/// A text column of a chart's derived table.
pub fn texts(out: &ChartOutput, name: &str) -> Vec<String> {
    match derived_column(out, name) {
        DerivedColumn::Text(v) => v.clone(),
        other => panic!("derived column {name} is not text: {other:?}"),
    }
}

/// The points of a path's moves and lines, in order.
pub fn path_points(cmds: &[PathCmd]) -> Vec<(f64, f64)> {
    cmds.iter()
        .filter_map(|c| match c {
            PathCmd::MoveTo(p) | PathCmd::LineTo(p) => Some((p.x, p.y)),
            _ => None,
        })
        .collect()
}

/// The texts of the axis titles of a chart.
pub fn axis_titles(out: &ChartOutput) -> Vec<String> {
    let mut titles = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Role::AxisTitle, Shape::Text(t)) = (&item.role, &item.shape) {
            titles.push(t.content.clone());
        }
    });
    titles
}

/// A 3-D `.npy` (shape nz × ny × nx, x fastest) of `f(i, j, k)` as f64.
pub fn volume_npy(n: [usize; 3], f: impl Fn(f64, f64, f64) -> f64) -> Vec<u8> {
    let mut data = Vec::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                data.extend(f(i as f64, j as f64, k as f64).to_le_bytes());
            }
        }
    }
    npy("<f8", &format!("({}, {}, {})", n[2], n[1], n[0]), &data)
}

/// Uniform numbers in [0, 1) from a fixed xorshift64 seed: the same sequence on every run, so
/// test data built from it is the same everywhere.
pub fn seeded_uniform() -> impl FnMut() -> f64 {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The first chart of `spec` (over source `d`, read from `d.csv` = `csv`) drawn with its rows
/// left in the source's plan, and drawn from the same rows held in memory (a selection over the
/// source needs them held: its range is over the numeric column `field`); `what` names the
/// case in failures.
pub fn streamed_and_held(spec: &str, csv: &str, field: &str, what: &str) -> (ChartOutput, ChartOutput) {
    let draw = |text: String| {
        let fixture = Fixture::new(&text, &[("d.csv", csv.as_bytes())]);
        let loaded = fixture.load().unwrap_or_else(|e| panic!("{e}"));
        let in_plan = loaded.plans.contains_key("d");
        let out = dataink::pipeline::draw_chart(&loaded, 0, &loaded.spec.chart[0])
            .unwrap_or_else(|e| panic!("{}", loaded.source.render(&dataink::pipeline::mark_diagnostic(&loaded, &e))));
        (out, in_plan)
    };
    let (streamed, in_plan) = draw(spec.to_string());
    let (held, held_in_plan) =
        draw(format!("[selection.some]\ndata = \"d\"\nrange = {{ {field} = [0, 1] }}\n\n{spec}"));
    assert!(in_plan && !held_in_plan, "{what}: in plan {in_plan}, held in plan {held_in_plan}");
    (streamed, held)
}

/// A chart's warnings as the reader sees them.
pub fn warning_texts(out: &ChartOutput) -> Vec<String> {
    out.warnings.iter().map(|w| w.to_string()).collect()
}
