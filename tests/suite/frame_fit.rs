//! How the drawing fills its canvas: `aspect = "equal"` in the shared x/y frame, and the kinds
//! that lay out their own panels (surface, segments, the link matrix) using the room they have.

use crate::common::Fixture;
use dataink::data::PathPolicy;
use dataink::mark::ChartOutput;
use dataink::pipeline;
use dataink::scene::{PathCmd, Point, Rect, Role, Shape};

/// Three points at (0, 0), (10, 0) and (0, 2): nice domains 0..10 and 0..2.
fn scatter(extra: &str) -> ChartOutput {
    let spec = format!(
        "[data.d]\nvalues = [{{ x = 0, y = 0 }}, {{ x = 10, y = 0 }}, {{ x = 0, y = 2 }}]\n[[chart]]\nname = \"s\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\nsize = [640, 420]\n{extra}"
    );
    Fixture::new(&spec, &[]).draw().unwrap_or_else(|e| panic!("{e}")).remove(0)
}

/// The point centres and the plot (the data group's clip).
fn points_and_plot(out: &ChartOutput) -> (Vec<Point>, Rect) {
    let (mut centers, mut plot) = (Vec::new(), None);
    out.scene.walk(|item| match &item.shape {
        Shape::Points(batch) => centers.extend(batch.centers.iter().copied()),
        Shape::Group { clip: Some(clip), .. } if item.role == Role::DataMark => plot = Some(*clip),
        _ => {}
    });
    (centers, plot.expect("a clipped data group"))
}

#[test]
fn equal_aspect_gives_one_unit_the_same_length_on_both_axes() {
    let (c, plot) = points_and_plot(&scatter("aspect = \"equal\"\n"));
    let per_x = (c[1].x - c[0].x) / 10.0;
    let per_y = (c[0].y - c[2].y) / 2.0;
    assert!((per_x - per_y).abs() < 1e-9, "{per_x} px per unit on x, {per_y} on y");
    // Ten units across, two up: the plot is five times as wide as it is tall (plus the insets
    // that keep the markers off the edges, 3.5 + 1 px at both ends of each axis).
    assert!(((plot.w - 9.0) - 5.0 * (plot.h - 9.0)).abs() < 1e-9, "{plot:?}");

    // Without the key (or with `auto`) the plot fills the frame as before.
    let (c, auto) = points_and_plot(&scatter(""));
    assert_eq!(auto, Rect::new(63.0, 21.0, 560.0, 339.0));
    assert_eq!(points_and_plot(&scatter("aspect = \"auto\"\n")).1, auto);
    assert!((c[1].x - c[0].x) / 10.0 < (c[0].y - c[2].y) / 2.0, "auto stretches y");
    // The equal plot is the auto one shrunk in height and centred in it.
    assert_eq!((plot.x, plot.w), (auto.x, auto.w));
    assert!(((plot.y + plot.h / 2.0) - (auto.y + auto.h / 2.0)).abs() <= 0.5, "{plot:?} in {auto:?}");
}

#[test]
fn equal_aspect_needs_linear_axes() {
    let spec = "[data.d]\nvalues = [{ x = 1, y = 1 }, { x = 100, y = 2 }]\n[[chart]]\nname = \"s\"\nkind = \"scatter\"\ndata = \"d\"\nx = { field = \"x\", scale = \"log\" }\ny = \"y\"\naspect = \"equal\"\n";
    let err = Fixture::new(spec, &[]).draw().err().expect("an error");
    assert!(err.contains("`aspect = \"equal\"` needs two linear axes"), "{err}");
}

#[test]
fn equal_aspect_is_refused_where_it_is_not_applied() {
    let spec = "[data.d]\nvalues = [{ x = 1, y = 1, z = 1 }]\n[[chart]]\nname = \"s\"\nkind = \"parallel\"\ndata = \"d\"\ncolumns = [\"x\", \"y\", \"z\"]\naspect = \"equal\"\n";
    let err = Fixture::new(spec, &[]).draw().err().expect("an error");
    assert!(err.contains("`aspect = \"equal\"` is not applied by `parallel` charts"), "{err}");
}

/// The share of the canvas covered by the bounding box of a scene's data marks.
fn data_coverage(out: &ChartOutput) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let mut add = |p: Point| {
        (lo[0], lo[1]) = (lo[0].min(p.x), lo[1].min(p.y));
        (hi[0], hi[1]) = (hi[0].max(p.x), hi[1].max(p.y));
    };
    out.scene.walk(|item| {
        if item.role != Role::DataMark {
            return;
        }
        match &item.shape {
            Shape::Rect(r) => {
                add(Point::new(r.x, r.y));
                add(Point::new(r.right(), r.bottom()));
            }
            Shape::Image(r) => {
                add(Point::new(r.dest.x, r.dest.y));
                add(Point::new(r.dest.right(), r.dest.bottom()));
            }
            Shape::Path(cmds) => {
                for c in cmds {
                    if let PathCmd::MoveTo(p) | PathCmd::LineTo(p) = c {
                        add(*p);
                    }
                }
            }
            Shape::Mesh(mesh) => {
                if let Some(r) = mesh.bounds() {
                    add(Point::new(r.x, r.y));
                    add(Point::new(r.right(), r.bottom()));
                }
            }
            _ => {}
        }
    });
    (hi[0] - lo[0]) * (hi[1] - lo[1]) / (out.scene.width * out.scene.height)
}

fn gallery_chart(name: &str) -> ChartOutput {
    let loaded = pipeline::load(&crate::common::root().join("examples/gallery.toml"), PathPolicy::InsideSpecFolder)
        .unwrap_or_else(|f| panic!("{}", f.render()));
    let (i, chart) = loaded.spec.chart.iter().enumerate().find(|(_, c)| c.name == name).expect("a gallery chart");
    pipeline::draw_chart(&loaded, i, chart).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn panel_kinds_fit_their_drawing_to_the_canvas() {
    // Share of the canvas under the data marks' bounding box. Fitted: 0.319, 0.326 and 0.625;
    // before, read off the PNGs: about 0.21 (the box in a square), 0.30 (108 px kept for labels
    // either side) and 0.54 (whole-pixel cells on the 760 px default canvas).
    for (name, at_least) in [("surface-franke", 0.31), ("grid-segments", 0.32), ("flights-matrix", 0.61)] {
        let covered = data_coverage(&gallery_chart(name));
        assert!(covered >= at_least, "{name}: the data covers {covered:.3} of the canvas");
    }
}
