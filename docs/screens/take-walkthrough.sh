#!/bin/bash
# A walkthrough of the real kiosk as a visitor and an operator would take it, on one screen
# shape and in one language: OUT/walk-NAME-LANG-STEP.png for each step. Run it under an Xvfb
# screen of the shape wanted, e.g. the four shapes of issue 29 in the four languages:
#   for s in 1920x1080:16x9 1280x1024:5x4 1080x1920:9x16 2560x1080:21x9; do for l in en de fr ja; do
#     xvfb-run -a -s "-screen 0 ${s%:*}x24" docs/screens/take-walkthrough.sh build/release/mallet OUT ${s#*:} $l
#   done; done
# The steps: 1-attract (the invitation), 2-play (the mouse sweeps onto the third bar),
# 3-operator (Ctrl+Alt+O), 4-doctor (D), 5-calibration (D, R: the mouse's calibration),
# 6-calibration-esc (Esc stops it), 7-texture and 8-wall (the page's S, then Esc and a move).
#   needs: xvfb-run (xvfb), xdotool, import (imagemagick)
set -eu
mallet=$1; out=$2; name=$3; lang=$4
dropin="[kiosk]\nlanguage = \"$lang\"\n"
. "$(dirname "$0")/start-kiosk.sh"
shot() { sleep "${2:-1}"; import -window root "$out/walk-$name-$lang-$1.png"; }
shot 1-attract 4
. "$(dirname "$0")/sweep-third-bar.sh"
shot 2-play 0.3
xdotool key ctrl+alt+o; shot 3-operator 1.5
xdotool key d; shot 4-doctor 2
xdotool key d r; shot 5-calibration 1.5
xdotool key Escape; shot 6-calibration-esc 1
xdotool key s; sleep 2; xdotool key Escape; xdotool mousemove $(( w / 3 )) $(( h / 2 )); shot 7-texture 2
xdotool key ctrl+alt+o; sleep 0.5; xdotool key s; sleep 2; xdotool key Escape
xdotool mousemove $(( w / 2 )) $(( h / 3 )); shot 8-wall 2
grep -i "operator:\|calibration\|warning\|refused" "$work/log" >&2 || true
