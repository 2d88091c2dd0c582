//! Bars of means, medians and counts with whiskers (`aggregate`, `error`) and value labels
//! (`labels`), against hand-computed numbers and geometry.

use crate::bar::{draw_err, draw_ok};
use crate::common::{axis_titles, bars, lint_codes, numbers, path_points, plot};
use dataink::mark::ChartOutput;
use dataink::scene::{Color, Item, Shape, Text};

/// The whiskers: (label, vertices).
fn whiskers(out: &ChartOutput) -> Vec<(String, Vec<(f64, f64)>)> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Some(label), Shape::Path(cmds)) = (item.label.as_deref(), &item.shape)
            && label.starts_with("error: ")
        {
            found.push((label.to_string(), path_points(cmds)));
        }
    });
    found
}

/// The value labels drawn on or beside the bars.
fn labels(out: &ChartOutput) -> Vec<Text> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if let (Some("bar value"), Shape::Text(t)) = (item.label.as_deref(), &item.shape) {
            found.push(t.clone());
        }
    });
    found
}

/// Group a: 2, 4, 4, 4, 5, 5, 7, 9 (mean 5, squared deviations 32, sd √(32/7), n 8); group b:
/// 1, 3 (mean 2, sd √2, sem 1).
const GROUPS: &str = "k,v\na,2\na,4\na,4\nb,1\na,4\na,5\na,5\nb,3\na,7\na,9\n";

#[test]
fn mean_bars_with_a_95_percent_interval_by_hand() {
    let out = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\naggregate = \"mean\"\nerror = \"ci95\"\n");
    assert_eq!(numbers(&out, "v"), vec![5.0, 2.0]);
    assert_eq!(numbers(&out, "rows"), vec![8.0, 2.0]);
    // a: t(0.975, 7) = 2.364624 times sem √(32/7)/√8; b: t(0.975, 1) = 12.706205 times 1.
    let half_a = 2.364_624_251_6 * (32.0f64 / 7.0).sqrt() / 8f64.sqrt();
    let half_b = 12.706_204_736_2;
    let (lower, upper) = (numbers(&out, "lower"), numbers(&out, "upper"));
    for (got, want) in
        lower.iter().zip([5.0 - half_a, 2.0 - half_b]).chain(upper.iter().zip([5.0 + half_a, 2.0 + half_b]))
    {
        assert!((got - want).abs() < 1e-8, "{got} vs {want}");
    }
    let csv = out.derived.to_csv(&Default::default());
    assert!(csv.starts_with("k,v,rows,lower,upper\na,5,8,"), "{csv}");
    assert!(axis_titles(&out).contains(&"Mean of v ± 95% CI".to_string()), "{:?}", axis_titles(&out));
    // The whiskers are centred on their bars, vertical, with caps, and the axis covers them:
    // b's reaches below zero (2 − 12.7) and above a's top.
    let p = plot(&out);
    let w = whiskers(&out);
    assert_eq!(w.len(), 2);
    let drawn = bars(&out);
    for ((label, points), (bar_label, rect, _)) in w.iter().zip(&drawn) {
        assert_eq!(label, &format!("error: {bar_label}"));
        let (x0, y0) = points[0];
        let (x1, y1) = points[1];
        assert!((x0 - (rect.x + rect.w / 2.0)).abs() < 1e-9 && x0 == x1, "{points:?}");
        assert!(y0 >= p.y - 1e-9 && y1 >= p.y - 1e-9 && y0 <= p.bottom() + 1e-9 && y1 <= p.bottom() + 1e-9);
        assert_eq!(points.len(), 6, "a line and two caps");
    }
    // Pixel lengths are proportional to the values: whisker a / bar a = 2·half_a / 5.
    let (rect_a, wa) = (drawn[0].1, &w[0].1);
    let ratio = (wa[0].1 - wa[1].1).abs() / rect_a.h;
    assert!((ratio - 2.0 * half_a / 5.0).abs() < 1e-9, "{ratio}");
}

