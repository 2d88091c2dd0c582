//! Sources on a real Spark Connect server (`engine = "sc://..."`): a Spark standalone master,
//! two workers with one executor each and a Spark Connect server, started as separate processes
//! on 127.0.0.1 by `scripts/spark_cluster.sh` (Spark from PyPI's `pyspark`, installed by
//! `.ci/run`). The same specs run in-process and on the engine and their count grids are
//! compared bit for bit; the engine's errors name it and the query; an executor killed in the
//! middle of a query leaves either the right grid or an error, never a wrong grid.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use crate::common::{Fixture, root, run_with_timeout, seeded_uniform, skip_outside_ci};
use dataink::data::density::Bins;
use dataink::data::density::plan::PlanRows;
use dataink::data::engine::{EngineQuery, EngineUrl};
use dataink::mark::ChartOutput;
use polars::prelude::*;

/// A running cluster, stopped when dropped.
struct Cluster {
    dir: tempfile::TempDir,
    url: String,
}

fn script() -> PathBuf {
    root().join("scripts/spark_cluster.sh")
}

impl Cluster {
    /// Start one, or `None` (outside CI) when Java or pyspark is missing.
    fn start() -> Option<Cluster> {
        let java = Command::new("java").arg("-version").output().is_ok_and(|o| o.status.success());
        let pyspark = Command::new("python3").args(["-c", "import pyspark"]).output().is_ok_and(|o| o.status.success());
        if !(java && pyspark) {
            skip_outside_ci(
                "Java and pyspark are needed for the Spark Connect tests (.ci/run installs pyspark)",
                "note: skipping the Spark Connect tests: run `bash scripts/spark_cluster.sh install` (needs Java 17+)",
            );
            return None;
        }
        let dir = tempfile::tempdir().expect("temp dir");
        let mut start = Command::new("bash");
        start.arg(script()).arg("start").arg(dir.path());
        let out = run_with_timeout(start, 400).expect("the cluster started within 400 s");
        let mut cluster = Cluster { url: String::new(), dir };
        assert!(
            out.status.success(),
            "spark_cluster.sh start failed:\n{}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        let url = std::fs::read_to_string(cluster.dir.path().join("connect_url")).expect("connect_url");
        cluster.url = url.trim().to_string();
        Some(cluster)
    }

    /// Process ids of the executors.
    fn executors(&self) -> Vec<u32> {
        let out = Command::new("bash").arg(script()).arg("executors").arg(self.dir.path()).output().expect("executors");
        String::from_utf8_lossy(&out.stdout).lines().filter_map(|l| l.trim().parse().ok()).collect()
    }

    fn query(&self, query: &str, seconds: u64) -> EngineQuery {
        EngineQuery {
            url: EngineUrl::parse(&self.url).expect("url"),
            query: query.to_string(),
            timeout: Duration::from_secs(seconds),
        }
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        let _ = Command::new("bash").arg(script()).arg("stop").arg(self.dir.path()).output();
    }
}

/// `n` seeded rows: `x` (f32) on a lattice of quarter steps, so values sit exactly on bin edges,
/// every 97th missing and every 101st NaN; `y` (f64) spread over [0, 7), every 89th ≤ 0 (for a log
/// axis) and one infinite; `t` a timestamp (µs) one minute per row.
fn points(n: usize) -> DataFrame {
    let mut next = seeded_uniform();
    let mut xs = Vec::with_capacity(n);
    let mut ys = Vec::with_capacity(n);
    for i in 0..n {
        let x = (next() * 40.0).floor() as f32 / 4.0;
        xs.push(if i % 97 == 0 {
            None
        } else if i % 101 == 0 {
            Some(f32::NAN)
        } else {
            Some(x)
        });
        let y = next() * next() * 7.0;
        ys.push(if i == 5 {
            f64::INFINITY
        } else if i % 89 == 0 {
            -y
        } else {
            y
        });
    }
    let ts: Vec<i64> = (0..n as i64).map(|i| 1_700_000_000_000_000 + i * 60_000_000).collect();
    let mut df = df!("x" => xs, "y" => ys, "t" => ts).expect("frame");
    let t = df.column("t").expect("t").cast(&DataType::Datetime(TimeUnit::Microseconds, None)).expect("cast");
    df.with_column(t).expect("t");
    df
}

fn parquet(df: &mut DataFrame) -> Vec<u8> {
    let mut bytes = Vec::new();
    ParquetWriter::new(&mut bytes).with_row_group_size(Some(50_000)).finish(df).expect("parquet");
    bytes
}

fn spec(engine: Option<&str>, source: &str, chart: &str) -> String {
    let engine = engine.map(|u| format!("engine = \"{u}\"\n")).unwrap_or_default();
    format!(
        "[data.p]\npath = \"p.parquet\"\n{engine}{source}\n[[chart]]\nname = \"d\"\nkind = \"scatter\"\ndata = \"p\"\n\
         title = \"Rows\"\n{chart}\n"
    )
}

fn draw(text: &str, file: &[u8]) -> Result<(ChartOutput, bool), String> {
    let fixture = Fixture::new(text, &[("p.parquet", file)]);
    let loaded = fixture.load()?;
    let kept = loaded.plans.contains_key("p");
    let out = dataink::pipeline::draw_chart(&loaded, 0, &loaded.spec.chart[0])
        .map_err(|e| loaded.source.render(&dataink::pipeline::mark_diagnostic(&loaded, &e)))?;
    Ok((out, kept))
}

/// The grid in-process (the file's plan) and on the engine (`query`), over the same bins.
fn both_grids(cluster: &Cluster, file: &Path, query: &str, x: (&str, &Bins), y: (&str, &Bins), repeat: u64) {
    let frame = LazyFrame::scan_parquet(file.to_str().expect("path").into(), Default::default()).expect("scan");
    let local = PlanRows::new(frame, "p").expect("plan").count(x.0, y.0, x.1, y.1).expect("count");
    let remote = PlanRows::on_engine(cluster.query(query, 300), "p").expect("engine rows");
    let grid = remote.count(x.0, y.0, x.1, y.1).expect("engine count");
    let scaled: Vec<u64> = local.counts.iter().map(|c| c * repeat).collect();
    assert_eq!(grid.counts, scaled);
    assert_eq!((grid.missing, grid.outside), (local.missing * repeat, local.outside * repeat));
    let l = &local.losses;
    let scaled = [l.missing, l.infinite, l.non_positive, l.outside].map(|a| a.map(|v| v * repeat));
    let r = &grid.losses;
    assert_eq!([r.missing, r.infinite, r.non_positive, r.outside], scaled, "why rows missed the grid, per axis");
}

#[test]
fn spark_connect_sources_count_the_grid_in_process_counts() {
    let Some(cluster) = Cluster::start() else { return };
    let mut df = points(120_000);
    let file = parquet(&mut df);
    let url = cluster.url.clone();

    // The same spec, in-process and on the engine: the same bins, counts and warnings.
    for (source, chart) in [
        ("", "x = \"x\"\ny = \"y\"\nmode = \"density\""),
        (
            "transform = [{ sql = \"SELECT x, y, t FROM source WHERE t IS NOT NULL\" }]",
            "x = \"x\"\ny = { field = \"y\", scale = \"log\" }\nmode = \"density\"",
        ),
        ("", "x = \"t\"\ny = \"y\"\nmode = \"density\"\nbin = 3"),
        ("transform = [{ filter = \"y < 2 and x != 3\" }]", "x = \"x\"\ny = \"y\"\nmode = \"density\""),
        // Domains that cut rows on each axis: the same counts outside, per axis.
        (
            "",
            "x = { field = \"x\", domain = [1, 8] }\ny = { field = \"y\", scale = \"log\", domain = [0.1, 5] }\n\
             mode = \"density\"",
        ),
    ] {
        let (local, _) = draw(&spec(None, source, chart), &file).unwrap_or_else(|e| panic!("{e}"));
        let (remote, kept) = draw(&spec(Some(&url), source, chart), &file).unwrap_or_else(|e| panic!("{chart}: {e}"));
        assert!(kept, "the engine source's rows stay on the engine");
        assert_eq!(remote.derived, local.derived, "{source} {chart}");
        assert_eq!(remote.warnings, local.warnings, "{source} {chart}");
    }

    // A chart that draws rows gets them back (only the columns it needs).
    let points_chart = "x = \"x\"\ny = \"y\"\nmode = \"points\"";
    let (local, _) = draw(&spec(None, "", points_chart), &file).unwrap_or_else(|e| panic!("{e}"));
    let (remote, kept) = draw(&spec(Some(&url), "", points_chart), &file).unwrap_or_else(|e| panic!("{e}"));
    assert!(!kept);
    assert_eq!(remote.scene.items.len(), local.scene.items.len());
    assert_eq!(remote.warnings, local.warnings);

    // Grids at bin edges, log axes and a `sql` step, against the plan in-process directly.
    let dir = tempfile::tempdir().expect("dir");
    let path = dir.path().join("p.parquet");
    std::fs::write(&path, &file).expect("write");
    let read = format!("SELECT * FROM parquet.`{}`", path.display());
    // Rows for a chart that draws them come back only up to a limit, else an error says why.
    let err = cluster.query(&read, 120).rows_of(None, 1000).expect_err("120,000 rows are more than 1,000");
    assert!(err.contains("more than 1000 rows") && err.contains("density"), "{err}");
    assert_eq!(
        cluster.query(&read, 120).rows_of(Some(&["y".to_string()]), 120_000).expect("rows").shape(),
        (120_000, 1)
    );
    let (bx, by) = (Bins::new(0.0, 10.0, 40, false).expect("bins"), Bins::new(0.01, 7.0, 57, true).expect("bins"));
    both_grids(&cluster, &path, &read, ("x", &bx), ("y", &by), 1);
    let odd = Bins::new(-0.3, 9.7, 1000, false).expect("bins");
    both_grids(&cluster, &path, &read, ("x", &odd), ("y", &by), 1);

    // The engine's own errors, a time limit and a closed port name the engine and the query.
    let bad = spec(Some(&url), "transform = [{ filter = \"nope > 1\" }]", "x = \"x\"\ny = \"y\"\nmode = \"density\"");
    let err = draw(&bad, &file).err().expect("an unknown column fails");
    assert!(err.contains(&format!("engine {url}")) && err.contains("nope") && err.contains("query:"), "{err}");
    let slow = spec(Some(&url), "timeout = 0.05", "x = \"x\"\ny = \"y\"\nmode = \"density\"");
    let err = draw(&slow, &file).err().expect("too short a time limit fails");
    assert!(err.contains("no complete answer within 0.05 s"), "{err}");

    // An executor killed in the middle of a long count: the right grid (Spark runs the lost
    // tasks again) or a clear error, never a wrong grid.
    let repeat = 600;
    let long = format!("SELECT p.* FROM ({read}) AS p CROSS JOIN range({repeat}) AS r");
    let executors = cluster.executors();
    assert_eq!(executors.len(), 2, "two executors run: {executors:?}");
    let victim = executors[0];
    let killer = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_secs(4));
        Command::new("kill").args(["-9", &victim.to_string()]).status().expect("kill")
    });
    let frame = LazyFrame::scan_parquet(path.to_str().expect("path").into(), Default::default()).expect("scan");
    let local = PlanRows::new(frame, "p").expect("plan").count("x", "y", &bx, &by).expect("count");
    let started = std::time::Instant::now();
    let remote = PlanRows::on_engine(cluster.query(&long, 600), "p").and_then(|rows| rows.count("x", "y", &bx, &by));
    assert!(killer.join().expect("killer").success());
    let elapsed = started.elapsed();
    assert!(elapsed > Duration::from_secs(5), "the query ended before the kill ({elapsed:?}); make it longer");
    let outcome = match remote {
        Ok(grid) => {
            let scaled: Vec<u64> = local.counts.iter().map(|c| c * repeat).collect();
            assert_eq!(grid.counts, scaled, "after the kill the grid is still exact");
            assert_eq!(grid.missing, local.missing * repeat);
            "the exact grid".to_string()
        }
        Err(e) => {
            assert!(e.contains(&format!("engine {url}")), "{e}");
            format!("an error: {e}")
        }
    };
    eprintln!("executor {victim} killed 4 s into a query of {elapsed:?}; it gave {outcome}");
}
