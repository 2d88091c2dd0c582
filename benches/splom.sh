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
$(held_selection "$kind")

[[chart]]
name = "matrix"
kind = "splom"
data = "points"
columns = ["x", "y", "r"]
SPEC
done
compare_streamed_and_held 3 0 matrix
