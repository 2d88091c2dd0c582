//! Treemap layout: nested rectangles whose areas are proportional to summed leaf values.
//!
//! Each inner node's children tile the node's rectangle, parents before children (a level order
//! walked with a queue, so a 100,000-deep chain needs no recursion; sums go the other way, bit for
//! bit those of `Hierarchy::sum_leaves`). Three tilings:
//!
//! - [`Tiling::Squarified`] — Bruls, Huizing & van Wijk (2000), "Squarified Treemaps". Children
//!   (largest first when [`TreemapOptions::sort`] is set) are laid in rows along the shorter side
//!   of the space still free; a row takes the next child as long as that does not worsen the
//!   row's worst aspect ratio. As in d3-hierarchy, the aspect measured is `t / l` against a
//!   target [`TreemapOptions::ratio`] (`t` the row's thickness, `l` a cell's length along the
//!   row); with ratio 1 this is exactly the paper's algorithm.
//! - [`Tiling::SliceDice`] — Shneiderman (1992), "Tree visualization with tree-maps": children
//!   split the parent side by side, left to right at even depths (the root's children) and top to
//!   bottom at odd depths.
//! - [`Tiling::Strip`] — ordered strip treemap of Bederson, Shneiderman & Wattenberg (2002),
//!   "Ordered and quantum treemaps": children in input order fill full-width horizontal strips
//!   from top to bottom, left to right inside a strip; a strip takes the next child unless that
//!   raises the strip's average aspect ratio (plain aspect `max(w/h, h/w)`; `ratio` is not used).
//!   The average is kept up to date in `O(log k)` per child, so a strip of a million children
//!   stays fast.
//!
//! Padding follows d3's construction: children tile the parent's rectangle inset by `padding / 2`
//! (plus the header band at the top of every inner node but the root), then each child is inset
//! by `padding / 2`, which leaves a gap of `padding` between siblings and between children and
//! their parent's border. A rectangle too small for its inset collapses to an empty one (zero
//! width or height) inside the parent rather than getting a negative size.
//!
//! Weights: negative, NaN and ±inf leaf values count as 0 (counted in [`WeightReport`]). A node
//! with value 0 gets an empty rectangle at the top-left corner of its parent's inner rectangle and
//! is not meant to be drawn; the root always gets the full bounds.

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::fmt;

use super::hierarchy::Hierarchy;

/// The golden ratio, d3-hierarchy's default target aspect ratio for squarified rows.
pub const GOLDEN_RATIO: f64 = 1.618_033_988_749_895;

/// How the children of one node split the node's rectangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tiling {
    /// Rows of near-square cells, Bruls, Huizing & van Wijk (2000).
    #[default]
    Squarified,
    /// Slices alternating between columns (even depths) and rows (odd depths), Shneiderman (1992).
    SliceDice,
    /// Ordered horizontal strips keeping sibling order, Bederson, Shneiderman & Wattenberg (2002).
    Strip,
}

/// An axis-aligned rectangle in pixels, `x0 <= x1` and `y0 <= y1` (y grows downwards).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rect {
    /// Left edge.
    pub x0: f64,
    /// Top edge.
    pub y0: f64,
    /// Right edge.
    pub x1: f64,
    /// Bottom edge.
    pub y1: f64,
}

impl Rect {
    /// A rectangle from its left, top, right and bottom edges.
    pub fn new(x0: f64, y0: f64, x1: f64, y1: f64) -> Self {
        Self { x0, y0, x1, y1 }
    }

    /// `x1 - x0`.
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }

    /// `y1 - y0`.
    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }

    /// `width × height`.
    pub fn area(&self) -> f64 {
        self.width() * self.height()
    }

    /// True when the rectangle has no interior (zero or negative width or height): not drawn.
    pub fn is_empty(&self) -> bool {
        self.width().partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
            || self.height().partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
    }

    /// A zero-size rectangle at a point.
    fn point(x: f64, y: f64) -> Self {
        Self { x0: x, y0: y, x1: x, y1: y }
    }

    /// The rectangle shrunk by the given margins; an axis with no room left collapses to a
    /// point inside the original span.
    fn inset(&self, left: f64, top: f64, right: f64, bottom: f64) -> Self {
        let (x0, x1) = shrink_span(self.x0, self.x1, left, right);
        let (y0, y1) = shrink_span(self.y0, self.y1, top, bottom);
        Self { x0, y0, x1, y1 }
    }
}

/// Shrinks `[lo, hi]` by `a` at the low end and `b` at the high end; when nothing is left, the
/// span collapses to the midpoint of the would-be span, clamped into `[lo, hi]`.
fn shrink_span(lo: f64, hi: f64, a: f64, b: f64) -> (f64, f64) {
    let (s, e) = (lo + a, hi - b);
    if s <= e {
        (s, e)
    } else {
        let mid = (0.5 * (s + e)).max(lo).min(hi);
        (mid, mid)
    }
}

/// Layout settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TreemapOptions {
    /// The tiling used at every inner node.
    pub tiling: Tiling,
    /// Gap in pixels between siblings and between children and their parent's border (≥ 0).
    pub padding: f64,
    /// Height in pixels of a label band at the top of each inner node except the root (≥ 0).
    pub header: f64,
    /// Squarified only: lay children out largest first (ties in input order). Slice-and-dice and
    /// strip always keep input order.
    pub sort: bool,
    /// Squarified only: target aspect ratio of cells (≥ 1; 1 is the paper's square target).
    pub ratio: f64,
}

