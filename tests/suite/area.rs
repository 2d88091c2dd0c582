//! The `area` kind against hand-computed stacks: totals, shares, gap filling, order, the
//! streamgraph's thickness, and bad input.

use crate::common::{Fixture, numbers, texts};
use dataink::mark::ChartOutput;

/// Two series over x = 1, 2, 3; `b` has no row at x = 2.
const CSV: &str = "x,y,s\n1,1,a\n2,2,a\n3,3,a\n1,4,b\n3,2,b\n";

fn draw(csv: &str, extra: &str) -> Result<ChartOutput, String> {
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"a\"\nkind = \"area\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\n{extra}"
    );
    Fixture::new(&spec, &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

#[test]
fn stacked_series_reach_the_totals_and_a_missing_value_counts_as_zero() {
    let out = draw(CSV, "color = \"s\"").unwrap();
    assert_eq!(texts(&out, "s"), ["a", "a", "a", "b", "b", "b"]);
    assert_eq!(numbers(&out, "value"), [1.0, 2.0, 3.0, 4.0, 0.0, 2.0]);
    assert_eq!(numbers(&out, "y0"), [0.0, 0.0, 0.0, 1.0, 2.0, 3.0]);
    assert_eq!(numbers(&out, "y1"), [1.0, 2.0, 3.0, 5.0, 2.0, 5.0]);
    let note: Vec<String> = out.warnings.iter().map(|w| w.to_string()).collect();
    assert!(note.iter().any(|w| w.contains("1 series values were missing") && w.contains("as zero")), "{note:?}");
    // Chosen explicitly, the fill is not remarked on.
    let linear = draw(CSV, "color = \"s\"\nfill = \"linear\"").unwrap();
    assert_eq!(numbers(&linear, "value")[4], 3.0, "halfway between 4 and 2");
    assert!(linear.warnings.is_empty(), "{:?}", linear.warnings);
}

#[test]
fn normalised_stacks_end_at_100_and_centred_ones_are_symmetric() {
    let norm = draw(CSV, "color = \"s\"\nstack = \"normalize\"").unwrap();
    let y1 = numbers(&norm, "y1");
    assert!(y1[3..].iter().all(|v| (v - 100.0).abs() < 1e-9), "{y1:?}");
    assert!((y1[0] - 20.0).abs() < 1e-9, "a is 1 of 5 at x = 1");
    let center = draw(CSV, "color = \"s\"\nstack = \"center\"").unwrap();
    let (y0, y1) = (numbers(&center, "y0"), numbers(&center, "y1"));
    for j in 0..3 {
        assert!((y0[j] + y1[3 + j]).abs() < 1e-9);
    }
}

#[test]
fn a_streamgraph_keeps_every_layers_thickness() {
    let csv = "x,y,s\n0,1,a\n1,3,a\n2,2,a\n0,2,b\n1,2,b\n2,5,b\n0,4,c\n1,1,c\n2,1,c\n";
    let out = draw(csv, "color = \"s\"\nstack = \"wiggle\"").unwrap();
    let (value, y0, y1) = (numbers(&out, "value"), numbers(&out, "y0"), numbers(&out, "y1"));
    for k in 0..value.len() {
        assert!((y1[k] - y0[k] - value[k]).abs() < 1e-9);
    }
    assert!(y0.iter().any(|v| *v < 0.0), "the baseline moves below zero: {y0:?}");
}

#[test]
fn sum_order_puts_the_largest_series_at_the_bottom() {
    let csv = "x,y,s\n1,1,a\n2,1,a\n1,5,b\n2,5,b\n";
    let legend = draw(csv, "color = \"s\"").unwrap();
    assert_eq!(texts(&legend, "s"), ["a", "a", "b", "b"]);
    let sum = draw(csv, "color = \"s\"\norder = \"sum\"").unwrap();
    assert_eq!(texts(&sum, "s"), ["b", "b", "a", "a"]);
    assert_eq!(numbers(&sum, "y1"), [5.0, 5.0, 6.0, 6.0]);
}

#[test]
fn dates_on_x_and_a_single_series_from_zero() {
    let csv = "d,v\n2024-01-01,3\n2024-02-01,5\n2024-03-01,4\n";
    let spec =
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"a\"\nkind = \"area\"\ndata = \"d\"\nx = \"d\"\ny = \"v\"";
    let out = Fixture::new(spec, &[("d.csv", csv.as_bytes())]).draw().unwrap().remove(0);
    assert_eq!(texts(&out, "d")[1], "2024-02-01 00:00:00");
    assert_eq!(numbers(&out, "y1"), [3.0, 5.0, 4.0]);
}

#[test]
fn bad_input_gets_clear_errors() {
    let negative = draw("x,y,s\n1,-1,a\n2,2,a\n", "color = \"s\"").unwrap_err();
    assert!(negative.contains("negative values (row 0: -1)") && negative.contains("stack = \"none\""), "{negative}");
    assert!(draw("x,y,s\n1,-1,a\n2,2,a\n", "color = \"s\"\nstack = \"none\"").is_ok());
    let text = draw("x,y\na,1\nb,2\n", "").unwrap_err();
    assert!(text.contains("holds text") && text.contains("bar chart"), "{text}");
    let spec = "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"a\"\nkind = \"area\"\ndata = \"d\"\nx = \"x\"\n\
                y = { field = \"y\", scale = \"log\" }";
    let log = Fixture::new(spec, &[("d.csv", CSV.as_bytes())]).draw().unwrap_err();
    assert!(log.contains("measured from its baseline"), "{log}");
}
