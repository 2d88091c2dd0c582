//! A line's uncertainty band: its polygon follows the upper edge out and the lower edge back,
//! the y axis covers it, missing edges split it, and bad input is refused.

use crate::common::{Fixture, plot};
use dataink::mark::ChartOutput;
use dataink::scene::{Item, PathCmd, Shape};

fn draw(csv: &str, extra: &str) -> Result<ChartOutput, String> {
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"l\"\nkind = \"line\"\ndata = \"d\"\nx = \"x\"\n{extra}"
    );
    Fixture::new(&spec, &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

/// The band polygons: their vertices.
fn bands(out: &ChartOutput) -> Vec<Vec<(f64, f64)>> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Some(label), Shape::Path(cmds)) = (item.label.as_deref(), &item.shape)
            && label.ends_with(" band")
        {
            found.push(
                cmds.iter()
                    .filter_map(|c| match c {
                        PathCmd::MoveTo(p) | PathCmd::LineTo(p) => Some((p.x, p.y)),
                        _ => None,
                    })
                    .collect(),
            );
        }
    });
    found
}

const CSV: &str = "x,y,lo,hi\n1,5,4,6\n2,6,3,9\n3,4,1,10\n";

#[test]
fn the_band_runs_out_along_the_upper_edge_and_back_along_the_lower() {
    let out = draw(CSV, "y = \"y\"\nband = { lower = \"lo\", upper = \"hi\" }").unwrap();
    let b = bands(&out);
    assert_eq!(b.len(), 1);
    let v = &b[0];
    assert_eq!(v.len(), 6);
    // x goes out and comes back; upper edges sit above (smaller pixel y than) the lower ones.
    assert!(v[0].0 < v[1].0 && v[1].0 < v[2].0);
    assert_eq!((v[3].0, v[4].0, v[5].0), (v[2].0, v[1].0, v[0].0));
    for k in 0..3 {
        assert!(v[k].1 < v[5 - k].1);
    }
    // The y axis covers the band: its extremes (1 and 10) lie inside the plot.
    let p = plot(&out);
    assert!(v.iter().all(|&(_, y)| y >= p.y - 1e-9 && y <= p.bottom() + 1e-9));
    // Heights are proportional to the intervals: 2, 6, 9 units.
    let h: Vec<f64> = (0..3).map(|k| v[5 - k].1 - v[k].1).collect();
    assert!((h[1] / h[0] - 3.0).abs() < 1e-9 && (h[2] / h[0] - 4.5).abs() < 1e-9, "{h:?}");
}

#[test]
fn a_missing_edge_splits_the_band_and_each_series_gets_its_own() {
    let out =
        draw("x,y,lo,hi\n1,5,4,6\n2,6,,9\n3,4,1,10\n4,4,2,5\n", "y = \"y\"\nband = { lower = \"lo\", upper = \"hi\" }")
            .unwrap();
    let b = bands(&out);
    assert_eq!(b.iter().map(Vec::len).collect::<Vec<_>>(), [2, 4]);
    let two = draw(
        "x,y,lo,hi,s\n1,5,4,6,a\n2,6,3,9,a\n1,2,1,3,b\n2,3,2,4,b\n",
        "y = \"y\"\ncolor = \"s\"\nband = { lower = \"lo\", upper = \"hi\" }",
    )
    .unwrap();
    assert_eq!(bands(&two).len(), 2);
}

#[test]
fn bad_bands_are_refused_with_their_reason() {
    let two_y = draw(CSV, "y = [\"y\", \"lo\"]\nband = { lower = \"lo\", upper = \"hi\" }").unwrap_err();
    assert!(two_y.contains("2 y columns are given"), "{two_y}");
    let text = draw("x,y,lo,hi\n1,5,a,6\n", "y = \"y\"\nband = { lower = \"lo\", upper = \"hi\" }").unwrap_err();
    assert!(text.contains("band lower column `lo` holds text"), "{text}");
    let missing = draw(CSV, "y = \"y\"\nband = { lower = \"low\", upper = \"hi\" }").unwrap_err();
    assert!(missing.contains("no column `low`") && missing.contains("did you mean `lo`"), "{missing}");
}

