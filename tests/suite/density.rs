//! Scatters in density mode: rows counted in bins, exactly (a brute-force count by the bins'
//! edges), the same grid whether the rows are read into memory or streamed through the source's
//! plan, the plan's transforms honoured, and bad input named.

use crate::common::{Fixture, numbers, seeded_uniform};
use dataink::mark::ChartOutput;
use dataink::scene::{Item, Role, Shape};

/// `n` seeded rows: x on a lattice of quarter steps (so values sit exactly on bin edges), y
/// spread, every 97th x missing, and a text column.
fn rows_csv(n: usize) -> String {
    let mut next = seeded_uniform();
    let mut csv = String::from("x,y,word\n");
    for i in 0..n {
        let x = if i % 97 == 0 { String::new() } else { format!("{}", (next() * 40.0).floor() / 4.0) };
        csv.push_str(&format!("{x},{:.5},w{}\n", next() * next() * 7.0, i % 3));
    }
    csv
}

fn spec(extra_source: &str, extra_chart: &str) -> String {
    format!(
        "[data.p]\npath = \"p.csv\"\n{extra_source}\n[[chart]]\nname = \"d\"\nkind = \"scatter\"\ndata = \"p\"\n\
         title = \"Rows\"\nx = \"x\"\ny = \"y\"\nmode = \"density\"\n{extra_chart}\n"
    )
}

fn draw(text: &str, csv: &str) -> (ChartOutput, bool) {
    let fixture = Fixture::new(text, &[("p.csv", csv.as_bytes())]);
    let loaded = fixture.load().unwrap_or_else(|e| panic!("{e}"));
    let in_plan = loaded.plans.contains_key("p");
    let out = dataink::pipeline::draw_chart(&loaded, 0, &loaded.spec.chart[0])
        .unwrap_or_else(|e| panic!("{}", loaded.source.render(&dataink::pipeline::mark_diagnostic(&loaded, &e))));
    (out, in_plan)
}

/// The non-empty bins as (x_from, x_to, y_from, y_to, rows).
fn bins(out: &ChartOutput) -> Vec<[f64; 5]> {
    let cols = ["x_from", "x_to", "y_from", "y_to", "rows"].map(|c| numbers(out, c));
    (0..cols[4].len()).map(|k| [cols[0][k], cols[1][k], cols[2][k], cols[3][k], cols[4][k]]).collect()
}

fn parsed(csv: &str) -> Vec<(Option<f64>, f64)> {
    csv.lines()
        .skip(1)
        .map(|l| {
            let mut parts = l.split(',');
            (parts.next().and_then(|x| x.parse().ok()), parts.next().and_then(|y| y.parse().ok()).unwrap_or(f64::NAN))
        })
        .collect()
}

#[test]
fn every_row_is_counted_once_in_the_bin_its_edges_say() {
    let csv = rows_csv(20_000);
    let (out, in_plan) = draw(&spec("", ""), &csv);
    assert!(in_plan, "a source only counted stays in its plan");
    let bins = bins(&out);
    let rows = parsed(&csv);
    let placed = rows.iter().filter(|(x, _)| x.is_some()).count();
    assert_eq!(bins.iter().map(|b| b[4]).sum::<f64>() as usize, placed);
    // Brute force: each row lies in exactly one listed bin, lower edge in, upper edge out (the
    // top bin of an axis also holding its upper end); every listed bin's count is matched.
    let (x_top, y_top) = bins.iter().fold((f64::MIN, f64::MIN), |(a, b), k| (a.max(k[1]), b.max(k[3])));
    let inside = |v: f64, lo: f64, hi: f64, top: f64| v >= lo && (v < hi || (hi == top && v <= hi));
    let mut found = vec![0usize; bins.len()];
    for (x, y) in rows.iter().filter_map(|(x, y)| Some((x.as_ref().copied()?, *y))) {
        let hits: Vec<usize> = (0..bins.len())
            .filter(|&k| inside(x, bins[k][0], bins[k][1], x_top) && inside(y, bins[k][2], bins[k][3], y_top))
            .collect();
        assert_eq!(hits.len(), 1, "row ({x}, {y}) is in bins {hits:?}");
        found[hits[0]] += 1;
    }
    assert_eq!(found.iter().map(|&c| c as f64).collect::<Vec<_>>(), bins.iter().map(|b| b[4]).collect::<Vec<_>>());
    let missing = rows.len() - placed;
    assert!(
        out.warnings.iter().any(|w| w.to_string()
            == format!("chart \"d\": dropped {missing} of {} rows with missing or non-finite values (`x`: {missing} missing or NaN)", rows.len())),
        "{:?}",
        out.warnings
    );
}

