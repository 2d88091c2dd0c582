//! Values of a volume at any world point. World points go to fractional voxel indices through the
//! inverse of the volume's voxel-to-world matrix, so spacing and orientation are honoured.
//!
//! - **Nearest**: the voxel whose cell holds the point; cells reach half a voxel beyond the outer
//!   voxel centres, so the volume covers indices `[-0.5, n - 0.5]` along each axis.
//! - **Trilinear**: the eight voxels around the point weighted by the point's fractional offsets;
//!   exact for fields linear in x, y and z, and equal to the voxel's value at its centre. It
//!   covers indices `[0, n - 1]` (an axis of one voxel is a slab half a voxel thick each way).
//!   A missing (NaN) voxel among the eight makes the point missing.
//!
//! Points outside the covered box have no value (`None`), which is not the same as a missing
//! value inside it (`Some(NaN)`).

use crate::data::volume::Volume;

/// How a value between voxel centres is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// The value of the nearest voxel.
    Nearest,
    /// The trilinear interpolation of the eight surrounding voxels.
    Trilinear,
}

/// Reads a volume's values at world points.
#[derive(Clone, Debug)]
pub struct Sampler<'a> {
    volume: &'a Volume,
    /// Rows of the world-to-index map: `index = inverse · (x, y, z, 1)`.
    inverse: [[f64; 4]; 3],
    dims: [usize; 3],
}

impl<'a> Sampler<'a> {
    /// A sampler of `volume`, or why there is none (its voxel-to-world matrix cannot be inverted).
    pub fn new(volume: &'a Volume) -> Result<Sampler<'a>, String> {
        let inverse = invert(volume.affine()).ok_or_else(|| {
            format!(
                "the voxel-to-world matrix {:?} flattens the volume (its 3 × 3 part has no inverse)",
                volume.affine()
            )
        })?;
        Ok(Sampler { volume, inverse, dims: volume.dims() })
    }

    /// The volume read.
    pub fn volume(&self) -> &'a Volume {
        self.volume
    }

    /// The fractional voxel index of world point `w`.
    pub fn index_of(&self, w: [f64; 3]) -> [f64; 3] {
        self.inverse.map(|row| row[0] * w[0] + row[1] * w[1] + row[2] * w[2] + row[3])
    }

    /// The index range the volume covers along each axis under `how` (see the module docs).
    pub fn covered(&self, how: Interpolation) -> [(f64, f64); 3] {
        self.dims.map(|n| {
            let last = n.saturating_sub(1) as f64;
            match how {
                Interpolation::Trilinear if n > 1 => (0.0, last),
                _ => (-0.5, last + 0.5),
            }
        })
    }

    /// The value at world point `w`: `None` outside the covered box, NaN where missing.
    pub fn at(&self, w: [f64; 3], how: Interpolation) -> Option<f64> {
        self.at_index(self.index_of(w), how)
    }

    /// The value at fractional voxel index `p`: `None` outside the covered box, NaN where missing.
    pub fn at_index(&self, p: [f64; 3], how: Interpolation) -> Option<f64> {
        let covered = self.covered(how);
        if !(0..3).all(|a| p[a] >= covered[a].0 && p[a] <= covered[a].1) {
            return None;
        }
        let v = self.volume;
        match how {
            Interpolation::Nearest => {
                let [i, j, k] = [0, 1, 2].map(|a| (p[a].round().max(0.0) as usize).min(self.dims[a] - 1));
                Some(v.value(i, j, k))
            }
            Interpolation::Trilinear => {
                // Lower corner and weight per axis; an axis of one voxel reads its only plane.
                let mut lower = [0usize; 3];
                let mut t = [0.0; 3];
                for a in 0..3 {
                    if self.dims[a] > 1 {
                        let i0 = (p[a].floor().max(0.0) as usize).min(self.dims[a] - 2);
                        lower[a] = i0;
                        t[a] = p[a] - i0 as f64;
                    }
                }
                let step = |a: usize| usize::from(self.dims[a] > 1);
                let [i, j, k] = lower;
                let (di, dj, dk) = (step(0), step(1), step(2));
                let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
                let c00 = lerp(v.value(i, j, k), v.value(i + di, j, k), t[0]);
                let c10 = lerp(v.value(i, j + dj, k), v.value(i + di, j + dj, k), t[0]);
                let c01 = lerp(v.value(i, j, k + dk), v.value(i + di, j, k + dk), t[0]);
                let c11 = lerp(v.value(i, j + dj, k + dk), v.value(i + di, j + dj, k + dk), t[0]);
                Some(lerp(lerp(c00, c10, t[1]), lerp(c01, c11, t[1]), t[2]))
            }
        }
    }

    /// The eight world corners of the covered box under `how`; bit 0 of the index picks the
    /// i side, bit 1 j, bit 2 k.
    pub fn corners(&self, how: Interpolation) -> [[f64; 3]; 8] {
        let covered = self.covered(how);
        std::array::from_fn(|c| {
            let [i, j, k] = [0, 1, 2].map(|a| if c >> a & 1 == 1 { covered[a].1 } else { covered[a].0 });
            self.volume.world(i, j, k)
        })
    }
}

