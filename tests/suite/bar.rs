//! The `bar` kind against hand-computed geometry: band positions, lengths from zero, grouping,
//! sums, the non-finite policy, negative values and bad input.

use crate::common::{Fixture, bars, derived_column, numbers, plot, tick_labels};
use dataink::mark::{ChartOutput, DerivedColumn};
use dataink::scene::{Item, Role, Shape};

/// A bar chart of `d.csv` (written from `csv`) with extra chart keys (600 × 400 px).
fn spec(extra: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"b\"\nkind = \"bar\"\ndata = \"d\"\nsize = [600, 400]\n{extra}"
    )
}

pub fn draw(csv: &str, extra: &str) -> Result<ChartOutput, String> {
    Fixture::new(&spec(extra), &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

pub fn draw_ok(csv: &str, extra: &str) -> ChartOutput {
    draw(csv, extra).unwrap_or_else(|e| panic!("{e}"))
}

pub fn draw_err(csv: &str, extra: &str) -> String {
    match draw(csv, extra) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// Three categories whose rows sum to 30, 40 and 20 (a: 10 + 20).
const SUMS: &str = "k,v\na,10\nb,40\nc,20\na,20\n";

#[test]
fn bars_sit_in_equal_bands_with_lengths_proportional_to_the_sums() {
    let out = draw_ok(SUMS, "x = \"k\"\ny = \"v\"\n");
    let p = plot(&out);
    // The value axis runs from 0 to the nice 40, so the bar of b fills the plot's height.
    assert_eq!(tick_labels(&out, "y axis").last().map(String::as_str), Some("40"));
    let bars = bars(&out);
    let labels: Vec<&str> = bars.iter().map(|b| b.0.as_str()).collect();
    assert_eq!(labels, ["a", "b", "c"], "categories in order of first appearance");
    // Band scale: 3 bands, inner padding 0.2 and outer 0.1 of the step; step = width / 3.
    let step = p.w / 3.0;
    for (i, (_, r, _)) in bars.iter().enumerate() {
        assert!(close(r.x, p.x + step * (0.1 + i as f64)), "bar {i} starts at {}", r.x);
        assert!(close(r.w, step * 0.8), "bar {i} is {} wide", r.w);
        assert!(close(r.bottom(), p.bottom()), "bar {i} rises from zero at the plot's bottom");
    }
    for ((_, r, _), sum) in bars.iter().zip([30.0, 40.0, 20.0]) {
        assert!(close(r.h, p.h * sum / 40.0), "{} vs {}", r.h, p.h * sum / 40.0);
    }
    // The rows of a are both in its bar; the y title says the rows were summed.
    assert_eq!(bars[0].2, vec![0, 3]);
    let mut titles = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Role::AxisTitle, Shape::Text(t)) = (&item.role, &item.shape) {
            titles.push(t.content.clone());
        }
    });
    assert!(titles.contains(&"Sum of v".to_string()), "{titles:?}");
}

#[test]
fn derived_csv_has_one_row_per_bar_with_its_sum_and_row_count() {
    let out = draw_ok(SUMS, "x = \"k\"\ny = \"v\"\n");
    let csv = out.derived.to_csv(&Default::default());
    assert_eq!(csv, "k,v,rows\na,30,2\nb,40,1\nc,20,1\n");
}