#[test]
fn stdev_sem_minmax_and_median_by_hand() {
    let sd_a = (32.0f64 / 7.0).sqrt();
    let out = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\naggregate = \"mean\"\nerror = \"stdev\"\n");
    assert_eq!(numbers(&out, "lower"), vec![5.0 - sd_a, 2.0 - 2f64.sqrt()]);
    assert_eq!(numbers(&out, "upper"), vec![5.0 + sd_a, 2.0 + 2f64.sqrt()]);
    assert!(axis_titles(&out).contains(&"Mean of v ± 1 SD".to_string()));
    let out = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\naggregate = \"mean\"\nerror = \"sem\"\n");
    assert_eq!(numbers(&out, "lower"), vec![5.0 - sd_a / 8f64.sqrt(), 1.0]);
    let out = draw_ok(
        GROUPS,
        "x = \"k\"\ny = { field = \"v\", title = \"Value\" }\naggregate = \"median\"\nerror = \"minmax\"\n",
    );
    assert_eq!(numbers(&out, "v"), vec![4.5, 2.0]);
    assert_eq!(numbers(&out, "lower"), vec![2.0, 1.0]);
    assert_eq!(numbers(&out, "upper"), vec![9.0, 3.0]);
    assert!(axis_titles(&out).contains(&"Value, median with min–max".to_string()), "{:?}", axis_titles(&out));
    let out = draw_ok(GROUPS, "x = \"k\"\ny = \"v\"\naggregate = \"count\"\n");
    assert_eq!(numbers(&out, "v"), vec![8.0, 2.0]);
    assert!(axis_titles(&out).contains(&"Rows".to_string()));
}

#[test]
fn horizontal_error_bars_run_along_x() {
    let out = draw_ok(
        GROUPS,
        "x = \"k\"\ny = \"v\"\naggregate = \"mean\"\nerror = \"stdev\"\norientation = \"horizontal\"\n",
    );
    let p = plot(&out);
    let drawn = bars(&out);
    let w = whiskers(&out);
    let sd_a = (32.0f64 / 7.0).sqrt();
    for ((_, points), (_, rect, _)) in w.iter().zip(&drawn) {
        let ((x0, y0), (x1, y1)) = (points[0], points[1]);
        assert!(y0 == y1 && (y0 - (rect.y + rect.h / 2.0)).abs() < 1e-9, "horizontal whisker across the bar's middle");
        assert!(x0 < x1 && x0 >= p.x - 1e-9 && x1 <= p.right() + 1e-9);
    }
    // a: from 5 − sd to 5 + sd, in the bar's own pixels per unit (its width is 5 units).
    let per_unit = drawn[0].1.w / 5.0;
    let (x0, x1) = (w[0].1[0].0, w[0].1[1].0);
    assert!((x0 - (p.x + (5.0 - sd_a) * per_unit)).abs() < 1e-6 && (x1 - x0 - 2.0 * sd_a * per_unit).abs() < 1e-6);
}

#[test]
fn dodged_groups_get_whiskers_and_a_single_row_gets_none() {
    let csv = "k,g,v\na,p,1\na,p,3\na,q,2\na,q,6\nb,p,4\n";
    let out = draw_ok(csv, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\naggregate = \"mean\"\nerror = \"sem\"\n");
    let labels: Vec<String> = whiskers(&out).into_iter().map(|w| w.0).collect();
    assert_eq!(labels, ["error: a, p", "error: a, q"]);
    assert!(
        out.warnings.iter().any(|w| w.to_string().contains("1 of 3 bars combine a single row and have no whisker")),
        "{:?}",
        out.warnings
    );
    let lower = numbers(&out, "lower");
    assert_eq!(&lower[..2], &[1.0, 2.0]);
    assert!(lower[2].is_nan());
    let csv = out.derived.to_csv(&Default::default());
    assert!(csv.ends_with("b,p,4,1,,\n"), "{csv}");
}

#[test]
fn bad_input_gives_the_documented_errors() {
    let xy = "x = \"k\"\ny = \"v\"\n";
    let e = draw_err(GROUPS, &format!("{xy}error = \"ci95\"\n"));
    assert!(
        e.contains("`error = \"ci95\"` is a spread of the rows around a typical value, which a sum of the rows is not")
            && e.contains("set `aggregate = \"mean\"`"),
        "{e}"
    );
    let e = draw_err(GROUPS, &format!("{xy}aggregate = \"count\"\nerror = \"minmax\"\n"));
    assert!(
        e.contains("which a count of the rows is not") && e.contains("`aggregate = \"mean\"` or `\"median\"`"),
        "{e}"
    );
    let e = draw_err(
        "k,g,v\na,p,1\na,q,2\n",
        "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"stack\"\naggregate = \"mean\"\nerror = \"stdev\"\n",
    );
    assert!(e.contains("stacked bars end where the next begins") && e.contains("remove `stack`"), "{e}");
    let e = draw_err(GROUPS, &format!("{xy}aggregate = \"average\"\n"));
    assert!(e.contains("aggregate") && e.contains("average"), "{e}");
    let e = draw_err(GROUPS, &format!("{xy}error = \"ci99\"\n"));
    assert!(e.contains("error") && e.contains("ci99") && e.contains("did you mean"), "{e}");
    let e = draw_err(
        "k,g,v\na,p,1\na,q,2\n",
        "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"stack\"\nlabels = { position = \"outside\" }\n",
    );
    assert!(e.contains("stacked segments are labelled inside"), "{e}");
    let e = draw_err(GROUPS, &format!("{xy}labels = {{ decimals = 20 }}\n"));
    assert!(e.contains("decimals"), "{e}");
}

