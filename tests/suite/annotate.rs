//! Annotations (`[[chart.annotate]]`): rules, bands, text and arrows land where the frame's
//! scales put their values, the axes widen to show them, their labels keep clear of each other,
//! lint sees their labels, and values the axes cannot place are errors at their place in the spec.

use crate::common::{Fixture, lint_findings, plot};
use dataink::mark::ChartOutput;
use dataink::scene::{Item, PathCmd, Point, Rect, Role, Shape, Text};

/// Draw one chart of `keys` over `csv`, with `notes` (`[[chart.annotate]]` tables) after them.
fn draw(keys: &str, csv: &str, notes: &str) -> Result<ChartOutput, String> {
    Fixture::new(&spec(keys, notes), &[("d.csv", csv.as_bytes())]).draw().map(|mut v| v.remove(0))
}

fn spec(keys: &str, notes: &str) -> String {
    format!("[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\ndata = \"d\"\n{keys}\n\n{notes}")
}

const SCATTER: &str = "kind = \"scatter\"\nx = \"x\"\ny = \"y\"";
const POINTS: &str = "x,y\n0,0\n2,3\n4,1\n6,8\n8,5\n10,10\n";

/// The tick labels of `axis` with their positions along it.
fn ticks(out: &ChartOutput, axis: &str) -> Vec<(String, f64)> {
    let mut found = Vec::new();
    out.scene.walk(|item: &Item| {
        if item.role == Role::TickLabel
            && item.label.as_deref() == Some(axis)
            && let Shape::Text(t) = &item.shape
        {
            found.push((t.content.clone(), if axis == "x axis" { t.at.x } else { t.at.y }));
        }
    });
    found
}

/// The pixel of value `v` on a numeric axis, from its first and last tick labels.
fn pixel_of(out: &ChartOutput, axis: &str, v: f64) -> f64 {
    let t = ticks(out, axis);
    let ((a, pa), (b, pb)) = (&t[0], &t[t.len() - 1]);
    let (a, b): (f64, f64) = (a.parse().expect("numeric tick"), b.parse().expect("numeric tick"));
    pa + (v - a) * (pb - pa) / (b - a)
}

/// The annotation items whose label is `name` (e.g. `"annotate[0] rule"`).
fn named<'a>(out: &'a ChartOutput, name: &str) -> Vec<&'a Item> {
    let mut found = Vec::new();
    out.scene.walk(|item: &'a Item| {
        if item.label.as_deref() == Some(name) {
            found.push(item);
        }
    });
    found
}

/// The two ends of a straight path.
fn ends(item: &Item) -> (Point, Point) {
    match &item.shape {
        Shape::Path(cmds) => match cmds.as_slice() {
            [PathCmd::MoveTo(a), PathCmd::LineTo(b)] => (*a, *b),
            other => panic!("not a straight line: {other:?}"),
        },
        other => panic!("not a path: {other:?}"),
    }
}

