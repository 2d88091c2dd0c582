//! Vertex normals. [`NormalRule::Gradient`](super::NormalRule::Gradient): the gradient of the
//! field, by central differences at the voxels (one-sided at the volume's edge or next to a
//! missing voxel) interpolated linearly along the crossed edge (trilinearly for an interior
//! vertex), taken to world space by the inverse transpose of the affine's 3 × 3 part, negated
//! and made unit length; where that is zero or not finite, the face normal is used.
//! [`NormalRule::Faces`](super::NormalRule::Faces): the area-weighted mean of the normals of the
//! triangles around the vertex.

use rayon::prelude::*;

use super::cube::{corner_position, cross, norm, scale, sub};
use crate::data::volume::Volume;

/// The gradient of the field at voxel `v`, in index space.
pub(super) fn voxel_gradient(volume: &Volume, v: [usize; 3]) -> [f64; 3] {
    let [i, j, k] = v;
    let here = volume.value(i, j, k);
    std::array::from_fn(|a| {
        let step = |up: bool| {
            let mut w = v;
            if up {
                w[a] += 1;
            } else if w[a] == 0 {
                return f64::NAN;
            } else {
                w[a] -= 1;
            }
            volume.value(w[0], w[1], w[2])
        };
        let (lo, hi) = (step(false), step(true));
        match (lo.is_finite(), hi.is_finite()) {
            (true, true) => 0.5 * (hi - lo),
            (false, true) => hi - here,
            (true, false) => here - lo,
            (false, false) => 0.0,
        }
    })
}

/// The voxel gradients of the cell at `cell` interpolated trilinearly to cell-local point `p`.
pub(super) fn corner_gradients_at(volume: &Volume, cell: [usize; 3], p: [f64; 3]) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for c in 0..8 {
        let q = corner_position(c);
        let w: f64 = (0..3).map(|a| if q[a] == 1 { p[a] } else { 1.0 - p[a] }).product();
        let grad = voxel_gradient(volume, [cell[0] + q[0], cell[1] + q[1], cell[2] + q[2]]);
        for a in 0..3 {
            sum[a] += w * grad[a];
        }
    }
    sum
}

/// `v` made unit length, if it has a direction.
fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = norm(v);
    (n.is_finite() && n > 0.0).then(|| scale(v, 1.0 / n))
}

/// Unit world normals for `positions` (world) and `triangles`: from the index-space gradients
/// `grads` (negated, through the inverse transpose of `inverse`'s map) when given, else — and
/// wherever a gradient has no direction — the area-weighted mean of the triangle normals (summed
/// only when some vertex needs it).
pub(super) fn world_normals(
    positions: &[[f64; 3]],
    triangles: &[[u32; 3]],
    grads: &[[f64; 3]],
    inverse: [[f64; 4]; 3],
) -> Vec<[f64; 3]> {
    let from_gradients: Vec<Option<[f64; 3]>> = (0..positions.len())
        .into_par_iter()
        .map(|v| {
            grads.get(v).and_then(|g| {
                // ∇_world f = Rᵀ ∇_index f, R the 3 × 3 part of the world-to-index map.
                let w: [f64; 3] = std::array::from_fn(|x| -(0..3).map(|a| inverse[a][x] * g[a]).sum::<f64>());
                unit(w)
            })
        })
        .collect();
    if from_gradients.iter().all(Option::is_some) {
        return from_gradients.into_iter().map(|n| n.unwrap_or([0.0, 0.0, 1.0])).collect();
    }
    let mut faces = vec![[0.0; 3]; positions.len()];
    for t in triangles {
        let p = t.map(|v| positions.get(v as usize).copied().unwrap_or([0.0; 3]));
        // Twice the area times the unit normal: the area weighting for free.
        let n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        for &v in t {
            if let Some(f) = faces.get_mut(v as usize) {
                *f = [f[0] + n[0], f[1] + n[1], f[2] + n[2]];
            }
        }
    }
    from_gradients
        .into_iter()
        .zip(&faces)
        .map(|(gradient, face)| gradient.or_else(|| unit(*face)).unwrap_or([0.0, 0.0, 1.0]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::cube::dot;
    use super::*;

    #[test]
    fn gradient_to_world_uses_the_inverse_transpose() {
        // Index i runs along world y with spacing 2: f = i means f = y / 2, ∇f = (0, 0.5, 0);
        // the outward normal is −∇f.
        let inverse = [[0.0, 0.5, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];
        let n = world_normals(&[[0.0; 3]], &[], &[[1.0, 0.0, 0.0]], inverse);
        assert!(dot(n[0], [0.0, -1.0, 0.0]) > 1.0 - 1e-12, "{n:?}");
    }
}
