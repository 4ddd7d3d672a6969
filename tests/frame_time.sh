#!/usr/bin/env bash
# Measures the app's frame time while the operating point is dragged across
# the J map, at 1280x800 under Xvfb with software rendering.
# Needs: xvfb, xdotool, a release build (cargo build --release).
# Usage: xvfb-run -s "-screen 0 1280x800x24" tests/frame_time.sh
# Prints the summary the app writes with DMPSCOPE_FRAME_LOG (frame intervals
# and egui CPU time per frame, recorded once the landscape is complete).
set -euo pipefail
cd "$(dirname "$0")/.."
log=$(mktemp)
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
DMPSCOPE_FRAME_LOG="$log" ./target/release/dmpscope > /dev/null 2>&1 &
app=$!
sleep 12                       # the landscape fills in the background
# The J map sits at about x 382..556, y 55..230 at 1280x800.
# One xdotool process chains every move (a process per move would cap the
# event rate at ~30 per second): a move every 10 ms for 10 s.
moves=()
for i in $(seq 1 1000); do
  moves+=(mousemove $(( 395 + (i * 7) % 150 )) $(( 70 + (i * 5) % 150 )) sleep 0.01)
done
xdotool mousemove 450 150 mousedown 1 "${moves[@]}"
xdotool mouseup 1
sleep 1
kill "$app"
cat "$log"
