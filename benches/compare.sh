#!/usr/bin/env bash
# Whole-command timings against the peer, in one run. Needs hyperfine (apt-get install hyperfine)
# and, for the peers, python3 with pandas, matplotlib and contourpy (pip install pandas matplotlib contourpy).
# Usage: benches/compare.sh            (results also in target/bench/*.md)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
mkdir -p target/bench/out
# (Re)made when missing or written before it had the `panel` column.
head -1 benches/data/points.csv 2>/dev/null | grep -q panel || python3 benches/make_points.py benches/data/points.csv 1000000

echo "== 1M-point scatter to a 1000x1000 PNG, whole process (CSV read included)"
hyperfine --warmup 2 --runs 10 --export-markdown target/bench/scatter_1m.md \
  -n dataink 'target/release/dataink render benches/scatter_1m.toml --format png --out target/bench/out --quiet' \
  -n pandas+matplotlib 'python3 benches/peer_matplotlib.py benches/data/points.csv target/bench/out/peer.png'
python3 benches/peer_matplotlib.py benches/data/points.csv target/bench/out/peer.png

echo "== histogram of 1M values (auto bins) to an 800x500 PNG, whole process (CSV read included)"
hyperfine --warmup 2 --runs 10 --export-markdown target/bench/histogram_1m.md \
  -n dataink 'target/release/dataink render benches/histogram_1m.toml --format png --out target/bench/out --quiet' \
  -n pandas+matplotlib-hist 'python3 benches/peer_matplotlib_hist.py benches/data/points.csv target/bench/out/peer_hist.png'

echo "== 1M points faceted into 10 scatter panels (shared scales) to a 1600x1000 PNG, whole process (CSV read included)"
hyperfine --warmup 2 --runs 10 --export-markdown target/bench/facet_1m.md \
  -n dataink 'target/release/dataink render benches/facet_1m.toml --format png --out target/bench/out --quiet' \
  -n pandas+matplotlib-subplots 'python3 benches/peer_matplotlib_facet.py benches/data/points.csv target/bench/out/peer_facet.png'

echo "== small line chart to SVG + PNG, whole cold process"
hyperfine -N --warmup 5 --runs 50 --export-markdown target/bench/line_small.md \
  -n dataink 'target/release/dataink render benches/line_small.toml --format svg,png --out target/bench/out --quiet'

for spec in "table_50k 50000 6" "table_20k 20000 8" "table_1m 1000000 8"; do
  set -- $spec
  [ -f benches/data/$1.csv ] || python3 benches/make_table.py benches/data/$1.csv $2 $3
done

echo "== splom, 6 columns x 50,000 rows to PNG, whole process"
hyperfine --warmup 1 --runs 5 --export-markdown target/bench/splom_50k.md \
  -n dataink 'target/release/dataink render benches/splom_50k.toml --format png --out target/bench/out --quiet' \
  -n pandas-scatter_matrix 'python3 benches/peer_pandas_splom.py benches/data/table_50k.csv target/bench/out/peer_splom.png'

echo "== parallel coordinates, 8 columns x 20,000 rows to PNG, whole process"
hyperfine --warmup 1 --runs 5 --export-markdown target/bench/parallel_20k.md \
  -n dataink 'target/release/dataink render benches/parallel_20k.toml --format png --out target/bench/out --quiet' \
  -n pandas-parallel_coordinates 'python3 benches/peer_pandas_parallel.py benches/data/table_20k.csv target/bench/out/peer_parallel.png'

echo "== circle segments, 8 columns x 1,000,000 rows to PNG, whole process (no peer)"
hyperfine --warmup 1 --runs 5 --export-markdown target/bench/segments_1m.md \
  -n dataink 'target/release/dataink render benches/segments_1m.toml --format png --out target/bench/out --quiet'

[ -f benches/data/gyre_512.csv ] || python3 benches/make_flow.py benches/data/gyre_512.csv 512

echo "== flow: streamlines of a 512x512 double gyre to a 1000x500 PNG, whole process (CSV read included)"
hyperfine --warmup 1 --runs 5 --export-markdown target/bench/flow_512.md \
  -n dataink 'target/release/dataink render benches/flow_512.toml --format png --out target/bench/out --quiet' \
  -n matplotlib-streamplot 'python3 benches/peer_matplotlib_streamplot.py benches/data/gyre_512.csv target/bench/out/peer_flow.png'
python3 benches/peer_matplotlib_streamplot.py benches/data/gyre_512.csv target/bench/out/peer_flow.png

[ -f benches/data/grid_2000.npy ] || python3 benches/make_grid_npy.py benches/data/grid_2000.npy

echo "== contour: 10 levels (lines and bands) of a 2000x2000 .npy grid to PNG, whole process (load included)"
hyperfine -N --warmup 2 --runs 10 --export-markdown target/bench/contour_npy.md \
  -n dataink 'target/release/dataink render benches/contour_npy.toml --format png --out target/bench/out --quiet' \
  -n np.load+contourpy 'python3 benches/peer_contourpy_npy.py benches/data/grid_2000.npy'

echo "== contour: 10 levels, lines only, of the same grid to PNG, whole process (load included)"
hyperfine -N --warmup 2 --runs 10 --export-markdown target/bench/contour_npy_lines.md \
  -n dataink 'target/release/dataink render benches/contour_npy_lines.toml --format png --out target/bench/out --quiet' \
  -n np.load+contourpy 'python3 benches/peer_contourpy_npy.py benches/data/grid_2000.npy --lines-only'
