//! Categorical colours: `domain` and `range` on a colour encoding, one colour per category
//! across every chart of a spec, and small whole-number columns coloured as categories.

use dataink::lint::rules::colour_keys::colour_keys;
use dataink::mark::ChartOutput;
use dataink::scene::Color;

use crate::common::Fixture;

/// The legend entries (label, colour as hex) of a drawn chart's first categorical legend.
fn legend(output: &ChartOutput) -> Vec<(String, String)> {
    let keys = colour_keys(&output.scene);
    let key = keys.first().expect("a categorical legend");
    key.entries.iter().map(|(l, c)| (l.clone(), c.hex())).collect()
}

/// The colour of `label` in a legend.
fn colour_of(entries: &[(String, String)], label: &str) -> String {
    entries
        .iter()
        .find(|(l, _)| l == label)
        .map(|(_, c)| c.clone())
        .unwrap_or_else(|| panic!("no {label}: {entries:?}"))
}

fn hex(c: Color) -> String {
    c.hex()
}

/// Two sources listing their countries in different orders, and a scatter chart over each.
fn two_sources(color_a: &str, color_b: &str) -> Fixture {
    let a = b"x,y,country\n1,1,Japan\n2,2,Germany\n3,3,USA\n";
    let b = b"x,y,country\n1,1,USA\n2,2,France\n3,3,Japan\n";
    let spec = format!(
        "[data.a]\npath = \"a.csv\"\n\n[data.b]\npath = \"b.csv\"\n\n\
         [[chart]]\nname = \"first\"\nkind = \"scatter\"\ndata = \"a\"\ntitle = \"A\"\nx = \"x\"\ny = \"y\"\ncolor = {color_a}\n\n\
         [[chart]]\nname = \"second\"\nkind = \"scatter\"\ndata = \"b\"\ntitle = \"B\"\nx = \"x\"\ny = \"y\"\ncolor = {color_b}\n"
    );
    Fixture::new(&spec, &[("a.csv", a), ("b.csv", b)])
}

#[test]
fn a_category_has_one_colour_in_every_chart() {
    let out = two_sources("\"country\"", "\"country\"").draw().unwrap_or_else(|e| panic!("{e}"));
    let (first, second) = (legend(&out[0]), legend(&out[1]));
    let okabe = dataink::guide::color::categorical("okabe-ito").expect("okabe-ito");
    // The spec-wide order is the first chart's (Japan, Germany, USA), then France from the second.
    assert_eq!(colour_of(&first, "USA"), hex(okabe[2]));
    assert_eq!(colour_of(&second, "USA"), hex(okabe[2]));
    assert_eq!(colour_of(&second, "Japan"), colour_of(&first, "Japan"));
    assert_eq!(colour_of(&second, "France"), hex(okabe[3]));
    // Each legend lists its own categories, in the shared order.
    let labels: Vec<&str> = second.iter().map(|(l, _)| l.as_str()).collect();
    assert_eq!(labels, ["Japan", "USA", "France"]);
}

#[test]
fn domain_and_range_set_the_colours_and_the_legend_order() {
    let color = r##"{ field = "country", domain = ["USA", "Japan", "Germany", "France"], range = ["#1f77b4", "red", "#2ca02c", "black"] }"##;
    let out = two_sources(color, color).draw().unwrap_or_else(|e| panic!("{e}"));
    for chart in &out {
        assert_eq!(colour_of(&legend(chart), "USA"), "#1f77b4");
    }
    assert_eq!(
        legend(&out[0]),
        [("USA".into(), "#1f77b4".into()), ("Japan".into(), "#ff0000".into()), ("Germany".into(), "#2ca02c".into())]
    );
    // A domain given in one chart orders the column for the charts that give none.
    let out = two_sources(r#"{ field = "country", domain = ["France", "USA", "Japan", "Germany"] }"#, "\"country\"")
        .draw()
        .unwrap_or_else(|e| panic!("{e}"));
    let okabe = dataink::guide::color::categorical("okabe-ito").expect("okabe-ito");
    assert_eq!(colour_of(&legend(&out[1]), "USA"), hex(okabe[1]));
}

#[test]
fn categories_outside_the_domain_and_short_ranges_are_errors() {
    let err = two_sources(r#"{ field = "country", domain = ["USA"] }"#, "\"country\"").draw().unwrap_err();
    assert!(err.contains("\"Japan\", \"Germany\" of column `country` are not in the colour `domain`"), "{err}");
    let err = two_sources(r#"{ field = "country", range = ["red", "blue"] }"#, "\"country\"").draw().unwrap_err();
    assert!(err.contains("the colour `range` has 2 colours for 4 categories"), "{err}");
    let err = two_sources(r#"{ field = "country", range = ["red", "nope", "blue", "black"] }"#, "\"country\"")
        .draw()
        .unwrap_err();
    assert!(err.contains("`nope` in the colour `range` is not a colour"), "{err}");
    let err =
        two_sources(r#"{ field = "x", type = "continuous", domain = [1, 2] }"#, "\"country\"").draw().unwrap_err();
    assert!(err.contains("`domain` sets categorical colours, but `x` is coloured continuously"), "{err}");
}

/// A scatter coloured by a whole-number column with `groups` distinct values.
fn by_group(groups: usize, color: &str) -> ChartOutput {
    let mut csv = String::from("x,y,group\n");
    for i in 0..groups * 2 {
        csv.push_str(&format!("{i},{},{}\n", i % 5, 1 + i % groups));
    }
    let spec = format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\ntitle = \"T\"\nx = \"x\"\ny = \"y\"\ncolor = {color}\n"
    );
    let mut out = Fixture::new(&spec, &[("d.csv", csv.as_bytes())]).draw().unwrap_or_else(|e| panic!("{e}"));
    out.remove(0)
}

#[test]
fn few_whole_numbers_are_coloured_as_categories() {
    // 1..=12: categories with a legend, in numeric order.
    let labels: Vec<String> = legend(&by_group(12, "\"group\"")).into_iter().map(|(l, _)| l).collect();
    assert_eq!(labels.len(), 12);
    assert_eq!(labels[..3], ["1", "2", "3"]);
    // 13 distinct values, or `type = "continuous"`: a colour bar and no categorical legend.
    assert!(colour_keys(&by_group(13, "\"group\"").scene).is_empty());
    assert!(colour_keys(&by_group(4, r#"{ field = "group", type = "continuous" }"#).scene).is_empty());
}
