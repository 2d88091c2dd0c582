# Sourced by the large-data benchmarks: from the repository root, sets `rows` (the first
# argument, default 1e8) and `data` (the absolute path of benches/data/points_$rows.parquet,
# made by make_big_points.py when missing), builds the release binary, and defines the helpers
# below.
rows=${1:-1e8}
data="$PWD/benches/data/points_$rows.parquet"
[ -f "$data" ] || python3 benches/make_big_points.py "$data" "$rows"
cargo build --release --quiet

# For the benchmarks that draw the same charts twice, from specs `$out/streamed.toml` (rows left
# in the source's plan) and `$out/held.toml` (rows read into memory): the selection that makes
# the held spec's source `points` read its rows (print it into the spec when $1 is `held`).
held_selection() {
    if [ "$1" = held ]; then printf '[selection.some]\ndata = "points"\nrange = { x = [0, 1] }\n'; fi
}

# Time both specs in the same hyperfine run ($1 runs after $2 warm-ups), then each one's peak
# memory, and check that the PNGs of the charts named after them are byte-identical.
compare_streamed_and_held() {
    local runs=$1 warmup=$2
    shift 2
    run() { echo "target/release/dataink render $out/$1.toml --format png --out $out/$1 --quiet --allow-outside-paths"; }
    hyperfine --warmup "$warmup" --runs "$runs" -n streamed "$(run streamed)" -n held "$(run held)"
    for kind in streamed held; do
        /usr/bin/time -f "$kind: peak resident %M KB" $(run $kind)
    done
    for chart in "$@"; do
        cmp "$out/streamed/$chart.png" "$out/held/$chart.png" && echo "the two $chart PNGs are identical"
    done
}
