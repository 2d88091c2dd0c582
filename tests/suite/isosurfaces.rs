//! `kind = "isosurface"`: surfaces of a volume drawn in 3-D and written as glTF, PLY and OBJ.
//! Areas and enclosed volumes are checked against the sphere's formulas, the files against
//! their formats, and bad specs against their documented errors.

use crate::common::{Fixture, numbers, run_dataink};
use dataink::mark::ChartOutput;
use dataink::scene::{Item, Shape};

/// A 3-D `.npy` (shape nz × ny × nx, x fastest) of `f` at the voxels' world points
/// `(i·sx, j·sy, k·sz)`.
fn volume_npy(n: [usize; 3], spacing: [f64; 3], f: impl Fn([f64; 3]) -> f64) -> Vec<u8> {
    let mut data = Vec::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let p = [i as f64 * spacing[0], j as f64 * spacing[1], k as f64 * spacing[2]];
                data.extend(f(p).to_le_bytes());
            }
        }
    }
    crate::common::npy("<f8", &format!("({}, {}, {})", n[2], n[1], n[0]), &data)
}

/// Distance from (20, 20, 20): spheres of radius r are its level sets.
fn distance(p: [f64; 3]) -> f64 {
    ((p[0] - 20.0).powi(2) + (p[1] - 20.0).powi(2) + (p[2] - 20.0).powi(2)).sqrt()
}

fn spec(chart: &str, spacing: [f64; 3]) -> String {
    format!(
        "[data.field]\npath = \"field.npy\"\nspacing = {spacing:?}\n\n[[chart]]\nname = \"iso\"\nkind = \"isosurface\"\ndata = \"field\"\ntitle = \"Spheres\"\n{chart}"
    )
}

fn draw(chart: &str, spacing: [f64; 3], npy: &[u8]) -> Result<ChartOutput, String> {
    Fixture::new(&spec(chart, spacing), &[("field.npy", npy)]).draw().map(|mut v| v.remove(0))
}

fn mesh_labels(out: &ChartOutput) -> Vec<String> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if let Shape::Mesh(_) = &item.shape {
            found.push(item.label.clone().unwrap_or_default());
        }
    });
    found
}

#[test]
fn a_sphere_has_the_area_and_volume_of_a_sphere_with_spacing_honoured() {
    for spacing in [[1.0, 1.0, 1.0], [1.0, 1.0, 2.0]] {
        let n = [41, 41, (40.0 / spacing[2]) as usize + 1];
        let npy = volume_npy(n, spacing, distance);
        let out = draw("levels = [12]\n", spacing, &npy).unwrap_or_else(|e| panic!("{e}"));
        let r: f64 = 12.0;
        let area = numbers(&out, "area")[0];
        let volume = numbers(&out, "enclosed_volume")[0].abs();
        let area_error = (area / (4.0 * std::f64::consts::PI * r * r) - 1.0).abs();
        let volume_error = (volume / (4.0 / 3.0 * std::f64::consts::PI * r.powi(3)) - 1.0).abs();
        assert!(area_error < 0.02 && volume_error < 0.02, "{spacing:?}: area {area}, volume {volume}");
        assert_eq!((numbers(&out, "components"), numbers(&out, "euler_characteristic")), (vec![1.0], vec![2.0]));
        assert_eq!(mesh_labels(&out), ["value = 12"]);
        // The caption states the triangle count.
        let triangles = numbers(&out, "triangles")[0] as usize;
        let mut caption = String::new();
        out.scene.walk(|item: &Item| {
            if item.role == dataink::scene::Role::Caption
                && let Shape::Text(t) = &item.shape
            {
                caption = t.content.clone();
            }
        });
        let shown = triangles.to_string();
        let grouped: String = shown
            .chars()
            .enumerate()
            .flat_map(|(k, c)| (k > 0 && (shown.len() - k) % 3 == 0).then_some(',').into_iter().chain([c]))
            .collect();
        assert!(caption.starts_with(&format!("{grouped} triangles (marching cubes")), "{caption}");
    }
}

