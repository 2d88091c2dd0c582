//! `kind = "volume"`: ray-cast images of a volume. The maximum intensity projection is checked
//! against the volume's maximum, the mean along each ray against the maximum along the same ray,
//! compositing against opacity and its transparent surroundings, and bad specs against their
//! documented errors.

use crate::common::{Fixture, lint_codes, lint_findings, numbers, texts, volume_npy};
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
        ("mode = \"mip\"\nopacity = [[1, 0.5]]", "`opacity` applies to mode = \"composite\""),
        ("mode = \"average\"\ngradient_opacity = true", "`gradient_opacity` applies to mode = \"composite\""),
        ("labels = []", "no labels"),
        ("labels = [{ value = 1 }]\nopacity = [[1, 0.5]]", "`opacity` does not go with `labels`"),
        ("labels = [{ value = 1 }]\nclassify = \"after\"", "`classify` does not go with `labels`"),
        ("labels = [{ value = 1 }, { value = 1 }]", "label 1 is listed twice"),
        ("labels = [{ value = 1, color = \"nope\" }]", "`nope` is not a colour"),
        ("labels = [{ value = 1, opacity = 3 }]", "label 1 has opacity 3"),
        (
            "renderer = \"shear-warp\"\nprojection = \"perspective\"",
            "`projection` does not go with renderer = \"shear-warp\"",
        ),
        ("renderer = \"shear-warp\"\nclassify = \"after\"", "`classify` does not go with renderer = \"shear-warp\""),
        ("renderer = \"shear-warp\"\nstep = 0.25", "`step` does not go with renderer = \"shear-warp\""),
        ("mode = \"mip\"\nrenderer = \"shear-warp\"", "`renderer` applies to mode = \"composite\""),
        ("renderer = \"splatting\"", "unknown renderer `splatting`"),
        // i + j + k has whole numbers only, but the blob does not: see below.
    ] {
        let err = draw(chart, &npy).map(|_| ()).expect_err(chart);
        assert!(err.contains(message), "{chart}: wants {message:?}\n{err}");
    }
    let err = draw("labels = [{ value = 1 }]", &volume_npy([4, 4, 4], blob)).map(|_| ()).expect_err("not labels");
    assert!(err.contains("not a whole number: labels need a segmentation"), "{err}");
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

/// The legend items of a chart: (texts, circles, rectangles).
fn legend_parts(out: &ChartOutput) -> (Vec<String>, usize, usize) {
    let (mut texts, mut circles, mut rects) = (Vec::new(), 0, 0);
    out.scene.walk(|item: &Item| {
        if item.role != Role::Legend {
            return;
        }
        match &item.shape {
            Shape::Text(t) => texts.push(t.content.clone()),
            Shape::Circle { .. } => circles += 1,
            Shape::Rect(_) => rects += 1,
            _ => {}
        }
    });
    (texts, circles, rects)
}

#[test]
fn the_legend_draws_the_transfer_function_over_the_histogram() {
    let npy = volume_npy([16, 13, 11], blob);
    let out = draw("opacity = [[2, 0], [5, 0.4], [8, 0.9]]\nresolution = 32\n", &npy).unwrap();
    let (texts, circles, rects) = legend_parts(&out);
    // A dot per control point; the opacity axis under the panel; histogram bars beside the
    // ramp and panel frames.
    assert_eq!(circles, 3, "{texts:?}");
    assert!(texts.iter().any(|t| t == "opacity"), "{texts:?}");
    assert!(rects > 10, "{rects} rectangles: the histogram's bars");
    // The value axis reaches the data's range (0 to 10), beyond the control points.
    assert!(texts.iter().any(|t| t == "10") && texts.iter().any(|t| t == "0"), "{texts:?}");
    // Without the legend: no legend items, and lint rule SC006 says so.
    let bare = draw("opacity = [[2, 0], [5, 0.4], [8, 0.9]]\nresolution = 32\nlegend = false\n", &npy).unwrap();
    assert_eq!(legend_parts(&bare), (Vec::new(), 0, 0));
    let spec = |extra: &str| {
        format!(
            "[data.field]\npath = \"field.npy\"\n\n[[chart]]\nname = \"v\"\nkind = \"volume\"\ndata = \"field\"\n\
             title = \"Rays\"\nresolution = 32\n{extra}"
        )
    };
    let files: &[(&str, &[u8])] = &[("field.npy", &npy)];
    let found = lint_findings(&spec("legend = false\n"), files, "SC006");
    assert_eq!(found.len(), 1);
    assert!(found[0].message.contains("no legend shows which values are which colour"), "{}", found[0].message);
    assert!(!lint_codes(&spec(""), files).contains(&"SC006"));
}

