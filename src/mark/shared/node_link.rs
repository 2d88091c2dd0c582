//! Drawing a network as nodes and links (placement, node sizes and colours, edge widths and
//! colours by weight, arrowheads, greedy label placement), shared by `graph` and `linkmap`'s
//! link mode, and label placement reused by `hypertree`.

use crate::guide::Theme;
use crate::guide::axis::title_with_unit;
use crate::guide::layout::LayoutError;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::frame::Fit;
use crate::mark::network_input::{NetworkInput, Placement, node_column, place};
use crate::mark::size::{area_radius, size_legend};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, encode, frame};
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Rect, Role, Shape, Stroke, Style, Text};
use crate::spec::{Chart, GraphLayout, NodeTable};
use crate::text::measure;

/// Nodes labelled by default up to this many.
const AUTO_LABEL_LIMIT: usize = 150;
/// Colour of edges without a weight.
const PLAIN_EDGE: Color = Color::rgb(0x99, 0x99, 0x99);

/// How a network is drawn: the options `graph` and `linkmap` have in common.
pub struct Look<'s> {
    /// Node placement.
    pub layout: GraphLayout,
    /// Force-layout seed.
    pub seed: u64,
    /// Draw arrowheads.
    pub directed: bool,
    /// Label nodes (`None`: when there are few).
    pub labels: Option<bool>,
    /// Node radius without a size column.
    pub node_radius: Option<f64>,
    /// The weight column and its unit, if edges are weighted.
    pub weight: Option<(&'s str, Option<&'s str>)>,
    /// Continuous scheme of edge colours by weight.
    pub scheme: &'s str,
    /// Edge widths in pixels for the lowest and highest weight.
    pub widths: (f64, f64),
    /// Where on the colour map the lowest weight starts (0: the map's light end), and whether
    /// light edges are also made transparent (SeeNet's fading of unimportant links).
    pub fade: (f64, bool),
    /// The node table's spec.
    pub nodes: Option<&'s NodeTable>,
}

/// Draw a network: place, fit, draw edges (lightest first), nodes and labels, with legends.
pub fn draw_network(chart: &Chart, input: NetworkInput, look: &Look) -> Result<ChartOutput, MarkError> {
    let placement = place(look.layout, look.seed, &input, look.nodes)?;
    let network = &input.network;
    let n = network.node_count();
    let node_rows: Vec<Option<u32>> = network.graph.node_weights().map(|w| w.row).collect();
    let mut legends = Vec::new();

    // Node colour and size from the node table.
    let (node_color, color_legend) = node_colors(chart, look, &input, &node_rows)?;
    legends.extend(color_legend);
    let base_radius = look.node_radius.unwrap_or_else(|| (70.0 / (n as f64).sqrt()).clamp(2.5, 6.0));
    let (radii, size_legend) = node_radii(look, &input, &node_rows, base_radius)?;
    legends.extend(size_legend);

    // Edge colour and width from the weight.
    let weights = network.weights();
    let weight_scale = match look.weight {
        Some((field, unit)) => {
            let map = encode::continuous_map(&["scheme"], Some(look.scheme))?.starting_at(look.fade.0);
            let (lo, hi) = encode::finite_extent(weights.iter().copied()).unwrap_or((0.0, 1.0));
            let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 0.5, hi + 0.5) };
            legends.push(Legend::ColorBar { title: title_with_unit(field, unit), map: map.clone(), domain: (lo, hi) });
            Some((map, lo, hi))
        }
        None => None,
    };

    let mut chart = chart.clone();
    chart.caption.get_or_insert_with(|| caption(&input, &placement, look));
    let chart = &chart;
    let canvas = frame::PanelCanvas::new(chart, legends);
    let theme = &canvas.theme;
    let m = theme.margin;
    let rect = [m, canvas.top(), canvas.width - 2.0 * m - canvas.legend_room(), canvas.room];
    if rect[2] < 80.0 || rect[3] < 80.0 {
        let error = LayoutError::TooSmall { plot_width: rect[2], plot_height: rect[3] };
        return Err(MarkError::layout(error));
    }
    let inset = radii.iter().copied().fold(0.0, f64::max) + 2.0;
    let bends = placement.paths.iter().flatten().copied();
    let fit = Fit::new(placement.positions.iter().copied().chain(bends), rect, inset, placement.uniform);
    let centers: Vec<Point> = placement.positions.iter().map(|&p| fit.at(p)).collect();

    let mut items = vec![canvas.background()];
    let pairs = network.edge_pairs();
    // Light, thin edges first so that heavy ones stay on top.
    let mut order: Vec<usize> = (0..pairs.len()).collect();
    order.sort_by(|&a, &b| weights[a].total_cmp(&weights[b]));
    let many = pairs.len() > 2000;
    for e in order {
        let (s, t) = (pairs[e].0 as usize, pairs[e].1 as usize);
        if s == t {
            continue;
        }
        let (color, width) = match &weight_scale {
            Some((map, lo, hi)) => {
                let k = ((weights[e] - lo) / (hi - lo)).clamp(0.0, 1.0);
                let color = map.at(k);
                let color = if look.fade.1 { color.with_opacity(0.3 + 0.7 * k) } else { color };
                (color, look.widths.0 + (look.widths.1 - look.widths.0) * k)
            }
            None => (PLAIN_EDGE.with_opacity(if many { 0.35 } else { 0.7 }), if many { 0.5 } else { 0.9 }),
        };
        let points: Vec<Point> = match placement.paths.get(e).filter(|p| p.len() >= 2) {
            Some(path) => path.iter().map(|&p| fit.at(p)).collect(),
            None => vec![centers[s], centers[t]],
        };
        let row = network.graph.raw_edges()[e].weight.row;
        items.push(edge_item(&points, color, width, row));
        if look.directed {
            items.extend(arrowhead(&points, radii[t], width, color).map(|a| a.with_rows(vec![row])));
        }
    }
    for (i, c) in centers.iter().enumerate() {
        let mut style = Style::fill(node_color(i));
        style.stroke = Some(Stroke::solid(Color::rgb(255, 255, 255), 0.8));
        let rows = node_rows[i].into_iter().collect();
        items.push(
            Item::new(Role::DataMark, Shape::Circle { center: *c, radius: radii[i] }, style)
                .with_rows(rows)
                .labelled(input.labels[i].clone()),
        );
    }
    let degrees = network.degrees();
    let mut hidden = 0;
    if look.labels.unwrap_or(n <= AUTO_LABEL_LIMIT) {
        let size = theme.label_size * 0.9;
        let (labels, left_out) = place_labels(&input.labels, &centers, &radii, &degrees, &|_| size, theme, rect);
        items.extend(labels);
        hidden = left_out;
    }
    let labels_word = if hidden == 1 { "label" } else { "labels" };
    let note = (hidden > 0).then(|| {
        format!("{} ({hidden} {labels_word} left out where they would overlap)", chart.caption.as_deref().unwrap_or(""))
    });
    let derived = derived(&input, &placement, &centers, &fit, &degrees);
    let mut warnings = input.warnings;
    if hidden > 0 {
        let verb = if hidden == 1 { "was" } else { "were" };
        let note = format!("{hidden} node {labels_word} {verb} left out to avoid overlaps");
        warnings.push(Warning::from(note));
    }
    let scene = canvas.scene(chart, items, note.as_deref());
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

