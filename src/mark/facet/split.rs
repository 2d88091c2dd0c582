//! Splitting a chart's rows into facet panels: the values of the facet columns, their order,
//! and where each panel sits in the grid.

use std::collections::HashMap;

use crate::data::{Column, Table};
use crate::guide::format::format_value;
use crate::guide::time::format_timestamp;
use crate::mark::MarkError;
use crate::spec::{Facet, FacetSort};

/// The most panels a facet draws.
pub const MAX_PANELS: usize = 100;

/// One panel's rows and place.
#[derive(Clone, Debug, PartialEq)]
pub struct PanelRows {
    /// Grid row and column of the panel.
    pub cell: (usize, usize),
    /// The panel's value of the `row` column, if faceted by rows.
    pub row_value: Option<String>,
    /// The panel's value of the `column` column, if faceted by columns.
    pub column_value: Option<String>,
    /// The table rows drawn in the panel, ascending.
    pub rows: Vec<u32>,
}

/// How a chart's rows split into panels.
#[derive(Clone, Debug, PartialEq)]
pub struct Split {
    /// The `row` column, if any.
    pub row_field: Option<String>,
    /// The `column` column, if any.
    pub column_field: Option<String>,
    /// Grid rows and columns.
    pub grid: (usize, usize),
    /// Whether panels of one column facet wrap onto several grid rows (each panel then has
    /// its own header).
    pub wrapped: bool,
    /// The panels that have rows, in reading order (row by row).
    pub panels: Vec<PanelRows>,
    /// Rows left out because a facet column had no value there, per facet column.
    pub missing: Vec<(String, usize)>,
    /// Rows left out for a missing facet value (a row missing both counts once).
    pub left_out: usize,
}

impl Split {
    /// The header text of a panel's column value (`"island = Biscoe"`).
    pub fn column_header(&self, panel: &PanelRows) -> Option<String> {
        Some(format!("{} = {}", self.column_field.as_ref()?, panel.column_value.as_ref()?))
    }

    /// The header text of a panel's row value (`"sex = female"`).
    pub fn row_header(&self, panel: &PanelRows) -> Option<String> {
        Some(format!("{} = {}", self.row_field.as_ref()?, panel.row_value.as_ref()?))
    }

    /// A panel's name in the scene and in messages: its values, row first.
    pub fn panel_name(&self, panel: &PanelRows) -> String {
        let parts: Vec<String> = [self.row_header(panel), self.column_header(panel)].into_iter().flatten().collect();
        parts.join(", ")
    }
}

/// The values of one facet column: a value index per row (`None` where missing) and the
/// values' labels in panel order.
struct Levels {
    of_row: Vec<Option<u32>>,
    labels: Vec<String>,
}

/// Split `table` by the chart's `facet`.
pub fn split(facet: &Facet, table: &Table) -> Result<Split, MarkError> {
    let options = facet.options();
    if options.row.is_none() && options.column.is_none() {
        return Err(MarkError::at(
            &["facet"],
            "`facet` names no column to split the panels by",
            "give `column = \"...\"` (panels side by side), `row = \"...\"` (panels stacked), or both",
        ));
    }
    if options.wrap.is_some() && (options.row.is_some() || options.column.is_none()) {
        return Err(MarkError::at(
            &["facet", "wrap"],
            "`wrap` applies to a `column` facet alone",
            "remove `wrap`, or facet by `column` only",
        ));
    }
    let sort = options.sort.unwrap_or_default();
    let row_levels = options.row.as_deref().map(|f| levels(table, f, "row", sort)).transpose()?;
    let column_levels = options.column.as_deref().map(|f| levels(table, f, "column", sort)).transpose()?;
    let nr = row_levels.as_ref().map_or(1, |l| l.labels.len());
    let nc = column_levels.as_ref().map_or(1, |l| l.labels.len());
    if nr * nc > MAX_PANELS {
        return Err(MarkError::at(
            &["facet"],
            format!("the facet makes {nr} × {nc} = {} panels; at most {MAX_PANELS} are drawn", nr * nc),
            "facet by columns with fewer values, or filter the rows first (a `filter` transform)",
        ));
    }

    let mut cells: Vec<Vec<u32>> = vec![Vec::new(); nr * nc];
    let mut missing = [0usize; 2];
    let mut left_out = 0;
    for r in 0..table.rows {
        let ri = match &row_levels {
            Some(l) => l.of_row[r],
            None => Some(0),
        };
        let ci = match &column_levels {
            Some(l) => l.of_row[r],
            None => Some(0),
        };
        match (ri, ci) {
            (Some(ri), Some(ci)) => cells[ri as usize * nc + ci as usize].push(r as u32),
            (ri, ci) => {
                missing[0] += usize::from(ri.is_none());
                missing[1] += usize::from(ci.is_none());
                left_out += 1;
            }
        }
    }
    let label = |levels: &Option<Levels>, i: usize| levels.as_ref().map(|l| l.labels[i].clone());
    let wrapped = row_levels.is_none() && (options.wrap.is_some() || facet.wraps_by_default());
    let per_row = match (wrapped, options.wrap) {
        (false, _) => nc,
        (true, Some(w)) => (w as usize).clamp(1, nc.max(1)),
        (true, None) if nc <= 3 => nc,
        (true, None) => (nc as f64).sqrt().ceil() as usize,
    };
    let mut panels = Vec::new();
    for ri in 0..nr {
        for ci in 0..nc {
            let rows = std::mem::take(&mut cells[ri * nc + ci]);
            let cell = if wrapped { (ci / per_row, ci % per_row) } else { (ri, ci) };
            panels.push(PanelRows {
                cell,
                row_value: label(&row_levels, ri),
                column_value: label(&column_levels, ci),
                rows,
            });
        }
    }
    let grid = if wrapped { (nc.div_ceil(per_row), per_row) } else { (nr, nc) };
    // A wrapped facet has a panel for every value; a grid leaves combinations without rows empty.
    panels.retain(|p| !p.rows.is_empty());
    let fields = [options.row.clone(), options.column.clone()];
    let missing = fields.into_iter().zip(missing).filter_map(|(f, n)| Some((f?, n))).filter(|(_, n)| *n > 0).collect();
    Ok(Split { row_field: options.row, column_field: options.column, grid, wrapped, panels, missing, left_out })
}

