#!/usr/bin/env bash
# Runs a command under a private Xvfb server.
#   Usage: with_xvfb.sh WxHxD COMMAND [ARGS...]
# The server gets a display number of its own, away from the low numbers other servers and earlier runs take
# (:100–:899, one without a lock file), and the command starts only once an X client has connected to it. On a
# loaded 2-core machine a fresh server on the lowest free display (`-displayfd`) now and then refused every client
# (server alive, socket present; a server of an earlier run that was still going away held the display's socket):
# a server that takes no client within 10 s is replaced by one on another display, up to 5 times. The GUI tests take
# RESOURCE_LOCK display_0 or display_1 in turn (tests/gui/CMakeLists.txt): at most two windows at a time.
set -euo pipefail
screen="$1"; shift
xvfb_pid=""
stop_xvfb() {
  if [ -n "$xvfb_pid" ]; then
    kill "$xvfb_pid" 2>/dev/null || true
    # Wait for it to be gone: a dying Xvfb unlinks its socket late.
    wait "$xvfb_pid" 2>/dev/null || true
  fi
  xvfb_pid=""
}
trap stop_xvfb EXIT
for attempt in 1 2 3 4 5; do
  display=""
  for _ in $(seq 1 50); do
    n=$((100 + RANDOM % 800))
    if [ ! -e "/tmp/.X$n-lock" ] && [ ! -e "/tmp/.X11-unix/X$n" ]; then display="$n"; break; fi
  done
  [ -n "$display" ] || { echo "with_xvfb: no free display number" >&2; exit 1; }
  Xvfb ":$display" -screen 0 "$screen" -nolisten tcp 2>/dev/null &
  xvfb_pid=$!
  for _ in $(seq 1 100); do
    if DISPLAY=":$display" xdotool getdisplaygeometry >/dev/null 2>&1; then
      DISPLAY=":$display" "$@"
      exit $?
    fi
    kill -0 "$xvfb_pid" 2>/dev/null || break  # the server died (a display taken meanwhile): try another
    sleep 0.1
  done
  echo "with_xvfb: Xvfb on :$display took no client (attempt $attempt), trying another display" >&2
  stop_xvfb
done
echo "with_xvfb: no Xvfb server took a client after 5 attempts" >&2
exit 1
