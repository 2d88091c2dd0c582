//! The command-line tool end to end: the README's gallery command, exit codes, help and schema.

use std::process::Command;

use crate::common::{assert_svg_parses, root};

fn dataink() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dataink"))
}

#[test]
fn gallery_renders_every_chart_as_svg_png_and_csv() {
    let out = tempfile::tempdir().expect("temp dir");
    let status = dataink()
        .args(["render", "examples/gallery.toml", "--format", "svg,png,csv", "--out"])
        .arg(out.path())
        .current_dir(root())
        .output()
        .expect("run dataink");
    let stderr = String::from_utf8_lossy(&status.stderr);
    assert!(status.status.success(), "{stderr}");
    let spec = std::fs::read_to_string(root().join("examples/gallery.toml")).expect("gallery");
    // Each chart's name and the kind written after it.
    let quoted = |l: &str, key: &str| l.strip_prefix(key).and_then(|r| r.strip_suffix('"')).map(str::to_string);
    let mut names: Vec<(String, String)> = Vec::new();
    for line in spec.lines() {
        if let Some(name) = quoted(line, "name = \"") {
            names.push((name, String::new()));
        } else if let (Some(kind), Some(last)) = (quoted(line, "kind = \""), names.last_mut()) {
            last.1 = kind;
        }
    }
    assert!(names.len() >= 6, "{names:?}");
    for (name, kind) in names {
        let svg = std::fs::read_to_string(out.path().join(format!("{name}.svg"))).expect("svg written");
        assert_svg_parses(&svg);
        let png = std::fs::read(out.path().join(format!("{name}.png"))).expect("png written");
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{name}.png is a PNG");
        let csv = std::fs::read_to_string(out.path().join(format!("{name}.csv"))).expect("csv written");
        // A header and rows: one per point, line, cell... or per group for box plots and violins;
        // one per surface for isosurfaces, one per transfer-function point (or colour-bar end)
        // for volume rendering.
        let rows = csv.lines().count() - 1;
        assert!(rows >= if kind == "isosurface" || kind == "volume" { 1 } else { 3 }, "{name}.csv has rows");
    }
    // The cars data has missing values: the warning says how many rows were dropped.
    assert!(stderr.contains("warning: chart \"cars-power\": dropped 14 of 406 rows"), "{stderr}");
}

#[test]
fn chart_filter_and_scale_set_the_png_size() {
    let out = tempfile::tempdir().expect("temp dir");
    let status = dataink()
        .args(["render", "examples/gallery.toml", "--chart", "decay", "--format", "png", "--scale", "2", "--out"])
        .arg(out.path())
        .current_dir(root())
        .output()
        .expect("run dataink");
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
    let files: Vec<_> = std::fs::read_dir(out.path()).expect("out dir").collect();
    assert_eq!(files.len(), 1);
    let png = std::fs::read(out.path().join("decay.png")).expect("png");
    // IHDR width and height (big-endian) at bytes 16..24: the decay chart is 480×320 at scale 2.
    let w = u32::from_be_bytes([png[16], png[17], png[18], png[19]]);
    let h = u32::from_be_bytes([png[20], png[21], png[22], png[23]]);
    assert_eq!((w, h), (960, 640));
}

#[test]
fn bad_spec_exits_with_code_2_and_unknown_chart_is_named() {
    let out = tempfile::tempdir().expect("temp dir");
    let run = dataink()
        .args(["render", "examples/gallery.toml", "--chart", "iris-scater", "--out"])
        .arg(out.path())
        .current_dir(root())
        .output()
        .expect("run dataink");
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("error: no chart named `iris-scater` in the spec"), "{stderr}");
    assert!(stderr.contains("did you mean `iris-scatter`?"), "{stderr}");

    let run = dataink().args(["render", "no/such/spec.toml"]).output().expect("run dataink");
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("cannot read spec file `no/such/spec.toml`"));
}

#[test]
fn help_shows_examples_and_exit_codes() {
    for args in [&["--help"][..], &["render", "--help"][..], &["schema", "--help"][..]] {
        let run = dataink().args(args).output().expect("run dataink");
        assert!(run.status.success());
        let text = String::from_utf8_lossy(&run.stdout);
        assert!(text.contains("Example"), "{args:?}: {text}");
    }
    let run = dataink().args(["render", "--help"]).output().expect("run dataink");
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("2  bad input"), "{text}");
}

#[test]
fn schema_is_json_with_closed_chart_tables() {
    let run = dataink().arg("schema").output().expect("run dataink");
    assert!(run.status.success());
    let schema: serde_json::Value = serde_json::from_slice(&run.stdout).expect("schema is JSON");
    let text = schema.to_string();
    assert!(text.contains("\"additionalProperties\":false"));
    assert!(text.contains("scatter") && text.contains("line"));
}

