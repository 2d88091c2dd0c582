//! Conventional defaults: keys a chart leaves out take the columns of the conventional names
//! (grid `x`/`y`/`value`, flow `x`/`y`/`u`/`v`, trees `id`/`parent` and `name`, networks
//! `source`/`target`/`weight`), and a line chart's `color` splits series.

use dataink::scene::{Color, Role, Scene, Shape};

use crate::common::{Fixture, npy_f8};

/// The scene of the only chart of a spec, or the rendered diagnostics.
fn scene(spec: &str, files: &[(&str, &[u8])]) -> Result<Scene, String> {
    Fixture::new(spec, files).draw().map(|mut out| out.remove(0).scene)
}

/// The load error of a spec that must fail.
fn error(spec: &str, files: &[(&str, &[u8])]) -> String {
    Fixture::new(spec, files).load().expect_err("the spec should fail")
}

/// The stroke colour of each line labelled as a series, by label.
fn series_colours(scene: &Scene) -> Vec<(String, Color)> {
    let mut out = Vec::new();
    scene.walk(|item| {
        if let (Role::DataMark, Shape::Path(_), Some(label), Some(stroke)) =
            (item.role, &item.shape, &item.label, &item.style.stroke)
        {
            out.push((label.clone(), stroke.color));
        }
    });
    out
}

#[test]
fn a_contour_of_an_npy_grid_needs_no_column_names() {
    let values: Vec<f64> = (0..30).map(|i| ((i % 6) as f64 - 2.5).powi(2) + ((i / 6) as f64 - 2.0).powi(2)).collect();
    let grid = npy_f8(5, 6, &values);
    let files: &[(&str, &[u8])] = &[("g.npy", &grid)];
    let head = "[data.g]\npath = \"g.npy\"\n\n[[chart]]\nname = \"c\"\ndata = \"g\"\nkind = \"contour\"\nlevels = [1.0, 4.0]\n";
    let bare = scene(head, files).unwrap_or_else(|e| panic!("{e}"));
    let named = scene(&format!("{head}x = \"x\"\ny = \"y\"\nz = \"value\"\n"), files).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(bare, named, "the defaults draw what naming the columns draws");
    let loaded = Fixture::new(head, files).load().unwrap();
    let taken: Vec<(String, String)> = loaded.defaults["c"].iter().map(|t| (t.key.clone(), t.value.clone())).collect();
    let expected = [("x", "\"x\""), ("y", "\"y\""), ("z", "\"value\"")];
    assert_eq!(taken, expected.map(|(k, v)| (k.to_owned(), v.to_owned())));
    // A named key is kept: z from another column is not overridden.
    let other = Fixture::new(&format!("{head}z = \"x\"\n"), files).load().unwrap();
    assert!(other.defaults["c"].iter().all(|t| t.key != "z"));
}

#[test]
fn grid_kinds_read_an_npy_grid_directly_and_draw_what_its_long_form_draws() {
    use dataink::data::ColumnValues;
    let (rows, cols) = (5, 6);
    let values: Vec<f64> = (0..30).map(|i| ((i % 6) as f64 - 2.5).powi(2) + ((i / 6) as f64 - 2.0).powi(2)).collect();
    let grid = npy_f8(rows, cols, &values);
    let mut csv = String::from("x,y,value\n");
    for (k, v) in values.iter().enumerate() {
        // The extent below maps column j to x = 10 + 2j and row i to y = -1 + i / 2.
        csv.push_str(&format!("{},{},{v}\n", 10.0 + 2.0 * (k % cols) as f64, -1.0 + 0.5 * (k / cols) as f64));
    }
    let files: &[(&str, &[u8])] = &[("g.npy", &grid), ("g.csv", csv.as_bytes())];
    for (kind, extra) in [("contour", ""), ("image", ""), ("surface", ""), ("section", "at_y = [0.0, 0.5]\n")] {
        let chart = format!("[[chart]]\nname = \"c\"\ndata = \"g\"\nkind = \"{kind}\"\n{extra}");
        let npy = format!("[data.g]\npath = \"g.npy\"\nextent = [10.0, 20.0, -1.0, 1.0]\n\n{chart}");
        let long = format!("[data.g]\npath = \"g.csv\"\n\n{chart}");
        let fixture = Fixture::new(&npy, files);
        let loaded = fixture.load().unwrap_or_else(|e| panic!("{kind}: {e}"));
        let table = &loaded.tables["g"];
        let drawn = dataink::pipeline::draw_chart(&loaded, 0, &loaded.spec.chart[0]).unwrap_or_else(|e| panic!("{e}"));
        // The coordinate columns were never spread over the 30 rows.
        for name in ["x", "y"] {
            let Some(ColumnValues::Axis(axis)) = table.column(name).map(|c| &c.values) else {
                panic!("{name} is an axis")
            };
            assert!(!axis.is_spread(), "{kind}: `{name}` was read row by row");
        }
        let from_csv = scene(&long, files).unwrap_or_else(|e| panic!("{kind}: {e}"));
        assert_eq!(drawn.scene, from_csv, "{kind}: the npy grid draws what its long form draws");
    }
}

