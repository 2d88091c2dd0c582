//! A rooted tree over node indices `0..len`, stored compactly (children in one flat list) so that
//! trees with millions of nodes cost a handful of allocations.
//!
//! Node names, values and source rows live with the caller; this type holds only the shape.

use std::fmt;

/// Marker for "no parent" in [`Hierarchy::parent_raw`].
pub const NO_PARENT: u32 = u32::MAX;

/// A rooted tree: every node but the root has exactly one parent, and there are no cycles.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Hierarchy {
    parent: Vec<u32>,
    offsets: Vec<u32>,
    children: Vec<u32>,
    root: u32,
}

/// Why a parent list is not a tree. Indices are node indices as given.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HierarchyError {
    /// There are no nodes.
    Empty,
    /// More nodes than a `u32` index can hold.
    TooLarge(usize),
    /// No node is without a parent (every node is on or below a cycle).
    NoRoot,
    /// Several nodes have no parent; the first few are listed.
    SeveralRoots(Vec<usize>),
    /// A parent index is out of range.
    ParentOutOfRange {
        /// The node whose parent is bad.
        node: usize,
        /// The bad parent index.
        parent: usize,
    },
    /// Following parents from this node comes back to it (a self-parent is a cycle of one).
    Cycle(Vec<usize>),
}

impl fmt::Display for HierarchyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => write!(f, "the tree has no nodes"),
            Self::TooLarge(n) => write!(f, "the tree has {n} nodes; at most {} are supported", u32::MAX - 1),
            Self::NoRoot => write!(f, "every node has a parent, so there is no root (the parents form a cycle)"),
            Self::SeveralRoots(roots) => write!(f, "{} nodes have no parent (a tree has one root)", roots.len()),
            Self::ParentOutOfRange { node, parent } => {
                write!(f, "node {node} names parent {parent}, which does not exist")
            }
            Self::Cycle(nodes) => write!(f, "the parents form a cycle through {} nodes", nodes.len()),
        }
    }
}

impl std::error::Error for HierarchyError {}

