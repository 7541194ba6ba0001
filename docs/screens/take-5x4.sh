#!/bin/bash
# Takes docs/screens/{play,operator}-5x4.png from the real kiosk under a 5:4 Xvfb screen.
#   run: xvfb-run -a -s "-screen 0 1280x1024x24" docs/screens/take-5x4.sh build/debug/mallet docs/screens
# 5:4 (1280x1024): the kiosk played with the mouse, then its operator page.
set -eu
mallet=$1; out=$2
work=$(mktemp -d); export XDG_RUNTIME_DIR=$work/xdg MALLET_STATE_DIR=$work/state; mkdir -m 700 "$XDG_RUNTIME_DIR"
"$mallet" run --windowed --size 1280x1024 >"$work/log" 2>&1 & pid=$!
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
xdotool windowmove "$win" 0 0 windowfocus "$win"; sleep 3
for y in $(seq 300 25 800) $(seq 800 -40 600); do xdotool mousemove 420 "$y"; sleep 0.05; done; sleep 0.3
import -window root "$out/play-5x4.png"
xdotool key ctrl+alt+o; sleep 1
import -window root "$out/operator-5x4.png"
grep "input:\|timing:" "$work/log" >&2
