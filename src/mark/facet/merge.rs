//! Putting facet panels back together: the union of their axes and legends, and one derived
//! table and warning list in the rows of the whole table.

use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::Legend;
use crate::mark::ChartOutput;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::warning::{ColumnLoss, Warning};
use crate::scene::{Item, Shape};

use super::split::Split;
use crate::mark::panel::Seen;

/// One axis whose domain covers every panel's: continuous extents joined, categories in the
/// order they appear panel by panel.
pub fn union_axis<'a>(axes: impl Iterator<Item = &'a PositionAxis>) -> Option<PositionAxis> {
    let mut union: Option<PositionAxis> = None;
    for axis in axes {
        let Some(u) = union.as_mut() else {
            union = Some(axis.clone());
            continue;
        };
        u.inset = u.inset.max(axis.inset);
        match (&mut u.domain, &axis.domain) {
            (Domain::Continuous(lo, hi), Domain::Continuous(a, b)) => {
                *lo = lo.min(*a);
                *hi = hi.max(*b);
            }
            (Domain::Categories(have), Domain::Categories(more)) => merge_in_order(have, more, |a, b| a == b),
            _ => {}
        }
    }
    union
}

/// The domain of each column axis over every panel, by column (columns in first-seen order).
pub fn union_columns<'a>(lists: impl Iterator<Item = &'a [(String, PositionAxis)]>) -> Vec<(String, Domain)> {
    let mut by_field: Vec<(String, Vec<&PositionAxis>)> = Vec::new();
    for list in lists {
        for (field, axis) in list {
            match by_field.iter_mut().find(|(f, _)| f == field) {
                Some((_, axes)) => axes.push(axis),
                None => by_field.push((field.clone(), vec![axis])),
            }
        }
    }
    by_field.into_iter().filter_map(|(field, axes)| Some((field, union_axis(axes.into_iter())?.domain))).collect()
}

/// Add the items of `more` missing from `have`, each after the item it follows in `more`, so
/// that orders the lists agree on are kept.
fn merge_in_order<T: Clone>(have: &mut Vec<T>, more: &[T], same: impl Fn(&T, &T) -> bool) {
    let mut after: Option<usize> = None;
    for item in more {
        match have.iter().position(|h| same(h, item)) {
            Some(i) => after = Some(i),
            None => {
                let at = after.map_or(have.len(), |i| i + 1);
                have.insert(at, item.clone());
                after = Some(at);
            }
        }
    }
}

/// The panels' legends as one stack: legends of the same title joined (categories merged in
/// order, then in the colour `order` where it lists them; colour-bar ranges joined), the others
/// kept once.
pub fn union_legends<'a>(lists: impl Iterator<Item = &'a [Legend]>, order: &[String]) -> Vec<Legend> {
    let mut out: Vec<Legend> = Vec::new();
    for list in lists {
        for legend in list {
            let found = out.iter_mut().find(|l| l.title() == legend.title() && same_kind(l, legend));
            match (found, legend) {
                (None, _) => out.push(legend.clone()),
                (Some(Legend::Categorical { entries, .. }), Legend::Categorical { entries: more, .. }) => {
                    merge_in_order(entries, more, |a, b| a.0 == b.0)
                }
                (Some(Legend::ColorBar { domain, .. }), Legend::ColorBar { domain: more, .. }) => {
                    *domain = (domain.0.min(more.0), domain.1.max(more.1));
                }
                _ => {}
            }
        }
    }
    for legend in &mut out {
        if let Legend::Categorical { entries, .. } = legend {
            entries.sort_by_key(|(label, _)| order.iter().position(|o| o == label).unwrap_or(usize::MAX));
        }
    }
    out
}

fn same_kind(a: &Legend, b: &Legend) -> bool {
    std::mem::discriminant(a) == std::mem::discriminant(b)
}

/// The size encoding every panel shares: the largest of the panels' largest values, and the size
/// legend in `legends` replaced by the one of the panel that has it (drawn on that mapping).
/// `None` when no panel has a size encoding.
pub fn share_size(legends: &mut [Legend], seen: &[Seen]) -> Option<f64> {
    let widest = (0..seen.len())
        .filter(|&i| seen[i].size_max.is_some())
        .max_by(|&a, &b| seen[a].size_max.unwrap_or(0.0).total_cmp(&seen[b].size_max.unwrap_or(0.0)))?;
    let own = seen[widest].legends.iter().find(|l| matches!(l, Legend::Size { .. }));
    if let (Some(own), Some(slot)) = (own, legends.iter_mut().find(|l| matches!(l, Legend::Size { .. }))) {
        *slot = own.clone();
    }
    seen[widest].size_max
}

