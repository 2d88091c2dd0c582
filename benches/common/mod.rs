//! Helpers shared by the benchmarks.

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