impl Default for TreemapOptions {
    /// Squarified, no padding or header, sorted, golden-ratio target (d3-hierarchy's defaults).
    fn default() -> Self {
        Self { tiling: Tiling::Squarified, padding: 0.0, header: 0.0, sort: true, ratio: GOLDEN_RATIO }
    }
}

/// How many leaf values were not usable weights; each counts as 0 in the layout.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WeightReport {
    /// Finite leaf values below zero.
    pub negative: usize,
    /// Leaf values that are NaN or ±inf.
    pub nan: usize,
    /// Leaf values exactly zero (these are valid, but their nodes are not drawn).
    pub zero: usize,
}

impl WeightReport {
    /// Leaves treated as 0 because their value was negative, NaN or infinite.
    pub fn invalid(&self) -> usize {
        self.negative + self.nan
    }
}

/// The result of [`layout`].
#[derive(Clone, Debug, PartialEq)]
pub struct Treemap {
    /// One rectangle per node of the hierarchy, indexed by node; empty ones are not drawn.
    pub rects: Vec<Rect>,
    /// Summed value per node (invalid leaf values counted as 0).
    pub values: Vec<f64>,
    /// Counts of unusable leaf values, for a warning.
    pub weights: WeightReport,
}

/// Why a treemap cannot be laid out.
#[derive(Clone, Debug, PartialEq)]
pub enum TreemapError {
    /// `leaf_values` does not have one entry per node.
    LengthMismatch {
        /// Entries given.
        values: usize,
        /// Nodes in the hierarchy.
        nodes: usize,
    },
    /// The bounds have a non-finite edge or no area.
    BadBounds(Rect),
    /// Padding is negative or not finite.
    BadPadding(f64),
    /// Header height is negative or not finite.
    BadHeader(f64),
    /// Target aspect ratio is below 1 or not finite.
    BadRatio(f64),
    /// The leaf values add up to more than an `f64` holds.
    ValueOverflow(f64),
}

impl fmt::Display for TreemapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::LengthMismatch { values, nodes } => {
                write!(f, "got {values} values for {nodes} nodes; give one value per node (inner nodes' are ignored)")
            }
            Self::BadBounds(r) => write!(
                f,
                "treemap bounds ({}, {})–({}, {}) are not a finite rectangle with area; give x0 < x1 and y0 < y1",
                r.x0, r.y0, r.x1, r.y1
            ),
            Self::BadPadding(p) => write!(f, "treemap padding {p} is invalid; use a finite number ≥ 0"),
            Self::BadHeader(h) => write!(f, "treemap header height {h} is invalid; use a finite number ≥ 0"),
            Self::BadRatio(r) => write!(f, "treemap aspect ratio {r} is invalid; use a finite number ≥ 1"),
            Self::ValueOverflow(s) => {
                write!(f, "leaf values add up to {s}; divide them by a common factor so the total is finite")
            }
        }
    }
}

impl std::error::Error for TreemapError {}

/// Lays out `tree` inside `bounds`. `leaf_values` has one entry per node; only leaves' entries
/// are read, and negative, NaN and ±inf ones count as 0. Inner nodes get the sum of their leaves.
pub fn layout(
    tree: &Hierarchy,
    leaf_values: &[f64],
    bounds: Rect,
    options: &TreemapOptions,
) -> Result<Treemap, TreemapError> {
    check_inputs(tree, leaf_values, bounds, options)?;
    let (mut values, weights) = clean_leaf_values(tree, leaf_values);
    let order = top_down_order(tree);
    sum_up(tree, &order, &mut values);
    let total = values.get(tree.root()).copied().unwrap_or(0.0);
    if !total.is_finite() {
        return Err(TreemapError::ValueOverflow(total));
    }
    let rects = tile_tree(tree, &order, &values, bounds, options);
    Ok(Treemap { rects, values, weights })
}

/// Nodes level by level from the root, so every parent comes before its children (no recursion).
fn top_down_order(tree: &Hierarchy) -> Vec<u32> {
    let mut order = Vec::with_capacity(tree.len());
    order.push(tree.root() as u32);
    let mut next = 0;
    while let Some(&node) = order.get(next) {
        order.extend_from_slice(tree.children(node as usize));
        next += 1;
    }
    order
}

/// Adds every node's value into its parent's, children first: the sums of
/// [`Hierarchy::sum_leaves`], bit for bit (each parent adds its children last to first), done in
/// place with the level order already at hand.
fn sum_up(tree: &Hierarchy, order: &[u32], values: &mut [f64]) {
    for &node in order.iter().rev() {
        if let (Some(p), Some(&v)) = (tree.parent(node as usize), values.get(node as usize))
            && let Some(total) = values.get_mut(p)
        {
            *total += v;
        }
    }
}