/// The range of the continuous colour scale every panel uses: the joined colour bar's.
pub fn colour_range(legends: &[Legend]) -> Option<(f64, f64)> {
    legends.iter().find_map(|l| match l {
        Legend::ColorBar { domain, .. } => Some(*domain),
        _ => None,
    })
}

/// Map the data marks' rows of a panel (rows of its own table) to rows of the whole table.
pub fn to_table_rows(items: &mut [Item], panel_rows: &[u32]) {
    for item in items {
        for r in &mut item.rows {
            *r = panel_rows.get(*r as usize).copied().unwrap_or(u32::MAX);
        }
        if let Shape::Group { items, .. } = &mut item.shape {
            to_table_rows(items, panel_rows);
        }
    }
}

/// The panels' derived tables one after another, in rows of the whole table, each output row
/// with its panel's facet values.
pub fn concat_derived(outputs: &[ChartOutput], split: &Split, table_rows: usize) -> Derived {
    let mut names: Vec<String> = Vec::new();
    for o in outputs {
        for (name, _) in &o.derived.columns {
            if !names.contains(name) {
                names.push(name.clone());
            }
        }
    }
    let facet_fields: Vec<&String> = [&split.row_field, &split.column_field].into_iter().flatten().collect();
    let by_rows = outputs.iter().any(|o| !o.derived.rows.is_empty());
    let mut rows: Vec<u32> = Vec::new();
    let mut columns: Vec<(String, DerivedColumn)> = Vec::new();
    let mut facet_values: Vec<Vec<String>> = vec![Vec::new(); facet_fields.len()];
    for (o, panel) in outputs.iter().zip(&split.panels) {
        let n = o.derived.len();
        if by_rows {
            rows.extend(o.derived.rows.iter().map(|&r| panel.rows.get(r as usize).copied().unwrap_or(u32::MAX)));
        }
        // Rows of the whole table read their facet values from it; only output rows that are
        // not table rows (bins, groups) need them written out.
        if !by_rows {
            for (k, field) in facet_fields.iter().enumerate() {
                let value =
                    if Some(*field) == split.row_field.as_ref() { &panel.row_value } else { &panel.column_value };
                facet_values[k].extend(std::iter::repeat_n(value.clone().unwrap_or_default(), n));
            }
        }
        for name in &names {
            let own = o.derived.column(name);
            let at = match columns.iter().position(|(c, _)| c == name) {
                Some(at) => at,
                None => {
                    let empty = match own {
                        Some(DerivedColumn::Text(_)) => DerivedColumn::Text(Vec::new()),
                        Some(DerivedColumn::Source(s)) => DerivedColumn::Source(s.clone()),
                        Some(DerivedColumn::RowIndex) => DerivedColumn::RowIndex,
                        Some(DerivedColumn::Selected(_)) => DerivedColumn::Selected(vec![false; table_rows]),
                        _ => DerivedColumn::Number(Vec::new()),
                    };
                    columns.push((name.clone(), empty));
                    columns.len() - 1
                }
            };
            match (&mut columns[at].1, own) {
                (DerivedColumn::Number(all), Some(DerivedColumn::Number(v))) => all.extend(v.iter().copied()),
                (DerivedColumn::Number(all), _) => all.extend(std::iter::repeat_n(f64::NAN, n)),
                (DerivedColumn::Text(all), Some(DerivedColumn::Text(v))) => all.extend(v.iter().cloned()),
                (DerivedColumn::Text(all), _) => all.extend(std::iter::repeat_n(String::new(), n)),
                (DerivedColumn::Selected(all), Some(DerivedColumn::Selected(flags))) => {
                    for (r, &f) in flags.iter().enumerate() {
                        if let Some(&t) = panel.rows.get(r) {
                            all[t as usize] = f;
                        }
                    }
                }
                _ => {}
            }
        }
    }
    let mut derived = Derived { rows, columns };
    for (field, values) in facet_fields.into_iter().zip(facet_values) {
        if !names.contains(field) {
            let column = if by_rows { DerivedColumn::Source(field.clone()) } else { DerivedColumn::Text(values) };
            derived.columns.insert(0, (field.clone(), column));
        }
    }
    derived
}

