//! Extraction in slabs on several threads against extraction in one pass: the same mesh, bit
//! for bit, for any cut into slabs and any number of threads.

use std::collections::HashSet;

use super::*;

/// One slab: the serial extraction.
const ONE: Split = Split { slabs: 1, min_cells: 1 };

/// Positions, normals and triangles with every number as its bits.
type Bits<'m> = (Vec<[u64; 3]>, Vec<[u64; 3]>, &'m [[u32; 3]]);

/// The mesh with every number as its bits, so `==` is bitwise (and `-0.0 ≠ 0.0`).
fn bits(mesh: &IsoMesh) -> Bits<'_> {
    let b = |v: &[[f64; 3]]| v.iter().map(|p| p.map(f64::to_bits)).collect();
    (b(&mesh.positions), b(&mesh.normals), &mesh.triangles)
}

/// Random values in [0, 1).
fn noise(dims: [usize; 3], seed: u64) -> Volume {
    let mut rng = Rng::new(seed);
    volume(dims, (0..dims.iter().product()).map(|_| rng.next()).collect())
}

/// Small integers 0..=4: many voxels exactly at integer levels, so crossings snap onto voxels
/// (shared by cells on both sides of a slab boundary) and folded sheets cancel.
fn integers(dims: [usize; 3], seed: u64) -> Volume {
    let mut rng = Rng::new(seed);
    volume(dims, (0..dims.iter().product()).map(|_| (rng.next() * 5.0).floor()).collect())
}

/// An egg crate: `sin x · sin y · sin z` with a period of about 7 voxels, many closed blobs and,
/// at level 0, one sheet with tunnels; every z layer of cells is crossed.
fn egg_crate(dims: [usize; 3]) -> Volume {
    sampled(dims, spaced([1.0; 3]), |p| p.iter().map(|x| (0.9 * x).sin()).product())
}

/// Checks that cutting into `split` gives the serial mesh.
fn same_as_serial(vol: &Volume, iso: f64, split: Split, what: &str) {
    for method in [Method::MarchingCubes, Method::Tetrahedra] {
        for rule in [NormalRule::Gradient, NormalRule::Faces] {
            let serial = extract_split(vol, iso, method, rule, None, ONE).expect("mesh");
            let sliced = extract_split(vol, iso, method, rule, None, split).expect("mesh");
            assert!(
                bits(&sliced) == bits(&serial),
                "{what} iso {iso} {method:?} {rule:?} {split:?}: the meshes differ"
            );
        }
    }
}

#[test]
fn slabs_cut_between_z_layers_and_cover_the_list() {
    let layer = 10;
    let list: Vec<u32> = (0..400).filter(|c| c % 3 != 0).collect();
    for slabs in [1, 2, 3, 7, 40, 1000] {
        let ranges = Split { slabs, min_cells: 1 }.ranges(&list, layer);
        assert_eq!(ranges.first().map(|r| r.start), Some(0));
        assert_eq!(ranges.last().map(|r| r.end), Some(list.len()));
        assert!(ranges.len() <= slabs);
        for w in ranges.windows(2) {
            assert_eq!(w[0].end, w[1].start);
            assert!(list[w[0].end - 1] / 10 < list[w[1].start] / 10, "{slabs} slabs: a cut inside a layer");
        }
    }
    assert_eq!(Split { slabs: 40, min_cells: 1 }.ranges(&list, layer).len(), 40, "one slab a layer");
    assert_eq!(Split { slabs: 8, min_cells: 100 }.ranges(&list, layer).len(), 2, "no slab under 100 cells");
    assert_eq!(Split { slabs: 8, min_cells: 1 }.ranges(&[], layer), vec![0..0]);
    assert_eq!(Split::for_threads(1).slabs, 1);
}

