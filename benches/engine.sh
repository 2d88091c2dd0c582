#!/usr/bin/env bash
# The distributed path against in-process, same run: 10⁸ points (benches/data/points_1e8.parquet,
# made by make_big_points.py) to a 1000² density PNG, read by a local Spark cluster through
# Spark Connect (scripts/spark_cluster.sh: master, two one-core workers, Connect server) and by
# dataink itself. Needs hyperfine, Java 17 and `bash scripts/spark_cluster.sh install`.
#   bash benches/engine.sh [ROWS]     ROWS: 1e7 or 1e8 (default 1e8)
set -euo pipefail
cd "$(dirname "$0")/.."
. benches/big_points.sh "${1:-1e8}"
cluster=$(mktemp -d /tmp/dataink-spark.XXXXXX)
trap 'bash scripts/spark_cluster.sh stop "$cluster"' EXIT
bash scripts/spark_cluster.sh start "$cluster"
url=$(cat "$cluster/connect_url")
out=target/bench/engine
mkdir -p "$out"
spec() {  # $1: extra source line
    printf '[data.points]\npath = "%s"\n%s\n\n[[chart]]\nname = "density"\nkind = "scatter"\ndata = "points"\nsize = [1000, 1000]\nx = "x"\ny = "y"\nmode = "density"\nbin = 1\n' "$data" "$1"
}
spec "" > "$out/local.toml"
spec "engine = \"$url\"" > "$out/engine.toml"
hyperfine --warmup 1 --runs 3 \
    -n in-process "target/release/dataink render $out/local.toml --format png --out $out/local --quiet --allow-outside-paths" \
    -n spark-connect "target/release/dataink render $out/engine.toml --format png --out $out/engine --quiet --allow-outside-paths"
cmp "$out/local/density.png" "$out/engine/density.png" && echo "the two PNGs are identical"