#[test]
fn lint_reports_a_transfer_function_that_shows_almost_nothing_or_almost_everything() {
    // Values 0 to 10 (the blob); 16·13·11 = 2288 voxels.
    let npy = volume_npy([16, 13, 11], blob);
    let spec = |opacity: &str| {
        format!(
            "[data.field]\npath = \"field.npy\"\n\n[[chart]]\nname = \"v\"\nkind = \"volume\"\ndata = \"field\"\n\
             title = \"Rays\"\nresolution = 32\nopacity = {opacity}\n"
        )
    };
    let files: &[(&str, &[u8])] = &[("field.npy", &npy)];
    // Opaque only above 9.99: one voxel at most (the peak is 10 at one voxel) — under 0.1%.
    let blank = lint_findings(&spec("[[9.99, 0], [10, 1]]"), files, "TQ006");
    assert_eq!(blank.len(), 1, "{blank:?}");
    assert!(blank[0].message.contains("nearly blank"), "{}", blank[0].message);
    // A floor of 0.1 everywhere: every voxel shown — a fog.
    let fog = lint_findings(&spec("[[0, 0.1], [10, 0.5]]"), files, "TQ006");
    assert_eq!(fog.len(), 1);
    assert!(fog[0].message.contains("shows 100% of the voxels"), "{}", fog[0].message);
    // Half the range clear: neither.
    assert!(!lint_codes(&spec("[[4, 0], [10, 0.5]]"), files).contains(&"TQ006"));
    // A rainbow scheme on the transfer function: CL001.
    let rainbow = format!("{}scheme = \"turbo\"\n", spec("[[4, 0], [10, 0.5]]"));
    assert!(lint_codes(&rainbow, files).contains(&"CL001"));
}

#[test]
fn gradient_opacity_fades_uniform_regions_and_keeps_boundaries() {
    // A cube of value 1 inside a volume of 0: uniform inside, a sharp boundary at its faces.
    let inside = |v: f64| (4.0..=11.0).contains(&v);
    let cube = |i: f64, j: f64, k: f64| f64::from(u8::from(inside(i) && inside(j) && inside(k)));
    let npy = volume_npy([16, 16, 16], cube);
    let chart = "opacity = [[0.5, 0], [0.6, 0.3]]\nresolution = 48\nshade = false\nazimuth = 0\nelevation = 0\n";
    let plain = image(&draw(chart, &npy).unwrap());
    let scaled_out = draw(&format!("{chart}gradient_opacity = true\n"), &npy).unwrap();
    let scaled = image(&scaled_out);
    let alpha = |r: &Raster, x: u32, y: u32| r.rgba[((y * r.width + x) * 4 + 3) as usize];
    // Through the middle of the cube, the plain ray crosses 7 voxels of opacity 0.3: nearly
    // opaque. With gradient opacity the inside is uniform and only the two faces count.
    let mid = 24;
    assert!(alpha(&plain, mid, mid) > 200, "{}", alpha(&plain, mid, mid));
    assert!(alpha(&scaled, mid, mid) < alpha(&plain, mid, mid) / 2, "{}", alpha(&scaled, mid, mid));
    assert!(alpha(&scaled, mid, mid) > 0, "the faces remain");
    assert_eq!(alpha(&scaled, 0, 0), 0);
    assert!(caption(&scaled_out).contains("opacity scaled by the gradient magnitude"), "{}", caption(&scaled_out));
}