#[test]
fn three_mistakes_are_reported_in_one_run_with_exit_code_2() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("iris.csv"), "petal_length,petal_width,species\n1,2,a\n").expect("data");
    let spec = "[data.iris]\npath = \"iris.csv\"\n\n[[chart]]\nname = \"iris\"\nkind = \"scatter\"\ndata = \"iris\"\nx = \"petal_lenght\"\ny = \"petal_width\"\ncolour = \"species\"\nsize = \"big\"\n";
    std::fs::write(dir.path().join("spec.toml"), spec).expect("spec");
    let run = dataink().args(["render", "spec.toml", "--out", "out"]).current_dir(dir.path()).output().expect("run");
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    for (position, message) in [
        ("spec.toml:10:1", "unknown key `colour`"),
        ("spec.toml:11:8", "`size` must be an array of 2 numbers, found a string"),
        ("spec.toml:8:5", "has no column `petal_lenght`"),
    ] {
        assert!(stderr.contains(position) && stderr.contains(message), "{position} {message}: {stderr}");
    }
    assert_eq!(stderr.matches("= hint:").count(), 3, "{stderr}");
    assert!(stderr.contains("error: 3 problems in `spec.toml`"), "{stderr}");
    assert!(!dir.path().join("out").exists(), "nothing is written when the spec has errors");
}

/// Run `dataink` with `args` in `dir`, its standard output a pipe whose reading end is already
/// closed: the exit code and standard error.
fn run_into_closed_pipe(args: &[&str], dir: &std::path::Path) -> (Option<i32>, String) {
    let (reader, writer) = std::io::pipe().expect("pipe");
    drop(reader);
    let run = dataink()
        .args(args)
        .current_dir(dir)
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .output()
        .expect("run dataink");
    (run.status.code(), String::from_utf8_lossy(&run.stderr).into_owned())
}

#[test]
fn a_closed_standard_output_ends_every_command_quietly() {
    let fx = crate::common::Fixture::new(
        "[data.d]\nvalues = [{ x = 1, y = 2 }, { x = 2, y = 3 }]\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\n",
        &[],
    );
    let spec = fx.spec.to_str().expect("utf-8 path");
    for args in [&["schema"][..], &["lint", "--rules"], &["lint", spec, "--format", "json"], &["lint", spec]] {
        let (code, stderr) = run_into_closed_pipe(args, fx.dir.path());
        assert_eq!(code, Some(0), "dataink {args:?}: {stderr}");
        assert_eq!(stderr, "", "dataink {args:?} says nothing");
    }
}

#[test]
fn a_failing_chart_does_not_hide_the_charts_that_were_written() {
    let fx = crate::common::Fixture::new(
        r#"
[data.d]
values = [{ k = "a", v = 1.0 }, { k = "b", v = 2.0 }]

[[chart]]
name = "good"
kind = "bar"
data = "d"
x = "k"
y = "v"

[[chart]]
name = "bad"
kind = "bar"
data = "d"
x = "k"
y = { field = "v", scale = "log" }
"#,
        &[],
    );
    let out = fx.dir.path().join("out");
    let run = dataink()
        .args(["render", "spec.toml", "--format", "svg", "--out"])
        .arg(&out)
        .current_dir(fx.dir.path())
        .output()
        .expect("run dataink");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    let wrote = stderr.find(&format!("wrote {}", out.join("good.svg").display())).expect(&stderr);
    let lint = stderr.find("lint ").expect(&stderr);
    let error = stderr.find("error: chart \"bad\": a bar's length is measured from zero").expect(&stderr);
    assert!(wrote < lint && lint < error, "written files and their lint line come before the error:\n{stderr}");
    assert!(out.join("good.svg").is_file());
    assert!(!out.join("bad.svg").exists());
}

#[test]
fn the_summary_line_names_the_defaults_a_chart_took() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("e.csv"), "source,target\na,b\nb,c\n").unwrap();
    let spec = "[data.e]\npath = \"e.csv\"\n\n[[chart]]\nname = \"g\"\ndata = \"e\"\nkind = \"graph\"\n\n\
                [[chart]]\nname = \"h\"\ndata = \"e\"\nkind = \"graph\"\nsource = \"target\"\ntarget = \"source\"\n";
    std::fs::write(dir.path().join("spec.toml"), spec).unwrap();
    let run = dataink().args(["render", "spec.toml", "--out", "out"]).current_dir(dir.path()).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(stderr.contains("out/g.png (by convention: source = \"source\", target = \"target\")\n"), "{stderr}");
    assert!(stderr.contains("out/h.png\n"), "a chart naming its columns takes nothing: {stderr}");
}
