//! The bad-input checklist of DESIGN.md for specs, data and scales: each case asserts the exact
//! diagnostic (message, position and hint) or the documented fallback.

use crate::common::Fixture;
use dataink::data::PathPolicy;

const XY_CHART: &str = r#"
[[chart]]
name = "c"
kind = "scatter"
data = "d"
x = "x"
y = "y"
"#;

/// A spec reading `file` as data source `d`, with a scatter of x against y.
fn spec_for(file: &str) -> String {
    format!("[data.d]\npath = \"{file}\"\n{XY_CHART}")
}

fn data_error(file: &str, bytes: &[u8]) -> String {
    Fixture::new(&spec_for(file), &[(file, bytes)]).load().expect_err("loading should fail")
}

fn draw_error(file: &str, bytes: &[u8]) -> String {
    Fixture::new(&spec_for(file), &[(file, bytes)]).draw().expect_err("drawing should fail")
}

#[test]
fn typo_wrong_type_and_missing_column_are_reported_together() {
    let spec = r#"[data.iris]
path = "iris.csv"

[[chart]]
name = "iris"
kind = "scatter"
data = "iris"
x = "petal_lenght"
y = "petal_width"
colour = "species"
size = "big"
"#;
    let fx = Fixture::new(spec, &[("iris.csv", b"petal_length,petal_width,species\n1,2,a\n")]);
    let out = fx.load().expect_err("three problems");
    assert!(out.contains("error: unknown key `colour` in chart \"iris\"\n"), "{out}");
    assert!(out.contains("spec.toml:10:1\n"), "{out}");
    assert!(out.contains("^^^^^^ did you mean `color`?"), "{out}");
    assert!(out.contains("error: `size` must be an array of 2 numbers, found a string\n"), "{out}");
    assert!(out.contains("spec.toml:11:8\n"), "{out}");
    assert!(out.contains("error: chart \"iris\": data \"iris\" has no column `petal_lenght`\n"), "{out}");
    assert!(out.contains("spec.toml:8:5\n"), "{out}");
    assert!(
        out.contains("= hint: did you mean `petal_length`? columns: `petal_length`, `petal_width`, `species`"),
        "{out}"
    );
    assert_eq!(out.matches("error:").count(), 3, "{out}");
}

#[test]
fn toml_syntax_error_points_at_the_line() {
    let out = Fixture::new("[data.d]\npath = \"x.csv\n", &[]).load().expect_err("syntax");
    assert!(out.starts_with("error: "), "{out}");
    assert!(out.contains("spec.toml:2:"), "{out}");
}

#[test]
fn canvas_sizes_must_be_positive_finite_and_bounded() {
    for (size, expect, message) in [
        ("[0, 400]", "spec.toml:10:9", "error: `size[0]` must be greater than 0 and at most 16384, found 0\n"),
        ("[-5, 400]", "spec.toml:10:9", "error: `size[0]` must be greater than 0 and at most 16384, found -5\n"),
        (
            "[640, 1e9]",
            "spec.toml:10:14",
            "error: `size[1]` must be greater than 0 and at most 16384, found 1000000000\n",
        ),
        ("[nan, 400]", "spec.toml:10:9", "error: `size[0]` must be a finite number, found nan\n"),
        ("[640]", "spec.toml:10:8", "error: `size` must be an array of 2 numbers"),
    ] {
        let spec = format!("[data.d]\nvalues = [{{ x = 1, y = 2 }}]\n{XY_CHART}size = {size}\n");
        let out = Fixture::new(&spec, &[]).load().expect_err(size);
        assert!(out.contains(expect), "{size}: {out}");
        assert!(out.contains(message), "{size}: {out}");
    }
}

