//! Stacking series of values over shared x positions: layers on a zero baseline, normalised to
//! shares of each position's total, centred on zero (silhouette), or on the baseline that
//! minimises the layers' weighted wiggle (Byron & Wattenberg's streamgraph, 2008).

/// Where a stack's first layer starts at each x position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Offset {
    /// On zero.
    Zero,
    /// On zero, each position scaled so its layers add up to 1.
    Normalize,
    /// Centred on zero: the baseline is minus half the total.
    Center,
    /// The streamgraph baseline minimising the weighted slope of every layer, then centred.
    Wiggle,
}

/// Lower and upper edges of every layer: `bounds[layer][position] = (y0, y1)`.
pub type Bounds = Vec<Vec<(f64, f64)>>;

/// Stack `layers[layer][position]` (non-negative values, all layers of equal length, positions at
/// `x`) with `offset`, layers in the given order from the bottom.
pub fn stack(layers: &[Vec<f64>], x: &[f64], offset: Offset) -> Bounds {
    let positions = x.len();
    let totals: Vec<f64> = (0..positions).map(|j| layers.iter().map(|l| l[j]).sum()).collect();
    let base: Vec<f64> = match offset {
        Offset::Zero | Offset::Normalize => vec![0.0; positions],
        Offset::Center => totals.iter().map(|t| -t / 2.0).collect(),
        Offset::Wiggle => wiggle_baseline(layers, x, &totals),
    };
    let scale = |j: usize| match offset {
        Offset::Normalize if totals[j] > 0.0 => 1.0 / totals[j],
        Offset::Normalize => 0.0,
        _ => 1.0,
    };
    let mut running = base;
    layers
        .iter()
        .map(|layer| {
            (0..positions)
                .map(|j| {
                    let y0 = running[j];
                    let y1 = y0 + layer[j] * scale(j);
                    running[j] = y1;
                    (y0, y1)
                })
                .collect()
        })
        .collect()
}

/// The baseline g with g' = −Σᵢ (Σ_{k<i} f_k' + f_i'/2) f_i / Σᵢ f_i, integrated over `x` (the
/// weighted-wiggle minimiser), shifted so the stack is centred on zero on average.
fn wiggle_baseline(layers: &[Vec<f64>], x: &[f64], totals: &[f64]) -> Vec<f64> {
    let positions = x.len();
    let mut base = vec![0.0; positions];
    for j in 1..positions {
        let dx = x[j] - x[j - 1];
        let mut weighted = 0.0;
        let mut below = 0.0;
        for layer in layers {
            let slope = if dx > 0.0 { (layer[j] - layer[j - 1]) / dx } else { 0.0 };
            weighted += (below + slope / 2.0) * layer[j];
            below += slope;
        }
        let g_slope = if totals[j] > 0.0 { -weighted / totals[j] } else { 0.0 };
        base[j] = base[j - 1] + g_slope * dx;
    }
    // Centre the stack: the mean of its middle line is zero.
    let mean_middle = (0..positions).map(|j| base[j] + totals[j] / 2.0).sum::<f64>() / positions.max(1) as f64;
    base.iter_mut().for_each(|b| *b -= mean_middle);
    base
}

#[cfg(test)]
mod tests {
    use super::*;

    const X: [f64; 4] = [0.0, 1.0, 2.0, 4.0];

    fn layers() -> Vec<Vec<f64>> {
        vec![vec![1.0, 2.0, 0.0, 3.0], vec![4.0, 0.0, 0.0, 1.0], vec![0.5, 0.5, 2.0, 0.0]]
    }

    #[test]
    fn every_offset_keeps_each_layers_thickness_and_stacks_without_gaps() {
        let l = layers();
        for offset in [Offset::Zero, Offset::Center, Offset::Wiggle] {
            let b = stack(&l, &X, offset);
            for (i, layer) in l.iter().enumerate() {
                for j in 0..X.len() {
                    assert!((b[i][j].1 - b[i][j].0 - layer[j]).abs() < 1e-12, "{offset:?} layer {i} at {j}");
                    if i > 0 {
                        assert_eq!(b[i][j].0, b[i - 1][j].1, "{offset:?}: layer {i} starts where {} ends", i - 1);
                    }
                }
            }
        }
    }

    #[test]
    fn zero_stacks_reach_the_totals_and_normalised_ones_reach_one() {
        let l = layers();
        let zero = stack(&l, &X, Offset::Zero);
        assert_eq!(zero[2].iter().map(|b| b.1).collect::<Vec<_>>(), [5.5, 2.5, 2.0, 4.0]);
        assert!(zero[0].iter().all(|b| b.0 == 0.0));
        let norm = stack(&l, &X, Offset::Normalize);
        assert!(norm[2].iter().all(|b| (b.1 - 1.0).abs() < 1e-12));
        assert!((norm[0][0].1 - 1.0 / 5.5).abs() < 1e-12);
        // A position where every layer is zero stays at zero.
        let empty = stack(&[vec![0.0, 1.0], vec![0.0, 1.0]], &[0.0, 1.0], Offset::Normalize);
        assert_eq!(empty[1][0], (0.0, 0.0));
    }

    #[test]
    fn centred_stacks_are_symmetric_about_zero() {
        let c = stack(&layers(), &X, Offset::Center);
        for j in 0..X.len() {
            assert!((c[0][j].0 + c[2][j].1).abs() < 1e-12);
        }
    }

    #[test]
    fn the_wiggle_baseline_matches_its_closed_form_for_two_layers() {
        // Two layers f (bottom) and h over x = 0, 1: g' = −((f'/2)·f + (f' + h'/2)·h) / (f + h)
        // at x = 1, with f: 1 → 3 and h: 2 → 2, so g' = −((1)·3 + (2)·2) / 5 = −7/5.
        let b = stack(&[vec![1.0, 3.0], vec![2.0, 2.0]], &[0.0, 1.0], Offset::Wiggle);
        let g = [b[0][0].0, b[0][1].0];
        assert!((g[1] - g[0] + 1.4).abs() < 1e-12, "{g:?}");
        // Centred: the middle line's mean is zero.
        let middle = [g[0] + 1.5, g[1] + 2.5];
        assert!((middle[0] + middle[1]).abs() < 1e-12);
    }
}
