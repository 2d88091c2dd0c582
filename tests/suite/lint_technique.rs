//! Integrity, comparison and technique lint rules (DI001, DI002, CM001, TQ001–TQ005): for every
//! rule a spec that triggers it and a near-identical one that does not, and the numbers the
//! findings report against hand computations.

use crate::common::{lint_codes, lint_findings};

/// Whether `code` is among the sorted codes found.
fn has(codes: &[&str], code: &str) -> bool {
    codes.contains(&code)
}

// DI001 nonzero-baseline.

const BARS: &str = "k,v\na,50\nb,60\n";

fn bar_spec(y: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"b\"\nkind = \"bar\"\ndata = \"d\"\ntitle = \"Bars\"\nx = \"k\"\ny = {y}\n"
    )
}

#[test]
fn di001_fires_for_bars_from_a_nonzero_domain_and_reports_the_lie_factor() {
    let files: [(&str, &[u8]); 1] = [("d.csv", BARS.as_bytes())];
    let spec = bar_spec("{ field = \"v\", domain = [40, 70] }");
    let found = lint_findings(&spec, &files, "DI001");
    assert_eq!(found.len(), 1, "{found:?}");
    // Drawn from 40, the bars are 10 and 20 long: the shown effect (20 − 10) / 10 = 1 against
    // the data's (60 − 50) / 50 = 0.2, a lie factor of 5.
    let m = &found[0].message;
    assert!(m.contains("starts at 40 instead of 0"), "{m}");
    assert!(m.contains("drawn 2.00× as long"), "{m}");
    assert!(m.contains("only 1.20× as large"), "{m}");
    assert!(m.contains("lie factor 5.00"), "{m}");
    assert_eq!(found[0].path, "chart[0].y.domain");
    assert_eq!(found[0].severity.name(), "error");
    // The same bars from zero are honest.
    assert!(!has(&lint_codes(&bar_spec("\"v\""), &files), "DI001"));
    assert!(!has(&lint_codes(&bar_spec("{ field = \"v\", domain = [0, 70] }"), &files), "DI001"));
}

#[test]
fn di001_zero_false_hides_the_smallest_bar_entirely() {
    let files: [(&str, &[u8]); 1] = [("d.csv", BARS.as_bytes())];
    // The nice domain of 50..60 starts at 50: the smallest bar has no length at all.
    let found = lint_findings(&bar_spec("{ field = \"v\", zero = false }"), &files, "DI001");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].message.contains("lie factor ∞"), "{}", found[0].message);
    assert_eq!(found[0].path, "chart[0].y.zero");
    assert!(!has(&lint_codes(&bar_spec("{ field = \"v\", zero = true }"), &files), "DI001"));
}

#[test]
fn di001_measures_negative_bars_from_the_top() {
    let data = "k,v\na,-50\nb,-60\n";
    let files: [(&str, &[u8]); 1] = [("d.csv", data.as_bytes())];
    let found = lint_findings(&bar_spec("{ field = \"v\", domain = [-70, -40] }"), &files, "DI001");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].message.contains("starts at −40 instead of 0"), "{}", found[0].message);
    assert!(found[0].message.contains("lie factor 5.00"), "{}", found[0].message);
    assert!(!has(&lint_codes(&bar_spec("\"v\""), &files), "DI001"));
}

// DI002 size-by-radius.

const SIZED: &str = "x,y,s\n1,1,1\n2,2,4\n3,3,2\n4,4,0\n";

fn sized_spec(mapping: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"s\"\nkind = \"scatter\"\ndata = \"d\"\ntitle = \"Sized\"\nx = \"x\"\ny = \"y\"\npoint_size = {{ field = \"s\"{mapping} }}\n"
    )
}

#[test]
fn di002_fires_for_radius_mapping_with_the_measured_lie_factor() {
    let files: [(&str, &[u8]); 1] = [("d.csv", SIZED.as_bytes())];
    let found = lint_findings(&sized_spec(", mapping = \"radius\""), &files, "DI002");
    assert_eq!(found.len(), 1, "{found:?}");
    // Values 4 and 1 (0 is left out): radii 4:1, areas 16:1, values 4:1, lie factor 4.
    let m = &found[0].message;
    assert!(m.contains("largest value (4) is 4.00× the smallest non-zero one (1)"), "{m}");
    assert!(m.contains("covers 16.00× the area, a lie factor of 4.00"), "{m}");
    assert_eq!(found[0].path, "chart[0].point_size.mapping");
    assert!(!has(&lint_codes(&sized_spec(""), &files), "DI002"));
    assert!(!has(&lint_codes(&sized_spec(", mapping = \"area\""), &files), "DI002"));
}

// CM001 unshared-scales.

