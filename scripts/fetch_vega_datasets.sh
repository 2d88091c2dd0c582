#!/usr/bin/env bash
# Installs the npm package `vega-datasets` (pinned) into tests/data/vega/ (ignored by git), for the
# integration tests in tests/suite/datasets.rs that read real files as they are shipped
# (miserables.json, volcano.json, flights-200k.arrow, earthquakes.json, movies.json).
# Usage: bash scripts/fetch_vega_datasets.sh   (needs npm; retries three times)
set -euo pipefail
cd "$(dirname "$0")/.."

version="3.2.1"
dest="tests/data/vega"
data="$dest/node_modules/vega-datasets/data"

if [ -f "$data/miserables.json" ] && grep -q "\"version\": \"$version\"" "$dest/node_modules/vega-datasets/package.json"; then
    exit 0
fi
mkdir -p "$dest"
for attempt in 1 2 3; do
    if npm install --prefix "$dest" --no-save --no-audit --no-fund --loglevel=error "vega-datasets@$version" >/dev/null; then
        echo "vega-datasets $version installed in $data"
        exit 0
    fi
    echo "npm install failed (attempt $attempt of 3); retrying" >&2
    sleep $((attempt * 15))
done
echo "error: could not install vega-datasets $version with npm" >&2
exit 1
