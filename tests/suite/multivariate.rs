//! Multivariate kinds (splom, parallel, daisy, faces, segments) and selections: linking by row
//! identity, geometric invariants, and bad input giving the documented results.

use crate::common::Fixture;
use dataink::mark::ChartOutput;
use dataink::scene::{Item, Shape};

/// A small iris-like table with a text column, a constant column and one NaN cell (row 5).
const DATA: &str = "a,b,c,k,kind\n\
1,10,5,7,x\n\
2,8,6,7,y\n\
3,9,4,7,x\n\
4,4,7,7,z\n\
5,5,3,7,y\n\
6,NaN,2,7,x\n\
7,2,1,7,z\n\
8,1,8,7,x\n";

fn spec(charts: &str) -> String {
    format!(
        r#"
[data.t]
path = "t.csv"

[selection.low]
data = "t"
range = {{ a = [2, 4.5] }}

{charts}
"#
    )
}

fn draw(charts: &str) -> Result<Vec<ChartOutput>, String> {
    Fixture::new(&spec(charts), &[("t.csv", DATA.as_bytes())]).draw()
}

fn draw_ok(charts: &str) -> Vec<ChartOutput> {
    draw(charts).unwrap_or_else(|e| panic!("{e}"))
}

fn draw_err(charts: &str) -> String {
    match draw(charts) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

/// Every data-mark leaf item of a scene, depth first.
fn leaves(out: &ChartOutput) -> Vec<&Item> {
    let mut found = Vec::new();
    out.scene.walk(|item| {
        if item.role == dataink::scene::Role::DataMark && !matches!(item.shape, Shape::Group { .. }) {
            found.push(item);
        }
    });
    found
}

/// Rows drawn in colour (not grey context) by point batches.
fn batches(out: &ChartOutput) -> Vec<(bool, Vec<u32>)> {
    leaves(out)
        .into_iter()
        .filter_map(|i| match &i.shape {
            Shape::Points(_) => Some((i.label.as_deref().is_some_and(|l| l.contains("not selected")), i.rows.clone())),
            _ => None,
        })
        .collect()
}

#[test]
fn a_selection_links_every_cell_of_a_splom_by_row() {
    let out = draw_ok(
        r#"[[chart]]
name = "m"
kind = "splom"
data = "t"
columns = ["a", "b", "c"]
highlight = "low""#,
    );
    // Row 5 has a NaN and is dropped; rows 1, 2, 3 have a in [2, 4.5].
    let cells: Vec<Vec<u32>> = out[0]
        .scene
        .items
        .iter()
        .filter(|i| matches!(i.shape, Shape::Group { .. }) && i.label.as_deref().is_some_and(|l| l.contains('×')))
        .map(|g| match &g.shape {
            Shape::Group { items, .. } => items.last().map(|b| b.rows.clone()).unwrap_or_default(),
            _ => unreachable!(),
        })
        .collect();
    assert_eq!(cells.len(), 6, "3 × 3 full matrix has 6 point cells");
    for selected in cells {
        assert_eq!(selected, vec![1, 2, 3]);
    }
    let csv = out[0].derived.to_csv(&Default::default());
    assert!(csv.starts_with("row,a,b,c,selected\n"), "{csv}");
}

#[test]
fn scatter_and_parallel_highlight_the_same_rows() {
    let out = draw_ok(
        r#"[[chart]]
name = "s"
kind = "scatter"
data = "t"
x = "a"
y = "c"
highlight = "low"

[[chart]]
name = "p"
kind = "parallel"
data = "t"
columns = ["a", "b", "kind"]
highlight = "low""#,
    );
    let scatter_selected: Vec<u32> =
        batches(&out[0]).into_iter().filter(|(grey, _)| !grey).flat_map(|(_, r)| r).collect();
    assert_eq!(scatter_selected, vec![1, 2, 3]);
    // Parallel: one polyline per row; the last three drawn are the selected ones, on top.
    let lines = leaves(&out[1]);
    let rows: Vec<u32> = lines.iter().flat_map(|i| i.rows.clone()).collect();
    assert_eq!(rows.len(), 7, "row 5 has a NaN in b and is dropped");
    assert_eq!(rows[rows.len() - 3..], [1, 2, 3]);
}

#[test]
fn parallel_positions_are_on_their_axes_and_inversion_flips_them() {
    let charts = |invert: &str| {
        format!(
            r#"[[chart]]
name = "p"
kind = "parallel"
data = "t"
columns = ["a", "c", "kind"]
invert = [{invert}]"#
        )
    };
    let position = |out: &ChartOutput, row: &str, column: usize| -> f64 {
        let csv = out.derived.to_csv(&Default::default());
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let col = header.iter().position(|h| *h == format!("pos_{}", ["a", "c", "kind"][column])).unwrap();
        let line = csv.lines().find(|l| l.split(',').next() == Some(row)).unwrap();
        line.split(',').nth(col).unwrap().parse().unwrap()
    };
    let plain = draw_ok(&charts(""));
    let flipped = draw_ok(&charts("\"a\""));
    for row in ["0", "3", "7"] {
        let p = position(&plain[0], row, 0);
        assert!((0.0..=1.0).contains(&p), "{p}");
        assert!((p + position(&flipped[0], row, 0) - 1.0).abs() < 1e-9, "inverting mirrors the position");
    }
    // Larger a sits higher on a normal axis.
    assert!(position(&plain[0], "7", 0) > position(&plain[0], "0", 0));
    let e = draw_err(&charts("\"aa\""));
    assert!(e.contains("`invert` names `aa`") && e.contains("did you mean `a`"), "{e}");
}

#[test]
fn daisy_vertices_lie_on_the_circle_inside_their_arcs() {
    let out = draw_ok(
        r#"[[chart]]
name = "d"
kind = "daisy"
data = "t"
columns = ["a", "b", "c", "kind"]"#,
    );
    let csv = out[0].derived.to_csv(&Default::default());
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("row,column,value,angle_deg,x,y"));
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let (angle, x, y): (f64, f64, f64) = (f[3].parse().unwrap(), f[4].parse().unwrap(), f[5].parse().unwrap());
        assert!((x * x + y * y - 1.0).abs() < 1e-9);
        let arc = ["a", "b", "c", "kind"].iter().position(|c| *c == f[1]).unwrap() as f64;
        assert!(angle > arc * 90.0 && angle < (arc + 1.0) * 90.0, "{line}: outside its quarter");
    }
}

