#!/bin/bash
# Takes docs/screens/{attract,play,operator,calibration}.png from the real kiosk (a debug
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
xdotool key r; sleep 0.5                   # recalibrate: with the mouse as the dot
for t in "128 72" "640 72" "1152 72"; do
  xdotool mousemove $t; sleep 0.1; xdotool mousemove_relative 1 0; sleep 2.2
done
xdotool mousemove 128 360; sleep 0.8      # the fourth target, its ring part-filled
shot calibration
grep -v '^<6>strike' "$work/mallet.log" >&2 || true
