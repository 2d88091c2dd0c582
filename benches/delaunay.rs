//! Delaunay benchmark (criterion): `cargo bench --bench delaunay`.
//! 1,000,000 uniformly random points; the d3-delaunay peer is `benches/peer_d3_delaunay.mjs`.

mod common;

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use dataink::enrich::scattered::Triangulation;

fn random_points(n: usize) -> (Vec<(f64, f64)>, Vec<f64>) {
    let mut uniform = common::uniform(0x9e37_79b9_7f4a_7c15);
    let points: Vec<(f64, f64)> = (0..n).map(|_| (uniform(), uniform())).collect();
    let values = points.iter().map(|p| p.0 + p.1).collect();
    (points, values)
}

fn delaunay_1m(c: &mut Criterion) {
    let (points, values) = random_points(1_000_000);
    let mut group = c.benchmark_group("delaunay");
    group.sample_size(10);
    // Each iteration also frees the result.
    group.bench_function("1m_random_points", |b| {
        b.iter(|| Triangulation::new(black_box(&points), black_box(&values)).expect("triangulates"))
    });
    group.finish();
}

criterion_group!(benches, delaunay_1m);
criterion_main!(benches);
