//! Hierarchy and network kinds (treemap, hypertree, graph, linkmap): geometric invariants of the
//! drawn charts, determinism, and bad input giving the documented errors.

use crate::common::Fixture;
use dataink::mark::{ChartOutput, DerivedColumn};
use dataink::scene::{Role, Shape};

/// A small tree: root → a (→ a1 = 6, a2 = 2), b (→ b1 = 4, b2 = 0), c = 8.
const TREE: &str = "id,parent,size,kind\n\
root,,,\n\
a,root,,\n\
b,root,,\n\
c,root,8,leaf\n\
a1,a,6,leaf\n\
a2,a,2,leaf\n\
b1,b,4,leaf\n\
b2,b,0,leaf\n";

/// A small network: a triangle x-y-z, a tail z → w, and an isolated pair p → q.
const EDGES: &str = "from,to,w\nx,y,1\ny,z,2\nz,x,3\nz,w,4\np,q,5\n";
const NODES: &str = "id,name,group,pop,lon,lat\nx,Ex,1,10,0,0\ny,Why,1,20,1,0\nz,Zed,2,30,1,1\nw,Dub,2,40,2,2\np,Pe,3,50,3,0\nq,Qu,3,60,4,0\n";

fn draw(charts: &str) -> Result<Vec<ChartOutput>, String> {
    let spec = format!(
        "[data.tree]\npath = \"tree.csv\"\n[data.edges]\npath = \"edges.csv\"\n[data.nodes]\npath = \"nodes.csv\"\n{charts}"
    );
    let files: [(&str, &[u8]); 3] =
        [("tree.csv", TREE.as_bytes()), ("edges.csv", EDGES.as_bytes()), ("nodes.csv", NODES.as_bytes())];
    Fixture::new(&spec, &files).draw()
}

fn draw_one(chart: &str) -> ChartOutput {
    draw(chart).unwrap_or_else(|e| panic!("{e}")).remove(0)
}

fn draw_err(chart: &str) -> String {
    match draw(chart) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

fn numbers<'a>(out: &'a ChartOutput, name: &str) -> &'a [f64] {
    match out.derived.columns.iter().find(|(n, _)| n == name) {
        Some((_, DerivedColumn::Number(v))) => v,
        _ => panic!("no numeric column {name}"),
    }
}

fn texts<'a>(out: &'a ChartOutput, name: &str) -> &'a [String] {
    match out.derived.columns.iter().find(|(n, _)| n == name) {
        Some((_, DerivedColumn::Text(v))) => v,
        _ => panic!("no text column {name}"),
    }
}

const TREEMAP: &str = r#"
[[chart]]
name = "t"
kind = "treemap"
data = "tree"
tree = { id = "id", parent = "parent" }
value = "size"
padding = 0
headers = false
"#;

#[test]
fn treemap_areas_are_proportional_to_values_and_children_tile_their_parent() {
    for tiling in ["squarified", "slice-dice", "strip"] {
        let out = draw_one(&format!("{TREEMAP}tiling = \"{tiling}\"\n"));
        let ids = texts(&out, "id");
        let parents = texts(&out, "parent");
        let value = numbers(&out, "value");
        let (x0, y0, x1, y1) = (numbers(&out, "x0"), numbers(&out, "y0"), numbers(&out, "x1"), numbers(&out, "y1"));
        let area = |i: usize| (x1[i] - x0[i]) * (y1[i] - y0[i]);
        let root = ids.iter().position(|i| i == "root").unwrap();
        assert_eq!(value[root], 20.0, "{tiling}: 6 + 2 + 4 + 0 + 8");
        for (i, id) in ids.iter().enumerate() {
            // Every node's area is its share of the root's.
            let expected = area(root) * value[i] / value[root];
            assert!((area(i) - expected).abs() <= 1e-9 * area(root), "{tiling}: {id} {} vs {expected}", area(i));
            let children: Vec<usize> = (0..ids.len()).filter(|&c| parents[c] == *id).collect();
            if !children.is_empty() {
                let sum: f64 = children.iter().map(|&c| area(c)).sum();
                assert!((sum - area(i)).abs() <= 1e-9 * area(root), "{tiling}: children of {id}");
                for (k, &a) in children.iter().enumerate() {
                    assert!(
                        x0[a] >= x0[i] - 1e-9
                            && x1[a] <= x1[i] + 1e-9
                            && y0[a] >= y0[i] - 1e-9
                            && y1[a] <= y1[i] + 1e-9
                    );
                    for &b in &children[k + 1..] {
                        let w = (x1[a].min(x1[b]) - x0[a].max(x0[b])).max(0.0);
                        let h = (y1[a].min(y1[b]) - y0[a].max(y0[b])).max(0.0);
                        assert!(w * h <= 1e-9, "{tiling}: {} and {} overlap", ids[a], ids[b]);
                    }
                }
            }
        }
    }
}

