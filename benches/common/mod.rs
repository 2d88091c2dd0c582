//! Helpers shared by the benchmarks; each benchmark uses some of them.
#![allow(dead_code)]

/// A fixed-seed xorshift generator of uniform numbers in [0, 1), so every run and every machine
/// benchmarks the same data.
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed.max(1);
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// f = Σ exp(−|p − cᵢ|² / 0.02) over four centres, p the voxel's position in [0, 1]³, stored as
/// `f32`; `n` voxels a side. `benches/make_blobs.py` writes the same field.
pub fn blobs(n: usize) -> dataink::data::volume::Volume {
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
    dataink::data::volume::Volume::new([n; 3], dataink::data::volume::Voxels::F32(values), [1.0; 3])
        .expect("valid volume")
}
