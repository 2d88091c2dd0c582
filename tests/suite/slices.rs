//! `kind = "slice"`: planes through a volume drawn as images. Pixels are checked against the
//! analytic fields the volumes sample, shapes against the known sections of a cube, contour
//! lines against circles of a radial field, and bad specs against their documented errors.

use crate::common::{Fixture, numbers, volume_npy};
use dataink::guide::color;
use dataink::mark::ChartOutput;
use dataink::scene::{Item, PathCmd, Raster, Role, Shape};

fn draw_one(chart: &str, spacing: &str, npy: &[u8]) -> Result<ChartOutput, String> {
    let spec = format!(
        "[data.field]\npath = \"field.npy\"\nspacing = {spacing}\n\n[[chart]]\nname = \"s\"\nkind = \"slice\"\ndata = \"field\"\ntitle = \"Slices\"\n{chart}"
    );
    Fixture::new(&spec, &[("field.npy", npy)]).draw().map(|mut v| v.remove(0))
}

fn images(out: &ChartOutput) -> Vec<(String, Raster)> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if item.role == Role::DataMark
            && let Shape::Image(r) = &item.shape
        {
            found.push((item.label.clone().unwrap_or_default(), r.clone()));
        }
    });
    found
}

fn pixel(r: &Raster, px: usize, py: usize) -> [u8; 4] {
    let at = (py * r.width as usize + px) * 4;
    [r.rgba[at], r.rgba[at + 1], r.rgba[at + 2], r.rgba[at + 3]]
}

#[test]
fn an_axial_slice_of_a_linear_field_shows_its_trilinear_values_with_spacing_kept() {
    // f = x + 2y + 3z in world units; spacing (1, 0.5, 2): z = 3 lies between voxel planes 1 and 2.
    let npy = volume_npy([5, 4, 6], |i, j, k| i + 2.0 * (0.5 * j) + 3.0 * (2.0 * k));
    let out = draw_one("at = [3.0]\nvalue = { scheme = \"viridis\", domain = [0, 60] }\n", "[1, 0.5, 2]", &npy)
        .unwrap_or_else(|e| panic!("{e}"));
    let shown = images(&out);
    assert_eq!(shown.len(), 1);
    let (label, r) = &shown[0];
    assert_eq!(label, "z = 3");
    // The slice spans x 0..4 and y 0..1.5: drawn 4 : 1.5, not squashed to the voxel counts.
    let aspect = r.dest.w / r.dest.h;
    assert!((aspect - 4.0 / 1.5).abs() < 0.02, "aspect {aspect}");
    let map = color::continuous("viridis").expect("viridis");
    for (px, py) in
        [(0, 0), (r.width as usize / 3, r.height as usize / 2), (r.width as usize - 1, r.height as usize - 1)]
    {
        let u = 4.0 * (px as f64 + 0.5) / r.width as f64;
        let v = 1.5 - 1.5 * (py as f64 + 0.5) / r.height as f64;
        let want = map.at((u + 2.0 * v + 9.0) / 60.0);
        let got = pixel(r, px, py);
        for (g, w) in got.iter().zip([want.r, want.g, want.b, 255]) {
            assert!((*g as i32 - w as i32).abs() <= 1, "pixel ({px}, {py}): {got:?} vs {want:?}");
        }
    }
    // The derived table names the plane and the range shown (pixel centres, inside the ends).
    assert_eq!(numbers(&out, "point_z"), vec![3.0]);
    assert_eq!(numbers(&out, "normal_z"), vec![1.0]);
    let (lo, hi) = (numbers(&out, "min")[0], numbers(&out, "max")[0]);
    assert!(lo > 9.0 && lo < 9.2 && hi < 16.0 && hi > 15.8, "{lo} {hi}");
}

