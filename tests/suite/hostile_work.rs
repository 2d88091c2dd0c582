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

/// Render `spec` over one generated CSV `d.csv` and return stderr of a run that must fail with
/// exit code 2 within 60 s.
fn refused(spec: &str, csv: &str) -> String {
    let fixture = Fixture::new(spec, &[("d.csv", csv.as_bytes())]);
    let out = run_dataink(fixture.dir.path(), &["render", "spec.toml", "--out", "out"], 60)
        .expect("the refusal comes within 60 s");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    stderr
}

/// A graph of 10⁶ edges on 10 nodes took 16–24 s and wrote a 136 MB SVG; above the edge cap it
/// is refused before any layout, with the aggregation that fixes it.
#[test]
fn a_network_above_the_edge_cap_is_refused_with_the_fix() {
    let rows = dataink::mark::network_input::MAX_EDGE_ROWS + 1;
    let mut csv = String::with_capacity(rows * 6 + 16);
    csv.push_str("source,target,w\n");
    for i in 0..rows {
        csv.push_str(&format!("{},{},1\n", i % 10, (i / 10) % 10));
    }
    for kind in ["graph", "linkmap"] {
        let spec = format!(
            "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"g\"\nkind = \"{kind}\"\ndata = \"d\"\nsource = \"source\"\ntarget = \"target\"\nweight = \"w\"\n"
        );
        let err = refused(&spec, &csv);
        assert!(
            err.contains(&format!("the edge table has {rows} rows but a network chart draws at most 250000")),
            "{err}"
        );
        assert!(err.contains("groupby = [\"source\", \"target\"]"), "{err}");
    }
}

/// A hyperbolic tree of 10⁶ leaves ran for over 60 s; above the tree cap it is refused at once.
#[test]
fn a_tree_above_the_node_cap_is_refused() {
    let rows = dataink::mark::tree_input::MAX_TREE_ROWS + 1;
    let mut csv = String::with_capacity(rows * 12 + 16);
    csv.push_str("path\n");
    for i in 0..rows {
        csv.push_str(&format!("r/{}/{i}\n", i % 100));
    }
    for kind in ["hypertree", "treemap"] {
        let spec = format!(
            "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"t\"\nkind = \"{kind}\"\ndata = \"d\"\ntree = {{ path = \"path\" }}\n"
        );
        let err = refused(&spec, &csv);
        assert!(err.contains(&format!("the tree has {rows} rows but a tree chart draws at most 250000")), "{err}");
    }
}

/// Filled contours of uniform noise on 1000 × 1000 nodes took 44 s, 11.3 GB and wrote a 395 MB
/// SVG; the crossings are counted before tracing and the chart is refused with the way out.
#[test]
fn contours_of_noise_above_the_crossing_cap_are_refused() {
    let n = 1000;
    let mut state: u64 = 7;
    let mut csv = String::with_capacity(n * n * 16);
    csv.push_str("x,y,z\n");
    for j in 0..n {
        for i in 0..n {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            csv.push_str(&format!("{i},{j},{:.4}\n", (state >> 11) as f64 / (1u64 << 53) as f64));
        }
    }
    let spec = "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"c\"\nkind = \"contour\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\nz = \"z\"\ntitle = \"noise\"\n";
    let err = refused(spec, &csv);
    assert!(err.contains("crossings are traced"), "{err}");
    assert!(err.contains("kind = \"image\""), "{err}");
}

/// Streaklines from a rake of 10,000 seeds release 161 particles each, hundreds of steps per
/// particle (about 6 × 10⁸ steps): particle traces now take their steps from the chart's budget
/// and the chart ends with the budget's warning.
#[test]
fn streaklines_from_ten_thousand_seeds_finish_within_the_budget() {
    let mut csv = String::from("x,y,t,u,v\n");
    for t in [0, 10] {
        for y in 0..10 {
            for x in 0..10 {
                csv.push_str(&format!("{x},{y},{t},0.05,0.01\n"));
            }
        }
    }
    let spec = "[data.f]\npath = \"f.csv\"\n[[chart]]\nname = \"s\"\nkind = \"flow\"\ndata = \"f\"\nx = \"x\"\ny = \"y\"\nu = \"u\"\nv = \"v\"\nt = \"t\"\nlayers = [\"streaklines\"]\nseeds = \"rake\"\nrake = [[0.5, 0.5], [0.5, 8.5]]\nseed_count = 10000\ntitle = \"s\"\n";
    let fixture = Fixture::new(spec, &[("f.csv", csv.as_bytes())]);
    let out = run_dataink(fixture.dir.path(), &["render", "spec.toml", "--out", "out"], 120)
        .expect("the streakline chart finishes within 120 s");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("streamlines or particle traces stopped at the per-chart limit"), "{stderr}");
}
