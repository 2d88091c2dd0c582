#!/usr/bin/env bash
# A bar chart (mean of y ± 95% CI per whole x) and a heatmap (rows per whole x and whole y) of
# 10⁸ rows (benches/data/points_1e8.parquet, made by make_big_points.py; the keys computed by a
# `calculate` step), to PNG: grouped while the rows stream through the source's plan, against
# the same charts with their rows held in memory (a selection over the source makes it read its
# rows), same run; then each one's peak memory.
#   bash benches/groups.sh [ROWS]     ROWS: 1e7, 1e8 or 1e9 (default 1e8)
set -euo pipefail
cd "$(dirname "$0")/.."
. benches/big_points.sh "${1:-1e8}"
out=target/bench/groups
mkdir -p "$out"
for kind in streamed held; do
    cat > "$out/$kind.toml" <<SPEC
[data.points]
path = "$data"
transform = [
  { calculate = "round(x)", as = "kx" },
  { calculate = "round(y)", as = "ky" },
]
$(held_selection "$kind")

[[chart]]
name = "bars"
kind = "bar"
data = "points"
x = { field = "kx", title = "x (rounded)" }
y = { field = "y", title = "y" }
aggregate = "mean"
error = "ci95"

[[chart]]
name = "cells"
kind = "heatmap"
data = "points"
x = { field = "kx", title = "x (rounded)" }
y = { field = "ky", title = "y (rounded)" }
SPEC
done
compare_streamed_and_held 4 1 bars cells