#[test]
fn several_surfaces_draw_opaque_first_and_warn_about_values_outside_the_data() {
    let npy = volume_npy([41, 41, 41], [1.0; 3], distance);
    let out = draw("levels = [6, 12, 99]\n", [1.0; 3], &npy).unwrap_or_else(|e| panic!("{e}"));
    // Two surfaces exist (99 lies outside 0..34.6); the inner one (6) is opaque and drawn
    // before the translucent outer one.
    assert_eq!(mesh_labels(&out), ["value = 6", "value = 12"]);
    let warned: Vec<String> = out.warnings.iter().map(|w| w.message()).collect();
    assert!(warned.iter().any(|w| w.contains("level 99 is outside the volume's values")), "{warned:?}");
    // Lint rule DI008 reports the missing surface as an error; levels inside the data pass.
    let files: &[(&str, &[u8])] = &[("field.npy", &npy)];
    let found = crate::common::lint_findings(&spec("levels = [6, 12, 99, -1]\n", [1.0; 3]), files, "DI008");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].message.starts_with("levels 99, −1 are outside the volume's values (0 to"),
        "{}",
        found[0].message
    );
    assert!(crate::common::lint_findings(&spec("levels = [6, 12]\n", [1.0; 3]), files, "DI008").is_empty());
    // Opaque surfaces share one mesh, so its depth buffer decides which hides which.
    let opaque = draw("levels = [6, 12]\nopacity = 1\n", [1.0; 3], &npy).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(mesh_labels(&opaque), ["values = 6, 12"]);
    let tetra = draw("levels = 12\nmethod = \"tetrahedra\"\nnormals = \"faces\"\n", [1.0; 3], &npy)
        .unwrap_or_else(|e| panic!("{e}"));
    let area = numbers(&tetra, "area")[0];
    assert!((area / (4.0 * std::f64::consts::PI * 144.0) - 1.0).abs() < 0.03, "{area}");
}

#[test]
fn surfaces_are_written_as_glb_ply_and_obj() {
    let npy = volume_npy([21, 21, 21], [1.0; 3], |p| distance([p[0] + 10.0, p[1] + 10.0, p[2] + 10.0]));
    let fx = Fixture::new(&spec("levels = [4, 8]\n", [1.0; 3]), &[("field.npy", &npy)]);
    let out =
        run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--format", "png,csv,glb,ply,obj"], 120)
            .expect("finished");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let dir = fx.dir.path().join("out");
    let glb = std::fs::read(dir.join("iso.glb")).expect("glb");
    assert_eq!(&glb[..4], b"glTF");
    assert_eq!(u32::from_le_bytes([glb[8], glb[9], glb[10], glb[11]]) as usize, glb.len());
    let json_len = u32::from_le_bytes([glb[12], glb[13], glb[14], glb[15]]) as usize;
    let doc: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).expect("JSON chunk");
    assert_eq!(doc["meshes"].as_array().map(Vec::len), Some(2));
    // Levels outside the data: no surface, no glb file, and the command says it wrote nothing.
    let none = Fixture::new(&spec("levels = [99]\n", [1.0; 3]), &[("field.npy", &npy)]);
    let out = run_dataink(none.dir.path(), &["render", "spec.toml", "--out", "out", "--format", "glb"], 120)
        .expect("finished");
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(said.contains("wrote nothing for chart \"iso\": it has nothing in the formats asked for"), "{said}");
    assert!(!none.dir.path().join("out/iso.glb").exists());
    let csv = std::fs::read_to_string(dir.join("iso.csv")).expect("csv");
    let vertices: Vec<usize> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).and_then(|v| v.parse::<f64>().ok()).expect("vertices") as usize)
        .collect();
    let ply = std::fs::read(dir.join("iso.ply")).expect("ply");
    let head = String::from_utf8_lossy(&ply[..300]);
    assert!(head.contains(&format!("element vertex {}\n", vertices.iter().sum::<usize>())), "{head}");
    let obj = std::fs::read_to_string(dir.join("iso.obj")).expect("obj");
    assert_eq!(obj.lines().filter(|l| l.starts_with("v ")).count(), vertices.iter().sum::<usize>());
    assert_eq!(obj.lines().filter(|l| l.starts_with("o ")).count(), 2);
    // The first surface's glTF positions lie on its sphere (radius 4 about the volume's middle).
    let accessor =
        &doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].as_u64().expect("a") as usize];
    let (lo, hi) = (&accessor["min"], &accessor["max"]);
    for a in 0..3 {
        let (l, h) = (lo[a].as_f64().expect("min"), hi[a].as_f64().expect("max"));
        assert!((l - 6.0).abs() < 0.3 && (h - 14.0).abs() < 0.3, "axis {a}: {l} to {h}");
    }
}

