//! Flow benchmark (criterion): `cargo bench --bench flow`.
//! The double gyre (A = 0.1, ε = 0.25, t = 0) on [0, 2] × [0, 1] with 1024 × 1024 nodes: LIC to a
//! 1024 × 1024 raster, and its critical points. The VTK peer for the critical points is
//! `python3 benches/peer_vtk_topology.py` (same field).

use std::f64::consts::PI;
use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};

use dataink::enrich::flow::field::VectorField;
use dataink::enrich::flow::lic::{LicOptions, lic};
use dataink::enrich::flow::topology::critical_points;

/// The double gyre at t = 0 (f(x) = x there) on n × n nodes.
fn gyre(n: usize) -> VectorField {
    let a = 0.1;
    let xs: Vec<f64> = (0..n).map(|i| 2.0 * i as f64 / (n - 1) as f64).collect();
    let ys: Vec<f64> = (0..n).map(|j| j as f64 / (n - 1) as f64).collect();
    VectorField::from_fn(xs, ys, |x, y| {
        [-PI * a * (PI * x).sin() * (PI * y).cos(), PI * a * (PI * x).cos() * (PI * y).sin()]
    })
    .expect("valid grid")
}

fn flow_1024(c: &mut Criterion) {
    let field = gyre(1024);
    let options = LicOptions::new(1024, 1024);
    let mut group = c.benchmark_group("flow");
    group.sample_size(10);
    group.bench_function("lic_1024", |b| b.iter(|| lic(black_box(&field), &options)));
    group.bench_function("topology_1024", |b| b.iter(|| critical_points(black_box(&field), 1e-3)));
    group.finish();
}

criterion_group!(benches, flow_1024);
criterion_main!(benches);
