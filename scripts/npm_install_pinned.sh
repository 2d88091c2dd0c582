#!/usr/bin/env bash
# Installs one npm package at a pinned version into DEST/node_modules/NAME (for folders that git
# ignores under tests/data/), unless that version is already there; retries three times.
# Usage: bash scripts/npm_install_pinned.sh NAME VERSION DEST   (needs npm)
set -euo pipefail
cd "$(dirname "$0")/.."

name="$1"
version="$2"
dest="$3"
package="$dest/node_modules/$name"

if [ -f "$package/package.json" ] && grep -q "\"version\": \"$version\"" "$package/package.json"; then
    exit 0
fi
mkdir -p "$dest"
for attempt in 1 2 3; do
    if npm install --prefix "$dest" --no-save --no-audit --no-fund --loglevel=error "$name@$version" >/dev/null; then
        echo "$name $version installed in $package"
        exit 0
    fi
    echo "npm install failed (attempt $attempt of 3); retrying" >&2
    sleep $((attempt * 15))
done
echo "error: could not install $name $version with npm" >&2
exit 1
