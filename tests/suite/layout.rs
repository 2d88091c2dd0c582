//! Layout invariants of every gallery chart: text stays on the canvas, no two texts overlap, every
//! chart has a title, axis titles and tick labels, and colour encodings get a legend.

use dataink::data::PathPolicy;
use dataink::pipeline;
use dataink::scene::{Rect, Role, Scene, Shape};
use dataink::text::{bounds, texts_overlap};

/// Every gallery chart: its name, its kind and its scene.
fn gallery_scenes() -> Vec<(String, &'static str, Scene)> {
    let loaded = pipeline::load(&crate::common::root().join("examples/gallery.toml"), PathPolicy::InsideSpecFolder)
        .unwrap_or_else(|f| panic!("{}", f.render()));
    loaded
        .spec
        .chart
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let out = pipeline::draw_chart(&loaded, i, c).unwrap_or_else(|e| panic!("{e}"));
            (c.name.clone(), c.kind.name(), out.scene)
        })
        .collect()
}

fn texts(scene: &Scene) -> Vec<(Role, String, Rect)> {
    let mut out = Vec::new();
    scene.walk(|item| {
        if let Shape::Text(t) = &item.shape {
            out.push((item.role, t.content.clone(), bounds(t)));
        }
    });
    out
}

#[test]
fn text_stays_inside_the_canvas() {
    for (name, _, scene) in gallery_scenes() {
        let canvas = Rect::new(0.0, 0.0, scene.width, scene.height);
        for (role, content, b) in texts(&scene) {
            assert!(canvas.contains_rect(&b, 0.5), "{name}: {role:?} `{content}` at {b:?} leaves the canvas");
        }
    }
}

#[test]
fn no_two_texts_overlap() {
    for (name, _, scene) in gallery_scenes() {
        let mut all = Vec::new();
        scene.walk(|item| {
            if let Shape::Text(t) = &item.shape {
                all.push((item.role, t));
            }
        });
        for (i, (ra, a)) in all.iter().enumerate() {
            for (rb, b) in &all[i + 1..] {
                // Glyph boxes shrunk by half a pixel, turned text by its turned box: touching
                // boxes are fine, overlapping ink is not.
                assert!(
                    !texts_overlap(a, b),
                    "{name}: {ra:?} `{}` {:?} overlaps {rb:?} `{}` {:?}",
                    a.content,
                    bounds(a),
                    b.content,
                    bounds(b)
                );
            }
        }
    }
}

#[test]
fn every_chart_is_labelled() {
    for (name, kind, scene) in gallery_scenes() {
        let all = texts(&scene);
        let count = |role: Role| all.iter().filter(|(r, _, _)| *r == role).count();
        assert_eq!(count(Role::Title), 1, "{name} has a title");
        if kind == "faces" {
            // Faces have no axes; their key names each feature's column and direction.
            assert!(count(Role::Legend) >= 3, "{name} has a feature key");
        } else if ["treemap", "hypertree", "graph", "linkmap"].contains(&kind) {
            // Hierarchies and networks have no axes: their nodes (or matrix rows) are labelled.
            assert!(count(Role::Annotation) + count(Role::TickLabel) >= 10, "{name} labels its nodes");
        } else {
            assert!(count(Role::AxisTitle) >= 2, "{name} has axis titles");
            assert!(count(Role::TickLabel) >= 4, "{name} has tick labels");
        }
        // Network nodes carry node-table rows, so without a node table only their edges have rows.
        let network = ["graph", "linkmap"].contains(&kind);
        let (mut marks, mut with_rows) = (0, 0);
        scene.walk(|item| {
            let node = network && matches!(item.shape, Shape::Circle { .. });
            if item.role == Role::DataMark && !matches!(item.shape, Shape::Group { .. }) && !node {
                marks += 1;
                with_rows += usize::from(!item.rows.is_empty());
            }
        });
        assert!(marks >= 1, "{name} has data marks");
        // Marks drawn one per row keep their rows; derived geometry (contour lines, sections,
        // surface quads, slices, isosurfaces, ray-cast images) is not one row per mark.
        // Hyperbolic-tree edges are geometry between two rows' nodes.
        let derived =
            ["contour", "section", "surface", "hyperslice", "hypertree", "flow", "slice", "isosurface", "volume"]
                .contains(&kind);
        if !derived {
            assert_eq!(with_rows, marks, "{name}: every data mark keeps its source rows");
        }
    }
}

#[test]
fn colour_encodings_have_a_legend() {
    for (name, _, scene) in gallery_scenes() {
        let multi_colour = {
            let mut found = false;
            scene.walk(|item| {
                if let Shape::Points(b) = &item.shape
                    && matches!(b.fill, dataink::scene::PerPoint::Each(_))
                {
                    found = true;
                }
            });
            found
        };
        let legend_items = {
            let mut n = 0;
            scene.walk(|item| {
                if item.role == Role::Legend {
                    n += 1;
                }
            });
            n
        };
        if multi_colour {
            assert!(legend_items > 0, "{name} encodes colour but has no legend");
        }
    }
}

#[test]
fn every_kind_draws_at_the_size_the_canvas_check_assumes() {
    let loaded = pipeline::load(&crate::common::root().join("examples/gallery.toml"), PathPolicy::InsideSpecFolder)
        .unwrap_or_else(|f| panic!("{}", f.render()));
    let mut kinds = std::collections::BTreeSet::new();
    for (i, chart) in loaded.spec.chart.iter().enumerate() {
        let unsized_chart = dataink::spec::Chart { size: None, ..chart.clone() };
        let out = pipeline::draw_chart(&loaded, i, &unsized_chart).unwrap_or_else(|e| panic!("{e}"));
        // Volumes are not tables; their charts draw at the kind's default size, as `render_all` checks.
        let [w, h] = match loaded.tables.get(&chart.data) {
            Some(table) => dataink::mark::canvas_size_in(&unsized_chart, table),
            None => dataink::mark::canvas_size(&unsized_chart),
        };
        assert_eq!([out.scene.width, out.scene.height], [w, h], "{}", chart.name);
        kinds.insert(chart.kind.name());
    }
    assert!(kinds.len() >= 15, "the gallery covers most kinds: {kinds:?}");
}
