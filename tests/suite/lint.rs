//! Lint engine and the scale, labelling, integrity and overplotting rules: for every rule one spec
//! that triggers it and a near-identical one that does not; configuration (`allow`, `deny`,
//! unknown rules); the command's formats and exit codes; and the gallery linting clean.

use std::process::Command;

use dataink::lint::Finding;

use crate::common::{Fixture, lint_codes, lint_findings, root};

/// 200 rows: `x` in [0, 10), `y` in [0, 5), `temp_c` = 20 + 5 sin x, `w` in [−1, 3), `cat` with
/// 40 levels; a fixed linear congruential sequence, so every run sees the same data.
fn table_csv() -> Vec<u8> {
    let mut state: u64 = 12345;
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut out = String::from("x,y,temp_c,w,cat\n");
    for i in 0..200 {
        let (x, y, w) = (10.0 * next(), 5.0 * next(), 4.0 * next() - 1.0);
        out.push_str(&format!("{x:.4},{y:.4},{:.3},{w:.3},c{}\n", 20.0 + 5.0 * x.sin(), i % 40));
    }
    out.into_bytes()
}

/// A scatter chart of the table with extra keys.
fn scatter(extra: &str) -> String {
    format!("[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\n{extra}\n")
}

/// The codes found in a scatter chart with `extra` keys.
fn codes(extra: &str) -> Vec<&'static str> {
    let data = table_csv();
    lint_codes(&scatter(extra), &[("d.csv", &data)])
}

const TITLED: &str = "title = \"Scatter\"\nopacity = 0.4\nx = \"x\"\ny = \"y\"";

#[test]
fn a_plain_titled_scatter_is_clean() {
    assert_eq!(codes(TITLED), Vec::<&str>::new());
}

#[test]
fn lb001_missing_title() {
    assert_eq!(codes("opacity = 0.4\nx = \"x\"\ny = \"y\""), ["LB001"]);
    assert!(!codes(TITLED).contains(&"LB001"));
}

#[test]
fn sc001_axis_without_ticks() {
    let tiny = "title = \"T\"\nopacity = 0.3\nsize = [170, 150]\nfont_size = 14\nx = \"x\"\ny = \"y\"";
    let found = codes(tiny);
    assert!(found.contains(&"SC001"), "{found:?}");
    let roomy = "title = \"T\"\nopacity = 0.3\nsize = [170, 250]\nfont_size = 14\nx = \"x\"\ny = \"y\"";
    assert!(!codes(roomy).contains(&"SC001"), "{:?}", codes(roomy));
}

#[test]
fn sc002_axis_title_without_unit() {
    let data = table_csv();
    let spec = scatter("title = \"T\"\nopacity = 0.4\nx = \"x\"\ny = { field = \"temp_c\", title = \"Temperature\" }");
    let found = lint_findings(&spec, &[("d.csv", &data)], "SC002");
    assert_eq!(found.len(), 1);
    assert!(found[0].message.contains("°C"), "{}", found[0].message);
    assert_eq!(found[0].path, "chart[0].y");
    let with_unit =
        "title = \"T\"\nopacity = 0.4\nx = \"x\"\ny = { field = \"temp_c\", title = \"Temperature\", unit = \"°C\" }";
    assert!(!codes(with_unit).contains(&"SC002"));
}

#[test]
fn sc003_tick_count() {
    assert!(codes(&format!("{TITLED}\n")).iter().all(|c| *c != "SC003"));
    let few = "title = \"T\"\nopacity = 0.4\nx = { field = \"x\", ticks = 2 }\ny = \"y\"";
    assert_eq!(codes(few), ["SC003"]);
    let many = "title = \"T\"\nopacity = 0.4\nsize = [1600, 400]\nx = { field = \"x\", ticks = 40 }\ny = \"y\"";
    let data = table_csv();
    let found = lint_findings(&scatter(many), &[("d.csv", &data)], "SC003");
    assert_eq!(found.len(), 1);
    assert!(found[0].message.contains("too many"), "{}", found[0].message);
    let six = "title = \"T\"\nopacity = 0.4\nsize = [1600, 400]\nx = { field = \"x\", ticks = 6 }\ny = \"y\"";
    assert!(!codes(six).contains(&"SC003"));
}