/// The panels' warnings as the whole chart's: rows dropped summed over the panels (with the
/// rows no facet value placed), notes said once (with their panels when not every panel
/// raised them).
pub fn merge_warnings(
    outputs: &[ChartOutput],
    split: &Split,
    chart: &str,
    table_rows: usize,
) -> Vec<crate::mark::Warning> {
    let mut dropped = 0usize;
    let mut columns: Vec<ColumnLoss> = Vec::new();
    for (field, n) in &split.missing {
        columns.push(ColumnLoss { field: field.clone(), missing: *n, infinite: 0, non_positive: 0 });
    }
    let mut notes: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, o) in outputs.iter().enumerate() {
        for w in &o.warnings {
            match w {
                Warning::DroppedRows { dropped: d, columns: lost, .. } => {
                    dropped += d;
                    for loss in lost {
                        match columns.iter_mut().find(|c| c.field == loss.field) {
                            Some(c) => {
                                c.missing += loss.missing;
                                c.infinite += loss.infinite;
                                c.non_positive += loss.non_positive;
                            }
                            None => columns.push(loss.clone()),
                        }
                    }
                }
                Warning::OutsideDomain { text, .. } | Warning::Note(text) => {
                    match notes.iter_mut().find(|(t, _)| t == text) {
                        Some((_, panels)) => panels.push(i),
                        None => notes.push((text.clone(), vec![i])),
                    }
                }
            }
        }
    }
    let mut out = Vec::new();
    // Rows without a facet value never reach a panel.
    let dropped = dropped + split.left_out;
    if dropped > 0 {
        out.push(Warning::DroppedRows { chart: chart.to_string(), dropped, rows: table_rows, columns });
    }
    for (text, panels) in notes {
        if panels.len() == outputs.len() {
            out.push(Warning::Note(text));
        } else {
            let names: Vec<String> = panels.iter().map(|&i| split.panel_name(&split.panels[i])).collect();
            out.push(Warning::Note(format!("{text} (panel {})", names.join("; "))));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Color;
    use crate::spec::ScaleKind;

    fn axis(domain: Domain) -> PositionAxis {
        PositionAxis {
            title: "x".into(),
            kind: ScaleKind::Linear,
            domain,
            nice: true,
            ticks: None,
            grid: true,
            inset: 0.0,
        }
    }

    #[test]
    fn axes_join_extents_and_categories_in_order() {
        let a = [axis(Domain::Continuous(1.0, 5.0)), axis(Domain::Continuous(-2.0, 3.0))];
        assert_eq!(union_axis(a.iter()).map(|a| a.domain), Some(Domain::Continuous(-2.0, 5.0)));
        let cats = |v: &[&str]| axis(Domain::Categories(v.iter().map(|s| s.to_string()).collect()));
        let b = [cats(&["Adelie", "Gentoo"]), cats(&["Adelie", "Chinstrap"]), cats(&["Gentoo"])];
        let joined = union_axis(b.iter()).map(|a| a.domain);
        assert_eq!(joined, Some(Domain::Categories(vec!["Adelie".into(), "Chinstrap".into(), "Gentoo".into()])));
        assert_eq!(union_axis([].iter()), None);
    }

    #[test]
    fn legends_of_one_title_join() {
        let cat = |entries: &[&str]| Legend::Categorical {
            title: "species".into(),
            entries: entries.iter().map(|e| (e.to_string(), Color::BLACK)).collect(),
            symbol: crate::guide::legend::Symbol::Circle,
        };
        let joined =
            union_legends([vec![cat(&["a", "c"])], vec![cat(&["a", "b", "c"])]].iter().map(Vec::as_slice), &[]);
        assert_eq!(joined.len(), 1);
        let Legend::Categorical { entries, .. } = &joined[0] else { panic!("categorical") };
        let labels: Vec<&str> = entries.iter().map(|e| e.0.as_str()).collect();
        assert_eq!(labels, ["a", "b", "c"]);
        let order = ["c".to_string(), "a".to_string()];
        let joined = union_legends([vec![cat(&["a", "b"])], vec![cat(&["c"])]].iter().map(Vec::as_slice), &order);
        let Legend::Categorical { entries, .. } = &joined[0] else { panic!("categorical") };
        let labels: Vec<&str> = entries.iter().map(|e| e.0.as_str()).collect();
        assert_eq!(labels, ["c", "a", "b"], "the colour order first, the rest after");
    }
}