/// The values of facet column `field` (under key `key` of `facet`), in panel order.
fn levels(table: &Table, field: &str, key: &str, sort: FacetSort) -> Result<Levels, MarkError> {
    let column = table.column(field).ok_or_else(|| {
        let names = table.column_names();
        MarkError::at(
            &["facet", key],
            format!("no column `{field}` to facet by"),
            crate::spec::suggest::hint(field, &names, "columns", true),
        )
    })?;
    let levels = match column.categories() {
        Some(cats) => text_levels(cats, sort),
        None => number_levels(column, sort),
    }
    .ok_or_else(|| {
        MarkError::at(
            &["facet", key],
            format!("column `{field}` has more than {MAX_PANELS} distinct values; a facet draws one panel per value"),
            "facet by a column with few values (a category), or bin it first (a `bin` transform)",
        )
    })?;
    if levels.labels.is_empty() {
        return Err(MarkError::at(
            &["facet", key],
            format!("column `{field}` has no values to facet by"),
            "facet by a column with values in the chart's rows",
        ));
    }
    Ok(levels)
}

/// Text values: used levels, alphabetically or in order of appearance.
fn text_levels(cats: &crate::data::Categories, sort: FacetSort) -> Option<Levels> {
    // Blank text is a missing value, as everywhere else.
    let blank: Vec<bool> = cats.levels.iter().map(|l| l.trim().is_empty()).collect();
    let mut used = vec![false; cats.levels.len()];
    for &code in &cats.codes {
        if let Some(u) = used.get_mut(code as usize) {
            *u = !blank[code as usize];
        }
    }
    let mut order: Vec<usize> = (0..cats.levels.len()).filter(|&i| used[i]).collect();
    if order.len() > MAX_PANELS {
        return None;
    }
    if sort == FacetSort::Ascending {
        order.sort_by(|&a, &b| cats.levels[a].trim().cmp(cats.levels[b].trim()));
    }
    let mut index = vec![None; cats.levels.len()];
    for (k, &level) in order.iter().enumerate() {
        index[level] = Some(k as u32);
    }
    let of_row = cats.codes.iter().map(|&c| index.get(c as usize).copied().flatten()).collect();
    let labels = order.iter().map(|&i| cats.levels[i].trim().to_string()).collect();
    Some(Levels { of_row, labels })
}

