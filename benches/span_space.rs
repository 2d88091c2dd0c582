//! Span-space benchmark (criterion): `cargo bench --bench span_space`.
//! A 256³ `f32` field of four Gaussian blobs. Index build against one brute-force
//! `active_cells` scan and one full marching-cubes `extract`; the index query against the scan
//! at a level few cells cross (0.5: about 0.4% of cells) and at one many cross (0.05).
//! `python3 benches/make_blobs.py` writes the same field as `.npy` for the volume-rendering
//! benchmark (benches/volume_256.toml).

mod common;

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use dataink::enrich::volume::SpanSpace;
use dataink::enrich::volume::isosurface::{Method, NormalRule, active_cells, extract};

fn span_space_256(c: &mut Criterion) {
    let vol = common::blobs(256);
    let cells = 255usize.pow(3);
    let index = SpanSpace::build(&vol);
    for iso in [0.5, 0.05] {
        let active = index.active_cells(&vol, iso);
        assert_eq!(active, active_cells(&vol, iso), "index and scan agree at {iso}");
        eprintln!(
            "iso {iso}: {} active cells of {cells} ({:.2}%); index {} × {} buckets, {:.1} MB",
            active.len(),
            100.0 * active.len() as f64 / cells as f64,
            index.buckets()[0],
            index.buckets()[1],
            index.memory_bytes() as f64 / 1e6
        );
    }
    let mut group = c.benchmark_group("span_space_256");
    group.sample_size(10);
    group.bench_function("build", |b| b.iter(|| SpanSpace::build(black_box(&vol))));
    group.bench_function("scan_active_cells_0.5", |b| b.iter(|| active_cells(black_box(&vol), 0.5)));
    group.bench_function("extract_mc_0.5", |b| {
        b.iter(|| extract(black_box(&vol), 0.5, Method::MarchingCubes, NormalRule::Gradient, None))
    });
    group.bench_function("query_0.5", |b| b.iter(|| index.active_cells(&vol, black_box(0.5))));
    group.bench_function("scan_active_cells_0.05", |b| b.iter(|| active_cells(black_box(&vol), 0.05)));
    group.bench_function("query_0.05", |b| b.iter(|| index.active_cells(&vol, black_box(0.05))));
    group.bench_function("extract_mc_0.5_from_index", |b| {
        b.iter(|| {
            let list = index.active_cells(&vol, black_box(0.5));
            extract(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, Some(&list))
        })
    });
    group.finish();
}

criterion_group!(benches, span_space_256);
criterion_main!(benches);