#[test]
fn an_oblique_plane_through_a_cube_is_a_regular_hexagon_of_one_value() {
    // The plane x + y + z = 15 through the centre of the cube [0, 10]³ cuts a regular hexagon
    // standing on a vertex in the plane's (u, v) axes: it fills 3/4 of its bounding box, which
    // is √3 : 2, and f = x + y + z is 15 all over it.
    let npy = volume_npy([11, 11, 11], |i, j, k| i + j + k);
    let chart =
        "planes = [{ point = [5, 5, 5], normal = [1, 1, 1] }]\nvalue = { scheme = \"viridis\", domain = [0, 30] }\n";
    let out = draw_one(chart, "[1, 1, 1]", &npy).unwrap_or_else(|e| panic!("{e}"));
    let (_, r) = &images(&out)[0];
    assert!((r.dest.w / r.dest.h - 3f64.sqrt() / 2.0).abs() < 0.01, "{} × {}", r.dest.w, r.dest.h);
    let want = color::continuous("viridis").expect("viridis").at(0.5);
    let opaque: Vec<[u8; 4]> = r.rgba.chunks(4).filter(|p| p[3] > 0).map(|p| [p[0], p[1], p[2], p[3]]).collect();
    let fraction = opaque.len() as f64 / (r.width * r.height) as f64;
    assert!((fraction - 0.75).abs() < 0.02, "hexagon fills {fraction}");
    assert!(
        opaque.iter().all(|p| (p[0] as i32 - want.r as i32).abs() <= 1 && (p[1] as i32 - want.g as i32).abs() <= 1)
    );
    assert!(out.scene.title.is_some());
}

#[test]
fn contour_lines_of_a_radial_field_are_circles() {
    let npy = volume_npy([11, 11, 11], |i, j, k| ((i - 5.0).powi(2) + (j - 5.0).powi(2) + (k - 5.0).powi(2)).sqrt());
    let out = draw_one("at = [5]\ncontours = [3]\n", "[1, 1, 1]", &npy).unwrap_or_else(|e| panic!("{e}"));
    let (_, r) = &images(&out)[0];
    let scale = r.dest.w / 10.0;
    let mut radii = Vec::new();
    out.scene.walk(|item: &Item| {
        if item.label.as_deref() == Some("z = 5: value = 3")
            && let Shape::Path(cmds) = &item.shape
        {
            for cmd in cmds {
                if let PathCmd::MoveTo(p) | PathCmd::LineTo(p) = cmd {
                    let (u, v) = ((p.x - r.dest.x) / scale, 10.0 - (p.y - r.dest.y) / scale);
                    radii.push((u - 5.0).hypot(v - 5.0));
                }
            }
        }
    });
    assert!(radii.len() > 20, "{} points", radii.len());
    assert!(radii.iter().all(|d| (d - 3.0).abs() < 0.08), "{radii:?}");
}

#[test]
fn a_lightbox_puts_evenly_spaced_slices_on_voxel_planes() {
    let npy = volume_npy([4, 4, 10], |_, _, k| k);
    let out = draw_one("count = 3\nresample = \"nearest\"\n", "[1, 1, 1]", &npy).unwrap_or_else(|e| panic!("{e}"));
    // Thirds of 0..9 (nearest covers −0.5..9.5) are 1.17, 4.5, 7.83 → voxel planes 1, 5 (4.5
    // rounds away from zero), 8.
    assert_eq!(numbers(&out, "point_z"), vec![1.0, 5.0, 8.0]);
    let labels: Vec<String> = images(&out).into_iter().map(|(l, _)| l).collect();
    assert_eq!(labels, ["z = 1", "z = 5", "z = 8"]);
    // Nearest shows each slice's voxels exactly: min = max = the plane's value.
    assert_eq!(numbers(&out, "min"), vec![1.0, 5.0, 8.0]);
    assert_eq!(numbers(&out, "max"), vec![1.0, 5.0, 8.0]);
}

#[test]
fn bad_slice_specs_give_their_documented_errors() {
    let npy = volume_npy([4, 4, 10], |i, _, _| i);
    for (chart, message) in [
        ("at = [50]", "z = 50 misses the volume"),
        ("at = [50]", "the volume spans z from 0 to 9"),
        ("at = [1]\nplanes = [{ point = [0, 0, 0], normal = [0, 0, 1] }]", "`at` and `planes` are both given"),
        ("planes = [{ point = [0, 0, 0], normal = [0, 0, 0] }]", "has no direction"),
        ("planes = [{ point = [0, 0, 90], normal = [0, 1, 1] }]", "misses the volume"),
        ("count = 0", "0 slices asked for; a chart draws 1 to 64"),
        ("at = [1]\ncount = 2", "`at` and `count` are both given"),
        ("value = { domain = [5, 1] }", "must be `[min, max]` with min < max"),
        ("value = { scheme = \"rainbowz\" }", "unknown continuous colour scheme"),
    ] {
        let err = draw_one(chart, "[1, 1, 1]", &npy).expect_err(chart);
        assert!(err.contains(message), "{chart}: {err}");
    }
    // A table that is not a lattice of x, y, z and value is not a volume.
    let spec = "[data.t]\nvalues = [{ a = 1 }]\n\n[[chart]]\nname = \"s\"\nkind = \"slice\"\ndata = \"t\"\n";
    let err = Fixture::new(spec, &[]).draw().expect_err("not a volume");
    assert!(err.contains("data \"t\" is not a volume"), "{err}");
}