/// Refuses a length mismatch, unusable bounds and out-of-range options.
fn check_inputs(tree: &Hierarchy, values: &[f64], bounds: Rect, options: &TreemapOptions) -> Result<(), TreemapError> {
    if values.len() != tree.len() {
        return Err(TreemapError::LengthMismatch { values: values.len(), nodes: tree.len() });
    }
    let finite = [bounds.x0, bounds.y0, bounds.x1, bounds.y1].iter().all(|v| v.is_finite());
    if !finite || bounds.is_empty() || !bounds.area().is_finite() {
        return Err(TreemapError::BadBounds(bounds));
    }
    if !(options.padding.is_finite() && options.padding >= 0.0) {
        return Err(TreemapError::BadPadding(options.padding));
    }
    if !(options.header.is_finite() && options.header >= 0.0) {
        return Err(TreemapError::BadHeader(options.header));
    }
    if !(options.ratio.is_finite() && options.ratio >= 1.0) {
        return Err(TreemapError::BadRatio(options.ratio));
    }
    Ok(())
}

/// Leaf weights with negative, NaN and ±inf replaced by 0 (inner entries 0), and the counts.
fn clean_leaf_values(tree: &Hierarchy, values: &[f64]) -> (Vec<f64>, WeightReport) {
    let mut report = WeightReport::default();
    let clean = values
        .iter()
        .enumerate()
        .map(|(node, &v)| {
            if !tree.is_leaf(node) {
                0.0
            } else if !v.is_finite() {
                report.nan += 1;
                0.0
            } else if v < 0.0 {
                report.negative += 1;
                0.0
            } else {
                if v == 0.0 {
                    report.zero += 1;
                }
                // Normalise -0.0 so that sums never carry a negative zero.
                v + 0.0
            }
        })
        .collect();
    (clean, report)
}

/// Reusable buffers for one parent's children: the positive ones in tiling order, sort keys,
/// their values, suffix sums of those values, and the strip's heap.
#[derive(Default)]
struct Scratch {
    ids: Vec<u32>,
    keys: Vec<u128>,
    vals: Vec<f64>,
    suffix: Vec<f64>,
    heap: BinaryHeap<Reverse<u64>>,
}

impl Scratch {
    /// Fills the buffers with the positive-valued children (sorted largest first when asked).
    fn collect(&mut self, kids: &[u32], values: &[f64], sort: bool) {
        self.ids.clear();
        self.ids.extend(kids.iter().copied().filter(|&k| value_of(values, k) > 0.0));
        if sort {
            // Largest value first, ties by node index (input order): one key per child, with the
            // complemented value bits (monotone for positive floats) above the index.
            self.keys.clear();
            self.keys
                .extend(self.ids.iter().map(|&k| (u128::from(!value_of(values, k).to_bits()) << 32) | u128::from(k)));
            self.keys.sort_unstable();
            self.ids.clear();
            self.ids.extend(self.keys.iter().map(|&key| key as u32));
        }
        self.vals.clear();
        self.vals.extend(self.ids.iter().map(|&k| value_of(values, k)));
        self.suffix.clear();
        self.suffix.resize(self.vals.len() + 1, 0.0);
        for i in (0..self.vals.len()).rev() {
            self.suffix[i] = self.suffix[i + 1] + self.vals[i];
        }
    }
}

/// The summed value of node `k` (0 for an index out of range, which a hierarchy never yields).
fn value_of(values: &[f64], k: u32) -> f64 {
    values.get(k as usize).copied().unwrap_or(0.0)
}

/// Places every node, parents before children.
fn tile_tree(tree: &Hierarchy, order: &[u32], values: &[f64], bounds: Rect, options: &TreemapOptions) -> Vec<Rect> {
    let mut rects = vec![Rect::default(); tree.len()];
    let root = tree.root();
    rects[root] = bounds;
    let depths = if options.tiling == Tiling::SliceDice { tree.depths() } else { Vec::new() };
    let half = 0.5 * options.padding;
    let sort = options.sort && options.tiling == Tiling::Squarified;
    let mut scratch = Scratch::default();
    for &node in order {
        let node = node as usize;
        let kids = tree.children(node);
        if kids.is_empty() {
            continue;
        }
        let parent = rects[node];
        let header = if node == root { 0.0 } else { options.header };
        let inner = parent.inset(options.padding, options.padding + header, options.padding, options.padding);
        for &k in kids {
            rects[k as usize] = Rect::point(inner.x0, inner.y0);
        }
        scratch.collect(kids, values, sort);
        if scratch.ids.is_empty() {
            continue;
        }
        let region = parent.inset(half, half + header, half, half);
        if region.is_empty() {
            for &k in &scratch.ids {
                rects[k as usize] = inner;
            }
            continue;
        }
        match options.tiling {
            Tiling::Squarified => squarify(&scratch, region, options.ratio, &mut rects),
            Tiling::SliceDice => {
                let along_x = depths.get(node).is_none_or(|d| d % 2 == 0);
                slice_dice(&scratch, region, along_x, &mut rects);
            }
            Tiling::Strip => strip(&mut scratch, region, &mut rects),
        }
        if half > 0.0 {
            for &k in &scratch.ids {
                let r = &mut rects[k as usize];
                *r = r.inset(half, half, half, half);
            }
        }
    }
    rects
}