/// Numbers and instants: distinct finite values, ascending or in order of appearance; `None`
/// beyond [`MAX_PANELS`] values.
fn number_levels(column: &Column, sort: FacetSort) -> Option<Levels> {
    let values = column.numbers().unwrap_or(&[]);
    let mut index: HashMap<u64, u32> = HashMap::new();
    let mut distinct: Vec<f64> = Vec::new();
    let mut of_row = Vec::with_capacity(values.len());
    for &v in values {
        if !v.is_finite() {
            of_row.push(None);
            continue;
        }
        let v = if v == 0.0 { 0.0 } else { v };
        let next = distinct.len() as u32;
        let k = *index.entry(v.to_bits()).or_insert(next);
        if k == next {
            distinct.push(v);
            if distinct.len() > MAX_PANELS {
                return None;
            }
        }
        of_row.push(Some(k));
    }
    let mut order: Vec<usize> = (0..distinct.len()).collect();
    if sort == FacetSort::Ascending {
        order.sort_by(|&a, &b| distinct[a].total_cmp(&distinct[b]));
    }
    let mut rank = vec![0u32; distinct.len()];
    for (k, &i) in order.iter().enumerate() {
        rank[i] = k as u32;
    }
    let of_row = of_row.into_iter().map(|k| k.map(|k| rank[k as usize])).collect();
    let label = |v: f64| if column.is_time() { format_timestamp(v) } else { format_value(v) };
    let labels = order.iter().map(|&i| label(distinct[i])).collect();
    Some(Levels { of_row, labels })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{Categories, ColumnValues};
    use crate::spec::FacetOptions;

    fn table() -> Table {
        Table::from_columns([
            ("g", ColumnValues::Text(Categories::from_values([Some("b"), Some("a"), None, Some("b"), Some("c")]))),
            ("n", ColumnValues::Number(vec![2.0, 10.0, 2.0, f64::NAN, 10.0])),
        ])
    }

    fn detailed(row: Option<&str>, column: Option<&str>) -> Facet {
        Facet::Detailed(FacetOptions {
            row: row.map(str::to_owned),
            column: column.map(str::to_owned),
            wrap: None,
            resolve: None,
            sort: None,
        })
    }

    #[test]
    fn a_bare_column_gives_one_panel_per_value_in_ascending_order() {
        let s = split(&Facet::Field("g".into()), &table()).unwrap_or_else(|e| panic!("{e}"));
        let values: Vec<_> = s.panels.iter().map(|p| p.column_value.clone().unwrap_or_default()).collect();
        assert_eq!(values, ["a", "b", "c"]);
        assert_eq!(s.panels[1].rows, [0, 3]);
        assert_eq!(s.grid, (1, 3));
        assert_eq!(s.missing, [("g".to_string(), 1)]);
        let total: usize = s.panels.iter().map(|p| p.rows.len()).sum();
        assert_eq!(total + 1, 5, "every row with a value is in exactly one panel");
    }

    #[test]
    fn numbers_sort_by_value_and_a_grid_skips_empty_combinations() {
        let s = split(&detailed(Some("n"), Some("g")), &table()).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.grid, (2, 3));
        let cells: Vec<_> = s.panels.iter().map(|p| (p.cell, p.rows.clone())).collect();
        assert_eq!(cells, [((0, 1), vec![0]), ((1, 0), vec![1]), ((1, 2), vec![4])], "2 before 10");
        assert_eq!(s.panels[0].row_value.as_deref(), Some("2"));
        assert_eq!(s.panel_name(&s.panels[0]), "n = 2, g = b");
    }

    #[test]
    fn data_order_and_wrapping() {
        let mut options = detailed(None, Some("g")).options();
        options.sort = Some(FacetSort::Data);
        options.wrap = Some(2);
        let s = split(&Facet::Detailed(options), &table()).unwrap_or_else(|e| panic!("{e}"));
        let values: Vec<_> = s.panels.iter().map(|p| (p.cell, p.column_value.clone().unwrap_or_default())).collect();
        assert_eq!(values, [((0, 0), "b".to_string()), ((0, 1), "a".into()), ((1, 0), "c".into())]);
        assert!(s.wrapped);
        assert_eq!(s.grid, (2, 2));
    }

    #[test]
    fn bad_facets_say_what_is_wrong() {
        let e = split(&Facet::Field("gg".into()), &table()).err().unwrap_or_else(|| panic!("no such column"));
        assert!(e.message.contains("no column `gg`") && e.hint.contains("`g`"), "{e:?}");
        let e = split(&detailed(None, None), &table()).err().unwrap_or_else(|| panic!("no column named"));
        assert!(e.message.contains("names no column"));
        let many = Table::from_columns([("id", ColumnValues::Number((0..500).map(f64::from).collect()))]);
        let e = split(&Facet::Field("id".into()), &many).err().unwrap_or_else(|| panic!("too many panels"));
        assert!(e.message.contains("more than 100 distinct values"), "{}", e.message);
        let mut wrap_rows = detailed(Some("g"), Some("n")).options();
        wrap_rows.wrap = Some(2);
        let e = split(&Facet::Detailed(wrap_rows), &table()).err().unwrap_or_else(|| panic!("wrap with rows"));
        assert_eq!(e.path.last(), Some(&crate::spec::PathSeg::Key("wrap".into())));
    }
}
