//! Rules about data the chart silently does not show: DI003 `log-nonpositive` (values ≤ 0 on a
//! log axis, whose rows are dropped), DI004 `dropped-rows` (rows left out for missing or
//! non-finite values) and DI005 `outside-domain` (rows outside a fixed axis domain, clipped away;
//! for bars, their totals).

use crate::lint::chart_info::cartesian_axes;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::derived::DerivedColumn;
use crate::mark::warning::Warning;
use crate::spec::{ChartKind, ScaleKind};

/// DI003.
pub static LOG_NONPOSITIVE: Rule = Rule {
    code: "DI003",
    name: "log-nonpositive",
    category: Category::Integrity,
    severity: Severity::Error,
    summary: "A log-scaled axis has values at or below zero, which it cannot show.",
    check: check_log,
};

/// DI004.
pub static DROPPED_ROWS: Rule = Rule {
    code: "DI004",
    name: "dropped-rows",
    category: Category::Integrity,
    severity: Severity::Warning,
    summary: "Rows were left out for missing or non-finite values and the caption does not say how many.",
    check: check_dropped,
};

/// DI005.
pub static OUTSIDE_DOMAIN: Rule = Rule {
    code: "DI005",
    name: "outside-domain",
    category: Category::Integrity,
    severity: Severity::Error,
    summary: "A fixed axis domain leaves data rows (for bars, their totals) outside the plot, where they are cut off.",
    check: check_domain,
};

/// Finite values of a numeric column (empty for text).
fn finite(s: &Subject<'_>, field: &str) -> Vec<f64> {
    s.table
        .column(field)
        .and_then(|c| c.numbers())
        .map(|v| v.iter().copied().filter(|x| x.is_finite()).collect())
        .unwrap_or_default()
}

fn check_log(s: &Subject<'_>) -> Vec<Issue> {
    cartesian_axes(s.chart)
        .into_iter()
        .filter(|a| a.scale() == Some(ScaleKind::Log))
        .filter_map(|a| {
            let (bad, of) = non_positive(s, &a.options.field);
            (bad > 0).then(|| {
                Issue::new(
                    a.name,
                    format!("{}.scale", a.key),
                    format!(
                        "{bad} of {of} values of `{}` are ≤ 0 and cannot be placed on the log-scaled {}: \
                         their rows are left out",
                        a.options.field, a.name
                    ),
                    "use a linear scale, or filter or transform the column so every value is positive",
                )
            })
        })
        .collect()
}

/// The values of `field` ≤ 0, and the values looked at: the table's finite ones, or, for a chart
/// whose rows stayed in their source's plan (its table has none), the column's count in the
/// dropped-rows warning out of the chart's rows.
fn non_positive(s: &Subject<'_>, field: &str) -> (usize, usize) {
    if s.table.rows > 0 {
        let values = finite(s, field);
        return (values.iter().filter(|v| **v <= 0.0).count(), values.len());
    }
    s.output
        .warnings
        .iter()
        .find_map(|w| match w {
            Warning::DroppedRows { rows, columns, .. } => {
                columns.iter().find(|c| c.field == field).map(|c| (c.non_positive, *rows))
            }
            _ => None,
        })
        .unwrap_or((0, 0))
}

fn check_dropped(s: &Subject<'_>) -> Vec<Issue> {
    s.output
        .warnings
        .iter()
        .filter_map(|w| w.dropped_rows().map(|counts| (w, counts)))
        .filter(|(_, (dropped, _))| !caption_states_count(s, *dropped))
        .map(|(w, _)| {
            Issue::new(
                "data",
                "data",
                w.message(),
                "say in the caption how many rows are missing, or clean the data so nothing is dropped silently",
            )
        })
        .collect()
}