#[test]
fn rows_in_memory_and_rows_in_the_plan_give_the_same_grid() {
    let csv = rows_csv(30_000);
    let (streamed, in_plan) = draw(&spec("", ""), &csv);
    // A selection over the source needs its rows, so they are read into memory.
    let selected = "[selection.some]\ndata = \"p\"\nrange = { y = [0, 1] }\n";
    let (held, held_in_plan) = draw(&spec(selected, ""), &csv);
    assert!(in_plan && !held_in_plan);
    assert_eq!(bins(&streamed), bins(&held));
}

#[test]
fn the_plan_runs_the_sources_transforms_before_counting() {
    let csv = rows_csv(10_000);
    let source = "transform = [{ filter = \"y < 2\" }]\n";
    let text = spec("", "").replacen("path = \"p.csv\"\n", &format!("path = \"p.csv\"\n{source}"), 1);
    let (out, in_plan) = draw(&text, &csv);
    assert!(in_plan);
    let kept = parsed(&csv).iter().filter(|(x, y)| x.is_some() && *y < 2.0).count();
    assert_eq!(bins(&out).iter().map(|b| b[4]).sum::<f64>() as usize, kept);
}

#[test]
fn a_narrow_domain_counts_the_rows_outside_in_a_warning() {
    let csv = rows_csv(5_000);
    let (out, _) = draw(&spec("", "").replace("x = \"x\"", "x = { field = \"x\", domain = [0, 5] }"), &csv);
    let rows = parsed(&csv);
    let outside = rows.iter().filter(|(x, _)| x.is_some_and(|x| x > 5.0)).count();
    let placeable = rows.iter().filter(|(x, _)| x.is_some()).count();
    let text = format!("chart \"d\": left out {outside} of {placeable} rows whose `x` lies outside the domain [0, 5]");
    assert!(out.warnings.iter().any(|w| w.to_string() == text), "{:?}", out.warnings);
    assert!(bins(&out).iter().all(|b| b[1] <= 5.0 + 1e-9));
}

#[test]
fn rows_a_density_scatter_leaves_out_are_linted_per_column_and_axis() {
    // 20 rows: 10 placed, x missing twice and infinite once, y ≤ 0 three times on the log axis,
    // x outside the domain [0, 1] four times.
    let mut csv = String::from("x,y\n");
    for i in 0..10 {
        csv.push_str(&format!("{},{}\n", i as f64 / 10.0, 1 + i));
    }
    csv.push_str(",2\n,3\ninf,4\n0.5,0\n0.5,-1\n0.5,-2\n5,2\n5,3\n6,4\n7,5\n");
    let text = spec("", "")
        .replace("x = \"x\"", "x = { field = \"x\", domain = [0, 1] }")
        .replace("y = \"y\"", "y = { field = \"y\", scale = \"log\" }");
    let (out, in_plan) = draw(&text, &csv);
    assert!(in_plan);
    assert_eq!(bins(&out).iter().map(|b| b[4]).sum::<f64>(), 10.0);
    let findings = |spec: &str, code: &str| -> Vec<String> {
        crate::common::lint_findings(spec, &[("p.csv", csv.as_bytes())], code).into_iter().map(|f| f.message).collect()
    };
    assert_eq!(
        findings(&text, "DI004"),
        ["dropped 6 of 20 rows with missing or non-finite values or values ≤ 0 on a log axis \
          (`x`: 2 missing or NaN, 1 infinite; `y`: 3 ≤ 0 on a log axis)"]
    );
    let di003 = findings(&text, "DI003");
    assert!(di003.len() == 1 && di003[0].starts_with("3 of 20 values of `y` are ≤ 0"), "{di003:?}");
    let di005 = findings(&text, "DI005");
    assert!(di005.len() == 1 && di005[0].starts_with("4 of 14 rows lie outside the fixed domain [0, 1]"), "{di005:?}");
    // Held in memory (a selection needs the rows), each rule still speaks once.
    let held = format!("{text}\n[selection.some]\ndata = \"p\"\nrange = {{ y = [0, 1] }}\n");
    for code in ["DI003", "DI004", "DI005"] {
        assert_eq!(findings(&held, code).len(), 1, "{code} with the rows held");
    }
}

fn legend_labels(items: &[Item], out: &mut Vec<String>) {
    for item in items {
        match &item.shape {
            Shape::Text(t) if item.role == Role::Legend => out.push(t.content.clone()),
            Shape::Group { items, .. } => legend_labels(items, out),
            _ => {}
        }
    }
}

