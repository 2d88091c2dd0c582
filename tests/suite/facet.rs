//! Facets (small multiples): panels split the rows exactly, share their scales (identical tick
//! labels, one legend), label only the outer axes, keep histogram bins alike, remap rows for
//! tooltips and the derived table, report unshared scales (CM001), and reject bad facets with
//! the documented errors.

use crate::common::{Fixture, lint_codes, numbers, root, texts};
use dataink::mark::ChartOutput;
use dataink::scene::{Item, Role, Shape};

fn iris() -> Vec<u8> {
    std::fs::read(root().join("examples/data/iris.csv")).unwrap_or_default()
}

fn spec(extra: &str) -> String {
    format!("[data.iris]\npath = \"iris.csv\"\n\n[[chart]]\nname = \"f\"\ndata = \"iris\"\ntitle = \"Iris\"\n{extra}")
}

fn draw(extra: &str) -> Result<ChartOutput, String> {
    let data = iris();
    Fixture::new(&spec(extra), &[("iris.csv", &data)]).draw().map(|mut v| v.remove(0))
}

fn draw_ok(extra: &str) -> ChartOutput {
    draw(extra).unwrap_or_else(|e| panic!("{e}"))
}

/// The scene's panels: each panel group's label and items.
fn panels(out: &ChartOutput) -> Vec<(String, &Vec<Item>)> {
    out.scene
        .items
        .iter()
        .filter_map(|i| match (&i.label, &i.shape) {
            (Some(l), Shape::Group { items, .. }) if l.starts_with("panel: ") => Some((l.clone(), items)),
            _ => None,
        })
        .collect()
}

/// The labelled ticks of `axis` among `items`.
fn ticks(items: &[Item], axis: &str) -> Vec<String> {
    let mut out = Vec::new();
    for item in items {
        match &item.shape {
            Shape::Group { items, .. } => out.extend(ticks(items, axis)),
            Shape::Text(t) if item.role == Role::TickLabel && item.label.as_deref() == Some(axis) => {
                out.push(t.content.clone())
            }
            _ => {}
        }
    }
    out
}

/// Every data-mark row among `items`.
fn rows(items: &[Item], into: &mut Vec<u32>) {
    for item in items {
        if item.role == Role::DataMark {
            into.extend(&item.rows);
        }
        if let Shape::Group { items, .. } = &item.shape {
            rows(items, into);
        }
    }
}

const SCATTER: &str = "kind = \"scatter\"\nx = \"petal_length\"\ny = \"petal_width\"\ncolor = \"species\"\n";

#[test]
fn panels_split_the_rows_exactly_and_in_order() {
    let out = draw_ok(&format!("{SCATTER}facet = \"species\""));
    let found = panels(&out);
    let names: Vec<&str> = found.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["panel: species = setosa", "panel: species = versicolor", "panel: species = virginica"]);
    let mut all = Vec::new();
    for (_, items) in &found {
        let mut own = Vec::new();
        rows(items, &mut own);
        assert_eq!(own.len(), 50, "50 iris of each species");
        all.extend(own);
    }
    all.sort_unstable();
    assert_eq!(all, (0..150).collect::<Vec<u32>>(), "every row drawn once, as a row of the whole table");
    // The first 50 rows of iris.csv are setosa: the first panel holds them.
    let mut first = Vec::new();
    rows(found[0].1, &mut first);
    first.sort_unstable();
    assert_eq!(first, (0..50).collect::<Vec<u32>>());
    // The derived table keeps whole-table rows, panel after panel.
    assert_eq!(out.derived.rows.len(), 150);
    assert!(out.derived.rows.iter().enumerate().all(|(k, &r)| (k < 50) == (r < 50)));
    let iris_csv = String::from_utf8(iris()).unwrap_or_default();
    let csv = out.derived.to_csv(&dataink::data::Table::default());
    assert!(csv.starts_with("row,"), "{csv}");
    assert!(!iris_csv.is_empty());
}