#[test]
fn labels_go_inside_where_they_fit_and_outside_otherwise() {
    // 100 fills the plot's height; 5 is 1/20 of it (about 15 px): too short for a 10.8 px label
    // with 4 px on each side, so its label goes above it.
    let out = draw_ok("k,v\ntall,100\nshort,5\n", "x = \"k\"\ny = \"v\"\nlabels = true\n");
    let drawn = bars(&out);
    let l = labels(&out);
    assert_eq!(l.iter().map(|t| t.content.as_str()).collect::<Vec<_>>(), ["100", "5"]);
    let (tall, short) = (drawn[0].1, drawn[1].1);
    let (inside, outside) = (&l[0], &l[1]);
    let size = 12.0 * 0.9;
    assert_eq!(inside.size, size);
    // Inside: centred across the bar, just under its top, in the colour that contrasts more
    // with the fill (the default blue takes white).
    assert!((inside.at.x - (tall.x + tall.w / 2.0)).abs() < 1e-9);
    assert!(inside.at.y > tall.y && inside.at.y < tall.y + 4.0 + size, "{} in {:?}", inside.at.y, tall);
    let fill = {
        let mut f = None;
        out.scene.walk(|item: &Item| {
            if item.label.as_deref() == Some("tall") {
                f = item.style.fill;
            }
        });
        f.expect("the tall bar")
    };
    assert_eq!(inside.color, dataink::guide::color::text_color_on(fill));
    // Outside: above the short bar's top, in the text colour, inside the plot.
    assert!(outside.at.y < short.y && outside.at.y > short.y - 4.0 - size, "{} over {:?}", outside.at.y, short);
    assert_eq!(outside.color, Color::rgb(0x22, 0x22, 0x22));
    // `position = "inside"` leaves the short bar's label out, with a warning; "outside" puts
    // both above their bars.
    let out = draw_ok("k,v\ntall,100\nshort,5\n", "x = \"k\"\ny = \"v\"\nlabels = { position = \"inside\" }\n");
    assert_eq!(labels(&out).len(), 1);
    assert!(out.warnings.iter().any(|w| w.to_string().contains("1 bar labels are left out")), "{:?}", out.warnings);
    let out = draw_ok("k,v\ntall,100\nshort,5\n", "x = \"k\"\ny = \"v\"\nlabels = { position = \"outside\" }\n");
    let (drawn, l) = (bars(&out), labels(&out));
    assert!(l.iter().zip(&drawn).all(|(t, (_, r, _))| t.at.y < r.y), "every label above its bar");
}

#[test]
fn the_value_axis_makes_room_for_labels_outside() {
    // Both bars end near the nice maximum: outside labels need room above 100.
    let out = draw_ok("k,v\na,100\nb,98\n", "x = \"k\"\ny = \"v\"\nlabels = { position = \"outside\" }\n");
    let p = plot(&out);
    let l = labels(&out);
    assert_eq!(l.len(), 2, "{:?}", out.warnings);
    for t in &l {
        let b = dataink::text::bounds(t);
        assert!(b.y >= p.y && b.bottom() <= p.bottom(), "{b:?} inside {p:?}");
    }
    // Horizontal: the labels sit right of the bars, inside the plot; negative values to the left.
    let out = draw_ok(
        "k,v\na,100\nb,-60\n",
        "x = \"k\"\ny = \"v\"\norientation = \"horizontal\"\nlabels = { position = \"outside\" }\n",
    );
    let (p, l, drawn) = (plot(&out), labels(&out), bars(&out));
    assert_eq!(l.iter().map(|t| t.content.as_str()).collect::<Vec<_>>(), ["100", "−60"]);
    assert!(l[0].at.x > drawn[0].1.right() && l[1].at.x < drawn[1].1.x);
    for t in &l {
        let b = dataink::text::bounds(t);
        assert!(b.x >= p.x && b.right() <= p.right(), "{b:?} inside {p:?}");
    }
}

