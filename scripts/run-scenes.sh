#!/usr/bin/env bash
# The main job: installs what is missing, builds, and plays every sample scene headless
# through loader -> layer -> simulated runtime (physhand-sample), one result line each
# (pass --json for the full result objects). PHYSICS_ONLY=1 runs physhand-scene instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
build=$("$root/scripts/build.sh" | tail -n 1)
export XDG_DATA_HOME="$build/share"
export XR_RUNTIME_JSON="${XR_RUNTIME_JSON:-$build/share/openxr/1/runtimes/physhand_simulated.json}"
for scene in "$root"/samples/scenes/*.json; do
    if [ "${PHYSICS_ONLY:-0}" = 1 ]; then
        "$build/samples/physhand-scene" "$scene" "$@"
    else
        PHYSHAND_SIM_SCENE="$scene" "$build/samples/physhand-sample" --headless "$scene" "$@"
    fi
done