#[test]
fn absolute_and_escaping_paths_are_refused_unless_allowed() {
    let out = Fixture::new(&spec_for("/etc/hosts"), &[]).load().expect_err("absolute");
    assert!(out.contains("error: data \"d\": data path `/etc/hosts` is absolute\n"), "{out}");
    assert!(out.contains("= hint: write the path relative to the spec file and keep the data beside it, or pass --allow-outside-paths"), "{out}");

    let out = Fixture::new(&spec_for("../outside.csv"), &[]).load().expect_err("escape");
    assert!(out.contains("error: data \"d\": data path `../outside.csv` leaves the spec's folder\n"), "{out}");
    assert!(out.contains("spec.toml:2:8"), "{out}");

    // With the flag, the same path is read (here it does not exist, which is the next error).
    let fx = Fixture::new(&spec_for("../definitely-missing-dataink.csv"), &[]);
    let out = fx.load_with(PathPolicy::AllowOutside).expect_err("missing");
    assert!(out.contains("definitely-missing-dataink.csv` does not exist"), "{out}");
}

#[test]
fn empty_file_has_no_columns() {
    let out = data_error("d.csv", b"");
    assert!(out.contains("error: data \"d\": `"), "{out}");
    assert!(out.contains("d.csv` has no columns (is the file empty?)\n"), "{out}");
    assert!(out.contains("= hint: the source needs a header row and at least one column"), "{out}");
}

#[test]
fn header_only_file_has_no_rows() {
    let out = draw_error("d.csv", b"x,y\n");
    assert!(out.contains("error: chart \"c\": data \"d\" has no rows\n"), "{out}");
}

#[test]
fn ragged_rows_are_a_parse_error() {
    let out = data_error("d.csv", b"x,y\n1,2\n3,4,5\n");
    assert!(out.contains("as CSV: found more fields than defined in 'Schema'\n"), "{out}");
    assert!(
        out.contains("= hint: CSV needs a header row, UTF-8 text and the same number of fields on every row"),
        "{out}"
    );
}

#[test]
fn byte_order_mark_is_ignored() {
    let out = Fixture::new(&spec_for("d.csv"), &[("d.csv", b"\xef\xbb\xbfx,y\n1,2\n2,3\n")]).draw().expect("BOM");
    assert_eq!(out[0].derived.len(), 2);
}

#[test]
fn invalid_utf8_is_a_parse_error() {
    let out = data_error("d.csv", b"x,y\n1,2\n\xff\xfe,3\n");
    assert!(out.contains("as CSV: invalid utf-8 sequence\n"), "{out}");
}

#[test]
fn non_finite_cells_are_dropped_with_a_counted_warning() {
    let fx = Fixture::new(&spec_for("d.csv"), &[("d.csv", b"x,y\n1,2\nNaN,3\ninf,4\n1e999,5\n2,6\n-inf,7\n")]);
    let out = fx.draw().expect("draws");
    assert_eq!(out[0].derived.len(), 2);
    assert_eq!(
        out[0].warnings.iter().map(ToString::to_string).collect::<Vec<_>>(),
        vec![
            "chart \"c\": dropped 4 of 6 rows with missing or non-finite values (`x`: 1 missing or NaN, 3 infinite)"
                .to_string()
        ]
    );
}

#[test]
fn all_missing_columns_leave_no_rows() {
    let out = draw_error("d.csv", b"x,y\n,\n,\n");
    assert!(
        out.contains("error: chart \"c\": no rows left to plot out of 2: every row has missing or non-finite values (`x`: 2 missing or NaN; `y`: 2 missing or NaN)\n"),
        "{out}"
    );
}

