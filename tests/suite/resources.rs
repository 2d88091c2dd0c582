//! Resource use: each example spec renders in a child process whose peak memory (resident set,
//! measured by `/usr/bin/time`) stays within the bound the README states under Limits.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::common::run_with_timeout;

/// The README's bound: peak resident memory at most `BASE_MIB` plus `PER_INPUT_BYTE` times the
/// bytes of the data files the spec reads.
const BASE_MIB: u64 = 192;
const PER_INPUT_BYTE: u64 = 32;

/// The data files a spec names with `path = "..."`, relative to its folder.
fn data_paths(spec: &Path) -> Vec<PathBuf> {
    let text = std::fs::read_to_string(spec).expect("read the spec");
    let dir = spec.parent().expect("the spec's folder");
    text.lines()
        .filter_map(|l| l.trim_start().strip_prefix("path = \"").and_then(|r| r.split('"').next()))
        .map(|p| dir.join(p))
        .collect()
}

/// Peak resident memory in KiB of `dataink ARGS`, from `/usr/bin/time -f %M`; `None` without it.
fn peak_kib(args: &[&str]) -> Option<u64> {
    let time = Path::new("/usr/bin/time");
    if !time.exists() {
        crate::common::skip_outside_ci(
            "/usr/bin/time is missing (Debian package `time`; .ci/run installs it)",
            "skipped: /usr/bin/time is missing (apt-get install time)",
        );
        return None;
    }
    let mut command = Command::new(time);
    command.args(["-f", "peak-kib %M"]).arg(env!("CARGO_BIN_EXE_dataink")).args(args);
    let out = run_with_timeout(command, 600).expect("the render ends within 600 s");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "dataink {args:?} failed: {stderr}");
    let line = stderr.lines().rev().find_map(|l| l.strip_prefix("peak-kib ")).expect("the peak line of /usr/bin/time");
    Some(line.trim().parse().expect("KiB"))
}

#[test]
fn every_example_renders_within_the_documented_memory_bound() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut specs: Vec<PathBuf> = std::fs::read_dir(&examples)
        .expect("examples/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    specs.sort();
    assert!(!specs.is_empty(), "no example specs in {}", examples.display());
    for spec in specs {
        let input: u64 = data_paths(&spec).iter().map(|p| std::fs::metadata(p).map(|m| m.len()).unwrap_or(0)).sum();
        let out = tempfile::tempdir().expect("temp dir");
        let args = ["render", spec.to_str().unwrap(), "--out", out.path().to_str().unwrap(), "--format", "svg,png"];
        let Some(peak) = peak_kib(&args) else { return };
        let bound = BASE_MIB * 1024 + PER_INPUT_BYTE * input / 1024;
        println!(
            "{}: peak {} MiB for {} KiB of data (bound {} MiB)",
            spec.display(),
            peak / 1024,
            input / 1024,
            bound / 1024
        );
        assert!(
            peak <= bound,
            "{}: peak {peak} KiB over the bound {bound} KiB ({input} bytes of data)",
            spec.display()
        );
    }
}
