//! Chart kinds against known answers: geometry that can be computed by hand.

use crate::common::Fixture;

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

/// The first chart's derived CSV as rows of fields (header dropped).
fn derived_csv(spec: &str) -> Vec<Vec<String>> {
    let fx = Fixture::new(spec, &[]);
    let loaded = fx.load().unwrap_or_else(|e| panic!("{e}"));
    let out = fx.draw().unwrap_or_else(|e| panic!("{e}"));
    let table = loaded.tables.values().next().expect("one table");
    out[0].derived.to_csv(table).lines().skip(1).map(|l| l.split(',').map(str::to_string).collect()).collect()
}

/// Parse the derived CSV into (method, x, y) rows.
fn derived_rows(spec: &str) -> Vec<(String, f64, f64)> {
    derived_csv(spec).into_iter().map(|f| (f[0].clone(), f[1].parse().expect("x"), f[2].parse().expect("y"))).collect()
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

/// A long-form grid spec: `rows` are (x, y, z) triples.
fn grid_spec(rows: &[(f64, f64, f64)], extra: &str) -> String {
    let values: Vec<String> = rows.iter().map(|(x, y, z)| format!("{{ x = {x:?}, y = {y:?}, z = {z:?} }}")).collect();
    format!(
        "[data.g]\nvalues = [\n{}\n]\n\n[[chart]]\nname = \"g\"\nkind = \"contour\"\ndata = \"g\"\nx = \"x\"\ny = \"y\"\nz = \"z\"\n{extra}",
        values.join(",\n")
    )
}

/// (level, line, x, y) rows of a contour chart's derived CSV.
fn contour_rows(spec: &str) -> Vec<(f64, usize, f64, f64)> {
    derived_csv(spec)
        .into_iter()
        .map(|f| {
            let n: Vec<f64> = f.iter().map(|v| v.parse().expect("number")).collect();
            (n[0], n[1] as usize, n[2], n[3])
        })
        .collect()
}

#[test]
fn contours_of_a_plane_are_straight_lines_at_the_level() {
    // f = x on a 5 × 4 grid: the level-L contour is the vertical line x = L.
    let mut rows = Vec::new();
    for j in 0..4 {
        for i in 0..5 {
            rows.push((i as f64, j as f64 * 0.5, i as f64));
        }
    }
    let out = contour_rows(&grid_spec(&rows, "levels = [0.5, 1.25, 3.0]\n"));
    assert!(!out.is_empty());
    for (level, _, x, y) in &out {
        assert!((x - level).abs() < 1e-12, "point ({x}, {y}) of level {level}");
        assert!((0.0..=1.5).contains(y));
    }
    for level in [0.5, 1.25, 3.0] {
        let ys: Vec<f64> = out.iter().filter(|r| r.0 == level).map(|r| r.3).collect();
        assert!(ys.contains(&0.0) && ys.contains(&1.5), "level {level} spans the grid: {ys:?}");
    }
}

#[test]
fn saddle_rule_decides_the_connectivity_of_the_issue_example() {
    // One cell: f00 = −3 at (0, 0), f10 = 1 at (1, 0), f01 = 10 at (0, 1), f11 = −5 at (1, 1).
    // Saddle value (f00·f11 − f01·f10)/(f00 + f11 − f01 − f10) = (15 − 10)/(−19) = −5/19 ≈ −0.263;
    // centre average 0.75. At level 0.25 the asymptotic decider puts the centre below the level
    // (−0.263 < 0.25) and the centre rule above it (0.75 ≥ 0.25): they pair the crossings
    // differently.
    let rows = [(0.0, 0.0, -3.0), (1.0, 0.0, 1.0), (0.0, 1.0, 10.0), (1.0, 1.0, -5.0)];
    let lines = |rule: &str| {
        let out = contour_rows(&grid_spec(&rows, &format!("levels = [0.25]\nsaddle = \"{rule}\"\n")));
        let mut by_line: Vec<Vec<(f64, f64)>> = Vec::new();
        for (_, line, x, y) in out {
            if by_line.len() <= line {
                by_line.resize(line + 1, Vec::new());
            }
            by_line[line].push((x, y));
        }
        let mut ends: Vec<[(i64, i64); 2]> = by_line
            .iter()
            .map(|l| {
                let key = |p: &(f64, f64)| ((p.0 * 1e6).round() as i64, (p.1 * 1e6).round() as i64);
                let mut e = [key(&l[0]), key(&l[l.len() - 1])];
                e.sort();
                e
            })
            .collect();
        ends.sort();
        ends
    };
    let asymptotic = lines("asymptotic");
    let center = lines("center");
    assert_eq!(asymptotic.len(), 2, "two segments: {asymptotic:?}");
    assert_eq!(center.len(), 2, "two segments: {center:?}");
    assert_ne!(asymptotic, center, "the two rules pair the four crossings differently");
    // Crossings on the edges at level 0.25: bottom x = 3.25/4, left y = 3.25/13,
    // right y = 0.75/6, top x = 9.75/15.
    let all: Vec<(i64, i64)> = asymptotic.iter().flatten().copied().collect();
    for p in [(0.8125, 0.0), (0.0, 0.25), (1.0, 0.125), (0.65, 1.0)] {
        let key = ((p.0 * 1e6_f64).round() as i64, (p.1 * 1e6_f64).round() as i64);
        assert!(all.contains(&key), "crossing {p:?} in {all:?}");
    }
}

#[test]
fn scattered_points_are_not_a_grid() {
    let rows = [(0.0, 0.0, 1.0), (1.0, 0.3, 2.0), (2.0, 0.7, 3.0), (3.0, 1.1, 4.0)];
    let out = Fixture::new(&grid_spec(&rows, ""), &[]).draw().expect_err("not a grid");
    assert!(out.contains("x and y do not form a regular grid: 4 rows for 4 distinct x × 4 distinct y values"), "{out}");
}

#[test]
fn duplicate_grid_nodes_are_refused() {
    let rows = [(0.0, 0.0, 1.0), (1.0, 0.0, 2.0), (0.0, 1.0, 3.0), (1.0, 1.0, 4.0), (1.0, 1.0, 5.0)];
    let out = Fixture::new(&grid_spec(&rows, ""), &[]).draw().expect_err("duplicate");
    assert!(out.contains("the grid node (1, 1) appears in more than one row (row 4)"), "{out}");
}

#[test]
fn constant_and_all_nan_fields() {
    let constant: Vec<(f64, f64, f64)> = (0..9).map(|k| ((k % 3) as f64, (k / 3) as f64, 2.0)).collect();
    let out = contour_rows(&grid_spec(&constant, ""));
    assert!(out.is_empty(), "a constant field has no contour lines");
    let nan_rows = "[data.g]\nvalues = [{ x = 0, y = 0, z = nan }, { x = 1, y = 0, z = nan }, { x = 0, y = 1, z = nan }, { x = 1, y = 1, z = nan }]\n[[chart]]\nname = \"g\"\nkind = \"contour\"\ndata = \"g\"\nx = \"x\"\ny = \"y\"\nz = \"z\"\n";
    let out = Fixture::new(nan_rows, &[]).draw().expect_err("all NaN");
    assert!(out.contains("every value of `z` is missing or non-finite"), "{out}");
}

#[test]
fn contour_geojson_has_closed_oriented_rings() {
    // A cone f = −√(x² + y²) + 3 on a 21 × 21 grid: bands are nested annuli around the peak.
    let mut rows = Vec::new();
    for j in 0..21 {
        for i in 0..21 {
            let (x, y) = (i as f64 * 0.3 - 3.0, j as f64 * 0.3 - 3.0);
            rows.push((x, y, 3.0 - (x * x + y * y).sqrt()));
        }
    }
    let out = Fixture::new(&grid_spec(&rows, "levels = [0.5, 1.5, 2.5]\n"), &[]).draw().expect("draws");
    let geojson = out[0].geojson.as_ref().expect("contour charts export GeoJSON").to_value();
    let features = geojson["features"].as_array().expect("features");
    let lines: Vec<_> = features.iter().filter(|f| f["properties"]["kind"] == "line").collect();
    let bands: Vec<_> = features.iter().filter(|f| f["properties"]["kind"] == "band").collect();
    assert_eq!(lines.len(), 3, "one closed ring per level around the peak");
    assert_eq!(bands.len(), 4, "min..0.5, 0.5..1.5, 1.5..2.5, 2.5..max");
    let signed_area = |ring: &[serde_json::Value]| -> f64 {
        ring.windows(2)
            .map(|w| {
                let (a, b) = (&w[0], &w[1]);
                a[0].as_f64().unwrap_or(0.0) * b[1].as_f64().unwrap_or(0.0)
                    - b[0].as_f64().unwrap_or(0.0) * a[1].as_f64().unwrap_or(0.0)
            })
            .sum::<f64>()
            / 2.0
    };
    let mut total = 0.0;
    for band in bands {
        for polygon in band["geometry"]["coordinates"].as_array().expect("polygons") {
            for (k, ring) in polygon.as_array().expect("rings").iter().enumerate() {
                let ring = ring.as_array().expect("ring");
                assert_eq!(ring.first(), ring.last(), "GeoJSON rings repeat their first point");
                let area = signed_area(ring);
                assert!(if k == 0 { area > 0.0 } else { area < 0.0 }, "outer CCW, holes CW: {area}");
                total += area;
            }
        }
    }
    // The bands tile the grid's domain, a 6 × 6 square.
    assert!((total - 36.0).abs() < 1e-9, "{total}");
}

#[test]
fn grid_files_load_as_long_form_tables() {
    // A CSV matrix: rows along y, columns along x, coordinates from `extent`.
    let spec = "[data.m]\npath = \"m.csv\"\nformat = \"matrix\"\nextent = [0.0, 1.0, 10.0, 20.0]\n\n[[chart]]\nname = \"m\"\nkind = \"contour\"\ndata = \"m\"\nx = \"x\"\ny = \"y\"\nz = \"value\"\nlevels = [1.5]\n";
    let fx = Fixture::new(spec, &[("m.csv", b"0,1\n2,3\n4,5\n")]);
    let loaded = fx.load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["m"];
    assert_eq!(t.column("x").and_then(|c| c.numbers()), Some(&[0.0, 1.0, 0.0, 1.0, 0.0, 1.0][..]));
    assert_eq!(t.column("y").and_then(|c| c.numbers()), Some(&[10.0, 10.0, 15.0, 15.0, 20.0, 20.0][..]));
    assert_eq!(t.column("value").and_then(|c| c.numbers()), Some(&[0.0, 1.0, 2.0, 3.0, 4.0, 5.0][..]));
    fx.draw().unwrap_or_else(|e| panic!("{e}"));

    // The same grid as a .npy file (version 1, little-endian f8, C order).
    let npy = crate::common::npy_f8(3, 2, &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    let spec = spec.replace("path = \"m.csv\"\nformat = \"matrix\"", "path = \"m.npy\"");
    let fx = Fixture::new(&spec, &[("m.npy", &npy)]);
    let loaded = fx.load().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.tables["m"], *t);

    let bad = Fixture::new(&spec, &[("m.npy", b"not numpy")]).load().expect_err("bad npy");
    assert!(bad.contains("as NumPy .npy: not a NumPy .npy file (bad magic bytes)"), "{bad}");
    assert!(bad.contains("= hint: save a 2-D (grid) or 3-D (volume) float or integer array with numpy.save"), "{bad}");
}

#[test]
fn contours_need_cells() {
    for rows in [&[(0.0, 0.0, 1.0)][..], &[(0.0, 0.0, 1.0), (1.0, 0.0, 2.0), (2.0, 0.0, 3.0)][..]] {
        let out = Fixture::new(&grid_spec(rows, ""), &[]).draw().expect_err("no cells");
        assert!(out.contains("contours need at least 2 × 2 grid nodes, the grid has"), "{out}");
    }
}

#[test]
fn a_missing_value_breaks_only_its_own_series() {
    // Long form: series a has no value at t = 1, series b has all three.
    let spec = r#"
[data.d]
values = [
  { t = 0, v = 1.0, s = "a" }, { t = 1, v = nan, s = "a" }, { t = 2, v = 3.0, s = "a" },
  { t = 0, v = 2.0, s = "b" }, { t = 1, v = 2.5, s = "b" }, { t = 2, v = 2.0, s = "b" },
]

[[chart]]
name = "l"
kind = "line"
data = "d"
x = "t"
y = "v"
series = "s"
"#;
    let out = Fixture::new(spec, &[]).draw().unwrap_or_else(|e| panic!("{e}"));
    let mut moves = std::collections::BTreeMap::new();
    out[0].scene.walk(|item| {
        if let (dataink::scene::Shape::Path(cmds), Some(label)) = (&item.shape, &item.label)
            && item.role == dataink::scene::Role::DataMark
        {
            let n = cmds.iter().filter(|c| matches!(c, dataink::scene::PathCmd::MoveTo(_))).count();
            moves.insert(label.clone(), n);
        }
    });
    assert_eq!(moves.get("a"), Some(&2), "a's gap at t = 1 starts a new subpath: {moves:?}");
    assert_eq!(moves.get("b"), Some(&1), "b is drawn in one piece: {moves:?}");
}

/// A line chart over two y columns written as `y_form`: (series label, y) of each drawn path
/// vertex in the derived CSV, the data-mark labels and the legend texts.
fn two_y_columns(y_form: &str) -> (Vec<(String, f64)>, Vec<String>, Vec<String>) {
    let spec = format!(
        r#"
[data.w]
values = [
  {{ date = 1, temp_max = 12.8, temp_min = 5.0 }},
  {{ date = 2, temp_max = 10.6, temp_min = 2.8 }},
  {{ date = 3, temp_max = 11.7, temp_min = 7.2 }},
]

[[chart]]
name = "w"
kind = "line"
data = "w"
x = "date"
y = {y_form}
"#
    );
    let rows = derived_csv(&spec).into_iter().map(|f| (f[0].clone(), f[3].parse().expect("y"))).collect();
    let out = Fixture::new(&spec, &[]).draw().unwrap_or_else(|e| panic!("{e}"));
    let (mut marks, mut legend) = (Vec::new(), Vec::new());
    out[0].scene.walk(|item| match (&item.role, &item.shape) {
        (dataink::scene::Role::DataMark, dataink::scene::Shape::Path(_)) => marks.extend(item.label.clone()),
        (dataink::scene::Role::Legend, dataink::scene::Shape::Text(t)) => legend.push(t.content.clone()),
        _ => {}
    });
    (rows, marks, legend)
}

#[test]
fn several_y_columns_draw_one_series_each_whether_written_as_names_or_tables() {
    let expected: Vec<(String, f64)> = [
        ("temp_max", 12.8),
        ("temp_max", 10.6),
        ("temp_max", 11.7),
        ("temp_min", 5.0),
        ("temp_min", 2.8),
        ("temp_min", 7.2),
    ]
    .iter()
    .map(|(s, v)| (s.to_string(), *v))
    .collect();
    for form in [r#"["temp_max", "temp_min"]"#, r#"[{ field = "temp_max" }, { field = "temp_min" }]"#] {
        let (rows, marks, legend) = two_y_columns(form);
        assert_eq!(rows, expected, "derived rows for y = {form}");
        assert_eq!(marks, ["temp_max", "temp_min"], "one path per column for y = {form}");
        for name in ["temp_max", "temp_min"] {
            assert!(legend.iter().any(|t| t == name), "legend names {name} for y = {form}: {legend:?}");
        }
    }
}

/// The axis titles of the first chart of a spec.
fn axis_titles(spec: &str) -> Vec<String> {
    let out = Fixture::new(spec, &[]).draw().unwrap_or_else(|e| panic!("{e}"));
    let mut titles = Vec::new();
    out[0].scene.walk(|item| {
        if let (dataink::scene::Role::AxisTitle, dataink::scene::Shape::Text(t)) = (&item.role, &item.shape) {
            titles.push(t.content.clone());
        }
    });
    titles
}

#[test]
fn a_title_that_already_names_its_unit_does_not_get_it_twice() {
    let data = r#"
[data.w]
values = [{ day = 1, hi = 12.8, lo = 5.0, mass = 3750.0 }, { day = 2, hi = 10.6, lo = 2.8, mass = 3800.0 }]
"#;
    let line = format!(
        r#"{data}
[[chart]]
name = "t"
kind = "line"
data = "w"
x = "day"
y = [{{ field = "hi", unit = "°C" }}, {{ field = "lo", unit = "°C" }}]
y_title = "Temperature (°C)"
"#
    );
    assert_eq!(axis_titles(&line), ["day", "Temperature (°C)"]);
    let scatter = format!(
        r#"{data}
[[chart]]
name = "m"
kind = "scatter"
data = "w"
x = {{ field = "mass", title = "Mass (g)", unit = "g" }}
y = {{ field = "hi", title = "High", unit = "°C" }}
"#
    );
    assert_eq!(axis_titles(&scatter), ["Mass (g)", "High (°C)"]);
}

#[test]
fn a_surface_is_one_mesh_whose_spike_hides_what_is_behind_it() {
    // A 4 × 4 grid, flat but for a spike at (1, 1), seen from the −y side (azimuth −90): the spike
    // stands in front of the far cells, so the PNG shows its colour where it covers them.
    let mut values = Vec::new();
    for y in 0..4 {
        for x in 0..4 {
            let z = if (x, y) == (1, 1) { 10 } else { 0 };
            values.push(format!("{{ x = {x}, y = {y}, z = {z} }}"));
        }
    }
    let spec = format!(
        "[data.g]\nvalues = [{}]\n[[chart]]\nname = \"s\"\nkind = \"surface\"\ndata = \"g\"\nx = \"x\"\ny = \"y\"\nz = \"z\"\nazimuth = -90\nelevation = 20\n",
        values.join(", ")
    );
    let out = Fixture::new(&spec, &[]).draw().unwrap_or_else(|e| panic!("{e}")).remove(0);
    let mut meshes = Vec::new();
    out.scene.walk(|item| {
        if let dataink::scene::Shape::Mesh(m) = &item.shape {
            meshes.push((m.clone(), item.rows.len()));
        }
    });
    let [(mesh, rows)] = meshes.as_slice() else { panic!("one mesh, got {}", meshes.len()) };
    assert_eq!((mesh.indices.len(), mesh.positions.len(), *rows), (2 * 9, 4 * 9, 16), "two triangles per cell");
    // Nothing in the mesh is broken.
    assert!((0..mesh.indices.len()).all(|i| mesh.triangle(i).is_some()));
    // In the PNG, the pixel just below the spike's top vertex shows the spike (its near faces),
    // not one of the flat cells behind it.
    let top = mesh.positions.iter().copied().min_by(|a, b| a[1].total_cmp(&b[1])).unwrap_or_default();
    let pixmap = dataink::render::to_pixmap(&out.scene, 1.0).unwrap_or_else(|e| panic!("{e}"));
    let below = pixmap.pixel(top[0] as u32, top[1] as u32 + 6).map(|c| [c.red(), c.green(), c.blue()]);
    let below = below.unwrap_or_default();
    let flat: Vec<[u8; 3]> = (0..mesh.indices.len())
        .filter_map(|i| mesh.triangle(i))
        .filter(|(p, _)| p.iter().all(|v| v != &top))
        .map(|(_, c)| [c[0].r, c[0].g, c[0].b])
        .filter(|c| c.iter().zip(below).all(|(a, b)| a.abs_diff(b) <= 8))
        .collect();
    assert!(flat.is_empty(), "{below:?} is the colour of a cell behind the spike: {flat:?}");
}
