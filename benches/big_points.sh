# Sourced by the large-data benchmarks: from the repository root, sets `rows` (the first
# argument, default 1e8) and `data` (the absolute path of benches/data/points_$rows.parquet,
# made by make_big_points.py when missing), and builds the release binary.
rows=${1:-1e8}
data="$PWD/benches/data/points_$rows.parquet"
[ -f "$data" ] || python3 benches/make_big_points.py "$data" "$rows"
cargo build --release --quiet
