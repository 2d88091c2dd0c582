//! DI007 `repeated-x`: a line drawn through several rows with the same x value within one
//! series. A line chart joins its rows in x order, so rows sharing an x are joined by vertical
//! strokes that zigzag up and down: the shape shows the order of the rows, not a trend. This is
//! what an unaggregated long-form table looks like (several measurements per day, or several
//! groups without `series`).

use std::collections::{BTreeMap, HashSet};

use crate::guide::format::format_value;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::encode::cell_text;
use crate::spec::ChartKind;

/// The rule.
pub static RULE: Rule = Rule {
    code: "DI007",
    name: "repeated-x",
    category: Category::Integrity,
    severity: Severity::Warning,
    summary: "A line runs through several rows with the same x within one series, so it zigzags.",
    check,
};

/// How many rows repeat an x value of their series, and the x value repeated most often with
/// its series and count.
struct Repeats {
    rows: usize,
    repeated: usize,
    worst: (String, String, usize),
}

/// The repeats of `x` within each group of `series` (one group without it), over rows whose x
/// is present.
fn repeats(s: &Subject<'_>, x: &str, series: Option<&str>) -> Option<Repeats> {
    let x_col = s.table.column(x)?;
    let series_col = series.and_then(|f| s.table.column(f));
    let mut counts: BTreeMap<(String, String), usize> = BTreeMap::new();
    let mut seen: HashSet<(String, u64)> = HashSet::new();
    let (mut rows, mut repeated) = (0, 0);
    for row in 0..s.table.rows {
        let key = match (x_col.numbers(), x_col.categories()) {
            (Some(v), _) => match v.get(row) {
                Some(x) if x.is_finite() => x.to_bits(),
                _ => continue,
            },
            (_, Some(c)) => match c.codes.get(row) {
                Some(&code) => u64::from(code),
                None => continue,
            },
            _ => continue,
        };
        let group = series_col.map(|c| cell_text(c, row as u32)).unwrap_or_default();
        rows += 1;
        if !seen.insert((group.clone(), key)) {
            repeated += 1;
            let label = match x_col.numbers() {
                Some(v) => v.get(row).map(|&x| format_value(x)).unwrap_or_default(),
                None => cell_text(x_col, row as u32),
            };
            *counts.entry((group, label)).or_insert(1) += 1;
        }
    }
    let ((group, label), n) = counts.into_iter().max_by_key(|(_, n)| *n)?;
    Some(Repeats { rows, repeated, worst: (group, label, n) })
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let ChartKind::Line(o) = &s.chart.kind else { return Vec::new() };
    if o.averages_rows() {
        // A spread band draws one point per x: the mean of the rows there.
        return Vec::new();
    }
    let x = o.x.field();
    let split = o.split_field();
    let Some(r) = repeats(s, x, split) else { return Vec::new() };
    let y = o.y.as_slice().first().map(|c| c.field().to_string()).unwrap_or_else(|| "y".into());
    let (group, value, n) = r.worst;
    let within = match split {
        Some(series) => format!(" in series \"{}\" (`{series}`)", crate::spec::validate::shorten(&group)),
        None => String::new(),
    };
    let mut groupby = vec![format!("\"{x}\"")];
    groupby.extend(split.iter().map(|s| format!("\"{s}\"")));
    let split = if split.is_none() {
        " or, if the rows belong to different groups, draw one line per group with `series = \"COLUMN\"`"
    } else {
        ""
    };
    vec![Issue::new(
        "x axis",
        "x",
        format!(
            "{} of {} rows repeat an x value of their series (x = {} appears {n} times{within}), so the line \
             zigzags up and down through them instead of showing one value per x",
            r.repeated,
            r.rows,
            crate::spec::validate::shorten(&value)
        ),
        format!(
            "aggregate to one row per x first, e.g. `transform = [{{ aggregate = {{ mean_{y} = \"mean({y})\" }}, \
             groupby = [{}] }}]` and plot `y = \"mean_{y}\"`, or let the line draw their mean with its \
             95% confidence band (`band = \"ci95\"`){split}",
            groupby.join(", ")
        ),
    )]
}