#[test]
fn treemap_depth_limit_folds_deeper_nodes_and_labels_fit_their_cells() {
    let out = draw_one(&format!("{TREEMAP}depth = 1\nlabel = \"id\"\n"));
    let ids = texts(&out, "id");
    assert_eq!(ids.len(), 4, "root, a, b, c: {ids:?}");
    let mut cells = Vec::new();
    let mut labels = Vec::new();
    out.scene.walk(|item| match &item.shape {
        Shape::Rect(r) if item.role == Role::DataMark => cells.push(*r),
        Shape::Text(t) if item.role == Role::Annotation => labels.push(dataink::text::bounds(t)),
        _ => {}
    });
    assert_eq!(cells.len(), 3, "a, b and c are drawn as leaves");
    for label in &labels {
        assert!(cells.iter().any(|c| c.contains_rect(label, 0.5)), "label {label:?} leaves its cell");
    }
}

#[test]
fn treemap_bad_trees_and_weights_are_reported() {
    let cycle = "id,parent,size\nr,,1\nx,y,1\ny,x,1\n";
    let spec = format!("[data.tree]\npath = \"c.csv\"\n{TREEMAP}");
    let err = Fixture::new(&spec, &[("c.csv", cycle.as_bytes())]).draw().unwrap_err();
    assert!(err.contains("cycle"), "{err}");
    let dangling = "id,parent,size\nr,,1\nx,zz,1\n";
    let err = Fixture::new(&spec, &[("c.csv", dangling.as_bytes())]).draw().unwrap_err();
    assert!(err.contains("names parent `zz`"), "{err}");
    let negative = "id,parent,size\nr,,\nx,r,-3\ny,r,2\n";
    let out = Fixture::new(&spec, &[("c.csv", negative.as_bytes())]).draw().unwrap().remove(0);
    assert!(
        out.warnings.iter().any(|w| w.to_string().contains("1 leaves have negative or missing values")),
        "{:?}",
        out.warnings
    );
    let zero = "id,parent,size\nr,,\nx,r,0\ny,r,0\n";
    let err = Fixture::new(&spec, &[("c.csv", zero.as_bytes())]).draw().unwrap_err();
    assert!(err.contains("add up to 0"), "{err}");
    let err = draw_err("[[chart]]\nname = \"t\"\nkind = \"treemap\"\ndata = \"tree\"\ntree = { id = \"id\" }\n");
    assert!(err.contains("`tree` has `id` but no `parent`"), "{err}");
    let err = draw_err(
        "[[chart]]\nname = \"t\"\nkind = \"treemap\"\ndata = \"tree\"\ntree = { id = \"id\", parent = \"parnet\" }\n",
    );
    assert!(err.contains("no column `parnet`") && err.contains("parent"), "{err}");
}

#[test]
fn nested_json_trees_load_and_paths_make_trees() {
    let json = r#"{"name": "r", "children": [{"name": "a", "size": 3}, {"name": "b", "children": [{"name": "c", "size": 1}]}]}"#;
    let spec = "[data.j]\npath = \"t.json\"\nformat = \"tree\"\n[[chart]]\nname = \"t\"\nkind = \"treemap\"\ndata = \"j\"\ntree = { path = \"path\" }\nvalue = \"size\"\n";
    let out = Fixture::new(spec, &[("t.json", json.as_bytes())]).draw().unwrap_or_else(|e| panic!("{e}")).remove(0);
    assert_eq!(texts(&out, "id"), ["r", "r/a", "r/b", "r/b/c"]);
    assert_eq!(numbers(&out, "value"), [4.0, 3.0, 1.0, 1.0]);
}

const HYPERTREE: &str =
    "[[chart]]\nname = \"h\"\nkind = \"hypertree\"\ndata = \"tree\"\ntree = { id = \"id\", parent = \"parent\" }\n";

#[test]
fn hypertree_puts_the_focus_at_the_centre_and_everything_inside_the_disk() {
    for focus in ["root", "a1", "b"] {
        let out = draw_one(&format!("{HYPERTREE}focus = \"{focus}\"\n"));
        let ids = texts(&out, "id");
        let (x, y) = (numbers(&out, "disk_x"), numbers(&out, "disk_y"));
        let f = ids.iter().position(|i| i == focus).unwrap();
        assert!(x[f].hypot(y[f]) < 1e-12, "{focus} at the centre");
        for i in 0..ids.len() {
            assert!(x[i].hypot(y[i]) < 1.0, "{} inside the disk", ids[i]);
        }
        assert!(numbers(&out, "scale")[f] > 0.999);
    }
    let err = draw_err(&format!("{HYPERTREE}focus = \"a3\"\n"));
    assert!(err.contains("no node has the id or label `a3`") && err.contains("a1"), "{err}");
}