#[test]
fn single_row_and_constant_columns_get_a_padded_domain() {
    for data in [&b"x,y\n1,2\n"[..], &b"x,y\n1,2\n1,2\n1,2\n"[..]] {
        let out = Fixture::new(&spec_for("d.csv"), &[("d.csv", data)]).draw().expect("draws");
        let scene = &out[0].scene;
        // The single point lands in the middle of the plot: the domain is padded symmetrically.
        let mut centre = None;
        scene.walk(|item| {
            if let dataink::scene::Shape::Points(batch) = &item.shape {
                centre = batch.centers.first().copied();
            }
        });
        let p = centre.expect("one point");
        let mut plot = None;
        scene.walk(|item| {
            if let dataink::scene::Shape::Group { clip: Some(r), .. } = &item.shape {
                plot = Some(*r);
            }
        });
        let r = plot.expect("plot clip");
        assert!((p.x - (r.x + r.w / 2.0)).abs() < 1e-6, "{p:?} {r:?}");
        assert!((p.y - (r.y + r.h / 2.0)).abs() < 1e-6, "{p:?} {r:?}");
    }
}

#[test]
fn missing_column_lists_the_real_columns() {
    let spec = format!("[data.d]\npath = \"d.csv\"\n{}", XY_CHART.replace("y = \"y\"", "y = \"why\""));
    let out = Fixture::new(&spec, &[("d.csv", b"x,y\n1,2\n")]).load().expect_err("missing");
    assert!(out.contains("error: chart \"c\": data \"d\" has no column `why`\n"), "{out}");
    assert!(out.contains("= hint: columns: `x`, `y`"), "{out}");
}

#[test]
fn corrupt_parquet_is_a_parse_error() {
    let out = data_error("d.parquet", b"PAR1 not really parquet");
    assert!(out.contains("as Parquet: "), "{out}");
    assert!(out.contains("= hint: the file is not a readable Parquet file"), "{out}");
}

#[test]
fn log_scale_with_a_non_positive_domain_names_the_smallest() {
    // Rows ≤ 0 on a log axis are dropped (see `log_axis_drops_rows_it_cannot_place`); a fixed
    // domain reaching zero or below is the spec's own mistake.
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n{}",
        XY_CHART.replace("x = \"x\"", "x = { field = \"x\", scale = \"log\", domain = [-1, 10] }")
    );
    let out = Fixture::new(&spec, &[("d.csv", b"x,y\n-1,2\n0,3\n5,4\n")]).draw().expect_err("log");
    assert!(
        out.contains(
            "error: chart \"c\": x axis: a log scale needs values greater than 0, but the smallest value is -1"
        ),
        "{out}"
    );
    assert!(out.contains("spec.toml:8:5"), "{out}");
}

#[test]
fn log_axis_drops_rows_it_cannot_place() {
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n{}",
        XY_CHART.replace("x = \"x\"", "x = { field = \"x\", scale = \"log\" }")
    );
    let files: &[(&str, &[u8])] = &[("d.csv", b"x,y\n0,1\n-1,2\n1,3\n10,4\n100,5\n")];
    let out = Fixture::new(&spec, files).draw().unwrap_or_else(|e| panic!("{e}"));
    let mut drawn = Vec::new();
    out[0].scene.walk(|item| {
        if item.role == dataink::scene::Role::DataMark && matches!(item.shape, dataink::scene::Shape::Points(_)) {
            drawn.extend(item.rows.iter().copied());
        }
    });
    assert_eq!(drawn, [2, 3, 4], "the rows with x = 1, 10, 100");
    assert_eq!(
        out[0].warnings.iter().map(ToString::to_string).collect::<Vec<_>>(),
        ["chart \"c\": dropped 2 of 5 rows with missing or non-finite values or values ≤ 0 on a log axis \
          (`x`: 2 ≤ 0 on a log axis)"]
    );
    let di003 = crate::common::lint_findings(&spec, files, "DI003");
    assert_eq!(di003.len(), 1, "{di003:?}");
    assert_eq!(
        di003[0].message,
        "2 of 5 values of `x` are ≤ 0 and cannot be placed on the log-scaled x axis: their rows are left out"
    );
}

#[test]
fn text_column_on_a_linear_scale_is_refused() {
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n{}",
        XY_CHART.replace("x = \"x\"", "x = { field = \"x\", scale = \"linear\" }")
    );
    let out = Fixture::new(&spec, &[("d.csv", b"x,y\na,2\nb,3\n")]).draw().expect_err("text");
    assert!(out.contains("error: chart \"c\": column `x` holds text, which a linear scale cannot place\n"), "{out}");
    assert!(out.contains("= hint: use scale = \"band\" for categories, or a numeric column"), "{out}");
}