#[test]
fn bad_isosurface_specs_give_their_documented_errors() {
    let npy = volume_npy([5, 5, 5], [1.0; 3], |p| p[0]);
    for (chart, message) in [
        ("levels = [1, 2, 3, 4, 5, 6, 7, 8, 9]", "9 iso values given; a chart draws 1 to 8 surfaces"),
        ("levels = []", "0 iso values given"),
        ("levels = [1, 2]\ncolors = [\"red\"]", "1 colours for 2 surfaces"),
        ("levels = 1\ncolors = [\"nope\"]", "`nope` is not a colour"),
        ("levels = 1\nopacity = 0", "opacity 0 is not in 0.05 to 1"),
        ("levels = [1, 2]\nopacity = [0.5]", "1 opacities for 2 surfaces"),
        ("levels = 1\nzoom = 0", "zoom"),
    ] {
        let err = draw(chart, [1.0; 3], &npy).expect_err(chart);
        assert!(err.contains(message), "{chart}: {err}");
    }
}

#[test]
fn the_readme_example_draws_the_orbitals_lobes_and_torus_lint_clean() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let start =
        readme.find("[data.hydrogen]\npath = \"data/hydrogen-3dz2.npy\"").expect("the README's isosurface example");
    let block = &readme[start..start + readme[start..].find("```").expect("end of block")];
    let npy = std::fs::read(root.join("examples/data/hydrogen-3dz2.npy")).expect("the shipped field");
    let fx = Fixture::new(block, &[("data/hydrogen-3dz2.npy", &npy)]);
    let out = fx.draw().unwrap_or_else(|e| panic!("{e}")).remove(0);
    // The 3dz² density |ψ|², ψ ∝ r²e^(−r/3)(3cos²θ − 1): along z the lobes peak at 4× the torus
    // around the waist. At half the peak only the two lobes remain (two spheres: χ = 2 + 2); at
    // a tenth the torus (χ = 0) joins them; every surface stays inside the box, so is closed.
    assert_eq!(numbers(&out, "iso"), [0.01, 0.1, 0.5]);
    let components = numbers(&out, "components");
    let euler = numbers(&out, "euler_characteristic");
    assert_eq!((components[2], euler[2]), (2.0, 4.0));
    assert_eq!((components[1], euler[1]), (3.0, 4.0));
    // The 0.5 surface is drawn first and opaque; the two around it see-through.
    assert_eq!(mesh_labels(&out), ["value = 0.5", "value = 0.1", "value = 0.01"]);
    let lint = fx.lint().unwrap_or_else(|e| panic!("{e}"));
    assert!(lint[0].findings.is_empty(), "{:?}", lint[0].findings);
}

/// The Marschner–Lobb signal's parameters as examples/data/make_fields.py samples it.
const ML_FM: f64 = 6.0;
const ML_ALPHA: f64 = 0.25;

/// The outward unit normal `−∇f / |∇f|` of the continuous Marschner–Lobb function
/// `f = (1 − sin(πz/2) + α(1 + ρ(r))) / (2(1 + α))`, `ρ(r) = cos(2π f_M cos(πr/2))`,
/// `r = √(x² + y²)`, at world point `p`: `ρ′(r) = π² f_M sin(πr/2) sin(2π f_M cos(πr/2))`, so
/// `∂f/∂x = α ρ′(r) x / r / (2(1 + α))` (likewise y; 0 on the axis, where ρ′(r)/r stays finite
/// and the x, y factors vanish) and `∂f/∂z = −(π/2) cos(πz/2) / (2(1 + α))`.
fn marschner_lobb_normal(p: [f64; 3]) -> [f64; 3] {
    use std::f64::consts::PI;
    let [x, y, z] = p;
    let r = x.hypot(y);
    let d_rho = PI * PI * ML_FM * (PI * r / 2.0).sin() * (2.0 * PI * ML_FM * (PI * r / 2.0).cos()).sin();
    let radial = if r > 0.0 { ML_ALPHA * d_rho / r } else { 0.0 };
    let denominator = 2.0 * (1.0 + ML_ALPHA);
    let grad = [radial * x / denominator, radial * y / denominator, -PI / 2.0 * (PI * z / 2.0).cos() / denominator];
    let length = (grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]).sqrt();
    grad.map(|g| -g / length)
}