#[test]
fn shared_scales_label_only_the_outer_panels_alike() {
    let out = draw_ok(&format!("{SCATTER}facet = {{ column = \"species\" }}\nsize = [900, 360]"));
    let found = panels(&out);
    assert_eq!(found.len(), 3);
    // One row of panels: each labels x, only the first labels y.
    let x: Vec<Vec<String>> = found.iter().map(|(_, items)| ticks(items, "x axis")).collect();
    assert!(!x[0].is_empty() && x.iter().all(|t| *t == x[0]), "every panel's x ticks alike: {x:?}");
    let y: Vec<Vec<String>> = found.iter().map(|(_, items)| ticks(items, "y axis")).collect();
    assert!(!y[0].is_empty() && y[1].is_empty() && y[2].is_empty(), "{y:?}");
    // The x domain covers every species' petals (1 to 6.9 cm), though setosa's reach 1.9.
    assert_eq!(x[0].first().map(String::as_str), Some("1"));
    assert_eq!(x[0].last().map(String::as_str), Some("7"));
    // One legend with all three species, one x title and one y title for the grid.
    let legend_texts: Vec<String> = {
        let mut v = Vec::new();
        out.scene.walk(|i| {
            if let (Role::Legend, Shape::Text(t)) = (i.role, &i.shape) {
                v.push(t.content.clone());
            }
        });
        v
    };
    for s in ["setosa", "versicolor", "virginica"] {
        assert_eq!(legend_texts.iter().filter(|t| *t == s).count(), 1, "{legend_texts:?}");
    }
    let mut titles = 0;
    out.scene.walk(|i| titles += usize::from(i.role == Role::AxisTitle));
    assert_eq!(titles, 2);
    assert!(
        lint_codes(&spec(&format!("{SCATTER}facet = \"species\"")), &[("iris.csv", &iris())])
            .iter()
            .all(|c| *c != "CM001")
    );
}

#[test]
fn a_grid_labels_x_on_the_bottom_row_and_y_on_the_first_column() {
    // Rows by sepal width (narrow below 3 cm), columns by species.
    let text = format!("{SCATTER}facet = {{ row = \"sepal\", column = \"species\" }}");
    let text = spec(&text).replace(
        "path = \"iris.csv\"\n",
        "path = \"iris.csv\"\ntransform = [{ calculate = \"if(sepal_width >= 3, 'wide', 'narrow')\", as = \"sepal\" }]\n",
    );
    let data = iris();
    let out =
        Fixture::new(&text, &[("iris.csv", &data)]).draw().map(|mut v| v.remove(0)).unwrap_or_else(|e| panic!("{e}"));
    let found = panels(&out);
    let names: Vec<&str> = found.iter().map(|(n, _)| n.as_str()).collect();
    // Every species has narrow and wide sepals: a full 2 × 3 grid, rows in ascending order.
    assert_eq!(names.len(), 6, "{names:?}");
    assert_eq!(names[0], "panel: sepal = narrow, species = setosa");
    assert_eq!(names[5], "panel: sepal = wide, species = virginica");
    let mut total = 0;
    for (k, (name, items)) in found.iter().enumerate() {
        let mut own = Vec::new();
        rows(items, &mut own);
        total += own.len();
        assert_eq!(!ticks(items, "x axis").is_empty(), k >= 3, "x labels on the bottom row only: {name}");
        assert_eq!(!ticks(items, "y axis").is_empty(), k % 3 == 0, "y labels in the first column only: {name}");
    }
    assert_eq!(total, 150);
    // Column headers once above the grid, row headers once on its right.
    let mut headers = Vec::new();
    out.scene.walk(|i| {
        if let (Some("facet header"), Shape::Text(t)) = (i.label.as_deref(), &i.shape) {
            headers.push(t.content.clone());
        }
    });
    assert_eq!(
        headers,
        ["species = setosa", "species = versicolor", "species = virginica", "sepal = narrow", "sepal = wide"]
    );
}

#[test]
fn independent_scales_are_labelled_everywhere_and_reported() {
    let extra = format!("{SCATTER}facet = {{ column = \"species\", resolve = {{ y = \"independent\" }} }}");
    let out = draw_ok(&extra);
    let y: Vec<Vec<String>> = panels(&out).iter().map(|(_, items)| ticks(items, "y axis")).collect();
    assert!(y.iter().all(|t| !t.is_empty()), "every panel labels its own y: {y:?}");
    assert_ne!(y[0], y[2], "setosa's petals are narrower than virginica's");
    let codes = lint_codes(&spec(&extra), &[("iris.csv", &iris())]);
    assert!(codes.contains(&"CM001"), "{codes:?}");
}

#[test]
fn histogram_panels_share_their_bins_and_counts_sum_to_the_rows() {
    let out = draw_ok("kind = \"histogram\"\nx = \"sepal_length\"\nfacet = \"species\"");
    let counts = numbers(&out, "count");
    assert_eq!(counts.iter().sum::<f64>(), 150.0);
    let (start, species) = (numbers(&out, "bin_start"), texts(&out, "species"));
    let of = |s: &str| -> Vec<f64> { start.iter().zip(&species).filter(|(_, p)| *p == s).map(|(b, _)| *b).collect() };
    assert_eq!(of("setosa"), of("virginica"), "the same bin edges in every panel");
    assert!(!of("setosa").is_empty());
    // Per panel the counts are each species' 50 rows.
    for s in ["setosa", "versicolor", "virginica"] {
        let n: f64 = counts.iter().zip(&species).filter(|(_, p)| *p == s).map(|(c, _)| c).sum();
        assert_eq!(n, 50.0, "{s}");
    }
}

