//! Trees from tables: an `id` + `parent` column pair, or one path column (`a/b/c`). Nested
//! JSON trees are flattened into an id/parent table when loaded (`format = "tree"`).
//!
//! The shape goes into a [`Hierarchy`]; every node remembers its id, its display name and the
//! table row it came from (none for nodes a path implies but no row names, and for a
//! synthetic root).

use std::collections::HashMap;
use std::fmt;

use super::{Column, Table};
use crate::layout::hierarchy::{Hierarchy, HierarchyError};

/// Name of the root added above several top-level nodes.
pub const SYNTHETIC_ROOT: &str = "(all)";

/// A tree read from a table.
#[derive(Clone, Debug)]
pub struct Tree {
    /// The shape.
    pub hierarchy: Hierarchy,
    /// Each node's id: the id cell, or the full path for path trees.
    pub ids: Vec<String>,
    /// Each node's display name: the last path segment, or the id.
    pub names: Vec<String>,
    /// The table row each node came from (`None` for implied nodes and a synthetic root).
    pub rows: Vec<Option<u32>>,
    /// True when several top-level nodes were put under a synthetic root, [`SYNTHETIC_ROOT`].
    pub synthetic_root: bool,
}

/// Why a table is not a tree. Each message names the offending ids or rows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TreeError {
    /// The table has no rows.
    Empty,
    /// Two rows carry the same id (or the same path).
    DuplicateId {
        /// The id.
        id: String,
        /// The first row carrying it.
        first: u32,
        /// The second.
        second: u32,
    },
    /// A row's id cell is missing.
    MissingId {
        /// The row.
        row: u32,
    },
    /// A parent names an id no row carries.
    DanglingParent {
        /// The child's id.
        id: String,
        /// The parent it names.
        parent: String,
    },
    /// Following parents loops back.
    Cycle {
        /// Ids on the cycle (the first few).
        ids: Vec<String>,
    },
    /// A node is its own parent.
    SelfParent {
        /// The id.
        id: String,
    },
    /// The shape is otherwise not a tree (e.g. too large).
    Shape(String),
}

impl fmt::Display for TreeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => write!(f, "the table has no rows, so there is no tree"),
            Self::DuplicateId { id, first, second } => {
                write!(f, "id `{id}` appears twice (rows {} and {}); ids must be unique", first + 1, second + 1)
            }
            Self::MissingId { row } => write!(f, "row {} has no id", row + 1),
            Self::DanglingParent { id, parent } => {
                write!(f, "node `{id}` names parent `{parent}`, but no row has that id")
            }
            Self::Cycle { ids } => write!(f, "the parents form a cycle: {}", ids.join(" → ")),
            Self::SelfParent { id } => write!(f, "node `{id}` is its own parent"),
            Self::Shape(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for TreeError {}

impl TreeError {
    /// How to fix it.
    pub fn hint(&self) -> &'static str {
        match self {
            Self::Empty => "give the tree's data source at least one row",
            Self::DuplicateId { .. } => "make each node's id unique (use full paths as ids if names repeat)",
            Self::MissingId { .. } => "fill in every row's id",
            Self::DanglingParent { .. } => {
                "add a row for the parent, or leave the parent cell empty for a top-level node"
            }
            Self::Cycle { .. } | Self::SelfParent { .. } => "a tree's parents must lead up to one root without looping",
            Self::Shape(_) => "check the tree's columns",
        }
    }
}

impl Tree {
    /// A tree from an id column and a parent column; rows with an empty parent are top-level.
    /// Several top-level rows get a synthetic root above them.
    pub fn from_parent_column(table: &Table, id: &Column, parent: &Column) -> Result<Tree, TreeError> {
        let n = table.rows;
        if n == 0 {
            return Err(TreeError::Empty);
        }
        let mut ids = Vec::with_capacity(n);
        let mut index: HashMap<String, u32> = HashMap::with_capacity(n);
        for row in 0..n {
            let key = id.key(row).ok_or(TreeError::MissingId { row: row as u32 })?;
            if let Some(&first) = index.get(&key) {
                return Err(TreeError::DuplicateId { id: key, first, second: row as u32 });
            }
            index.insert(key.clone(), row as u32);
            ids.push(key);
        }
        let mut parents: Vec<Option<usize>> = Vec::with_capacity(n + 1);
        for (row, own) in ids.iter().enumerate() {
            let p = match parent.key(row) {
                None => None,
                Some(p) if p == *own => return Err(TreeError::SelfParent { id: p }),
                Some(p) => match index.get(&p) {
                    Some(&i) => Some(i as usize),
                    None => return Err(TreeError::DanglingParent { id: own.clone(), parent: p }),
                },
            };
            parents.push(p);
        }
        let rows = (0..n as u32).map(Some).collect();
        Self::assemble(parents, ids.clone(), ids, rows)
    }

