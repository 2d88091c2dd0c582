#!/usr/bin/env bash
# Graphviz sfdp peer of `cargo bench --bench force_quality`: lays out data/graph_10k.gv
# (from make_graph.py) with `sfdp -Tplain`, prints the best wall time of 3 whole-process runs
# in seconds, and writes the positions of the last run to data/pos_sfdp.csv (node,x,y).
# Usage: bash benches/peer_sfdp.sh   (needs graphviz: apt-get install -y graphviz)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
graph="$here/data/graph_10k.gv"
plain="$(mktemp)"
trap 'rm -f "$plain"' EXIT
best=""
for run in 1 2 3; do
  start=$(date +%s.%N)
  sfdp -Tplain "$graph" > "$plain"
  end=$(date +%s.%N)
  best=$(awk -v s="$start" -v e="$end" -v b="$best" 'BEGIN { t = e - s; if (b == "" || t < b) b = t; print b }')
done
{
  echo "node,x,y"
  awk '$1 == "node" { print $2 "," $3 "," $4 }' "$plain"
} > "$here/data/pos_sfdp.csv"
printf 'sfdp -Tplain, 10k nodes / 40k edges: best of 3 = %.3f s\n' "$best"
