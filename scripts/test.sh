#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (CTest labels unit,
# physics, layer, overlay, conformance, stress). PHYSHAND_SANITIZE=1 runs it again under
# ASan+UBSan; extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
build=$("$root/scripts/build.sh" | tail -n 1)
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
