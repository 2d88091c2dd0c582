//! Span-space benchmark (criterion): `cargo bench --bench span_space`.
//! A 256³ `f32` field of four Gaussian blobs. Index build against one brute-force
//! `active_cells` scan and one full marching-cubes `extract`; the index query against the scan
//! at a level few cells cross (0.5: about 0.4% of cells) and at one many cross (0.05).
//! `python3 benches/make_blobs.py` writes the same field as `.npy` for the volume-rendering
//! benchmark (benches/volume_256.toml).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use dataink::data::volume::{Volume, Voxels};
use dataink::enrich::volume::SpanSpace;
use dataink::enrich::volume::isosurface::{Method, NormalRule, active_cells, extract};

/// f = Σ exp(−|p − cᵢ|² / 0.02) over four centres, p the voxel's position in [0, 1]³, stored as
/// `f32`; `n` voxels a side. `benches/make_blobs.py` writes the same field.
pub fn blobs(n: usize) -> Volume {
    let centres = [[0.3, 0.3, 0.3], [0.7, 0.35, 0.6], [0.4, 0.7, 0.45], [0.65, 0.7, 0.25]];
    let axis: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    let mut values = Vec::with_capacity(n * n * n);
    for &z in &axis {
        for &y in &axis {
            for &x in &axis {
                let f: f64 = centres
                    .iter()
                    .map(|c| (-((x - c[0]).powi(2) + (y - c[1]).powi(2) + (z - c[2]).powi(2)) / 0.02).exp())
                    .sum();
                values.push(f as f32);
            }
        }
    }
    Volume::new([n; 3], Voxels::F32(values), [1.0; 3]).expect("valid volume")
}

fn span_space_256(c: &mut Criterion) {
    let vol = blobs(256);
    let cells = 255usize.pow(3);
    let index = SpanSpace::build(&vol);
    for iso in [0.5, 0.05] {
        let active = index.active_cells(iso);
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
    group.bench_function("query_0.5", |b| b.iter(|| index.active_cells(black_box(0.5))));
    group.bench_function("scan_active_cells_0.05", |b| b.iter(|| active_cells(black_box(&vol), 0.05)));
    group.bench_function("query_0.05", |b| b.iter(|| index.active_cells(black_box(0.05))));
    group.bench_function("extract_mc_0.5_from_index", |b| {
        b.iter(|| {
            let list = index.active_cells(black_box(0.5));
            extract(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, Some(&list))
        })
    });
    group.finish();
}

criterion_group!(benches, span_space_256);
criterion_main!(benches);