#[test]
fn a_flow_table_with_x_y_u_v_columns_renders_as_written() {
    let mut csv = String::from("x,y,u,v\n");
    for j in 0..6 {
        for i in 0..6 {
            let (x, y) = (i as f64, j as f64);
            csv.push_str(&format!("{x},{y},{},{}\n", -(y - 2.5), x - 2.5));
        }
    }
    let spec = "[data.f]\npath = \"f.csv\"\n\n[[chart]]\nname = \"flow\"\ndata = \"f\"\nkind = \"flow\"\n";
    let files: &[(&str, &[u8])] = &[("f.csv", csv.as_bytes())];
    let bare = scene(spec, files).unwrap_or_else(|e| panic!("{e}"));
    let named = format!("{spec}x = \"x\"\ny = \"y\"\nu = \"u\"\nv = \"v\"\n");
    assert_eq!(bare, scene(&named, files).unwrap_or_else(|e| panic!("{e}")));
    // No `t` column: no `t` default.
    let loaded = Fixture::new(spec, files).load().unwrap();
    let keys: Vec<&str> = loaded.defaults["flow"].iter().map(|t| t.key.as_str()).collect();
    assert_eq!(keys, ["x", "y", "u", "v"]);
}

#[test]
fn a_key_whose_column_is_missing_too_says_what_was_looked_for() {
    let spec = "[data.f]\nvalues = [{ x = 0, y = 0, east = 1, north = 0 }]\n\n[[chart]]\nname = \"flow\"\ndata = \"f\"\nkind = \"flow\"\n";
    let e = error(spec, &[]);
    assert!(e.contains("chart \"flow\" is missing `u` and `v`"), "{e}");
    assert!(e.contains("u = \"u\"  # data \"f\" has no column `u` to take by default"), "{e}");
    assert!(e.contains("the columns of data \"f\" are `east`, `north`, `x`, `y`"), "{e}");
    assert!(!e.contains("missing `x`"), "x and y were taken: {e}");
}

#[test]
fn a_chart_whose_data_did_not_load_reports_only_the_load_error() {
    let spec = "[data.e]\npath = \"nope.csv\"\n\n[[chart]]\nname = \"g\"\ndata = \"e\"\nkind = \"graph\"\n";
    let e = error(spec, &[]);
    assert!(e.contains("does not exist"), "{e}");
    assert!(!e.contains("missing `source`"), "{e}");
    assert_eq!(e.matches("error:").count(), 1, "{e}");
}

