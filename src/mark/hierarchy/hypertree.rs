//! `hypertree`: a hierarchy in the Poincaré disk (Lamping, Rao & Pirolli 1995). The focus node
//! sits at the centre; the rest shrink towards the rim, so a whole tree fits while the
//! neighbourhood of the focus gets the room. Edges are hyperbolic geodesics (circle arcs
//! orthogonal to the rim); nodes and labels shrink with the local scale (1 − |z|²).
//!
//! The layout is computed once; refocusing is a Möbius map of the stored positions, O(n).

use crate::data::Table;
use crate::guide::layout::LayoutError;
use crate::guide::legend::Symbol;
use crate::layout::hyperbolic::{HyperbolicLayout, HyperbolicOptions, Mobius, geodesic, scale_at, view_from};
use crate::mark::derived::DerivedColumn;
use crate::mark::geometry::{Disk, DiskNode, Geometry};
use crate::mark::node_link::place_labels;
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::tree_input::{Branches, branch_legend, branch_palette, labels_of, node_rows, tree_of};
use crate::mark::{ChartOutput, MarkError, encode, frame, with_default_size};
use crate::scene::{Color, Item, PathCmd, Point, Role, Shape, Stroke, Style};
use crate::spec::{Chart, ColorChannel, TreeSource, defaults};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "hypertree"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct HypertreeOptions {
    /// The tree's columns: `{ id = "id", parent = "parent" }` or `{ path = "path" }`.
    pub tree: TreeSource,
    /// Column of node labels (default: the id, or the last path segment).
    #[serde(default)]
    pub label: Option<String>,
    /// Node brought to the centre: its id (its full path for path trees), or a label only one
    /// node has (default: the root).
    #[serde(default)]
    #[schemars(example = &"flare/vis")]
    pub focus: Option<String>,
    /// Colour nodes by a column (default: one hue per top-level branch).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Categorical scheme of the branch colours.
    #[serde(default)]
    pub scheme: Option<String>,
    /// Hyperbolic distance between a parent and its children (default 1.2; larger spreads the
    /// tree out and pushes deep levels to the rim).
    #[serde(default)]
    #[schemars(range(min = 0.2, max = 5))]
    pub spacing: Option<f64>,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [760.0, 680.0];
/// Node radius at the centre, in pixels.
const CENTRE_RADIUS: f64 = 6.0;
/// Nodes whose local scale is below this are too small to see and are not drawn.
const MIN_SCALE: f64 = 0.008;
/// Labels smaller than this many pixels are left out.
const MIN_LABEL: f64 = crate::guide::theme::MIN_TEXT_SIZE;
/// Fill of the disk.
const DISK_FILL: Color = Color::rgb(0xf7, 0xf7, 0xf5);
/// Colour of edges.
const EDGE: Color = Color::rgb(0x8c, 0x8c, 0x8c);

/// The node named by `focus`: an id (or path), else a label that only one node has.
fn find_focus(ids: &[String], labels: &[String], wanted: &str) -> Result<usize, MarkError> {
    if let Some(node) = ids.iter().position(|i| i == wanted) {
        return Ok(node);
    }
    let matches: Vec<usize> = (0..labels.len()).filter(|&n| labels[n] == wanted).collect();
    match matches.as_slice() {
        [one] => Ok(*one),
        [] => {
            let names: Vec<&str> = labels.iter().map(String::as_str).collect();
            Err(MarkError::at(
                &["focus"],
                format!("no node has the id or label `{wanted}`"),
                crate::spec::suggest::hint(wanted, &names, "labels", true),
            ))
        }
        several => Err(MarkError::at(
            &["focus"],
            format!("{} nodes are labelled `{wanted}`", several.len()),
            format!("name the node by its id instead, e.g. `{}`", ids[several[0]]),
        )),
    }
}

/// Draw a hyperbolic tree, its view moved by `view` after centring the spec's focus (the explorer's drag
/// and click-to-focus), also returning the disk and every node's position in it. With a moved
/// view the ring and the caption name the node nearest the centre.
pub fn draw(chart: &Chart, options: &HypertreeOptions, table: &Table, view: &Mobius) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let tree = tree_of(chart, &options.tree, table)?;
    let labels = labels_of(chart, &tree, options.label.as_deref(), table)?;
    let h = &tree.hierarchy;
    let focus = match options.focus.as_deref() {
        None => h.root(),
        Some(wanted) => find_focus(&tree.ids, &labels, wanted)?,
    };
    let layout_options = HyperbolicOptions { spacing: options.spacing.unwrap_or(1.2), weight_by_leaves: true };
    let layout =
        HyperbolicLayout::new(h, &layout_options).map_err(|e| MarkError::at(&["spacing"], format!("{e}"), ""))?;
    let positions = view_from(&layout, focus, view).map_err(|e| MarkError::at(&["focus"], format!("{e}"), ""))?;
    let focus = if *view == Mobius::identity() { focus } else { nearest_centre(&positions).unwrap_or(focus) };

    // Colours: a column, or one hue per branch.
    let branches = Branches::of(&tree);
    let palette;
    let (color_of, legend): (Box<dyn Fn(usize) -> Color>, _) = if options.color.is_some() {
        let rows: Vec<u32> = tree.rows.iter().flatten().copied().collect();
        let (encoding, legend) =
            encode::color_encoding(chart, options.color.as_ref(), None, table, &rows, Symbol::Circle)?;
        let node_rows = tree.rows.clone();
        (Box::new(move |n| node_rows[n].map_or(encode::MISSING_COLOR, |r| encoding.color_of(r))), legend)
    } else {
        palette = branch_palette(options.scheme.as_deref(), branches.heads.len())?;
        let legend = branch_legend(&branches, &labels, &palette);
        let (b, p) = (&branches, &palette);
        (Box::new(move |n| b.color(n, p)), legend)
    };

    let depths = h.depths();
    let mut chart = chart.clone();
    chart.caption.get_or_insert_with(|| {
        format!(
            "Hyperbolic tree: {} nodes, {} levels; focus: {}. Nodes and labels shrink with distance from the focus.",
            h.len(),
            depths.iter().max().copied().unwrap_or(0),
            labels[focus]
        )
    });
    let chart = &chart;
    let canvas = frame::PanelCanvas::new(chart, legend.into_iter().collect());
    let theme = &canvas.theme;
    let m = theme.margin;
    let width = canvas.width - 2.0 * m - canvas.legend_room();
    let radius = (width.min(canvas.room) / 2.0 - 4.0).floor();
    if radius < 60.0 {
        let error = LayoutError::TooSmall { plot_width: width, plot_height: canvas.room };
        return Err(MarkError::layout(error));
    }
    let center = Point::new(m + width / 2.0, canvas.top() + canvas.room / 2.0);
    let to_px = |z: [f64; 2]| Point::new(center.x + radius * z[0], center.y - radius * z[1]);
    let scales: Vec<f64> = positions.iter().map(|&z| scale_at(z)).collect();
    let visible = |n: usize| scales[n] >= MIN_SCALE;

    let mut items = vec![canvas.background()];
    let mut disk = Style::fill(DISK_FILL);
    disk.stroke = Some(Stroke::solid(theme.grid, 1.0));
    items.push(Item::new(Role::Grid, Shape::Circle { center, radius }, disk));
    // Edges as geodesics, thinner towards the rim; one path per edge.
    for node in h.preorder().into_iter().map(|n| n as usize) {
        let Some(parent) = h.parent(node) else { continue };
        if !visible(node) && !visible(parent) {
            continue;
        }
        let (a, b) = (positions[parent], positions[node]);
        let points = geodesic(a, b).points(0.05);
        let mut cmds = Vec::with_capacity(points.len());
        for (i, &p) in points.iter().enumerate() {
            cmds.push(if i == 0 { PathCmd::MoveTo(to_px(p)) } else { PathCmd::LineTo(to_px(p)) });
        }
        let width = (1.4 * scales[node].max(scales[parent]).sqrt()).max(0.25);
        items.push(Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(EDGE, width)));
    }
    let centers: Vec<Point> = positions.iter().map(|&z| to_px(z)).collect();
    let radii: Vec<f64> = scales.iter().map(|s| CENTRE_RADIUS * s).collect();
    for node in (0..h.len()).filter(|&n| visible(n)) {
        let mut style = Style::fill(color_of(node));
        style.stroke = Some(Stroke::solid(Color::rgb(255, 255, 255), 0.8 * scales[node]));
        let rows = tree.rows[node].into_iter().collect();
        items.push(
            Item::new(Role::DataMark, Shape::Circle { center: centers[node], radius: radii[node] }, style)
                .with_rows(rows)
                .labelled(labels[node].clone()),
        );
    }
    // A ring marks the focus.
    items.push(Item::new(
        Role::Annotation,
        Shape::Circle { center: centers[focus], radius: CENTRE_RADIUS + 3.0 },
        Style::stroke(theme.text, 1.2),
    ));
    let priority: Vec<usize> = scales.iter().map(|s| (s * 1e6) as usize).collect();
    let label_size = theme.label_size;
    let sizes = |n: usize| {
        let s = label_size * scales[n].powf(0.6);
        if s >= MIN_LABEL { s } else { 0.0 }
    };
    let plot = [center.x - radius, center.y - radius, 2.0 * radius, 2.0 * radius];
    let (texts, _) = place_labels(&labels, &centers, &radii, &priority, &sizes, theme, plot);
    items.extend(texts);

    let nodes: Vec<usize> = h.preorder().into_iter().map(|n| n as usize).collect();
    let mut d = node_rows(&tree, &labels, &nodes, &depths);
    d.push("disk_x", DerivedColumn::Number(nodes.iter().map(|&n| positions[n][0]).collect()));
    d.push("disk_y", DerivedColumn::Number(nodes.iter().map(|&n| positions[n][1]).collect()));
    d.push("scale", DerivedColumn::Number(nodes.iter().map(|&n| scales[n]).collect()));
    let scene = canvas.scene(chart, items, None);
    let nodes = (0..h.len())
        .map(|n| DiskNode {
            position: positions[n],
            radius: if visible(n) { radii[n] } else { 0.0 },
            label: labels[n].clone(),
            row: tree.rows[n],
        })
        .collect();
    let geometry = Geometry { disk: Some(Disk { center, radius, nodes }), ..Geometry::default() };
    Ok(ChartOutput {
        scene,
        derived: d,
        warnings: Vec::new(),
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry,
    })
}

/// The node nearest the disk's centre.
fn nearest_centre(positions: &[[f64; 2]]) -> Option<usize> {
    let norm = |z: &[f64; 2]| z[0] * z[0] + z[1] * z[1];
    (0..positions.len())
        .filter(|&n| norm(&positions[n]).is_finite())
        .min_by(|&a, &b| norm(&positions[a]).total_cmp(&norm(&positions[b])))
}

/// `kind = "hypertree"`.
pub static KIND: KindInfo =
    KindInfo::new("hypertree", &["tree", "label", "color"]).conventions(defaults::TREE).sized(DEFAULT_SIZE);

impl Technique for HypertreeOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.view.unwrap_or(&Mobius::identity()))
    }

    fn scheme(&self) -> Option<&str> {
        self.scheme.as_deref()
    }

    crate::mark::registry::color_key!();
}