#[test]
fn bars_and_boxes_facet_with_categories_in_place() {
    let out = draw_ok("kind = \"box\"\nx = \"species\"\ny = \"sepal_length\"\nfacet = \"species\"");
    assert_eq!(panels(&out).len(), 3);
    let parallel = draw_ok(
        "kind = \"parallel\"\ncolumns = [\"sepal_length\", \"sepal_width\", \"petal_length\"]\ncolor = \"species\"\nfacet = \"species\"",
    );
    assert_eq!(panels(&parallel).len(), 3);
    assert!(parallel.scene.width > 900.0, "room for three panels: {}", parallel.scene.width);
    // Each column's axis spans every species' values in every panel.
    let y: Vec<Vec<String>> = panels(&parallel).iter().map(|(_, items)| ticks(items, "y axis")).collect();
    assert!(!y[0].is_empty() && y.iter().all(|t| *t == y[0]), "{y:?}");
    let spec_text = spec("kind = \"parallel\"\ncolumns = [\"sepal_length\", \"petal_length\"]\nfacet = \"species\"");
    let codes = lint_codes(&spec_text, &[("iris.csv", &iris())]);
    assert!(!codes.contains(&"CM001"), "{codes:?}");
}

#[test]
fn bad_facets_give_the_documented_errors() {
    let e = draw(&format!("{SCATTER}facet = \"specie\"")).err().unwrap_or_default();
    assert!(e.contains("no column `specie`") && e.contains("facet = \"specie\"") && e.contains("species"), "{e}");
    let ids: String = (0..150).map(|i| format!("{i},{}\n", i % 7)).collect();
    let e = Fixture::new(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"id\"\ny = \"v\"\nfacet = \"id\"",
        &[("d.csv", format!("id,v\n{ids}").as_bytes())],
    )
    .draw()
    .err()
    .unwrap_or_default();
    assert!(e.contains("column `id` has more than 100 distinct values"), "{e}");
    let e = draw(&format!("{SCATTER}facet = {{ colum = \"species\" }}")).err().unwrap_or_default();
    assert!(e.contains("colum"), "{e}");
    let e = draw(&format!("{SCATTER}facet = \"species\"\nsize = [200, 120]")).err().unwrap_or_default();
    assert!(e.contains("too small for 1 × 3 facet panels"), "{e}");
    let e = Fixture::new(
        "[data.g]\npath = \"g.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"contour\"\ndata = \"g\"\nx = \"x\"\ny = \"y\"\nz = \"z\"\nfacet = \"x\"",
        &[("g.csv", b"x,y,z\n0,0,1\n1,0,2\n0,1,3\n1,1,4\n")],
    )
    .draw()
    .err()
    .unwrap_or_default();
    assert!(e.contains("cannot be faceted"), "{e}");
}

#[test]
fn end_labels_of_neighbouring_panels_keep_apart() {
    // Years 1955–2005 tick at 1950, 1980, 2010: the panels' end labels meet in the gap between
    // them, which must keep them apart (LB002) without dropping them (SC001).
    let mut csv = String::from("year,value,group\n");
    for g in ["a", "b", "c"] {
        for (k, year) in (1955..=2005).step_by(5).enumerate() {
            csv.push_str(&format!("{year},{},{g}\n", k * 3 + g.len()));
        }
    }
    let spec = "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"line\"\ndata = \"d\"\ntitle = \"T\"\nx = \"year\"\ny = \"value\"\nfacet = \"group\"\nsize = [760, 300]";
    let codes = lint_codes(spec, &[("d.csv", csv.as_bytes())]);
    assert!(!codes.contains(&"LB002") && !codes.contains(&"SC001"), "{codes:?}");
    let out = Fixture::new(spec, &[("d.csv", csv.as_bytes())])
        .draw()
        .map(|mut v| v.remove(0))
        .unwrap_or_else(|e| panic!("{e}"));
    for (name, items) in panels(&out) {
        assert!(ticks(items, "x axis").len() >= 2, "{name} labels its x axis");
    }
}

