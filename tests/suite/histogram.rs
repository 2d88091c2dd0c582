//! The `histogram` kind against known answers: bin counts (numpy's edges), counts summing to the
//! rows, densities integrating to one, cumulative ends, stacked and grouped bars, the domain,
//! the selection, and bad input.

use crate::common::{Fixture, bars, numbers, plot, texts};
use dataink::mark::ChartOutput;

/// A histogram of `d.csv` (written from `csv`) with extra chart keys.
fn spec(extra: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"h\"\nkind = \"histogram\"\ndata = \"d\"\nsize = [600, 400]\n{extra}"
    )
}

fn draw(csv: &str, extra: &str) -> Result<ChartOutput, String> {
    Fixture::new(&spec(extra), &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

fn draw_ok(csv: &str, extra: &str) -> ChartOutput {
    draw(csv, extra).unwrap_or_else(|e| panic!("{e}"))
}

fn draw_err(csv: &str, extra: &str) -> String {
    match draw(csv, extra) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// The iris sepal lengths (examples/data/iris.csv) as a one-column CSV.
fn sepal_lengths() -> String {
    let iris = std::fs::read_to_string(crate::common::root().join("examples/data/iris.csv")).unwrap();
    let mut csv = String::from("x,species\n");
    for line in iris.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        csv.push_str(&format!("{},{}\n", cells[0], cells[4]));
    }
    csv
}

#[test]
fn exact_bins_count_as_numpy_histogram_does() {
    // np.histogram(sepal_length, bins="fd") and bins=10 (scripts/histogram_reference.py).
    let csv = sepal_lengths();
    let fd = draw_ok(&csv, "x = \"x\"\nbins = \"fd\"\nnice = false");
    assert_eq!(numbers(&fd, "count"), [11.0, 30.0, 24.0, 24.0, 31.0, 17.0, 7.0, 6.0]);
    assert!(close(numbers(&fd, "bin_start")[0], 4.3));
    assert!(close(*numbers(&fd, "bin_end").last().unwrap(), 7.9));
    let ten = draw_ok(&csv, "x = \"x\"\nbins = 10\nnice = false");
    assert_eq!(numbers(&ten, "count"), [9.0, 23.0, 14.0, 27.0, 16.0, 26.0, 18.0, 6.0, 5.0, 6.0]);
}

#[test]
fn counts_sum_to_the_rows_and_bars_are_proportional_to_them() {
    let csv = sepal_lengths();
    let out = draw_ok(&csv, "x = \"x\"");
    let counts = numbers(&out, "count");
    assert_eq!(counts.iter().sum::<f64>(), 150.0);
    // Nice edges: round numbers one step apart, covering 4.3 .. 7.9.
    let (start, end) = (numbers(&out, "bin_start"), numbers(&out, "bin_end"));
    let step = end[0] - start[0];
    assert!(start[0] <= 4.3 && *end.last().unwrap() >= 7.9);
    assert!(start.iter().zip(end).all(|(s, e)| close(e - s, step)));
    assert!(close((start[0] / step).round() * step, start[0]), "start {} is a multiple of {step}", start[0]);
    // Bar heights in pixels are proportional to the counts (one bar per non-empty bin).
    let drawn = bars(&out);
    let nonzero: Vec<f64> = counts.iter().copied().filter(|&c| c > 0.0).collect();
    assert_eq!(drawn.len(), nonzero.len());
    let per_row = drawn[0].1.h / nonzero[0];
    for ((_, rect, rows), count) in drawn.iter().zip(&nonzero) {
        assert!((rect.h - per_row * count).abs() < 1e-6);
        assert_eq!(rows.len() as f64, *count);
    }
    // Bars stand on the plot's bottom.
    let p = plot(&out);
    assert!(drawn.iter().all(|(_, r, _)| (r.y + r.h - p.bottom()).abs() < 1e-6));
}

#[test]
fn densities_integrate_to_one_and_cumulative_bars_end_at_the_total() {
    let csv = sepal_lengths();
    for extra in ["", "\nnice = false\nbins = 7", "\nstep = 0.3"] {
        let out = draw_ok(&csv, &format!("x = \"x\"\nstat = \"density\"{extra}"));
        let (start, end, height) = (numbers(&out, "bin_start"), numbers(&out, "bin_end"), numbers(&out, "height"));
        let area: f64 = (0..height.len()).map(|k| height[k] * (end[k] - start[k])).sum();
        assert!(close(area, 1.0), "{extra}: area {area}");
    }
    let cumulative = draw_ok(&csv, "x = \"x\"\ncumulative = true");
    assert_eq!(*numbers(&cumulative, "height").last().unwrap(), 150.0);
    let proportion = draw_ok(&csv, "x = \"x\"\ncumulative = true\nstat = \"density\"");
    assert!(close(*numbers(&proportion, "height").last().unwrap(), 1.0));
    let heights = numbers(&proportion, "height");
    assert!(heights.windows(2).all(|w| w[0] <= w[1]), "cumulative heights never fall");
}

#[test]
fn stacked_groups_reach_the_height_of_the_whole() {
    let csv = sepal_lengths();
    let whole = draw_ok(&csv, "x = \"x\"\nstep = 0.5");
    let stacked = draw_ok(&csv, "x = \"x\"\nstep = 0.5\ncolor = \"species\"");
    // Each bin's stacked bars add up to the ungrouped bar's height (the legend narrows the plot
    // of the grouped chart, not its height).
    let stack_heights = |out: &ChartOutput| {
        let mut by_left: std::collections::BTreeMap<i64, f64> = Default::default();
        for (_, r, _) in bars(out) {
            *by_left.entry((r.x * 1000.0).round() as i64).or_insert(0.0) += r.h;
        }
        by_left.into_values().collect::<Vec<f64>>()
    };
    let (a, b) = (stack_heights(&whole), stack_heights(&stacked));
    assert_eq!(a.len(), b.len());
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-6), "{a:?} vs {b:?}");
    // Percentages of stacked groups are of all rows: they sum to 100.
    let percent = draw_ok(&csv, "x = \"x\"\ncolor = \"species\"\nstat = \"percent\"");
    assert!(close(numbers(&percent, "height").iter().sum::<f64>(), 100.0));
    assert_eq!(
        texts(&percent, "species").iter().filter(|s| *s == "setosa").count(),
        numbers(&percent, "count").len() / 3
    );
}

