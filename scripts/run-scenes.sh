#!/usr/bin/env bash
# The main job: installs what is missing, builds, and plays every sample scene through
# loader -> layer -> simulated runtime (physhand-sample), one result line each (pass --json
# for the full result objects), with a line for each touch that begins. The four paper
# scenes (throw, sphere, displacement, stack), press_table and app_push are rendered (Vulkan;
# lavapipe when no other device is set) with capture: their frames go to out/SCENE/ and one
# contact sheet each to out/SCENE_contact_sheet.png. The others play headless. PHYSICS_ONLY=1 runs physhand-scene instead; VIEW_SIZE sets the rendered views'
# width in pixels (default 320). The simulated head sits at the table, close enough for 4 cm
# cubes to read on the contact sheets (for sphere: above the table's far end, to see into the
# basket on the floor beyond it); PHYSHAND_SIM_HEAD_POSITION and PHYSHAND_SIM_HEAD_PITCH_DEG
# put it elsewhere.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
build=$("$root/scripts/build.sh" | tail -n 1)
export XDG_DATA_HOME="$build/share"
export XR_RUNTIME_JSON="${XR_RUNTIME_JSON:-$build/share/openxr/1/runtimes/physhand_simulated.json}"
lavapipe=/usr/share/vulkan/icd.d/lvp_icd.$(uname -m).json
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -f "$lavapipe" ]; then export VK_ICD_FILENAMES="$lavapipe"; fi
out="$root/out"
for scene in "$root"/samples/scenes/*.json; do
    name=$(basename "$scene" .json)
    if [ "${PHYSICS_ONLY:-0}" = 1 ]; then
        "$build/samples/physhand-scene" "$scene" "$@"
    elif [[ " throw sphere displacement stack press_table app_push " == *" $name "* ]]; then
        rm -rf "${out:?}/$name"
        mkdir -p "$out/$name"
        if [ "$name" = sphere ]; then head=(0.1,1.45,-0.45 -64); else head=(0.15,1.1,0.05 -40); fi
        PHYSHAND_SIM_SCENE="$scene" PHYSHAND_SIM_CAPTURE="$out/$name" \
            PHYSHAND_SIM_CONTACT_SHEET="$out/${name}_contact_sheet.png" \
            PHYSHAND_SIM_HEAD_POSITION="${PHYSHAND_SIM_HEAD_POSITION:-${head[0]}}" \
            PHYSHAND_SIM_HEAD_PITCH_DEG="${PHYSHAND_SIM_HEAD_PITCH_DEG:-${head[1]}}" \
            "$build/samples/physhand-sample" --view-size "${VIEW_SIZE:-320}" "$scene" "$@"
    else
        PHYSHAND_SIM_SCENE="$scene" "$build/samples/physhand-sample" --headless "$scene" "$@"
    fi
done
