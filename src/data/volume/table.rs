//! Long tables as volumes: rows of `x, y, z, value` in any order become a volume when each
//! coordinate's values lie on a regular lattice (`first + n × step`). Lattice points no row
//! gives are missing (NaN); two rows at one point, a coordinate off the lattice or a
//! non-finite coordinate are errors that name the value.

use super::{MAX_VOXELS, Volume, Voxels};
use crate::data::Table;

/// Relative tolerance of a coordinate against its lattice, in steps.
const TOLERANCE: f64 = 1e-6;

/// One axis of the lattice: its first coordinate, its step and how many points.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Axis {
    first: f64,
    step: f64,
    count: usize,
}

impl Axis {
    /// The lattice of `values` (finite), or the first value off it. The step is the smallest gap
    /// between distinct values; an axis of one value gets step 1.
    fn of(name: &str, values: &[f64]) -> Result<Axis, String> {
        let mut distinct: Vec<f64> = values.to_vec();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        let first = *distinct.first().ok_or("the table has no rows")?;
        let last = *distinct.last().unwrap_or(&first);
        let step = distinct.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
        if !step.is_finite() {
            return Ok(Axis { first, step: 1.0, count: 1 });
        }
        if step <= (last - first).abs() * f64::EPSILON * 4.0 {
            return Err(format!("{name} values {first} and {} are too close to be lattice steps", first + step));
        }
        let spans = ((last - first) / step).round();
        if spans >= MAX_VOXELS as f64 {
            return Err(format!(
                "{name} runs from {first} to {last} in steps of {step}: {spans} steps, more than a volume holds"
            ));
        }
        let axis = Axis { first, step, count: spans as usize + 1 };
        for &v in &distinct {
            if axis.position(v).is_none() {
                return Err(format!(
                    "{name} = {v} is not on the regular lattice {first} + n × {step} (the smallest gap between {name} values); the rows are not a regular grid"
                ));
            }
        }
        Ok(axis)
    }

    /// The lattice index of `v`, if it lies on the lattice.
    fn position(&self, v: f64) -> Option<usize> {
        let n = (v - self.first) / self.step;
        let rounded = n.round();
        ((n - rounded).abs() <= TOLERANCE && rounded >= 0.0 && (rounded as usize) < self.count)
            .then_some(rounded as usize)
    }
}