#[test]
fn unknown_colour_scheme_suggests_the_closest() {
    let spec = format!("[data.d]\npath = \"d.csv\"\n{}color = {{ field = \"y\", scheme = \"virdis\" }}\n", XY_CHART);
    // Fractional values: a continuous colour (few whole numbers would be categories).
    let out = Fixture::new(&spec, &[("d.csv", b"x,y\n1,2.5\n2,3.25\n")]).draw().expect_err("scheme");
    assert!(out.contains("error: chart \"c\": unknown continuous colour scheme `virdis`\n"), "{out}");
    assert!(out.contains("= hint: did you mean `viridis`?"), "{out}");
}

#[test]
fn canvas_too_small_for_its_guides() {
    let spec = format!("[data.d]\nvalues = [{{ x = 1, y = 2 }}]\n{XY_CHART}size = [60, 40]\n");
    let out = Fixture::new(&spec, &[]).draw().expect_err("too small");
    assert!(out.contains("error: chart \"c\": the canvas is too small"), "{out}");
    assert!(out.contains("= hint: make `size` larger or `font_size` smaller"), "{out}");
}

#[test]
fn missing_values_as_people_write_them_keep_a_column_numeric() {
    // Each spelling alone in a numeric column: before, `nan` or `NA` turned `y` into text,
    // drawn as band categories with no warning.
    for missing in ["nan", "NA", "N/A", "null", "None", "#N/A", "-nan", "<NA>"] {
        let csv = format!("x,y\n1,2\n2,{missing}\n3,4\n");
        let fx = Fixture::new(&spec_for("d.csv"), &[("d.csv", csv.as_bytes())]);
        let out = fx.draw().unwrap_or_else(|e| panic!("{missing}: {e}"));
        assert_eq!(out[0].derived.len(), 2, "{missing}");
        assert_eq!(
            out[0].warnings.iter().map(ToString::to_string).collect::<Vec<_>>(),
            vec![
                "chart \"c\": dropped 1 of 3 rows with missing or non-finite values (`y`: 1 missing or NaN)"
                    .to_string()
            ],
            "{missing}"
        );
    }
}

#[test]
fn null_values_replaces_the_missing_list() {
    let spec = |list: &str| {
        format!(
            "[data.d]\npath = \"d.csv\"\nnull_values = {list}\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\n"
        )
    };
    // A sentinel the source names is missing; `NA` is then an ordinary text again.
    let csv: &[u8] = b"x,y\n1,2\n2,-999\n3,4\n";
    let out = Fixture::new(&spec("[\"-999\"]"), &[("d.csv", csv)]).draw().expect("draws");
    assert_eq!(out[0].derived.len(), 2);
    let loaded = Fixture::new(&spec("[]"), &[("d.csv", b"x,y\n1,2\n2,NA\n3,4\n")]).load().expect("loads");
    let y = loaded.tables["d"].column("y").expect("y");
    let dataink::data::ColumnValues::Text(categories) = &y.values else { panic!("`NA` is text under `[]`: {y:?}") };
    assert_eq!(categories.levels, ["2", "NA", "4"]);
}

#[test]
fn a_quote_opening_the_last_field_is_refused_before_parsing() {
    // polars' line parser read past its buffer on this ending (an abort in a debug build).
    for ending in ["\"", "1,\""] {
        let csv = format!("x,y\n1,2\n{ending}");
        let out = data_error("d.csv", csv.as_bytes());
        assert!(out.contains("the file ends with a quote that opens a field and is never closed"), "{out}");
    }
}