fn text_of(item: &Item) -> &Text {
    match &item.shape {
        Shape::Text(t) => t,
        other => panic!("not text: {other:?}"),
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

#[test]
fn a_rule_lands_on_the_pixel_its_value_maps_to() {
    let out = draw(SCATTER, POINTS, "[[chart.annotate]]\ny = 7\nlabel = \"target\"\n").unwrap();
    let (a, b) = ends(named(&out, "annotate[0] rule")[0]);
    let want = pixel_of(&out, "y axis", 7.0);
    assert!(close(a.y, want) && close(b.y, want), "rule at {a:?}–{b:?}, y = 7 maps to {want}");
    let p = plot(&out);
    assert_eq!((a.x, b.x), (p.x, p.right()), "across the whole plot");
    let label = text_of(named(&out, "annotate[0] label")[0]);
    assert_eq!(label.content, "target");
    let bounds = dataink::text::bounds(label);
    assert!(p.contains_rect(&bounds, 0.0), "label {bounds:?} inside the plot {p:?}");
    assert!(bounds.bottom() <= want && bounds.bottom() > want - 8.0, "just above its line: {bounds:?}");
    assert!(bounds.right() > p.right() - 8.0, "at the right end: {bounds:?}");
}

#[test]
fn the_axis_widens_to_show_a_rule_outside_the_data() {
    let plain = draw(SCATTER, POINTS, "").unwrap();
    let top =
        |out: &ChartOutput| ticks(out, "y axis").iter().map(|(l, _)| l.parse::<f64>().unwrap()).fold(0.0, f64::max);
    assert!(top(&plain) < 50.0);
    let out = draw(SCATTER, POINTS, "[[chart.annotate]]\ny = 50\n").unwrap();
    assert!(top(&out) >= 50.0, "{:?}", ticks(&out, "y axis"));
    let (a, _) = ends(named(&out, "annotate[0] rule")[0]);
    let p = plot(&out);
    assert!(a.y >= p.y && a.y <= p.bottom(), "rule at {} inside the plot {p:?}", a.y);
    assert!(close(a.y, pixel_of(&out, "y axis", 50.0)));
}

#[test]
fn a_fixed_domain_is_kept_and_what_lies_outside_it_is_cut_off() {
    // The explorer zooms the same way: by fixing the domain of the channels.
    let keys = "kind = \"scatter\"\nx = \"x\"\ny = { field = \"y\", domain = [0, 10] }";
    let notes = "[[chart.annotate]]\ny = 50\nlabel = \"off the top\"\n\n\
                 [[chart.annotate]]\ntext = \"also off\"\nat = [5, 50]\n\n\
                 [[chart.annotate]]\narrow = [[5, 50], [5, 5]]\nlabel = \"from above\"\n\n\
                 [[chart.annotate]]\ny = [8, 20]\nlabel = \"high\"\n";
    let out = draw(keys, POINTS, notes).unwrap();
    let top = ticks(&out, "y axis").iter().map(|(l, _)| l.parse::<f64>().unwrap()).fold(0.0, f64::max);
    assert_eq!(top, 10.0, "the domain is kept");
    for i in 0..3 {
        assert!(named(&out, &format!("annotate[{i}] label")).is_empty(), "no label for annotation {i} outside");
    }
    assert_eq!(named(&out, "annotate[2] arrow").len(), 1, "the arrow's visible part is drawn");
    let p = plot(&out);
    let high = dataink::text::bounds(text_of(named(&out, "annotate[3] label")[0]));
    assert!(p.contains_rect(&high, 0.0) && high.bottom() <= pixel_of(&out, "y axis", 8.0), "{high:?} in {p:?}");
}

#[test]
fn a_band_spans_the_mapped_range_under_the_data() {
    let notes = "[[chart.annotate]]\ny = [6, 2]\nlabel = \"normal\"\ncolor = \"steelblue\"\nopacity = 0.3\n";
    let out = draw(SCATTER, POINTS, notes).unwrap();
    let band = named(&out, "annotate[0] band")[0];
    let Shape::Rect(r) = band.shape else { panic!("a rectangle") };
    let (top, bottom) = (pixel_of(&out, "y axis", 6.0), pixel_of(&out, "y axis", 2.0));
    assert!(close(r.y, top) && close(r.bottom(), bottom), "{r:?} spans {top}–{bottom}");
    let p = plot(&out);
    assert_eq!((r.x, r.w), (p.x, p.w));
    assert_eq!(band.style.fill.map(|c| c.a), Some(77), "opacity 0.3");
    // Bands are drawn before the data, so they tint the background, not the points.
    let order: Vec<Role> = out.scene.items.iter().map(|i| i.role).collect();
    let band_at = order.iter().position(|r| *r == Role::Annotation).unwrap();
    let data_at = order.iter().position(|r| *r == Role::DataMark).unwrap();
    assert!(band_at < data_at, "{order:?}");
    let label = dataink::text::bounds(text_of(named(&out, "annotate[0] label")[0]));
    assert!(label.y >= top && label.bottom() <= bottom, "label {label:?} inside the band");
}

const DAYS: &str = "date,v\n2010-01-01,1\n2012-05-01,4\n2016-01-01,3\n";

#[test]
fn a_date_rule_lands_between_its_year_ticks() {
    let keys = "kind = \"line\"\nx = \"date\"\ny = \"v\"";
    let out = draw(keys, DAYS, "[[chart.annotate]]\nx = \"2013-07-02\"\nlabel = \"mid 2013\"\n").unwrap();
    let (a, b) = ends(named(&out, "annotate[0] rule")[0]);
    assert!(close(a.x, b.x), "vertical");
    let t = ticks(&out, "x axis");
    let at = |year: &str| t.iter().find(|(l, _)| l == year).unwrap_or_else(|| panic!("tick {year} in {t:?}")).1;
    let (y2013, y2014) = (at("2013"), at("2014"));
    assert!(y2013 < a.x && a.x < y2014, "{} between {y2013} and {y2014}", a.x);
    // 2 July is day 182 of 365: half way through the year, to the pixel.
    let expected = y2013 + (y2014 - y2013) * 182.0 / 365.0;
    assert!((a.x - expected).abs() < 0.01, "{} vs {expected}", a.x);
}

#[test]
fn a_category_rule_sits_at_the_band_centre() {
    let keys = "kind = \"bar\"\nx = \"k\"\ny = \"v\"";
    let csv = "k,v\na,1\nb,3\nc,2\n";
    let out = draw(keys, csv, "[[chart.annotate]]\nx = \"b\"\n\n[[chart.annotate]]\nx = [\"a\", \"b\"]\n").unwrap();
    let (a, _) = ends(named(&out, "annotate[0] rule")[0]);
    let t = ticks(&out, "x axis");
    let centre = |k: &str| t.iter().find(|(l, _)| l == k).unwrap().1;
    assert!(close(a.x, centre("b")), "{} vs {}", a.x, centre("b"));
    // A band over categories covers their bars, edge to edge.
    let Shape::Rect(band) = named(&out, "annotate[1] band")[0].shape else { panic!("a rectangle") };
    let bars = crate::common::bars(&out);
    let edge = |k: &str| bars.iter().find(|(l, ..)| l.contains(k)).map(|(_, r, _)| *r).unwrap();
    assert!(close(band.x, edge("a").x) && close(band.right(), edge("b").right()), "{band:?} vs {bars:?}");
}

#[test]
fn an_arrow_points_from_its_tail_to_its_head() {
    let notes = "[[chart.annotate]]\narrow = [[2, 8], [6, 8]]\nlabel = \"rise\"\n";
    let out = draw(SCATTER, POINTS, notes).unwrap();
    let (tail, end) = ends(named(&out, "annotate[0] arrow")[0]);
    let (x2, x6, y8) = (pixel_of(&out, "x axis", 2.0), pixel_of(&out, "x axis", 6.0), pixel_of(&out, "y axis", 8.0));
    assert!(close(tail.x, x2) && close(tail.y, y8), "{tail:?}");
    assert!(end.x < x6 && end.x > x6 - 12.0, "the shaft stops at the arrowhead: {end:?}");
    let Shape::Path(head) = &named(&out, "annotate[0] arrowhead")[0].shape else { panic!("a path") };
    assert!(matches!(head[0], PathCmd::MoveTo(p) if close(p.x, x6) && close(p.y, y8)), "{head:?}");
    // The label sits left of the tail, away from the head.
    let label = dataink::text::bounds(text_of(named(&out, "annotate[0] label")[0]));
    assert!(label.right() <= tail.x && label.y < y8 && label.bottom() > y8, "{label:?}");
}

#[test]
fn labels_of_two_close_rules_do_not_overlap() {
    let notes = "[[chart.annotate]]\ny = 5\nlabel = \"at 5\"\n\n[[chart.annotate]]\ny = 5.2\nlabel = \"at 5.2\"\n\n\
                 [[chart.annotate]]\nx = 4\nlabel = \"start\"\n\n[[chart.annotate]]\nx = 4.1\nlabel = \"end\"\n";
    let spec = format!("{}\n", spec(&format!("{SCATTER}\ntitle = \"t\"\ncaption = \"c\""), notes));
    let fixture = Fixture::new(&spec, &[("d.csv", POINTS.as_bytes())]);
    let out = fixture.draw().unwrap().remove(0);
    let p = plot(&out);
    let boxes: Vec<Rect> =
        (0..4).map(|i| dataink::text::bounds(text_of(named(&out, &format!("annotate[{i}] label"))[0]))).collect();
    for (i, a) in boxes.iter().enumerate() {
        assert!(p.contains_rect(a, 0.0), "label {i} {a:?} inside the plot");
        for b in &boxes[i + 1..] {
            assert!(!dataink::text::boxes_overlap(a, b), "{a:?} overlaps {b:?}");
        }
    }
    // No label crosses the other rule's line either.
    let (a, _) = ends(named(&out, "annotate[1] rule")[0]);
    assert!(boxes[0].bottom() <= a.y || boxes[0].y >= a.y, "label 0 {:?} crosses the line at {}", boxes[0], a.y);
    let codes: Vec<&str> = fixture.lint().unwrap().iter().flat_map(|c| c.findings.iter().map(|f| f.code)).collect();
    assert!(!codes.contains(&"LB002") && !codes.contains(&"LB003"), "{codes:?}");
}

#[test]
fn lint_reports_colliding_and_clipped_annotation_text() {
    let notes = "[[chart.annotate]]\ntext = \"Recession\"\nat = [5, 5]\n\n[[chart.annotate]]\ntext = \"Recovery\"\nat = [5, 5]\n";
    let overlaps = lint_findings(&spec(SCATTER, notes), &[("d.csv", POINTS.as_bytes())], "LB002");
    assert_eq!(overlaps.len(), 1, "{overlaps:?}");
    assert!(overlaps[0].message.contains("the label \"Recession\" overlaps the label \"Recovery\""), "{overlaps:?}");
    let long = "a very long note ".repeat(12);
    let notes = format!("[[chart.annotate]]\ny = 5\nlabel = \"{long}\"\n");
    let clipped = lint_findings(&spec(SCATTER, &notes), &[("d.csv", POINTS.as_bytes())], "LB003");
    assert_eq!(clipped.len(), 1, "{clipped:?}");
    assert!(clipped[0].message.contains("runs") && clipped[0].message.contains("a very long note"), "{clipped:?}");
}

#[test]
fn text_is_written_at_its_point_and_kept_on_the_canvas() {
    let notes = "[[chart.annotate]]\ntext = \"peak\"\nat = [6, 8]\nanchor = \"start\"\n\n\
                 [[chart.annotate]]\ntext = \"far right\"\nat = [10, 0]\n";
    let out = draw(SCATTER, POINTS, notes).unwrap();
    let peak = text_of(named(&out, "annotate[0] label")[0]);
    assert!(close(peak.at.x, pixel_of(&out, "x axis", 6.0)) && close(peak.at.y, pixel_of(&out, "y axis", 8.0)));
    assert_eq!(peak.anchor, dataink::scene::Anchor::Start);
    // Centred on the plot's corner it would stick out; it moves just inside.
    let edge = dataink::text::bounds(text_of(named(&out, "annotate[1] label")[0]));
    let p = plot(&out);
    assert!(p.contains_rect(&edge, 1e-9), "{edge:?} in {p:?}");
    assert!(close(edge.right(), p.right()) && close(edge.bottom(), p.bottom()), "{edge:?} {p:?}");
}

#[test]
fn values_an_axis_cannot_place_are_errors_at_their_key() {
    let line = "kind = \"line\"\nx = \"date\"\ny = \"v\"";
    let notes = "[[chart.annotate]]\ny = 2\n\n[[chart.annotate]]\nx = \"2012-01-01\"\n\n[[chart.annotate]]\nx = \"2014-13-01\"\n";
    let err = draw(line, DAYS, notes).unwrap_err();
    assert!(err.contains("chart \"c\": annotate[2].x: `\"2014-13-01\"` is not a date"), "{err}");
    assert!(err.contains("spec.toml:18:5"), "points at the value: {err}");
    assert!(err.contains("ISO 8601"), "{err}");
    let err = draw(line, DAYS, "[[chart.annotate]]\nx = 2014\n").unwrap_err();
    assert!(err.contains("annotate[0].x: `2014` is a number, but the x axis shows dates"), "{err}");
    let err = draw(line, DAYS, "[[chart.annotate]]\ny = \"high\"\n").unwrap_err();
    assert!(err.contains("annotate[0].y: `\"high\"` is text, but the y axis is numeric"), "{err}");
    let err = draw(line, DAYS, "[[chart.annotate]]\ntext = \"a\"\nat = [\"2012-01-01\", \"x\"]\n").unwrap_err();
    assert!(err.contains("annotate[0].at[1]: `\"x\"` is text"), "{err}");
    let bar = "kind = \"bar\"\nx = \"k\"\ny = \"v\"";
    let err = draw(bar, "k,v\napple,1\npear,2\n", "[[chart.annotate]]\nx = [\"apple\", \"peer\"]\n").unwrap_err();
    assert!(err.contains("annotate[0].x[1]: `\"peer\"` is not a category of the x axis"), "{err}");
    assert!(err.contains("did you mean `pear`?"), "{err}");
    let err = draw(SCATTER, POINTS, "[[chart.annotate]]\ny = 1\ncolor = \"blurple\"\n").unwrap_err();
    assert!(err.contains("annotate[0].color: `blurple` is not a colour"), "{err}");
    let err = draw(SCATTER, POINTS, "[[chart.annotate]]\narrow = [[1, 1], [1, 1]]\n").unwrap_err();
    assert!(err.contains("annotate[0].arrow: the arrow's two points are less than a pixel apart"), "{err}");
}

#[test]
fn the_spec_check_names_misspelt_and_misplaced_keys() {
    let load = |keys: &str, notes: &str| {
        Fixture::new(&spec(keys, notes), &[("d.csv", POINTS.as_bytes())]).load().map(|_| ()).unwrap_err()
    };
    let err = load(SCATTER, "[[chart.annotate]]\ny = 1\nlable = \"x\"\n");
    assert!(err.contains("unknown key `lable` in `annotate[0]` of chart \"c\""), "{err}");
    assert!(err.contains("did you mean `label`?"), "{err}");
    let err = load(SCATTER, "[[chart.annotate]]\nx = 1\ny = 2\n");
    assert!(err.contains("`annotate[0]` of chart \"c\" has both `x` and `y`"), "{err}");
    let err = load(SCATTER, "[[chart.annotate]]\ny = 1\nopacity = 0.5\n");
    assert!(err.contains("is a rule and does not take `opacity`"), "{err}");
    assert!(err.contains("`opacity` is for bands"), "{err}");
    let err = load(SCATTER, "[[chart.annotate]]\ny = [1, 2, 3]\n");
    assert!(err.contains("`annotate[0].y` must be"), "{err}");
    let err = load("kind = \"parallel\"\ncolumns = [\"x\", \"y\"]", "[[chart.annotate]]\ny = 1\n");
    assert!(err.contains("`annotate` is not drawn by `parallel` charts"), "{err}");
    assert!(err.contains("scatter, line, area, bar, histogram"), "{err}");
}

#[test]
fn kinds_in_one_frame_draw_annotations() {
    let cases = [
        ("kind = \"histogram\"\nx = \"y\"", "[[chart.annotate]]\nx = 5\n"),
        ("kind = \"area\"\nx = \"x\"\ny = \"y\"", "[[chart.annotate]]\ny = [2, 4]\n"),
        ("kind = \"box\"\ny = \"y\"\norientation = \"horizontal\"", "[[chart.annotate]]\nx = 5\n"),
        ("kind = \"line\"\nx = \"x\"\ny = \"y\"", "[[chart.annotate]]\ntext = \"t\"\nat = [1, 1]\n"),
    ];
    for (keys, notes) in cases {
        let out = draw(keys, POINTS, notes).unwrap_or_else(|e| panic!("{keys}: {e}"));
        assert!(
            !named(&out, "annotations").is_empty()
                || !named(&out, "annotations under the data").is_empty()
                || !named(&out, "annotation labels").is_empty(),
            "{keys}"
        );
    }
}