#[test]
fn sc004_colour_without_legend() {
    let hidden = "title = \"T\"\nopacity = 0.4\nx = \"x\"\ny = \"y\"\ncolor = { field = \"w\", legend = false }";
    assert_eq!(codes(hidden), ["SC004"]);
    let shown = "title = \"T\"\nopacity = 0.4\nx = \"x\"\ny = \"y\"\ncolor = { field = \"w\" }";
    assert!(!codes(shown).contains(&"SC004"));
}

#[test]
fn lb002_and_lb003_text_overlap_and_clipping() {
    let long = "title = \"Long y title\"\nsize = [400, 220]\nopacity = 0.4\nx = \"x\"\n\
                y = { field = \"y\", title = \"A very long axis title that is much longer than the plot is tall\" }";
    let found = codes(long);
    assert!(found.contains(&"LB002") && found.contains(&"LB003"), "{found:?}");
    let data = table_csv();
    let overlap = lint_findings(&scatter(long), &[("d.csv", &data)], "LB002");
    assert!(
        overlap[0].message.contains("y axis title") && overlap[0].message.contains("title \"Long y title\""),
        "{}",
        overlap[0].message
    );
    let short = "title = \"Long y title\"\nsize = [400, 220]\nopacity = 0.4\nx = \"x\"\ny = { field = \"y\", title = \"Height\" }";
    let found = codes(short);
    assert!(!found.contains(&"LB002") && !found.contains(&"LB003"), "{found:?}");
}

#[test]
fn lb003_a_long_legend_is_cut_to_the_room_it_has() {
    // 40 categories beside a 200 px tall chart: the legend shows what fits and says how many
    // more there are, so nothing runs off the canvas.
    let many = "title = \"T\"\nsize = [400, 200]\nopacity = 0.4\nx = \"x\"\ny = \"y\"\ncolor = \"cat\"";
    assert!(!codes(many).contains(&"LB003"));
    let data = table_csv();
    let out = Fixture::new(&scatter(many), &[("d.csv", &data)]).draw().unwrap_or_else(|e| panic!("{e}"));
    let mut summary = None;
    out[0].scene.walk(|item| {
        if let dataink::scene::Shape::Text(t) = &item.shape
            && t.content.starts_with("… and ")
        {
            summary = Some(t.content.clone());
        }
    });
    assert_eq!(summary.as_deref(), Some("… and 35 more"));
}

#[test]
fn lb004_text_too_small() {
    let small = "title = \"T\"\nfont_size = 7\nopacity = 0.4\nx = \"x\"\ny = \"y\"";
    let data = table_csv();
    let found = lint_findings(&scatter(small), &[("d.csv", &data)], "LB004");
    assert_eq!(found.len(), 1);
    assert!(found[0].message.contains("7.0 px"), "{}", found[0].message);
    let nine = "title = \"T\"\nfont_size = 10\nopacity = 0.4\nx = \"x\"\ny = \"y\"";
    assert!(!codes(nine).contains(&"LB004"));
}

#[test]
fn lb005_treemap_labels_keep_aa_contrast_on_every_cell() {
    // Labels choose black or white for their cell, which always reaches 4.58:1; dataink draws no
    // low-contrast text itself, so the rule's trigger is tested on a hand-made scene in
    // `src/lint/rules/text_contrast.rs`. Here: a treemap with mid-tone cells stays clean.
    let data = b"id,parent,size\nroot,,\na,root,10\nb,root,20\nc,root,30\nd,root,25\ne,root,15\n";
    let spec = "[data.t]\npath = \"t.csv\"\n\n[[chart]]\nname = \"t\"\nkind = \"treemap\"\ndata = \"t\"\ntitle = \"T\"\n\
                tree = { id = \"id\", parent = \"parent\" }\nvalue = \"size\"\ncolor_by = \"value\"\nscheme = \"greys\"\n";
    assert!(!lint_codes(spec, &[("t.csv", data)]).contains(&"LB005"));
}

