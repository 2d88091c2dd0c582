//! Output that is safe to write: a run killed or failing mid-write leaves no partial file under a
//! final name, links at final names are replaced rather than followed, two runs into one folder
//! do not mix their files, and no output overwrites the spec's own inputs.

use crate::common::{Fixture, run_dataink, run_with_timeout};
use std::path::Path;
use std::time::Duration;

/// A scatter of `rows` points in three charts: SVG, PNG and CSV outputs of a few MB each.
fn big_fixture(rows: usize) -> Fixture {
    let mut csv = String::from("x,y\n");
    for i in 0..rows {
        let t = i as f64 * 0.618_033_988_7;
        csv.push_str(&format!("{},{}\n", t.fract(), (t * 1.7).sin()));
    }
    let charts: String = ["a", "b", "c"]
        .iter()
        .map(|n| {
            format!(
                "[[chart]]\nname = \"{n}\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\ntitle = \"{n}\"\n"
            )
        })
        .collect();
    Fixture::new(&format!("[data.d]\npath = \"d.csv\"\n{charts}"), &[("d.csv", csv.as_bytes())])
}

/// Every file under a final name in `out` (not a dot-file) parses completely: SVG as XML by usvg,
/// PNG by the decoder down to the last row, CSV as rows of the header's width ending in a newline.
fn assert_every_final_file_parses(out: &Path) {
    let Ok(entries) = std::fs::read_dir(out) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let bytes = std::fs::read(entry.path()).expect("read output");
        match name.rsplit_once('.').map(|(_, ext)| ext) {
            Some("svg") => {
                let text = std::str::from_utf8(&bytes).unwrap_or_else(|_| panic!("{name}: not UTF-8"));
                usvg::Tree::from_str(text, &usvg::Options::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
            }
            Some("png") => {
                let mut reader = png::Decoder::new(std::io::Cursor::new(&bytes[..]))
                    .read_info()
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                let mut buf = vec![0; reader.output_buffer_size().expect("size")];
                reader.next_frame(&mut buf).unwrap_or_else(|e| panic!("{name}: {e}"));
            }
            Some("csv") => {
                let text = std::str::from_utf8(&bytes).unwrap_or_else(|_| panic!("{name}: not UTF-8"));
                assert!(text.ends_with('\n'), "{name}: ends mid-line");
                let mut lines = text.lines();
                let width = lines.next().expect("header").split(',').count();
                for line in lines {
                    assert_eq!(line.split(',').count(), width, "{name}: short row `{line}`");
                }
            }
            _ => panic!("unexpected output {name}"),
        }
    }
}

fn final_names(out: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(out)
        .map(|entries| entries.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default();
    names.retain(|n| !n.starts_with('.'));
    names.sort();
    names
}

/// `dataink render` with a file-size limit (in KiB) set by the shell: the kernel stops the
/// process (SIGXFSZ) at the first write past it, exactly mid-file; with the signal ignored the
/// write fails instead, as on a full disk.
#[cfg(unix)]
fn render_with_file_limit(dir: &Path, kib: u64, ignore_signal: bool) -> std::process::Output {
    let trap = if ignore_signal { "trap '' XFSZ; " } else { "" };
    let script =
        format!("{trap}ulimit -f {kib}; exec \"$0\" render spec.toml --out out --format svg --format png --format csv");
    let mut command = std::process::Command::new("sh");
    command.current_dir(dir).arg("-c").arg(script).arg(env!("CARGO_BIN_EXE_dataink"));
    run_with_timeout(command, 120).expect("render finished within 120 s")
}

#[cfg(unix)]
#[test]
fn a_run_stopped_mid_write_leaves_no_partial_file() {
    use std::os::unix::process::ExitStatusExt;
    let fx = big_fixture(60_000);
    // Each chart's SVG is several MB: the limit stops the first one mid-file.
    let out = render_with_file_limit(fx.dir.path(), 1024, false);
    assert_eq!(out.status.signal(), Some(25), "stopped by SIGXFSZ: {out:?}");
    let outputs = fx.dir.path().join("out");
    assert_every_final_file_parses(&outputs);
    assert!(final_names(&outputs).iter().all(|n| !n.ends_with(".svg")), "{:?}", final_names(&outputs));
}

#[cfg(unix)]
#[test]
fn a_failed_write_is_an_error_and_leaves_nothing_partial() {
    let fx = big_fixture(60_000);
    let out = render_with_file_limit(fx.dir.path(), 1024, true);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("cannot write `out/a.svg`: File too large"), "{stderr}");
    let outputs = fx.dir.path().join("out");
    assert_every_final_file_parses(&outputs);
    // No temporary file stays behind either: only whole outputs.
    let all: Vec<String> =
        std::fs::read_dir(&outputs).unwrap().flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect();
    assert!(all.iter().all(|n| !n.starts_with('.')), "{all:?}");
}

