//! Whole volumes with known answers: spheres (unit, anisotropic, rotated and flipped
//! placements), a torus, two spheres, random volumes, and the two textbook ambiguities.

use std::f64::consts::PI;

use super::*;

/// `f = r − |p − c|`: the ball of radius `r` around `c` is inside.
fn ball(c: [f64; 3], r: f64) -> impl Fn([f64; 3]) -> f64 {
    move |p| r - cube::norm(cube::sub(p, c))
}

/// Relative error of `got` against `want`.
fn rel(got: f64, want: f64) -> f64 {
    (got - want).abs() / want.abs()
}

/// The mean angle, in degrees, between the mesh's normals and the outward radial direction from
/// `c`.
fn radial_error(mesh: &IsoMesh, c: [f64; 3]) -> f64 {
    let sum: f64 = mesh
        .positions
        .iter()
        .zip(&mesh.normals)
        .map(|(p, n)| {
            let d = cube::sub(*p, c);
            (cube::dot(d, *n) / cube::norm(d)).clamp(-1.0, 1.0).acos().to_degrees()
        })
        .sum();
    sum / mesh.positions.len() as f64
}

struct Measured {
    area: f64,
    volume: f64,
    angle: f64,
}

/// Extracts the sphere of radius `r` around `c` from `vol` and checks it is one closed, outward
/// sphere; returns its errors.
fn sphere(vol: &Volume, c: [f64; 3], r: f64, method: Method, rule: NormalRule) -> Measured {
    let mesh = extract(vol, 0.0, method, rule, None).expect("mesh");
    check_closed(&mesh, |_| Vec::new()).expect("closed and oriented");
    assert!(smallest_area(&mesh) > 1e-9);
    assert_eq!(mesh.euler_characteristic(), 2, "a sphere");
    assert_eq!(mesh.components(), 1);
    assert_eq!(mesh.normals.len(), mesh.positions.len());
    assert!(mesh.normals.iter().all(|n| (cube::norm(*n) - 1.0).abs() < 1e-9), "unit normals");
    let volume = mesh.enclosed_volume();
    assert!(volume > 0.0, "counter-clockwise from outside: positive volume, got {volume}");
    Measured {
        area: rel(mesh.area(), 4.0 * PI * r * r),
        volume: rel(volume, 4.0 / 3.0 * PI * r.powi(3)),
        angle: radial_error(&mesh, c),
    }
}

#[test]
fn a_sampled_sphere_has_the_right_area_volume_topology_and_normals() {
    let (c, r) = ([20.0, 20.0, 20.0], 15.0);
    let vol = sampled([41; 3], spaced([1.0; 3]), ball(c, r));
    let m = sphere(&vol, c, r, Method::MarchingCubes, NormalRule::Gradient);
    eprintln!(
        "sphere, marching cubes, gradient normals: area {:.4}%, volume {:.4}%, normals {:.3}°",
        100.0 * m.area,
        100.0 * m.volume,
        m.angle
    );
    assert!(m.area < 0.01 && m.volume < 0.01 && m.angle < 2.0);
    let f = sphere(&vol, c, r, Method::MarchingCubes, NormalRule::Faces);
    eprintln!("sphere, marching cubes, face normals: normals {:.3}°", f.angle);
    assert!(f.angle < 2.0);
    let t = sphere(&vol, c, r, Method::Tetrahedra, NormalRule::Gradient);
    eprintln!(
        "sphere, tetrahedra: area {:.4}%, volume {:.4}%, normals {:.3}°",
        100.0 * t.area,
        100.0 * t.volume,
        t.angle
    );
    assert!(t.area < 0.02 && t.volume < 0.02 && t.angle < 2.0);
}

