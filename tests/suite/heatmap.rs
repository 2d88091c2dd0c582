//! The `heatmap` kind against hand-computed cells: aggregates, empty pairs, cell geometry,
//! ordering, label contrast, and bad input.

use crate::common::{Fixture, bars, numbers, plot, texts};
use dataink::mark::ChartOutput;
use dataink::scene::{Item, Role, Shape};

/// Columns c (x), r (y) and v: cell (p, a) has 1 and 3, (p, b) has 5, (q, a) has 2; (q, b) none.
const CSV: &str = "c,r,v\np,a,1\np,a,3\np,b,5\nq,a,2\n";

fn draw(csv: &str, extra: &str) -> Result<ChartOutput, String> {
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"h\"\nkind = \"heatmap\"\ndata = \"d\"\nsize = [500, 400]\nx = \"c\"\ny = \"r\"\n{extra}"
    );
    Fixture::new(&spec, &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

/// The cell labels drawn: (text, colour).
fn labels(out: &ChartOutput) -> Vec<(String, dataink::scene::Color)> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Role::Annotation, Shape::Text(t)) = (&item.role, &item.shape) {
            found.push((t.content.clone(), t.color));
        }
    });
    found
}

#[test]
fn cells_hold_the_aggregate_of_their_rows_and_pairs_without_rows_stay_empty() {
    let mean = draw(CSV, "z = \"v\"").unwrap();
    assert_eq!(texts(&mean, "c"), ["p", "q", "p"]);
    assert_eq!(texts(&mean, "r"), ["a", "a", "b"]);
    assert_eq!(numbers(&mean, "value"), [2.0, 2.0, 5.0]);
    assert_eq!(numbers(&mean, "rows"), [2.0, 1.0, 1.0]);
    assert_eq!(bars(&mean).len(), 3, "three cells drawn, (q, b) left empty");
    let sum = draw(CSV, "z = \"v\"\naggregate = \"sum\"").unwrap();
    assert_eq!(numbers(&sum, "value"), [4.0, 2.0, 5.0]);
    let count = draw(CSV, "").unwrap();
    assert_eq!(numbers(&count, "value"), [2.0, 1.0, 1.0]);
}

#[test]
fn cells_tile_the_plot_with_the_first_row_at_the_top() {
    let out = draw(CSV, "z = \"v\"").unwrap();
    let p = plot(&out);
    let cells = bars(&out);
    for (_, r, _) in &cells {
        assert!((r.w - p.w / 2.0).abs() < 1e-9 && (r.h - p.h / 2.0).abs() < 1e-9);
    }
    let (label, top_left, _) = &cells[0];
    assert_eq!(label, "p, a");
    assert!((top_left.x - p.x).abs() < 1e-9 && (top_left.y - p.y).abs() < 1e-9);
}

#[test]
fn value_order_puts_the_highest_mean_first_and_numbers_ascend() {
    let by_value = draw(CSV, "z = \"v\"\norder_y = \"value\"").unwrap();
    assert_eq!(texts(&by_value, "r")[0], "b", "row b's mean 5 beats row a's 2");
    let numeric = draw("c,r\n10,1\n9,1\n100,2\n", "").unwrap();
    assert_eq!(texts(&numeric, "c"), ["9", "10", "100"]);
}

#[test]
fn labels_contrast_with_their_cells_and_can_be_turned_off() {
    let out = draw(CSV, "z = \"v\"").unwrap();
    let found = labels(&out);
    assert_eq!(found.iter().map(|(t, _)| t.as_str()).collect::<Vec<_>>(), ["2.00", "2.00", "5.00"]);
    let cells = bars(&out);
    assert_eq!(cells.len(), found.len());
    let findings = crate::common::lint_findings(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"h\"\nkind = \"heatmap\"\ndata = \"d\"\nx = \"c\"\ny = \"r\"\nz = \"v\"",
        &[("d.csv", CSV.as_bytes())],
        "LB005",
    );
    assert!(findings.is_empty(), "every label is legible: {findings:?}");
    let off = draw(CSV, "z = \"v\"\nlabels = false").unwrap();
    assert!(labels(&off).is_empty());
}

#[test]
fn bad_input_gets_clear_errors() {
    let no_z = draw(CSV, "aggregate = \"mean\"").unwrap_err();
    assert!(no_z.contains("has no `z`"), "{no_z}");
    let text_z = draw(CSV, "z = \"c\"").unwrap_err();
    assert!(text_z.contains("holds text"), "{text_z}");
    let mut many = String::from("c,r\n");
    for i in 0..501 {
        many.push_str(&format!("k{i},a\n"));
    }
    let wide = draw(&many, "").unwrap_err();
    assert!(wide.contains("more than 500 distinct values"), "{wide}");
}

/// `n` seeded rows: text `c` (some cells empty; first seen in a row whose `v` is missing),
/// numbers `r` (with NaN and `inf`, which are the category "(missing)", and −0), whole-number
/// values `v` with every 101st empty and every 499th `inf`.
fn many_rows(n: usize) -> String {
    let mut next = crate::common::seeded_uniform();
    let names = ["zeta", "alpha", "", "mid", "beta"];
    let mut csv = String::from("c,r,v\n");
    for i in 0..n {
        let c = if i == 0 { "zeta" } else { names[(next() * 5.0) as usize] };
        let r = match i % 13 {
            0 => "NaN".to_string(),
            1 => "inf".to_string(),
            2 => "-0".to_string(),
            k => format!("{}", k % 6),
        };
        let v = match i {
            0 => String::new(),
            _ if i % 101 == 0 => String::new(),
            _ if i % 499 == 0 => "inf".to_string(),
            _ => format!("{}", (next() * 50.0).floor()),
        };
        csv.push_str(&format!("{c},{r},{v}\n"));
    }
    csv
}

#[test]
fn cells_of_rows_left_in_the_plan_equal_the_cells_of_rows_in_memory() {
    let csv = many_rows(240_000);
    for extra in [
        "",
        "z = \"v\"\n",
        "z = \"v\"\naggregate = \"median\"\norder_y = \"value\"\n",
        "z = \"v\"\naggregate = \"sum\"\norder_x = \"label\"\n",
        "z = \"v\"\naggregate = \"min\"\n",
        "z = \"v\"\naggregate = \"max\"\n",
    ] {
        let spec = format!(
            "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"h\"\nkind = \"heatmap\"\ndata = \"d\"\nsize = [500, 400]\nx = \"c\"\ny = \"r\"\n{extra}"
        );
        let (streamed, held) = crate::common::streamed_and_held(&spec, &csv, "v", extra);
        for name in ["c", "r"] {
            assert_eq!(texts(&streamed, name), texts(&held, name), "{extra}: column {name}");
        }
        assert_eq!(numbers(&streamed, "rows"), numbers(&held, "rows"), "{extra}");
        let (a, b) = (numbers(&streamed, "value"), numbers(&held, "value"));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-9 * y.abs().max(1.0), "{extra}: {x} vs {y}");
        }
        let notes = crate::common::warning_texts;
        assert_eq!(notes(&streamed), notes(&held), "{extra}");
        assert_eq!(bars(&streamed).len(), bars(&held).len(), "{extra}");
        assert!(texts(&streamed, "r").iter().any(|r| r == "(missing)"), "{extra}");
        assert!(!texts(&held, "r").iter().any(|r| r == "-0"), "{extra}: −0 and 0 are one category");
    }
}
