#!/usr/bin/env bash
# The large-data density benchmark, in one run: 10⁸ points from Parquet to a 1000 × 1000 density
# PNG, dataink against datashader + pandas reading the same file (its PNG export included), then
# each command's peak memory. With `1e9` as the argument, the 10⁹-row file instead (9 GB of disk;
# dataink only, one run).
# Needs hyperfine and GNU time (apt-get install hyperfine time) and, for the data and the peer,
# pip install numpy pyarrow pandas datashader pillow.
# Usage: benches/density.sh [1e8|1e9]
set -euo pipefail
cd "$(dirname "$0")/.."
rows="${1:-1e8}"
cargo build --release --quiet
mkdir -p target/bench/out
data="benches/data/points_${rows}.parquet"
[ -f "$data" ] || python3 benches/make_big_points.py "$data" "$rows"
spec="benches/density_${rows}.toml"

if [ "$rows" = "1e8" ]; then
  echo "== 10^8 points from Parquet to a 1000x1000 density PNG, whole process"
  hyperfine --warmup 1 --runs 5 --export-markdown target/bench/density_1e8.md \
    -n dataink "target/release/dataink render $spec --format png --out target/bench/out --quiet" \
    -n datashader+pandas "python3 benches/peer_datashader.py $data target/bench/out/peer_density.png"
  echo "== peak memory (maximum resident set, kB)"
  /usr/bin/time -f "dataink %M kB, %e s" target/release/dataink render "$spec" --format png --out target/bench/out --quiet
  POLARS_FORCE_ASYNC=1 /usr/bin/time -f "dataink, file read into buffers %M kB, %e s" \
    target/release/dataink render "$spec" --format png --out target/bench/out --quiet
  /usr/bin/time -f "datashader+pandas %M kB, %e s" python3 benches/peer_datashader.py "$data" target/bench/out/peer_density.png
else
  echo "== $rows points from Parquet to a 1000x1000 density PNG, whole process, peak memory"
  /usr/bin/time -f "dataink %M kB, %e s" target/release/dataink render "$spec" --format png --out target/bench/out --quiet
  POLARS_FORCE_ASYNC=1 /usr/bin/time -f "dataink, file read into buffers %M kB, %e s" \
    target/release/dataink render "$spec" --format png --out target/bench/out --quiet
fi
