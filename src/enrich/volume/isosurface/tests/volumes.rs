//! The cell list, voxels exactly at the level, missing voxels, thin volumes, normals' fallback
//! and errors.

use std::collections::HashSet;

use super::*;

/// The cells (by number) that give triangles when extracted one at a time.
fn emitting(vol: &Volume, iso: f64, method: Method) -> Vec<u32> {
    let [nx, ny, nz] = vol.dims();
    let count = (nx - 1) * (ny - 1) * (nz - 1);
    (0..count as u32)
        .filter(|&c| !extract(vol, iso, method, NormalRule::Faces, Some(&[c])).expect("mesh").triangles.is_empty())
        .collect()
}

/// The corner range of cell `c`.
fn cell_range(vol: &Volume, c: u32) -> (f64, f64) {
    let [nx, ny, _] = vol.dims();
    let c = c as usize;
    let (i, j, k) = (c % (nx - 1), c / (nx - 1) % (ny - 1), c / ((nx - 1) * (ny - 1)));
    let mut range = (f64::INFINITY, f64::NEG_INFINITY);
    for d in 0..8 {
        let v = vol.value(i + (d & 1), j + (d >> 1 & 1), k + (d >> 2 & 1));
        range = (range.0.min(v), range.1.max(v));
    }
    range
}

#[test]
fn active_cells_are_the_cells_that_give_triangles() {
    let mut rng = Rng::new(7);
    let dims = [5, 4, 6];
    let n: usize = dims.iter().product();
    // Floats: no voxel at the level, so active ⇔ triangles.
    let floats = volume(dims, (0..n).map(|_| rng.next()).collect());
    for iso in [0.2, 0.5, 0.77] {
        for method in [Method::MarchingCubes, Method::Tetrahedra] {
            assert_eq!(active_cells(&floats, iso), emitting(&floats, iso, method), "iso {iso} {method:?}");
        }
    }
    // Small integers and integer levels, including the data's minimum and maximum: every cell
    // with triangles is active, and an active cell without triangles touches the level exactly.
    let ints = volume(dims, (0..n).map(|_| (rng.next() * 4.0).floor()).collect());
    let (lo, hi) = ints.range().0.expect("values");
    for iso in [lo, 1.0, 2.0, hi] {
        let active = active_cells(&ints, iso);
        for method in [Method::MarchingCubes, Method::Tetrahedra] {
            let emit = emitting(&ints, iso, method);
            assert!(emit.iter().all(|c| active.binary_search(c).is_ok()), "iso {iso}: a cell outside the list");
            for c in &active {
                let (a, b) = cell_range(&ints, *c);
                assert!(emit.contains(c) || a == iso || b == iso, "iso {iso}: active cell {c} ({a}, {b}) is silent");
            }
        }
    }
    assert!(extract(&ints, lo, Method::MarchingCubes, NormalRule::Gradient, None).expect("mesh").triangles.is_empty());
    // A constant volume: every cell is active at its value, none has a surface.
    let flat = volume([3, 3, 3], vec![2.0; 27]);
    assert_eq!(active_cells(&flat, 2.0).len(), 8);
    assert!(active_cells(&flat, 2.5).is_empty());
    assert!(extract(&flat, 2.0, Method::MarchingCubes, NormalRule::Gradient, None).expect("mesh").triangles.is_empty());
}

#[test]
fn active_cells_follow_the_corner_range_rule() {
    let mut rng = Rng::new(11);
    // Rows of 64 cells and more cross the 64-cell words the scan packs.
    for dims in [[2, 2, 2], [5, 3, 4], [9, 7, 6], [1, 4, 4], [64, 3, 2], [65, 2, 3], [130, 3, 3], [129, 2, 2]] {
        let n: usize = dims.iter().product();
        // Small integers (voxels at the level), a few missing and infinite voxels.
        let values: Vec<f64> = (0..n)
            .map(|_| match rng.next() {
                r if r < 0.05 => f64::NAN,
                r if r < 0.08 => f64::INFINITY,
                r if r < 0.1 => f64::NEG_INFINITY,
                r => (r * 4.0).floor(),
            })
            .collect();
        let vol = volume(dims, values);
        let offsets = corner_offsets(&vol);
        let [nx, ny, _] = dims;
        let cells = dims.map(|d| d.saturating_sub(1));
        for iso in [0.0, 0.5, 1.0, 2.0, 3.0, 3.5] {
            let mut expected = Vec::new();
            for (id, c) in (0..cells.iter().product::<usize>()).enumerate() {
                let (i, j, k) = (c % cells[0], c / cells[0] % cells[1], c / (cells[0] * cells[1]));
                let range = corner_range(&vol, (k * ny + j) * nx + i, &offsets);
                if range.is_some_and(|(lo, hi)| lo <= iso && iso <= hi) {
                    expected.push(id as u32);
                }
            }
            assert_eq!(active_cells(&vol, iso), expected, "dims {dims:?} iso {iso}");
        }
    }
}