#[test]
fn anisotropic_rotated_and_flipped_placements_keep_the_sphere() {
    let r = 15.0;
    // Spacing [1, 1, 2.5]: the sphere is defined in the world, so it spans fewer voxels in z.
    let c = [20.0, 20.0, 50.0];
    let vol = sampled([41; 3], spaced([1.0, 1.0, 2.5]), ball(c, r));
    for method in [Method::MarchingCubes, Method::Tetrahedra] {
        let m = sphere(&vol, c, r, method, NormalRule::Gradient);
        eprintln!(
            "anisotropic sphere, {method:?}: area {:.4}%, volume {:.4}%, normals {:.3}°",
            100.0 * m.area,
            100.0 * m.volume,
            m.angle
        );
        let tol = if method == Method::MarchingCubes { 0.01 } else { 0.02 };
        assert!(m.area < tol && m.volume < tol && m.angle < 2.0);
    }
    // A flipped x axis (negative determinant, as in many NIfTI files): still outward.
    let flipped = [[-1.0, 0.0, 0.0, 40.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];
    let c = [20.0, 20.0, 20.0];
    let vol = sampled([41; 3], flipped, ball(c, r));
    for method in [Method::MarchingCubes, Method::Tetrahedra] {
        let m = sphere(&vol, c, r, method, NormalRule::Gradient);
        eprintln!(
            "flipped sphere, {method:?}: area {:.4}%, volume {:.4}%, normals {:.3}°",
            100.0 * m.area,
            100.0 * m.volume,
            m.angle
        );
        assert!(m.volume < 0.02 && m.angle < 2.0);
        assert!(sphere(&vol, c, r, method, NormalRule::Faces).angle < 2.0, "face normals outward too");
    }
    // Rotated 30° about z, sheared spacing, flipped z: the gradient goes to the world through
    // the inverse transpose.
    let (s, co) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    let affine = [[co * 1.2, -s * 1.5, 0.0, 5.0], [s * 1.2, co * 1.5, 0.0, -3.0], [0.0, 0.0, -1.3, 60.0]];
    let c = affine.map(|row| row[0] * 20.0 + row[1] * 20.0 + row[2] * 20.0 + row[3]);
    let vol = sampled([41; 3], affine, ball(c, r));
    let m = sphere(&vol, c, r, Method::MarchingCubes, NormalRule::Gradient);
    eprintln!("rotated sphere: area {:.4}%, volume {:.4}%, normals {:.3}°", 100.0 * m.area, 100.0 * m.volume, m.angle);
    assert!(m.area < 0.01 && m.volume < 0.01 && m.angle < 2.0);
}

#[test]
fn a_torus_has_euler_characteristic_0_and_two_spheres_are_two_components() {
    let torus = |p: [f64; 3]| {
        let [x, y, z] = [p[0] - 20.0, p[1] - 20.0, p[2] - 20.0];
        let ring = (x * x + y * y).sqrt() - 12.0;
        5.0 - (ring * ring + z * z).sqrt()
    };
    let vol = sampled([41; 3], spaced([1.0; 3]), torus);
    for method in [Method::MarchingCubes, Method::Tetrahedra] {
        let mesh = extract(&vol, 0.0, method, NormalRule::Gradient, None).expect("mesh");
        check_closed(&mesh, |_| Vec::new()).expect("closed");
        assert_eq!(mesh.euler_characteristic(), 0, "{method:?}");
        assert_eq!(mesh.components(), 1);
        let want = 2.0 * PI * PI * 12.0 * 25.0;
        assert!(rel(mesh.enclosed_volume(), want) < 0.02, "{} vs {want}", mesh.enclosed_volume());
    }
    let (a, b) = (ball([12.0, 20.0, 20.0], 6.0), ball([29.0, 20.0, 20.0], 6.0));
    let vol = sampled([41; 3], spaced([1.0; 3]), move |p| a(p).max(b(p)));
    for method in [Method::MarchingCubes, Method::Tetrahedra] {
        let mesh = extract(&vol, 0.0, method, NormalRule::Gradient, None).expect("mesh");
        check_closed(&mesh, |_| Vec::new()).expect("closed");
        assert_eq!(mesh.components(), 2);
        assert_eq!(mesh.euler_characteristic(), 4);
    }
}

#[test]
fn random_volumes_are_watertight_and_consistently_oriented() {
    for seed in 1..=6u64 {
        let mut rng = Rng::new(seed);
        let dims = [8, 8, 8];
        let vol = volume(dims, (0..512).map(|_| rng.next() * 2.0 - 1.0).collect());
        for method in [Method::MarchingCubes, Method::Tetrahedra] {
            for iso in [-0.3, 0.0, 0.25] {
                let mesh = extract(&vol, iso, method, NormalRule::Gradient, None).expect("mesh");
                assert!(!mesh.triangles.is_empty());
                check_closed(&mesh, box_faces(dims))
                    .unwrap_or_else(|e| panic!("seed {seed} {method:?} iso {iso}: {e}"));
                assert!(smallest_area(&mesh) > 1e-12, "seed {seed} {method:?}: a degenerate triangle");
                assert!(mesh.normals.iter().all(|n| (cube::norm(*n) - 1.0).abs() < 1e-9));
            }
        }
    }
}

/// The values of a face whose diagonal corners (0, 0) and (1, 1) are `high` and the other two
/// −1, below the level 0.
fn saddle_face(high: f64) -> [f64; 4] {
    // Face values a, b, c, d (corners (0,0), (1,0), (0,1), (1,1)): a = d = high, b = c = −1;
    // saddle (a·d − b·c)/(a + d − b − c) = (high² − 1)/(2·high + 2).
    [high, -1.0, -1.0, high]
}

#[test]
fn the_face_ambiguity_follows_the_saddle_value() {
    for (high, joined) in [(1.5, true), (0.6, false)] {
        let face = saddle_face(high);
        let saddle = (face[0] * face[3] - face[1] * face[2]) / (face[0] + face[3] - face[1] - face[2]);
        assert_eq!(saddle > 0.0, joined);
        // One cell: bottom face ambiguous, top face all below.
        let mut values = face.to_vec();
        values.extend([-1.0; 4]);
        let mesh = extract(&volume([2, 2, 2], values.clone()), 0.0, Method::MarchingCubes, NormalRule::Gradient, None)
            .expect("mesh");
        // Classic table-only marching cubes always cuts the two corners off separately (two
        // triangles); the trilinear function joins them when the saddle is above the level.
        assert_eq!(mesh.components(), if joined { 1 } else { 2 }, "high {high}");
        assert_eq!(mesh.triangles.len(), if joined { 4 } else { 2 });
        // The same face shared by two cells: both decide it alike, so no crack.
        let mut two = vec![-1.0; 4];
        two.extend(face);
        two.extend([-1.0; 4]);
        let mesh =
            extract(&volume([2, 2, 3], two), 0.0, Method::MarchingCubes, NormalRule::Gradient, None).expect("mesh");
        check_closed(&mesh, box_faces([2, 2, 3])).expect("closed across the shared face");
        assert_eq!(mesh.components(), if joined { 1 } else { 2 });
        // Joined: the two cells' hexagons glued along the face's two segments, an annulus
        // (χ = 0) around the high ridge; apart: two disks of two triangles each (χ = 2).
        assert_eq!(mesh.euler_characteristic(), if joined { 0 } else { 2 });
    }
}

#[test]
fn the_interior_ambiguity_of_case_4_gives_a_tube_when_the_centre_is_inside() {
    for (low, tube) in [(-0.2, true), (-0.5, false)] {
        let mut g = [low; 8];
        g[0] = 1.0;
        g[7] = 1.0;
        let mesh = extract(&volume([2, 2, 2], g.to_vec()), 0.0, Method::MarchingCubes, NormalRule::Gradient, None)
            .expect("mesh");
        let uses = edge_uses(&mesh);
        let open = uses.values().filter(|u| u[0] + u[1] == 1).count();
        assert_eq!(open, 6, "two triangles' worth of boundary edges");
        if tube {
            assert_eq!((mesh.components(), mesh.euler_characteristic()), (1, 0), "one tube (an annulus)");
        } else {
            assert_eq!((mesh.components(), mesh.euler_characteristic()), (2, 2), "two disks");
        }
    }
}
