//! The `box` and `violin` kinds against hand-computed and numpy-computed statistics: quartiles,
//! whiskers, outliers, notches, kernel bandwidths, mirrored outlines, counts, orientation,
//! dodging by colour, selections, the non-finite policy, bad input, and the lint rules that read
//! their axes.

use crate::common::{Fixture, lint_codes, lint_findings, plot, tick_labels};
use dataink::guide::scale::Scale;
use dataink::mark::{ChartOutput, DerivedColumn};
use dataink::scene::{Item, PathCmd, Point, Rect, Role, Shape, path_points};

/// A chart of `kind` over `d.csv` with extra chart keys.
fn spec(kind: &str, extra: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"{kind}\"\ndata = \"d\"\ntitle = \"T\"\n\
         size = [600, 400]\n{extra}"
    )
}

fn draw(kind: &str, csv: &str, extra: &str) -> Result<ChartOutput, String> {
    Fixture::new(&spec(kind, extra), &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

fn draw_ok(kind: &str, csv: &str, extra: &str) -> ChartOutput {
    draw(kind, csv, extra).unwrap_or_else(|e| panic!("{e}"))
}

fn draw_err(kind: &str, csv: &str, extra: &str) -> String {
    match draw(kind, csv, extra) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

/// Every item of the scene, groups opened, in drawing order.
fn all_items(items: &[Item]) -> Vec<&Item> {
    let mut out = Vec::new();
    for i in items {
        out.push(i);
        if let Shape::Group { items, .. } = &i.shape {
            out.extend(all_items(items));
        }
    }
    out
}

/// The item labelled `label` (the last one, if several).
fn item<'a>(out: &'a ChartOutput, label: &str) -> &'a Item {
    all_items(&out.scene.items)
        .into_iter()
        .rev()
        .find(|i| i.label.as_deref() == Some(label))
        .unwrap_or_else(|| panic!("no item labelled `{label}`"))
}

fn has_item(out: &ChartOutput, label: &str) -> bool {
    all_items(&out.scene.items).iter().any(|i| i.label.as_deref() == Some(label))
}

fn rect(out: &ChartOutput, label: &str) -> Rect {
    match &item(out, label).shape {
        Shape::Rect(r) => *r,
        other => panic!("`{label}` is not a rect: {other:?}"),
    }
}

fn path(out: &ChartOutput, label: &str) -> Vec<Point> {
    match &item(out, label).shape {
        Shape::Path(cmds) => path_points(cmds).collect(),
        other => panic!("`{label}` is not a path: {other:?}"),
    }
}

/// The value → pixel map of a numeric axis, read off its tick labels and their positions.
fn value_map(out: &ChartOutput, axis: &str) -> impl Fn(f64) -> f64 {
    let mut ticks = Vec::new();
    out.scene.walk(|i: &Item| {
        if i.role == Role::TickLabel
            && i.label.as_deref() == Some(axis)
            && let Shape::Text(t) = &i.shape
            && let Ok(v) = t.content.replace('−', "-").parse::<f64>()
        {
            ticks.push((v, if axis == "x axis" { t.at.x } else { t.at.y }));
        }
    });
    assert!(ticks.len() >= 2, "{axis} has numeric ticks: {ticks:?}");
    let ((v0, p0), (v1, p1)) = (ticks[0], ticks[ticks.len() - 1]);
    let slope = (p1 - p0) / (v1 - v0);
    move |v| p0 + slope * (v - v0)
}

fn numbers(out: &ChartOutput, name: &str) -> Vec<f64> {
    match out.derived.columns.iter().find(|(n, _)| n == name) {
        Some((_, DerivedColumn::Number(v))) => v.clone(),
        other => panic!("no number column `{name}`: {other:?}"),
    }
}

/// Texts of one role.
fn texts(out: &ChartOutput, role: Role) -> Vec<String> {
    let mut found = Vec::new();
    out.scene.walk(|i: &Item| {
        if let (true, Shape::Text(t)) = (i.role == role, &i.shape) {
            found.push(t.content.clone());
        }
    });
    found
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6 * (1.0 + b.abs())
}

fn assert_close(a: f64, b: f64, what: &str) {
    assert!(close(a, b), "{what}: {a} vs {b}");
}

/// Group a: 1..=8; group b: eleven values whose numpy quartiles are pasted below.
const TWO: &str = "k,v\na,1\na,2\na,3\na,4\na,5\na,6\na,7\na,8\n\
                   b,2.5\nb,0.3\nb,9.1\nb,4.4\nb,7.7\nb,1.2\nb,6.6\nb,3.9\nb,8.8\nb,5.0\nb,0.9\n";

/// −20, 1..=8 and 30 in scrambled order (rows 1 and 5 hold 30 and −20).
const TAILS: &str = "v\n5\n30\n1\n2\n3\n-20\n4\n6\n7\n8\n";

#[test]
fn boxes_span_the_quartiles_by_numpys_default_method() {
    let out = draw_ok("box", TWO, "x = \"k\"\ny = \"v\"\n");
    // a = 1..=8 by hand (type 7): positions 1.75, 3.5, 5.25 → 2.75, 4.5, 6.25.
    // b: python3 -c "import numpy as np; print(np.percentile([2.5,0.3,9.1,4.4,7.7,1.2,6.6,3.9,8.8,5.0,0.9], [25,50,75]))"
    //    → [1.85 4.4  7.15]
    let expected = [[2.75, 4.5, 6.25], [1.85, 4.4, 7.15]];
    for (column, k) in [("q1", 0), ("median", 1), ("q3", 2)] {
        let got = numbers(&out, column);
        for (g, want) in got.iter().zip(expected.iter().map(|e| e[k])) {
            assert_close(*g, want, column);
        }
    }
    assert_eq!(numbers(&out, "n"), [8.0, 11.0]);
    let y = value_map(&out, "y axis");
    for (label, [q1, median, q3]) in ["a", "b"].into_iter().zip(expected) {
        let r = rect(&out, label);
        assert_close(r.y, y(q3), "box top at Q3");
        assert_close(r.bottom(), y(q1), "box bottom at Q1");
        let m = path(&out, &format!("median: {label}"));
        assert!(m.iter().all(|p| close(p.y, y(median))), "median line at {median}: {m:?}");
        assert_close(m[0].x, r.x, "median across the box");
        assert_close(m[1].x, r.right(), "median across the box");
    }
    // Each box carries its group's rows, for lint and the explorer.
    assert_eq!(item(&out, "a").rows, (0..8).collect::<Vec<u32>>());
    assert_eq!(item(&out, "b").rows, (8..19).collect::<Vec<u32>>());
    // The hinge method can be changed: numpy's 'weibull' gives [1.2, 4.4, 7.7] for b.
    let weibull = draw_ok("box", TWO, "x = \"k\"\ny = \"v\"\nquantiles = \"weibull\"\n");
    assert_eq!(numbers(&weibull, "q1")[1], 1.2);
    assert_eq!(numbers(&weibull, "q3")[1], 7.7);
}

#[test]
fn whiskers_reach_the_last_values_inside_the_fences_and_outliers_are_points() {
    let out = draw_ok("box", TAILS, "y = \"v\"\n");
    // Q1 = 2.25, Q3 = 6.75 (numpy: [2.25, 4.5, 6.75]); fences −4.5 and 13.5.
    assert_eq!(numbers(&out, "whisker_low"), [1.0]);
    assert_eq!(numbers(&out, "whisker_high"), [8.0]);
    assert_eq!(numbers(&out, "outliers"), [2.0]);
    assert_eq!((numbers(&out, "min"), numbers(&out, "max")), (vec![-20.0], vec![30.0]));
    let y = value_map(&out, "y axis");
    let whiskers = path(&out, "whiskers: v");
    let (top, bottom) = whiskers.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.y), b.max(p.y)));
    assert_close(top, y(8.0), "upper whisker");
    assert_close(bottom, y(1.0), "lower whisker");
    let outliers = item(&out, "outliers");
    assert_eq!(outliers.rows, [1, 5], "the rows of 30 and −20");
    let Shape::Points(batch) = &outliers.shape else { panic!("outliers are points") };
    assert_close(batch.centers[0].y, y(30.0), "outlier 30");
    assert_close(batch.centers[1].y, y(-20.0), "outlier −20");
    // Whiskers of 10 IQR reach both: no outliers.
    let wide = draw_ok("box", TAILS, "y = \"v\"\nwhisker = 10\n");
    assert_eq!(numbers(&wide, "outliers"), [0.0]);
    assert!(!has_item(&wide, "outliers"), "no outlier batch");
}

