#!/usr/bin/env bash
# Installs the npm package `vega-datasets` (pinned) into tests/data/vega/ (ignored by git), for the
# integration tests in tests/suite/datasets.rs that read real files as they are shipped
# (miserables.json, volcano.json, flights-200k.arrow, earthquakes.json, movies.json).
# Usage: bash scripts/fetch_vega_datasets.sh   (needs npm; retries three times)
set -euo pipefail
exec bash "$(dirname "$0")/npm_install_pinned.sh" vega-datasets 3.2.1 tests/data/vega