/// A grid where z = x·(1 + 9y) on x, y ∈ {0, 0.5, 1}: the section at y = 1 is ten times the one
/// at y = 0.
fn section_spec(extra: &str) -> (String, String) {
    let mut csv = String::from("x,y,z\n");
    for y in [0.0, 0.5, 1.0] {
        for x in [0.0, 0.25, 0.5, 0.75, 1.0] {
            csv.push_str(&format!("{x},{y},{}\n", x * (1.0 + 9.0 * y)));
        }
    }
    let spec = format!(
        "[data.g]\npath = \"g.csv\"\n\n[[chart]]\nname = \"m\"\nkind = \"section\"\ndata = \"g\"\ntitle = \"Sections\"\nsize = [640, 600]\nx = \"x\"\ny = \"y\"\nz = \"z\"\nat_y = [0, 1]\nlayout = \"multiples\"\n{extra}"
    );
    (spec, csv)
}

#[test]
fn cm001_fires_for_section_multiples_with_their_own_scales() {
    let (spec, csv) = section_spec("shared_scale = false\n");
    let files: [(&str, &[u8]); 1] = [("g.csv", csv.as_bytes())];
    let found = lint_findings(&spec, &files, "CM001");
    assert_eq!(found.len(), 1, "{found:?}");
    let m = &found[0].message;
    assert!(m.contains("the 2 panels do not share their value scale (1 differs from the first"), "{m}");
    assert!(m.contains("panel 1: 0.0 to 1.0") && m.contains("panel 2: 0 to 10"), "{m}");
    assert_eq!(found[0].path, "chart[0].shared_scale");
    let (spec, csv) = section_spec("");
    let files: [(&str, &[u8]); 1] = [("g.csv", csv.as_bytes())];
    assert!(!has(&lint_codes(&spec, &files), "CM001"));
}

// TQ001 tiny-treemap-leaves.

/// A root with one leaf of `big` and 40 leaves of 1.
fn treemap_spec(big: f64) -> (String, String) {
    let mut csv = String::from("id,parent,size\nroot,,\nbig,root,");
    csv.push_str(&format!("{big}\n"));
    for i in 0..40 {
        csv.push_str(&format!("leaf{i},root,1\n"));
    }
    let spec = "[data.t]\npath = \"t.csv\"\n\n[[chart]]\nname = \"t\"\nkind = \"treemap\"\ndata = \"t\"\ntitle = \"Tree\"\ntree = { id = \"id\", parent = \"parent\" }\nvalue = \"size\"\n".to_string();
    (spec, csv)
}

#[test]
fn tq001_fires_when_most_leaves_are_slivers() {
    // One leaf of a million beside 40 of 1: each small leaf gets under a pixel².
    let (spec, csv) = treemap_spec(1e6);
    let files: [(&str, &[u8]); 1] = [("t.csv", csv.as_bytes())];
    let found = lint_findings(&spec, &files, "TQ001");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].message.starts_with("40 of 41 leaves (98%) are under 2 px"), "{}", found[0].message);
    // With the big leaf only 40 times a small one, every leaf is large enough.
    let (spec, csv) = treemap_spec(40.0);
    let files: [(&str, &[u8]); 1] = [("t.csv", csv.as_bytes())];
    assert!(!has(&lint_codes(&spec, &files), "TQ001"));
}

// TQ002 edge-crossings.

/// 40 nodes on a circle with `edges` as (source, target) pairs.
fn graph_spec(edges: &[(u32, u32)]) -> (String, String) {
    let mut csv = String::from("from,to\n");
    for (a, b) in edges {
        csv.push_str(&format!("n{a},n{b}\n"));
    }
    let spec = "[data.e]\npath = \"e.csv\"\n\n[[chart]]\nname = \"g\"\nkind = \"graph\"\ndata = \"e\"\ntitle = \"Graph\"\nsource = \"from\"\ntarget = \"to\"\nlayout = \"circular\"\nlabels = false\n".to_string();
    (spec, csv)
}

#[test]
fn tq002_fires_for_a_random_dense_graph_on_a_circle_but_not_for_a_tree() {
    // 200 distinct random edges between 40 nodes (a fixed linear congruential sequence).
    let mut state: u64 = 12345;
    let mut next = |n: u64| {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 33) % n) as u32
    };
    let mut edges: Vec<(u32, u32)> = Vec::new();
    while edges.len() < 200 {
        let (a, b) = (next(40), next(40));
        if a != b && !edges.contains(&(a, b)) && !edges.contains(&(b, a)) {
            edges.push((a, b));
        }
    }
    let (spec, csv) = graph_spec(&edges);
    let files: [(&str, &[u8]); 1] = [("e.csv", csv.as_bytes())];
    let found = lint_findings(&spec, &files, "TQ002");
    assert_eq!(found.len(), 1, "{found:?}");
    // About m / 6 ≈ 33 crossings per edge for random chords, fewer after the circular order.
    let per_edge: f64 = found[0]
        .message
        .split(" crossings per edge")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{}", found[0].message));
    assert!(per_edge > 10.0 && per_edge < 40.0, "{per_edge}");
    assert!(found[0].message.starts_with("the 200 edges cross"), "{}", found[0].message);
    // A binary tree on the same 40 nodes.
    let tree: Vec<(u32, u32)> = (1..40).map(|i| ((i - 1) / 2, i)).collect();
    let (spec, csv) = graph_spec(&tree);
    let files: [(&str, &[u8]); 1] = [("e.csv", csv.as_bytes())];
    assert!(!has(&lint_codes(&spec, &files), "TQ002"));
}