#[test]
fn colour_groups_bars_side_by_side_with_a_legend() {
    // Category a has groups p and q, b only q: b's p slot stays empty.
    let csv = "k,g,v\na,p,1\na,q,2\nb,q,4\na,p,1\n";
    let out = draw_ok(csv, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\n");
    let p = plot(&out);
    let bars = bars(&out);
    let labels: Vec<&str> = bars.iter().map(|b| b.0.as_str()).collect();
    assert_eq!(labels, ["a, p", "a, q", "b, q"]);
    let step = p.w / 2.0;
    let (band, bandwidth) = (|i: f64| p.x + step * (0.1 + i), step * 0.8);
    // Two groups in a band: inner step = bandwidth / (2 − 0.1), bars 0.9 of it wide.
    let inner = bandwidth / 1.9;
    assert!(close(bars[0].1.x, band(0.0)) && close(bars[0].1.w, inner * 0.9));
    assert!(close(bars[1].1.x, band(0.0) + inner) && close(bars[1].1.w, inner * 0.9));
    assert!(close(bars[2].1.x, band(1.0) + inner), "b's q bar keeps q's place");
    // Sums: a/p = 1 + 1 = 2, a/q = 2: equal heights; b/q = 4 twice as tall.
    assert!(close(bars[0].1.h, bars[1].1.h));
    assert!(close(bars[2].1.h, 2.0 * bars[1].1.h));
    assert_ne!(bars[0].1.h, 0.0);
    // Each group has its own colour, and the legend names both.
    let fill = |i: usize| {
        let mut fills = Vec::new();
        out.scene.walk(|item: &Item| {
            if item.role == Role::DataMark && matches!(item.shape, Shape::Rect(_)) {
                fills.push(item.style.fill);
            }
        });
        fills[i]
    };
    assert_ne!(fill(0), fill(1));
    assert_eq!(fill(1), fill(2));
    let mut legend = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Role::Legend, Shape::Text(t)) = (&item.role, &item.shape) {
            legend.push(t.content.clone());
        }
    });
    assert!(legend.contains(&"p".to_string()) && legend.contains(&"q".to_string()), "{legend:?}");
    let csv = out.derived.to_csv(&Default::default());
    assert_eq!(csv, "k,g,v,rows\na,p,2,2\na,q,2,1\nb,q,4,1\n");
}

#[test]
fn numbers_on_x_are_categories_in_ascending_order() {
    let out = draw_ok("cyl,n\n8,1\n4,3\n6,2\n4,1\n", "x = \"cyl\"\ny = \"n\"\n");
    let labels: Vec<String> = bars(&out).into_iter().map(|b| b.0).collect();
    assert_eq!(labels, ["4", "6", "8"]);
    assert_eq!(tick_labels(&out, "x axis"), ["4", "6", "8"]);
    let DerivedColumn::Number(sums) = derived_column(&out, "n") else { panic!("numbers") };
    assert_eq!(sums, &[4.0, 2.0, 1.0]);
}

#[test]
fn non_finite_values_are_dropped_with_the_usual_warning() {
    // c's only row is NaN: c disappears; a keeps its finite row.
    let out = draw_ok("k,v\na,10\na,NaN\nb,20\nc,inf\n", "x = \"k\"\ny = \"v\"\n");
    let labels: Vec<String> = bars(&out).into_iter().map(|b| b.0).collect();
    assert_eq!(labels, ["a", "b"]);
    assert!(
        out.warnings.iter().any(|w| w.to_string().contains("dropped 2 of 4 rows")
            && w.to_string().contains("`v`: 1 missing or NaN, 1 infinite")),
        "{:?}",
        out.warnings
    );
    assert_eq!(out.derived.to_csv(&Default::default()), "k,v,rows\na,10,1\nb,20,1\n");
}

#[test]
fn negative_sums_hang_below_a_zero_line() {
    let out = draw_ok("k,v\na,30\nb,-10\n", "x = \"k\"\ny = \"v\"\n");
    let p = plot(&out);
    let bars = bars(&out);
    // Both bars meet at zero: a's bottom is b's top.
    assert!(close(bars[0].1.bottom(), bars[1].1.y));
    let zero = bars[0].1.bottom();
    assert!(zero > p.y && zero < p.bottom(), "zero inside the plot");
    assert!(close(bars[0].1.h, 3.0 * bars[1].1.h), "lengths 30 and 10");
    let mut baseline = false;
    out.scene.walk(|item: &Item| baseline |= item.role == Role::Axis && item.label.as_deref() == Some("baseline"));
    assert!(baseline, "a zero line separates positive and negative bars");
}

