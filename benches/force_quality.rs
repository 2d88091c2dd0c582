//! Force-layout benchmark and quality comparison: `cargo bench --bench force_quality`.
//!
//! Reads `benches/data/graph_10k.csv` (10,000 nodes, 40,000 random edges, written by
//! `benches/make_graph.py`), times `force_layout` with default options (best of 3), writes the
//! positions to `benches/data/pos_dataink.csv`, and prints the normalized stress (exact, one BFS
//! per node) and the edge crossings of dataink's layout and of the peers' layouts when their
//! position files exist (`pos_sfdp.csv` from `peer_sfdp.sh`, `pos_d3.csv` from
//! `peer_d3_force.mjs`). Wall times are noisy on a shared machine.

use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use dataink::layout::force::{ForceOptions, force_layout};
use dataink::layout::quality::{edge_crossings, normalized_stress};

/// Nodes in the benchmark graph, as written by make_graph.py (isolated nodes included).
const NODES: usize = 10_000;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("benches").join("data")
}

fn read_edges(path: &Path) -> Result<Vec<(u32, u32)>, String> {
    let text = fs::read_to_string(path).map_err(|e| format!("{}: {e} (run benches/make_graph.py)", path.display()))?;
    let mut edges = Vec::new();
    for (line_no, line) in text.lines().enumerate().skip(1) {
        let mut parts = line.split(',');
        let (Some(s), Some(t)) = (parts.next(), parts.next()) else {
            return Err(format!("{}:{}: expected source,target", path.display(), line_no + 1));
        };
        let parse = |v: &str| v.trim().parse::<u32>().map_err(|e| format!("{}:{}: {e}", path.display(), line_no + 1));
        edges.push((parse(s)?, parse(t)?));
    }
    Ok(edges)
}

fn read_positions(path: &Path) -> Result<Vec<[f64; 2]>, String> {
    let text = fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut positions = vec![[f64::NAN; 2]; NODES];
    for (line_no, line) in text.lines().enumerate().skip(1) {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let bad = || format!("{}:{}: expected node,x,y", path.display(), line_no + 1);
        let [node, x, y] = fields[..] else { return Err(bad()) };
        let node: usize = node.trim_matches('"').parse().map_err(|_| bad())?;
        let x: f64 = x.parse().map_err(|_| bad())?;
        let y: f64 = y.parse().map_err(|_| bad())?;
        match positions.get_mut(node) {
            Some(slot) => *slot = [x, y],
            None => return Err(bad()),
        }
    }
    Ok(positions)
}

fn write_positions(path: &Path, positions: &[[f64; 2]]) -> Result<(), String> {
    let mut out = String::from("node,x,y\n");
    for (i, p) in positions.iter().enumerate() {
        out.push_str(&format!("{i},{},{}\n", p[0], p[1]));
    }
    fs::write(path, out).map_err(|e| format!("{}: {e}", path.display()))
}

fn report(name: &str, positions: &[[f64; 2]], edges: &[(u32, u32)]) -> Result<(), String> {
    let start = Instant::now();
    let stress = normalized_stress(positions, NODES, edges).map_err(|e| format!("{name}: {e}"))?;
    let crossings = edge_crossings(positions, edges).map_err(|e| format!("{name}: {e}"))?;
    let secs = start.elapsed().as_secs_f64();
    println!("{name:>8}: normalized stress {stress:.5}, edge crossings {crossings:>9}   (metrics took {secs:.2} s)");
    Ok(())
}

fn run() -> Result<(), String> {
    let dir = data_dir();
    let edges = read_edges(&dir.join("graph_10k.csv"))?;
    let options = ForceOptions::default();
    let mut best = f64::INFINITY;
    let mut positions = Vec::new();
    for _ in 0..3 {
        let start = Instant::now();
        positions = force_layout(NODES, &edges, None, &options).map_err(|e| e.to_string())?;
        best = best.min(start.elapsed().as_secs_f64());
    }
    println!("dataink force_layout, {NODES} nodes / {} edges: best of 3 = {best:.3} s", edges.len());
    write_positions(&dir.join("pos_dataink.csv"), &positions)?;
    report("dataink", &positions, &edges)?;
    for (name, file) in [("sfdp", "pos_sfdp.csv"), ("d3", "pos_d3.csv")] {
        let path = dir.join(file);
        if path.exists() {
            report(name, &read_positions(&path)?, &edges)?;
        } else {
            println!("{name:>8}: no {} (run its peer script)", path.display());
        }
    }
    Ok(())
}

pub fn main() {
    if std::env::args().any(|a| a == "--list") {
        return;
    }
    if let Err(message) = run() {
        eprintln!("force_quality: {message}");
        std::process::exit(1);
    }
}