#[test]
fn any_cut_into_slabs_gives_the_serial_mesh_bit_for_bit() {
    let cuts =
        [Split { slabs: 2, min_cells: 1 }, Split { slabs: 5, min_cells: 1 }, Split { slabs: 1000, min_cells: 1 }];
    for split in cuts {
        for seed in 1..=3u64 {
            let vol = noise([9, 8, 11], seed);
            for iso in [0.3, 0.5] {
                same_as_serial(&vol, iso, split, &format!("noise seed {seed}"));
            }
            let vol = integers([8, 9, 10], 40 + seed);
            for iso in [1.0, 2.0, 3.0] {
                same_as_serial(&vol, iso, split, &format!("integers seed {seed}"));
            }
        }
        let vol = egg_crate([20, 18, 24]);
        for iso in [0.0, 0.3, -0.6] {
            same_as_serial(&vol, iso, split, "egg crate");
        }
        // A flipped axis (winding reversed) and a given, unsorted cell list.
        let vol = noise([7, 7, 9], 9).with_affine([[-1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 2.0, 0.0]]);
        let vol = vol.expect("finite affine");
        let mut cells = active_cells(&vol, 0.5);
        cells.reverse();
        let serial = extract_split(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, Some(&cells), ONE);
        let sliced = extract_split(&vol, 0.5, Method::MarchingCubes, NormalRule::Gradient, Some(&cells), split);
        assert!(bits(&sliced.expect("mesh")) == bits(&serial.expect("mesh")), "flipped {split:?}");
    }
}

#[test]
fn one_thread_and_four_give_the_same_watertight_mesh() {
    let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().expect("a thread pool");
    let (one, four) = (pool(1), pool(4));
    // Big enough for several slabs of at least 4096 cells on four threads.
    let fields =
        [("noise", noise([34, 36, 70], 5), vec![0.5, 0.3]), ("egg crate", egg_crate([40, 40, 64]), vec![0.05, 0.4])];
    for (name, vol, levels) in &fields {
        for &iso in levels {
            let active = active_cells(vol, iso);
            assert!(active.len() >= 4 * 4096, "{name} {iso}: {} active cells, too few for 4 slabs", active.len());
            assert_eq!(one.install(|| active_cells(vol, iso)), four.install(|| active_cells(vol, iso)));
            for method in [Method::MarchingCubes, Method::Tetrahedra] {
                let what = format!("{name} iso {iso} {method:?}");
                let run = |pool: &rayon::ThreadPool| {
                    pool.install(|| extract(vol, iso, method, NormalRule::Gradient, None)).expect("mesh")
                };
                let (a, b) = (run(&one), run(&four));
                assert!(bits(&a) == bits(&b), "{what}: the meshes differ");
                // The measures agree too, and the mesh has one vertex per point (the slabs'
                // shared vertices were found again across every cut); the mesh is closed wherever it does not meet the volume's faces.
                assert_eq!(a.euler_characteristic(), b.euler_characteristic(), "{what}");
                assert_eq!(a.components(), b.components(), "{what}");
                assert_eq!(a.area().to_bits(), b.area().to_bits(), "{what}");
                assert_eq!(a.enclosed_volume().to_bits(), b.enclosed_volume().to_bits(), "{what}");
                let distinct: HashSet<[u64; 3]> = b.positions.iter().map(|p| p.map(f64::to_bits)).collect();
                assert_eq!(distinct.len(), b.positions.len(), "{what}: two vertices at one point");
                check_closed(&b, box_faces(vol.dims())).unwrap_or_else(|e| panic!("{what}: {e}"));
            }
        }
    }
}

/// Random fields have every ambiguous configuration many times over, tunnels in thousands of
/// cells among them: the mesh is still closed (every edge has one triangle on each side) away
/// from the volume's faces, so no two cells ever join the same two crossings on their shared
/// face.
#[test]
fn random_fields_give_closed_meshes() {
    for seed in 1..=6u64 {
        let vol = noise([30, 30, 30], seed);
        for iso in [0.5, 0.3] {
            for method in [Method::MarchingCubes, Method::Tetrahedra] {
                let mesh = extract(&vol, iso, method, NormalRule::Faces, None).expect("mesh");
                let what = format!("seed {seed} iso {iso} {method:?}");
                check_closed(&mesh, box_faces(vol.dims())).unwrap_or_else(|e| panic!("{what}: {e}"));
            }
        }
    }
}