#[test]
fn without_zero_bars_start_at_the_bottom_of_the_axis() {
    // zero = false with a fixed domain [40, 70]: lengths are value − 40.
    let out = draw_ok("k,v\na,50\nb,60\n", "x = \"k\"\ny = { field = \"v\", domain = [40, 70] }\n");
    let p = plot(&out);
    let bars = bars(&out);
    for ((_, r, _), v) in bars.iter().zip([50.0, 60.0]) {
        assert!(close(r.bottom(), p.bottom()));
        assert!(close(r.h, p.h * (v - 40.0) / 30.0), "{} vs {}", r.h, p.h * (v - 40.0) / 30.0);
    }
}

#[test]
fn bad_input_gives_the_documented_errors() {
    let xy = "x = \"k\"\ny = \"v\"\n";
    let e = draw_err("k,v\n", xy);
    assert!(e.contains("error: chart \"b\": data \"d\" has no rows"), "{e}");
    let e = draw_err("k,v\na,NaN\nb,\n", xy);
    assert!(e.contains("error: chart \"b\": no rows left to plot out of 2"), "{e}");
    let e = draw_err("k,v\na,x\n", xy);
    assert!(e.contains("column `v` holds text; a bar's length needs numbers"), "{e}");
    let e = draw_err(SUMS, "x = \"k\"\ny = { field = \"v\", scale = \"log\" }\n");
    assert!(e.contains("a bar's length is measured from zero, which a log scale does not have"), "{e}");
    let e = draw_err("n,v\n1,2\n", "x = { field = \"n\", scale = \"linear\" }\ny = \"v\"\n");
    assert!(e.contains("bars place every x value in its own band, so x cannot have a linear scale"), "{e}");
    let e = draw_err("k,g,v\na,1,2\n", "x = \"k\"\ny = \"v\"\ncolor = { field = \"g\", type = \"continuous\" }\n");
    assert!(e.contains("bars are grouped by colour, which needs categories"), "{e}");
    let e = draw_err(SUMS, "x = \"kk\"\ny = \"v\"\n");
    assert!(e.contains("has no column `kk`") && e.contains("did you mean `k`?"), "{e}");
    // 1000 categories do not fit 600 px: refused before anything is laid out.
    let many: String = std::iter::once("k,v\n".to_string()).chain((0..1000).map(|i| format!("c{i},1\n"))).collect();
    let e = draw_err(&many, xy);
    assert!(e.contains("1000 categories do not fit a 600 px wide chart"), "{e}");
}

#[test]
fn many_narrow_bars_draw_with_a_warning() {
    let many: String = std::iter::once("k,v\n".to_string()).chain((0..400).map(|i| format!("c{i},{i}\n"))).collect();
    let out = draw_ok(&many, "x = \"k\"\ny = \"v\"\n");
    assert_eq!(bars(&out).len(), 399, "the zero bar has no length");
    assert!(out.warnings.iter().any(|w| w.to_string().contains("too narrow to see")), "{:?}", out.warnings);
    // Tick labels are thinned so they do not overlap.
    let shown = tick_labels(&out, "x axis").len();
    assert!(shown > 1 && shown < 400, "{shown} labels");
}

#[test]
fn dates_are_categories_and_missing_text_is_its_own() {
    let out = draw_ok("d,v\n2015-01-02,1\n2015-01-01,2\n2015-01-02,3\n", "x = \"d\"\ny = \"v\"\n");
    let labels: Vec<String> = bars(&out).into_iter().map(|b| b.0).collect();
    assert_eq!(labels, ["2015-01-01", "2015-01-02"], "dates ascending, summed per day");
    assert_eq!(out.derived.to_csv(&Default::default()), "d,v,rows\n2015-01-01,2,1\n2015-01-02,4,2\n");
    let out = draw_ok("k,v\n,5\nb,1\na,2\n", "x = \"k\"\ny = \"v\"\n");
    let labels: Vec<String> = bars(&out).into_iter().map(|b| b.0).collect();
    assert_eq!(labels, ["b", "a", "(missing)"]);
}

