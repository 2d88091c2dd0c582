//! Category axes label every category: long labels are wrapped, turned or cut (with the full
//! name kept as hover text) instead of thinned, the frame makes room for them, and labels are
//! left out only when even turned labels cannot fit, with a warning that counts them. Numeric
//! axes still thin their labels.
//!
//! With `DATAINK_TEST_PNG=DIR` set, the charts drawn here are also written to `DIR` as PNGs.

use crate::common::{Fixture, plot};

use dataink::lint::Severity;
use dataink::mark::ChartOutput;
use dataink::render;
use dataink::scene::{Item, Rect, Role, Shape, Text};

/// A bar chart of `d.csv` with extra chart keys.
fn spec(extra: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"b\"\nkind = \"bar\"\ndata = \"d\"\ntitle = \"Bars\"\n{extra}"
    )
}

fn draw(csv: &str, extra: &str, png: &str) -> ChartOutput {
    let out = Fixture::new(&spec(extra), &[("d.csv", csv.as_bytes())])
        .draw()
        .map(|mut v| v.remove(0))
        .unwrap_or_else(|e| panic!("{e}"));
    if let Some(dir) = std::env::var_os("DATAINK_TEST_PNG") {
        let bytes = render::png::to_png(&out.scene, 1.0).expect("png");
        std::fs::write(std::path::Path::new(&dir).join(format!("{png}.png")), bytes).expect("write png");
    }
    out
}

/// Error-level lint findings of the chart.
fn lint_errors(csv: &str, extra: &str) -> Vec<String> {
    let linted = Fixture::new(&spec(extra), &[("d.csv", csv.as_bytes())]).lint().unwrap_or_else(|e| panic!("{e}"));
    linted
        .iter()
        .flat_map(|c| &c.findings)
        .filter(|f| f.severity == Severity::Error)
        .map(|f| format!("{}: {}", f.code, f.message))
        .collect()
}

/// The tick-label items of `axis` with their text.
fn labels<'a>(out: &'a ChartOutput, axis: &str) -> Vec<(&'a Item, &'a Text)> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if item.role == Role::TickLabel
            && item.label.as_deref() == Some(axis)
            && let Shape::Text(t) = &item.shape
        {
            found.push((item, t));
        }
    });
    found
}

fn axis_title<'a>(out: &'a ChartOutput, axis: &str) -> &'a Text {
    let mut found = None;
    out.scene.walk(|item: &Item| {
        if item.role == Role::AxisTitle
            && item.label.as_deref() == Some(axis)
            && let Shape::Text(t) = &item.shape
        {
            found = Some(t);
        }
    });
    found.expect("an axis title")
}

/// `n` long category names, one row each.
fn long_names(n: usize) -> (Vec<String>, String) {
    names_csv((0..n).map(|i| format!("Category {i}: a department with a long name")).collect())
}

/// `n` category names wider than a third of a 700 px canvas.
fn longer_names(n: usize) -> (Vec<String>, String) {
    names_csv((0..n).map(|i| format!("Category {i}: a department with a name far too long to fit")).collect())
}

fn names_csv(names: Vec<String>) -> (Vec<String>, String) {
    let mut csv = String::from("name,value\n");
    for (i, n) in names.iter().enumerate() {
        csv.push_str(&format!("\"{n}\",{}\n", 10 + i));
    }
    (names, csv)
}

fn within(inner: &Rect, outer: &Rect) -> bool {
    inner.x >= outer.x - 0.5
        && inner.y >= outer.y - 0.5
        && inner.right() <= outer.right() + 0.5
        && inner.bottom() <= outer.bottom() + 0.5
}

