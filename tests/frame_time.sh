#!/usr/bin/env bash
# Measures the app's frame time while something is dragged, at 1280x800
# under Xvfb with software rendering.
# Needs: xvfb, xdotool, a release build (cargo build --release).
# Usage: xvfb-run -s "-screen 0 1280x800x24" tests/frame_time.sh [WHAT]
#   op          (default) the operating point dragged across the J map
#   new-target  the same with the New target tab on (its run recomputed and
#               its plots drawn every frame)
#   goal        the New target tab on, its goal dragged in the 3D view
# Prints the summary the app writes with DMPSCOPE_FRAME_LOG (frame intervals
# and egui CPU time per frame, recorded once the landscape is complete; on
# Linux also the app thread's own CPU per frame and its wait for a core,
# thread_cpu_ms and thread_wait_ms: egui's figure is wall time).
# PINS=LIST pins those gain sets first (the app's --pin: Table I names or
# DM:KM, comma separated), e.g. the six of issue 45's budget:
#   PINS=extracted,pick,Hrstc1,Hrstc2,Hrstc3,Hrstc4
# RUNS=N runs it N times and prints each run's CPU median and their median
# (one run's median varies by about 0.2 ms here).
set -euo pipefail
self="$(cd "$(dirname "$0")" && pwd)/$(basename "$0")"
cd "$(dirname "$0")/.."
what=${1:-op}
runs=${RUNS:-1}
if [ "$runs" -gt 1 ]; then
  medians=()
  for r in $(seq 1 "$runs"); do
    out=$(RUNS=1 "$self" "$what")
    line=$(grep '^cpu_ms' <<<"$out")
    echo "run $r: $line; $(grep '^thread_cpu_ms' <<<"$out" || true)"
    medians+=("$(awk '{print $3}' <<<"$line")")
  done
  printf '%s\n' "${medians[@]}" | sort -n | awk '{a[NR] = $1} END {
    m = NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2
    printf "cpu_ms median of %d runs %.2f (run medians %.2f-%.2f)\n", NR, m, a[1], a[NR]
  }'
  exit 0
fi
log=$(mktemp)
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
pins=()
if [ -n "${PINS:-}" ]; then
  pins=(--pin "$PINS")
fi
DMPSCOPE_FRAME_LOG="$log" ./target/release/dmpscope "${pins[@]}" > /dev/null 2>&1 &
app=$!
sleep 12                       # the landscape fills in the background
if [ "$what" != op ]; then
  # The right panel's "New target" tab, then its "Run the DMP at a new
  # target" box (where they are at 1280x800).
  xdotool mousemove 1190 37 click 1
  sleep 1
  xdotool mousemove 916 117 click 1
  sleep 2
fi
# One xdotool process chains every move (a process per move would cap the
# event rate at ~30 per second): a move every 10 ms for 10 s.
moves=()
if [ "$what" = goal ]; then
  # The 3D view's goal handle, where the app's frame log says it is drawn
  # (the log is rewritten every 10 frames: hover to make frames).
  for i in $(seq 1 40); do
    grep -q '^handles' "$log" && break
    xdotool mousemove $(( 600 + i % 2 )) 450
    sleep 0.25
  done
  if ! read -r gx gy < <(awk '/^handles/ {print $6, $7}' "$log"); then
    echo "the frame log never said where the goal handle is" >&2
    kill "$app"
    exit 1
  fi
  for i in $(seq 1 1000); do
    moves+=(mousemove $(( gx - 60 + (i * 3) % 120 )) $(( gy - 20 + (i * 2) % 40 )) sleep 0.01)
  done
  xdotool mousemove "$gx" "$gy" mousedown 1 "${moves[@]}"
else
  # The J map sits at about x 382..556, y 55..230 at 1280x800.
  for i in $(seq 1 1000); do
    moves+=(mousemove $(( 395 + (i * 7) % 150 )) $(( 70 + (i * 5) % 150 )) sleep 0.01)
  done
  xdotool mousemove 450 150 mousedown 1 "${moves[@]}"
fi
xdotool mouseup 1
sleep 1
kill "$app"
cat "$log"