/// The default caption: layout, counts and components.
fn caption(input: &NetworkInput, placement: &Placement, look: &Look) -> String {
    let network = &input.network;
    let components = network.components();
    let mut text = format!("{} nodes, {} edges", network.node_count(), network.graph.edge_count() - network.self_loops);
    if components > 1 {
        text.push_str(&format!(" in {components} components"));
    }
    text.push_str(&format!("; {}", placement.description));
    if let Some((field, _)) = look.weight {
        text.push_str(&format!("; edge width and colour: {field}"));
    }
    text.push('.');
    let mut chars = text.chars();
    chars.next().map(|c| c.to_uppercase().collect::<String>() + chars.as_str()).unwrap_or(text)
}

type NodeColor = Box<dyn Fn(usize) -> Color>;

/// Node fill per node, with its legend.
fn node_colors(
    chart: &Chart,
    look: &Look,
    input: &NetworkInput,
    node_rows: &[Option<u32>],
) -> Result<(NodeColor, Option<Legend>), MarkError> {
    let (Some(spec), Some(table)) = (look.nodes, input.nodes) else {
        return Ok((Box::new(|_| encode::DEFAULT_MARK_COLOR), None));
    };
    let Some(channel) = spec.color.as_ref() else { return Ok((Box::new(|_| encode::DEFAULT_MARK_COLOR), None)) };
    node_column(spec, "color", channel.field(), table)?;
    let rows: Vec<u32> = node_rows.iter().flatten().copied().collect();
    let (encoding, legend) = encode::color_encoding(chart, Some(channel), None, table, &rows, Symbol::Circle)?;
    let node_rows = node_rows.to_vec();
    let color = move |i: usize| match node_rows.get(i).copied().flatten() {
        Some(r) => encoding.color_of(r),
        None => encode::MISSING_COLOR,
    };
    Ok((Box::new(color), legend))
}