#[test]
fn notches_are_the_median_plus_minus_1_57_iqr_over_root_n() {
    let out = draw_ok("box", TAILS, "y = \"v\"\nnotch = true\n");
    // python3 -c "import math; print(4.5 - 1.57*4.5/math.sqrt(10), 4.5 + 1.57*4.5/math.sqrt(10))"
    //   → 2.26585083309104 6.73414916690896
    let (lo, hi) = (numbers(&out, "notch_low")[0], numbers(&out, "notch_high")[0]);
    assert_close(lo, 2.26585083309104, "notch low");
    assert_close(hi, 6.73414916690896, "notch high");
    // The notched box is a polygon through Q1, the notch ends, the median (pinched in by a
    // quarter of the width each side) and Q3.
    let y = value_map(&out, "y axis");
    let body = path(&out, "v");
    let mut levels: Vec<f64> = body.iter().map(|p| p.y).collect();
    levels.sort_by(f64::total_cmp);
    levels.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    let want: Vec<f64> = [6.75, hi, 4.5, lo, 2.25].into_iter().map(&y).collect();
    assert_eq!(levels.len(), 5, "{levels:?}");
    for (got, want) in levels.iter().zip(&want) {
        assert_close(*got, *want, "notch vertex");
    }
    let xs: Vec<f64> = body.iter().map(|p| p.x).collect();
    let (left, right) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let pinched: Vec<&Point> = body.iter().filter(|p| close(p.y, y(4.5))).collect();
    assert_eq!(pinched.len(), 2);
    assert_close(pinched[0].x.min(pinched[1].x), left + (right - left) / 4.0, "notch depth");
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
}

