//! Isosurface benchmark (criterion): `cargo bench --bench isosurface`.
//! One whole `extract` (the `active_cells` scan included) of the 256³ `f32` field of four
//! Gaussian blobs, read from `benches/data/blobs_256.npy` (`python3 benches/make_blobs.py`), the
//! same file the peers read (`python3 benches/peer_marching_cubes.py`: scikit-image and VTK).
//! Marching cubes and marching tetrahedra at a level few cells cross (0.5) and one many cross
//! (0.05), each on a pool of one thread and of two. Before timing it checks that both pools give
//! the same mesh and prints each mesh's vertex and triangle counts.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::Path;

use dataink::data::volume::npy;
use dataink::enrich::volume::isosurface::{Method, NormalRule, extract};

fn isosurface_256(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/data/blobs_256.npy");
    let vol = npy::read(&path, [1.0; 3]).expect("benches/data/blobs_256.npy: run `python3 benches/make_blobs.py`");
    let pools: Vec<(usize, rayon::ThreadPool)> = [1, 2]
        .into_iter()
        .map(|n| (n, rayon::ThreadPoolBuilder::new().num_threads(n).build().expect("a thread pool")))
        .collect();
    let methods = [(Method::MarchingCubes, "mc"), (Method::Tetrahedra, "tetra")];
    for iso in [0.5, 0.05] {
        for (method, name) in methods {
            let meshes: Vec<_> = pools
                .iter()
                .map(|(_, pool)| {
                    pool.install(|| extract(&vol, iso, method, NormalRule::Gradient, None)).expect("a mesh")
                })
                .collect();
            assert!(meshes.windows(2).all(|w| w[0] == w[1]), "{name} {iso}: the pools disagree");
            eprintln!(
                "{name} iso {iso}: {} vertices, {} triangles",
                meshes[0].positions.len(),
                meshes[0].triangles.len()
            );
        }
    }
    let mut group = c.benchmark_group("isosurface_256");
    group.sample_size(10);
    for iso in [0.5, 0.05] {
        for (method, name) in methods {
            for (threads, pool) in &pools {
                group.bench_function(format!("{name}_{iso}_{threads}t"), |b| {
                    b.iter(|| pool.install(|| extract(black_box(&vol), iso, method, NormalRule::Gradient, None)))
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, isosurface_256);
criterion_main!(benches);
