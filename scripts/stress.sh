#!/usr/bin/env bash
# The long stress run (the `stress` label runs a short one in the test suite): SECONDS of
# wall time in all (default 600). Half goes to randomised pathological tracking for every
# drive, seed after seed from 1 (tests/stress/pathological_tracking.*, the suite's own test
# with PHYSHAND_STRESS_SECONDS), printing per drive nonfinite_count, max_body_speed against
# the limit and recovery_s, and every failing seed with the command that replays it. The
# other half is shared by the three libFuzzer targets through scripts/fuzz.sh (clang,
# everything instrumented, in build-fuzz/). FUZZ=0 skips the fuzzers.
#
#   scripts/stress.sh [SECONDS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-600}
case "$seconds" in
    '' | *[!0-9]*)
        echo "usage: $0 [SECONDS]" >&2
        exit 2
        ;;
esac
"$root/scripts/install-deps.sh"
build=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j"${JOBS:-$(nproc)}" --target physhand_stress_tests

status=0
tracking=$((${FUZZ:-1} == 0 ? seconds : seconds / 2))
echo "== pathological tracking, every drive, ${tracking} s"
PHYSHAND_STRESS_SECONDS=$tracking "$build/tests/physhand_stress_tests" \
    --gtest_filter=Stress.RandomPathologicalTrackingStaysFiniteAndRecovers || status=1

if [ "${FUZZ:-1}" != 0 ]; then
    each=$(((seconds - tracking) / 3))
    for target in fuzz_scene_loader fuzz_config fuzz_extension; do
        echo "== $target, ${each} s"
        BUILD_DIR=$root/build-fuzz "$root/scripts/fuzz.sh" "$target" "$each" || status=1
    done
fi
exit $status