#[test]
fn di003_log_axis_with_nonpositive_values() {
    let log = "title = \"T\"\nopacity = 0.4\nx = \"x\"\ny = { field = \"w\", scale = \"log\", domain = [0.1, 3] }";
    let found = codes(log);
    assert!(found.contains(&"DI003"), "{found:?}");
    let linear = "title = \"T\"\nopacity = 0.4\nx = \"x\"\ny = { field = \"y\", scale = \"log\", domain = [0.001, 5] }";
    assert!(!codes(linear).contains(&"DI003"), "{:?}", codes(linear));
}

#[test]
fn di004_dropped_rows_unless_the_caption_says_how_many() {
    let data = b"x,y\n1,2\n2,NaN\n3,4\n4,\n5,6\n";
    let spec = |caption: &str| {
        format!(
            "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\ntitle = \"T\"\n{caption}x = \"x\"\ny = \"y\"\n"
        )
    };
    let found = lint_findings(&spec(""), &[("d.csv", data)], "DI004");
    assert_eq!(found.len(), 1);
    assert!(found[0].message.contains("dropped 2 of 5 rows"), "{}", found[0].message);
    assert!(lint_findings(&spec("caption = \"2 readings are missing\"\n"), &[("d.csv", data)], "DI004").is_empty());
    let clean = b"x,y\n1,2\n2,3\n3,4\n4,5\n5,6\n";
    assert!(lint_findings(&spec(""), &[("d.csv", clean)], "DI004").is_empty());
}

#[test]
fn di005_rows_outside_a_fixed_domain() {
    let data = table_csv();
    let narrow = scatter("title = \"T\"\nopacity = 0.4\nx = { field = \"x\", domain = [0, 5] }\ny = \"y\"");
    let found = lint_findings(&narrow, &[("d.csv", &data)], "DI005");
    assert_eq!(found.len(), 1);
    // Count the rows with x > 5 by hand.
    let text = String::from_utf8(data.clone()).expect("utf-8");
    let outside = text
        .lines()
        .skip(1)
        .filter(|l| l.split(',').next().and_then(|v| v.parse::<f64>().ok()).is_some_and(|x| x > 5.0))
        .count();
    assert!(found[0].message.starts_with(&format!("{outside} of 200 rows")), "{} vs {outside}", found[0].message);
    let wide = "title = \"T\"\nopacity = 0.4\nx = { field = \"x\", domain = [0, 10] }\ny = \"y\"";
    assert!(!codes(wide).contains(&"DI005"));
}

#[test]
fn di006_banking_to_45_degrees() {
    // A random walk with uniform steps in [−0.5, 0.5).
    let mut walk = String::from("t,v\n");
    let (mut v, mut state) = (0.0f64, 7u64);
    for t in 0..300 {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        v += (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        walk.push_str(&format!("{t},{v:.4}\n"));
    }
    let spec = |size: &str| {
        format!(
            "[data.w]\npath = \"w.csv\"\n\n[[chart]]\nname = \"w\"\nkind = \"line\"\ndata = \"w\"\ntitle = \"Walk\"\nsize = {size}\nx = \"t\"\ny = \"v\"\n"
        )
    };
    // Its steps are large for its range: drawn 600 × 500 the segments are steep (median ~82°);
    // 1200 × 150 banks them near 45°.
    let steep = lint_findings(&spec("[600, 500]"), &[("w.csv", walk.as_bytes())], "DI006");
    assert_eq!(steep.len(), 1);
    assert!(steep[0].message.contains("82°"), "{}", steep[0].message);
    assert!(steep[0].hint.contains("size = [600, "), "{}", steep[0].hint);
    assert!(lint_findings(&spec("[1200, 150]"), &[("w.csv", walk.as_bytes())], "DI006").is_empty());
}

#[test]
fn cm002_overplotting() {
    let opaque = "title = \"T\"\nopacity = 1\nradius = 6\nsize = [300, 200]\nx = \"x\"\ny = \"y\"";
    let data = table_csv();
    let found = lint_findings(&scatter(opaque), &[("d.csv", &data)], "CM002");
    assert_eq!(found.len(), 1, "{found:?}");
    let faint = "title = \"T\"\nopacity = 0.3\nradius = 6\nsize = [300, 200]\nx = \"x\"\ny = \"y\"";
    assert!(!codes(faint).contains(&"CM002"));
}

#[test]
fn cm002_reports_translucent_points_that_stack_until_the_ink_saturates() {
    // 3,000 rows on 35 spots (about 86 a spot) at opacity 0.2: 18 marks already reach 98% ink.
    let stacked: String =
        std::iter::once("x,y\n".to_owned()).chain((0..3000).map(|i| format!("{},{}\n", i % 5, i % 7))).collect();
    // The same rows spread out: at most one mark a spot.
    let spread: String =
        std::iter::once("x,y\n".to_owned()).chain((0..3000).map(|i| format!("{},{}\n", i % 60, i / 60))).collect();
    let keys = "title = \"T\"\nopacity = 0.2\nradius = 2\nsize = [400, 300]\nx = \"x\"\ny = \"y\"";
    let found = lint_findings(&scatter(keys), &[("d.csv", stacked.as_bytes())], "CM002");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].message.contains("100% of 3000 points") && found[0].message.contains("18 or more"),
        "{}",
        found[0].message
    );
    assert!(found[0].hint.contains("density"), "{}", found[0].hint);
    assert!(lint_findings(&scatter(keys), &[("d.csv", spread.as_bytes())], "CM002").is_empty());
}