/// The inverse of an affine map given as the top three rows of a 4 × 4 matrix, if it has one.
pub fn invert(m: [[f64; 4]; 3]) -> Option<[[f64; 4]; 3]> {
    let [a, b, c] = [m[0], m[1], m[2]];
    let det =
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    let size = m.iter().flat_map(|r| &r[..3]).fold(0.0f64, |s, v| s.max(v.abs()));
    if !(det.is_finite() && det.abs() > 1e-12 * size.powi(3)) {
        return None;
    }
    let r = [
        [(b[1] * c[2] - b[2] * c[1]) / det, (a[2] * c[1] - a[1] * c[2]) / det, (a[1] * b[2] - a[2] * b[1]) / det],
        [(b[2] * c[0] - b[0] * c[2]) / det, (a[0] * c[2] - a[2] * c[0]) / det, (a[2] * b[0] - a[0] * b[2]) / det],
        [(b[0] * c[1] - b[1] * c[0]) / det, (a[1] * c[0] - a[0] * c[1]) / det, (a[0] * b[1] - a[1] * b[0]) / det],
    ];
    let t = [a[3], b[3], c[3]];
    Some(r.map(|row| [row[0], row[1], row[2], -(row[0] * t[0] + row[1] * t[1] + row[2] * t[2])]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::volume::Voxels;

    /// A volume of f = 2 + 3x − y + 0.5z at its world points, for spacing (1, 2, 0.5) and a
    /// rotated, shifted placement.
    fn linear() -> Volume {
        let [nx, ny, nz] = [4, 3, 5];
        let affine = [[0.0, -2.0, 0.0, 10.0], [1.0, 0.0, 0.0, -3.0], [0.0, 0.0, 0.5, 1.0]];
        let mut values = Vec::new();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let w = affine.map(|r| r[0] * i as f64 + r[1] * j as f64 + r[2] * k as f64 + r[3]);
                    values.push(2.0 + 3.0 * w[0] - w[1] + 0.5 * w[2]);
                }
            }
        }
        Volume::new([nx, ny, nz], Voxels::F64(values), [1.0, 2.0, 0.5])
            .expect("volume")
            .with_affine(affine)
            .expect("finite")
    }

    #[test]
    fn trilinear_is_exact_for_a_linear_field_and_nearest_reads_voxels() {
        let v = linear();
        let s = Sampler::new(&v).expect("invertible");
        let f = |w: [f64; 3]| 2.0 + 3.0 * w[0] - w[1] + 0.5 * w[2];
        for p in [[0.3, 1.7, 2.2], [3.0, 2.0, 4.0], [1.5, 0.5, 0.25]] {
            let w = v.world(p[0], p[1], p[2]);
            let back = s.index_of(w);
            assert!((0..3).all(|a| (back[a] - p[a]).abs() < 1e-12), "{back:?} vs {p:?}");
            let got = s.at(w, Interpolation::Trilinear).expect("inside");
            assert!((got - f(w)).abs() < 1e-9, "{got} vs {}", f(w));
        }
        // Nearest: the voxel at (1, 2, 2) for a point a little off its centre.
        let w = v.world(1.2, 1.8, 2.4);
        assert_eq!(s.at(w, Interpolation::Nearest), Some(v.value(1, 2, 2)));
        // Just past the last centre: nearest still covers half a voxel, trilinear does not.
        let w = v.world(3.4, 1.0, 1.0);
        assert_eq!(s.at(w, Interpolation::Nearest), Some(v.value(3, 1, 1)));
        assert_eq!(s.at(w, Interpolation::Trilinear), None);
        assert_eq!(s.at(v.world(-0.6, 0.0, 0.0), Interpolation::Nearest), None);
    }

    #[test]
    fn missing_voxels_make_missing_values_and_thin_axes_are_slabs() {
        let mut values = vec![1.0; 8];
        values[7] = f64::NAN;
        let v = Volume::new([2, 2, 2], Voxels::F64(values), [1.0; 3]).expect("volume");
        let s = Sampler::new(&v).expect("invertible");
        assert!(s.at([0.5, 0.5, 0.5], Interpolation::Trilinear).is_some_and(f64::is_nan));
        assert_eq!(s.at([0.2, 0.2, 0.2], Interpolation::Nearest), Some(1.0));
        // One voxel thick in z: the plane is read within half a voxel either side.
        let thin = Volume::new([2, 1, 1], Voxels::U8(vec![10, 20]), [1.0; 3]).expect("volume");
        let s = Sampler::new(&thin).expect("invertible");
        assert_eq!(s.at([0.25, 0.3, -0.4], Interpolation::Trilinear), Some(12.5));
        assert_eq!(s.at([0.25, 0.0, 0.6], Interpolation::Trilinear), None);
    }

    #[test]
    fn a_flat_matrix_has_no_inverse() {
        assert!(invert([[1.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]).is_none());
        let m = [[0.0, 2.0, 0.0, 1.0], [-1.0, 0.0, 0.0, 2.0], [0.0, 0.0, 4.0, 3.0]];
        let inv = invert(m).expect("invertible");
        let p = [1.0, -2.0, 0.5];
        let w = m.map(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3]);
        let back = inv.map(|r| r[0] * w[0] + r[1] * w[1] + r[2] * w[2] + r[3]);
        assert_eq!(back, p);
    }
}