/// Node radii (area proportional to the size column, else all alike), with a size key.
fn node_radii(
    look: &Look,
    input: &NetworkInput,
    node_rows: &[Option<u32>],
    base: f64,
) -> Result<(Vec<f64>, Option<Legend>), MarkError> {
    let (Some(spec), Some(table)) = (look.nodes, input.nodes) else { return Ok((vec![base; node_rows.len()], None)) };
    let Some(field) = spec.size.as_deref() else { return Ok((vec![base; node_rows.len()], None)) };
    let column = node_column(spec, "size", field, table)?;
    encode::require_numeric("nodes", column, "a node size", "size nodes by a numeric column")?;
    let values = column.numbers().unwrap_or(&[]);
    let value_of =
        |r: &Option<u32>| r.and_then(|r| values.get(r as usize).copied()).filter(|v| v.is_finite() && *v > 0.0);
    let max = node_rows.iter().filter_map(value_of).fold(0.0, f64::max);
    let max_radius = (base * 2.5).max(6.0);
    // Nodes without a usable size keep a small dot so that their edges still end somewhere.
    let radii =
        node_rows.iter().map(|r| value_of(r).map_or(1.5, |v| area_radius(v, max, max_radius).max(1.5))).collect();
    let legend = (max > 0.0).then(|| size_legend(field, None, max, max_radius));
    Ok((radii, legend))
}

fn edge_item(points: &[Point], color: Color, width: f64, row: u32) -> Item {
    let mut cmds = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        cmds.push(if i == 0 { PathCmd::MoveTo(*p) } else { PathCmd::LineTo(*p) });
    }
    Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(color, width)).with_rows(vec![row])
}

/// A small filled triangle where the last segment meets the target node's rim.
fn arrowhead(points: &[Point], target_radius: f64, width: f64, color: Color) -> Option<Item> {
    let (a, b) = (points.get(points.len().checked_sub(2)?)?, points.last()?);
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len = (dx * dx + dy * dy).sqrt();
    let size = 4.0 + 1.5 * width;
    if len < target_radius + size * 1.5 {
        return None;
    }
    let (ux, uy) = (dx / len, dy / len);
    let tip = Point::new(b.x - ux * (target_radius + 0.5), b.y - uy * (target_radius + 0.5));
    let base = Point::new(tip.x - ux * size, tip.y - uy * size);
    let half = size * 0.45;
    let cmds = vec![
        PathCmd::MoveTo(tip),
        PathCmd::LineTo(Point::new(base.x - uy * half, base.y + ux * half)),
        PathCmd::LineTo(Point::new(base.x + uy * half, base.y - ux * half)),
        PathCmd::Close,
    ];
    Some(Item::new(Role::DataMark, Shape::Path(cmds), Style::fill(color.with_opacity(1.0))))
}

/// Node labels, most connected nodes first, each beside its node on the first side where it
/// overlaps no other label, no node and stays inside the plot; returns the labels and how many
/// were left out.
pub fn place_labels(
    labels: &[String],
    centers: &[Point],
    radii: &[f64],
    priority: &[usize],
    sizes: &dyn Fn(usize) -> f64,
    theme: &Theme,
    plot: [f64; 4],
) -> (Vec<Item>, usize) {
    let mut order: Vec<usize> = (0..labels.len()).collect();
    order.sort_by(|&a, &b| priority[b].cmp(&priority[a]).then(a.cmp(&b)));
    let mut grid = Grid::new(plot, 48.0);
    for (i, c) in centers.iter().enumerate() {
        let r = radii[i];
        grid.insert(Rect::new(c.x - r, c.y - r, 2.0 * r, 2.0 * r), i);
    }
    let mut items = Vec::new();
    let mut left_out = 0;
    for i in order {
        let text = &labels[i];
        let size = sizes(i);
        if size <= 0.0 {
            continue;
        }
        let w = measure(text, size).width;
        let (c, r) = (centers[i], radii[i]);
        let candidates = [
            (
                Point::new(c.x + r + 2.0, c.y),
                Anchor::Start,
                Baseline::Middle,
                Rect::new(c.x + r + 2.0, c.y - size * 0.6, w, size * 1.2),
            ),
            (
                Point::new(c.x - r - 2.0, c.y),
                Anchor::End,
                Baseline::Middle,
                Rect::new(c.x - r - 2.0 - w, c.y - size * 0.6, w, size * 1.2),
            ),
            (
                Point::new(c.x, c.y - r - 1.0),
                Anchor::Middle,
                Baseline::Bottom,
                Rect::new(c.x - w / 2.0, c.y - r - 1.0 - size * 1.2, w, size * 1.2),
            ),
            (
                Point::new(c.x, c.y + r + 1.0),
                Anchor::Middle,
                Baseline::Top,
                Rect::new(c.x - w / 2.0, c.y + r + 1.0, w, size * 1.2),
            ),
        ];
        let inside = |b: &Rect| {
            b.x >= plot[0] - 4.0
                && b.right() <= plot[0] + plot[2] + 4.0
                && b.y >= plot[1]
                && b.bottom() <= plot[1] + plot[3]
        };
        let free = candidates.iter().find(|(_, _, _, b)| inside(b) && !grid.hits(b, i));
        match free {
            Some((at, anchor, baseline, b)) => {
                grid.insert(*b, usize::MAX);
                let halo = Rect::new(b.x - 1.5, b.y, b.w + 3.0, b.h);
                items.push(Item::new(
                    Role::Annotation,
                    Shape::Rect(halo),
                    Style::fill(theme.background.with_opacity(0.75)),
                ));
                items.push(Item::text(
                    Role::Annotation,
                    Text {
                        at: *at,
                        content: text.clone(),
                        size,
                        anchor: *anchor,
                        baseline: *baseline,
                        angle: 0.0,
                        color: theme.text,
                    },
                ));
            }
            None => left_out += 1,
        }
    }
    (items, left_out)
}