#[test]
fn layered_and_dodged_groups_are_each_normalised_and_dodged_bars_share_their_bin() {
    let csv = sepal_lengths();
    let layered = draw_ok(&csv, "x = \"x\"\ncolor = \"species\"\nstat = \"percent\"\nposition = \"layer\"");
    let groups = texts(&layered, "species");
    let heights = numbers(&layered, "height");
    for species in ["setosa", "versicolor", "virginica"] {
        let sum: f64 = groups.iter().zip(&heights).filter(|(g, _)| *g == species).map(|(_, h)| h).sum();
        assert!(close(sum, 100.0), "{species}: {sum}");
    }
    let dodged = draw_ok(&csv, "x = \"x\"\ncolor = \"species\"\nposition = \"dodge\"\nstep = 0.5");
    let whole = draw_ok(&csv, "x = \"x\"\nstep = 0.5");
    let bin_width = bars(&whole)[0].1.w + 1.0; // the bar plus its one-pixel gap
    let mut drawn = bars(&dodged);
    drawn.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));
    for pair in drawn.windows(2) {
        assert!(pair[0].1.x + pair[0].1.w <= pair[1].1.x + 1e-6, "dodged bars do not overlap");
    }
    for (_, r, _) in &drawn {
        assert!(r.w < bin_width / 3.0 + 1e-6);
    }
}

