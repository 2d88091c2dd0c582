//! What the hierarchy kinds (treemap, hypertree) share: reading the tree from the chart's
//! table, node labels, and the top-level branch each node belongs to (for branch colours).

use crate::data::Table;
use crate::data::tree::Tree;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::{MarkError, encode};
use crate::scene::Color;
use crate::spec::{Chart, TreeSource};

/// Most rows (nodes) a treemap or hyperbolic tree reads: past this many, leaves are smaller than
/// a pixel and the layout's work is wasted.
pub const MAX_TREE_ROWS: usize = 250_000;

/// The chart's tree, or an error pointing at `tree`.
pub fn tree_of(chart: &Chart, source: &TreeSource, table: &Table) -> Result<Tree, MarkError> {
    if table.rows > MAX_TREE_ROWS {
        return Err(MarkError::at(
            &["data"],
            format!("the tree has {} rows but a tree chart draws at most {MAX_TREE_ROWS}", table.rows),
            "aggregate the leaves to a coarser level first (an `aggregate` transform grouped by the parent path), or \
             filter to one branch",
        ));
    }
    let built = match (&source.path, &source.id, &source.parent) {
        (Some(path), None, None) => {
            let column = encode::column(chart, "tree", path, table)?;
            Tree::from_paths(table, column, source.separator.as_deref().unwrap_or("/"))
        }
        (None, Some(id), Some(parent)) => {
            let id = encode::column(chart, "tree", id, table)?;
            let parent = encode::column(chart, "tree", parent, table)?;
            Tree::from_parent_column(table, id, parent)
        }
        _ => {
            return Err(MarkError::at(
                &["tree"],
                format!("`tree` needs `path`, or `id` with `parent`"),
                "write `tree = { id = \"id\", parent = \"parent\" }` or `tree = { path = \"path\" }`",
            ));
        }
    };
    built.map_err(|e| MarkError::at(&["tree"], format!("{e}"), e.hint()))
}

/// Each node's label: the `label` column at its row, else its name.
pub fn labels_of(chart: &Chart, tree: &Tree, label: Option<&str>, table: &Table) -> Result<Vec<String>, MarkError> {
    let Some(field) = label else { return Ok(tree.names.clone()) };
    let column = encode::column(chart, "label", field, table)?;
    Ok(tree
        .rows
        .iter()
        .zip(&tree.names)
        .map(|(row, name)| match row {
            Some(r) => column.key(*r as usize).unwrap_or_else(|| name.clone()),
            None => name.clone(),
        })
        .collect())
}

/// The branches of a tree: the first level below the root with more than one node (a root
/// with a single child passes the role down), and for every node the branch it lies in
/// (`None` for the nodes above that level).
pub struct Branches {
    /// The branch nodes, in child order.
    pub heads: Vec<usize>,
    /// Per node: the index into `heads` of its branch.
    pub of_node: Vec<Option<usize>>,
}

impl Branches {
    /// Find the branches of `tree`.
    pub fn of(tree: &Tree) -> Branches {
        let h = &tree.hierarchy;
        let mut top = h.root();
        while h.children(top).len() == 1 {
            top = h.children(top)[0] as usize;
        }
        let heads: Vec<usize> = h.children(top).iter().map(|&c| c as usize).collect();
        let mut of_node = vec![None; h.len()];
        for (i, &head) in heads.iter().enumerate() {
            of_node[head] = Some(i);
        }
        for node in h.preorder() {
            let node = node as usize;
            if of_node[node].is_none()
                && let Some(p) = h.parent(node)
            {
                of_node[node] = of_node[p];
            }
        }
        Branches { heads, of_node }
    }
}

/// Branches named in the legend before the rest are summed up in one entry.
const MAX_LEGEND_BRANCHES: usize = 12;

/// The categorical palette of the branches: the named scheme, or Okabe–Ito for up to eight
/// branches and its 12-colour extension `okabe-ito-12` above that (both pass lint rule CL003).
pub fn branch_palette(scheme: Option<&str>, branches: usize) -> Result<Vec<Color>, MarkError> {
    let name = scheme.or((branches > 8).then_some("okabe-ito-12"));
    encode::palette(&["scheme"], name)
}

/// A legend naming each branch's colour (the first dozen; the rest are counted).
pub fn branch_legend(branches: &Branches, labels: &[String], palette: &[Color]) -> Option<Legend> {
    let mut entries: Vec<(String, Color)> = branches
        .heads
        .iter()
        .enumerate()
        .take(MAX_LEGEND_BRANCHES)
        .map(|(i, &n)| (labels[n].clone(), palette[i % palette.len().max(1)]))
        .collect();
    if branches.heads.len() > MAX_LEGEND_BRANCHES {
        let more = branches.heads.len() - MAX_LEGEND_BRANCHES;
        entries.push((format!("… {more} more (colours repeat)"), Color::TRANSPARENT));
    }
    (!entries.is_empty()).then(|| Legend::Categorical { title: "branch".into(), entries, symbol: Symbol::Square })
}

impl Branches {
    /// The colour of `node`'s branch (grey above the branch level).
    pub fn color(&self, node: usize, palette: &[Color]) -> Color {
        match self.of_node.get(node).copied().flatten() {
            Some(i) => palette[i % palette.len().max(1)],
            None => crate::guide::color::MISSING,
        }
    }
}

/// Derived output for `nodes` of a tree: one row each with its id, label, parent id and depth;
/// kinds add their geometry columns.
pub fn node_rows(tree: &Tree, labels: &[String], nodes: &[usize], depths: &[u32]) -> Derived {
    let h = &tree.hierarchy;
    let mut d = Derived::default();
    d.push("id", DerivedColumn::Text(nodes.iter().map(|&n| tree.ids[n].clone()).collect()));
    d.push("label", DerivedColumn::Text(nodes.iter().map(|&n| labels[n].clone()).collect()));
    let parent = |n: usize| h.parent(n).map(|p| tree.ids[p].clone()).unwrap_or_default();
    d.push("parent", DerivedColumn::Text(nodes.iter().map(|&n| parent(n)).collect()));
    d.push("depth", DerivedColumn::Number(nodes.iter().map(|&n| depths[n] as f64).collect()));
    d
}