/// Barley-like rows (yield, variety, year, site): variety totals Manchuria 700, Glabron 450,
/// Trebi 650.
const BARLEY: &str = "yield,variety,year,site\n300,Manchuria,1931,Morris\n400,Manchuria,1932,Crookston\n\
                      200,Glabron,1931,Morris\n250,Glabron,1932,Crookston\n350,Trebi,1931,Morris\n300,Trebi,1932,Crookston\n";

/// The labels of the bars that carry a clip mark, from the marks' own labels.
fn clip_marked(out: &ChartOutput) -> Vec<String> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Role::DataMark, Shape::Path(_), Some(label)) = (&item.role, &item.shape, &item.label)
            && let Some(bar) = label.strip_prefix(dataink::mark::cartesian::bar::CLIPPED_PREFIX)
        {
            found.push(bar.to_string());
        }
    });
    found
}

#[test]
fn bars_past_a_fixed_domain_are_cut_with_a_mark_a_warning_and_di005() {
    let extra = "x = \"variety\"\ny = { field = \"yield\", domain = [0, 600] }\n";
    let out = draw_ok(BARLEY, extra);
    let p = plot(&out);
    let drawn = bars(&out);
    let top = |name: &str| drawn.iter().find(|(l, _, _)| l == name).map(|(_, r, _)| r.y).expect("bar");
    // The cut bars end at the top of the plot; Glabron (450) at three quarters of it.
    assert!((top("Manchuria") - p.y).abs() < 1e-9 && (top("Trebi") - p.y).abs() < 1e-9);
    assert!((top("Glabron") - (p.y + p.h * 0.25)).abs() < 1e-6, "{} vs {p:?}", top("Glabron"));
    assert_eq!(clip_marked(&out), ["Manchuria", "Trebi"], "only the cut bars carry the mark");
    assert_eq!(
        out.warnings.iter().map(ToString::to_string).collect::<Vec<_>>(),
        ["chart \"b\": 2 of 3 bars reach past the y domain [0, 600] and are cut at its end (marked with a break); \
          widen `domain` to cover [450, 700], or remove it"]
    );
    let svg = dataink::render::svg::to_svg(&out.scene);
    assert_eq!(svg.matches("clipped: ").count(), 2, "the marks reach the SVG");

    let files: &[(&str, &[u8])] = &[("d.csv", BARLEY.as_bytes())];
    let di005 = crate::common::lint_findings(&spec(extra), files, "DI005");
    assert_eq!(di005.len(), 1, "{di005:?}");
    assert_eq!(
        di005[0].message,
        "2 of 3 bars have totals outside the fixed domain [0, 600] of the y axis (totals: 450 to 700) and are cut at its end"
    );
}

#[test]
fn a_domain_leaving_zero_out_is_judged_by_the_bar_totals_not_the_rows() {
    // Every row (200 to 400) lies below 450, but every total (450 to 700) is inside the domain.
    let extra = "x = \"variety\"\ny = { field = \"yield\", domain = [450, 800] }\n";
    let files: &[(&str, &[u8])] = &[("d.csv", BARLEY.as_bytes())];
    assert!(crate::common::lint_findings(&spec(extra), files, "DI005").is_empty());
    assert!(clip_marked(&draw_ok(BARLEY, extra)).is_empty());
}

/// Two categories, two groups: a = 10 (g) + 30 (h); b = 20 (g) + 20 (h) + 40 (h again).
const GROUPS: &str = "k,g,v\na,g,10\na,h,30\nb,g,20\nb,h,20\nb,h,40\n";