#[test]
fn allow_drops_and_deny_raises_findings() {
    let data = table_csv();
    let untitled = "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nopacity = 0.4\nx = \"x\"\ny = \"y\"\n";
    let fx = Fixture::new(&format!("[lint]\nallow = [\"missing-title\"]\n\n{untitled}"), &[("d.csv", &data)]);
    let result = fx.lint().unwrap_or_else(|e| panic!("{e}"));
    assert!(result[0].findings.is_empty());
    assert_eq!(result[0].allowed.len(), 1);
    let fx = Fixture::new(&format!("[lint]\ndeny = [\"LB001\"]\n\n{untitled}"), &[("d.csv", &data)]);
    let result = fx.lint().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(result[0].findings[0].severity, dataink::lint::Severity::Error);
    // A chart's own table wins over the spec's.
    let fx = Fixture::new(
        &format!("[lint]\ndeny = [\"LB001\"]\n\n{untitled}lint = {{ allow = [\"LB001\"] }}\n"),
        &[("d.csv", &data)],
    );
    let result = fx.lint().unwrap_or_else(|e| panic!("{e}"));
    assert!(result[0].findings.is_empty());
}

#[test]
fn unknown_rules_are_spec_errors_with_a_suggestion() {
    let data = table_csv();
    let fx = Fixture::new(&format!("[lint]\nallow = [\"missing-titel\"]\n\n{}", scatter(TITLED)), &[("d.csv", &data)]);
    let err = fx.load().expect_err("an unknown rule is an error");
    assert!(err.contains("no lint rule `missing-titel`"), "{err}");
    assert!(err.contains("did you mean `missing-title`"), "{err}");
    assert!(err.contains("spec.toml:2:"), "{err}");
}

#[test]
fn findings_point_at_the_spec_line() {
    let data = table_csv();
    let spec = scatter("title = \"T\"\nopacity = 0.4\nx = { field = \"x\", ticks = 2 }\ny = \"y\"");
    let found = lint_findings(&spec, &[("d.csv", &data)], "SC003");
    // `x = ...` is line 10 of the spec; the finding points at its `ticks` key.
    assert_eq!(found[0].line, Some(10));
    assert_eq!(found[0].path, "chart[0].x.ticks");
}

