//! Treemap benchmark (criterion): `cargo bench --bench treemap`.
//! A squarified treemap of 1,000,000 leaves in 3 levels (100 × 100 × 100 under one root), values
//! uniform in (1, 100), in a 1000×1000 box, timed from a parent list (build the hierarchy, sum,
//! sort, tile). The d3-hierarchy peer is `benches/peer_d3_treemap.mjs` (same shape and values).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use dataink::layout::hierarchy::Hierarchy;
use dataink::layout::treemap::{Rect, TreemapOptions, layout};

mod common;

/// Parents of a root with `fanout` children per node over `levels` levels, numbered level by level.
fn parents(fanout: usize, levels: u32) -> Vec<Option<usize>> {
    let mut parents = vec![None];
    let mut level_start = 0;
    let mut level_len = 1;
    for _ in 0..levels {
        for p in level_start..level_start + level_len {
            parents.extend(std::iter::repeat_n(Some(p), fanout));
        }
        level_start += level_len;
        level_len *= fanout;
    }
    parents
}

fn treemap_1m(c: &mut Criterion) {
    let parents = parents(100, 3);
    // Leaves are the last 1,000,000 nodes, drawn in index order (the peer's depth-first order).
    let inner = parents.len() - 1_000_000;
    let mut rng = common::uniform(42);
    let values: Vec<f64> = (0..parents.len()).map(|i| if i < inner { 0.0 } else { 1.0 + 99.0 * rng() }).collect();
    let bounds = Rect::new(0.0, 0.0, 1000.0, 1000.0);
    let options = TreemapOptions::default();
    let mut group = c.benchmark_group("treemap");
    group.sample_size(10);
    group.bench_function("squarify_1m_3_levels", |b| {
        b.iter(|| {
            let tree = Hierarchy::from_parents(black_box(&parents)).expect("a tree");
            layout(&tree, black_box(&values), bounds, &options).expect("valid input")
        })
    });
    group.finish();
}

criterion_group!(benches, treemap_1m);
criterion_main!(benches);