/// Keep one DI004 finding per data source: the first chart's (in the order given), its
/// message naming every chart over that source that drops rows; the other charts' DI004
/// findings are removed. `lints` pairs each chart's findings with its data source's name.
pub fn one_dropped_rows_per_source(lints: &mut [(&str, &mut crate::lint::ChartLint)]) {
    let is_dropped = |f: &crate::lint::Finding| f.code == DROPPED_ROWS.code;
    let mut sources: Vec<&str> = lints.iter().map(|(d, _)| *d).collect();
    sources.sort_unstable();
    sources.dedup();
    for source in sources {
        let charts: Vec<String> = lints
            .iter()
            .filter(|(d, l)| *d == source && l.findings.iter().any(is_dropped))
            .map(|(_, l)| format!("\"{}\"", l.chart))
            .collect();
        if charts.len() < 2 {
            continue;
        }
        let mut first = true;
        for (_, lint) in lints.iter_mut().filter(|(d, _)| *d == source) {
            if !lint.findings.iter().any(is_dropped) {
                continue;
            }
            if first {
                for f in lint.findings.iter_mut().filter(|f| is_dropped(f)) {
                    f.message =
                        format!("{}; charts over data \"{source}\" that drop rows: {}", f.message, charts.join(", "));
                }
                first = false;
            } else {
                lint.findings.retain(|f| !is_dropped(f));
            }
        }
    }
}

/// Whether the chart's caption states the number of dropped rows, which tells the reader what
/// is missing.
fn caption_states_count(s: &Subject<'_>, dropped: usize) -> bool {
    let count = dropped.to_string();
    s.chart
        .caption
        .as_deref()
        .is_some_and(|caption| caption.split(|c: char| !c.is_ascii_digit()).any(|word| word == count))
}

fn check_domain(s: &Subject<'_>) -> Vec<Issue> {
    // Rows left in their source's plan: the chart counted those outside a domain; bar totals
    // are in its derived table either way.
    let counted = s.table.rows == 0;
    let mut issues = if counted { counted_outside_domain(s) } else { Vec::new() };
    issues.extend(cartesian_axes(s.chart).into_iter().filter_map(|a| {
        let [lo, hi] = a.options.domain?;
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        let totals = bar_totals(s, a.key, &a.options.field);
        if counted && totals.is_none() {
            return None;
        }
        let values = totals.clone().unwrap_or_else(|| finite(s, &a.options.field));
        let outside = values.iter().filter(|v| **v < lo || **v > hi).count();
        (outside > 0).then(|| {
            let (min, max) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
            let n = values.len();
            let message = if totals.is_some() {
                format!(
                    "{outside} of {n} bars have totals outside the fixed domain [{lo}, {hi}] of the {} \
                         (totals: {min} to {max}) and are cut at its end",
                    a.name
                )
            } else {
                format!(
                    "{outside} of {n} rows lie outside the fixed domain [{lo}, {hi}] of the {} \
                         (data: {min} to {max}) and are not shown",
                    a.name
                )
            };
            let hint = format!("widen `domain` to cover [{min}, {max}], or remove it");
            Issue::new(a.name, format!("{}.domain", a.key), message, hint)
        })
    }));
    issues
}

/// DI005 for a chart whose rows stayed in their source's plan (its table has none): the rows
/// outside a domain as the chart counted them.
fn counted_outside_domain(s: &Subject<'_>) -> Vec<Issue> {
    let axes = cartesian_axes(s.chart);
    s.output
        .warnings
        .iter()
        .filter_map(|w| {
            let Warning::OutsideDomain { field, outside, rows, .. } = w else { return None };
            let axis = axes.iter().find(|a| a.options.field == *field)?;
            let [lo, hi] = axis.options.domain?;
            Some(Issue::new(
                axis.name,
                format!("{}.domain", axis.key),
                format!(
                    "{outside} of {rows} rows lie outside the fixed domain [{lo}, {hi}] of the {} and are not shown",
                    axis.name
                ),
                "widen `domain` to cover the data, or remove it",
            ))
        })
        .collect()
}

/// A bar chart's y axis draws the bars' totals, not the rows: those totals (finite ones, from the
/// chart's derived table). `None` for every other axis.
fn bar_totals(s: &Subject<'_>, key: &str, field: &str) -> Option<Vec<f64>> {
    if !matches!(s.chart.kind, ChartKind::Bar(_)) || key != "y" {
        return None;
    }
    s.output.derived.columns.iter().find_map(|(name, column)| match column {
        DerivedColumn::Number(totals) if name == field => {
            Some(totals.iter().copied().filter(|v| v.is_finite()).collect())
        }
        _ => None,
    })
}
