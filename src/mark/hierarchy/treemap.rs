//! `treemap`: a hierarchy as nested rectangles whose areas are proportional to the sums of the
//! leaves' values (squarified, slice-and-dice or ordered strips), with a header band naming
//! each inner node and labels that shrink, truncate or hide to fit their rectangle.

use crate::data::Table;
use crate::data::tree::Tree;
use crate::guide::axis::title_with_unit;
use crate::guide::color::{self, darken, lighten, text_color_on};
use crate::guide::format::format_value;
use crate::guide::layout::LayoutError;
use crate::guide::legend::{Legend, Symbol, truncate_to_width};
use crate::layout::treemap::{self as tiling, Rect as Cell, TreemapOptions as TilingOptions};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::tree_input::{Branches, branch_legend, branch_palette, labels_of, node_rows, tree_of};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, encode, frame, with_default_size};
use crate::scene::{Anchor, Baseline, Color, Item, Point, Rect, Role, Shape, Style, Text};
use crate::spec::{Chart, ColorChannel, TreeSource, defaults};
use crate::text::measure;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "treemap"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct TreemapOptions {
    /// The tree's columns: `{ id = "id", parent = "parent" }` or `{ path = "path" }`.
    pub tree: TreeSource,
    /// Numeric column of leaf sizes (default: every leaf counts 1). Inner nodes are the sum of
    /// their leaves; negative and missing values count as 0, with a warning.
    #[serde(default)]
    #[schemars(example = &"size")]
    pub value: Option<String>,
    /// Unit of `value`, shown in labels and the caption.
    #[serde(default)]
    pub unit: Option<String>,
    /// Column of node labels (default: the id, or the last path segment).
    #[serde(default)]
    pub label: Option<String>,
    /// Colour leaves by a column (text: categories; numbers: a colour map).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Without `color`: `branch` (default: one hue per top-level branch), `depth`, or `value`
    /// (a colour map of each leaf's value).
    #[serde(default)]
    pub color_by: Option<TreemapColor>,
    /// Colour scheme: categorical for `branch`, continuous for `depth` and `value`.
    #[serde(default)]
    pub scheme: Option<String>,
    /// `squarified` (default; Bruls et al.), `slice-dice` (alternating by depth) or `strip`
    /// (ordered rows keeping the data order).
    #[serde(default)]
    pub tiling: Option<Tiling>,
    /// Gap in pixels between siblings and inside each parent's border (default 2).
    #[serde(default)]
    #[schemars(range(min = 0, max = 50))]
    pub padding: Option<f64>,
    /// Draw a header band with its name over each inner node (default true).
    #[serde(default)]
    pub headers: Option<bool>,
    /// Deepest level drawn below the root (default: all); deeper nodes fold into their
    /// ancestor at that level.
    #[serde(default)]
    #[schemars(range(min = 1, max = 64))]
    pub depth: Option<u32>,
}

/// What colours a treemap without a `color` column.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum TreemapColor {
    /// One hue per child of the root; everything below it shares that hue.
    Branch,
    /// A colour map of each node's depth.
    Depth,
    /// A colour map of each leaf's value.
    Value,
}

/// How a treemap splits a rectangle among children.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Tiling {
    /// Rows of near-square rectangles, largest first (Bruls, Huizing & van Wijk 2000).
    Squarified,
    /// Slices across, alternating horizontal and vertical by depth (Shneiderman 1992).
    SliceDice,
    /// Ordered strips that keep the data order (Bederson, Shneiderman & Wattenberg 2002).
    Strip,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [820.0, 560.0];
/// Average area in px² a drawn cell should have at least when the depth is chosen automatically.
const MIN_CELL_AREA: f64 = 120.0;
/// Smallest font a label may shrink to before it is truncated or hidden.
const MIN_LABEL_SIZE: f64 = crate::guide::theme::MIN_TEXT_SIZE;