#[test]
fn faces_map_columns_in_feature_order_and_refuse_more_than_fifteen() {
    let out = draw_ok(
        r#"[[chart]]
name = "f"
kind = "faces"
data = "t"
columns = ["a", "c"]
label = "kind""#,
    );
    let csv = out[0].derived.to_csv(&Default::default());
    let header = csv.lines().next().unwrap();
    assert_eq!(header, "row,label,x,y,face_width,face_height");
    // a runs 1..8 over the drawn rows: row 0 is the narrowest face, row 7 the widest.
    let width = |row: &str| -> f64 {
        csv.lines().find(|l| l.starts_with(&format!("{row},"))).unwrap().split(',').nth(4).unwrap().parse().unwrap()
    };
    assert_eq!((width("0"), width("7")), (0.0, 1.0));
    let many = (0..16).map(|_| "\"a\"").collect::<Vec<_>>().join(", ");
    let e = draw_err(&format!("[[chart]]\nname = \"f\"\nkind = \"faces\"\ndata = \"t\"\ncolumns = [{many}]"));
    assert!(e.contains("16 columns given; faces show at most 15"), "{e}");
    let e = draw_err("[[chart]]\nname = \"f\"\nkind = \"faces\"\ndata = \"t\"\ncolumns = [\"kind\"]");
    assert!(e.contains("holds text"), "{e}");
}