/// Per vertex, its distance from the z axis and the angle in degrees between its normal and the
/// analytic normal at its position.
fn normal_errors(mesh: &dataink::enrich::volume::isosurface::IsoMesh) -> Vec<(f64, f64)> {
    mesh.positions
        .iter()
        .zip(&mesh.normals)
        .map(|(&p, n)| {
            let m = marschner_lobb_normal(p);
            let cos = (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]).clamp(-1.0, 1.0);
            (p[0].hypot(p[1]), cos.acos().to_degrees())
        })
        .collect()
}

/// The mean and 95th percentile of `angles`.
fn mean_and_p95(mut angles: Vec<f64>) -> (f64, f64) {
    angles.sort_by(f64::total_cmp);
    let mean = angles.iter().sum::<f64>() / angles.len() as f64;
    let p95 = angles[(angles.len() * 95).div_ceil(100) - 1];
    (mean, p95)
}

/// The README's normal accuracy on Marschner–Lobb (f_M = 6, α = 0.25, 41³ on [−1, 1]³, level
/// 0.5), over all vertices and over those within 0.5 of the z axis, where the rings of the
/// signal are still three or more voxels long (further out they near two, the Nyquist limit):
/// `cargo test --test suite marschner_lobb -- --nocapture` prints the numbers. The same voxels
/// placed with x flipped (a negative determinant) sample the same function, which is even in
/// x, so the normals must come out as accurate there.
#[test]
fn marschner_lobb_vertex_normals_follow_the_analytic_gradient() {
    use dataink::enrich::volume::isosurface::{Method, NormalRule, extract};
    let path = crate::common::root().join("examples/data/marschner-lobb.npy");
    let volume = dataink::data::volume::npy::read(&path, [0.05; 3])
        .unwrap_or_else(|e| panic!("{e:?}"))
        .with_origin([-1.0; 3])
        .expect("origin");
    let flipped = volume
        .clone()
        .with_affine([[-0.05, 0.0, 0.0, 1.0], [0.0, 0.05, 0.0, -1.0], [0.0, 0.0, 0.05, -1.0]])
        .expect("affine");
    for (placed, v) in [("", &volume), (", x flipped", &flipped)] {
        // (mean, p95) over all vertices and within r < 0.5, per rule.
        let mut measured = Vec::new();
        for rule in [NormalRule::Gradient, NormalRule::Faces] {
            let mesh = extract(v, 0.5, Method::MarchingCubes, rule, None).expect("the surface");
            let errors = normal_errors(&mesh);
            let inner: Vec<f64> = errors.iter().filter(|e| e.0 < 0.5).map(|e| e.1).collect();
            let (all, inner) = (mean_and_p95(errors.iter().map(|e| e.1).collect()), mean_and_p95(inner));
            println!(
                "Marschner–Lobb 41³, level 0.5{placed}, {rule:?} normals: angle to the analytic normal mean {:.1}°, 95th percentile {:.1}° ({} vertices); within r < 0.5: mean {:.1}°, 95th percentile {:.1}°",
                all.0,
                all.1,
                errors.len(),
                inner.0,
                inner.1
            );
            measured.push((rule, all, inner));
        }
        for &(rule, all, inner) in &measured {
            // The measured values (32.0°, 68.7°; 12.6°, 30.1° and 36.4°, 120.9°; 17.9°, 63.4°)
            // with a quarter's margin.
            let [all_bound, inner_bound] = match rule {
                NormalRule::Gradient => [(40.0, 86.0), (16.0, 38.0)],
                NormalRule::Faces => [(46.0, 151.0), (22.5, 79.0)],
            };
            assert!(
                all.0 < all_bound.0 && all.1 < all_bound.1 && inner.0 < inner_bound.0 && inner.1 < inner_bound.1,
                "{rule:?}{placed}: all {all:.2?}, r < 0.5 {inner:.2?}"
            );
        }
        let (gradient, faces) = (&measured[0], &measured[1]);
        assert!(
            gradient.1.0 <= faces.1.0 && gradient.1.1 <= faces.1.1 && gradient.2.0 <= faces.2.0,
            "gradient normals {:.2?} are worse than face normals {:.2?}",
            gradient,
            faces
        );
    }
}