/// Rows sharing an x: at 1 the values 2, 4, 6 (mean 4, sd 2, n 3), at 2 the values 1, 3 (mean
/// 2, sd √2, n 2), at 3 a single 5.
const REPEATED: &str = "x,y\n1,2\n1,4\n2,1\n1,6\n2,3\n3,5\n";

/// A numeric column of the derived table.
fn column(out: &ChartOutput, name: &str) -> Vec<f64> {
    crate::common::numbers(out, name)
}

#[test]
fn a_spread_band_averages_the_rows_at_each_x() {
    let out = draw(REPEATED, "y = \"y\"\nband = \"ci95\"").unwrap();
    assert_eq!(column(&out, "y"), vec![4.0, 2.0, 5.0]);
    assert_eq!(column(&out, "rows"), vec![3.0, 2.0, 1.0]);
    // t(0.975, 2) = 4.302653 times sem 2/√3; t(0.975, 1) = 12.706205 times sem 1.
    let half = [4.302_652_729_7 * 2.0 / 3f64.sqrt(), 12.706_204_736_2];
    let (lower, upper) = (column(&out, "lower"), column(&out, "upper"));
    for (k, (centre, h)) in [(4.0, half[0]), (2.0, half[1])].into_iter().enumerate() {
        assert!(
            (lower[k] - (centre - h)).abs() < 1e-8 && (upper[k] - (centre + h)).abs() < 1e-8,
            "{lower:?} {upper:?}"
        );
    }
    assert!(lower[2].is_nan() && upper[2].is_nan(), "one row: no interval");
    assert!(
        out.warnings.iter().any(|w| w.to_string().contains("1 of 3 points rest on a single row")),
        "{:?}",
        out.warnings
    );
    // The band covers the two points with an interval; the y axis reaches its extremes.
    let b = bands(&out);
    assert_eq!(b.len(), 1);
    assert_eq!(b[0].len(), 4);
    let p = plot(&out);
    assert!(b[0].iter().all(|&(_, y)| y >= p.y - 1e-9 && y <= p.bottom() + 1e-9));
    let titles = crate::common::axis_titles(&out);
    assert!(titles.contains(&"Mean of y ± 95% CI".to_string()), "{titles:?}");
    let csv = out.derived.to_csv(&Default::default());
    // The x column is read from the source table, which `to_csv` is not given here.
    assert!(csv.starts_with("series,x,y,lower,upper,rows\ny,,4,"), "{csv}");
}

#[test]
fn spread_bands_per_series_and_as_a_table() {
    let csv = "x,y,s\n1,1,a\n1,3,a\n2,2,a\n2,6,a\n1,10,b\n1,20,b\n2,30,b\n2,50,b\n";
    let out = draw(
        csv,
        "y = { field = \"y\", title = \"Level\" }\ncolor = \"s\"\nband = { spread = \"minmax\", opacity = 0.5 }",
    )
    .unwrap();
    assert_eq!(bands(&out).len(), 2);
    assert_eq!(column(&out, "y"), vec![2.0, 4.0, 15.0, 40.0]);
    assert_eq!(column(&out, "lower"), vec![1.0, 2.0, 10.0, 30.0]);
    assert_eq!(column(&out, "upper"), vec![3.0, 6.0, 20.0, 50.0]);
    let out = draw(csv, "y = \"y\"\ncolor = \"s\"\nband = \"stdev\"").unwrap();
    let sd = 2f64.sqrt();
    assert_eq!(column(&out, "lower")[0], 2.0 - sd);
    let out = draw(csv, "y = \"y\"\ncolor = \"s\"\nband = \"sem\"").unwrap();
    assert_eq!(column(&out, "upper")[0], 2.0 + sd / 2f64.sqrt());
}

#[test]
fn a_band_names_columns_or_a_spread_not_both() {
    let both = draw(REPEATED, "y = \"y\"\nband = { spread = \"sem\", lower = \"y\" }").unwrap_err();
    assert!(both.contains("takes no `lower` or `upper` column"), "{both}");
    let half = draw(CSV, "y = \"y\"\nband = { lower = \"lo\" }").unwrap_err();
    assert!(half.contains("the band has no `upper` edge"), "{half}");
    let unknown = draw(REPEATED, "y = \"y\"\nband = \"ci90\"").unwrap_err();
    assert!(unknown.contains("band"), "{unknown}");
}
