//! The `flow` kind on analytic fields with known answers: critical points and their classes,
//! streamlines staying in the domain, unsteady traces, and bad input.

use crate::common::Fixture;
use dataink::mark::{ChartOutput, DerivedColumn};

/// A long-form grid of `f` on [-1, 1]², 21 × 21 nodes.
fn grid(f: impl Fn(f64, f64) -> (f64, f64)) -> String {
    let mut s = String::from("x,y,u,v\n");
    for j in 0..21 {
        for i in 0..21 {
            let (x, y) = (-1.0 + 0.1 * i as f64, -1.0 + 0.1 * j as f64);
            let (u, v) = f(x, y);
            s.push_str(&format!("{x},{y},{u},{v}\n"));
        }
    }
    s
}

fn draw(data: &str, extra: &str) -> Result<ChartOutput, String> {
    let spec = format!(
        "[data.f]\npath = \"f.csv\"\n[[chart]]\nname = \"f\"\nkind = \"flow\"\ndata = \"f\"\nx = \"x\"\ny = \"y\"\nu = \"u\"\nv = \"v\"\n{extra}"
    );
    Fixture::new(&spec, &[("f.csv", data.as_bytes())]).draw().map(|mut v| v.remove(0))
}

fn column<'a>(out: &'a ChartOutput, name: &str) -> &'a DerivedColumn {
    &out.derived.columns.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no column {name}")).1
}

fn critical(out: &ChartOutput) -> Vec<(String, f64, f64, [f64; 4])> {
    let (DerivedColumn::Text(element), DerivedColumn::Text(class)) = (column(out, "element"), column(out, "class"))
    else {
        panic!()
    };
    let num = |n: &str| match column(out, n) {
        DerivedColumn::Number(v) => v.clone(),
        _ => panic!(),
    };
    let (x, y) = (num("x"), num("y"));
    let e = [num("eigen1_re"), num("eigen1_im"), num("eigen2_re"), num("eigen2_im")];
    (0..element.len())
        .filter(|&i| element[i] == "critical point")
        .map(|i| (class[i].clone(), x[i], y[i], [e[0][i], e[1][i], e[2][i], e[3][i]]))
        .collect()
}

#[test]
fn critical_points_of_linear_fields_have_their_textbook_classes() {
    type Field = fn(f64, f64) -> (f64, f64);
    let cases: [(&str, Field, [f64; 4]); 3] = [
        ("saddle", |x, y| (x, -y), [1.0, 0.0, -1.0, 0.0]),
        ("centre", |x, y| (-y, x), [0.0, 1.0, 0.0, -1.0]),
        ("attracting focus", |x, y| (-x - y, x - y), [-1.0, 1.0, -1.0, -1.0]),
    ];
    for (class, f, eigen) in cases {
        let out = draw(&grid(f), "layers = [\"topology\"]\n").unwrap_or_else(|e| panic!("{e}"));
        let points = critical(&out);
        assert_eq!(points.len(), 1, "{class}: {points:?}");
        let (c, x, y, e) = &points[0];
        assert_eq!(c, class);
        assert!(x.abs() < 1e-9 && y.abs() < 1e-9, "{class} at the origin");
        // Eigenvalues in either order.
        let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(p, q)| (p - q).abs() < 1e-9);
        assert!(same(e, &eigen) || same(&[e[2], e[3], e[0], e[1]], &eigen), "{class}: {e:?}");
    }
}

#[test]
fn streamlines_stay_in_the_domain_and_a_zero_field_draws_no_lines() {
    let out = draw(&grid(|x, y| (-y, x)), "layers = [\"streamlines\"]\n").unwrap();
    let (DerivedColumn::Number(x), DerivedColumn::Number(y)) = (column(&out, "x"), column(&out, "y")) else { panic!() };
    assert!(x.len() > 100, "lines were traced");
    for (a, b) in x.iter().zip(y) {
        assert!(a.is_finite() && b.is_finite() && a.abs() <= 1.0 + 1e-9 && b.abs() <= 1.0 + 1e-9);
    }
    let still = draw(&grid(|_, _| (0.0, 0.0)), "layers = [\"streamlines\"]\n").unwrap();
    let DerivedColumn::Number(x) = column(&still, "x") else { panic!() };
    assert!(x.is_empty(), "no streamline in a field at rest");
}

#[test]
fn traces_need_time_and_seeds_need_their_geometry() {
    let data = grid(|x, y| (x, -y));
    let err = draw(&data, "layers = [\"pathlines\"]\n").unwrap_err();
    assert!(err.contains("particle traces need an unsteady field"), "{err}");
    let err = draw(&data, "layers = [\"streamlines\"]\nseeds = \"rake\"\n").unwrap_err();
    assert!(err.contains("`seeds = \"rake\"` needs `rake`"), "{err}");
    let err = draw("x,y,u,v\n0,0,1,1\n", "").unwrap_err();
    assert!(err.contains("at least") || err.contains("2"), "{err}");
}

#[test]
fn pathlines_of_an_unsteady_uniform_flow_are_straight() {
    // u = 0.1, v = 0 at t = 0 and t = 1: a particle from (−0.5, 0) moves 0.1 to the right.
    let mut data = String::from("x,y,t,u,v\n");
    for t in [0, 1] {
        for j in 0..5 {
            for i in 0..5 {
                data.push_str(&format!("{},{},{t},0.1,0\n", -1.0 + 0.5 * i as f64, -1.0 + 0.5 * j as f64));
            }
        }
    }
    let out = draw(
        &data,
        "t = \"t\"\nlayers = [\"pathlines\"]\nseeds = \"rake\"\nrake = [[-0.5, 0], [-0.5, 0.5]]\nseed_count = 2\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (DerivedColumn::Number(x), DerivedColumn::Number(y)) = (column(&out, "x"), column(&out, "y")) else { panic!() };
    let last_x = x.iter().cloned().fold(f64::MIN, f64::max);
    assert!((last_x - (-0.4)).abs() < 1e-6, "{last_x}");
    assert!(y.iter().all(|v| v.abs() < 1e-9 || (v - 0.5).abs() < 1e-9), "straight lines");
}
