#!/usr/bin/env bash
# Configures and builds physhand into BUILD_DIR (default: build). With PHYSHAND_SANITIZE=1
# it builds with clang, AddressSanitizer and UndefinedBehaviorSanitizer into build-asan.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ "${PHYSHAND_SANITIZE:-0}" = 1 ]; then
    build=${BUILD_DIR:-$root/build-asan}
    extra=(-DPHYSHAND_SANITIZE=ON -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++)
else
    build=${BUILD_DIR:-$root/build}
    extra=()
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${extra[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)"
echo "$build"
