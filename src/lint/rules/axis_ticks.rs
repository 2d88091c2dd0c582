//! SC001 `axis-without-ticks` and SC003 `tick-count`: a quantitative axis needs labelled ticks
//! to show its scale, and a readable number of them.

use crate::lint::chart_info::{AxisSpec, cartesian_axes};
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::{Role, Shape};
use crate::spec::ScaleKind;

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

/// The quantitative axes of the chart with their number of labelled ticks in the scene.
fn labelled_axes(s: &Subject<'_>) -> Vec<(AxisSpec, usize)> {
    cartesian_axes(s.chart)
        .into_iter()
        .filter(|a| a.scale() != Some(ScaleKind::Band) && is_numeric(s, &a.options.field))
        .map(|a| {
            let mut n = 0;
            s.output.scene.walk(|item| {
                if item.role == Role::TickLabel
                    && item.label.as_deref() == Some(a.name)
                    && matches!(&item.shape, Shape::Text(t) if !t.content.trim().is_empty())
                {
                    n += 1;
                }
            });
            (a, n)
        })
        .collect()
}

/// Whether the chart's column `field` holds numbers or times (not text categories).
fn is_numeric(s: &Subject<'_>, field: &str) -> bool {
    s.table.column(field).is_some_and(|c| c.numbers().is_some())
}

fn check_missing(s: &Subject<'_>) -> Vec<Issue> {
    labelled_axes(s)
        .into_iter()
        .filter(|(_, n)| *n < MIN_LABELS)
        .map(|(a, n)| {
            Issue::new(
                a.name,
                a.key,
                format!(
                    "the {} of `{}` has {n} labelled tick{}, so its scale cannot be read",
                    a.name,
                    a.options.field,
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
        .filter(|(_, n)| *n >= MIN_LABELS && (*n < FEW_LABELS || *n > MANY_LABELS))
        .map(|(a, n)| {
            let (what, hint) = if n < FEW_LABELS {
                ("too few to read values between them", "ask for more ticks (`ticks = 5`) or make the axis longer")
            } else {
                ("too many to read at a glance", "ask for fewer ticks (`ticks = 6`); about 5 to 10 labels read best")
            };
            Issue::new(
                a.name,
                format!("{}.ticks", a.key),
                format!("the {} has {n} labelled ticks, {what}", a.name),
                hint,
            )
        })
        .collect()
}
