//! TQ002 `edge-crossings`: a node-link drawing whose edges cross each other so often that paths
//! cannot be followed (Purchase 1997: crossings are the aesthetic that most hurts reading a
//! graph).
//!
//! The rule reads the drawn edges from the scene (stroked data-mark paths of `graph` and of
//! `linkmap` in link mode, bends included), joins their vertices at equal positions, and counts
//! proper crossings between segments of different edges with
//! [`edge_crossings`](crate::layout::quality::edge_crossings) (edges meeting at a node do not
//! count). The density is crossings per drawn edge; above [`MAX_PER_EDGE`] the rule fires.
//! Drawings of more than [`SAMPLE`] edges are measured on a fixed pseudo-random sample of that
//! many edges: crossings among `k` of `m` edges, scaled by `m(m − 1) / (k(k − 1))`, estimate the
//! total without bias.
//!
//! The threshold: the gallery's force-directed *Les Misérables* graph (77 nodes, 254 edges) has
//! 3.5 crossings per edge and the layered Flare package imports (106 edges, bends included) 4.9;
//! both can be read. A random graph drawn on a circle has about `m / 6` crossings per edge for
//! `m` edges (two chords between four distinct points of a circle cross with probability 1/3),
//! so 33 for 200 edges, and a tree in dataink's layouts has few or none. Ten crossings per edge,
//! twice the readable gallery graphs, means a reader following any edge meets ten others. The
//! gallery's US flights link map (810 links among 30 airports, nearly every pair) has 78 and
//! fires: its matrix view is the readable one.

use std::collections::HashMap;

use crate::layout::quality::edge_crossings;
use crate::layout::split_mix::SplitMix64;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::mark::network::linkmap::LinkMode;
use crate::scene::{PathCmd, Role, Shape};
use crate::spec::ChartKind;

/// The rule fires above this many crossings per drawn edge.
pub const MAX_PER_EDGE: f64 = 10.0;
/// Drawings with more edges than this are measured on a sample of this many.
pub const SAMPLE: usize = 4_000;

/// The rule.
pub static RULE: Rule = Rule {
    code: "TQ002",
    name: "edge-crossings",
    category: Category::Technique,
    severity: Severity::Warning,
    summary: "A node-link drawing has more than 10 edge crossings per edge, too many to follow its edges.",
    check,
};

/// Crossings per edge among drawn polylines (each a list of vertices in canvas units), estimated
/// from a sample when there are more than [`SAMPLE`]. Returns `(crossings per edge, edges)`.
pub fn crossings_per_edge(polylines: &[Vec<[f64; 2]>]) -> (f64, usize) {
    let m = polylines.len();
    if m < 2 {
        return (0.0, m);
    }
    let chosen: Vec<&Vec<[f64; 2]>> = if m > SAMPLE {
        let mut rng = SplitMix64(0x5eed_ed6e);
        let mut order: Vec<usize> = (0..m).collect();
        rng.shuffle(&mut order);
        order.truncate(SAMPLE);
        order.iter().filter_map(|&i| polylines.get(i)).collect()
    } else {
        polylines.iter().collect()
    };
    let mut ids: HashMap<(u64, u64), u32> = HashMap::new();
    let mut positions: Vec<[f64; 2]> = Vec::new();
    let mut segments: Vec<(u32, u32)> = Vec::new();
    for line in &chosen {
        let mut previous: Option<u32> = None;
        for p in line.iter() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                previous = None;
                continue;
            }
            let id = *ids.entry((p[0].to_bits(), p[1].to_bits())).or_insert_with(|| {
                positions.push(*p);
                (positions.len() - 1) as u32
            });
            if let Some(prev) = previous.filter(|&q| q != id) {
                segments.push((prev, id));
            }
            previous = Some(id);
        }
    }
    let crossings = edge_crossings(&positions, &segments).unwrap_or(0) as f64;
    let k = chosen.len() as f64;
    let total = if m > chosen.len() { crossings * (m as f64 * (m as f64 - 1.0)) / (k * (k - 1.0)) } else { crossings };
    (total / m as f64, m)
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let node_link = match &s.chart.kind {
        ChartKind::Graph(_) => true,
        ChartKind::Linkmap(o) => o.mode.unwrap_or(LinkMode::Links) == LinkMode::Links,
        _ => false,
    };
    if !node_link {
        return Vec::new();
    }
    let mut polylines: Vec<Vec<[f64; 2]>> = Vec::new();
    s.output.scene.walk(|item| {
        if item.role != Role::DataMark
            || item.rows.is_empty()
            || item.style.fill.is_some()
            || item.style.stroke.is_none()
        {
            return;
        }
        let Shape::Path(cmds) = &item.shape else { return };
        let mut line = Vec::with_capacity(cmds.len());
        for cmd in cmds {
            match cmd {
                PathCmd::MoveTo(p) | PathCmd::LineTo(p) => line.push([p.x, p.y]),
                // Curves are not drawn for edges; a path that has them is not an edge.
                _ => return,
            }
        }
        polylines.push(line);
    });
    let (density, edges) = crossings_per_edge(&polylines);
    if density <= MAX_PER_EDGE {
        return Vec::new();
    }
    let estimated = if edges > SAMPLE { format!("; estimated from {SAMPLE} sampled edges") } else { String::new() };
    vec![Issue::new(
        "edges",
        "layout",
        format!(
            "the {edges} edges cross each other about {:.0} times, {density:.1} crossings per edge (more than \
             {MAX_PER_EDGE}{estimated}), too many to follow an edge from end to end",
            density * edges as f64
        ),
        "try another `layout` (a force layout untangles clusters; layered suits directed acyclic graphs), filter \
         weak edges, or show a dense network as an adjacency matrix (`kind = \"linkmap\"`, `mode = \"matrix\"`)",
    )]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_crossing_diagonals_and_a_shared_endpoint() {
        // The two diagonals of a square cross once; a third edge from a shared corner crosses none.
        let lines = vec![vec![[0.0, 0.0], [10.0, 10.0]], vec![[0.0, 10.0], [10.0, 0.0]], vec![[0.0, 0.0], [0.0, 10.0]]];
        let (density, edges) = crossings_per_edge(&lines);
        assert_eq!(edges, 3);
        assert!((density - 1.0 / 3.0).abs() < 1e-12, "{density}");
    }

    #[test]
    fn consecutive_segments_of_one_polyline_do_not_cross() {
        let lines = vec![vec![[0.0, 0.0], [10.0, 10.0], [0.0, 10.0], [10.0, 0.0]]];
        assert_eq!(crossings_per_edge(&lines).0, 0.0);
    }
}