#[test]
fn a_domain_bins_only_its_range_and_says_what_it_left_out() {
    let csv = "x\n1\n2\n3\n4\n50\n";
    let out = draw_ok(csv, "x = { field = \"x\", domain = [0, 10] }\nbins = 5\nnice = false");
    assert_eq!(numbers(&out, "count").iter().sum::<f64>(), 4.0);
    assert!(close(numbers(&out, "bin_start")[0], 0.0));
    assert!(close(*numbers(&out, "bin_end").last().unwrap(), 10.0));
    let text: Vec<String> = out.warnings.iter().map(|w| w.to_string()).collect();
    assert!(text.iter().any(|w| w.contains("left out 1 of 5 rows")), "{text:?}");
    let e = draw_err(csv, "x = { field = \"x\", domain = [100, 200] }");
    assert!(e.contains("no value of `x` lies in the domain [100, 200]"), "{e}");
}

#[test]
fn a_selection_is_drawn_over_the_whole_distribution() {
    let csv = sepal_lengths();
    let spec = format!(
        "{}\nx = \"x\"\nstep = 0.5\nhighlight = \"big\"\n\n[selection.big]\ndata = \"d\"\nrange = {{ x = [6.5, 8] }}\n",
        spec("")
    );
    let out = Fixture::new(&spec, &[("d.csv", csv.as_bytes())]).draw().unwrap().remove(0);
    let drawn = bars(&out);
    let (context, selected): (Vec<_>, Vec<_>) = drawn.iter().partition(|(label, _, _)| label.ends_with("(all rows)"));
    assert_eq!(context.iter().map(|(_, _, rows)| rows.len()).sum::<usize>(), 150);
    let chosen: usize = selected.iter().map(|(_, _, rows)| rows.len()).sum();
    let expected = csv.lines().skip(1).filter(|l| l.split(',').next().unwrap().parse::<f64>().unwrap() >= 6.5).count();
    assert_eq!(chosen, expected);
    // Each selected bar is no taller than the whole bar of its bin and stands on the same base.
    for (_, s, _) in &selected {
        let whole = context.iter().find(|(_, c, _)| (c.x - s.x).abs() < 1e-6).expect("a whole bar under it");
        assert!(s.h <= whole.1.h + 1e-6 && (s.y + s.h - whole.1.y - whole.1.h).abs() < 1e-6);
    }
}

#[test]
fn non_finite_values_are_dropped_with_the_shared_warning() {
    let out = draw_ok("x\n1\nNaN\n2\n\n3\n", "x = \"x\"");
    assert_eq!(numbers(&out, "count").iter().sum::<f64>(), 3.0);
    assert!(out.warnings.iter().any(|w| w.to_string().contains("dropped 2 of 5 rows")), "{:?}", out.warnings);
}

#[test]
fn bad_input_gets_the_documented_errors() {
    let text = draw_err("x\na\nb\n", "x = \"x\"");
    assert!(text.contains("holds text; binning needs numbers"), "{text}");
    let dates = draw_err("x\n2020-01-01\n2020-02-01\n", "x = \"x\"");
    assert!(dates.contains("holds dates or times"), "{dates}");
    let log = draw_err("x\n1\n10\n", "x = { field = \"x\", scale = \"log\" }");
    assert!(log.contains("equal widths on a linear axis"), "{log}");
    let both = draw_err("x\n1\n10\n", "x = \"x\"\nbins = 5\nstep = 1");
    assert!(both.contains("`bins` and `step` both set the bins"), "{both}");
    let tiny = draw_err("x\n0\n100\n", "x = \"x\"\nstep = 0.01");
    assert!(tiny.contains("makes 10000 bins"), "{tiny}");
    let zero = draw_err("x\n0\n100\n", "x = \"x\"\nbins = 0");
    assert!(zero.contains("bins"), "{zero}");
    let missing = draw_err("y\n1\n", "x = \"x\"");
    assert!(missing.contains("no column `x`"), "{missing}");
}

