#!/usr/bin/env bash
# The main job: installs what is missing, builds, and plays every sample scene headless,
# one result line each (pass --json for the full result objects).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
build=$("$root/scripts/build.sh" | tail -n 1)
status=0
for scene in "$root"/samples/scenes/*.json; do
    "$build/samples/physhand-scene" "$scene" "$@" || status=1
done
exit $status
