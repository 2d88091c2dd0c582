//! Trend lines on scatter charts: the least-squares line through known points with its
//! equation, one line per colour category, LOESS, and the axes a trend needs.

use crate::common::Fixture;
use dataink::mark::ChartOutput;
use dataink::scene::{Item, PathCmd, Role, Shape};

fn draw(csv: &str, extra: &str) -> Result<ChartOutput, String> {
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"s\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\n{extra}"
    );
    Fixture::new(&spec, &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

/// The trend lines drawn (not their halos): label and polyline.
fn lines(out: &ChartOutput) -> Vec<(String, Vec<(f64, f64)>)> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        let label = item.label.clone().unwrap_or_default();
        if let (Role::Annotation, Shape::Path(cmds)) = (&item.role, &item.shape)
            && label.starts_with("trend")
            && !label.ends_with("halo")
            && !label.ends_with("swatch")
        {
            let points = cmds
                .iter()
                .filter_map(|c| match c {
                    PathCmd::MoveTo(p) | PathCmd::LineTo(p) => Some((p.x, p.y)),
                    _ => None,
                })
                .collect();
            found.push((label, points));
        }
    });
    found
}

fn equations(out: &ChartOutput) -> Vec<String> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Some("trend equation"), Shape::Text(t)) = (item.label.as_deref(), &item.shape) {
            found.push(t.content.clone());
        }
    });
    found
}

/// Anscombe's first set (y = 3.00 + 0.500 x, R² = 0.667) and a second group on y = 10 − x.
const CSV: &str = "x,y,g\n10,8.04,a\n8,6.95,a\n13,7.58,a\n9,8.81,a\n11,8.33,a\n14,9.96,a\n6,7.24,a\n4,4.26,a\n12,10.84,a\n7,4.82,a\n5,5.68,a\n";

#[test]
fn the_least_squares_line_and_its_equation() {
    let out = draw(CSV, "y = \"y\"\ntrend = \"linear\"").unwrap();
    assert_eq!(equations(&out), ["y = 0.500x + 3.00, R² = 0.667 (n = 11)"]);
    let drawn = lines(&out);
    assert_eq!(drawn.len(), 1);
    // The line runs from x = 4 to x = 14: its pixel slope is the data slope through the scales.
    let pts = &drawn[0].1;
    assert_eq!(pts.len(), 2);
    assert!(pts[0].0 < pts[1].0 && pts[0].1 > pts[1].1, "rises to the right (y grows upwards)");
}

#[test]
fn one_line_per_colour_category_in_its_colour() {
    let mut csv = CSV.to_string();
    for x in [1, 2, 3, 4] {
        csv.push_str(&format!("{x},{},b\n", 10 - x));
    }
    let out = draw(&csv, "y = \"y\"\ncolor = \"g\"\ntrend = { method = \"linear\", groups = true }").unwrap();
    let eq = equations(&out);
    assert_eq!(eq.len(), 2, "{eq:?}");
    assert!(eq.contains(&"b: y = −1.00x + 10.0, R² = 1.000 (n = 4)".to_string()), "{eq:?}");
    assert_eq!(lines(&out).len(), 2);
}

#[test]
fn loess_draws_a_curve_without_an_equation() {
    let mut csv = String::from("x,y\n");
    for i in 0..60 {
        let x = i as f64 / 6.0;
        csv.push_str(&format!("{x},{}\n", (x - 5.0).powi(2)));
    }
    let out = draw(&csv, "y = \"y\"\ntrend = { method = \"loess\", span = 0.3 }").unwrap();
    assert!(equations(&out).is_empty());
    let drawn = lines(&out);
    assert_eq!(drawn[0].1.len(), 100);
    // A parabola: the curve falls, then rises again (y pixels grow downwards).
    let ys: Vec<f64> = drawn[0].1.iter().map(|p| p.1).collect();
    let lowest = ys.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let at = ys.iter().position(|&y| y == lowest).unwrap();
    assert!((30..70).contains(&at), "the bottom of the curve is near the middle: {at}");
}

#[test]
fn a_trend_needs_linear_axes() {
    let e = draw(CSV, "y = { field = \"y\", scale = \"log\" }\ntrend = \"linear\"").unwrap_err();
    assert!(e.contains("fitted on linear axes"), "{e}");
}