#[test]
fn thirty_long_category_names_are_all_labelled_turned_and_clear_of_each_other() {
    let (names, csv) = long_names(30);
    let extra = "x = \"name\"\ny = \"value\"\nsize = [800, 500]\n";
    let out = draw(&csv, extra, "thirty-long-names");
    let found = labels(&out, "x axis");
    assert_eq!(found.len(), 30, "one label per category");
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    let angle = found[0].1.angle;
    assert!(angle == -45.0 || angle == -90.0, "turned: {angle}");
    let p = plot(&out);
    let canvas = Rect::new(0.0, 0.0, out.scene.width, out.scene.height);
    for ((item, t), name) in found.iter().zip(&names) {
        assert_eq!(t.angle, angle, "every label turned alike");
        // Cut with an ellipsis, the full name kept as hover text.
        let kept = t.content.trim_end_matches('…');
        assert!(name.starts_with(kept) && kept.len() > 10, "{} for {name}", t.content);
        if t.content != *name {
            assert_eq!(item.tooltips, vec![name.clone()]);
        }
        // Below the plot and on the canvas.
        let Some(corners) = dataink::text::corners(t, 0.0) else { panic!("corners") };
        assert!(corners.iter().all(|c| c.y > p.bottom()), "{} reaches into the plot", t.content);
        assert!(within(&dataink::text::bounds(t), &canvas), "{} leaves the canvas", t.content);
    }
    // Each label ends at its bar's centre.
    for ((_, t), (_, bar, _)) in found.iter().zip(crate::common::bars(&out)) {
        assert!((t.at.x - (bar.x + bar.w / 2.0)).abs() < 1e-9, "{} at {}", t.content, t.at.x);
    }
    for pair in found.windows(2) {
        assert!(!dataink::text::texts_overlap(pair[0].1, pair[1].1), "{} / {}", pair[0].1.content, pair[1].1.content);
    }
    // The x title sits below the lowest label.
    let lowest = found.iter().map(|(_, t)| dataink::text::bounds(t).bottom()).fold(0.0, f64::max);
    assert!(dataink::text::bounds(axis_title(&out, "x axis")).y >= lowest - 0.5);
    assert_eq!(lint_errors(&csv, extra), Vec::<String>::new());
}

#[test]
fn turned_labels_shrink_the_plot_to_make_room() {
    let (_, csv) = long_names(30);
    let short: String = (0..30).fold(String::from("name,value\n"), |s, i| s + &format!("c{i},{i}\n"));
    let extra = "x = \"name\"\ny = \"value\"\nsize = [800, 500]\n";
    let (long, flat) = (plot(&draw(&csv, extra, "room-long")), plot(&draw(&short, extra, "room-short")));
    assert!(long.h < flat.h - 80.0, "{} vs {}", long.h, flat.h);
}

#[test]
fn labels_wider_than_their_band_wrap_onto_lines() {
    let csv = "region,sales\nNorth America,5\nSouth America,3\nEurope,4\nAsia Pacific,6\n";
    let extra = "x = \"region\"\ny = \"sales\"\nsize = [300, 300]\n";
    let out = draw(csv, extra, "wrapped");
    let found = labels(&out, "x axis");
    let lines: Vec<&str> = found.iter().map(|(_, t)| t.content.as_str()).collect();
    assert_eq!(lines, ["North", "America", "South", "America", "Europe", "Asia", "Pacific"]);
    assert!(found.iter().all(|(_, t)| t.angle == 0.0));
    // The second line sits one line below the first, under the same tick.
    let (first, second) = (found[0].1, found[1].1);
    assert_eq!(first.at.x, second.at.x);
    let m = dataink::text::measure("Ag", 12.0);
    assert!((second.at.y - first.at.y - (m.ascent + m.descent)).abs() < 1e-9);
    assert_eq!(found[0].0.tooltips, vec!["North America".to_string()]);
    assert!(found[4].0.tooltips.is_empty(), "Europe is not shortened");
    // The x title is below the second line.
    assert!(dataink::text::bounds(axis_title(&out, "x axis")).y >= dataink::text::bounds(second).bottom());
    assert_eq!(lint_errors(csv, extra), Vec::<String>::new());
}