#[cfg(unix)]
#[test]
fn kill_9_at_any_moment_leaves_only_whole_files() {
    let fx = big_fixture(60_000);
    let outputs = fx.dir.path().join("out");
    for delay_ms in [150, 400, 700, 1000, 1400, 1900, 2500, 3200] {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_dataink"))
            .current_dir(fx.dir.path())
            .args(["render", "spec.toml", "--out", "out", "--format", "svg", "--format", "png", "--format", "csv"])
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("start render");
        std::thread::sleep(Duration::from_millis(delay_ms));
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        assert_every_final_file_parses(&outputs);
    }
    // The next run cleans up what the killed ones left and writes everything.
    let done =
        run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--format", "svg"], 120).expect("finished");
    assert!(done.status.success(), "{}", String::from_utf8_lossy(&done.stderr));
    let all: Vec<String> =
        std::fs::read_dir(&outputs).unwrap().flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect();
    assert!(all.iter().all(|n| !n.ends_with(".tmp")), "{all:?}");
    assert_every_final_file_parses(&outputs);
}

#[cfg(unix)]
#[test]
fn a_link_at_an_output_name_is_replaced_not_followed() {
    let fx = big_fixture(10);
    let outputs = fx.dir.path().join("out");
    std::fs::create_dir(&outputs).unwrap();
    let precious = fx.dir.path().join("precious.txt");
    std::fs::write(&precious, "keep me").unwrap();
    std::os::unix::fs::symlink(&precious, outputs.join("a.svg")).unwrap();
    let out = run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out"], 60).expect("finished");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(std::fs::read_to_string(&precious).unwrap(), "keep me");
    assert!(!std::fs::symlink_metadata(outputs.join("a.svg")).unwrap().file_type().is_symlink());
    assert_every_final_file_parses(&outputs);
}

#[test]
fn an_output_over_an_input_is_refused_before_drawing() {
    // A chart named like its data file, written as CSV beside it.
    let spec = "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"d\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\ntitle = \"t\"\n";
    let data: &[u8] = b"x,y\n1,2\n2,3\n";
    let fx = Fixture::new(spec, &[("d.csv", data)]);
    let out =
        run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", ".", "--format", "csv"], 60).expect("finished");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("output `./d.csv` would overwrite the input"), "{stderr}");
    assert_eq!(std::fs::read(fx.dir.path().join("d.csv")).unwrap(), data);
    // The same through a folder link: `out` is the spec's own folder by another name.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(fx.dir.path(), fx.dir.path().join("out")).unwrap();
        let out = run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--format", "csv"], 60)
            .expect("finished");
        assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
        assert_eq!(std::fs::read(fx.dir.path().join("d.csv")).unwrap(), data);
    }
    // A report whose page would replace the spec.
    let fx = Fixture::new(spec, &[("d.csv", data)]);
    std::fs::rename(fx.dir.path().join("spec.toml"), fx.dir.path().join("report.md")).unwrap();
    let out = run_dataink(fx.dir.path(), &["report", "report.md", "--out", "."], 60).expect("finished");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("would overwrite the input `report.md`"), "{stderr}");
    assert_eq!(std::fs::read_to_string(fx.dir.path().join("report.md")).unwrap(), spec);
}

#[test]
fn two_runs_into_one_folder_leave_one_run_s_files() {
    // Two specs draw chart `c` at different sizes; whichever run finishes last, the SVG and the
    // PNG in the folder must come from the same run (the lock serialises the two).
    let spec = |w: u32, h: u32| {
        format!(
            "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\ntitle = \"t\"\nsize = [{w}, {h}]\n"
        )
    };
    let fx = big_fixture(20_000);
    std::fs::write(fx.dir.path().join("small.toml"), spec(300, 200)).unwrap();
    std::fs::write(fx.dir.path().join("large.toml"), spec(900, 700)).unwrap();
    for _ in 0..3 {
        let start = |name: &str| {
            std::process::Command::new(env!("CARGO_BIN_EXE_dataink"))
                .current_dir(fx.dir.path())
                .args(["render", name, "--out", "out"])
                .stderr(std::process::Stdio::null())
                .spawn()
                .expect("start")
        };
        let (mut a, mut b) = (start("small.toml"), start("large.toml"));
        assert!(a.wait().unwrap().success() && b.wait().unwrap().success());
        let svg = std::fs::read_to_string(fx.dir.path().join("out/c.svg")).unwrap();
        let png = std::fs::read(fx.dir.path().join("out/c.png")).unwrap();
        let info = png::Decoder::new(std::io::Cursor::new(&png[..])).read_info().unwrap().info().clone();
        let svg_width = if svg.contains("width=\"300\"") { 300 } else { 900 };
        assert!(svg.contains(&format!("width=\"{svg_width}\"")));
        assert_eq!(info.width, svg_width, "the PNG comes from the same run as the SVG");
    }
}