#[test]
fn segments_fill_every_disk_pixel_and_order_rows_by_a_column() {
    let out = draw_ok(
        r#"[[chart]]
name = "g"
kind = "segments"
data = "t"
columns = ["a", "b", "c"]
order_by = "c"
descending = true"#,
    );
    let raster = leaves(&out[0])
        .into_iter()
        .find_map(|i| match &i.shape {
            Shape::Image(r) => Some(r.clone()),
            _ => None,
        })
        .expect("one raster");
    let d = raster.width as f64;
    let mut inside = 0;
    for y in 0..raster.height {
        for x in 0..raster.width {
            let (dx, dy) = (x as f64 + 0.5 - d / 2.0, y as f64 + 0.5 - d / 2.0);
            let alpha = raster.rgba[((y * raster.width + x) * 4 + 3) as usize];
            if dx * dx + dy * dy <= (d / 2.0) * (d / 2.0) {
                assert_eq!(alpha, 255, "disk pixel ({x}, {y}) left empty");
                inside += 1;
            } else {
                assert_eq!(alpha, 0, "pixel ({x}, {y}) outside the disk painted");
            }
        }
    }
    assert!(inside > 1000);
    // Descending c: 8, 7, 6, 5, 4, 3, 2, 1 → rows 7, 3, 1, 0, 2, 4, 5, 6. NaN cells keep their row.
    let csv = out[0].derived.to_csv(&Default::default());
    let order: Vec<&str> = csv.lines().skip(1).map(|l| l.split(',').next().unwrap()).collect();
    assert_eq!(order, ["7", "3", "1", "0", "2", "4", "5", "6"]);
}

#[test]
fn constant_columns_and_single_rows_draw_with_warnings() {
    let charts = r#"[[chart]]
name = "m"
kind = "splom"
data = "t"
columns = ["a", "k"]

[[chart]]
name = "p"
kind = "parallel"
data = "t"
columns = ["k", "a"]

[[chart]]
name = "d"
kind = "daisy"
data = "t"
columns = ["k", "a", "c"]

[[chart]]
name = "f"
kind = "faces"
data = "t"
columns = ["a", "k"]

[[chart]]
name = "g"
kind = "segments"
data = "t"
columns = ["a", "k"]"#;
    let out = draw_ok(charts);
    assert!(out[3].warnings.iter().any(|w| w.to_string().contains("`k` is constant")), "{:?}", out[3].warnings);
    assert!(out[4].warnings.iter().any(|w| w.to_string().contains("`k` is constant")), "{:?}", out[4].warnings);
    let one_row = "[data.t]\nvalues = [{ a = 1, b = 2, c = 3 }]\n\n[[chart]]\nname = \"m\"\nkind = \"splom\"\ndata = \"t\"\ncolumns = [\"a\", \"b\", \"c\"]\n\n[[chart]]\nname = \"p\"\nkind = \"parallel\"\ndata = \"t\"\ncolumns = [\"a\", \"b\"]\n\n[[chart]]\nname = \"d\"\nkind = \"daisy\"\ndata = \"t\"\ncolumns = [\"a\", \"b\", \"c\"]\n\n[[chart]]\nname = \"f\"\nkind = \"faces\"\ndata = \"t\"\ncolumns = [\"a\", \"b\"]\n\n[[chart]]\nname = \"g\"\nkind = \"segments\"\ndata = \"t\"\ncolumns = [\"a\", \"b\"]\n";
    let out = Fixture::new(one_row, &[]).draw().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.len(), 5);
    for o in &out {
        assert!(!leaves(o).is_empty(), "{} drew nothing", o.scene.title.clone().unwrap_or_default());
    }
}

#[test]
fn selection_mistakes_are_reported_where_they_are() {
    let text = r#"
[data.t]
path = "t.csv"

[data.u]
values = [{ a = 1 }]

[selection.low]
data = "t"
range = { aa = [2, 4] }

[selection.empty]
data = "t"

[selection.backwards]
data = "t"
range = { a = [5, 1] }

[[chart]]
name = "s"
kind = "scatter"
data = "t"
x = "a"
y = "c"
highlight = "lwo"

[[chart]]
name = "u"
kind = "scatter"
data = "u"
x = "a"
y = "a"
highlight = "backwards"

[[chart]]
name = "c"
kind = "line"
data = "t"
x = "a"
y = "c"
highlight = "low"
"#;
    let e = Fixture::new(text, &[("t.csv", DATA.as_bytes())]).load().map(|_| ()).unwrap_err();
    assert!(e.contains("unknown selection `lwo`; did you mean `low`?"), "{e}");
    assert!(e.contains("`selection.empty` selects nothing"), "{e}");
    assert!(e.contains("range of `a` must be `[min, max]`"), "{e}");
    assert!(e.contains("selection `backwards` is over data `t`, but this chart draws `u`"), "{e}");
    assert!(e.contains("`highlight` is not drawn by `line` charts"), "{e}");
    // The unknown column is found once the spec is otherwise valid.
    let text = "[data.t]\npath = \"t.csv\"\n\n[selection.low]\ndata = \"t\"\nrange = { aa = [2, 4] }\n\n[[chart]]\nname = \"s\"\nkind = \"scatter\"\ndata = \"t\"\nx = \"a\"\ny = \"c\"\nhighlight = \"low\"\n";
    let e = Fixture::new(text, &[("t.csv", DATA.as_bytes())]).load().map(|_| ()).unwrap_err();
    assert!(e.contains("selection \"low\": data \"t\" has no column `aa`") && e.contains("did you mean `a`"), "{e}");
}