#[test]
fn stacked_bars_reach_the_category_totals_and_normalised_ones_100() {
    let out = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"stack\"");
    assert_eq!(numbers(&out, "from"), [0.0, 10.0, 0.0, 20.0]);
    assert_eq!(numbers(&out, "to"), [10.0, 40.0, 20.0, 80.0]);
    // Each stack fills its band: the bars of one category share x and width.
    let drawn = bars(&out);
    assert_eq!(drawn[0].1.x, drawn[1].1.x);
    assert_eq!(drawn[0].1.w, drawn[1].1.w);
    assert!((drawn[1].1.y + drawn[1].1.h - drawn[0].1.y).abs() < 1e-9, "h sits on g");
    let norm = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"normalize\"");
    let to = numbers(&norm, "to");
    assert!((to[1] - 100.0).abs() < 1e-9 && (to[3] - 100.0).abs() < 1e-9, "{to:?}");
    assert!((to[0] - 25.0).abs() < 1e-9 && (to[2] - 25.0).abs() < 1e-9, "{to:?}");
    assert!(tick_labels(&norm, "y axis").contains(&"100".to_string()));
}

#[test]
fn negative_sums_stack_downwards_and_categories_sort_by_total() {
    let out = draw_ok("k,g,v\na,g,10\na,h,-5\na,i,-3\n", "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"stack\"");
    assert_eq!(numbers(&out, "from"), [0.0, 0.0, -5.0]);
    assert_eq!(numbers(&out, "to"), [10.0, -5.0, -8.0]);
    let sorted = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\nsort = \"descending\"");
    let DerivedColumn::Text(k) = derived_column(&sorted, "k") else { panic!() };
    assert_eq!(k, &["b", "a"], "b totals 80, a 40");
    let ascending = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\nsort = \"ascending\"");
    let DerivedColumn::Text(k) = derived_column(&ascending, "k") else { panic!() };
    assert_eq!(k, &["a", "b"]);
}

#[test]
fn normalising_without_groups_is_refused() {
    let e = draw_err(GROUPS, "x = \"k\"\ny = \"v\"\nstack = \"normalize\"");
    assert!(e.contains("the chart has no `color`"), "{e}");
}

#[test]
fn horizontal_bars_run_right_from_zero_with_the_first_category_on_top() {
    let out = draw_ok(SUMS, "x = \"k\"\ny = \"v\"\norientation = \"horizontal\"\n");
    let p = plot(&out);
    let drawn = bars(&out);
    let labels: Vec<&str> = drawn.iter().map(|b| b.0.as_str()).collect();
    assert_eq!(labels, ["a", "b", "c"]);
    // Every bar starts at the plot's left edge (zero) and its length is proportional to its sum.
    assert!(drawn.iter().all(|(_, r, _)| close(r.x, p.x)), "{drawn:?}");
    let per_unit = drawn[0].1.w / 30.0;
    assert!(close(drawn[1].1.w, 40.0 * per_unit) && close(drawn[2].1.w, 20.0 * per_unit));
    // Equal bands down the plot, a on top.
    assert!(drawn[0].1.y < drawn[1].1.y && drawn[1].1.y < drawn[2].1.y);
    assert!(close(drawn[1].1.y - drawn[0].1.y, drawn[2].1.y - drawn[1].1.y));
    assert!(close(drawn[0].1.h, drawn[1].1.h));
    // The categories label the y axis, the values the x axis.
    assert_eq!(tick_labels(&out, "y axis"), ["c", "b", "a"], "bottom to top");
    assert_eq!(tick_labels(&out, "x axis").first().map(String::as_str), Some("0"));
}