impl Hierarchy {
    /// Builds the tree from each node's parent (`None` for the root). Children keep the order
    /// in which they appear in `parents`.
    pub fn from_parents(parents: &[Option<usize>]) -> Result<Self, HierarchyError> {
        let n = parents.len();
        if n == 0 {
            return Err(HierarchyError::Empty);
        }
        if n >= NO_PARENT as usize {
            return Err(HierarchyError::TooLarge(n));
        }
        let mut roots = Vec::new();
        let mut counts = vec![0u32; n + 1];
        for (node, parent) in parents.iter().enumerate() {
            match *parent {
                None => roots.push(node),
                Some(p) if p >= n => return Err(HierarchyError::ParentOutOfRange { node, parent: p }),
                Some(p) => counts[p + 1] += 1,
            }
        }
        if roots.len() > 1 {
            roots.truncate(8);
            return Err(HierarchyError::SeveralRoots(roots));
        }
        let Some(&root) = roots.first() else {
            return Err(HierarchyError::NoRoot);
        };
        for i in 1..=n {
            counts[i] += counts[i - 1];
        }
        let offsets = counts.clone();
        let mut fill = counts;
        let mut children = vec![0u32; n - 1];
        let mut parent = vec![NO_PARENT; n];
        for (node, p) in parents.iter().enumerate() {
            if let Some(p) = *p {
                children[fill[p] as usize] = node as u32;
                fill[p] += 1;
                parent[node] = p as u32;
            }
        }
        let tree = Self { parent, offsets, children, root: root as u32 };
        let reached = tree.preorder().len();
        if reached != n {
            return Err(HierarchyError::Cycle(tree.a_cycle()));
        }
        Ok(tree)
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// Always false: a hierarchy has at least its root.
    pub fn is_empty(&self) -> bool {
        self.parent.is_empty()
    }

    /// The root node.
    pub fn root(&self) -> usize {
        self.root as usize
    }

    /// The parent of `node`, or `None` for the root.
    pub fn parent(&self, node: usize) -> Option<usize> {
        let p = self.parent[node];
        (p != NO_PARENT).then_some(p as usize)
    }

    /// Every node's parent index, [`NO_PARENT`] for the root.
    pub fn parent_raw(&self) -> &[u32] {
        &self.parent
    }

    /// The children of `node`, in input order.
    pub fn children(&self, node: usize) -> &[u32] {
        &self.children[self.offsets[node] as usize..self.offsets[node + 1] as usize]
    }

    /// True when `node` has no children.
    pub fn is_leaf(&self, node: usize) -> bool {
        self.offsets[node] == self.offsets[node + 1]
    }

    /// Nodes in depth-first preorder from the root: every parent comes before its children, and
    /// siblings keep their order. Reversed, it visits children before parents.
    pub fn preorder(&self) -> Vec<u32> {
        let mut order = Vec::with_capacity(self.len());
        let mut stack = vec![self.root];
        while let Some(node) = stack.pop() {
            order.push(node);
            stack.extend(self.children(node as usize).iter().rev());
        }
        order
    }

    /// Depth of every node (the root is 0).
    pub fn depths(&self) -> Vec<u32> {
        let mut depth = vec![0u32; self.len()];
        for node in self.preorder() {
            let node = node as usize;
            if let Some(p) = self.parent(node) {
                depth[node] = depth[p] + 1;
            }
        }
        depth
    }

    /// Sums leaf weights up the tree: the result holds, for every node, the sum of `leaf[l]`
    /// over the leaves `l` below it (a leaf's own entry for a leaf). Entries of inner nodes in
    /// `leaf` are ignored.
    pub fn sum_leaves(&self, leaf: &[f64]) -> Vec<f64> {
        let mut total: Vec<f64> =
            (0..self.len()).map(|node| if self.is_leaf(node) { leaf[node] } else { 0.0 }).collect();
        for &node in self.preorder().iter().rev() {
            if let Some(p) = self.parent(node as usize) {
                total[p] += total[node as usize];
            }
        }
        total
    }

    /// The nodes of one cycle, for an error message (only called when some node is unreachable).
    fn a_cycle(&self) -> Vec<usize> {
        let n = self.len();
        let mut reached = vec![false; n];
        for node in self.preorder() {
            reached[node as usize] = true;
        }
        let Some(start) = (0..n).find(|&i| !reached[i]) else {
            return Vec::new();
        };
        // Walk parents n steps to be sure to stand on the cycle, then collect it.
        let mut node = start;
        for _ in 0..n {
            node = self.parent[node] as usize;
        }
        let mut cycle = vec![node];
        let mut next = self.parent[node] as usize;
        while next != node {
            cycle.push(next);
            next = self.parent[next] as usize;
        }
        cycle
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn children_keep_input_order_and_depths_count_edges() {
        let tree = Hierarchy::from_parents(&[None, Some(0), Some(0), Some(1), Some(1), Some(2)]).unwrap();
        assert_eq!(tree.root(), 0);
        assert_eq!(tree.children(0), &[1, 2]);
        assert_eq!(tree.children(1), &[3, 4]);
        assert!(tree.is_leaf(3) && !tree.is_leaf(2));
        assert_eq!(tree.preorder(), vec![0, 1, 3, 4, 2, 5]);
        assert_eq!(tree.depths(), vec![0, 1, 1, 2, 2, 2]);
        assert_eq!(tree.sum_leaves(&[9.0, 9.0, 9.0, 1.0, 2.0, 4.0]), vec![7.0, 3.0, 4.0, 1.0, 2.0, 4.0]);
    }

    #[test]
    fn bad_parent_lists_are_refused_with_the_reason() {
        assert_eq!(Hierarchy::from_parents(&[]), Err(HierarchyError::Empty));
        assert_eq!(Hierarchy::from_parents(&[None, None, Some(0)]), Err(HierarchyError::SeveralRoots(vec![0, 1])));
        assert_eq!(Hierarchy::from_parents(&[Some(1), Some(0)]), Err(HierarchyError::NoRoot));
        assert_eq!(
            Hierarchy::from_parents(&[None, Some(7)]),
            Err(HierarchyError::ParentOutOfRange { node: 1, parent: 7 })
        );
        let cycle = Hierarchy::from_parents(&[None, Some(0), Some(3), Some(2)]).unwrap_err();
        let HierarchyError::Cycle(mut nodes) = cycle else { panic!("{cycle:?}") };
        nodes.sort();
        assert_eq!(nodes, vec![2, 3]);
        assert!(matches!(Hierarchy::from_parents(&[None, Some(1)]), Err(HierarchyError::Cycle(_))));
    }
}