    /// A tree from one path column: `a/b/c` is node `c` under `b` under `a`. Nodes a path
    /// implies but no row names are added without a row; several top-level names get a
    /// synthetic root. Empty segments (`a//b`, a leading `/`) are skipped.
    pub fn from_paths(table: &Table, path: &Column, separator: &str) -> Result<Tree, TreeError> {
        let n = table.rows;
        if n == 0 {
            return Err(TreeError::Empty);
        }
        let separator = if separator.is_empty() { "/" } else { separator };
        let mut ids: Vec<String> = Vec::with_capacity(n);
        let mut names: Vec<String> = Vec::with_capacity(n);
        let mut rows: Vec<Option<u32>> = Vec::with_capacity(n);
        let mut parents: Vec<Option<usize>> = Vec::with_capacity(n);
        let mut index: HashMap<String, usize> = HashMap::with_capacity(n);
        for row in 0..n {
            let text = path.key(row).ok_or(TreeError::MissingId { row: row as u32 })?;
            let segments: Vec<&str> = text.split(separator).map(str::trim).filter(|s| !s.is_empty()).collect();
            if segments.is_empty() {
                return Err(TreeError::MissingId { row: row as u32 });
            }
            let mut parent: Option<usize> = None;
            let mut full = String::new();
            for (depth, segment) in segments.iter().enumerate() {
                if depth > 0 {
                    full.push_str(separator);
                }
                full.push_str(segment);
                let last = depth + 1 == segments.len();
                let node = match index.get(&full) {
                    Some(&node) => node,
                    None => {
                        let node = ids.len();
                        index.insert(full.clone(), node);
                        ids.push(full.clone());
                        names.push((*segment).to_string());
                        rows.push(None);
                        parents.push(parent);
                        node
                    }
                };
                if last {
                    if let Some(first) = rows[node] {
                        return Err(TreeError::DuplicateId { id: full, first, second: row as u32 });
                    }
                    rows[node] = Some(row as u32);
                }
                parent = Some(node);
            }
        }
        Self::assemble(parents, ids, names, rows)
    }

    /// Adds a synthetic root when needed and checks the shape.
    fn assemble(
        mut parents: Vec<Option<usize>>,
        mut ids: Vec<String>,
        mut names: Vec<String>,
        mut rows: Vec<Option<u32>>,
    ) -> Result<Tree, TreeError> {
        let top = parents.iter().filter(|p| p.is_none()).count();
        let synthetic_root = top > 1;
        if synthetic_root {
            let root = parents.len();
            for p in parents.iter_mut().filter(|p| p.is_none()) {
                *p = Some(root);
            }
            parents.push(None);
            ids.push(SYNTHETIC_ROOT.to_string());
            names.push(SYNTHETIC_ROOT.to_string());
            rows.push(None);
        }
        let hierarchy = Hierarchy::from_parents(&parents).map_err(|e| match e {
            HierarchyError::Cycle(nodes) | HierarchyError::SeveralRoots(nodes) => {
                TreeError::Cycle { ids: nodes.iter().take(6).filter_map(|&i| ids.get(i).cloned()).collect() }
            }
            HierarchyError::NoRoot => TreeError::Cycle { ids: ids.iter().take(6).cloned().collect() },
            other => TreeError::Shape(other.to_string()),
        })?;
        Ok(Tree { hierarchy, ids, names, rows, synthetic_root })
    }

    /// The node with this id (or path), if any.
    pub fn find(&self, id: &str) -> Option<usize> {
        self.ids.iter().position(|i| i == id)
    }

