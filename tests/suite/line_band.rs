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
