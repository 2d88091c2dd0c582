//! PCHIP evaluation benchmark (criterion): `cargo bench --bench interp`.
//! 1,000 knots, 10,000,000 sorted evaluation points; the SciPy peer is
//! `python3 benches/peer_scipy_pchip.py` (same workload).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use dataink::enrich::interp1d::{Interpolant, Method, Slopes};

fn pchip_10m(c: &mut Criterion) {
    let n = 1_000;
    let x: Vec<f64> = (0..n).map(|i| i as f64 + 0.3 * ((i * 7919 % 13) as f64 / 13.0)).collect();
    let y: Vec<f64> = x.iter().map(|v| (v * 0.05).sin() + 0.01 * v).collect();
    let curve = Interpolant::new(&x, &y, Method::Hermite(Slopes::HarmonicMean), false).expect("pchip");
    let (lo, hi) = curve.domain();
    let m = 10_000_000;
    let ts: Vec<f64> = (0..m).map(|i| lo + (hi - lo) * i as f64 / (m - 1) as f64).collect();
    let mut out = vec![0.0; m];
    let mut group = c.benchmark_group("pchip");
    group.sample_size(10);
    group.bench_function("1000_knots_10m_evaluations", |b| {
        b.iter(|| curve.eval_many(black_box(&ts), black_box(&mut out)).expect("lengths match"))
    });
    group.finish();
}

criterion_group!(benches, pchip_10m);
criterion_main!(benches);
