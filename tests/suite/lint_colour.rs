//! Colour lint rules (CL001–CL005): for every rule a spec that triggers it and a near-identical
//! one that does not, with the numbers the messages quote.

use crate::common::{lint_codes, lint_findings};

/// Scattered points coloured by a numeric column `v` (−4 to 10) and a text column `g`.
fn points(groups: usize) -> Vec<u8> {
    let mut csv = String::from("x,y,v,g\n");
    for i in 0..groups.max(1) * 3 {
        let g = i % groups.max(1);
        csv.push_str(&format!("{},{},{},g{:02}\n", i, (i * 7) % 11, (i as f64 * 1.3) % 14.0 - 4.0, g));
    }
    // The first and last rows fix v's range to exactly −4 .. 10.
    csv.push_str("50,1,-4,g00\n51,2,10,g00\n");
    csv.into_bytes()
}

/// A 4×3 grid whose values run from −4 to 10.
fn grid() -> Vec<u8> {
    let mut csv = String::from("x,y,z\n");
    let values = [-4.0, -2.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0];
    for (i, z) in values.iter().enumerate() {
        csv.push_str(&format!("{},{},{z}\n", i % 4, i / 4));
    }
    csv.into_bytes()
}

fn scatter(color: &str) -> String {
    format!(
        r#"
[data.d]
path = "data.csv"

[[chart]]
name = "points"
kind = "scatter"
data = "d"
title = "Points"
x = "x"
y = "y"
color = {color}
"#
    )
}

fn image(z: &str) -> String {
    format!(
        r#"
[data.d]
path = "data.csv"

[[chart]]
name = "field"
kind = "image"
data = "d"
title = "A field"
x = "x"
y = "y"
z = {z}
"#
    )
}

fn has(codes: &[&str], code: &str) -> bool {
    codes.contains(&code)
}

// CL001 rainbow-map.