#[test]
fn the_explorer_brushes_a_faceted_scatter_panel_by_panel() {
    use dataink::explore::brush::Mode;
    use dataink::explore::{Session, Target};
    let data = iris();
    let fx = Fixture::new(&spec(&format!("{SCATTER}facet = \"species\"")), &[("iris.csv", &data)]);
    let mut session = Session::new(fx.load().unwrap_or_else(|e| panic!("{e}")), 1.0);
    let plots = session.charts[0].geometry.plots.clone();
    assert_eq!(plots.len(), 3, "one brushable plot per panel");
    assert!(plots.windows(2).all(|w| w[0].rect.right() < w[1].rect.x), "side by side, apart");
    // Brush all of the last (virginica) panel's plot: every row whose petals lie in the shared
    // ranges is selected — all 150, as every panel spans every species' values.
    let p = plots[2].rect;
    let (a, b) = (dataink::scene::Point::new(p.x, p.y), dataink::scene::Point::new(p.right(), p.bottom()));
    let target = session.target_at(0, dataink::scene::Point::new(p.x + 1.0, p.y + 1.0));
    assert_eq!(target, Some(Target::Plot(2)));
    session.brush(0, Target::Plot(2), a, b, Mode::Replace);
    let lit = session.mask("iris").map(|m| m.iter().filter(|&&on| on).count());
    assert_eq!(lit, Some(150));
    // Petal lengths below 2.5 cm: only the setosa rows.
    let x_at = |v: f64| plots[0].x.as_ref().map_or(f64::NAN, |x| x.scale.map(v));
    let from = dataink::scene::Point::new(x_at(0.0), p.y);
    let to = dataink::scene::Point::new(x_at(2.5), p.bottom());
    session.brush(0, Target::Plot(0), from, to, Mode::Replace);
    let mask = session.mask("iris").unwrap_or_default();
    assert_eq!(mask.iter().filter(|&&on| on).count(), 50);
    assert!(mask[..50].iter().all(|&on| on), "the setosa rows");
}

#[test]
fn the_derived_table_gives_each_row_its_own_facet_value() {
    // Faceted by species without colouring by it: the facet column is added to the CSV.
    let data = iris();
    let fx = Fixture::new(
        &spec("kind = \"scatter\"\nx = \"petal_length\"\ny = \"petal_width\"\nfacet = \"species\"\n"),
        &[("iris.csv", &data)],
    );
    let loaded = fx.load().unwrap_or_else(|e| panic!("{e}"));
    let out = fx.draw().unwrap_or_else(|e| panic!("{e}")).remove(0);
    let csv = out.derived.to_csv(&loaded.tables["iris"]);
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    assert_eq!(header[0], "species", "{header:?}");
    let row_at = header.iter().position(|h| *h == "row").expect("a row column");
    let species: Vec<String> = String::from_utf8(data)
        .unwrap_or_default()
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap_or_default().trim_matches('"').to_string())
        .collect();
    let mut n = 0;
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let row: usize = cells[row_at].parse().expect("a row number");
        assert_eq!(cells[0], species[row], "row {row}");
        n += 1;
    }
    assert_eq!(n, 150);
}

#[test]
fn a_size_encoding_maps_one_value_to_one_marker_size_in_every_panel() {
    // Petal widths run to 0.6 cm in setosa and to 2.5 cm in virginica: one mapping for all.
    let out = draw_ok(
        "kind = \"scatter\"\nx = \"petal_length\"\ny = \"sepal_length\"\npoint_size = \"petal_width\"\nfacet = \"species\"\n",
    );
    let widths: Vec<f64> = String::from_utf8(iris())
        .unwrap_or_default()
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(3).and_then(|v| v.parse().ok()).unwrap_or(f64::NAN))
        .collect();
    fn points(items: &[Item], into: &mut Vec<(u32, f64)>) {
        for item in items {
            match &item.shape {
                Shape::Points(batch) if item.role == Role::DataMark => {
                    into.extend(item.rows.iter().enumerate().map(|(k, &r)| (r, batch.radius.at(k).unwrap_or(f64::NAN))))
                }
                Shape::Group { items, .. } => points(items, into),
                _ => {}
            }
        }
    }
    let mut drawn = Vec::new();
    points(&out.scene.items, &mut drawn);
    assert_eq!(drawn.len(), 150);
    // Area proportional to the value: r² / value is one constant, 12² / 2.5 (the largest width
    // gets the default largest radius, 12 px).
    for (row, r) in drawn {
        let w = widths[row as usize];
        assert!((r * r / w - 144.0 / 2.5).abs() < 1e-6, "row {row}: width {w} drawn with radius {r}");
    }
}
