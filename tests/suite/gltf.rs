//! `--format glb` files checked by Khronos' glTF validator: the npm package `gltf-validator`,
//! installed by `scripts/fetch_gltf_validator.sh` into `tests/data/gltf-validator/` (ignored by
//! git) and run by `scripts/validate_gltf.mjs`. Without it (or without Node.js) these tests print
//! a note and pass, except in CI (`CI` set), where they fail.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{Fixture, root, run_dataink, run_with_timeout, skip_outside_ci, volume_npy};
use dataink::render::meshfile::glb::to_glb;
use dataink::scene::WorldMesh;
use serde_json::Value;

/// The installed validator package, or `None` (with a note) when it or Node.js is absent
/// outside CI.
fn validator() -> Option<PathBuf> {
    let dir = std::env::var_os("GLTF_VALIDATOR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("tests/data/gltf-validator/node_modules/gltf-validator"));
    let node = Command::new("node").arg("--version").output().is_ok_and(|o| o.status.success());
    if dir.join("module.mjs").is_file() && node {
        return Some(dir);
    }
    let missing =
        if node { format!("gltf-validator is missing from {}", dir.display()) } else { "node is missing".into() };
    skip_outside_ci(
        &format!("{missing}: CI must run scripts/fetch_gltf_validator.sh (which needs npm and node) first"),
        &format!("note: {missing}; run scripts/fetch_gltf_validator.sh to validate the glb files"),
    );
    None
}

/// The validator's reports on `files`, by file name.
fn validate(validator: &Path, files: &[PathBuf]) -> Vec<(String, Value)> {
    let mut command = Command::new("node");
    command.arg(root().join("scripts/validate_gltf.mjs")).args(files).env("GLTF_VALIDATOR", validator);
    let out = run_with_timeout(command, 300).expect("the validator finishes within 5 minutes");
    assert!(out.status.success(), "validate_gltf.mjs failed: {}", String::from_utf8_lossy(&out.stderr));
    let reports: Vec<Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("a JSON report: {e}: {l}")))
        .collect();
    assert_eq!(reports.len(), files.len(), "one report per file");
    files.iter().map(|f| f.file_name().expect("a name").to_string_lossy().into_owned()).zip(reports).collect()
}

/// Assert that a report has no errors; warnings, infos and hints are counted in the message.
fn assert_valid(name: &str, report: &Value) {
    let issues = &report["issues"];
    let count = |key: &str| issues[key].as_u64().unwrap_or_else(|| panic!("{name}: no {key} in {report}"));
    assert_eq!(
        count("numErrors"),
        0,
        "{name}: glTF validator {}: {} errors, {} warnings, {} infos, {} hints: {}",
        report["validatorVersion"],
        count("numErrors"),
        count("numWarnings"),
        count("numInfos"),
        count("numHints"),
        issues["messages"]
    );
    eprintln!(
        "{name}: glTF validator {}: 0 errors, {} warnings, {} infos, {} hints",
        report["validatorVersion"],
        count("numWarnings"),
        count("numInfos"),
        count("numHints")
    );
}

/// The rendered surfaces: a sphere; hydrogen's 3dz² density at three nested levels, the outer
/// two translucent; and a NIfTI t-map whose voxel-to-world matrix flips x (LAS, determinant
/// −27) at t = ±3, open where the surfaces leave the volume.
const SPEC: &str = r#"
[data.sphere]
path = "sphere.npy"

[data.hydrogen]
path = "hydrogen-3dz2.npy"
origin = [-24, -24, -24]

[data.tmap]
path = "motor-tmap.nii.gz"

[[chart]]
name = "sphere"
kind = "isosurface"
data = "sphere"
levels = 6

[[chart]]
name = "hydrogen"
kind = "isosurface"
data = "hydrogen"
levels = [0.01, 0.1, 0.5]

[[chart]]
name = "tmap"
kind = "isosurface"
data = "tmap"
levels = [-3, 3]
"#;

#[test]
fn rendered_glb_files_pass_the_khronos_validator() {
    let Some(validator) = validator() else { return };
    let sphere = volume_npy([17, 17, 17], |i, j, k| ((i - 8.0).powi(2) + (j - 8.0).powi(2) + (k - 8.0).powi(2)).sqrt());
    let example = |name: &str| std::fs::read(root().join("examples/data").join(name)).expect("an example file");
    let (hydrogen, tmap) = (example("hydrogen-3dz2.npy"), example("motor-tmap.nii.gz"));
    let fx =
        Fixture::new(SPEC, &[("sphere.npy", &sphere), ("hydrogen-3dz2.npy", &hydrogen), ("motor-tmap.nii.gz", &tmap)]);
    let out = run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--format", "glb,csv"], 300)
        .expect("the render finishes");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let dir = fx.dir.path().join("out");
    let files: Vec<PathBuf> = ["sphere", "hydrogen", "tmap"].iter().map(|n| dir.join(format!("{n}.glb"))).collect();
    for (name, report) in validate(&validator, &files) {
        assert_valid(&name, &report);
        // The validator's own count of what the file draws matches the surfaces' table.
        let csv = std::fs::read_to_string(dir.join(name.replace(".glb", ".csv"))).expect("csv");
        let triangles: f64 = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(1).and_then(|v| v.parse::<f64>().ok()).expect("triangles"))
            .sum();
        let info = &report["info"];
        assert_eq!(info["totalTriangleCount"].as_f64(), Some(triangles), "{name}: {info}");
        let surfaces = csv.lines().count() - 1;
        assert_eq!(info["drawCallCount"].as_u64(), Some(surfaces as u64), "{name}: {info}");
    }
    // The nested surfaces are blended: translucency is part of what was validated.
    let glb = std::fs::read(dir.join("hydrogen.glb")).expect("glb");
    let json_len = u32::from_le_bytes(glb[12..16].try_into().expect("4 bytes")) as usize;
    let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).expect("JSON chunk");
    let modes: Vec<&str> =
        doc["materials"].as_array().expect("materials").iter().filter_map(|m| m["alphaMode"].as_str()).collect();
    assert_eq!(modes, ["BLEND", "BLEND", "OPAQUE"], "levels 0.01, 0.1 and 0.5");
}

#[test]
fn glb_files_with_no_surface_or_one_triangle_pass_the_khronos_validator() {
    let Some(validator) = validator() else { return };
    let triangle = WorldMesh {
        name: "value = 1".into(),
        positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        normals: vec![[0.0, 0.0, 1.0]; 3],
        colors: vec![[200, 100, 50, 255]; 3],
        triangles: vec![[0, 1, 2]],
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let files: Vec<PathBuf> =
        [("empty.glb", vec![]), ("only-empty.glb", vec![WorldMesh::default()]), ("triangle.glb", vec![triangle])]
            .into_iter()
            .map(|(name, meshes)| {
                let path = dir.path().join(name);
                std::fs::write(&path, to_glb(&meshes)).expect("write");
                path
            })
            .collect();
    for (name, report) in validate(&validator, &files) {
        assert_valid(&name, &report);
    }
}