/// Run the binary in `dir` with `args`; returns (exit code, stdout, stderr).
fn run(dir: &std::path::Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_dataink")).current_dir(dir).args(args).output().expect("runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn the_command_exits_1_on_errors_and_with_deny_warnings_on_warnings() {
    let data = table_csv();
    let warn_only = Fixture::new(&scatter("opacity = 0.4\nx = \"x\"\ny = \"y\""), &[("d.csv", &data)]);
    let dir = warn_only.dir.path();
    let (code, out, _) = run(dir, &["lint", "spec.toml"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("warning[LB001 missing-title]"), "{out}");
    let (code, _, _) = run(dir, &["lint", "spec.toml", "--deny-warnings"]);
    assert_eq!(code, 1);
    let errors = Fixture::new(
        &scatter("title = \"T\"\nopacity = 0.4\nx = { field = \"x\", domain = [0, 5] }\ny = \"y\""),
        &[("d.csv", &data)],
    );
    let (code, out, _) = run(errors.dir.path(), &["lint", "spec.toml"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("error[DI005 outside-domain]"), "{out}");
    let (code, _, err) = run(dir, &["lint", "missing.toml"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn the_command_writes_sarif_json_and_junit() {
    let data = table_csv();
    let fx = Fixture::new(&scatter("opacity = 0.4\nx = \"x\"\ny = \"y\""), &[("d.csv", &data)]);
    let dir = fx.dir.path();
    let (_, sarif, _) = run(dir, &["lint", "spec.toml", "--format", "sarif"]);
    let doc: serde_json::Value = serde_json::from_str(&sarif).expect("SARIF is JSON");
    assert_eq!(doc["version"], "2.1.0");
    assert_eq!(doc["runs"][0]["results"][0]["ruleId"], "LB001");
    assert_eq!(
        doc["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
        "spec.toml"
    );
    let (_, json, _) = run(dir, &["lint", "spec.toml", "--format", "json"]);
    let doc: serde_json::Value = serde_json::from_str(&json).expect("JSON");
    assert_eq!(doc["warnings"], 1);
    assert_eq!(doc["charts"][0]["findings"][0]["code"], "LB001");
    let (_, junit, _) = run(dir, &["lint", "spec.toml", "--format", "junit", "--deny-warnings"]);
    assert!(junit.contains("<testsuites name=\"dataink lint\" tests=\"1\" failures=\"1\">"), "{junit}");
    let (code, rules, _) = run(dir, &["lint", "--rules"]);
    assert_eq!(code, 0);
    assert!(rules.lines().count() >= 14 && rules.contains("LB001  missing-title"), "{rules}");
}

#[test]
fn render_prints_a_lint_summary_per_chart() {
    let data = table_csv();
    let fx = Fixture::new(&scatter("opacity = 0.4\nx = \"x\"\ny = \"y\""), &[("d.csv", &data)]);
    let (code, _, err) = run(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--format", "svg"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("lint c: 0 errors, 1 warning, 0 notes (LB001)"), "{err}");
}

#[test]
fn the_gallery_lints_clean() {
    let loaded =
        dataink::pipeline::load(&root().join("examples/gallery.toml"), dataink::data::PathPolicy::InsideSpecFolder)
            .unwrap_or_else(|f| panic!("{}", f.render()));
    let linted = dataink::pipeline::draw_and_lint(&loaded, &[]).unwrap_or_else(|_| panic!("the gallery draws"));
    let findings: Vec<String> = linted
        .iter()
        .flat_map(|l| &l.lint.findings)
        .filter(|f| f.severity != dataink::lint::Severity::Note)
        .map(|f| format!("{} {}: {}", f.code, f.chart, f.message))
        .collect();
    assert!(findings.is_empty(), "gallery findings:\n{}", findings.join("\n"));
}

#[test]
fn di004_is_reported_once_per_data_source_naming_its_charts() {
    let data = b"x,y\n1,2\n2,NaN\n3,4\n4,\n5,6\n";
    let chart = |name: &str| {
        format!(
            "[[chart]]\nname = \"{name}\"\nkind = \"scatter\"\ndata = \"d\"\ntitle = \"T\"\nx = \"x\"\ny = \"y\"\n\n"
        )
    };
    let spec = format!("[data.d]\npath = \"d.csv\"\n\n{}{}{}", chart("a"), chart("b"), chart("c"));
    let found = lint_findings(&spec, &[("d.csv", data)], "DI004");
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].chart, "a");
    assert!(
        found[0].message.ends_with("charts over data \"d\" that drop rows: \"a\", \"b\", \"c\""),
        "{}",
        found[0].message
    );
}

/// A line chart over `rows` (x, y, g) with extra keys.
fn line_codes(rows: &str, extra: &str) -> Vec<Finding> {
    let data = format!("x,y,g\n{rows}");
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"line\"\ndata = \"d\"\ntitle = \"T\"\nx = \"x\"\ny = \"y\"\n{extra}\n"
    );
    lint_findings(&spec, &[("d.csv", data.as_bytes())], "DI007")
}

#[test]
fn di007_a_line_through_repeated_x_values() {
    let rows = "1,2,a\n1,5,b\n2,3,a\n2,6,b\n3,2,a\n3,7,b\n3,1,b\n";
    let found = line_codes(rows, "");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].message.starts_with("4 of 7 rows repeat an x value of their series (x = 3 appears 3 times)"),
        "{}",
        found[0].message
    );
    assert!(
        found[0].hint.contains(r#"transform = [{ aggregate = { mean_y = "mean(y)" }, groupby = ["x"] }]"#),
        "{}",
        found[0].hint
    );
    assert!(found[0].hint.contains("series = "), "{}", found[0].hint);
    // One series per group: each x once per series, except b's two rows at x = 3.
    let found = line_codes(rows, "series = \"g\"");
    assert_eq!(found.len(), 1);
    assert!(
        found[0]
            .message
            .starts_with("1 of 7 rows repeat an x value of their series (x = 3 appears 2 times in series \"b\" (`g`))"),
        "{}",
        found[0].message
    );
    assert!(found[0].hint.contains(r#"groupby = ["x", "g"]"#), "{}", found[0].hint);
    assert!(line_codes("1,2,a\n1,5,b\n2,3,a\n2,6,b\n3,2,a\n3,7,b\n", "series = \"g\"").is_empty());
    // A band of the rows' spread draws their mean at each x: nothing zigzags.
    assert!(line_codes(rows, "band = \"ci95\"").is_empty());
    assert!(line_codes(rows, "band = { spread = \"minmax\" }").is_empty());
    assert!(found[0].hint.contains("band = \"ci95\""), "{}", found[0].hint);
}

/// A bar chart whose x categories are `labels`.
fn bar_codes(labels: &[&str]) -> Vec<Finding> {
    let mut data = String::from("label,v\n");
    for (i, l) in labels.iter().enumerate() {
        data.push_str(&format!("\"{l}\",{}\n", i + 1));
    }
    let spec = "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"bar\"\ndata = \"d\"\ntitle = \"T\"\nx = \"label\"\ny = \"v\"\n";
    lint_findings(spec, &[("d.csv", data.as_bytes())], "SC005")
}

#[test]
fn sc005_numbers_and_dates_read_as_text_on_a_band_axis() {
    let found = bar_codes(&["1,234", "2,500", "12,000", "3.5%"]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].message.contains("4 of its 4 values look like numbers (\"1,234\", \"2,500\", \"12,000\")"),
        "{}",
        found[0].message
    );
    assert!(found[0].hint.contains(r#"parse = { label = "number" }"#), "{}", found[0].hint);
    let found = bar_codes(&["12/06/1998", "13/06/1998", "14/06/1998"]);
    assert_eq!(found.len(), 1);
    assert!(found[0].message.contains("look like dates"), "{}", found[0].message);
    assert!(bar_codes(&["apples", "pears", "plums"]).is_empty());
    // One odd value in three is too many for a column of numbers.
    assert!(bar_codes(&["1,234", "2,500", "n/a"]).is_empty());
}

#[test]
fn sc001_checks_each_axis_of_a_scatter_plot_matrix() {
    let data = table_csv();
    let splom = |size: &str| {
        format!(
            "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"m\"\nkind = \"splom\"\ndata = \"d\"\ntitle = \"T\"\nsize = {size}\ncolumns = [\"x\", \"y\", \"temp_c\", \"w\"]\n"
        )
    };
    let cramped = lint_findings(&splom("[260, 260]"), &[("d.csv", &data)], "SC001");
    assert!(!cramped.is_empty());
    assert!(cramped.iter().all(|f| f.element.contains(" axis of `")), "{cramped:?}");
    assert!(lint_findings(&splom("[800, 800]"), &[("d.csv", &data)], "SC001").is_empty());
}