#[test]
fn a_tree_table_with_id_and_parent_is_a_treemap_labelled_by_name() {
    let csv = "id,parent,name,size\n1,,root,\n2,1,alpha,3\n3,1,beta,5\n4,2,gamma,2\n";
    let spec =
        "[data.t]\npath = \"t.csv\"\n\n[[chart]]\nname = \"tm\"\ndata = \"t\"\nkind = \"treemap\"\nvalue = \"size\"\n";
    let files: &[(&str, &[u8])] = &[("t.csv", csv.as_bytes())];
    let bare = scene(spec, files).unwrap_or_else(|e| panic!("{e}"));
    let named = spec
        .replace("value = \"size\"", "value = \"size\"\ntree = { id = \"id\", parent = \"parent\" }\nlabel = \"name\"");
    assert_eq!(bare, scene(&named, files).unwrap_or_else(|e| panic!("{e}")));
    let mut texts = Vec::new();
    bare.walk(|item| {
        if let Shape::Text(t) = &item.shape {
            texts.push(t.content.clone());
        }
    });
    assert!(texts.iter().any(|t| t == "beta"), "leaves are labelled by `name`: {texts:?}");
    // A table with a `path` column instead.
    let csv = "path,size\na/b,3\na/c,5\nd,2\n";
    let spec =
        "[data.t]\npath = \"t.csv\"\n\n[[chart]]\nname = \"tm\"\ndata = \"t\"\nkind = \"treemap\"\nvalue = \"size\"\n";
    let loaded = Fixture::new(spec, &[("t.csv", csv.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.defaults["tm"][0].value, "{ path = \"path\" }");
}

#[test]
fn an_edge_table_with_source_and_target_is_a_graph_weighted_by_value() {
    let csv = "source,target,value\na,b,1\nb,c,4\nc,a,2\nc,d,1\n";
    let spec = "[data.e]\npath = \"e.csv\"\n\n[[chart]]\nname = \"g\"\ndata = \"e\"\nkind = \"graph\"\n";
    let files: &[(&str, &[u8])] = &[("e.csv", csv.as_bytes())];
    let bare = scene(spec, files).unwrap_or_else(|e| panic!("{e}"));
    let named = format!("{spec}source = \"source\"\ntarget = \"target\"\nweight = \"value\"\n");
    assert_eq!(bare, scene(&named, files).unwrap_or_else(|e| panic!("{e}")));
}

#[test]
fn a_line_chart_coloured_by_a_column_splits_series_with_shared_colours() {
    // The two tables meet the cities in opposite orders.
    let a = "t,temp,city\n1,5,Oslo\n2,6,Oslo\n1,20,Rome\n2,22,Rome\n";
    let b = "t,temp,city\n1,21,Rome\n2,23,Rome\n1,4,Oslo\n2,7,Oslo\n";
    let chart = |name: &str, data: &str, split: &str| {
        format!("[[chart]]\nname = \"{name}\"\ndata = \"{data}\"\nkind = \"line\"\nx = \"t\"\ny = \"temp\"\n{split}\n")
    };
    let files: &[(&str, &[u8])] = &[("a.csv", a.as_bytes()), ("b.csv", b.as_bytes())];
    let data = "[data.a]\npath = \"a.csv\"\n[data.b]\npath = \"b.csv\"\n\n";
    let colours = |split: &str| {
        let spec = format!("{data}{}{}", chart("one", "a", split), chart("two", "b", split));
        let out = Fixture::new(&spec, files).draw().unwrap_or_else(|e| panic!("{e}"));
        let find = |s: &Scene, city: &str| series_colours(s).into_iter().find(|(l, _)| l == city).map(|(_, c)| c);
        (find(&out[0].scene, "Oslo"), find(&out[1].scene, "Oslo"), out)
    };
    let (first, second, out) = colours("color = \"city\"");
    assert!(first.is_some() && first == second, "Oslo has one colour in both charts: {first:?} {second:?}");
    assert_eq!(series_colours(&out[0].scene).len(), 2);
    // `series` colours by order of appearance per chart, so the orders differ.
    let (first, second, _) = colours("series = \"city\"");
    assert_ne!(first, second);
    // One chart alone: `color` draws what `series` draws.
    let alone = |split: &str| scene(&format!("{data}{}", chart("one", "a", split)), files).unwrap();
    assert_eq!(alone("color = \"city\""), alone("series = \"city\""));
    // A table sets colours by `range` in `domain` order.
    let ranged =
        alone("color = { field = \"city\", domain = [\"Rome\", \"Oslo\"], range = [\"#ff0000\", \"#0000ff\"] }");
    let mut got = series_colours(&ranged);
    got.sort_by(|x, y| x.0.cmp(&y.0));
    assert_eq!(got, [("Oslo".to_owned(), Color::rgb(0, 0, 255)), ("Rome".to_owned(), Color::rgb(255, 0, 0))]);
}

#[test]
fn a_line_chart_refuses_series_and_color_together() {
    let spec = "[data.d]\nvalues = [{ t = 1, v = 2, c = \"a\" }, { t = 2, v = 3, c = \"a\" }]\n\n[[chart]]\nname = \"l\"\ndata = \"d\"\nkind = \"line\"\nx = \"t\"\ny = \"v\"\nseries = \"c\"\ncolor = \"c\"\n";
    let e = Fixture::new(spec, &[]).draw().expect_err("both split");
    assert!(e.contains("`series` and `color` both split the rows into series"), "{e}");
    let continuous = spec.replace("series = \"c\"\ncolor = \"c\"", "color = { field = \"v\", type = \"continuous\" }");
    let e = Fixture::new(&continuous, &[]).draw().expect_err("continuous");
    assert!(e.contains("a line chart's `color` splits the rows into series by category"), "{e}");
}

#[test]
fn a_flat_parent_table_read_as_a_nested_tree_is_refused() {
    let json = r#"[{"id": 1, "name": "flare"}, {"id": 2, "name": "vis", "parent": 1, "size": 3}]"#;
    let spec = "[data.t]\npath = \"flare.json\"\nformat = \"tree\"\n\n[[chart]]\nname = \"tm\"\ndata = \"t\"\nkind = \"treemap\"\nvalue = \"size\"\n";
    let e = error(spec, &[("flare.json", json.as_bytes())]);
    assert!(e.contains("remove `format = \"tree\"` to read it as a table"), "{e}");
    // Without `format`, it is a table whose `id` and `parent` make the tree.
    let spec = spec.replace("format = \"tree\"\n", "");
    scene(&spec, &[("flare.json", json.as_bytes())]).unwrap_or_else(|e| panic!("{e}"));
}