#[test]
fn horizontal_boxes_swap_the_axes() {
    let vertical = draw_ok("box", TWO, "x = \"k\"\ny = \"v\"\n");
    let out = draw_ok("box", TWO, "x = \"k\"\ny = \"v\"\norientation = \"horizontal\"\n");
    // Categories down the y axis, the first on top; values along x.
    let mut at = Vec::new();
    out.scene.walk(|i: &Item| {
        if let (Role::TickLabel, Some("y axis"), Shape::Text(t)) = (i.role, i.label.as_deref(), &i.shape) {
            at.push((t.content.clone(), t.at.y));
        }
    });
    at.sort_by(|a, b| a.1.total_cmp(&b.1));
    assert_eq!(at.iter().map(|a| a.0.as_str()).collect::<Vec<_>>(), ["a", "b"], "a above b");
    let x = value_map(&out, "x axis");
    for (label, q1, q3) in [("a", 2.75, 6.25), ("b", 1.85, 7.15)] {
        let r = rect(&out, label);
        assert_close(r.x, x(q1), "box starts at Q1");
        assert_close(r.right(), x(q3), "box ends at Q3");
        // As wide across as the vertical box is.
        assert_close(r.h, rect(&vertical, label).w.min(r.h), "same band size");
        let tick = at.iter().find(|a| a.0 == label).map_or(f64::NAN, |a| a.1);
        assert_close(r.y + r.h / 2.0, tick, "box centred on its category");
    }
    assert!(tick_labels(&vertical, "x axis").contains(&"a".to_string()));
    assert_eq!(texts(&out, Role::AxisTitle), ["v", "k"], "value title on x, category title on y");
}

