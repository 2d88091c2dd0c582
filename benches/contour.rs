//! Contour benchmark (criterion): `cargo bench --bench contour`.
//! A smooth 2000×2000 field with 10 nice levels; the contourpy peer is
//! `python3 benches/peer_contourpy.py` (same field and levels).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use dataink::enrich::contour::{Saddle, contour_bands, contour_lines, nice_levels};
use dataink::enrich::grid::Grid;

/// f = sin(1.7x)·cos(1.3y) + 0.2(x² − y²) + 0.1xy + 0.2 on [−3, 3]², n × n nodes.
fn field(n: usize) -> Grid {
    let axis: Vec<f64> = (0..n).map(|i| -3.0 + 6.0 * i as f64 / (n - 1) as f64).collect();
    let mut values = Vec::with_capacity(n * n);
    for &y in &axis {
        for &x in &axis {
            values.push((1.7 * x).sin() * (1.3 * y).cos() + 0.2 * (x * x - y * y) + 0.1 * x * y + 0.2);
        }
    }
    Grid::new(axis.clone(), axis, values).expect("valid grid")
}

fn contours_2000(c: &mut Criterion) {
    let grid = field(2000);
    let (lo, hi) = grid.range().expect("finite field");
    let levels = nice_levels(lo, hi, 10);
    let mut edges = vec![lo];
    edges.extend(&levels);
    edges.push(hi);
    let mut group = c.benchmark_group("contour_2000x2000_10_levels");
    group.sample_size(10);
    group.bench_function("lines", |b| b.iter(|| contour_lines(black_box(&grid), &levels, Saddle::Asymptotic)));
    group.bench_function("bands", |b| b.iter(|| contour_bands(black_box(&grid), &edges, Saddle::Asymptotic)));
    group.finish();
}

criterion_group!(benches, contours_2000);
criterion_main!(benches);