#[test]
fn splom_of_text_columns_explains_itself() {
    let e = draw_err("[[chart]]\nname = \"m\"\nkind = \"splom\"\ndata = \"t\"\ncolumns = [\"a\", \"kind\"]");
    assert!(e.contains("column `kind` holds text; a scatter-plot matrix needs numbers"), "{e}");
}

#[test]
fn segments_order_text_alphabetically_keeping_ties_in_data_order() {
    let order = |descending: bool| {
        let out = draw_ok(&format!(
            "[[chart]]\nname = \"g\"\nkind = \"segments\"\ndata = \"t\"\ncolumns = [\"a\", \"c\"]\norder_by = \"kind\"\ndescending = {descending}"
        ));
        let csv = out[0].derived.to_csv(&Default::default());
        csv.lines().skip(1).map(|l| l.split(',').next().unwrap().to_string()).collect::<Vec<_>>()
    };
    assert_eq!(order(false), ["0", "2", "5", "7", "1", "4", "3", "6"]);
    assert_eq!(order(true), ["3", "6", "1", "4", "0", "2", "5", "7"]);
}

/// Penguin-like rows: island has three categories, Biscoe the most common (as in the Palmer
/// penguins, where it holds 167 of 342 rows).
const PENGUINS: &str = "species,island,bill_length_mm,bill_depth_mm,flipper_length_mm,body_mass_g\n\
Adelie,Torgersen,39.1,18.7,181,3750\n\
Adelie,Biscoe,37.8,18.3,174,3400\n\
Gentoo,Biscoe,46.1,13.2,211,4500\n\
Gentoo,Biscoe,50.0,16.3,230,5700\n\
Chinstrap,Dream,46.5,17.9,192,3500\n\
Adelie,Dream,39.5,16.7,178,3250\n\
Adelie,Torgersen,40.3,18.0,195,3250\n";

#[test]
fn daisy_names_every_category_of_a_text_column() {
    let spec = r#"
[data.p]
path = "p.csv"

[[chart]]
name = "d"
kind = "daisy"
data = "p"
columns = ["bill_length_mm", "bill_depth_mm", "flipper_length_mm", "body_mass_g", "island", "species"]
color = "species"
"#;
    let out = Fixture::new(spec, &[("p.csv", PENGUINS.as_bytes())]).draw().unwrap_or_else(|e| panic!("{e}"));
    let mut texts = Vec::new();
    out[0].scene.walk(|item: &Item| {
        if let (dataink::scene::Role::TickLabel, Shape::Text(t)) = (&item.role, &item.shape) {
            texts.push(t.content.clone());
        }
    });
    for category in ["Torgersen", "Biscoe", "Dream", "Adelie", "Gentoo", "Chinstrap"] {
        assert!(texts.iter().any(|t| t == category), "{category} is labelled: {texts:?}");
    }
}

/// `n` seeded rows of three columns: `a` continuous with a long tail, `b` on a lattice (ties,
/// values on bin edges), `c` a date; every 101st `a` empty, every 499th `b` `inf`.
fn many_rows(n: usize) -> String {
    let mut next = crate::common::seeded_uniform();
    let mut csv = String::from("a,b,c\n");
    for i in 0..n {
        let a = if i % 101 == 0 { String::new() } else { format!("{}", -next().ln() * 3.0 - 1.0) };
        let b = if i % 499 == 0 { "inf".to_string() } else { format!("{}", (next() * 40.0).floor() / 4.0) };
        let c = format!("2020-{:02}-{:02}", 1 + i % 12, 1 + i % 28);
        csv.push_str(&format!("{a},{b},{c}\n"));
    }
    csv
}

