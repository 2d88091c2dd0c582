//! SC001 `axis-without-ticks` and SC003 `tick-count`: a quantitative axis needs labelled ticks
//! to show its scale, and a readable number of them. Every quantitative axis is checked: the x
//! and y of cartesian charts, a surface's projected x, y and z, and each column's axes of a
//! scatter-plot matrix.

use crate::lint::chart_info::cartesian_axes;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{Item, Role, Shape};
use crate::spec::{ChartKind, ScaleKind};

/// Fewer labelled ticks than this leave the scale unreadable.
const MIN_LABELS: usize = 2;
/// Fewer labelled ticks than this make values hard to read off (SC003).
const FEW_LABELS: usize = 3;
/// More labelled ticks than this crowd the axis (SC003).
const MANY_LABELS: usize = 12;

/// SC001.
pub static AXIS_WITHOUT_TICKS: Rule = Rule {
    code: "SC001",
    name: "axis-without-ticks",
    category: Category::Scale,
    severity: Severity::Error,
    summary: "A quantitative axis has fewer than two labelled ticks, so its scale cannot be read.",
    check: check_missing,
};

/// SC003.
pub static TICK_COUNT: Rule = Rule {
    code: "SC003",
    name: "tick-count",
    category: Category::Scale,
    severity: Severity::Warning,
    summary: "A quantitative axis has fewer than 3 or more than 12 labelled ticks.",
    check: check_count,
};

/// A quantitative axis as the scene labels it, with its spec key and column.
struct Ticked {
    /// The label its tick labels carry in the scene (`"x axis"`, `"z axis"`, `"y axis: FIELD"`).
    name: String,
    /// The spec key of its channel, relative to the chart.
    key: String,
    /// The column it shows.
    field: String,
    /// Its labelled ticks in the scene.
    labels: usize,
}

/// Every quantitative axis of the chart: a cartesian chart's x and y (unless on a band
/// scale), a surface's projected x, y and z axes, and each column's x and y axis of a
/// scatter-plot matrix; axes over text columns are left out.
fn quantitative_axes(s: &Subject<'_>) -> Vec<(String, String, String)> {
    let mut axes: Vec<(String, String, String)> = cartesian_axes(s.chart)
        .into_iter()
        .filter(|a| a.scale() != Some(ScaleKind::Band))
        .map(|a| (a.name.to_string(), a.key.to_string(), a.options.field))
        .collect();
    match &s.chart.kind {
        ChartKind::Surface(o) => {
            for (name, key, field) in
                [("x axis", "x", o.x.field()), ("y axis", "y", o.y.field()), ("z axis", "z", o.z.field())]
            {
                axes.push((name.to_string(), key.to_string(), field.to_string()));
            }
        }
        ChartKind::Splom(o) => {
            for c in &o.columns {
                let field = c.field();
                for side in ["x", "y"] {
                    axes.push((format!("{side} axis: {field}"), "columns".to_string(), field.to_string()));
                }
            }
        }
        _ => {}
    }
    axes.retain(|(_, _, field)| is_numeric(s, field));
    axes
}

/// The quantitative axes of the chart with their number of labelled ticks in the scene. A
/// faceted chart's axes are counted in each panel that labels them (the outer panels).
fn labelled_axes(s: &Subject<'_>) -> Vec<Ticked> {
    let panels: Vec<&Item> =
        s.output.scene.items.iter().filter(|i| i.label.as_deref().is_some_and(|l| l.starts_with("panel: "))).collect();
    let mut out = Vec::new();
    for (name, key, field) in quantitative_axes(s) {
        if panels.is_empty() {
            let labels = tick_labels(&s.output.scene.items, &name);
            out.push(Ticked { name, key, field, labels });
            continue;
        }
        let mut counts: Vec<usize> = panels
            .iter()
            .map(|p| match &p.shape {
                Shape::Group { items, .. } => tick_labels(items, &name),
                _ => 0,
            })
            .filter(|&n| n > 0)
            .collect();
        counts.sort_unstable();
        counts.dedup();
        if counts.is_empty() {
            counts.push(0);
        }
        out.extend(counts.into_iter().map(|labels| Ticked {
            name: name.clone(),
            key: key.clone(),
            field: field.clone(),
            labels,
        }));
    }
    out
}

/// The non-empty tick labels of axis `name` among `items` and their children.
fn tick_labels(items: &[Item], name: &str) -> usize {
    items
        .iter()
        .map(|item| match &item.shape {
            Shape::Group { items, .. } => tick_labels(items, name),
            Shape::Text(t) => usize::from(
                item.role == Role::TickLabel && item.label.as_deref() == Some(name) && !t.content.trim().is_empty(),
            ),
            _ => 0,
        })
        .sum()
}

