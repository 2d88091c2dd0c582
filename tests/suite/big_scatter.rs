//! Scatters above the vector limit: the SVG carries the point layer as one embedded raster drawn
//! by the PNG renderer's blitter, with axes and text still vectors.

use crate::common::{Fixture, assert_svg_parses};
use dataink::mark::ChartOutput;
use dataink::render::{self, svg::POINT_RASTER_SCALE};
use dataink::scene::{Item, PointBatch, Scene, Shape};

/// `n` seeded points in two overlapping clouds, as CSV.
fn points_csv(n: usize) -> String {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut csv = String::from("x,y\n");
    for i in 0..n {
        let (u, v) = (next(), next());
        let c = if i % 2 == 0 { 0.0 } else { 3.0 };
        csv.push_str(&format!("{:.4},{:.4}\n", c + 4.0 * u * u, v * (1.0 + u)));
    }
    csv
}

fn scatter(n: usize) -> ChartOutput {
    let spec = "[data.p]\npath = \"p.csv\"\n[[chart]]\nname = \"big\"\nkind = \"scatter\"\ndata = \"p\"\ntitle = \"Points\"\nx = \"x\"\ny = \"y\"\n";
    let csv = points_csv(n);
    Fixture::new(spec, &[("p.csv", csv.as_bytes())]).draw().unwrap_or_else(|e| panic!("{e}")).remove(0)
}

/// The scene without its point batches.
fn without_points(scene: &Scene) -> Scene {
    fn strip(items: &[Item]) -> Vec<Item> {
        items
            .iter()
            .filter(|i| !matches!(i.shape, Shape::Points(_)))
            .map(|i| match &i.shape {
                Shape::Group { items, clip } => {
                    Item { shape: Shape::Group { items: strip(items), clip: *clip }, ..i.clone() }
                }
                _ => i.clone(),
            })
            .collect()
    }
    Scene { items: strip(&scene.items), ..scene.clone() }
}

/// The first embedded image of a parsed SVG: its top-left corner and its PNG bytes.
fn embedded_png(group: &usvg::Group) -> Option<((f32, f32), Vec<u8>)> {
    for node in group.children() {
        match node {
            usvg::Node::Image(image) => {
                if let usvg::ImageKind::PNG(data) = image.kind() {
                    let b = image.abs_bounding_box();
                    return Some(((b.x(), b.y()), data.to_vec()));
                }
            }
            usvg::Node::Group(g) => {
                if let Some(found) = embedded_png(g) {
                    return Some(found);
                }
            }
            _ => {}
        }
    }
    None
}

#[test]
fn a_big_scatter_embeds_its_points_as_one_raster_in_the_svg() {
    let n = 200_000;
    let out = scatter(n);
    assert!(
        out.warnings.iter().any(|w| w.to_string().contains("200000 points drawn as an embedded raster in the SVG")),
        "{:?}",
        out.warnings
    );
    let svg = render::to_svg(&out.scene);
    // One `<circle>` per point would take about 11 MB here (57.7 MB for a million); the raster
    // of these noisy clouds takes 1.8 MB.
    assert!(svg.len() < 2_500_000, "{} bytes", svg.len());
    assert_eq!(svg.matches("<image").count(), 1);
    assert_eq!(svg.matches("<circle").count(), 0);
    assert!(svg.contains("<text"), "axes and titles stay text");
    assert_svg_parses(&svg);

    // What the raster shows is what the PNG shows: the raster laid over the chart drawn without
    // its points gives the chart drawn with them. Not within the golden tolerance: the points
    // (opacity 0.35 here) pile up on a transparent layer, whose 8-bit premultiplied channels
    // keep fewer levels than the same pile on the opaque white plot, so deep piles round
    // differently (measured: at most 12/255).
    let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).unwrap();
    let ((x, y), png_bytes) = embedded_png(tree.root()).expect("an embedded PNG");
    let decoder = png::Decoder::new(std::io::Cursor::new(png_bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut raster = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut raster).unwrap();
    let s = POINT_RASTER_SCALE;
    let full = render::to_pixmap(&out.scene, s).unwrap();
    let base = render::to_pixmap(&without_points(&out.scene), s).unwrap();
    let (x0, y0) = ((f64::from(x) * s).round() as usize, (f64::from(y) * s).round() as usize);
    let width = full.width() as usize;
    let (mut worst, mut differing, mut inked, mut total) = (0u8, 0usize, 0usize, 0u64);
    for row in 0..info.height as usize {
        for col in 0..info.width as usize {
            let src = &raster[(row * info.width as usize + col) * 4..][..4];
            let at = ((y0 + row) * width + x0 + col) * 4;
            let (dst, want) = (&base.data()[at..at + 4], &full.data()[at..at + 4]);
            let a = f64::from(src[3]) / 255.0;
            inked += usize::from(src[3] > 0);
            let mut off = false;
            for k in 0..3 {
                let got = (f64::from(src[k]) * a + f64::from(dst[k]) * (1.0 - a)).round() as i32;
                let d = (got - i32::from(want[k])).unsigned_abs() as u8;
                worst = worst.max(d);
                total += u64::from(d);
                off |= d > 1;
            }
            differing += usize::from(off);
        }
    }
    assert!(inked > 10_000, "the raster holds the points: {inked} inked pixels");
    let mean = total as f64 / (3.0 * f64::from(info.width) * f64::from(info.height));
    assert!(
        worst <= 16 && mean < 1.5,
        "largest channel difference {worst}/255, mean {mean:.2}, {differing} pixels off by more than 1"
    );
}

#[test]
fn scatters_up_to_the_limit_stay_vector() {
    let out = scatter(1_000);
    assert!(out.warnings.iter().all(|w| !w.to_string().contains("embedded raster")), "{:?}", out.warnings);
    let svg = render::to_svg(&out.scene);
    assert_eq!(svg.matches("<image").count(), 0);
    assert_eq!(svg.matches("<circle").count(), 1_000);
    assert_eq!(PointBatch::VECTOR_LIMIT, 100_000, "the documented limit");
}
