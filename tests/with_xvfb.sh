#!/usr/bin/env bash
# Runs a command under a private Xvfb server. Unlike `xvfb-run -a`, the server picks its own free display and
# reports it through -displayfd once it accepts connections, so no two runs race for a display number.
#   Usage: with_xvfb.sh WxHxD COMMAND [ARGS...]
# The ctest entries that use it are RUN_SERIAL: with other GL tests running beside it, XOpenDisplay on the fresh
# server failed now and then on 2-core machines (server alive, socket present); alone it never did.
set -euo pipefail
screen="$1"; shift
fifo="$(mktemp -u)"; mkfifo "$fifo"
Xvfb -displayfd 3 -screen 0 "$screen" -nolisten tcp 3>"$fifo" 2>/dev/null &
xvfb_pid=$!
# Wait for the server to be gone at exit: a dying Xvfb unlinks its socket late, which would delete the socket of
# the next server that reuses its display number.
trap 'kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true; rm -f "$fifo"' EXIT
read -r -t 30 display <"$fifo" || { echo "with_xvfb: Xvfb did not start" >&2; exit 1; }
DISPLAY=":$display" "$@"