#[test]
fn horizontal_normalised_stacks_fill_the_plot_and_di001_reads_their_lengths() {
    let csv = "k,g,v\na,p,1\na,q,3\nb,p,2\nb,q,2\n";
    let out =
        draw_ok(csv, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"normalize\"\norientation = \"horizontal\"\n");
    let p = plot(&out);
    for category in ["a", "b"] {
        let width: f64 = bars(&out).iter().filter(|b| b.0.starts_with(category)).map(|b| b.1.w).sum();
        assert!((width - p.w).abs() < 1e-6, "{category}: {width} of {}", p.w);
    }
    // A value axis that leaves zero out is reported whichever way the bars run.
    let codes = crate::common::lint_codes(
        &spec("x = \"k\"\ny = { field = \"v\", zero = false }\norientation = \"horizontal\"\n"),
        &[("d.csv", SUMS.as_bytes())],
    );
    assert!(codes.contains(&"DI001"), "{codes:?}");
    let honest = crate::common::lint_findings(
        &spec("x = \"k\"\ny = \"v\"\norientation = \"horizontal\"\n"),
        &[("d.csv", SUMS.as_bytes())],
        "DI001",
    );
    assert!(honest.is_empty(), "{honest:?}");
}

/// `n` seeded rows: a text category `k` (first seen in a row whose `v` is missing; some cells
/// empty), a colour `c`, a numeric key `g` (with NaN), a date `day` and whole-number values `v`
/// (sums exact in any order), every 101st cell empty and every 499th `inf`.
fn many_rows(n: usize) -> String {
    let mut next = crate::common::seeded_uniform();
    let names = ["zeta", "alpha", "mid", "", "beta", "alpha", "mid"];
    let mut csv = String::from("k,c,g,day,v\n");
    for i in 0..n {
        let k = if i == 0 { "zeta" } else { names[(next() * 7.0) as usize] };
        let c = ["red", "blue", "green"][i % 3];
        let g = if i % 997 == 0 { "NaN".to_string() } else { format!("{}", (i % 5) as f64 * 0.5 - 1.0) };
        let day = format!("2024-{:02}-01", 1 + i % 12);
        let v = match i {
            0 => String::new(),
            _ if i % 101 == 0 => String::new(),
            _ if i % 499 == 0 => "inf".to_string(),
            _ => format!("{}", (next() * 100.0).floor() - 20.0),
        };
        csv.push_str(&format!("{k},{c},{g},{day},{v}\n"));
    }
    csv
}

#[test]
fn bars_of_rows_left_in_the_plan_equal_the_bars_of_rows_in_memory() {
    // More rows than the count from which a source's rows stay in its plan.
    let csv = many_rows(240_000);
    for extra in [
        "x = \"k\"\ny = \"v\"\n",
        "x = \"k\"\ny = \"v\"\ncolor = \"c\"\nstack = \"stack\"\nlabels = true\n",
        "x = \"g\"\ny = \"v\"\naggregate = \"mean\"\nerror = \"ci95\"\n",
        "x = \"k\"\ny = \"v\"\naggregate = \"median\"\nerror = \"minmax\"\norientation = \"horizontal\"\n",
        "x = \"day\"\ny = \"v\"\naggregate = \"count\"\ncolor = \"g\"\nsort = \"descending\"\n",
    ] {
        let (streamed, held) = crate::common::streamed_and_held(&spec(extra), &csv, "v", extra);
        let field = |out: &ChartOutput, name: &str| match derived_column(out, name) {
            DerivedColumn::Text(v) => v.clone(),
            DerivedColumn::Number(v) => v.iter().map(|x| format!("{x}")).collect(),
            other => panic!("{other:?}"),
        };
        for name in
            ["k", "g", "day", "c", "rows"].into_iter().filter(|n| extra.contains(&format!("\"{n}\"")) || *n == "rows")
        {
            assert_eq!(field(&streamed, name), field(&held, name), "{extra}: column {name}");
        }
        for name in ["v", "lower", "upper"].into_iter().filter(|n| *n == "v" || extra.contains("error")) {
            let (a, b) = (numbers(&streamed, name), numbers(&held, name));
            assert_eq!(a.len(), b.len(), "{extra}: column {name}");
            for (x, y) in a.iter().zip(&b) {
                assert!(
                    (x - y).abs() <= 1e-9 * y.abs().max(1.0) || (x.is_nan() && y.is_nan()),
                    "{extra}: {name} {x} vs {y}"
                );
            }
        }
        let notes = crate::common::warning_texts;
        assert_eq!(notes(&streamed), notes(&held), "{extra}");
        assert!(notes(&streamed).iter().any(|w| w.contains("dropped ") && w.contains("of 240000 rows")), "{extra}");
        let (a, b) = (bars(&streamed), bars(&held));
        assert_eq!(a.len(), b.len(), "{extra}");
        for ((la, ra, _), (lb, rb, _)) in a.iter().zip(&b) {
            assert_eq!(la, lb, "{extra}");
            assert!(
                (ra.x - rb.x).abs() < 1e-6 && (ra.w - rb.w).abs() < 1e-6 && (ra.h - rb.h).abs() < 1e-6,
                "{extra}: {la}"
            );
        }
    }
}