    /// Each node's value from a numeric column, read at its row (NaN where it has none).
    pub fn values_of(&self, column: &Column) -> Vec<f64> {
        let values = column.numbers().unwrap_or(&[]);
        self.rows.iter().map(|r| r.and_then(|r| values.get(r as usize).copied()).unwrap_or(f64::NAN)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{Categories, ColumnValues};

    fn text(name: &str, values: &[&str]) -> (String, ColumnValues) {
        let cats = Categories::from_values(values.iter().map(|v| if v.is_empty() { None } else { Some(*v) }));
        (name.to_string(), ColumnValues::Text(cats))
    }

    fn id_parent(ids: &[&str], parents: &[&str]) -> Result<Tree, TreeError> {
        let table = Table::from_columns([text("id", ids), text("parent", parents)]);
        Tree::from_parent_column(&table, table.column("id").unwrap(), table.column("parent").unwrap())
    }

    #[test]
    fn id_and_parent_columns_make_a_tree_in_row_order() {
        let tree = id_parent(&["root", "a", "b", "a1"], &["", "root", "root", "a"]).unwrap();
        assert_eq!(tree.hierarchy.root(), 0);
        assert_eq!(tree.hierarchy.children(0), &[1, 2]);
        assert_eq!(tree.hierarchy.children(1), &[3]);
        assert_eq!(tree.rows, vec![Some(0), Some(1), Some(2), Some(3)]);
        assert!(!tree.synthetic_root);
    }

    #[test]
    fn numeric_ids_work_and_several_roots_get_a_synthetic_root() {
        let table = Table::from_columns([
            ("id".to_string(), ColumnValues::Number(vec![1.0, 2.0, 3.0])),
            ("parent".to_string(), ColumnValues::Number(vec![f64::NAN, f64::NAN, 1.0])),
        ]);
        let tree =
            Tree::from_parent_column(&table, table.column("id").unwrap(), table.column("parent").unwrap()).unwrap();
        assert!(tree.synthetic_root);
        assert_eq!(tree.hierarchy.root(), 3);
        assert_eq!(tree.names[3], SYNTHETIC_ROOT);
        assert_eq!(tree.hierarchy.children(3), &[0, 1]);
        assert_eq!(tree.find("3"), Some(2));
        assert_eq!(tree.hierarchy.parent(2), Some(0));
    }

    #[test]
    fn bad_id_parent_tables_name_the_problem() {
        assert_eq!(
            id_parent(&["a", "b", "a"], &["", "a", "b"]).unwrap_err(),
            TreeError::DuplicateId { id: "a".into(), first: 0, second: 2 }
        );
        assert_eq!(
            id_parent(&["a", "b"], &["", "zz"]).unwrap_err(),
            TreeError::DanglingParent { id: "b".into(), parent: "zz".into() }
        );
        assert_eq!(id_parent(&["a", "b"], &["", "b"]).unwrap_err(), TreeError::SelfParent { id: "b".into() });
        let cycle = id_parent(&["r", "x", "y"], &["", "y", "x"]).unwrap_err();
        assert!(matches!(&cycle, TreeError::Cycle { ids } if ids.len() == 2), "{cycle:?}");
        assert!(cycle.to_string().contains("cycle"));
        assert_eq!(id_parent(&[], &[]).unwrap_err(), TreeError::Empty);
        assert_eq!(id_parent(&["a", ""], &["", "a"]).unwrap_err(), TreeError::MissingId { row: 1 });
    }

    #[test]
    fn paths_imply_their_inner_nodes() {
        let table =
            Table::from_columns([text("path", &["flare/vis/axis", "flare/vis/legend", "flare/util", "/flare//x/"])]);
        let tree = Tree::from_paths(&table, table.column("path").unwrap(), "/").unwrap();
        assert_eq!(tree.ids, vec!["flare", "flare/vis", "flare/vis/axis", "flare/vis/legend", "flare/util", "flare/x"]);
        assert_eq!(tree.names[1], "vis");
        assert_eq!(tree.rows, vec![None, None, Some(0), Some(1), Some(2), Some(3)]);
        assert_eq!(tree.hierarchy.children(1), &[2, 3]);
        assert!(!tree.synthetic_root);
        let dup = Table::from_columns([text("path", &["a/b", "a/b"])]);
        assert!(matches!(
            Tree::from_paths(&dup, dup.column("path").unwrap(), "/"),
            Err(TreeError::DuplicateId { first: 0, second: 1, .. })
        ));
        let two = Table::from_columns([text("path", &["a.x", "b.y"])]);
        let tree = Tree::from_paths(&two, two.column("path").unwrap(), ".").unwrap();
        assert!(tree.synthetic_root && tree.hierarchy.len() == 5);
    }

    #[test]
    fn values_follow_rows() {
        let table = Table::from_columns([
            text("path", &["a/b", "a/c"]),
            ("v".to_string(), ColumnValues::Number(vec![2.0, 5.0])),
        ]);
        let tree = Tree::from_paths(&table, table.column("path").unwrap(), "/").unwrap();
        let values = tree.values_of(table.column("v").unwrap());
        assert!(values[0].is_nan());
        assert_eq!(&values[1..], &[2.0, 5.0]);
    }
}
