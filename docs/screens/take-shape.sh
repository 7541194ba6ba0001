#!/bin/bash
# Takes OUT/play-NAME.png (and, with a fourth argument "operator", OUT/operator-NAME.png)
# from the real kiosk on a screen of one shape: run it under an Xvfb screen of that size.
#   usage: take-shape.sh MALLET OUT NAME [operator], e.g. for every shape:
#   for s in 1920x1200:16x10 1024x768:4x3 1280x1024:5x4 2560x1080:21x9 1080x1920:9x16; do
#          xvfb-run -a -s "-screen 0 ${s%:*}x24" docs/screens/take-shape.sh build/debug/mallet docs/screens ${s#*:}
#        done
# The kiosk fullscreen, as on a museum's screen; a visitor's mouse sweeps down onto the
# third wooden bar and up again; then (operator) the operator page.
#   needs: xvfb-run (xvfb), xdotool, import (imagemagick)
set -eu
mallet=$1; out=$2; name=$3; page=${4:-}
work=$(mktemp -d); export XDG_RUNTIME_DIR=$work/xdg MALLET_STATE_DIR=$work/state; mkdir -m 700 "$XDG_RUNTIME_DIR"
"$mallet" run >"$work/log" 2>&1 & pid=$!
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
read -r w h < <(xdotool getdisplaygeometry)
sleep 3
. "$(dirname "$0")/sweep-third-bar.sh"
sleep 0.3
import -window root "$out/play-$name.png"
if [ "$page" = operator ]; then
  xdotool key ctrl+alt+o; sleep 1
  import -window root "$out/operator-$name.png"
fi
grep "input:\|render:" "$work/log" >&2
