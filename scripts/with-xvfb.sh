#!/usr/bin/env bash
# Runs a command under its own Xvfb server (Mesa llvmpipe renders into it).
# The server picks a free display itself (-displayfd), so back-to-back or
# parallel runs never race for the same display number, as `xvfb-run -a`
# can when a previous server on :99 is still shutting down. -noreset: the
# server would otherwise reset when its last client closes, and a script that
# closes one window and opens the next then fails ("bad X server connection").
#   scripts/with-xvfb.sh COMMAND [ARGS...]
set -euo pipefail
fifo=$(mktemp -u)
mkfifo "$fifo"
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$fifo" >/dev/null 2>&1 &
xvfb=$!
trap 'kill "$xvfb" 2>/dev/null || true; wait "$xvfb" 2>/dev/null || true; rm -f "$fifo"' EXIT
# The server writes its display number once it accepts connections.
if ! read -r -t 30 display <"$fifo"; then
  echo "with-xvfb: Xvfb did not start within 30 s" >&2
  exit 1
fi
DISPLAY=":$display" "$@"