/// How a message names an axis: `x axis`, or `x axis of `FIELD`` for a matrix cell's axis.
fn axis_name(a: &Ticked) -> String {
    match a.name.split_once(": ") {
        Some((side, field)) => format!("{side} of `{field}`"),
        None => a.name.clone(),
    }
}

/// Whether the chart's column `field` holds numbers or times (not text categories).
fn is_numeric(s: &Subject<'_>, field: &str) -> bool {
    s.table.column(field).is_some_and(|c| c.numbers().is_some())
}

fn check_missing(s: &Subject<'_>) -> Vec<Issue> {
    labelled_axes(s)
        .into_iter()
        .filter(|a| a.labels < MIN_LABELS)
        .map(|a| {
            let n = a.labels;
            let name = axis_name(&a);
            let of = if a.name.contains(": ") { String::new() } else { format!(" of `{}`", a.field) };
            Issue::new(
                name.clone(),
                a.key,
                format!(
                    "the {name}{of} has {n} labelled tick{}, so its scale cannot be read",
                    if n == 1 { "" } else { "s" }
                ),
                "make the chart larger (`size`) or the text smaller (`font_size`) so at least two tick labels fit",
            )
        })
        .collect()
}

fn check_count(s: &Subject<'_>) -> Vec<Issue> {
    labelled_axes(s)
        .into_iter()
        .filter(|a| a.labels >= MIN_LABELS && (a.labels < FEW_LABELS || a.labels > MANY_LABELS))
        .map(|a| {
            let n = a.labels;
            let (what, hint) = if n < FEW_LABELS {
                ("too few to read values between them", "ask for more ticks (`ticks = 5`) or make the axis longer")
            } else {
                ("too many to read at a glance", "ask for fewer ticks (`ticks = 6`); about 5 to 10 labels read best")
            };
            let name = axis_name(&a);
            // Only cartesian channels have a `ticks` key.
            let key = if a.key == "x" || a.key == "y" { format!("{}.ticks", a.key) } else { a.key };
            Issue::new(name.clone(), key, format!("the {name} has {n} labelled ticks, {what}"), hint)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::data::{ColumnValues, Table};
    use crate::lint::Subject;
    use crate::lint::test_support::output;
    use crate::scene::{Anchor, Baseline, Color, Item, Point, Role, Scene, Text};
    use crate::spec::{SourceFile, parse_spec};

    /// A tick label of the axis labelled `axis`.
    fn tick(axis: &str, content: &str) -> Item {
        let text = Text {
            at: Point::new(10.0, 10.0),
            content: content.into(),
            size: 12.0,
            anchor: Anchor::Middle,
            baseline: Baseline::Top,
            angle: 0.0,
            color: Color::rgb(0x55, 0x55, 0x55),
        };
        Item::text(Role::TickLabel, text).labelled(axis)
    }

    /// The SC001 issues of a surface chart whose scene has `ticks` labels per axis.
    fn surface_issues(ticks: [(&str, usize); 3]) -> Vec<crate::lint::Issue> {
        let text = "[data.d]\nvalues = [{ x = 1, y = 2, z = 3 }]\n\n[[chart]]\nname = \"s\"\nkind = \"surface\"\ndata = \"d\"\ntitle = \"T\"\nx = \"x\"\ny = \"y\"\nz = \"z\"\n";
        let chart = parse_spec(&SourceFile::new("t.toml", text)).expect("a valid spec").spec.chart.remove(0);
        let number = |v: f64| ColumnValues::Number(vec![v]);
        let table = Table::from_columns([("x", number(1.0)), ("y", number(2.0)), ("z", number(3.0))]);
        let items = ticks.iter().flat_map(|(axis, n)| (0..*n).map(|i| tick(axis, &i.to_string()))).collect();
        let out = output(Scene { width: 400.0, height: 300.0, background: Color::WHITE, title: None, items });
        super::check_missing(&Subject { chart: &chart, index: 0, table: &table, nodes: None, output: &out })
    }

    #[test]
    fn a_surface_z_axis_with_one_tick_is_reported() {
        let issues = surface_issues([("x axis", 3), ("y axis", 4), ("z axis", 1)]);
        assert_eq!(issues.len(), 1, "{issues:?}");
        assert_eq!((issues[0].element.as_str(), issues[0].key.as_str()), ("z axis", "z"));
        assert_eq!(issues[0].message, "the z axis of `z` has 1 labelled tick, so its scale cannot be read");
        assert!(surface_issues([("x axis", 3), ("y axis", 4), ("z axis", 2)]).is_empty());
    }
}
