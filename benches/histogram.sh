#!/usr/bin/env bash
# A histogram of 10⁸ values (the x column of benches/data/points_1e8.parquet, made by
# make_big_points.py), "auto" bins, to PNG: counted while the rows stream through the source's
# plan, against the same chart with its rows held in memory (`rug = false` keeps the histogram
# the same but makes the source read its rows), same run; then each one's peak memory.
#   bash benches/histogram.sh [ROWS]     ROWS: 1e7, 1e8 or 1e9 (default 1e8)
set -euo pipefail
cd "$(dirname "$0")/.."
. benches/big_points.sh "${1:-1e8}"
out=target/bench/histogram
mkdir -p "$out"
for kind in streamed held; do
    cat > "$out/$kind.toml" <<SPEC
[data.points]
path = "$data"

[[chart]]
name = "hist"
kind = "histogram"
data = "points"
x = "x"
$([ "$kind" = held ] && echo 'rug = false')
SPEC
done
compare_streamed_and_held 4 1 hist
