//! Runaway work: inputs that once made a chart compute for minutes now finish within a bound, each
//! run as a child process with a timeout so a regression fails instead of hanging the suite.

use crate::common::{Fixture, run_dataink};

/// Streamlines over a 12-row field whose x spans 0, 1e-9, 1 and 1e9 (u = 1, v = x) ran for more
/// than 600 s: every line crowded into one background cell, so each step scanned a growing list.
/// The spacing test now takes from the chart's budget and the chart ends with its warning.
#[test]
fn streamlines_on_a_field_spanning_eighteen_decades_finish() {
    let mut csv = String::from("x,y,u,v\n");
    for y in [0, 1, 2] {
        for x in ["0", "1e-9", "1", "1e9"] {
            csv.push_str(&format!("{x},{y},1,{x}\n"));
        }
    }
    let spec = "[data.f]\npath = \"f.csv\"\n[[chart]]\nname = \"s\"\nkind = \"flow\"\ndata = \"f\"\nx = \"x\"\ny = \"y\"\nu = \"u\"\nv = \"v\"\n";
    let fixture = Fixture::new(spec, &[("f.csv", csv.as_bytes())]);
    let out = run_dataink(fixture.dir.path(), &["render", "spec.toml", "--out", "out"], 120)
        .expect("the streamline chart finishes within 120 s");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_ne!(out.status.code(), Some(101), "{stderr}");
    assert!(out.status.code().is_some(), "killed by a signal: {stderr}");
}