#[test]
fn label_volumes_show_listed_labels_in_their_colours() {
    // Three labels in slabs along x: 1 (x < 5), 2 (5 ≤ x < 10), 3 (x ≥ 10); 0 outside y 3..12.
    let seg = |i: f64, j: f64, _k: f64| {
        if !(3.0..=12.0).contains(&j) {
            0.0
        } else if i < 5.0 {
            1.0
        } else if i < 10.0 {
            2.0
        } else {
            3.0
        }
    };
    let npy = volume_npy([15, 16, 8], seg);
    let out = draw(
        "labels = [{ value = 2, name = \"grey matter\", color = \"#ff0000\" }, { value = 3, name = \"white matter\", color = \"#0000ff\", opacity = 0.5 }]\n\
         resolution = 64\nshade = false\nazimuth = -90\nelevation = 90\n",
        &npy,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    // Seen from above, x runs left to right: label 1 (unlisted) clear, 2 red, 3 blue.
    let img = image(&out);
    let colours: Vec<[u8; 4]> = img.rgba.chunks(4).map(|p| [p[0], p[1], p[2], p[3]]).collect();
    let red = colours.iter().filter(|p| p[3] == 255 && p[0] > 240 && p[2] < 15).count();
    let blue = colours.iter().filter(|p| p[3] > 200 && p[2] > 240 && p[0] < 15).count();
    let clear = colours.iter().filter(|p| p[3] == 0).count();
    assert!(red > 300 && blue > 300 && clear > 300, "red {red}, blue {blue}, clear {clear}");
    assert!(!colours.iter().any(|p| p[3] > 0 && p[1] > 60), "no colour but the labels'");
    // The legend names the labels; the derived table lists them.
    let (legend, _, _) = legend_parts(&out);
    assert_eq!(legend, ["label", "grey matter", "white matter"]);
    assert_eq!(numbers(&out, "value"), [2.0, 3.0]);
    assert_eq!(texts(&out, "name"), ["grey matter", "white matter"]);
    assert_eq!(numbers(&out, "opacity"), [1.0, 0.5]);
}

#[test]
fn the_readme_label_volume_example_draws_its_labels_lint_clean() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let start =
        readme.find("[data.phantom]\npath = \"data/shepp-logan-labels.npy.gz\"").expect("the README's label example");
    let block = &readme[start..start + readme[start..].find("```").expect("end of block")];
    let labels = std::fs::read(root.join("examples/data/shepp-logan-labels.npy.gz")).expect("the shipped phantom");
    let fx = Fixture::new(block, &[("data/shepp-logan-labels.npy.gz", &labels)]);
    let out = fx.draw().unwrap_or_else(|e| panic!("{e}")).remove(0);
    let (legend, _, _) = legend_parts(&out);
    assert_eq!(legend, ["label", "brain", "ventricle, right", "ventricle, left", "large tumour", "small tumours"]);
    let img = image(&out);
    assert!(img.rgba.chunks(4).filter(|p| p[3] > 0).count() > (img.width * img.height / 8) as usize);
    let lint = fx.lint().unwrap_or_else(|e| panic!("{e}"));
    assert!(lint.iter().all(|l| l.findings.is_empty()), "{:?}", lint.iter().map(|l| &l.findings).collect::<Vec<_>>());
}

#[test]
fn shear_warp_draws_the_image_ray_casting_draws() {
    // The blob seen obliquely, shaded: shear-warp against ray casting classified at the voxels
    // with a fine step, pixel by pixel over the image.
    let npy = volume_npy([16, 13, 11], blob);
    let chart = "opacity = [[2, 0], [5, 0.3], [10, 0.8]]\nresolution = 64\nazimuth = 25\nelevation = 35\n";
    let sw_out = draw(&format!("{chart}renderer = \"shear-warp\"\n"), &npy).unwrap_or_else(|e| panic!("{e}"));
    let rc = image(&draw(&format!("{chart}classify = \"before\"\nstep = 0.1\n"), &npy).unwrap());
    let sw = image(&sw_out);
    assert_eq!((sw.width, sw.height), (64, 64));
    let (mut shown, mut total, mut worst) = (0usize, 0u64, 0u8);
    for (a, b) in sw.rgba.chunks(4).zip(rc.rgba.chunks(4)) {
        if a[3] > 0 || b[3] > 0 {
            shown += 1;
            // Compare premultiplied channels: straight colour under low opacity means little.
            for c in 0..3 {
                let (x, y) = (u16::from(a[c]) * u16::from(a[3]) / 255, u16::from(b[c]) * u16::from(b[3]) / 255);
                let d = x.abs_diff(y) as u8;
                worst = worst.max(d);
                total += u64::from(d);
            }
            let d = a[3].abs_diff(b[3]);
            worst = worst.max(d);
            total += u64::from(d);
        }
    }
    let mean = total as f64 / (shown * 4) as f64;
    assert!(shown > 64 * 64 / 5, "{shown} pixels show the blob");
    // Measured: mean 2.1 levels, worst 26 on this coarse 16 × 13 × 11 volume (samples on the
    // voxel slices rather than every 0.1 voxel, opacity corrected and shaded at the voxels).
    assert!(mean < 3.0 && worst < 40, "mean {mean} levels, worst {worst}");
    assert!(caption(&sw_out).starts_with("shear-warp: 64 × 64 pixels, a sample per voxel"), "{}", caption(&sw_out));
}
