#!/usr/bin/env bash
# Installs the npm package `gltf-validator` (Khronos' glTF validator, pinned) into
# tests/data/gltf-validator/ (ignored by git), for the tests in tests/suite/gltf.rs that run
# `dataink render --format glb` output through it with scripts/validate_gltf.mjs.
# Usage: bash scripts/fetch_gltf_validator.sh   (needs npm; retries three times)
set -euo pipefail
exec bash "$(dirname "$0")/npm_install_pinned.sh" gltf-validator 2.0.0-dev.3.10 tests/data/gltf-validator