#[test]
fn colour_dodges_boxes_within_a_category_with_a_legend() {
    let csv = "k,g,v\na,p,1\na,p,2\na,p,3\na,q,4\na,q,5\na,q,6\nb,q,7\nb,q,8\nb,q,9\n";
    let out = draw_ok("box", csv, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\n");
    let (ap, aq, bq) = (rect(&out, "a, p"), rect(&out, "a, q"), rect(&out, "b, q"));
    assert!(ap.right() < aq.x, "p left of q within a");
    assert_close(ap.w, aq.w, "equal widths");
    assert_close(bq.x - aq.x, plot(&out).w / 2.0, "b's q keeps q's place, one band on");
    assert_ne!(item(&out, "a, p").style.fill, item(&out, "a, q").style.fill);
    assert_eq!(item(&out, "a, q").style.fill, item(&out, "b, q").style.fill);
    let legend = texts(&out, Role::Legend);
    assert!(legend.contains(&"p".to_string()) && legend.contains(&"q".to_string()), "{legend:?}");
    let csv_out = out.derived.to_csv(&Default::default());
    assert!(
        csv_out.starts_with("k,g,n,min,q1,median,q3,max,mean,whisker_low,whisker_high,outliers\na,p,3,"),
        "{csv_out}"
    );
    // Colour repeating x is not dodged: each box is centred on its tick.
    let same = draw_ok("box", TWO, "x = \"k\"\ny = \"v\"\ncolor = \"k\"\n");
    let p = plot(&same);
    for (i, label) in ["a", "b"].into_iter().enumerate() {
        let r = rect(&same, label);
        assert_close(r.x + r.w / 2.0, p.x + p.w / 2.0 * (i as f64 + 0.5), "centred in its band");
        assert_close(r.w, (p.w / 2.0 * 0.8).min(160.0), "as wide as the band, at most 160 px");
    }
}

#[test]
fn counts_and_means_are_drawn_at_each_box() {
    let out = draw_ok("box", TWO, "x = \"k\"\ny = \"v\"\nmean = true\n");
    assert_eq!(texts(&out, Role::Annotation), ["n = 8", "n = 11"]);
    let y = value_map(&out, "y axis");
    // b's mean: 50.4 / 11.
    let diamond = path(&out, "mean: b");
    let centre = (diamond[0].y + diamond[2].y) / 2.0;
    assert_close(centre, y(50.4 / 11.0), "mean diamond");
    assert_close(numbers(&out, "mean")[0], 4.5, "a's mean");
    // The counts sit below the lowest whisker, inside the plot.
    let p = plot(&out);
    let counts: Vec<Item> = {
        let mut v = Vec::new();
        out.scene.walk(|i: &Item| {
            if i.role == Role::Annotation {
                v.push(i.clone());
            }
        });
        v
    };
    for c in &counts {
        let Shape::Text(t) = &c.shape else { panic!("text") };
        assert!(t.at.y <= p.bottom() && t.at.y > y(0.3), "{t:?}");
    }
}

#[test]
fn derived_csv_has_one_row_per_group() {
    let out = draw_ok("box", "k,v\na,1\na,2\na,3\nb,10\n", "x = \"k\"\ny = \"v\"\n");
    assert_eq!(
        out.derived.to_csv(&Default::default()),
        "k,n,min,q1,median,q3,max,mean,whisker_low,whisker_high,outliers\n\
         a,3,1,1.5,2,2.5,3,2,1,3,0\nb,1,10,10,10,10,10,10,10,10,0\n"
    );
}

#[test]
fn non_finite_values_are_dropped_with_the_usual_warning() {
    for kind in ["box", "violin"] {
        let out = draw_ok(kind, "k,v\na,1\na,NaN\na,3\nb,inf\nb,2\nb,4\n", "x = \"k\"\ny = \"v\"\n");
        assert!(
            out.warnings.iter().any(|w| w.to_string().contains("dropped 2 of 6 rows")
                && w.to_string().contains("`v`: 1 missing or NaN, 1 infinite")),
            "{kind}: {:?}",
            out.warnings
        );
        assert_eq!(numbers(&out, "n"), [2.0, 2.0], "{kind}");
    }
}

#[test]
fn a_selection_draws_its_rows_as_points_over_grey_boxes() {
    let spec = format!(
        "{}x = \"k\"\ny = \"v\"\nhighlight = \"mid\"\n\n[selection.mid]\ndata = \"d\"\nrange = {{ v = [3, 8] }}\n",
        spec("box", "")
    );
    let out = Fixture::new(&spec, &[("d.csv", TWO.as_bytes())]).draw().unwrap_or_else(|e| panic!("{e}")).remove(0);
    let selected = item(&out, "mid (selected)");
    // a: 3..=8 (rows 2..=7); b: 4.4, 7.7, 6.6, 3.9, 5.0 (rows 11, 12, 14, 15, 17).
    assert_eq!(selected.rows, [2, 3, 4, 5, 6, 7, 11, 12, 14, 15, 17]);
    let Shape::Points(batch) = &selected.shape else { panic!("points") };
    let y = value_map(&out, "y axis");
    let r = rect(&out, "a");
    for (c, v) in batch.centers.iter().zip([3.0, 4.0, 5.0, 6.0, 7.0, 8.0]) {
        assert_close(c.y, y(v), "a selected row at its value");
        assert!(c.x > r.x && c.x < r.right(), "inside its box's width");
    }
    let grey = item(&out, "a").style.fill.expect("a fill");
    assert_eq!((grey.r, grey.g, grey.b), (0xc8, 0xc8, 0xc8), "the box is grey context");
    assert!(texts(&out, Role::Legend).contains(&"mid: 11 of 19 rows".to_string()));
}

#[test]
fn bad_input_gives_the_documented_errors() {
    let xy = "x = \"k\"\ny = \"v\"\n";
    for kind in ["box", "violin"] {
        let e = draw_err(kind, "k,v\n", xy);
        assert!(e.contains("error: chart \"c\": data \"d\" has no rows"), "{e}");
        let e = draw_err(kind, "k,v\na,NaN\nb,\n", xy);
        assert!(e.contains("no rows left to plot out of 2"), "{e}");
        let e = draw_err(kind, "k,v\na,x\n", xy);
        assert!(e.contains("column `v` holds text; a distribution needs numbers"), "{e}");
        let e = draw_err(kind, "k,v\na,2020-01-01\n", xy);
        assert!(e.contains("y column `v` holds dates or times"), "{e}");
        let e = draw_err(kind, "n,v\n1,2\n", "x = { field = \"n\", scale = \"linear\" }\ny = \"v\"\n");
        assert!(e.contains("place every x value in its own band, so x cannot have a linear scale"), "{e}");
        let e = draw_err(kind, "k,v\na,2\n", "x = \"k\"\ny = { field = \"v\", scale = \"band\" }\n");
        assert!(e.contains("need a continuous scale, not a band scale"), "{e}");
        let many: String = std::iter::once("k,v\n".to_string()).chain((0..300).map(|i| format!("c{i},1\n"))).collect();
        let e = draw_err(kind, &many, xy);
        assert!(e.contains("300 categories do not fit a 600 px wide chart (each needs at least 3 px)"), "{e}");
        let e = draw_err(kind, &many, "x = \"k\"\ny = \"v\"\norientation = \"horizontal\"\n");
        assert!(e.contains("300 categories do not fit a 400 px tall chart"), "{e}");
    }
    let e = draw_err("violin", TWO, "x = \"k\"\ny = { field = \"v\", scale = \"log\" }\n");
    assert!(e.contains("the values of violins need a continuous scale, not a log scale"), "{e}");
    let e = draw_err("violin", TWO, "x = \"k\"\ny = \"v\"\nbandwidth = 0\n");
    assert!(e.contains("`bandwidth` must be greater than 0, found 0"), "{e}");
    let e = draw_err("violin", TWO, "x = \"k\"\ny = \"v\"\nbandwidth = -0.5\n");
    assert!(e.contains("`bandwidth` must be greater than 0, found -0.5"), "{e}");
    let e = draw_err("box", TWO, "x = \"k\"\ny = \"v\"\nwhisker = -1\n");
    assert!(e.contains("`whisker` must be at least 0, found -1"), "{e}");
    // A log scale is fine for boxes; values ≤ 0 are dropped and counted.
    let out = draw_ok("box", "v\n-1\n1\n10\n100\n", "y = { field = \"v\", scale = \"log\" }\n");
    assert_eq!(numbers(&out, "n"), [3.0]);
    assert!(out.warnings.iter().any(|w| w.to_string().contains("dropped 1 of 4 rows")), "{:?}", out.warnings);
}

#[test]
fn the_violin_bandwidth_is_silvermans_and_the_chart_says_so() {
    let out = draw_ok("violin", "v\n1\n2\n3\n4\n5\n", "y = \"v\"\n");
    // 1..=5: sd = 1.5811, IQR/1.34 = 1.4925 → h = 0.9 · 1.4925 · 5^(−1/5) = 0.9736.
    let h = 0.9 * (2.0 / 1.34) * 5f64.powf(-0.2);
    assert_close(numbers(&out, "bandwidth")[0], h, "Silverman");
    let legend = texts(&out, Role::Legend);
    assert!(legend.contains(&"bandwidth 0.97 (Silverman)".to_string()), "{legend:?}");
    let given = draw_ok("violin", "v\n1\n2\n3\n4\n5\n", "y = \"v\"\nbandwidth = 0.5\n");
    assert_eq!(numbers(&given, "bandwidth"), [0.5]);
    assert!(texts(&given, Role::Legend).contains(&"bandwidth 0.5 (given)".to_string()));
    // Groups with their own bandwidths: the range. b is a scaled tenfold, and so is its bandwidth.
    let csv: String =
        std::iter::once("k,v\n".to_string()).chain((1..=8).map(|i| format!("a,{i}\nb,{}\n", 10 * i))).collect();
    let groups = draw_ok("violin", &csv, "x = \"k\"\ny = \"v\"\n");
    let h = numbers(&groups, "bandwidth");
    assert_close(h[1], 10.0 * h[0], "b's bandwidth");
    let legend = texts(&groups, Role::Legend);
    assert!(legend.contains(&"bandwidth 1.5–15".to_string()), "{legend:?}");
    assert!(legend.contains(&"(Silverman, per violin)".to_string()), "{legend:?}");
}

/// The outline of violin `label`: its points and the centre line it is mirrored about.
fn outline(out: &ChartOutput, label: &str) -> (Vec<Point>, usize) {
    let points = path(out, label);
    let half = points.len() / 2;
    (points, half)
}

#[test]
fn violins_are_mirrored_densities_as_wide_as_their_slot() {
    let out = draw_ok("violin", TWO, "x = \"k\"\ny = \"v\"\n");
    let y = value_map(&out, "y axis");
    let p = plot(&out);
    let band = (p.w / 2.0 * 0.8).min(160.0);
    for (label, lo, hi) in [("a", 1.0, 8.0), ("b", 0.3, 9.1)] {
        let (points, half) = outline(&out, label);
        let Some(Shape::Path(cmds)) = Some(&item(&out, label).shape) else { panic!("path") };
        assert!(matches!(cmds.last(), Some(PathCmd::Close)), "closed");
        // Right side up the values, the left side back down, mirrored about the centre.
        let (right, left) = points.split_at(half);
        let centre = (right[0].x + left[left.len() - 1].x) / 2.0;
        for (r, l) in right.iter().zip(left.iter().rev()) {
            assert_close(r.y, l.y, "mirrored at the same value");
            assert_close(r.x - centre, centre - l.x, "mirrored widths");
        }
        // Cut 0: from the smallest to the largest value; widest at the slot's half width.
        assert_close(right[0].y, y(lo), "starts at the minimum");
        assert_close(right[right.len() - 1].y, y(hi), "ends at the maximum");
        let widest = right.iter().map(|q| q.x - centre).fold(0.0, f64::max);
        assert_close(widest, band / 2.0, "scale = width");
    }
    // With cut = 2 the density runs two bandwidths past the data.
    let cut = draw_ok("violin", TWO, "x = \"k\"\ny = \"v\"\ncut = 2\n");
    let h = numbers(&cut, "bandwidth")[0];
    let y = value_map(&cut, "y axis");
    let (points, _) = outline(&cut, "a");
    assert_close(points[0].y, y(1.0 - 2.0 * h), "cut below");
}

#[test]
fn count_scaling_makes_areas_proportional_to_the_counts() {
    // b holds a's values twice: with one bandwidth their densities are the same curve.
    let mut csv = String::from("k,v\n");
    for v in [1.0, 2.0, 2.5, 3.0, 4.0, 6.0] {
        csv.push_str(&format!("a,{v}\nb,{v}\nb,{v}\n"));
    }
    let out = draw_ok("violin", &csv, "x = \"k\"\ny = \"v\"\nbandwidth = 1\nscale = \"count\"\n");
    let width = |label: &str| {
        let (points, half) = outline(&out, label);
        let xs: Vec<f64> = points[..half].iter().map(|p| p.x).collect();
        xs.iter().fold(0.0f64, |m, &x| m.max(x)) - points[half..].iter().map(|p| p.x).fold(f64::INFINITY, f64::min)
    };
    assert_close(width("b") / width("a"), 2.0, "twice the rows, twice the width everywhere");
    assert!(texts(&out, Role::Legend).contains(&"areas proportional to counts".to_string()));
}

#[test]
fn horizontal_violins_swap_the_axes() {
    let out = draw_ok("violin", TWO, "x = \"k\"\ny = \"v\"\norientation = \"horizontal\"\n");
    let x = value_map(&out, "x axis");
    let (points, half) = outline(&out, "b");
    let (right, left) = points.split_at(half);
    assert_close(right[0].x, x(0.3), "from b's minimum along x");
    assert_close(right[right.len() - 1].x, x(9.1), "to b's maximum");
    let centre = (right[0].y + left[left.len() - 1].y) / 2.0;
    for (r, l) in right.iter().zip(left.iter().rev()) {
        assert_close(r.x, l.x, "mirrored at the same value");
        assert_close(r.y - centre, centre - l.y, "mirrored about a horizontal centre line");
    }
}

#[test]
fn violin_insides_and_groups_without_a_density() {
    let out = draw_ok("violin", TWO, "x = \"k\"\ny = \"v\"\n");
    let y = value_map(&out, "y axis");
    let mut dots = Vec::new();
    out.scene.walk(|i: &Item| {
        if let (Some("median"), Shape::Circle { center, .. }) = (i.label.as_deref(), &i.shape) {
            dots.push(center.y);
        }
    });
    assert_eq!(dots.len(), 2);
    assert_close(dots[0], y(4.5), "a's median dot");
    let lines = draw_ok("violin", TWO, "x = \"k\"\ny = \"v\"\ninner = \"quartiles\"\n");
    let q1 = path(&lines, "first quartile");
    assert!(q1.iter().all(|p| close(p.y, value_map(&lines, "y axis")(1.85))), "b's Q1 across the violin");
    let bare = draw_ok("violin", TWO, "x = \"k\"\ny = \"v\"\ninner = \"none\"\n");
    let mut marks = 0;
    bare.scene
        .walk(|i: &Item| marks += usize::from(i.role == Role::DataMark && !matches!(i.shape, Shape::Group { .. })));
    assert_eq!(marks, 2, "the two outlines only");
    // One value has no spread for Silverman's rule: drawn as a point, with a note.
    let single = draw_ok("violin", "k,v\na,1\na,2\na,4\nb,3\n", "x = \"k\"\ny = \"v\"\n");
    let Shape::Points(batch) = &item(&single, "b").shape else { panic!("b is a point") };
    assert_eq!(batch.centers.len(), 1);
    assert!(single.warnings.iter().any(|w| w.to_string().contains("`b` has too few values")), "{:?}", single.warnings);
    assert!(numbers(&single, "bandwidth")[1].is_nan());
}

#[test]
fn lint_reads_the_value_axis_and_leaves_baselines_to_bars() {
    // Values near 100: the value axis leaves zero out, which is right for distributions.
    let csv = "k,temp_c\na,101\na,104\na,103\nb,108\nb,107\nb,110\nb,109\n";
    let files = [("d.csv", csv.as_bytes())];
    for kind in ["box", "violin"] {
        let codes = lint_codes(&spec(kind, "x = \"k\"\ny = { field = \"temp_c\", unit = \"°C\" }\n"), &files);
        assert!(!codes.contains(&"DI001"), "{kind}: {codes:?}");
        // SC002 finds the values' axis on x when the chart is horizontal.
        let horizontal =
            "x = \"k\"\ny = { field = \"temp_c\", title = \"Temperature\" }\norientation = \"horizontal\"\n";
        let found = lint_findings(&spec(kind, horizontal), &files, "SC002");
        assert_eq!(found.len(), 1, "{kind}: {found:?}");
        assert_eq!((found[0].element.as_str(), found[0].path.as_str()), ("x axis", "chart[0].y"));
    }
    // A bar chart with the same axis does get DI001: the test can see it.
    let bar = lint_codes(&spec("bar", "x = \"k\"\ny = { field = \"temp_c\", zero = false, unit = \"°C\" }\n"), &files);
    assert!(bar.contains(&"DI001"), "{bar:?}");
    // A fixed domain that leaves values out is reported for boxes as for other charts.
    let cut =
        lint_codes(&spec("box", "x = \"k\"\ny = { field = \"temp_c\", unit = \"°C\", domain = [100, 108] }\n"), &files);
    assert!(cut.contains(&"DI005"), "{cut:?}");
}

/// An explorer session over the data `TWO` with one chart per `(name, kind, keys)`.
/// A finished drag from `from` to `to` in the first plot of chart `chart`, replacing the selection.
fn drag(s: &mut dataink::explore::Session, chart: usize, from: Point, to: Point) {
    s.brush(chart, dataink::explore::Target::Plot(0), from, to, dataink::explore::brush::Mode::Replace);
    s.end_brush(chart);
}

/// How many rows of source `d` are lit (all 19 when nothing is selected).
fn lit(s: &dataink::explore::Session) -> usize {
    s.mask("d").map_or(19, |m| m.iter().filter(|&&on| on).count())
}

/// The canvas position of the middle of `category`'s band on a band scale.
fn band_centre(scale: &Scale, category: &str) -> f64 {
    let Scale::Band(band) = scale else { panic!("a band scale") };
    band.center(band.band_of(category).unwrap())
}

fn session_over_two(charts: &[(&str, &str, &str)]) -> dataink::explore::Session {
    let charts: String = charts
        .iter()
        .map(|(name, kind, keys)| format!("[[chart]]\nname = \"{name}\"\nkind = \"{kind}\"\ndata = \"d\"\n{keys}\n"))
        .collect();
    let fx = Fixture::new(&format!("[data.d]\npath = \"d.csv\"\n\n{charts}"), &[("d.csv", TWO.as_bytes())]);
    dataink::explore::Session::new(fx.load().unwrap_or_else(|e| panic!("{e}")), 1.0)
}

#[test]
fn a_brush_in_the_explorer_relights_the_selected_rows_in_boxes_and_violins() {
    let mut s = session_over_two(&[
        ("s", "scatter", "x = \"v\"\ny = \"v\"\n"),
        ("b", "box", "x = \"k\"\ny = \"v\"\n"),
        ("w", "violin", "x = \"k\"\ny = \"v\"\n"),
    ]);
    assert!(
        s.charts.iter().all(|v| v.error.is_none() && v.lit == (19, 19)),
        "{:?}",
        s.charts.iter().map(|v| (&v.error, v.lit)).collect::<Vec<_>>()
    );
    // Brush v in [3, 8] in the scatter: 11 rows, lit in the box and violin charts too.
    let plot = s.charts[0].geometry.plots[0].clone();
    let (x, y) = (plot.x.as_ref().unwrap(), plot.y.as_ref().unwrap());
    let (a, b) = (x.scale.map(3.0), x.scale.map(8.0));
    let (c, d) = (y.scale.map(3.0), y.scale.map(8.0));
    drag(&mut s, 0, Point::new(a, c), Point::new(b, d));
    for v in &s.charts {
        assert_eq!(v.lit, (11, 19), "chart {}", v.name);
    }
}

#[test]
fn the_explorer_brushes_boxes_histograms_and_heatmaps_by_the_columns_they_place() {
    let mut s = session_over_two(&[
        ("b", "box", "x = \"k\"\ny = \"v\"\n"),
        ("h", "histogram", "x = \"v\"\n"),
        ("m", "heatmap", "x = \"k\"\ny = \"k\"\n"),
    ]);

    // The box chart: its categories across, its values up.
    let plot = s.charts[0].geometry.plots[0].clone();
    let (x, y) = (plot.x.clone().expect("categories brush"), plot.y.clone().expect("values brush"));
    assert_eq!((x.field.as_str(), y.field.as_str()), ("k", "v"));
    // Over category b only (its band centre), values 3 to 8: 3.9, 4.4, 5.0, 6.6, 7.7.
    let bx = band_centre(&x.scale, "b");
    drag(&mut s, 0, Point::new(bx - 5.0, y.scale.map(8.0)), Point::new(bx + 5.0, y.scale.map(3.0)));
    assert_eq!(lit(&s), 5);

    // The histogram: counts are not a column, so a drag selects by v alone, whatever its height.
    let plot = s.charts[1].geometry.plots[0].clone();
    assert!(plot.y.is_none(), "counts place no column");
    let x = plot.x.clone().expect("values brush");
    let r = plot.rect;
    drag(&mut s, 1, Point::new(x.scale.map(0.0), r.y), Point::new(x.scale.map(2.0), r.y + 1.0));
    // v in [0, 2]: 1, 2 (a) and 0.3, 1.2, 0.9 (b).
    assert_eq!(lit(&s), 5);

    // The heatmap (k against k): a drag over the cell (b, b) selects category b (11 rows).
    let plot = s.charts[2].geometry.plots[0].clone();
    let (x, y) = (plot.x.expect("categories across"), plot.y.expect("categories up"));
    let (bx, by) = (band_centre(&x.scale, "b"), band_centre(&y.scale, "b"));
    drag(&mut s, 2, Point::new(bx - 3.0, by - 3.0), Point::new(bx + 3.0, by + 3.0));
    assert_eq!(lit(&s), 11);
}

#[test]
fn the_explorer_brushes_bars_by_category_and_lines_by_the_columns_they_draw() {
    let mut s = session_over_two(&[
        ("bars", "bar", "x = \"k\"\ny = \"v\"\n"),
        ("across", "bar", "x = \"k\"\ny = \"v\"\norientation = \"horizontal\"\n"),
        ("line", "line", "x = \"v\"\ny = \"v\"\n"),
        ("means", "line", "x = \"k\"\ny = \"v\"\nband = \"ci95\"\n"),
        // Bars and lines draw no selection; the histogram shows it (and gives the source a row set).
        ("shown", "histogram", "x = \"v\"\n"),
    ]);

    // Vertical bars: sums place no column up, so a drag over bar a (any height) selects its 8 rows.
    let plot = s.charts[0].geometry.plots[0].clone();
    assert!(plot.y.is_none(), "summed heights place no column");
    let x = plot.x.clone().expect("categories brush");
    assert_eq!(x.field, "k");
    let ax = band_centre(&x.scale, "a");
    drag(&mut s, 0, Point::new(ax - 5.0, plot.rect.y), Point::new(ax + 5.0, plot.rect.y + 20.0));
    assert_eq!(lit(&s), 8);

    // Horizontal bars: the categories run down, the lengths place no column.
    let plot = s.charts[1].geometry.plots[0].clone();
    assert!(plot.x.is_none(), "summed lengths place no column");
    let y = plot.y.clone().expect("categories brush");
    let by = band_centre(&y.scale, "b");
    drag(&mut s, 1, Point::new(plot.rect.x, by - 5.0), Point::new(plot.rect.x + 20.0, by + 5.0));
    assert_eq!(lit(&s), 11);

    // A line of rows places both columns: v in [3, 8] on both axes selects 11 rows.
    let plot = s.charts[2].geometry.plots[0].clone();
    let (x, y) = (plot.x.clone().expect("x brush"), plot.y.clone().expect("y brush"));
    drag(&mut s, 2, Point::new(x.scale.map(3.0), y.scale.map(3.0)), Point::new(x.scale.map(8.0), y.scale.map(8.0)));
    assert_eq!(lit(&s), 11);

    // A line of means with a band: the means place no column, the categories do.
    let plot = s.charts[3].geometry.plots[0].clone();
    assert!(plot.y.is_none(), "means of rows place no column");
    assert_eq!(plot.x.as_ref().map(|p| p.field.as_str()), Some("k"));
}