#[test]
fn too_many_categories_leave_labels_out_with_a_warning_that_counts_them() {
    let csv: String = (0..300).fold(String::from("name,value\n"), |s, i| s + &format!("item {i},{}\n", i % 7 + 1));
    let out = draw(&csv, "x = \"name\"\ny = \"value\"\nsize = [700, 400]\n", "too-many");
    let shown = labels(&out, "x axis").len();
    assert!(shown > 0 && shown < 300, "{shown}");
    let left_out = 300 - shown;
    // Bands 2.1 px apart, 13.5 px text: every seventh labelled (the README's example).
    assert_eq!(left_out, 257);
    let notes: Vec<String> = out.warnings.iter().map(ToString::to_string).collect();
    let expected = format!("{left_out} of 300 category labels on the x axis are left out");
    assert!(notes.iter().any(|n| n.contains(&expected)), "{notes:?} lacks {expected}");
    // Upright labels, and every band still has its tick mark.
    assert!(labels(&out, "x axis").iter().all(|(_, t)| t.angle == -90.0));
    let mut marks = 0;
    out.scene.walk(|item: &Item| {
        if let (Role::Axis, Some("x axis"), Shape::Path(cmds)) = (item.role, item.label.as_deref(), &item.shape) {
            marks = cmds.len() / 2 - 1;
        }
    });
    assert_eq!(marks, 300);
}

#[test]
fn left_axis_labels_wrap_or_cut_and_every_category_keeps_its_label() {
    let (names, csv) = longer_names(12);
    let extra = "x = \"name\"\ny = \"value\"\norientation = \"horizontal\"\nsize = [700, 500]\n";
    let out = draw(&csv, extra, "horizontal-wrapped");
    let found = labels(&out, "y axis");
    // Bands about 30 px tall: two lines each, none wider than a third of the canvas.
    assert_eq!(found.len(), 24, "{:?}", found.iter().map(|f| &f.1.content).collect::<Vec<_>>());
    let p = plot(&out);
    for (_, t) in &found {
        let b = dataink::text::bounds(t);
        assert!(b.w <= 700.0 / 3.0 + 0.5 && b.right() < p.x && b.x >= 0.0, "{}", t.content);
    }
    let tooltips: Vec<&String> = found.iter().step_by(2).flat_map(|(i, _)| &i.tooltips).collect();
    assert_eq!(tooltips.len(), 12);
    assert!(names.iter().all(|n| tooltips.contains(&n)));
    assert_eq!(lint_errors(&csv, extra), Vec::<String>::new());

    // Forty bands one line tall: one line each, cut with an ellipsis, none left out.
    let (_, csv) = longer_names(40);
    let extra = "x = \"name\"\ny = \"value\"\norientation = \"horizontal\"\nsize = [700, 700]\n";
    let out = draw(&csv, extra, "horizontal-cut");
    let found = labels(&out, "y axis");
    assert_eq!(found.len(), 40);
    assert!(found.iter().all(|(_, t)| t.content.ends_with('…')));
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    assert_eq!(lint_errors(&csv, extra), Vec::<String>::new());
}

#[test]
fn a_shortened_label_keeps_its_full_name_as_svg_hover_text() {
    let (_, csv) = long_names(30);
    let out = draw(&csv, "x = \"name\"\ny = \"value\"\nsize = [800, 500]\n", "svg-title");
    let svg = render::svg::to_svg(&out.scene);
    crate::common::assert_svg_parses(&svg);
    assert!(svg.contains("<g><title>Category 7: a department with a long name</title><text"), "no title");
}

#[test]
fn faceted_bars_with_long_names_turn_their_outer_labels_and_lint_clean() {
    let mut csv = String::from("name,half,value\n");
    for i in 0..16 {
        csv.push_str(&format!("Quite a long category name {i},{},{}\n", if i < 8 { "first" } else { "second" }, i + 1));
    }
    let extra = "x = \"name\"\ny = \"value\"\nfacet = \"half\"\n";
    let out = draw(&csv, extra, "facet-long-names");
    let mut turned = 0;
    out.scene.walk(|item: &Item| {
        if let (Role::TickLabel, Some("x axis"), Shape::Text(t)) = (item.role, item.label.as_deref(), &item.shape) {
            turned += usize::from(t.angle != 0.0);
        }
    });
    // Both panels label their x axis (one row of panels): 2 × 16 bands.
    assert_eq!(turned, 32);
    assert_eq!(lint_errors(&csv, extra), Vec::<String>::new());
}
