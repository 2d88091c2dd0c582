//! Hover texts in SVG: one-row marks list their row's values, bars their sums, listed columns
//! replace the chart's own, `tooltip = false` writes none, and hostile text is escaped.

use crate::common::Fixture;
use dataink::render::svg::to_svg;

const CSV: &str = "name,x,y,note\nalpha,1,2,first\nbeta,3,4,\"<b>&\"\"x\"\"</b>\"\n";

fn svg(chart: &str) -> Result<String, String> {
    let spec = format!("[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\ndata = \"d\"\n{chart}");
    let out = Fixture::new(&spec, &[("d.csv", CSV.as_bytes())]).draw()?;
    Ok(to_svg(&out[0].scene))
}

fn titles(svg: &str) -> Vec<String> {
    svg.split("<title>").skip(1).map(|s| s.split("</title>").next().unwrap_or_default().to_string()).collect()
}

#[test]
fn points_carry_their_rows_values_of_the_charts_columns() {
    let svg = svg("kind = \"scatter\"\nx = \"x\"\ny = \"y\"\ncolor = \"name\"").unwrap();
    let t = titles(&svg);
    assert!(t.contains(&"x: 1&#10;y: 2&#10;name: alpha".to_string()), "{t:?}");
    assert!(t.contains(&"x: 3&#10;y: 4&#10;name: beta".to_string()), "{t:?}");
}

#[test]
fn listed_columns_replace_the_charts_own_and_are_escaped() {
    let svg = svg("kind = \"scatter\"\nx = \"x\"\ny = \"y\"\ntooltip = [\"note\", \"name\"]").unwrap();
    let t = titles(&svg);
    assert!(t.contains(&"note: first&#10;name: alpha".to_string()), "{t:?}");
    assert!(t.contains(&"note: &lt;b&gt;&amp;&quot;x&quot;&lt;/b&gt;&#10;name: beta".to_string()), "{t:?}");
    assert!(!svg.contains("<b>"), "no markup from the data reaches the SVG");
}

#[test]
fn tooltip_false_writes_none_and_a_missing_column_is_a_positioned_error() {
    let none = svg("kind = \"scatter\"\nx = \"x\"\ny = \"y\"\ntooltip = false").unwrap();
    assert_eq!(titles(&none).len(), 0, "not even the chart title? {none}");
    let e = svg("kind = \"scatter\"\nx = \"x\"\ny = \"y\"\ntooltip = [\"nam\"]").unwrap_err();
    assert!(e.contains("no column `nam`") && e.contains("did you mean `name`"), "{e}");
}

#[test]
fn bars_show_their_sum_and_how_many_rows_it_adds() {
    let spec =
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"c\"\ndata = \"d\"\nkind = \"bar\"\nx = \"k\"\ny = \"v\"";
    let out = Fixture::new(spec, &[("d.csv", b"k,v\na,1.5\na,2\nb,4\n")]).draw().unwrap();
    let t = titles(&to_svg(&out[0].scene));
    assert!(t.contains(&"k: a&#10;v: 3.5 (sum of 2 rows)".to_string()), "{t:?}");
    assert!(t.contains(&"k: b&#10;v: 4".to_string()), "{t:?}");
}