const GRAPH: &str = "[[chart]]\nname = \"g\"\nkind = \"graph\"\ndata = \"edges\"\nsource = \"from\"\ntarget = \"to\"\nweight = \"w\"\nnodes = { data = \"nodes\", id = \"id\", label = \"name\", size = \"pop\", color = \"group\", x = \"lon\", y = \"lat\" }\n";

#[test]
fn force_layout_is_deterministic_for_a_seed() {
    let a = draw_one(&format!("{GRAPH}seed = 7\n"));
    let b = draw_one(&format!("{GRAPH}seed = 7\n"));
    let c = draw_one(&format!("{GRAPH}seed = 8\n"));
    // Six nodes, then the edges (whose x and y are empty).
    assert_eq!(numbers(&a, "x")[..6], numbers(&b, "x")[..6]);
    assert_eq!(numbers(&a, "y")[..6], numbers(&b, "y")[..6]);
    let differ = numbers(&a, "x").iter().zip(numbers(&c, "x")).any(|(p, q)| (p - q).abs() > 1e-6);
    assert!(differ, "another seed gives another layout");
    assert_eq!(texts(&a, "label")[..6], ["Ex", "Why", "Zed", "Dub", "Pe", "Qu"]);
    let mut legend = 0;
    a.scene.walk(|i| legend += usize::from(i.role == Role::Legend));
    assert!(legend > 0, "colour, size and weight legends");
}

#[test]
fn layered_edges_point_down_and_circular_nodes_share_a_circle() {
    let out = draw_one(&format!("{GRAPH}layout = \"layered\"\n"));
    let caption =
        out.scene.items.iter().any(|i| matches!(&i.shape, Shape::Text(t) if t.content.contains("1 edges reversed")));
    assert!(caption, "the triangle's cycle is broken by one reversed edge, and the caption says so");
    let (x, y) = (numbers(&out, "x"), numbers(&out, "y"));
    let ids = texts(&out, "id");
    let at = |id: &str| ids.iter().position(|i| i == id).unwrap();
    assert!(y[at("w")] > y[at("z")], "z → w points down");
    assert!(y[at("q")] > y[at("p")], "p → q points down");
    let out = draw_one(&format!("{GRAPH}layout = \"circular\"\n"));
    let (x2, y2) = (numbers(&out, "x"), numbers(&out, "y"));
    let (cx, cy) = (x2[..6].iter().sum::<f64>() / 6.0, y2[..6].iter().sum::<f64>() / 6.0);
    let r: Vec<f64> = (0..6).map(|i| (x2[i] - cx).hypot(y2[i] - cy)).collect();
    for ri in &r {
        assert!((ri - r[0]).abs() < 1e-6 * r[0], "{r:?}");
    }
    assert!(x.iter().all(|v| v.is_finite() || v.is_nan()));
}

#[test]
fn given_positions_keep_their_geometry() {
    let out = draw_one(&format!("{GRAPH}layout = \"given\"\n"));
    let (x, y) = (numbers(&out, "x"), numbers(&out, "y"));
    // lon/lat: x(Why) − x(Ex) = one unit = y(Ex) − y(Zed) (y up on the page).
    let unit = x[1] - x[0];
    assert!(unit > 0.0);
    assert!(((y[0] - y[2]) - unit).abs() < 1e-9, "uniform scale, north up");
    assert!(((x[5] - x[4]) - unit).abs() < 1e-9);
}

#[test]
fn network_bad_input_names_the_problem() {
    let short_nodes = "[data.few]\nvalues = [{ id = \"x\" }, { id = \"y\" }]\n[[chart]]\nname = \"g\"\nkind = \"graph\"\ndata = \"edges\"\nsource = \"from\"\ntarget = \"to\"\nnodes = { data = \"few\", id = \"id\" }\n";
    let err = draw_err(short_nodes);
    assert!(err.contains("names target `z`, which is not in the node table"), "{err}");
    let err = draw_err(
        "[[chart]]\nname = \"g\"\nkind = \"graph\"\ndata = \"edges\"\nsource = \"from\"\ntarget = \"to\"\nlayout = \"given\"\n",
    );
    assert!(err.contains("needs a node table with `x` and `y`"), "{err}");
    let err = draw_err(
        "[[chart]]\nname = \"g\"\nkind = \"graph\"\ndata = \"edges\"\nsource = \"from\"\ntarget = \"to\"\nnodes = { data = \"nodez\", id = \"id\" }\n",
    );
    assert!(err.contains("unknown data source `nodez`; did you mean `nodes`?"), "{err}");
    let err = draw_err(
        "[[chart]]\nname = \"g\"\nkind = \"graph\"\ndata = \"edges\"\nsource = \"from\"\ntarget = \"to\"\nnodes = { data = \"nodes\", id = \"idd\" }\n",
    );
    assert!(err.contains("data \"nodes\" has no column `idd`"), "{err}");
    let loops = "from,to\na,a\na,b\n";
    let spec = "[data.e]\npath = \"e.csv\"\n[[chart]]\nname = \"g\"\nkind = \"graph\"\ndata = \"e\"\nsource = \"from\"\ntarget = \"to\"\n";
    let out = Fixture::new(spec, &[("e.csv", loops.as_bytes())]).draw().unwrap().remove(0);
    assert!(out.warnings.iter().any(|w| w.to_string().contains("1 self-loops are not drawn")), "{:?}", out.warnings);
}