// TQ003 contour-levels-unlabelled.

fn contour_spec(extra: &str) -> (String, String) {
    let mut csv = String::from("x,y,z\n");
    for j in 0..11 {
        for i in 0..11 {
            let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
            csv.push_str(&format!("{x},{y},{}\n", x * x + y * y));
        }
    }
    let spec = format!(
        "[data.g]\npath = \"g.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"contour\"\ndata = \"g\"\ntitle = \"Bowl\"\nx = \"x\"\ny = \"y\"\nlevels = [0.5, 1, 1.5]\n{extra}"
    );
    (spec, csv)
}

#[test]
fn tq003_fires_for_contour_lines_without_labels_or_colour_bar() {
    let (spec, csv) = contour_spec("z = { field = \"z\", legend = false }\nlabels = false\n");
    let files: [(&str, &[u8]); 1] = [("g.csv", csv.as_bytes())];
    let found = lint_findings(&spec, &files, "TQ003");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].message.contains("contour lines at 3 levels carry no value labels"), "{}", found[0].message);
    assert_eq!(found[0].path, "chart[0].labels");
    // Labels on the lines tell the levels even without the colour bar; so does the colour bar.
    for extra in ["z = { field = \"z\", legend = false }\n", "z = \"z\"\nlabels = false\n"] {
        let (spec, csv) = contour_spec(extra);
        let files: [(&str, &[u8]); 1] = [("g.csv", csv.as_bytes())];
        assert!(!has(&lint_codes(&spec, &files), "TQ003"), "{extra}");
    }
}

// TQ004 flow-without-key.

fn flow_spec(layers: &str) -> (String, String) {
    let mut csv = String::from("x,y,u,v\n");
    for j in 0..21 {
        for i in 0..21 {
            let (x, y) = (-1.0 + 0.1 * i as f64, -1.0 + 0.1 * j as f64);
            csv.push_str(&format!("{x},{y},{},{}\n", -y, x));
        }
    }
    let spec = format!(
        "[data.f]\npath = \"f.csv\"\n\n[[chart]]\nname = \"f\"\nkind = \"flow\"\ndata = \"f\"\ntitle = \"Vortex\"\nx = \"x\"\ny = \"y\"\nu = \"u\"\nv = \"v\"\nlayers = {layers}\n"
    );
    (spec, csv)
}

#[test]
fn tq004_fires_when_speed_is_shown_nowhere() {
    for layers in ["[\"streamlines\"]", "[\"lic\"]"] {
        let (spec, csv) = flow_spec(layers);
        let files: [(&str, &[u8]); 1] = [("f.csv", csv.as_bytes())];
        let found = lint_findings(&spec, &files, "TQ004");
        assert_eq!(found.len(), 1, "{layers}: {found:?}");
        assert!(found[0].message.starts_with("the flow's speed is shown nowhere"), "{}", found[0].message);
        assert_eq!(found[0].path, "chart[0].layers");
    }
    // A speed image with its colour bar, or arrows with their key, show the speed.
    for layers in ["[\"speed\", \"streamlines\"]", "[\"lic\", \"arrows\"]", "[\"arrows\"]"] {
        let (spec, csv) = flow_spec(layers);
        let files: [(&str, &[u8]); 1] = [("f.csv", csv.as_bytes())];
        assert!(!has(&lint_codes(&spec, &files), "TQ004"), "{layers}");
    }
}

// TQ005 faces-without-key.

fn faces_spec(extra: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"f\"\nkind = \"faces\"\ndata = \"d\"\ntitle = \"Faces\"\ncolumns = [\"a\", \"b\"]\n{extra}"
    )
}

#[test]
fn tq005_fires_for_faces_without_their_key() {
    let data = "a,b\n1,4\n2,3\n3,2\n4,1\n";
    let files: [(&str, &[u8]); 1] = [("d.csv", data.as_bytes())];
    let found = lint_findings(&faces_spec("key = false\n"), &files, "TQ005");
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].severity.name(), "error");
    assert_eq!(found[0].path, "chart[0].key");
    assert!(!has(&lint_codes(&faces_spec(""), &files), "TQ005"));
    assert!(!has(&lint_codes(&faces_spec("key = true\n"), &files), "TQ005"));
}
