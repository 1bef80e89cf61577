#!/bin/sh
# Runs hello_xr (the arguments: its path and options) for CTest and fails unless it went
# through its whole frame loop: exit status 0, and the session reached EXITING.
#
# hello_xr quits as soon as a read of its standard input returns, end of file included.
# A FIFO that the process itself holds open for writing too never returns from a read.
dir=$(mktemp -d) || exit 1
trap 'rm -r "$dir"' EXIT
mkfifo "$dir/stdin" || exit 1
"$@" 0<>"$dir/stdin" >"$dir/output" 2>&1
status=$?
cat "$dir/output"
[ "$status" -eq 0 ] || exit "$status"
if ! grep -q "XR_SESSION_STATE_EXITING" "$dir/output"; then
    echo "run_hello_xr.sh: the session never reached XR_SESSION_STATE_EXITING" >&2
    exit 1
fi
