#!/usr/bin/env bash
# Whole-command timings against the peer, in one run. Needs hyperfine (apt-get install hyperfine)
# and, for the peer, python3 with pandas and matplotlib (pip install pandas matplotlib).
# Usage: benches/compare.sh            (results also in target/bench/*.md)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
mkdir -p target/bench/out
[ -f benches/data/points.csv ] || python3 benches/make_points.py benches/data/points.csv 1000000

echo "== 1M-point scatter to a 1000x1000 PNG, whole process (CSV read included)"
hyperfine --warmup 2 --runs 10 --export-markdown target/bench/scatter_1m.md \
  -n dataink 'target/release/dataink render benches/scatter_1m.toml --format png --out target/bench/out --quiet' \
  -n pandas+matplotlib 'python3 benches/peer_matplotlib.py benches/data/points.csv target/bench/out/peer.png'
python3 benches/peer_matplotlib.py benches/data/points.csv target/bench/out/peer.png

echo "== small line chart to SVG + PNG, whole cold process"
hyperfine -N --warmup 5 --runs 50 --export-markdown target/bench/line_small.md \
  -n dataink 'target/release/dataink render benches/line_small.toml --format svg,png --out target/bench/out --quiet'