#[test]
fn rainbow_map_on_ordered_values() {
    let data = points(3);
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let bad = scatter(r#"{ field = "v", scheme = "turbo" }"#);
    assert!(has(&lint_codes(&bad, files), "CL001"));
    assert!(!has(&lint_codes(&scatter(r#"{ field = "v", scheme = "viridis" }"#), files), "CL001"));
    assert!(!has(&lint_codes(&scatter(r#"{ field = "v" }"#), files), "CL001"));

    let f = lint_findings(&bad, files, "CL001");
    assert_eq!(f.len(), 1);
    assert!(f[0].path.ends_with("color.scheme"), "{}", f[0].path);
    assert!(f[0].message.starts_with("`turbo` is a rainbow colour map colouring `v`"), "{}", f[0].message);
    // Turbo's lightness: dark, light, dark.
    let story = f[0].message.split("L* ").nth(1).and_then(|s| s.split(" along").next()).unwrap();
    let l: Vec<f64> = story.split(" → ").map(|n| n.parse().unwrap()).collect();
    assert!(l.len() == 3 && l[1] > l[0] + 40.0 && l[1] > l[2] + 40.0, "{story}");
    assert!(f[0].hint.contains("viridis") && f[0].hint.contains("cividis"), "{}", f[0].hint);
}

#[test]
fn rainbow_map_on_a_grid_and_cyclic_ends() {
    let data = grid();
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let f = lint_findings(&image(r#"{ field = "z", scheme = "sinebow_r" }"#), files, "CL001");
    assert_eq!(f.len(), 1);
    assert!(f[0].path.ends_with("z.scheme"), "{}", f[0].path);
    assert!(f[0].message.contains("`sinebow_r`"), "{}", f[0].message);
    assert!(f[0].message.contains("its two ends are nearly the same colour (ΔE00 0.0)"), "{}", f[0].message);
    assert!(lint_findings(&image(r#"{ field = "z", scheme = "magma" }"#), files, "CL001").is_empty());
}

/// A circle-segments chart of `data.csv` with a chart-level colour scheme.
fn segments_with_scheme(scheme: &str) -> String {
    format!(
        r#"
[data.d]
path = "data.csv"

[[chart]]
name = "segments"
kind = "segments"
data = "d"
title = "Segments"
columns = ["x", "y", "v"]
scheme = "{scheme}"
"#
    )
}

#[test]
fn rainbow_map_as_a_chart_level_scheme() {
    let spec = segments_with_scheme;
    let data = points(3);
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let f = lint_findings(&spec("rainbow"), files, "CL001");
    assert_eq!(f.len(), 1, "{f:?}");
    assert!(f[0].path.ends_with("scheme") && f[0].message.contains("the chart's values"), "{f:?}");
    assert!(!has(&lint_codes(&spec("cividis"), files), "CL001"));
}

// CL002 diverging-midpoint.

#[test]
fn diverging_map_without_a_midpoint() {
    let data = grid();
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let f = lint_findings(&image(r#"{ field = "z", scheme = "rdbu" }"#), files, "CL002");
    assert_eq!(f.len(), 1, "{f:?}");
    // The middle of −4 .. 10 is 3.
    let m = &f[0].message;
    assert!(m.contains("diverging `rdbu` is centred on 3, the middle of `z`'s range \u{2212}4 to 10"), "{m}");
    assert!(f[0].path.ends_with("z.scheme"), "{}", f[0].path);
    assert!(f[0].hint.contains("midpoint"), "{}", f[0].hint);
    // A stated midpoint inside the data is what the rule asks for.
    assert!(!has(&lint_codes(&image(r#"{ field = "z", scheme = "rdbu", midpoint = 0 }"#), files), "CL002"));
    // Sequential maps need no midpoint.
    assert!(!has(&lint_codes(&image(r#"{ field = "z", scheme = "viridis" }"#), files), "CL002"));
}

#[test]
fn diverging_midpoint_outside_the_data() {
    let data = points(2);
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let f = lint_findings(&scatter(r#"{ field = "v", scheme = "spectral", midpoint = 20 }"#), files, "CL002");
    assert_eq!(f.len(), 1, "{f:?}");
    let m = &f[0].message;
    assert!(m.contains("the midpoint 20 of diverging `spectral` lies outside `v`'s range \u{2212}4 to 10"), "{m}");
    assert!(f[0].path.ends_with("color.midpoint"), "{}", f[0].path);
    // On the edge of the data is still inside it.
    assert!(!has(&lint_codes(&scatter(r#"{ field = "v", scheme = "spectral", midpoint = 10 }"#), files), "CL002"));
    assert!(!has(&lint_codes(&scatter(r#"{ field = "v", scheme = "spectral", midpoint = 2.5 }"#), files), "CL002"));
}

#[test]
fn diverging_chart_level_scheme_has_no_midpoint() {
    let spec = segments_with_scheme;
    let data = points(3);
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let f = lint_findings(&spec("puor"), files, "CL002");
    assert_eq!(f.len(), 1, "{f:?}");
    assert!(f[0].message.starts_with("diverging `puor` has no `midpoint` in this chart kind"), "{}", f[0].message);
    assert!(f[0].path.ends_with("scheme"), "{}", f[0].path);
    assert!(!has(&lint_codes(&spec("viridis"), files), "CL002"));
}

// CL003 cvd-confusable.

#[test]
fn red_green_categories_are_confusable() {
    let data = points(3);
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let f = lint_findings(&scatter(r#"{ field = "g", scheme = "category10" }"#), files, "CL003");
    assert_eq!(f.len(), 1, "{f:?}");
    let m = &f[0].message;
    // category10's orange and green: ΔE00 1.3 with protanopia, 55.2 with normal vision.
    assert!(
        m.starts_with("\"g01\" (#ff7f0e) and \"g02\" (#2ca02c) look alike with protanopia: ΔE00 1.3, below 10"),
        "{m}"
    );
    assert!(m.contains("(55.2 with normal vision)"), "{m}");
    assert!(f[0].path.ends_with("color.scheme"), "{}", f[0].path);
    assert_eq!(f[0].element, "legend \"g\"");
    // The default palette keeps the same three categories apart.
    assert!(!has(&lint_codes(&scatter(r#"{ field = "g" }"#), files), "CL003"));
}

#[test]
fn okabe_ito_passes_with_all_eight_colours_and_tableau_fails_from_five() {
    let eight = points(8);
    let codes = lint_codes(&scatter(r#"{ field = "g", scheme = "okabe-ito" }"#), &[("data.csv", &eight)]);
    assert!(!has(&codes, "CL003"), "{codes:?}");

    let four = points(4);
    let codes = lint_codes(&scatter(r#"{ field = "g", scheme = "tableau10" }"#), &[("data.csv", &four)]);
    assert!(!has(&codes, "CL003"), "{codes:?}");
    let five = points(5);
    let f = lint_findings(&scatter(r#"{ field = "g", scheme = "tableau10" }"#), &[("data.csv", &five)], "CL003");
    assert_eq!(f.len(), 1, "{f:?}");
    // Tableau's red (3rd) and green (5th): ΔE00 0.7 with deuteranopia.
    assert!(
        f[0].message.starts_with("\"g02\" (#e15759) and \"g04\" (#59a14f) look alike with deuteranopia: ΔE00 0.7"),
        "{}",
        f[0].message
    );
}

#[test]
fn repeated_palette_colours_are_confusable_for_everyone() {
    // Nine categories on an eight-colour palette: the ninth repeats the first.
    let nine = points(9);
    let f = lint_findings(&scatter(r#"{ field = "g" }"#), &[("data.csv", &nine)], "CL003");
    assert_eq!(f.len(), 1, "{f:?}");
    assert!(
        f[0].message.starts_with(
            "\"g00\" (#0072b2) and \"g08\" (#0072b2) have nearly the same colour: ΔE00 0.0 even with normal vision"
        ),
        "{}",
        f[0].message
    );
}

#[test]
fn line_series_palette_is_checked_from_the_legend() {
    let spec = |scheme: &str| {
        format!(
            r#"
[data.d]
path = "data.csv"

[[chart]]
name = "lines"
kind = "line"
data = "d"
title = "Lines"
x = "x"
y = "y"
series = "g"
scheme = "{scheme}"
"#
        )
    };
    let data = points(6);
    let files: &[(&str, &[u8])] = &[("data.csv", &data)];
    let f = lint_findings(&spec("paired"), files, "CL003");
    assert_eq!(f.len(), 1, "{f:?}");
    assert!(f[0].path.ends_with("scheme"), "{}", f[0].path);
    // paired's green and red (4th and 6th) are the closest of several close pairs.
    assert!(
        f[0].message.starts_with("\"g03\" (#33a02c) and \"g05\" (#e31a1c) look alike with deuteranopia: ΔE00 4.7"),
        "{}",
        f[0].message
    );
    assert!(f[0].message.contains("more pair"), "{}", f[0].message);
    assert!(!has(&lint_codes(&spec("okabe-ito"), files), "CL003"));
}

// CL004 too-many-categories.

#[test]
fn more_than_ten_colour_categories() {
    let eleven = points(11);
    let f = lint_findings(&scatter(r#"{ field = "g", scheme = "paired" }"#), &[("data.csv", &eleven)], "CL004");
    assert_eq!(f.len(), 1, "{f:?}");
    assert!(f[0].message.starts_with("11 colour categories, more than 10:"), "{}", f[0].message);
    assert!(f[0].path.ends_with("color"), "{}", f[0].path);
    // With the default palette the repeats are counted too.
    let f = lint_findings(&scatter(r#"{ field = "g" }"#), &[("data.csv", &eleven)], "CL004");
    assert!(
        f[0].message.starts_with("11 colour categories, more than 10 (the 11 shown use only 8 distinct colours)"),
        "{}",
        f[0].message
    );

    let ten = points(10);
    let codes = lint_codes(&scatter(r#"{ field = "g", scheme = "paired" }"#), &[("data.csv", &ten)]);
    assert!(!has(&codes, "CL004"), "{codes:?}");
}

#[test]
fn summarised_legend_entries_count() {
    // 30 categories: the legend shows 24 and "… and 6 more".
    let thirty = points(30);
    let f = lint_findings(&scatter(r#"{ field = "g" }"#), &[("data.csv", &thirty)], "CL004");
    assert_eq!(f.len(), 1, "{f:?}");
    assert!(f[0].message.starts_with("30 colour categories"), "{}", f[0].message);
}

#[test]
fn colour_rules_are_listed_in_code_order() {
    let codes: Vec<&str> = dataink::lint::rules::ALL.iter().map(|r| r.code).collect();
    let cl: Vec<&str> = codes.iter().copied().filter(|c| c.starts_with("CL")).collect();
    assert_eq!(cl, ["CL001", "CL002", "CL003", "CL004", "CL005"]);
    for (code, name) in [
        ("CL001", "rainbow-map"),
        ("CL002", "diverging-midpoint"),
        ("CL003", "cvd-confusable"),
        ("CL004", "too-many-categories"),
    ] {
        let rule = dataink::lint::find_rule(name).unwrap();
        assert_eq!(rule.code, code);
        assert_eq!(rule.category, dataink::lint::Category::Colour);
    }
}

// CL005 nominal-continuous-colour.

/// Points coloured by a whole-number column `station_id` (30 ids) and a measurement `v`.
fn stations() -> Vec<u8> {
    let mut csv = String::from("x,y,station_id,v\n");
    for i in 0..60 {
        csv.push_str(&format!("{i},{},{},{}\n", (i * 7) % 11, 1000 + i % 30, i as f64 * 0.5));
    }
    csv.into_bytes()
}

#[test]
fn identifiers_on_a_continuous_colour_map() {
    let data = stations();
    let found = lint_findings(&scatter("\"station_id\""), &[("data.csv", &data)], "CL005");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].message.starts_with("`station_id` holds whole-number identifiers (30 distinct values)"),
        "{}",
        found[0].message
    );
    assert!(found[0].hint.contains(r#"color = { field = "station_id", type = "categorical" }"#), "{}", found[0].hint);
    assert_eq!(found[0].path, "chart[0].color");
    // A measurement, or the ids as categories, is fine.
    assert!(lint_findings(&scatter("\"v\""), &[("data.csv", &data)], "CL005").is_empty());
    let categories = r#"{ field = "station_id", type = "categorical" }"#;
    assert!(lint_findings(&scatter(categories), &[("data.csv", &data)], "CL005").is_empty());
}