#[test]
fn keys_and_values_from_other_tools_get_the_dataink_spelling() {
    let values = "[data.d]\nvalues = [{ x = 1, y = 2 }, { x = 2, y = 3 }]\n";
    let out = |extra: &str| Fixture::new(&format!("{values}{XY_CHART}{extra}\n"), &[]).load().expect_err("unknown key");
    // matplotlib's `cmap = "jet"`: not "did you mean `color`", but how a scheme is named.
    let cmap = out("colormap = \"jet\"");
    assert!(cmap.contains("error: unknown key `colormap` in chart \"c\"\n"), "{cmap}");
    assert!(cmap.contains("a colour map is the `scheme` of a colour encoding"), "{cmap}");
    assert!(cmap.contains("= hint: write `color = { field = \"COLUMN\", scheme = \"viridis\" }`"), "{cmap}");
    let log = out("y_scale = \"log\"");
    // The hint names the chart's own column where it has one.
    assert!(log.contains("= hint: write `y = { field = \"y\", scale = \"log\" }`"), "{log}");
    assert!(!log.contains("keys allowed here"), "{log}");
    let label = out("xlabel = \"Time\"");
    assert!(label.contains("= hint: write `x = { field = \"x\", title = \"...\", unit = \"...\" }`"), "{label}");
    let hue = out("hue = \"species\"");
    assert!(hue.contains("= hint: write `color = \"COLUMN\"`"), "{hue}");
    // A rainbow scheme is named as one, with the schemes to use instead.
    let fractional = "[data.d]\nvalues = [{ x = 1, y = 2.5 }, { x = 2, y = 3.25 }]\n";
    let jet = Fixture::new(&format!("{fractional}{XY_CHART}color = {{ field = \"y\", scheme = \"jet\" }}\n"), &[])
        .draw()
        .expect_err("jet");
    assert!(jet.contains("error: chart \"c\": unknown continuous colour scheme `jet`\n"), "{jet}");
    assert!(jet.contains("rainbow maps") && jet.contains("use `viridis`, `cividis` or `magma`"), "{jet}");
    // interp1d's methods: the harmonic-mean slopes are `pchip`.
    let interp = "[data.d]\nvalues = [{ x = 1, y = 2 }, { x = 2, y = 3 }, { x = 3, y = 1 }]\n[[chart]]\nname = \"c\"\nkind = \"interp1d\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\nmethods = [\"harmonic\"]\n";
    let harmonic = Fixture::new(interp, &[]).load().expect_err("harmonic");
    assert!(harmonic.contains("(Fritsch–Carlson) is `pchip`; expected one of:"), "{harmonic}");
}

#[test]
fn engine_sources_name_what_they_lack_or_cannot_take() {
    let load =
        |source: &str| Fixture::new(&format!("[data.d]\n{source}\n{XY_CHART}"), &[]).load().expect_err("refused");
    let out = load("engine = \"sc://127.0.0.1:1\"");
    assert!(out.contains("error: `data.d` has an `engine` but neither `path` nor `table`"), "{out}");
    let out = load("engine = \"sc://127.0.0.1:1\"\npath = \"a.parquet\"\ntable = \"t\"");
    assert!(out.contains("error: `data.d` has both `path` and `table`"), "{out}");
    let out = load("engine = \"sc://127.0.0.1:1\"\ntable = \"t\"\nfrom = \"e\"");
    assert!(out.contains("error: `data.d` is on an engine and cannot take `from`"), "{out}");
    let out = load("path = \"a.csv\"\ntable = \"t\"");
    assert!(out.contains("error: `data.d` names a `table` but no `engine`"), "{out}");
    let out = load("engine = \"df://127.0.0.1:50050\"\ntable = \"t\"");
    assert!(out.contains("Ballista (`df://`) is not supported") && out.contains("spec.toml:2:10"), "{out}");
    let out = load("engine = \"sc://127.0.0.1:1\"\ntable = \"t\"\ntransform = [{ sample = 5 }]");
    assert!(out.contains("transform step 1: this step does not run on an engine source"), "{out}");
}