#[test]
fn a_bar_chart_of_rows_left_in_the_plan_sums_what_a_hand_count_gives() {
    // 300,000 rows: category i % 3, value i % 10 (a fifth of them missing), so each sum is known.
    let mut csv = String::from("k,v\n");
    for i in 0..300_000u64 {
        let v = if i % 5 == 4 { String::new() } else { (i % 10).to_string() };
        csv.push_str(&format!("k{},{v}\n", i % 3));
    }
    let (streamed, _) = crate::common::streamed_and_held(&spec("x = \"k\"\ny = \"v\"\n"), &csv, "v", "sums");
    let expected: Vec<f64> = (0..3u64)
        .map(|k| (0..300_000u64).filter(|i| i % 3 == k && i % 5 != 4).map(|i| (i % 10) as f64).sum())
        .collect();
    assert_eq!(numbers(&streamed, "v"), expected);
    assert_eq!(numbers(&streamed, "rows"), [80_000.0; 3]);
    let note = streamed.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n");
    assert!(note.contains("dropped 60000 of 300000 rows") && note.contains("`v`: 60000 missing"), "{note}");
    // DI001 reads the values of bars that carry no rows from the chart's derived table.
    let cut = spec("x = \"k\"\ny = { field = \"v\", zero = false }\n");
    let findings = crate::common::lint_findings(&cut, &[("d.csv", csv.as_bytes())], "DI001");
    assert_eq!(findings.len(), 1, "{findings:?}");
    // DI005 reads the totals from the derived table, rows held or not: each sum is 320,000.
    let capped = spec("x = \"k\"\ny = { field = \"v\", domain = [0, 300000] }\n");
    let findings = crate::common::lint_findings(&capped, &[("d.csv", csv.as_bytes())], "DI005");
    assert_eq!(findings.len(), 1, "{findings:?}");
    assert!(findings[0].message.contains("3 of 3 bars have totals outside"), "{}", findings[0].message);
}

#[test]
fn bars_of_rows_left_in_the_plan_refuse_what_bars_of_rows_in_memory_refuse() {
    let mut csv = String::from("k,t,v\n");
    for i in 0..210_000 {
        csv.push_str(&format!("k{},w{},{}\n", i % 4, i % 3, if i % 2 == 0 { "" } else { "1" }));
    }
    // A text value column: named, whether the rows are held or not.
    let err = draw_err(&csv, "x = \"k\"\ny = \"t\"\n");
    assert!(err.contains("`t`"), "{err}");
    // Every row dropped: the no-rows error with what the rows lack.
    let none = csv.replace(",1\n", ",inf\n");
    let err = draw_err(&none, "x = \"k\"\ny = \"v\"\n");
    assert!(err.contains("no rows left to plot out of 210000") && err.contains("`v`"), "{err}");
    // `normalize` without colour groups is refused before any scan.
    let err = draw_err(&csv, "x = \"k\"\ny = \"v\"\nstack = \"normalize\"\n");
    assert!(err.contains("has no `color`"), "{err}");
}