#[test]
fn a_density_splom_of_rows_left_in_the_plan_equals_the_one_of_rows_in_memory() {
    let csv = many_rows(240_000);
    for extra in [
        "columns = [\"a\", \"b\", \"c\"]\n",
        "columns = [\"a\", \"b\"]\nbins = 17\nlayout = \"lower\"\nshading = \"log\"\n",
        "columns = [\"c\", \"b\"]\nmode = \"density\"\n",
    ] {
        let spec = format!(
            "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"m\"\nkind = \"splom\"\ndata = \"d\"\nsize = [600, 600]\n{extra}"
        );
        let (streamed, held) = crate::common::streamed_and_held(&spec, &csv, "a", extra);
        let notes = crate::common::warning_texts;
        assert_eq!(notes(&streamed), notes(&held), "{extra}");
        assert!(notes(&streamed).iter().any(|w| w.contains("dropped ") && w.contains("of 240000 rows")), "{extra}");
        let rasters = |out: &ChartOutput| {
            let mut found = Vec::new();
            out.scene.walk(|item: &Item| {
                if let Shape::Image(r) = &item.shape {
                    found.push((r.width, r.height, r.rgba.clone()));
                }
            });
            found
        };
        let (a, b) = (rasters(&streamed), rasters(&held));
        assert!(
            !a.is_empty() && a == b,
            "{extra}: {} rasters streamed, {} held, or their pixels differ",
            a.len(),
            b.len()
        );
        // Everything drawn is the same; only the rows the held histograms carry are not there.
        let items = |out: &ChartOutput| {
            let mut found = Vec::new();
            out.scene.walk(|item: &Item| found.push(format!("{:?} {:?} {:?}", item.role, item.label, item.shape)));
            found
        };
        let (a, b) = (items(&streamed), items(&held));
        let first = a.iter().zip(&b).position(|(x, y)| x != y);
        let cut = |s: Option<&String>| s.map(|s| s.chars().take(300).collect::<String>());
        assert!(
            a == b,
            "{extra}: the two scenes differ ({} and {} items); first at {first:?}:\n{:?}\n{:?}",
            a.len(),
            b.len(),
            cut(first.and_then(|k| a.get(k))),
            cut(first.and_then(|k| b.get(k)))
        );
    }
}

#[test]
fn with_a_million_rows_the_diagonals_of_a_counted_splom_skip_the_quartiles_and_still_agree() {
    // Enough rows that Freedman–Diaconis gives 50 bins whenever the quartiles differ, which the
    // first tally shows: the streamed matrix finds no quartile, and must still equal the held one.
    let mut next = crate::common::seeded_uniform();
    let mut csv = String::from("a,b\n");
    for _ in 0..1_000_000 {
        csv.push_str(&format!("{},{}\n", (next() * 1000.0).floor(), next().powi(3)));
    }
    let spec = "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"m\"\nkind = \"splom\"\ndata = \"d\"\ncolumns = [\"a\", \"b\"]\n";
    let (streamed, held) = crate::common::streamed_and_held(spec, &csv, "a", "a million rows");
    let histograms = |out: &ChartOutput| {
        let mut found = Vec::new();
        out.scene.walk(|item: &Item| {
            if item.label.as_deref() == Some("histogram") {
                found.push(format!("{:?}", item.shape));
            }
        });
        found
    };
    assert_eq!(histograms(&streamed).len(), 2);
    assert_eq!(histograms(&streamed), histograms(&held));
}

#[test]
fn a_splom_left_in_the_plan_says_what_it_cannot_count() {
    let mut csv = String::from("a,t\n");
    for i in 0..210_000 {
        csv.push_str(&format!("{},w{}\n", i % 7, i % 3));
    }
    let spec = |columns: &str| {
        format!(
            "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"m\"\nkind = \"splom\"\ndata = \"d\"\ncolumns = {columns}\n"
        )
    };
    let err = Fixture::new(&spec("[\"a\", \"t\"]"), &[("d.csv", csv.as_bytes())]).draw().expect_err("text column");
    assert!(err.contains("`t`"), "{err}");
}