#[test]
fn f32_voxels_compared_as_stored_follow_the_corner_range_rule() {
    use crate::data::volume::Scale;
    let mut rng = Rng::new(23);
    let dims = [70, 5, 4];
    let n: usize = dims.iter().product();
    // Values a few f32 steps apart around 0.1 and 1e30, missing and infinite ones.
    let values: Vec<f32> = (0..n)
        .map(|_| match rng.next() {
            r if r < 0.05 => f32::NAN,
            r if r < 0.07 => f32::INFINITY,
            r if r < 0.5 => (0..(r * 100.0) as usize % 4).fold(0.1f32, |v, _| v.next_up()),
            r if r < 0.9 => (0..(r * 100.0) as usize % 4).fold(0.1f32, |v, _| v.next_down()),
            _ => 1e30,
        })
        .collect();
    let stored = Volume::new(dims, Voxels::F32(values.clone()), [1.0; 3]).expect("volume");
    // The same values as f64 voxels: the scan must not depend on how they are stored.
    let wide = volume(dims, values.iter().map(|&v| f64::from(v)).collect());
    // A scale of 1 · v + 0 takes the other path, through the values as numbers.
    let scaled = Volume::new(dims, Voxels::F32(values), [1.0; 3])
        .expect("volume")
        .with_scale(Some(Scale { slope: 1.0, inter: 0.0 }));
    let steps = |v: f32| [v.next_down(), v, v.next_up()].map(f64::from);
    let mut levels = vec![0.1, 1e30, 1e300, -1e300, f64::from(f32::MAX), 3.4028235677973366e38];
    levels.extend(steps(0.1).iter().flat_map(|&v| [v, v.next_up(), v.next_down()]));
    levels.extend(steps(1e30));
    for iso in levels {
        let expected = active_cells(&wide, iso);
        assert_eq!(active_cells(&stored, iso), expected, "iso {iso:e}");
        assert_eq!(active_cells(&scaled, iso), expected, "iso {iso:e}, scaled");
    }
    assert!(!active_cells(&wide, 0.1).is_empty() && !active_cells(&wide, 1e30).is_empty());
}

#[test]
fn voxels_at_the_level_make_no_degenerate_triangles_or_duplicate_vertices() {
    for seed in 1..=5u64 {
        let mut rng = Rng::new(100 + seed);
        let dims = [7, 6, 8];
        let n: usize = dims.iter().product();
        let vol = volume(dims, (0..n).map(|_| (rng.next() * 5.0).floor()).collect());
        for iso in [1.0, 2.0, 3.0] {
            for method in [Method::MarchingCubes, Method::Tetrahedra] {
                let mesh = extract(&vol, iso, method, NormalRule::Gradient, None).expect("mesh");
                let what = format!("seed {seed} iso {iso} {method:?}");
                assert!(!mesh.triangles.is_empty(), "{what}");
                assert!(smallest_area(&mesh) > 1e-9, "{what}: a degenerate triangle");
                let distinct: HashSet<[u64; 3]> = mesh.positions.iter().map(|p| p.map(f64::to_bits)).collect();
                assert_eq!(distinct.len(), mesh.positions.len(), "{what}: two vertices at one point");
                let sets: HashSet<[u32; 3]> = mesh
                    .triangles
                    .iter()
                    .map(|t| {
                        let mut t = *t;
                        t.sort_unstable();
                        t
                    })
                    .collect();
                assert_eq!(sets.len(), mesh.triangles.len(), "{what}: two triangles on the same three vertices");
                let used: HashSet<u32> = mesh.triangles.iter().flatten().copied().collect();
                assert_eq!(used.len(), mesh.positions.len(), "{what}: a vertex no triangle uses");
                // Closed and oriented: every edge inside the box used as often each way (where
                // the surface pinches at a voxel on the level, an edge may carry two sheets); on
                // the box's faces, where the surface ends, one use more one way.
                let open = box_faces(dims);
                let mut pinched = 0;
                for ((a, b), [f, r]) in edge_uses(&mesh) {
                    let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
                    let on_box = open(pa).iter().any(|face| open(pb).contains(face));
                    assert!(
                        f == r || (on_box && f.abs_diff(r) == 1),
                        "{what}: edge {pa:?}–{pb:?} used {f} + {r} times"
                    );
                    pinched += usize::from(f + r > 2);
                }
                eprintln!("{what}: {} triangles, {pinched} edges shared by more than two", mesh.triangles.len());
            }
        }
    }
}

