#!/usr/bin/env bash
# Fuzzes one target with libFuzzer for longer than the test suite does (15 s each): builds
# with clang into build-fuzz with everything instrumented (ASan, UBSan and the fuzzer's
# coverage, the layer and the simulated runtime included) and runs TARGET for SECONDS
# (default 600) from its seed corpus tests/fuzz/corpus/TARGET/. New inputs go to
# build-fuzz/tests/fuzz/TARGET.out/corpus/, crashes to build-fuzz/tests/fuzz/TARGET.out/;
# keep a fixed crash as a regression by copying it into the seed corpus, and replay one with
# build-fuzz/tests/fuzz/TARGET FILE. Further arguments go to libFuzzer (e.g. -jobs=2).
# JOBS: build jobs (default: nproc).
#
#   scripts/fuzz.sh fuzz_scene_loader|fuzz_config|fuzz_extension [SECONDS] [LIBFUZZER_ARG...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
case "${1:-}" in
    fuzz_scene_loader | fuzz_config | fuzz_extension) target=$1 ;;
    *)
        echo "usage: $0 fuzz_scene_loader|fuzz_config|fuzz_extension [SECONDS] [LIBFUZZER_ARG...]" >&2
        exit 2
        ;;
esac
seconds=${2:-600}
shift $(($# < 2 ? $# : 2))

"$root/scripts/install-deps.sh"
build=${BUILD_DIR:-$root/build-fuzz}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPHYSHAND_SANITIZE=ON \
    -DCMAKE_C_FLAGS=-fsanitize=fuzzer-no-link -DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link >/dev/null
cmake --build "$build" -j"${JOBS:-$(nproc)}" --target "$target"

out=$build/tests/fuzz/$target.out
mkdir -p "$out/corpus"
# The system OpenXR loader leaks a little per instance (fuzz_extension).
export LSAN_OPTIONS=suppressions=$root/tests/harness/loader_leaks.supp
"$build/tests/fuzz/$target" -max_total_time="$seconds" -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix="$out/" "$@" "$out/corpus" "$root/tests/fuzz/corpus/$target"
