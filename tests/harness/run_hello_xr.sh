#!/bin/sh
# Runs hello_xr (the arguments: its path and options) for CTest and fails unless it went
# through its whole frame loop: exit status 0, and the session reached EXITING.
#
# hello_xr quits as soon as a read of its standard input returns, end of file included.
# A FIFO that the process itself holds open for writing too never returns from a read.
#
# Optional, from the environment:
#   HELLO_XR_API_LAYERS    OpenXR API layers (names, space-separated) the loader must have
#                          loaded. Core validation's messages go to a file; any fails the run.
#   HELLO_XR_CAPTURE_CHECK a command given the last captured view 0 of the run
#                          (PHYSHAND_SIM_CAPTURE); its failure fails the run.
dir=$(mktemp -d) || exit 1
trap 'rm -r "$dir"' EXIT
mkfifo "$dir/stdin" || exit 1
if [ -n "$HELLO_XR_API_LAYERS" ]; then
    export XR_LOADER_DEBUG=info
    export XR_CORE_VALIDATION_EXPORT_TYPE=text
    export XR_CORE_VALIDATION_FILE_NAME="$dir/core_validation.txt"
fi
if [ -n "$HELLO_XR_CAPTURE_CHECK" ]; then
    export PHYSHAND_SIM_CAPTURE="$dir/capture"
    mkdir "$PHYSHAND_SIM_CAPTURE" || exit 1
fi
"$@" 0<>"$dir/stdin" >"$dir/output" 2>&1
status=$?
cat "$dir/output"
[ "$status" -eq 0 ] || exit "$status"
if ! grep -q "XR_SESSION_STATE_EXITING" "$dir/output"; then
    echo "run_hello_xr.sh: the session never reached XR_SESSION_STATE_EXITING" >&2
    exit 1
fi
for layer in $HELLO_XR_API_LAYERS; do
    if ! grep -q "succeeded loading layer $layer " "$dir/output"; then
        echo "run_hello_xr.sh: the loader did not load $layer" >&2
        exit 1
    fi
done
if [ -s "$dir/core_validation.txt" ]; then
    echo "run_hello_xr.sh: core validation reported:" >&2
    cat "$dir/core_validation.txt" >&2
    exit 1
fi
if [ -n "$HELLO_XR_CAPTURE_CHECK" ]; then
    last=$(ls "$PHYSHAND_SIM_CAPTURE"/frame_*_view0.png 2>/dev/null | tail -n 1)
    if [ -z "$last" ]; then
        echo "run_hello_xr.sh: nothing was captured" >&2
        exit 1
    fi
    # Without LD_PRELOAD: under the sanitizers it carries the ASan runtime that hello_xr
    # lacks, and the instrumented check carries its own.
    env -u LD_PRELOAD $HELLO_XR_CAPTURE_CHECK "$last" || exit 1
fi
