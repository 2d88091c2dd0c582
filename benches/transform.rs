//! Transforms through a spec against the same query in polars directly, in the same run:
//! `cargo bench --bench transform`.
//!
//! The workload: a 10,000,000-row Parquet file (a text category of 20 values, two float columns
//! and an integer column; written once to `target/bench-data/transform-10m.parquet` from a
//! fixed-seed generator), filtered by `x > 0.5 and k < 50` and aggregated to the mean of `y` and
//! a count per category.
//!
//! - `transform_10m/dataink`: the whole spec path — read and check the spec, plan the source,
//!   run the lazy plan, convert to dataink's table, and draw the bar chart of the result.
//! - `transform_10m/polars`: `scan_parquet` + `filter` + `group_by` + `agg` + `collect`,
//!   written by hand.
//!
//! dataink's overhead is the ratio of the two, minus one.

mod common;

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use polars::prelude::*;

use dataink::data::PathPolicy;
use dataink::pipeline;

const ROWS: usize = 10_000_000;

const SPEC: &str = r#"[data.events]
path = "transform-10m.parquet"
transform = [
  { filter = "x > 0.5 and k < 50" },
  { aggregate = { mean_y = "mean(y)", n = "count()" }, groupby = ["category"] },
]

[[chart]]
name = "by-category"
kind = "bar"
data = "events"
title = "Mean y per category"
x = "category"
y = "mean_y"
"#;

/// The benchmark folder with the data file and the spec, made once.
fn bench_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/bench-data");
    let data = dir.join("transform-10m.parquet");
    if !data.exists() {
        std::fs::create_dir_all(&dir).expect("bench folder");
        let mut uniform = common::uniform(0x9e37_79b9_7f4a_7c15);
        let names: Vec<String> = (0..20).map(|i| format!("cat-{i:02}")).collect();
        let mut category = Vec::with_capacity(ROWS);
        let mut x = Vec::with_capacity(ROWS);
        let mut y = Vec::with_capacity(ROWS);
        let mut k = Vec::with_capacity(ROWS);
        for _ in 0..ROWS {
            let u = uniform();
            category.push(names[((u * 20.0) as usize).min(19)].as_str());
            x.push(uniform());
            y.push(uniform() * 100.0);
            k.push((uniform() * 100.0) as i64);
        }
        let mut df = df!("category" => category, "x" => x, "y" => y, "k" => k).expect("frame");
        let tmp = dir.join("transform-10m.parquet.tmp");
        let file = std::fs::File::create(&tmp).expect("create");
        ParquetWriter::new(file).finish(&mut df).expect("write parquet");
        std::fs::rename(&tmp, &data).expect("rename");
    }
    std::fs::write(dir.join("transform.toml"), SPEC).expect("write spec");
    dir
}

fn by_hand(path: &Path) -> DataFrame {
    LazyFrame::scan_parquet(PlRefPath::new(path.to_string_lossy().as_ref()), ScanArgsParquet::default())
        .expect("scan")
        .filter(col("x").gt(lit(0.5)).and(col("k").lt(lit(50))))
        .group_by([col("category")])
        .agg([col("y").mean().alias("mean_y"), len().alias("n")])
        .collect()
        .expect("query")
}

fn through_spec(spec: &Path) -> usize {
    let loaded = pipeline::load(spec, PathPolicy::InsideSpecFolder).unwrap_or_else(|f| panic!("{}", f.render()));
    let chart = &loaded.spec.chart[0];
    let drawn = pipeline::draw_chart(&loaded, 0, chart).expect("draw");
    loaded.tables["events"].rows + drawn.warnings.len()
}

fn transform_10m(c: &mut Criterion) {
    let dir = bench_dir();
    let spec = dir.join("transform.toml");
    let data = dir.join("transform-10m.parquet");
    // Both answer the same: 20 categories.
    assert_eq!(through_spec(&spec), 20);
    assert_eq!(by_hand(&data).height(), 20);
    let mut group = c.benchmark_group("transform_10m");
    group.sample_size(20).measurement_time(Duration::from_secs(20));
    group.bench_function("dataink", |b| b.iter(|| black_box(through_spec(&spec))));
    group.bench_function("polars", |b| b.iter(|| black_box(by_hand(&data).height())));
    group.finish();
}

criterion_group!(benches, transform_10m);
criterion_main!(benches);
