#!/usr/bin/env bash
# A scatter-plot matrix in density mode of 10⁸ rows and three columns (x and y of
# benches/data/points_1e8.parquet, made by make_big_points.py, and r = √(x² + y²) from a
# `calculate` step), Freedman–Diaconis diagonals, to PNG: counted while the rows stream through
# the source's plan, against the same chart with its rows held in memory (a selection over the
# source makes it read its rows), same run; then each one's peak memory.
#   bash benches/splom.sh [ROWS]     ROWS: 1e7, 1e8 or 1e9 (default 1e8)
set -euo pipefail
cd "$(dirname "$0")/.."
. benches/big_points.sh "${1:-1e8}"
out=target/bench/splom
mkdir -p "$out"
for kind in streamed held; do
    cat > "$out/$kind.toml" <<SPEC
[data.points]
path = "$data"
transform = [{ calculate = "sqrt(x * x + y * y)", as = "r" }]
$([ "$kind" = held ] && printf '[selection.some]\ndata = "points"\nrange = { x = [0, 1] }\n')

[[chart]]
name = "matrix"
kind = "splom"
data = "points"
columns = ["x", "y", "r"]
SPEC
done
run() { echo "target/release/dataink render $out/$1.toml --format png --out $out/$1 --quiet --allow-outside-paths"; }
hyperfine --warmup 0 --runs 3 -n streamed "$(run streamed)" -n held "$(run held)"
for kind in streamed held; do
    /usr/bin/time -f "$kind: peak resident %M KB" $(run $kind)
done
cmp "$out/streamed/matrix.png" "$out/held/matrix.png" && echo "the two PNGs are identical"
