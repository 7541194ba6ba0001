#!/bin/bash
# Takes docs/screens/{attract,play,operator,doctor,calibration,texture,wall}.png from the real kiosk (a debug
# build) under Xvfb, driving it as a person would: the mouse (no Wii Remote attached, so
# `input.source = "auto"` falls back to it) and the operator's keys, injected with xdotool.
#   needs: xvfb-run (xvfb), xdotool, import (imagemagick)
#   run:   xvfb-run -a -s "-screen 0 1280x720x24" docs/screens/take.sh [build/debug/mallet]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
mallet=${1:-$here/../../build/debug/mallet}
work=$(mktemp -d)
export XDG_RUNTIME_DIR=$work/xdg MALLET_STATE_DIR=$work/state
mkdir -m 700 "$XDG_RUNTIME_DIR"
"$mallet" run --windowed --size 1280x720 >"$work/mallet.log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
xdotool windowmove "$win" 0 0 windowfocus "$win"
shot() { import -window root "$work/$1.png" && convert "$work/$1.png" -strip "$here/$1.png"; }
sleep 6                                    # the ghost plays a phrase
shot attract
# A visitor: the mouse sweeps down onto a wooden bar and up again.
for y in $(seq 250 25 600) $(seq 600 -40 420); do xdotool mousemove 420 "$y"; sleep 0.05; done
sleep 0.3
shot play
xdotool key ctrl+alt+o; sleep 1
shot operator
xdotool key d; sleep 4                     # the doctor's checks on the page (D), then back
shot doctor
xdotool key d; sleep 0.5
xdotool key r; sleep 0.5                   # recalibrate: with the mouse as the dot
for t in "128 72" "640 72" "1152 72"; do
  xdotool mousemove $t; sleep 0.1; xdotool mousemove_relative 1 0; sleep 2.2
done
xdotool mousemove 128 360; sleep 0.8      # the fourth target, its ring part-filled
shot calibration
grep -v '^<6>strike' "$work/mallet.log" >&2 || true

# The second paper's scenes, from the same binary: a visitor sweeps across the bump (the
# cursor lags on the way up), then taps the wall.
kill $pid 2>/dev/null || true; wait $pid 2>/dev/null || true
scene_shot() {  # scene, then the mouse path as "x y" pairs, then the shot's name
  local scene=$1 name=$2; shift 2
  "$mallet" run --windowed --size 1280x720 --scene "$here/../../config/scenes/$scene.toml" >"$work/$name.log" 2>&1 &
  pid=$!
  for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
  xdotool windowmove "$win" 0 0 windowfocus "$win"
  sleep 2
  while [ $# -ge 2 ]; do xdotool mousemove "$1" "$2"; sleep 0.03; shift 2; done
  shot "$name"
  kill $pid 2>/dev/null || true; wait $pid 2>/dev/null || true
}
path=(); for x in $(seq 300 12 560); do path+=("$x" 360); done
scene_shot texture texture "${path[@]}"
path=(); for y in $(seq 200 20 520); do path+=(700 "$y"); done
scene_shot wall wall "${path[@]}"