/// The volume of a long table's columns `names` (x, y, z, value): the lattice spacing as voxel
/// spacing, voxel (0, 0, 0) at the smallest coordinates.
pub fn from_table(table: &Table, names: [&str; 4]) -> Result<Volume, String> {
    let column = |name: &str| {
        let c = table
            .column(name)
            .ok_or_else(|| format!("the table has no column `{name}`; a volume needs columns {}", names.join(", ")))?;
        c.numbers().ok_or_else(|| format!("column `{name}` holds text; a volume needs numbers"))
    };
    let [xs, ys, zs, values] = [column(names[0])?, column(names[1])?, column(names[2])?, column(names[3])?];
    for (name, coords) in names.iter().zip([xs, ys, zs]) {
        if let Some((row, v)) = coords.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(format!("{name} is {v} in row {}; every row of a volume needs finite coordinates", row + 1));
        }
    }
    let axes = [Axis::of(names[0], xs)?, Axis::of(names[1], ys)?, Axis::of(names[2], zs)?];
    let dims = axes.map(|a| a.count);
    let count =
        dims.iter().try_fold(1usize, |n, &d| n.checked_mul(d)).filter(|&n| n <= MAX_VOXELS).ok_or_else(|| {
            format!(
                "the lattice has {} × {} × {} points, more than the limit of {MAX_VOXELS}",
                dims[0], dims[1], dims[2]
            )
        })?;
    let mut out = vec![f64::NAN; count];
    let mut seen = vec![false; count];
    for row in 0..table.rows {
        let at = |a: usize, coords: &[f64]| coords.get(row).and_then(|&v| axes[a].position(v)).unwrap_or(0);
        let (i, j, k) = (at(0, xs), at(1, ys), at(2, zs));
        let n = (k * dims[1] + j) * dims[0] + i;
        if std::mem::replace(&mut seen[n], true) {
            return Err(format!(
                "two rows give a value at {} = {}, {} = {}, {} = {} (the second is row {}); aggregate them first",
                names[0],
                xs[row],
                names[1],
                ys[row],
                names[2],
                zs[row],
                row + 1
            ));
        }
        let v = values.get(row).copied().unwrap_or(f64::NAN);
        out[n] = if v.is_finite() { v } else { f64::NAN };
    }
    let spacing = axes.map(|a| a.step);
    let affine = [
        [spacing[0], 0.0, 0.0, axes[0].first],
        [0.0, spacing[1], 0.0, axes[1].first],
        [0.0, 0.0, spacing[2], axes[2].first],
    ];
    Volume::new(dims, Voxels::F64(out), spacing)?.with_affine(affine)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::ColumnValues;

    const NAMES: [&str; 4] = ["x", "y", "z", "value"];

    fn table(rows: &[[f64; 4]]) -> Table {
        Table::from_columns(
            NAMES.iter().enumerate().map(|(c, n)| (*n, ColumnValues::Number(rows.iter().map(|r| r[c]).collect()))),
        )
    }

    #[test]
    fn shuffled_rows_with_a_hole_make_a_volume() {
        // A 3 × 2 × 2 lattice at x = 10, 10.5, 11; y = 0, 2; z = -1, 0; value = 100 i + 10 j + k.
        let mut rows = Vec::new();
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..3 {
                    if (i, j, k) != (1, 1, 0) {
                        let v = (100 * i + 10 * j + k) as f64;
                        rows.push([10.0 + 0.5 * i as f64, 2.0 * j as f64, k as f64 - 1.0, v]);
                    }
                }
            }
        }
        rows.reverse();
        rows.swap(0, 5);
        let v = from_table(&table(&rows), NAMES).expect("volume");
        assert_eq!(v.dims(), [3, 2, 2]);
        assert_eq!(v.spacing(), [0.5, 2.0, 1.0]);
        assert_eq!(v.value(2, 1, 1), 211.0);
        assert_eq!(v.value(1, 0, 1), 101.0);
        assert!(v.value(1, 1, 0).is_nan(), "the hole is missing");
        assert_eq!(v.range(), (Some((0.0, 211.0)), 1));
        assert_eq!(v.world(2.0, 1.0, 1.0), [11.0, 2.0, 0.0]);
    }

    #[test]
    fn irregular_coordinates_and_duplicates_are_named() {
        let rows = [[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [2.5, 0.0, 0.0, 1.0]];
        let err = from_table(&table(&rows), NAMES).expect_err("irregular");
        assert!(err.starts_with("x = 2.5 is not on the regular lattice 0 + n × 1"), "{err}");
        let rows = [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 2.0]];
        let err = from_table(&table(&rows), NAMES).expect_err("duplicate");
        assert!(err.starts_with("two rows give a value at x = 0, y = 0, z = 0 (the second is row 2)"), "{err}");
        let rows = [[0.0, f64::NAN, 0.0, 1.0]];
        assert_eq!(
            from_table(&table(&rows), NAMES),
            Err("y is NaN in row 1; every row of a volume needs finite coordinates".into())
        );
        let rows = [[0.0, 0.0, 0.0, 1.0], [1e-12, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]];
        let err = from_table(&table(&rows), NAMES).expect_err("too many steps");
        assert!(err.contains("more than a volume holds"), "{err}");
        let err = from_table(&table(&rows), ["x", "y", "w", "value"]).expect_err("no column");
        assert!(err.starts_with("the table has no column `w`"), "{err}");
        let one = from_table(&table(&[[5.0, 6.0, 7.0, 8.0]]), NAMES).expect("one point");
        assert_eq!((one.dims(), one.spacing(), one.value(0, 0, 0)), ([1, 1, 1], [1.0; 3], 8.0));
    }
}
