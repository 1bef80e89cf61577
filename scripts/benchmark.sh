#!/usr/bin/env bash
# Regenerates BENCHMARKS.md and bench/ (CSV + one SVG per scene): every drive over
# 1..16 substeps on the measurement scenes, and scaling with the number of colliders.
# Takes several minutes; not part of the tests.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
build=$("$root/scripts/build.sh" | tail -n 1)
out=$(mktemp -d)
"$build/tests/physhand-sweep" --out "$out" --repeat "${REPEAT:-3}"
"$build/tests/physhand-scaling" --out "$out" --repeat "${REPEAT:-3}"
mkdir -p "$root/bench"
cp "$out"/*.csv "$out"/*.svg "$root/bench/"
{
    cat "$root/bench/intro.md"
    echo
    echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(lscpu | sed -n 's/^Model name: *//p' | head -1)), \`REPEAT=${REPEAT:-3} scripts/benchmark.sh\`."
    echo
    cat "$out/sweep.md" "$out/scaling.md"
} > "$root/BENCHMARKS.md"
rm -rf "$out"
echo "wrote BENCHMARKS.md and bench/"
