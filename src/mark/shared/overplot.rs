//! Defaults that shrink as rows pile up: marker radius and opacity for `n` points (scatter,
//! splom), and the opacity of one polyline per row (parallel coordinates, daisy charts).

/// Default marker radius for `n` points: smaller as the plot fills up.
pub fn point_radius(n: usize) -> f64 {
    match n {
        0..=1_000 => 3.5,
        1_001..=10_000 => 2.5,
        10_001..=100_000 => 1.5,
        _ => 1.0,
    }
}

/// Default marker opacity for `n` points: lower as overplotting grows.
pub fn point_opacity(n: usize) -> f64 {
    match n {
        0..=1_000 => 0.85,
        1_001..=10_000 => 0.6,
        10_001..=100_000 => 0.35,
        _ => 0.2,
    }
}

/// Default line opacity for `n` rows: lower as overplotting grows.
pub fn line_opacity(n: usize) -> f64 {
    match n {
        0..=100 => 0.8,
        101..=1_000 => 0.45,
        1_001..=10_000 => 0.2,
        _ => 0.1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_shrink_with_row_count() {
        assert!(point_radius(100) > point_radius(1_000_000));
        assert!(point_opacity(100) > point_opacity(1_000_000));
        assert!(line_opacity(100) > line_opacity(1_000_000));
    }
}