#[test]
fn labels_beyond_whiskers_and_with_set_decimals() {
    let out = draw_ok(
        GROUPS,
        "x = \"k\"\ny = \"v\"\naggregate = \"mean\"\nerror = \"stdev\"\nlabels = { position = \"outside\", decimals = 2 }\n",
    );
    let l = labels(&out);
    assert_eq!(l.iter().map(|t| t.content.as_str()).collect::<Vec<_>>(), ["5.00", "2.00"]);
    for (t, (_, points)) in l.iter().zip(whiskers(&out)) {
        let top = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert!(dataink::text::bounds(t).bottom() < top, "the label clears the whisker's upper cap");
    }
}

#[test]
fn normalised_stack_labels_are_percentages_summing_to_100() {
    let csv = "k,g,v\na,p,1\na,q,2\na,r,5\nb,p,3\nb,q,1\n";
    let out = draw_ok(csv, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"normalize\"\nlabels = true\n");
    let l = labels(&out);
    let texts: Vec<&str> = l.iter().map(|t| t.content.as_str()).collect();
    assert_eq!(texts, ["12.5%", "25.0%", "62.5%", "75.0%", "25.0%"]);
    let share = |t: &str| t.trim_end_matches('%').parse::<f64>().expect("a number");
    assert_eq!(texts[..3].iter().map(|t| share(t)).sum::<f64>(), 100.0);
    assert_eq!(texts[3..].iter().map(|t| share(t)).sum::<f64>(), 100.0);
    // Each label sits in the middle of its segment.
    for (t, (_, r, _)) in l.iter().zip(bars(&out)) {
        assert!((t.at.y - (r.y + r.h / 2.0)).abs() < 1e-9 && (t.at.x - (r.x + r.w / 2.0)).abs() < 1e-9);
    }
    // A segment too thin for its label is skipped.
    let csv = "k,g,v\na,p,1\na,q,200\n";
    let out = draw_ok(csv, "x = \"k\"\ny = \"v\"\ncolor = \"g\"\nstack = \"stack\"\nlabels = true\n");
    assert_eq!(labels(&out).iter().map(|t| t.content.as_str()).collect::<Vec<_>>(), ["200"]);
}

#[test]
fn labelled_charts_lint_clean_of_text_overlaps() {
    let csv = "k,g,v\nalpha,p,12\nalpha,q,3\nbeta,p,7.5\nbeta,q,11\ngamma,p,0.5\ngamma,q,9\n";
    for extra in [
        "labels = true",
        "labels = { position = \"outside\" }",
        "orientation = \"horizontal\"\nlabels = true",
        "stack = \"stack\"\nlabels = true",
    ] {
        let spec = format!(
            "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"b\"\nkind = \"bar\"\ndata = \"d\"\ntitle = \"Values\"\n\
             x = {{ field = \"k\", title = \"Kind\" }}\ny = {{ field = \"v\", title = \"Value\" }}\ncolor = \"g\"\n{extra}\n"
        );
        let codes = lint_codes(&spec, &[("d.csv", csv.as_bytes())]);
        assert!(!codes.iter().any(|c| c.starts_with("LB")), "{extra}: {codes:?}");
    }
    // DI001 still reports bars cut from a non-zero baseline, with labels and whiskers on.
    let spec = "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"b\"\nkind = \"bar\"\ndata = \"d\"\ntitle = \"Values\"\n\
                x = { field = \"k\", title = \"Kind\" }\ny = { field = \"v\", title = \"Value\", zero = false }\n\
                aggregate = \"mean\"\nerror = \"sem\"\nlabels = true\n";
    let csv = "k,v\na,50\na,52\nb,60\nb,62\n";
    let codes = lint_codes(spec, &[("d.csv", csv.as_bytes())]);
    assert!(codes.contains(&"DI001"), "{codes:?}");
    // Bars of means from zero are honest: DI001 measures them by their means, not sums.
    let spec = spec
        .replace(", zero = false", "")
        .replace("error = \"sem\"\n", "error = \"sem\"\norientation = \"horizontal\"\n");
    let csv = "k,v\na,5\na,7\na,6\nb,-3\nb,-5\nb,-2\nc,12\nc,9\nd,1\n";
    let codes = lint_codes(&spec, &[("d.csv", csv.as_bytes())]);
    assert!(!codes.contains(&"DI001"), "{codes:?}");
}