#[test]
fn missing_voxels_leave_holes_and_thin_volumes_have_no_cells() {
    let c = [3.0, 3.0, 3.0];
    let mut vol = sampled([7, 7, 7], spaced([1.0; 3]), |p| 2.5 - cube::norm(cube::sub(p, c)));
    let closed = extract(&vol, 0.0, Method::MarchingCubes, NormalRule::Gradient, None).expect("mesh");
    let mut values: Vec<f64> = vol.values().collect();
    let hole = vol.index(5, 3, 3).expect("inside");
    values[hole] = f64::NAN;
    vol = volume([7, 7, 7], values);
    let active = active_cells(&vol, 0.0);
    // The eight cells around voxel (5, 3, 3) are skipped.
    let cell = |i: u32, j: u32, k: u32| (k * 6 + j) * 6 + i;
    for (i, j, k) in [(4, 2, 2), (5, 2, 2), (4, 3, 2), (5, 3, 2), (4, 2, 3), (5, 2, 3), (4, 3, 3), (5, 3, 3)] {
        assert!(!active.contains(&cell(i, j, k)));
    }
    let holed = extract(&vol, 0.0, Method::MarchingCubes, NormalRule::Gradient, None).expect("mesh");
    assert!(holed.triangles.len() < closed.triangles.len());
    let open = edge_uses(&holed).values().filter(|u| u[0] + u[1] == 1).count();
    assert!(open > 0, "the hole has a rim");
    assert_eq!(holed.components(), 1);
    // The rim lies on the skipped cells' faces: x ≥ 4.
    for ((a, b), u) in edge_uses(&holed) {
        if u[0] + u[1] == 1 {
            assert!(holed.positions[a as usize][0] >= 4.0 - 1e-12 && holed.positions[b as usize][0] >= 4.0 - 1e-12);
        }
    }
    // One voxel thick: no cells, no surface, no error.
    let thin = volume([1, 4, 5], (0..20).map(f64::from).collect());
    assert!(active_cells(&thin, 3.0).is_empty());
    let mesh = extract(&thin, 3.0, Method::MarchingCubes, NormalRule::Gradient, None).expect("no error");
    assert!(mesh.triangles.is_empty() && mesh.positions.is_empty());
}

#[test]
fn a_given_cell_list_is_sorted_and_deduplicated_and_checked() {
    let mut rng = Rng::new(3);
    let vol = volume([6, 6, 6], (0..216).map(|_| rng.next()).collect());
    let all = extract(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, None).expect("mesh");
    let mut cells = active_cells(&vol, 0.5);
    cells.reverse();
    cells.extend(cells.clone());
    let given = extract(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, Some(&cells)).expect("mesh");
    assert_eq!(given, all);
    let err = extract(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, Some(&[125])).expect_err("out of range");
    assert_eq!(err, IsoError::CellOutOfRange { cell: 125, cells: 125 });
    assert_eq!(err.to_string(), "cell 125 is not in the volume, which has 125 cells");
}

#[test]
fn bad_levels_and_flat_matrices_are_errors() {
    let vol = volume([2, 2, 2], vec![0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0]);
    let err = extract(&vol, f64::NAN, Method::MarchingCubes, NormalRule::Gradient, None).expect_err("NaN");
    assert!(matches!(err, IsoError::IsoNotFinite(_)));
    assert!(err.to_string().contains("is not a finite number"), "{err}");
    assert!(active_cells(&vol, f64::INFINITY).is_empty());
    let flat =
        vol.clone().with_affine([[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]).expect("finite");
    let err = extract(&flat, 0.5, Method::Tetrahedra, NormalRule::Gradient, None).expect_err("flat");
    assert!(err.to_string().contains("flattens the volume"), "{err}");
    let too_many = IsoError::TooManyTriangles { limit: MAX_TRIANGLES };
    assert!(too_many.to_string().contains("more than 67108864 triangles"), "{too_many}");
    let boxed: Box<dyn std::error::Error> = Box::new(too_many);
    assert!(!boxed.to_string().is_empty());
}

#[test]
fn gradient_normals_fall_back_to_face_normals_where_the_gradient_vanishes() {
    // f = 0, 1, 0, 1, 0 along x: central differences vanish at voxels 1, 2 and 3, so the
    // crossings at x = 1.5 and 2.5 have no gradient; their normals come from the faces.
    let row = [0.0, 1.0, 0.0, 1.0, 0.0];
    let vol = volume([5, 2, 2], (0..20).map(|n| row[n % 5]).collect());
    let mesh = extract(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, None).expect("mesh");
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        // Outward is toward the low side: −x at x = 0.5 and 2.5, +x at 1.5 and 3.5.
        let want = if (p[0] - 1.5).abs() < 1e-9 || (p[0] - 3.5).abs() < 1e-9 { 1.0 } else { -1.0 };
        assert!((n[0] - want).abs() < 1e-9 && n[1].abs() < 1e-9 && n[2].abs() < 1e-9, "{p:?}: {n:?}");
    }
    assert_eq!(mesh.positions.len(), 16);
}