/// `n` seeded rows of `x`: a quarter-step lattice (values on bin edges, many ties), a long
/// continuous tail, every 101st cell empty and every 499th `inf`.
fn many_rows(n: usize) -> String {
    let mut next = crate::common::seeded_uniform();
    let mut csv = String::from("x\n");
    for i in 0..n {
        let x = match i {
            _ if i % 101 == 0 => String::new(),
            _ if i % 499 == 0 => "inf".to_string(),
            _ if i % 3 == 0 => format!("{}", (next() * 40.0).floor() / 4.0),
            _ => format!("{}", -next().ln() * 2.5),
        };
        csv.push_str(&x);
        csv.push('\n');
    }
    csv
}

/// The histogram drawn with its rows streamed through the source's plan, and drawn from the
/// same rows held in memory.
fn streamed_and_held(csv: &str, extra: &str) -> (ChartOutput, ChartOutput) {
    crate::common::streamed_and_held(&spec(extra), csv, "x", extra)
}

#[test]
fn a_histogram_of_rows_left_in_the_plan_equals_the_one_of_rows_in_memory() {
    // More rows than the count from which a source's rows stay in its plan.
    let csv = many_rows(240_000);
    for extra in [
        "x = \"x\"\n",
        "x = \"x\"\nbins = \"fd\"\nnice = false\nstat = \"density\"\n",
        "x = \"x\"\nbins = \"sturges\"\ncumulative = true\nstat = \"percent\"\n",
        "x = { field = \"x\", domain = [1.3, 7.7] }\nstep = 0.5\n",
        "x = { field = \"x\", domain = [1.3, 7.7] }\nbins = 17\nnice = false\n",
    ] {
        let (streamed, held) = streamed_and_held(&csv, extra);
        for column in ["bin_start", "bin_end", "count", "height"] {
            assert_eq!(numbers(&streamed, column), numbers(&held, column), "{extra}: column {column}");
        }
        let notes = crate::common::warning_texts;
        assert_eq!(notes(&streamed), notes(&held), "{extra}");
        let dropped = (0..240_000).filter(|i| i % 101 == 0 || i % 499 == 0).count();
        let said = format!("dropped {dropped} of 240000 rows");
        assert!(notes(&streamed).iter().any(|w| w.contains(&said)), "{extra}: {:?}", notes(&streamed));
        assert_eq!(bars(&streamed).len(), bars(&held).len(), "{extra}");
    }
}

#[test]
fn a_streamed_histogram_names_a_column_it_cannot_bin() {
    let mut csv = String::from("x,t\n");
    for i in 0..210_000 {
        csv.push_str(&format!("{},w{}\n", i % 10, i % 3));
    }
    let err = draw_err(&csv, "x = \"t\"\n");
    assert!(err.contains("`t`"), "{err}");
    let err = draw_err(&csv, "x = { field = \"x\", domain = [20, 30] }\n");
    assert!(err.contains("no value of `x` lies in the domain [20, 30]"), "{err}");
}

#[test]
fn rows_left_out_by_a_domain_are_linted_when_the_rows_stay_in_the_plan() {
    let csv = many_rows(240_000);
    let extra = "x = { field = \"x\", domain = [1.3, 7.7] }\nstep = 0.5\n";
    let (streamed, held) = streamed_and_held(&csv, extra);
    let left_out = |out: &ChartOutput| {
        out.warnings.iter().find_map(|w| match w {
            dataink::mark::Warning::OutsideDomain { outside, rows, .. } => Some((*outside, *rows)),
            _ => None,
        })
    };
    assert_eq!(left_out(&streamed), left_out(&held));
    let (outside, rows) = left_out(&streamed).expect("the domain leaves rows out");
    for out in [&streamed, &held] {
        let note = out.warnings.iter().map(|w| w.to_string()).find(|w| w.contains("outside the domain")).unwrap();
        assert!(note.starts_with("chart \"h\": left out"), "the note names its chart: {note}");
    }
    let findings = crate::common::lint_findings(&spec(extra), &[("d.csv", csv.as_bytes())], "DI005");
    assert_eq!(findings.len(), 1, "{findings:?}");
    let said = format!("{outside} of {rows} rows lie outside the fixed domain [1.3, 7.7]");
    assert!(findings[0].message.contains(&said), "{}", findings[0].message);
}