/// Lays `ids` side by side across `span = (x0, x1)`, each spanning `band = (y0, y1)`, widths
/// proportional to `vals` (`sum` is their sum, accumulated in the same order); the last one ends
/// exactly at `x1`.
fn place_along_x(ids: &[u32], vals: &[f64], sum: f64, span: (f64, f64), band: (f64, f64), out: &mut [Rect]) {
    let (x0, x1) = span;
    let width = x1 - x0;
    let mut cum = 0.0;
    let mut left = x0;
    let last = ids.len().saturating_sub(1);
    for (i, (&id, &v)) in ids.iter().zip(vals).enumerate() {
        cum += v;
        let right = if i == last { x1 } else { (x0 + width * (cum / sum)).min(x1) };
        if let Some(r) = out.get_mut(id as usize) {
            *r = Rect::new(left, band.0, right, band.1);
        }
        left = right;
    }
}

/// Lays `ids` stacked down `span = (y0, y1)`, each spanning `band = (x0, x1)`, heights
/// proportional to `vals`; the last one ends exactly at `y1`.
fn place_along_y(ids: &[u32], vals: &[f64], sum: f64, span: (f64, f64), band: (f64, f64), out: &mut [Rect]) {
    let (y0, y1) = span;
    let height = y1 - y0;
    let mut cum = 0.0;
    let mut top = y0;
    let last = ids.len().saturating_sub(1);
    for (i, (&id, &v)) in ids.iter().zip(vals).enumerate() {
        cum += v;
        let bottom = if i == last { y1 } else { (y0 + height * (cum / sum)).min(y1) };
        if let Some(r) = out.get_mut(id as usize) {
            *r = Rect::new(band.0, top, band.1, bottom);
        }
        top = bottom;
    }
}

/// Slice-and-dice: all children in one run across the region.
fn slice_dice(s: &Scratch, region: Rect, along_x: bool, out: &mut [Rect]) {
    let total = s.vals.iter().sum();
    if along_x {
        place_along_x(&s.ids, &s.vals, total, (region.x0, region.x1), (region.y0, region.y1), out);
    } else {
        place_along_y(&s.ids, &s.vals, total, (region.y0, region.y1), (region.x0, region.x1), out);
    }
}

/// Squarified rows: each row along the shorter side of the free space, cut off when the next
/// child would worsen the row's worst aspect ratio.
fn squarify(s: &Scratch, region: Rect, ratio: f64, out: &mut [Rect]) {
    let n = s.ids.len();
    let mut free = region;
    let mut start = 0;
    while start < n {
        let remaining = s.suffix[start];
        let (end, row_sum) = squarify_row(&s.vals, start, remaining, free, ratio);
        let fraction = row_sum / remaining;
        let ids = &s.ids[start..end];
        let vals = &s.vals[start..end];
        if free.width() >= free.height() {
            // Short side vertical: the row is a column at the left.
            let edge = if end == n { free.x1 } else { (free.x0 + free.width() * fraction).min(free.x1) };
            place_along_y(ids, vals, row_sum, (free.y0, free.y1), (free.x0, edge), out);
            free.x0 = edge;
        } else {
            let edge = if end == n { free.y1 } else { (free.y0 + free.height() * fraction).min(free.y1) };
            place_along_x(ids, vals, row_sum, (free.x0, free.x1), (free.y0, edge), out);
            free.y0 = edge;
        }
        start = end;
    }
}

/// The end of the row starting at `start` and the row's value sum. `remaining` is the value of
/// everything from `start` on, which fills `free`.
fn squarify_row(vals: &[f64], start: usize, remaining: f64, free: Rect, ratio: f64) -> (usize, f64) {
    let short = free.width().min(free.height());
    let long = free.width().max(free.height());
    if short.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return (vals.len(), vals[start..].iter().sum());
    }
    let elongation = long / short;
    // A cell of value v in a row of sum s has thickness/length r = elongation·(s/R)·(s/v);
    // the row's worst is max(r(vmin)/ratio, ratio/r(vmax)).
    let worst = |sum: f64, lo: f64, hi: f64| {
        let base = elongation * (sum / remaining);
        ((base * (sum / lo)) / ratio).max(ratio / (base * (sum / hi)))
    };
    let first = vals[start];
    let (mut sum, mut lo, mut hi) = (first, first, first);
    let mut best = worst(sum, lo, hi);
    let mut end = start + 1;
    while let Some(&v) = vals.get(end) {
        let (s2, lo2, hi2) = (sum + v, lo.min(v), hi.max(v));
        let candidate = worst(s2, lo2, hi2);
        if candidate > best {
            break;
        }
        (sum, lo, hi, best) = (s2, lo2, hi2, candidate);
        end += 1;
    }
    (end, sum)
}

/// Ordered strips: full-width horizontal strips from the top, children left to right.
fn strip(s: &mut Scratch, region: Rect, out: &mut [Rect]) {
    let n = s.ids.len();
    let mut top = region.y0;
    let mut start = 0;
    while start < n {
        let remaining = s.suffix[start];
        let height = region.y1 - top;
        let (end, sum) = strip_run(&s.vals, start, remaining, region.width(), height, &mut s.heap);
        let bottom = if end == n { region.y1 } else { (top + height * (sum / remaining)).min(region.y1) };
        place_along_x(&s.ids[start..end], &s.vals[start..end], sum, (region.x0, region.x1), (top, bottom), out);
        top = bottom;
        start = end;
    }
}

