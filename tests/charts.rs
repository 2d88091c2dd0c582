//! Chart kinds against known answers: geometry that can be computed by hand.

mod common;

use common::Fixture;

const PROJECTILE: &str = r#"
[data.p]
values = [
  { t = 0.0, h = 0.0, v = 15.0 },
  { t = 0.5, h = 6.27375, v = 10.095 },
  { t = 1.0, h = 10.095, v = 5.19 },
  { t = 1.5, h = 11.46375, v = 0.285 },
  { t = 2.0, h = 10.38, v = -4.62 },
  { t = 2.5, h = 6.84375, v = -9.525 },
  { t = 3.0, h = 0.855, v = -14.43 },
]

[[chart]]
name = "p"
kind = "interp1d"
data = "p"
x = "t"
y = "h"
slopes = "v"
methods = ["hermite", "linear"]
samples = 301
"#;

/// Parse the derived CSV into (method, x, y) rows.
fn derived_rows(spec: &str) -> Vec<(String, f64, f64)> {
    let fx = Fixture::new(spec, &[]);
    let loaded = fx.load().unwrap_or_else(|e| panic!("{e}"));
    let out = fx.draw().unwrap_or_else(|e| panic!("{e}"));
    let table = loaded.tables.values().next().expect("one table");
    out[0]
        .derived
        .to_csv(table)
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].to_string(), f[1].parse().expect("x"), f[2].parse().expect("y"))
        })
        .collect()
}

#[test]
fn hermite_with_exact_velocities_reproduces_the_parabola() {
    // h(t) = 15 t − 9.81 t²/2 and v = h′: a cubic Hermite with exact slopes reproduces any
    // quadratic exactly, so every sample lies on the parabola.
    let rows = derived_rows(PROJECTILE);
    let hermite: Vec<_> = rows.iter().filter(|r| r.0 == "hermite").collect();
    assert_eq!(hermite.len(), 301);
    for (_, t, h) in hermite {
        let exact = 15.0 * t - 9.81 * t * t / 2.0;
        assert!((h - exact).abs() < 1e-9, "t = {t}: {h} vs {exact}");
    }
    // Linear interpolation cuts the corners: at t = 0.25 it is below the parabola.
    let linear = rows.iter().find(|r| r.0 == "linear" && (r.1 - 0.25).abs() < 1e-12).expect("t = 0.25 sampled");
    assert!((linear.2 - 6.27375 / 2.0).abs() < 1e-12);
    assert!(linear.2 < 15.0 * 0.25 - 9.81 * 0.0625 / 2.0);
}

#[test]
fn hermite_needs_slopes() {
    let spec = PROJECTILE.replace("slopes = \"v\"\n", "");
    let out = Fixture::new(&spec, &[]).draw().expect_err("no slopes");
    assert!(out.contains("error: chart \"p\": method `hermite` needs the slopes at the knots\n"), "{out}");
    assert!(out.contains("= hint: add `slopes = \"COLUMN\"`"), "{out}");
}

#[test]
fn duplicate_knots_are_refused_with_their_rows() {
    let spec = PROJECTILE
        .replace("{ t = 1.0, h = 10.095", "{ t = 0.5, h = 10.095")
        .replace("[\"hermite\", \"linear\"]", "[\"pchip\"]");
    let out = Fixture::new(&spec, &[]).draw().expect_err("duplicate x");
    assert!(out.contains("error: chart \"p\": x = 0.5 appears twice"), "{out}");
}

#[test]
fn pchip_stays_within_monotone_data_where_mean_slopes_overshoot() {
    let spec = r#"
[data.fc]
values = [
  { x = 7.99, y = 0.0 }, { x = 8.09, y = 2.76429e-5 }, { x = 8.19, y = 4.37498e-2 },
  { x = 8.7, y = 0.169183 }, { x = 9.2, y = 0.469428 }, { x = 10.0, y = 0.943740 },
  { x = 12.0, y = 0.998636 }, { x = 15.0, y = 0.999919 }, { x = 20.0, y = 0.999994 },
]

[[chart]]
name = "fc"
kind = "interp1d"
data = "fc"
x = "x"
y = "y"
methods = ["pchip", "hermite-mean"]
"#;
    let rows = derived_rows(spec);
    let max = |m: &str| rows.iter().filter(|r| r.0 == m).map(|r| r.2).fold(f64::NEG_INFINITY, f64::max);
    let min = |m: &str| rows.iter().filter(|r| r.0 == m).map(|r| r.2).fold(f64::INFINITY, f64::min);
    assert!(max("pchip") <= 0.999994 + 1e-15 && min("pchip") >= 0.0, "PCHIP stays in [0, max y]");
    assert!(max("hermite-mean") > 1.0, "mean slopes overshoot above 1: {}", max("hermite-mean"));
    let pchip: Vec<f64> = rows.iter().filter(|r| r.0 == "pchip").map(|r| r.2).collect();
    assert!(pchip.windows(2).all(|w| w[1] >= w[0]), "PCHIP is monotone");
}
