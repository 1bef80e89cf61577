#!/usr/bin/env bash
# Regenerates BENCHMARKS.md and bench/ (CSV + one SVG per scene): every drive over
# 1..16 substeps on the measurement scenes, scaling with the number of colliders (and the
# raw-Bullet floor under it, and a callgrind profile of the piles), the
# layer's overhead per call (bench/overhead.json), and the stress figures of every drive
# over STRESS_SEEDS (default 1-100) of pathological tracking and the extreme parameters, and
# the robustness benchmark (variants of the sample tasks, SEEDS seeds each, default 3, each
# played SHIFTS times moved a little, default 4), and
# the sample scenes at every display rate.
# Takes several minutes; not part of the tests.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
build=$("$root/scripts/build.sh" | tail -n 1)
out=$(mktemp -d)
"$build/tests/physhand-sweep" --out "$out" --repeat "${REPEAT:-3}"
"$build/tests/physhand-scaling" --out "$out" --repeat "${REPEAT:-3}"
"$root/scripts/profile-piles.sh" "$build" >"$out/profile.md"
lavapipe=$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json | head -n 1)
for size in "1024 1024" "2064 2208"; do
    # shellcheck disable=SC2086  # two numbers
    VK_ICD_FILENAMES=$lavapipe "$build/tests/overlay/physhand-overlay-bench" --frames 30 --size $size
done >"$out/overlay.jsonl"
"$build/tests/physhand-robustness" --out "$out" --repeat "${SEEDS:-3}" --shifts "${SHIFTS:-4}" >/dev/null
"$build/tests/physhand-display-rates" --out "$out" --repeat "${REPEAT:-3}" >/dev/null
"$build/tests/physhand-overhead" --benchmark_repetitions="${REPEAT:-3}" \
    --benchmark_out="$out/overhead.json" --benchmark_out_format=json --summary "$out/overhead.md"
seeds=${STRESS_SEEDS:-1-100}
PHYSHAND_STRESS_SEEDS=$seeds "$build/tests/physhand_stress_tests" \
    --gtest_filter='Stress.RandomPathologicalTrackingStaysFiniteAndRecovers:BadInput.ExtremeParametersStayFiniteAndBounded' \
    >"$out/stress.log" || true  # a failing run is in the report: its "failed runs"
mkdir -p "$root/bench"
cp "$out"/*.csv "$out"/*.svg "$out/overhead.json" "$root/bench/"
{
    cat "$root/bench/intro.md"
    echo
    echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(lscpu | sed -n 's/^Model name: *//p' | head -1)), \`REPEAT=${REPEAT:-3} scripts/benchmark.sh\`."
    echo
    cat "$out/sweep.md" "$out/scaling.md"
    echo
    echo "## Where a pile's step goes"
    echo
    echo "\`scripts/profile-piles.sh\`: callgrind's inclusive instruction counts in the scaling benchmark's both-hands piles of 10 and 50 cubes (default drive), each part as a share of the whole physics step; the parts marked physhand are the project's own, the rest is Bullet's (Debian's build: no SIMD, one thread). Narrowphase includes the capsule–box and box–box rows below it; allocation counts every allocation of the run."
    echo
    cat "$out/profile.md"
    echo
    echo "## Robustness"
    echo
    cat "$root/bench/robustness-intro.md"
    echo
    cat "$out/robustness.md"
    echo
    echo "## Display rates"
    echo
    echo "\`physhand-display-rates\`: the scenes shown at each display rate and at 90 Hz with each frame up to 2 ms early or late (\`physhand-scene --display-hz R --frame-jitter-ms J\`); the physics steps its own 90 Hz frames whatever the display. free_motion's tracking_error_rms_mm, jerk_rms of the returned wrist and fingertips beside the ghost's (ghost_jerk_rms), repeated_pose_frames and step_us_median (one display frame's call, median of ${REPEAT:-3} runs; at 120 and 144 Hz some calls step no physics frame), then how many of throw, sphere, displacement, stack and lift_hold succeed, and each one's max_shown_depth_mm (docs/metrics.md: the hand as shown against the colliders as shown, at every display time; displacement's is the hand wedged in the wall's hole: bones/1 16.0 mm on the 90 Hz frames themselves, its fingers' first bones in the hole's upper lip, where the joints' closing pulls them after the hand; unjoined, 5.25 mm)."
    echo
    cat "$out/display_rates.md"
    echo
    echo "## The overlay's memory and time"
    echo
    echo "\`physhand-overlay-bench --size W H\` on lavapipe: the renderer drawing two demo hands into both views of a W x H headset, at the size the layer draws them (\`overlay::drawn_extent\`: at most 1.2 M pixels a view, the runtime scaling the layer up); memory_mb is the device memory the renderer holds (its 4x multisampled colour and depth and its buffers; the runtime's swapchain images are not counted), CPU and GPU time per frame (lavapipe rasterises on the CPU)."
    echo
    echo "| views | drawn at | memory_mb | cpu_ms_median | gpu_ms_median |"
    echo "|---|---|---|---|---|"
    sed 's/.*"width": \([0-9]*\), "height": \([0-9]*\), "drawn_width": \([0-9]*\), "drawn_height": \([0-9]*\).*"cpu_ms_median": \([0-9.]*\),.*"gpu_ms_median": \([0-9.]*\),.*"memory_mb": \([0-9.]*\)}/| \1 x \2 | \3 x \4 | \7 | \5 | \6 |/' "$out/overlay.jsonl"
    echo
    echo "## Overhead through the layer"
    echo
    echo "overhead_ns (docs/metrics.md): the median CPU time of one call through the loader to the simulated runtime with the layer, minus the same without it (\`physhand-overhead\`, one run, ${REPEAT:-3} repetitions). Each hand locate is one frame later than the last, so the layer steps its simulation on every call it simulates. The \`xrEndFrame\` rows time whole frames of a Vulkan session on lavapipe, in which the layer intercepts only \`xrEndFrame\`, in wall time: the overlay draws on lavapipe's threads."
    echo
    cat "$out/overhead.md"
    echo
    echo "## Stress"
    echo
    echo "\`PHYSHAND_STRESS_SEEDS=$seeds physhand_stress_tests\`: randomised pathological tracking of both hands (README, Tests), per drive, at its own substeps; max_body_speed is the fastest any body moved, 'requested' what the drive and the contacts asked for before the 20 m/s limit, speed_clamps every body slowed to 20 m/s or to 100 rad/s. Then stiffness 1e4 and 1e6 on every drive at 1 substep against a 1 g grain, a 1000 kg anvil and a 50 m slab."
    echo
    sed -n 's/^\(stress\|extreme\): /- /p' "$out/stress.log"
} > "$root/BENCHMARKS.md"
rm -rf "$out"
echo "wrote BENCHMARKS.md and bench/"