const LINKMAP: &str = "[[chart]]\nname = \"l\"\nkind = \"linkmap\"\ndata = \"edges\"\nsource = \"from\"\ntarget = \"to\"\nweight = \"w\"\n";

#[test]
fn linkmap_draws_links_thin_to_thick_and_a_clustered_matrix() {
    let out = draw_one(LINKMAP);
    let mut widths = Vec::new();
    out.scene.walk(|item| {
        if item.role == Role::DataMark
            && let (Shape::Path(_), Some(stroke)) = (&item.shape, &item.style.stroke)
        {
            widths.push(stroke.width);
        }
    });
    assert_eq!(widths.len(), 5);
    assert!(widths.windows(2).all(|w| w[0] < w[1]), "heavier links later and wider: {widths:?}");
    let out = draw_one(&format!("{LINKMAP}mode = \"matrix\"\n"));
    assert_eq!(numbers(&out, "w").len(), 5, "one cell per link");
    let rows = numbers(&out, "row");
    let cols = numbers(&out, "column");
    let (src, dst) = (texts(&out, "source"), texts(&out, "target"));
    // The isolated pair p, q sits apart from the triangle: adjacent in the order.
    let pq = src.iter().position(|s| s == "p").unwrap();
    assert_eq!((rows[pq] - cols[pq]).abs(), 1.0, "p and q are neighbours in the clustered order ({:?})", dst);
}

/// Five airports: a, b, c linked near the origin; d and e far away and without a route.
const ROUTES: &str = r#"
[data.routes]
values = [{ from = "a", to = "b", n = 3 }, { from = "b", to = "c", n = 1 }]
[data.places]
values = [
  { id = "a", lon = 0, lat = 0 }, { id = "b", lon = 1, lat = 1 }, { id = "c", lon = 2, lat = 0 },
  { id = "d", lon = 150, lat = 10 }, { id = "e", lon = -120, lat = -30 },
]
"#;

/// The x extent of the drawn node circles.
fn node_circles(out: &ChartOutput) -> (usize, f64, f64) {
    let mut xs = Vec::new();
    out.scene.walk(|item| {
        if let (Role::DataMark, Shape::Circle { center, .. }) = (item.role, &item.shape) {
            xs.push(center.x);
        }
    });
    let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (xs.len(), lo, hi)
}

#[test]
fn link_views_leave_out_isolated_nodes_unless_asked() {
    let chart = |kind: &str, extra: &str| {
        format!(
            "{ROUTES}[[chart]]\nname = \"m\"\nkind = \"{kind}\"\ndata = \"routes\"\nsource = \"from\"\ntarget = \"to\"\nweight = \"n\"\nlayout = \"given\"\nnodes = {{ data = \"places\", id = \"id\", x = \"lon\", y = \"lat\"{extra} }}\n"
        )
    };
    for kind in ["linkmap", "graph"] {
        let out = draw_one(&chart(kind, ""));
        let (count, lo, hi) = node_circles(&out);
        assert_eq!(count, 3, "{kind}: only a, b and c are drawn");
        assert_eq!(texts(&out, "element").iter().filter(|e| *e == "node").count(), 3, "{kind}");
        // The linked nodes span the plot: their 2 units of longitude fill most of its width.
        assert!(hi - lo > 0.6 * out.scene.width, "{kind}: {lo}..{hi} of {}", out.scene.width);
        assert!(
            out.warnings.iter().any(|w| w.to_string().contains("2 nodes without a link were left out")),
            "{kind}: {:?}",
            out.warnings
        );
        let all = draw_one(&chart(kind, ", isolated = true"));
        let (count, lo, hi) = node_circles(&all);
        assert_eq!(count, 5, "{kind}: isolated = true draws every node");
        // 270 degrees of longitude now: a..c (2 degrees) shrink to under 2% of the spread.
        let abc: Vec<f64> = numbers(&all, "x")[..3].to_vec();
        assert!((abc[2] - abc[0]) < 0.02 * (hi - lo), "{abc:?} in {lo}..{hi}");
        assert!(all.warnings.iter().all(|w| !w.to_string().contains("left out")), "{:?}", all.warnings);
    }
}