/// Boxes bucketed in a uniform grid, for overlap queries.
struct Grid {
    origin: (f64, f64),
    cell: f64,
    cols: usize,
    rows: usize,
    buckets: Vec<Vec<(Rect, usize)>>,
}

impl Grid {
    fn new(area: [f64; 4], cell: f64) -> Grid {
        let cols = ((area[2] / cell).ceil() as usize + 2).min(4096);
        let rows = ((area[3] / cell).ceil() as usize + 2).min(4096);
        Grid { origin: (area[0] - cell, area[1] - cell), cell, cols, rows, buckets: vec![Vec::new(); cols * rows] }
    }

    fn span(&self, b: &Rect) -> (usize, usize, usize, usize) {
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        let x0 = clamp((b.x - self.origin.0) / self.cell, self.cols);
        let x1 = clamp((b.right() - self.origin.0) / self.cell, self.cols);
        let y0 = clamp((b.y - self.origin.1) / self.cell, self.rows);
        let y1 = clamp((b.bottom() - self.origin.1) / self.cell, self.rows);
        (x0, x1, y0, y1)
    }

    fn insert(&mut self, b: Rect, owner: usize) {
        let (x0, x1, y0, y1) = self.span(&b);
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.buckets[y * self.cols + x].push((b, owner));
            }
        }
    }

    /// Whether `b` overlaps a box of another owner.
    fn hits(&self, b: &Rect, owner: usize) -> bool {
        let (x0, x1, y0, y1) = self.span(b);
        (y0..=y1).any(|y| {
            (x0..=x1).any(|x| self.buckets[y * self.cols + x].iter().any(|(r, o)| *o != owner && r.intersects(b)))
        })
    }
}

/// One row per node (position in pixels, degree) and one per edge (its path in pixels).
fn derived(input: &NetworkInput, placement: &Placement, centers: &[Point], fit: &Fit, degrees: &[usize]) -> Derived {
    let network = &input.network;
    let n = network.node_count();
    let edges = network.graph.raw_edges();
    let mut element = vec!["node".to_string(); n];
    element.extend(std::iter::repeat_n("edge".to_string(), edges.len()));
    let ids: Vec<String> = network.graph.node_weights().map(|w| w.id.clone()).collect();
    let mut id = ids.clone();
    id.extend(edges.iter().map(|e| format!("{}→{}", ids[e.source().index()], ids[e.target().index()])));
    let mut label = input.labels.clone();
    label.extend(std::iter::repeat_n(String::new(), edges.len()));
    let nan = |k: usize| std::iter::repeat_n(f64::NAN, k);
    let x: Vec<f64> = centers.iter().map(|c| c.x).chain(nan(edges.len())).collect();
    let y: Vec<f64> = centers.iter().map(|c| c.y).chain(nan(edges.len())).collect();
    let degree: Vec<f64> = degrees.iter().map(|&d| d as f64).chain(nan(edges.len())).collect();
    let weight: Vec<f64> = nan(n).chain(edges.iter().map(|e| e.weight.weight)).collect();
    let mut path = vec![String::new(); n];
    path.extend(edges.iter().enumerate().map(|(i, e)| {
        let points: Vec<Point> = match placement.paths.get(i).filter(|p| p.len() >= 2) {
            Some(p) => p.iter().map(|&q| fit.at(q)).collect(),
            None => vec![centers[e.source().index()], centers[e.target().index()]],
        };
        points.iter().map(|p| format!("{:.2} {:.2}", p.x, p.y)).collect::<Vec<_>>().join(";")
    }));
    let mut d = Derived::default();
    d.push("element", DerivedColumn::Text(element));
    d.push("id", DerivedColumn::Text(id));
    d.push("label", DerivedColumn::Text(label));
    d.push("x", DerivedColumn::Number(x));
    d.push("y", DerivedColumn::Number(y));
    d.push("degree", DerivedColumn::Number(degree));
    d.push("weight", DerivedColumn::Number(weight));
    d.push("path", DerivedColumn::Text(path));
    d
}