#[test]
fn missing_voxels_take_the_nan_colour_and_outside_is_transparent() {
    let npy = volume_npy([3, 3, 3], |i, _, _| if i == 2.0 { f64::NAN } else { i });
    let out = draw_one("at = [1]\nresample = \"nearest\"\nnan_color = \"#ff00ff\"\n", "[1, 1, 1]", &npy)
        .unwrap_or_else(|e| panic!("{e}"));
    let (_, r) = &images(&out)[0];
    assert_eq!(pixel(r, r.width as usize - 1, 0), [255, 0, 255, 255]);
    // An oblique plane's corners lie outside the cube: transparent, not a colour.
    let out = draw_one("planes = [{ point = [1, 1, 1], normal = [1, 1, 1] }]", "[1, 1, 1]", &npy)
        .unwrap_or_else(|e| panic!("{e}"));
    let (_, r) = &images(&out)[0];
    assert_eq!(pixel(r, 0, 0)[3], 0);
}

#[test]
fn between_spreads_a_lightbox_over_a_range_ends_included() {
    let npy = volume_npy([4, 4, 21], |_, _, k| k);
    // z runs 0..10 in steps of 0.5; 1.3 to 8.3 in thirds is 1.3, 3.63, 5.97, 8.3 → voxel planes.
    let out = draw_one("count = 4\nbetween = [1.3, 8.3]\n", "[1, 1, 0.5]", &npy).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(numbers(&out, "point_z"), vec![1.5, 3.5, 6.0, 8.5]);
    let err = draw_one("count = 4\nbetween = [2, 14]\n", "[1, 1, 0.5]", &npy).expect_err("beyond");
    assert!(err.contains("between [2, 14] reaches beyond the volume"), "{err}");
    assert!(err.contains("the volume spans z from 0 to 10"), "{err}");
    let err = draw_one("at = [1]\nbetween = [0, 5]\n", "[1, 1, 0.5]", &npy).expect_err("between with at");
    assert!(err.contains("`between` is given with `at`"), "{err}");
}

#[test]
fn the_readme_slice_example_draws_the_template_lint_clean() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let start = readme.find("[data.mni152]\npath = \"data/mni152-t1.nii.gz\"").expect("the README's slice example");
    let block = &readme[start..start + readme[start..].find("```").expect("end of block")];
    let nii = std::fs::read(root.join("examples/data/mni152-t1.nii.gz")).expect("the shipped template");
    let fx = Fixture::new(block, &[("data/mni152-t1.nii.gz", &nii)]);
    let out = fx.draw().unwrap_or_else(|e| panic!("{e}")).remove(0);
    let labels: Vec<String> = images(&out).into_iter().map(|(l, _)| l).collect();
    assert_eq!(labels.len(), 12);
    assert_eq!((labels[0].as_str(), labels[11].as_str()), ("z = −45", "z = 75"));
    // 1 mm voxels from z = -72: every slice on the voxel plane nearest -45 + k · 120 / 11.
    let z = numbers(&out, "point_z");
    assert!(z.iter().all(|z| z.fract() == 0.0), "{z:?}");
    assert!(z.iter().enumerate().all(|(k, z)| (z - (-45.0 + k as f64 * 120.0 / 11.0)).abs() <= 0.5), "{z:?}");
    let lint = fx.lint().unwrap_or_else(|e| panic!("{e}"));
    assert!(lint[0].findings.is_empty(), "{:?}", lint[0].findings);
}

#[test]
fn lint_reads_a_slice_charts_colours() {
    let npy = volume_npy([4, 4, 4], |i, j, k| i + j + k);
    let spec = |value: &str| {
        format!(
            "[data.field]\npath = \"field.npy\"\n\n[[chart]]\nname = \"s\"\nkind = \"slice\"\ndata = \"field\"\ntitle = \"Slices\"\nvalue = {value}\n"
        )
    };
    let files: &[(&str, &[u8])] = &[("field.npy", &npy)];
    assert_eq!(crate::common::lint_codes(&spec("{ title = \"f\" }"), files), Vec::<&str>::new());
    assert!(crate::common::lint_codes(&spec("{ scheme = \"rainbow\" }"), files).contains(&"CL001"));
    assert!(crate::common::lint_codes(&spec("{ legend = false }"), files).contains(&"SC004"));
}