/// Draw a treemap.
pub fn draw(chart: &Chart, options: &TreemapOptions, table: &Table) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let tree = tree_of(chart, &options.tree, table)?;
    let labels = labels_of(chart, &tree, options.label.as_deref(), table)?;
    let mut warnings = Vec::new();
    let leaf_values = leaf_values(chart, options, &tree, table, &mut warnings)?;
    let h = &tree.hierarchy;
    let depths = h.depths();
    let limit = match options.depth {
        Some(d) => d,
        None => {
            let [w, hgt] = chart.size.unwrap_or(DEFAULT_SIZE);
            let limit = auto_depth(h, &depths, w * hgt * 0.7 / MIN_CELL_AREA);
            let deepest = depths.iter().max().copied().unwrap_or(0);
            if limit < deepest {
                warnings.push(Warning::from(format!(
                    "{deepest} levels are too many to show in this size; the top {limit} are drawn \
                     (set `depth` to choose)"
                )));
            }
            limit
        }
    };
    let shown_leaf = |node: usize| h.is_leaf(node) || depths[node] == limit;

    let fill = Fill::new(chart, options, table, (&tree, &labels), (&depths, limit))?;
    let value_title = options.value.as_deref().map(|v| title_with_unit(v, options.unit.as_deref()));
    let mut chart = chart.clone();
    let leaves = (0..h.len()).filter(|&n| h.is_leaf(n)).count();
    let levels = depths.iter().max().copied().unwrap_or(0);
    chart.caption.get_or_insert_with(|| {
        let area = value_title.clone().unwrap_or_else(|| "the number of leaves".into());
        format!("Area proportional to {area}; {leaves} leaves in {levels} levels.")
    });
    let chart = &chart;
    let canvas = frame::PanelCanvas::new(chart, fill.legend.clone().into_iter().collect());
    let theme = &canvas.theme;
    let m = theme.margin;
    let bounds = Cell::new(m, canvas.top(), canvas.width - m - canvas.legend_room(), canvas.top() + canvas.room);
    if bounds.width() < 60.0 || bounds.height() < 60.0 {
        let error = LayoutError::TooSmall { plot_width: bounds.width(), plot_height: bounds.height() };
        return Err(MarkError::layout(error));
    }
    let header = if options.headers.unwrap_or(true) { (theme.label_size * 1.45).round() } else { 0.0 };
    let tiling_options = TilingOptions {
        tiling: match options.tiling.unwrap_or(Tiling::Squarified) {
            Tiling::Squarified => tiling::Tiling::Squarified,
            Tiling::SliceDice => tiling::Tiling::SliceDice,
            Tiling::Strip => tiling::Tiling::Strip,
        },
        padding: options.padding.unwrap_or(2.0),
        header,
        ..TilingOptions::default()
    };
    let map = tiling::layout(h, &leaf_values, bounds, &tiling_options)
        .map_err(|e| MarkError::at(&["padding"], format!("{e}"), ""))?;
    if map.weights.invalid() > 0 {
        warnings.push(Warning::from(format!(
            "{} leaves have negative or missing values; they count as 0 and are not drawn",
            map.weights.invalid()
        )));
    }
    if map.values[h.root()] <= 0.0 {
        return Err(MarkError::at(
            &["value"],
            format!("the leaves' values add up to 0, so there is nothing to draw"),
            "check the `value` column: sizes must be positive numbers",
        ));
    }

    let mut items = vec![canvas.background()];
    let mut texts = Vec::new();
    for node in h.preorder() {
        let node = node as usize;
        let depth = depths[node];
        let cell = map.rects[node];
        if depth > limit || cell.is_empty() || (depth == 0 && !h.is_leaf(node)) {
            continue;
        }
        let rect = Rect::new(cell.x0, cell.y0, cell.width(), cell.height());
        let row: Vec<u32> = tree.rows[node].into_iter().collect();
        let value = map.values[node];
        if shown_leaf(node) {
            let color = fill.leaf(node, value, depth);
            items.push(Item::new(Role::DataMark, Shape::Rect(rect), Style::fill(color)).with_rows(row));
            texts.extend(leaf_label(&labels[node], value, options.unit.as_deref(), cell, color, theme.label_size));
        } else {
            let color = fill.inner(node, depth);
            items.push(Item::new(Role::DataMark, Shape::Rect(rect), Style::fill(color)).with_rows(row));
            if header > 0.0 {
                let value = with_unit(value, options.unit.as_deref());
                texts.extend(header_label(&labels[node], &value, cell, header, color, theme.label_size));
            }
        }
    }
    items.extend(texts);

    let derived = derived(&tree, &labels, &map, &depths, limit);
    let scene = canvas.scene(chart, items, None);
    Ok(ChartOutput {
        scene,
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// The deepest level to draw so that at most `max_cells` cells are drawn: the leaves above that
/// level plus the nodes at it (always at least one level).
fn auto_depth(h: &crate::layout::hierarchy::Hierarchy, depths: &[u32], max_cells: f64) -> u32 {
    let deepest = depths.iter().max().copied().unwrap_or(0) as usize;
    let mut at_depth = vec![0usize; deepest + 1];
    let mut leaves_at = vec![0usize; deepest + 1];
    for (n, &d) in depths.iter().enumerate() {
        at_depth[d as usize] += 1;
        if h.is_leaf(n) {
            leaves_at[d as usize] += 1;
        }
    }
    let mut leaves_above = 0;
    let mut limit = 1;
    for d in 1..=deepest {
        if d > 1 && (leaves_above + at_depth[d]) as f64 > max_cells {
            break;
        }
        limit = d as u32;
        leaves_above += leaves_at[d];
    }
    limit
}

/// Leaf sizes: the value column (or 1 per leaf), with a warning when inner nodes carry values
/// that the leaf sums override.
fn leaf_values(
    chart: &Chart,
    options: &TreemapOptions,
    tree: &Tree,
    table: &Table,
    warnings: &mut Vec<Warning>,
) -> Result<Vec<f64>, MarkError> {
    let h = &tree.hierarchy;
    let Some(field) = options.value.as_deref() else { return Ok(vec![1.0; h.len()]) };
    let column = encode::column(chart, "value", field, table)?;
    encode::require_numeric("value", column, "a treemap's area", "size rectangles by a numeric column")?;
    let values = tree.values_of(column);
    let sums =
        h.sum_leaves(&values.iter().map(|v| if v.is_finite() && *v > 0.0 { *v } else { 0.0 }).collect::<Vec<_>>());
    let overridden = (0..h.len())
        .filter(|&n| {
            !h.is_leaf(n) && values[n].is_finite() && (values[n] - sums[n]).abs() > 1e-9 * sums[n].abs().max(1.0)
        })
        .count();
    if overridden > 0 {
        warnings.push(Warning::from(format!(
            "{overridden} inner nodes have a `{field}` that differs from the sum of their leaves; \
             areas use the leaf sums"
        )));
    }
    Ok(values)
}

/// How rectangles are coloured, with the legend that explains it.
struct Fill {
    mode: FillMode,
    branches: Branches,
    palette: Vec<Color>,
    legend: Option<Legend>,
}

enum FillMode {
    Branch,
    Depth(color::ContinuousMap, f64),
    Value(color::ContinuousMap, f64, f64),
    Column(encode::ColorEncoding, Vec<Option<u32>>),
}

impl Fill {
    fn new(
        chart: &Chart,
        options: &TreemapOptions,
        table: &Table,
        (tree, labels): (&Tree, &[String]),
        (depths, limit): (&[u32], u32),
    ) -> Result<Fill, MarkError> {
        let h = &tree.hierarchy;
        let branches = Branches::of(tree);
        let shown_leaves: Vec<usize> =
            (0..h.len()).filter(|&n| depths[n] <= limit && (h.is_leaf(n) || depths[n] == limit)).collect();
        let mut palette = vec![encode::DEFAULT_MARK_COLOR];
        let (mode, legend) = if options.color.is_some() {
            let rows: Vec<u32> = shown_leaves.iter().filter_map(|&n| tree.rows[n]).collect();
            let (encoding, legend) =
                encode::color_encoding(chart, options.color.as_ref(), None, table, &rows, Symbol::Square)?;
            (FillMode::Column(encoding, tree.rows.clone()), legend)
        } else {
            match options.color_by.unwrap_or(TreemapColor::Branch) {
                TreemapColor::Branch => {
                    palette = branch_palette(options.scheme.as_deref(), branches.heads.len())?;
                    (FillMode::Branch, branch_legend(&branches, labels, &palette))
                }
                TreemapColor::Depth => {
                    let map = encode::continuous_map(&["scheme"], options.scheme.as_deref())?;
                    let deepest = shown_leaves.iter().map(|&n| depths[n]).max().unwrap_or(1).max(2) as f64;
                    let legend = Legend::ColorBar { title: "depth".into(), map: map.clone(), domain: (1.0, deepest) };
                    (FillMode::Depth(map, deepest), Some(legend))
                }
                TreemapColor::Value => {
                    let map = encode::continuous_map(&["scheme"], options.scheme.as_deref())?;
                    let sums =
                        tree.hierarchy.sum_leaves(&match options.value.as_deref().and_then(|f| table.column(f)) {
                            Some(c) => tree.values_of(c).iter().map(|v| if *v > 0.0 { *v } else { 0.0 }).collect(),
                            None => vec![1.0; h.len()],
                        });
                    let (lo, hi) = encode::finite_extent(shown_leaves.iter().map(|&n| sums[n])).unwrap_or((0.0, 1.0));
                    let (lo, hi) = encode::color_domain(&map, lo, hi, None);
                    let title = options
                        .value
                        .as_deref()
                        .map_or("leaves".into(), |v| title_with_unit(v, options.unit.as_deref()));
                    let legend = Legend::ColorBar { title, map: map.clone(), domain: (lo, hi) };
                    (FillMode::Value(map, lo, hi), Some(legend))
                }
            }
        };
        Ok(Fill { mode, branches, palette, legend })
    }

    fn branch_color(&self, node: usize) -> Color {
        self.branches.color(node, &self.palette)
    }

    /// Fill of a drawn leaf.
    fn leaf(&self, node: usize, value: f64, depth: u32) -> Color {
        match &self.mode {
            FillMode::Branch => lighten(self.branch_color(node), 0.12 * depth.saturating_sub(2).min(4) as f64),
            FillMode::Depth(map, deepest) => map.at((depth as f64 - 1.0) / (deepest - 1.0)),
            FillMode::Value(map, lo, hi) => map.at((value - lo) / (hi - lo)),
            FillMode::Column(encoding, rows) => match rows[node] {
                Some(r) => encoding.color_of(r),
                None => encode::MISSING_COLOR,
            },
        }
    }

    /// Fill of an inner node (its header band and the padding around its children).
    fn inner(&self, node: usize, depth: u32) -> Color {
        match &self.mode {
            // Deeper inner nodes get lighter, so that nested headers and gaps stay visible.
            FillMode::Branch if self.branches.of_node[node].is_some() => {
                let step = depth.saturating_sub(1) as f64;
                let c = self.branch_color(node);
                if step < 3.0 { darken(c, 0.36 - 0.12 * step) } else { lighten(c, 0.1 * (step - 2.0)) }
            }
            FillMode::Depth(map, deepest) => darken(map.at((depth as f64 - 1.0) / (deepest - 1.0)), 0.2),
            _ => Color::rgb(0x5f, 0x5f, 0x5f),
        }
    }
}

/// A value with its unit, e.g. `20.5k B`.
fn with_unit(value: f64, unit: Option<&str>) -> String {
    match unit {
        Some(u) => format!("{} {u}", format_value(value)),
        None => format_value(value),
    }
}

/// A leaf's name and value, shrunk to fit, truncated, or left out when the cell is too small.
fn leaf_label(name: &str, value: f64, unit: Option<&str>, cell: Cell, fill: Color, size: f64) -> Vec<Item> {
    let (w, h) = (cell.width() - 6.0, cell.height() - 4.0);
    let Some((text, size)) = fit(name, w, h, size) else { return Vec::new() };
    let color = text_color_on(fill);
    let at = Point::new(cell.x0 + 3.0, cell.y0 + 2.0);
    let mut out = vec![label_item(text, at, size, color)];
    let value_text = with_unit(value, unit);
    if h >= 2.3 * size && measure(&value_text, size).width <= w {
        out.push(label_item(value_text, Point::new(at.x, at.y + 1.15 * size), size, color));
    }
    out
}

/// An inner node's name (and value, when there is room) in its header band.
fn header_label(name: &str, value: &str, cell: Cell, header: f64, fill: Color, size: f64) -> Vec<Item> {
    let w = cell.width() - 6.0;
    if cell.height() < header + 2.0 {
        return Vec::new();
    }
    let full = format!("{name}  {value}");
    let text = if measure(&full, size).width <= w { full } else { name.to_string() };
    let Some((text, size)) = fit(&text, w, header - 2.0, size) else { return Vec::new() };
    let at = Point::new(cell.x0 + 3.0, cell.y0 + (header - size) / 2.0);
    vec![label_item(text, at, size, text_color_on(fill))]
}

/// The largest size down to [`MIN_LABEL_SIZE`] at which `text` fits `w` × `h`, truncating with
/// an ellipsis at the smallest size; `None` when not even a few letters fit.
fn fit(text: &str, w: f64, h: f64, size: f64) -> Option<(String, f64)> {
    let mut s = size;
    while s > MIN_LABEL_SIZE && measure(text, s).width > w {
        s = (s - 1.0).max(MIN_LABEL_SIZE);
    }
    if h < s * 1.05 || w < 2.0 * s {
        return None;
    }
    let fitted = truncate_to_width(text, w, s);
    (fitted.chars().count() >= text.chars().count().min(3)).then_some((fitted, s))
}

fn label_item(content: String, at: Point, size: f64, color: Color) -> Item {
    Item::text(
        Role::Annotation,
        Text { at, content, size, anchor: Anchor::Start, baseline: Baseline::Top, angle: 0.0, color },
    )
}

/// One row per node down to the drawn depth: id, name, parent, depth, value and rectangle in
/// canvas pixels.
fn derived(tree: &Tree, labels: &[String], map: &tiling::Treemap, depths: &[u32], limit: u32) -> Derived {
    let h = &tree.hierarchy;
    let nodes: Vec<usize> = h.preorder().into_iter().map(|n| n as usize).filter(|&n| depths[n] <= limit).collect();
    let mut d = node_rows(tree, labels, &nodes, depths);
    d.push("value", DerivedColumn::Number(nodes.iter().map(|&n| map.values[n]).collect()));
    let edge = |f: fn(&Cell) -> f64| DerivedColumn::Number(nodes.iter().map(|&n| f(&map.rects[n])).collect());
    d.push("x0", edge(|c| c.x0));
    d.push("y0", edge(|c| c.y0));
    d.push("x1", edge(|c| c.x1));
    d.push("y1", edge(|c| c.y1));
    d
}

/// `kind = "treemap"`.
pub static KIND: KindInfo =
    KindInfo::new("treemap", &["tree", "value", "label", "color"]).conventions(defaults::TREE).sized(DEFAULT_SIZE);

impl Technique for TreemapOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table)
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }

    crate::mark::registry::color_key!();
}