#[test]
fn the_legend_names_counts_under_every_shading() {
    let csv = rows_csv(20_000);
    for shading in ["eq_hist", "log", "linear"] {
        let (out, _) = draw(&spec("", &format!("shading = \"{shading}\"")), &csv);
        let mut labels = Vec::new();
        legend_labels(&out.scene.items, &mut labels);
        assert_eq!(labels.first().map(String::as_str), Some("rows per bin"), "{shading}: {labels:?}");
        let max = bins(&out).iter().map(|b| b[4]).fold(0.0, f64::max);
        let counts: Vec<f64> =
            labels[1..].iter().map(|l| l.parse::<f64>().unwrap_or_else(|_| panic!("{shading}: {l}"))).collect();
        assert!(counts.len() >= 2 && counts.iter().all(|&c| c >= 0.0 && c <= max), "{shading}: {counts:?} (max {max})");
        if shading != "linear" {
            assert_eq!(counts.iter().copied().fold(f64::MAX, f64::min), 1.0, "{shading}: the fewest rows a bin shows");
        }
    }
}

#[test]
fn text_columns_and_facets_are_refused_with_the_fix() {
    let csv = rows_csv(500);
    let fixture = Fixture::new(&spec("", "").replace("y = \"y\"", "y = \"word\""), &[("p.csv", csv.as_bytes())]);
    let err = fixture.draw().expect_err("text cannot be counted in bins");
    assert!(err.contains("column `word`") && err.contains("not numbers or times"), "{err}");
    let faceted = spec("", "facet = \"word\"");
    let err = Fixture::new(&faceted, &[("p.csv", csv.as_bytes())]).draw().expect_err("faceted density");
    assert!(err.contains("faceted scatter cannot be drawn in density mode"), "{err}");
}

#[test]
fn auto_mode_draws_points_up_to_the_threshold() {
    let csv = rows_csv(2_000);
    let fixture =
        Fixture::new(&spec("", "").replace("mode = \"density\"", "mode = \"auto\""), &[("p.csv", csv.as_bytes())]);
    let loaded = fixture.load().unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.plans.is_empty(), "2,000 rows are read and drawn as points");
    let out = dataink::pipeline::draw_chart(&loaded, 0, &loaded.spec.chart[0]).expect("draws");
    fn has_points(items: &[Item]) -> bool {
        items.iter().any(|i| {
            matches!(&i.shape, Shape::Points(_)) || matches!(&i.shape, Shape::Group { items, .. } if has_points(items))
        })
    }
    assert!(has_points(&out.scene.items));
}

#[test]
fn a_categorical_colour_mixes_in_the_bins_and_keys_its_categories() {
    let csv = rows_csv(20_000);
    let (out, in_plan) = draw(&spec("", "color = \"word\""), &csv);
    assert!(!in_plan, "colour categories are counted from rows in memory");
    let mut labels = Vec::new();
    legend_labels(&out.scene.items, &mut labels);
    for word in ["rows per bin", "word", "w0", "w1", "w2"] {
        assert!(labels.iter().any(|l| l == word), "{word} not in {labels:?}");
    }
    let placed = parsed(&csv).iter().filter(|(x, _)| x.is_some()).count();
    assert_eq!(bins(&out).iter().map(|b| b[4]).sum::<f64>() as usize, placed);
    assert!(!out.warnings.iter().any(|w| w.to_string().contains("`color`")), "{:?}", out.warnings);
}

#[test]
fn many_density_charts_of_one_streamed_source_render_in_parallel_without_waiting_on_each_other() {
    // More charts than cores: every drawing thread waits on its scan, and the scans' counting
    // must not need those threads (it once handed work to the same pool and hung for good).
    let csv = rows_csv(20_000);
    let mut text = String::from("[data.p]\npath = \"p.csv\"\n");
    for k in 0..8 {
        text.push_str(&format!(
            "\n[[chart]]\nname = \"d{k}\"\nkind = \"scatter\"\ndata = \"p\"\ntitle = \"Rows {k}\"\nx = \"x\"\ny = \"y\"\nmode = \"density\"\n"
        ));
    }
    let fixture = Fixture::new(&text, &[("p.csv", csv.as_bytes())]);
    let out = crate::common::run_dataink(
        fixture.dir.path(),
        &["render", "spec.toml", "--out", "out", "--format", "png", "--quiet"],
        120,
    )
    .expect("eight density charts of one source render within two minutes");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!((0..8).filter(|k| fixture.dir.path().join(format!("out/d{k}.png")).exists()).count(), 8);
}