/// The end of the strip starting at `start` and its value sum: children join while the strip's
/// average aspect ratio does not rise. Cell `i` has aspect `max(c·v_i, 1/(c·v_i))` with
/// `c = (width/height)·(R/s)/s`; `c` only falls as the strip grows, so cells only move from
/// "wide" (`c·v ≥ 1`, kept in a min-heap by value) to "tall", and the average is
/// `(c·Σwide v + Σtall 1/v / c) / k`.
fn strip_run(
    vals: &[f64],
    start: usize,
    remaining: f64,
    width: f64,
    height: f64,
    heap: &mut BinaryHeap<Reverse<u64>>,
) -> (usize, f64) {
    if !(width > 0.0 && height > 0.0) {
        return (vals.len(), vals[start..].iter().sum());
    }
    heap.clear();
    let shape = width / height;
    let (mut wide_sum, mut tall_inv_sum) = (0.0, 0.0);
    let mut sum = 0.0;
    let mut best = f64::INFINITY;
    let mut end = start;
    while let Some(&v) = vals.get(end) {
        let s2 = sum + v;
        let c = shape * (remaining / s2) / s2;
        heap.push(Reverse(v.to_bits()));
        wide_sum += v;
        while let Some(&Reverse(bits)) = heap.peek() {
            let w = f64::from_bits(bits);
            if c * w >= 1.0 {
                break;
            }
            heap.pop();
            wide_sum -= w;
            tall_inv_sum += 1.0 / w;
        }
        if heap.is_empty() {
            wide_sum = 0.0;
        }
        let count = (end - start + 1) as f64;
        let average = (c * wide_sum + tall_inv_sum / c) / count;
        if end > start && average > best {
            break;
        }
        best = average;
        sum = s2;
        end += 1;
    }
    (end, sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    const EPS: f64 = 1e-9;

    fn opts(tiling: Tiling) -> TreemapOptions {
        TreemapOptions { tiling, ..TreemapOptions::default() }
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= EPS * a.abs().max(b.abs()).max(1.0)
    }

    fn assert_rect(r: Rect, e: [f64; 4]) {
        assert!(close(r.x0, e[0]) && close(r.y0, e[1]) && close(r.x1, e[2]) && close(r.y1, e[3]), "{r:?} != {e:?}");
    }

    /// Root 0 with children 1..=k; leaves get `values`.
    fn flat(values: &[f64]) -> (Hierarchy, Vec<f64>) {
        let mut parents = vec![None];
        parents.extend(values.iter().map(|_| Some(0)));
        let mut v = vec![0.0];
        v.extend_from_slice(values);
        (Hierarchy::from_parents(&parents).unwrap(), v)
    }

    fn xorshift(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A random 4-level tree (root, 2–6 children per inner node), values in (0.5, 10.5).
    fn random_tree(seed: u64) -> (Hierarchy, Vec<f64>) {
        let mut rng = xorshift(seed);
        let mut parents = vec![None];
        let mut level = vec![0usize];
        for _ in 0..3 {
            let mut next = Vec::new();
            for &p in &level {
                for _ in 0..2 + (rng() * 5.0) as usize {
                    next.push(parents.len());
                    parents.push(Some(p));
                }
            }
            level = next;
        }
        let values = (0..parents.len()).map(|_| 0.5 + 10.0 * rng()).collect();
        (Hierarchy::from_parents(&parents).unwrap(), values)
    }

    fn interior_overlap(a: Rect, b: Rect) -> f64 {
        let w = a.x1.min(b.x1) - a.x0.max(b.x0);
        let h = a.y1.min(b.y1) - a.y0.max(b.y0);
        if w > 0.0 && h > 0.0 { w * h } else { 0.0 }
    }

    fn inside(r: Rect, outer: Rect) -> bool {
        r.x0 >= outer.x0 - EPS && r.y0 >= outer.y0 - EPS && r.x1 <= outer.x1 + EPS && r.y1 <= outer.y1 + EPS
    }

    const ALL: [Tiling; 3] = [Tiling::Squarified, Tiling::SliceDice, Tiling::Strip];

    #[test]
    fn squarified_reproduces_the_bruls_paper_example() {
        // Values 6,6,4,3,2,2,1 in a 6×4 rectangle: rows {6,6} (a column at the left), {4,3}
        // (a row on top of the remaining 3×4), then {2}, {2}, {1} as columns of the 3×5/3 rest.
        let (tree, values) = flat(&[6.0, 6.0, 4.0, 3.0, 2.0, 2.0, 1.0]);
        let options = TreemapOptions { ratio: 1.0, ..opts(Tiling::Squarified) };
        let map = layout(&tree, &values, Rect::new(0.0, 0.0, 6.0, 4.0), &options).unwrap();
        let r = &map.rects;
        assert_rect(r[1], [0.0, 0.0, 3.0, 2.0]);
        assert_rect(r[2], [0.0, 2.0, 3.0, 4.0]);
        assert_rect(r[3], [3.0, 0.0, 3.0 + 12.0 / 7.0, 7.0 / 3.0]);
        assert_rect(r[4], [3.0 + 12.0 / 7.0, 0.0, 6.0, 7.0 / 3.0]);
        assert_rect(r[5], [3.0, 7.0 / 3.0, 4.2, 4.0]);
        assert_rect(r[6], [4.2, 7.0 / 3.0, 5.4, 4.0]);
        assert_rect(r[7], [5.4, 7.0 / 3.0, 6.0, 4.0]);
        // The aspect ratios of the paper's final layout.
        let aspect = |r: Rect| (r.width() / r.height()).max(r.height() / r.width());
        let expected = [1.5, 1.5, 49.0 / 36.0, 49.0 / 27.0, 25.0 / 18.0, 25.0 / 18.0, 25.0 / 9.0];
        for (node, want) in (1..=7).zip(expected) {
            assert!(close(aspect(r[node]), want), "node {node}: {} vs {want}", aspect(r[node]));
        }
    }

    #[test]
    fn areas_are_conserved_and_proportional_for_every_tiling() {
        for tiling in ALL {
            for seed in 1..6 {
                let (tree, values) = random_tree(seed);
                let bounds = Rect::new(10.0, 20.0, 810.0, 620.0);
                let map = layout(&tree, &values, bounds, &opts(tiling)).unwrap();
                assert_eq!(map.values, tree.sum_leaves(&values), "sums as Hierarchy::sum_leaves, bit for bit");
                let density = bounds.area() / map.values[tree.root()];
                for node in 0..tree.len() {
                    let area = map.rects[node].area();
                    assert!(close(area / map.values[node], density), "{tiling:?} node {node}");
                    let kids = tree.children(node);
                    if !kids.is_empty() {
                        let sum: f64 = kids.iter().map(|&k| map.rects[k as usize].area()).sum();
                        assert!((sum - area).abs() <= EPS * area, "{tiling:?} node {node}: {sum} vs {area}");
                    }
                }
            }
        }
    }

    #[test]
    fn siblings_never_overlap_and_stay_inside_the_padded_parent() {
        for tiling in ALL {
            for (padding, header) in [(0.0, 0.0), (2.0, 0.0), (1.5, 12.0)] {
                let (tree, values) = random_tree(7);
                let options = TreemapOptions { padding, header, ..opts(tiling) };
                let map = layout(&tree, &values, Rect::new(0.0, 0.0, 1000.0, 700.0), &options).unwrap();
                for node in 0..tree.len() {
                    let kids = tree.children(node);
                    let band = if node == tree.root() { 0.0 } else { header };
                    let inner = map.rects[node].inset(padding, padding + band, padding, padding);
                    for (i, &a) in kids.iter().enumerate() {
                        let ra = map.rects[a as usize];
                        assert!(ra.x0 <= ra.x1 && ra.y0 <= ra.y1, "{ra:?}");
                        assert!(inside(ra, inner), "{tiling:?} {ra:?} outside {inner:?}");
                        for &b in &kids[i + 1..] {
                            let rb = map.rects[b as usize];
                            assert!(interior_overlap(ra, rb) <= EPS, "{tiling:?} {ra:?} overlaps {rb:?}");
                            if !ra.is_empty() && !rb.is_empty() {
                                let gap_x = (rb.x0 - ra.x1).max(ra.x0 - rb.x1);
                                let gap_y = (rb.y0 - ra.y1).max(ra.y0 - rb.y1);
                                assert!(gap_x.max(gap_y) >= padding - EPS, "{tiling:?} gap {gap_x} {gap_y}");
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn slice_dice_alternates_columns_and_rows_by_depth() {
        // Root → 2 children → 2 grandchildren each.
        let tree = Hierarchy::from_parents(&[None, Some(0), Some(0), Some(1), Some(1), Some(2), Some(2)]).unwrap();
        let values = [0.0, 0.0, 0.0, 1.0, 3.0, 2.0, 2.0];
        let map = layout(&tree, &values, Rect::new(0.0, 0.0, 8.0, 4.0), &opts(Tiling::SliceDice)).unwrap();
        let r = &map.rects;
        // Depth 0 splits along x (columns of widths 4 and 4).
        assert_rect(r[1], [0.0, 0.0, 4.0, 4.0]);
        assert_rect(r[2], [4.0, 0.0, 8.0, 4.0]);
        // Depth 1 splits along y (rows), in input order.
        assert_rect(r[3], [0.0, 0.0, 4.0, 1.0]);
        assert_rect(r[4], [0.0, 1.0, 4.0, 4.0]);
        assert_rect(r[5], [4.0, 0.0, 8.0, 2.0]);
        assert_rect(r[6], [4.0, 2.0, 8.0, 4.0]);
    }

    #[test]
    fn strip_keeps_sibling_order_in_reading_order() {
        // Four equal cells in a square: two strips of two (a 2×2 grid), in input order.
        let (tree, values) = flat(&[1.0, 1.0, 1.0, 1.0]);
        let map = layout(&tree, &values, Rect::new(0.0, 0.0, 2.0, 2.0), &opts(Tiling::Strip)).unwrap();
        assert_rect(map.rects[1], [0.0, 0.0, 1.0, 1.0]);
        assert_rect(map.rects[2], [1.0, 0.0, 2.0, 1.0]);
        assert_rect(map.rects[3], [0.0, 1.0, 1.0, 2.0]);
        assert_rect(map.rects[4], [1.0, 1.0, 2.0, 2.0]);
        // Random values: each later sibling is to the right in the same strip or in a lower strip,
        // and every strip spans the full width.
        let mut rng = xorshift(11);
        let vals: Vec<f64> = (0..200).map(|_| 1.0 + 9.0 * rng()).collect();
        let (tree, values) = flat(&vals);
        let map = layout(&tree, &values, Rect::new(0.0, 0.0, 900.0, 500.0), &opts(Tiling::Strip)).unwrap();
        let cells = &map.rects[1..];
        let mut strips = 1;
        for pair in cells.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            if a.y0 == b.y0 {
                assert!(a.y1 == b.y1 && a.x1 == b.x0, "{a:?} then {b:?}");
            } else {
                assert!(a.x1 == 900.0 && b.x0 == 0.0 && b.y0 == a.y1, "{a:?} then {b:?}");
                strips += 1;
            }
        }
        assert!(strips > 5 && strips < 40, "{strips} strips");
    }

    #[test]
    fn a_single_child_fills_its_parent_or_its_padded_inside() {
        let tree = Hierarchy::from_parents(&[None, Some(0), Some(1)]).unwrap();
        let bounds = Rect::new(0.0, 0.0, 100.0, 50.0);
        for tiling in ALL {
            let map = layout(&tree, &[0.0, 0.0, 3.0], bounds, &opts(tiling)).unwrap();
            assert!(map.rects.iter().all(|&r| r == bounds), "{tiling:?}");
            let padded = TreemapOptions { padding: 4.0, header: 10.0, ..opts(tiling) };
            let map = layout(&tree, &[0.0, 0.0, 3.0], bounds, &padded).unwrap();
            assert_eq!(map.rects[1], Rect::new(4.0, 4.0, 96.0, 46.0), "root has no header");
            assert_eq!(map.rects[2], Rect::new(8.0, 18.0, 92.0, 42.0));
        }
    }

    #[test]
    fn unusable_weights_count_as_zero_and_are_left_empty_at_the_corner() {
        // Root → a (leaves 1: 2.0, 2: −1, 3: NaN), b (leaves: 0, +inf), c (leaf 4.0).
        let parents = [None, Some(0), Some(0), Some(1), Some(1), Some(1), Some(2), Some(2), Some(0)];
        let tree = Hierarchy::from_parents(&parents).unwrap();
        let values = [9.0, 9.0, 9.0, 2.0, -1.0, f64::NAN, 0.0, f64::INFINITY, 4.0];
        for tiling in ALL {
            let options = TreemapOptions { padding: 1.0, ..opts(tiling) };
            let map = layout(&tree, &values, Rect::new(0.0, 0.0, 60.0, 60.0), &options).unwrap();
            assert_eq!(map.weights, WeightReport { negative: 1, nan: 2, zero: 1 });
            assert_eq!(map.weights.invalid(), 3);
            assert_eq!(map.values, vec![6.0, 2.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 4.0]);
            let inner_a = map.rects[1].inset(1.0, 1.0, 1.0, 1.0);
            for node in [4, 5] {
                assert_eq!(map.rects[node], Rect::point(inner_a.x0, inner_a.y0), "{tiling:?}");
            }
            // b (all-zero children) is itself zero: empty at the root's inner corner, as are its children.
            assert_eq!(map.rects[2], Rect::point(1.0, 1.0));
            assert!(map.rects[6].is_empty() && map.rects[7].is_empty());
            assert!(inside(map.rects[6], map.rects[2]) && inside(map.rects[7], map.rects[2]));
        }
        // A root whose leaves are all zero keeps the bounds; its children are empty.
        let (tree, values) = flat(&[0.0, -2.0, f64::NEG_INFINITY]);
        let bounds = Rect::new(0.0, 0.0, 10.0, 10.0);
        let map = layout(&tree, &values, bounds, &TreemapOptions::default()).unwrap();
        assert_eq!(map.rects[0], bounds);
        assert!(map.rects[1..].iter().all(|r| *r == Rect::point(0.0, 0.0)));
    }

    #[test]
    fn padding_and_header_without_room_give_empty_rects_inside_the_parent() {
        let tree = Hierarchy::from_parents(&[None, Some(0), Some(1), Some(1), Some(2)]).unwrap();
        let values = [0.0, 0.0, 0.0, 1.0, 1.0];
        for tiling in ALL {
            let options = TreemapOptions { padding: 3.0, header: 30.0, ..opts(tiling) };
            let bounds = Rect::new(0.0, 0.0, 40.0, 40.0);
            let map = layout(&tree, &values, bounds, &options).unwrap();
            assert_eq!(map.rects[1], Rect::new(3.0, 3.0, 37.0, 37.0));
            // Node 1's header leaves 1 px of height for its children, less than their padding needs.
            for node in [2, 3, 4] {
                let r = map.rects[node];
                assert!(r.is_empty() && r.x0 <= r.x1 && r.y0 <= r.y1, "{tiling:?} {r:?}");
                assert!(inside(r, map.rects[1]), "{tiling:?} {r:?}");
            }
        }
    }

    #[test]
    fn a_chain_of_100000_nodes_is_laid_out_without_recursion() {
        let n: usize = 100_000;
        let parents: Vec<Option<usize>> = (0..n).map(|i| i.checked_sub(1)).collect();
        let tree = Hierarchy::from_parents(&parents).unwrap();
        let mut values = vec![0.0; n];
        values[n - 1] = 5.0;
        let bounds = Rect::new(0.0, 0.0, 300.0, 200.0);
        let map = layout(&tree, &values, bounds, &TreemapOptions::default()).unwrap();
        assert!(map.rects.iter().all(|&r| r == bounds));
        assert!(map.values.iter().all(|&v| v == 5.0));
        let padded = TreemapOptions { padding: 1.0, ..TreemapOptions::default() };
        let map = layout(&tree, &values, bounds, &padded).unwrap();
        assert_eq!(map.rects[10], Rect::new(10.0, 10.0, 290.0, 190.0));
        assert!(map.rects[n - 1].is_empty() && inside(map.rects[n - 1], bounds));
    }

    #[test]
    fn a_strip_of_200000_siblings_in_a_wide_box_stays_fast_and_exact() {
        // Equal cells in a 1e6 × 1 box make one long strip: quadratic strip growth would hang.
        let (tree, values) = flat(&vec![1.0; 200_000]);
        let map = layout(&tree, &values, Rect::new(0.0, 0.0, 1e6, 1.0), &opts(Tiling::Strip)).unwrap();
        let cells = &map.rects[1..];
        assert!(cells.iter().all(|r| close(r.area(), 5.0)));
        assert!(cells.windows(2).all(|p| p[0].x1 == p[1].x0 || p[1].x0 == 0.0));
    }

    #[test]
    fn unsorted_squarify_keeps_input_order_and_sorting_is_deterministic() {
        let (tree, values) = flat(&[1.0, 2.0, 2.0, 3.0, 4.0, 6.0, 6.0]);
        let bounds = Rect::new(0.0, 0.0, 6.0, 4.0);
        let unsorted = TreemapOptions { sort: false, ratio: 1.0, ..opts(Tiling::Squarified) };
        let map = layout(&tree, &values, bounds, &unsorted).unwrap();
        // The first child (value 1) starts the first row, at the top-left corner.
        assert_eq!((map.rects[1].x0, map.rects[1].y0), (0.0, 0.0));
        // Sorted, the reversed input gives the paper's layout (6s in the left column).
        let sorted = TreemapOptions { ratio: 1.0, ..opts(Tiling::Squarified) };
        let map = layout(&tree, &values, bounds, &sorted).unwrap();
        assert_rect(map.rects[6], [0.0, 0.0, 3.0, 2.0]);
        assert_rect(map.rects[7], [0.0, 2.0, 3.0, 4.0]);
        // Same input, same bits.
        let (tree, values) = random_tree(3);
        let a = layout(&tree, &values, bounds, &TreemapOptions::default()).unwrap();
        let b = layout(&tree, &values, bounds, &TreemapOptions::default()).unwrap();
        let bits =
            |m: &Treemap| m.rects.iter().flat_map(|r| [r.x0, r.y0, r.x1, r.y1].map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
    }

    #[test]
    fn bad_inputs_are_refused_with_the_value_and_the_fix() {
        let (tree, values) = flat(&[1.0, 2.0]);
        let ok = Rect::new(0.0, 0.0, 10.0, 10.0);
        let run = |v: &[f64], b: Rect, o: TreemapOptions| layout(&tree, v, b, &o).unwrap_err();
        let d = TreemapOptions::default();
        assert_eq!(run(&values[..2], ok, d), TreemapError::LengthMismatch { values: 2, nodes: 3 });
        for bad in [Rect::new(0.0, 0.0, f64::NAN, 1.0), Rect::new(0.0, 0.0, 0.0, 5.0), Rect::new(5.0, 0.0, 1.0, 5.0)] {
            let TreemapError::BadBounds(got) = run(&values, bad, d) else { panic!("{bad:?} accepted") };
            assert_eq!(format!("{got:?}"), format!("{bad:?}"));
        }
        let inf = Rect::new(f64::NEG_INFINITY, 0.0, 1.0, 1.0);
        assert_eq!(run(&values, inf, d), TreemapError::BadBounds(inf));
        assert_eq!(run(&values, ok, TreemapOptions { padding: -1.0, ..d }), TreemapError::BadPadding(-1.0));
        assert_eq!(
            run(&values, ok, TreemapOptions { header: f64::INFINITY, ..d }),
            TreemapError::BadHeader(f64::INFINITY)
        );
        assert_eq!(run(&values, ok, TreemapOptions { ratio: 0.5, ..d }), TreemapError::BadRatio(0.5));
        let err = run(&[0.0, 1e308, 1e308], ok, d);
        assert_eq!(err, TreemapError::ValueOverflow(f64::INFINITY));
        assert!(err.to_string().contains("divide them"));
        let msg = run(&values, ok, TreemapOptions { ratio: 0.5, ..d }).to_string();
        assert!(msg.contains("0.5") && msg.contains("≥ 1"), "{msg}");
        let msg = run(&values, Rect::new(5.0, 0.0, 1.0, 5.0), d).to_string();
        assert!(msg.contains("(5, 0)") && msg.contains("x0 < x1"), "{msg}");
    }
}
