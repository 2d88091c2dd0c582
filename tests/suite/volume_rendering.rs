//! `kind = "volume"`: ray-cast images of a volume. The maximum intensity projection is checked
//! against the volume's maximum, the mean along each ray against the maximum along the same ray,
//! compositing against opacity and its transparent surroundings, and bad specs against their
//! documented errors.

use crate::common::{Fixture, numbers, volume_npy};
use dataink::mark::ChartOutput;
use dataink::scene::{Item, Raster, Role, Shape};

fn draw(chart: &str, npy: &[u8]) -> Result<ChartOutput, String> {
    let spec = format!(
        "[data.field]\npath = \"field.npy\"\nspacing = [1, 1, 2]\n\n[[chart]]\nname = \"v\"\nkind = \"volume\"\ndata = \"field\"\ntitle = \"Rays\"\n{chart}"
    );
    Fixture::new(&spec, &[("field.npy", npy)]).draw().map(|mut v| v.remove(0))
}

fn image(out: &ChartOutput) -> Raster {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if item.role == Role::DataMark
            && let Shape::Image(r) = &item.shape
        {
            found.push(r.clone());
        }
    });
    assert_eq!(found.len(), 1, "one image");
    found.remove(0)
}

/// A smooth blob: largest (10) at (8, 6, 5), falling off with distance.
fn blob(i: f64, j: f64, k: f64) -> f64 {
    10.0 * (-((i - 8.0).powi(2) + (j - 6.0).powi(2) + (k - 5.0).powi(2)) / 18.0).exp()
}

#[test]
fn the_mean_along_a_ray_never_exceeds_its_maximum() {
    let npy = volume_npy([16, 13, 11], blob);
    let mip_out = draw("mode = \"mip\"\nresolution = 64\n", &npy).unwrap_or_else(|e| panic!("{e}"));
    let mean_out = draw("mode = \"average\"\nresolution = 64\n", &npy).unwrap_or_else(|e| panic!("{e}"));
    let (mip, mean) = (image(&mip_out), image(&mean_out));
    assert_eq!((mip.width, mip.height), (64, 64));
    let hit = mip.rgba.chunks(4).zip(mean.rgba.chunks(4)).filter(|(a, b)| {
        assert_eq!(a[3], b[3], "the same rays meet the volume");
        a[3] == 255
    });
    assert!(hit.count() > 64 * 64 / 4, "rays meet the box");
    // Rays beside the box are transparent.
    assert_eq!(&mip.rgba[..4], &[0, 0, 0, 0]);
    // Each colour bar spans the values its rays found (the CSV gives its ends). The ray nearest
    // the peak (10) comes close to it; no mean exceeds the largest maximum, and the smallest
    // mean is at most the smallest maximum (the ray with that maximum has a smaller mean).
    let (max_ends, mean_ends) = (numbers(&mip_out, "value"), numbers(&mean_out, "value"));
    assert!(max_ends[1] <= 10.0 + 1e-9 && max_ends[1] > 9.0, "{max_ends:?}");
    assert!(mean_ends[1] < max_ends[1] && mean_ends[0] <= max_ends[0], "{mean_ends:?} vs {max_ends:?}");
}

#[test]
fn compositing_shows_the_opaque_core_and_clears_the_transparent_rest() {
    let npy = volume_npy([16, 13, 11], blob);
    // Only values above 5 are opaque: the core of the blob. Rays missing it stay clear.
    let out =
        draw("opacity = [[5, 0], [6, 1]]\nresolution = 48\nshade = false\n", &npy).unwrap_or_else(|e| panic!("{e}"));
    let img = image(&out);
    let alphas: Vec<u8> = img.rgba.chunks(4).map(|p| p[3]).collect();
    let opaque = alphas.iter().filter(|&&a| a == 255).count();
    let clear = alphas.iter().filter(|&&a| a == 0).count();
    assert!(opaque > 20 && clear > opaque, "{opaque} opaque, {clear} clear of {}", alphas.len());
    // The derived table lists the transfer function.
    assert_eq!(numbers(&out, "value"), [5.0, 6.0]);
    assert_eq!(numbers(&out, "opacity"), [0.0, 1.0]);
    let caption = caption(&out);
    assert!(caption.starts_with("ray casting: 48 × 48 rays, a sample every 0.5 voxel"), "{caption}");
    // Classifying before interpolation draws the same core.
    let before = image(&draw("opacity = [[5, 0], [6, 1]]\nresolution = 48\nclassify = \"before\"\n", &npy).unwrap());
    let half = |r: &Raster| r.rgba.chunks(4).filter(|p| p[3] > 127).count();
    let (after, before) = (half(&img), half(&before));
    assert!(before.abs_diff(after) <= after / 5, "{before} vs {after}");
}

fn caption(out: &ChartOutput) -> String {
    let mut found = String::new();
    out.scene.walk(|item: &Item| {
        if let Shape::Text(t) = &item.shape
            && item.role == Role::Caption
        {
            found = t.content.clone();
        }
    });
    found
}

#[test]
fn bad_volume_specs_give_their_documented_errors() {
    let npy = volume_npy([4, 4, 4], |i, j, k| i + j + k);
    for (chart, message) in [
        ("step = 0", "step 0 is not in 0.05 to 4 voxels"),
        ("resolution = 4", "resolution 4 is not in 16 to 2048"),
        ("opacity = []", "no opacity control points"),
        ("opacity = [[2, 0.1], [1, 0.5]]", "must rise in value: 1 comes after 2"),
        ("opacity = [[1, 2]]", "needs a finite value and an opacity from 0 to 1"),
        ("mode = \"xray\"", "unknown mode `xray`"),
        ("scheme = \"nope\"", "nope"),
    ] {
        let err = draw(chart, &npy).map(|_| ()).expect_err(chart);
        assert!(err.contains(message), "{chart}: wants {message:?}\n{err}");
    }
    let thin = volume_npy([4, 1, 4], |i, _, k| i + k);
    let err = draw("", &thin).map(|_| ()).expect_err("one voxel thick");
    assert!(err.contains("rays need at least two voxels along y"), "{err}");
}

#[test]
fn the_readme_volume_examples_draw_the_template_lint_clean() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let start = readme
        .find("[data.mni152]\npath = \"data/mni152-t1.nii.gz\"\n\n[[chart]]\nname = \"mni152-volume\"")
        .expect("the README's volume example");
    let block = &readme[start..start + readme[start..].find("```").expect("end of block")];
    let nii = std::fs::read(root.join("examples/data/mni152-t1.nii.gz")).expect("the shipped template");
    let fx = Fixture::new(block, &[("data/mni152-t1.nii.gz", &nii)]);
    let outs = fx.draw().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(outs.len(), 2);
    for out in &outs {
        let img = image(out);
        assert!(img.rgba.chunks(4).filter(|p| p[3] > 0).count() > (img.width * img.height / 8) as usize);
    }
    let lint = fx.lint().unwrap_or_else(|e| panic!("{e}"));
    assert!(lint.iter().all(|l| l.findings.is_empty()), "{:?}", lint.iter().map(|l| &l.findings).collect::<Vec<_>>());
}
