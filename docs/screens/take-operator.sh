#!/bin/bash
# Takes OUT/operator-faults-NAME.png and OUT/doctor-NAME.png from the real kiosk with the
# walkthrough's three faults (issue 29): a misspelt key in a drop-in, a scene choice with a
# negative disc radius and a visitor protocol that does not exist. Run it under an Xvfb
# screen of the shape wanted:
#   xvfb-run -a -s "-screen 0 1280x1024x24" docs/screens/take-operator.sh build/release/mallet docs/screens 5x4
#   needs: xvfb-run (xvfb), xdotool, import (imagemagick)
set -eu
mallet=$1; out=$2; name=$3
work=$(mktemp -d); export XDG_RUNTIME_DIR=$work/xdg MALLET_STATE_DIR=$work/state; mkdir -m 700 "$XDG_RUNTIME_DIR"
here=$(cd "$(dirname "$0")/../.." && pwd)
cp -r "$here/config" "$work/config"
mkdir "$work/config/mallet.toml.d"
printf '[audio]\nvolum = 0.5\n' >"$work/config/mallet.toml.d/50-room.toml"
sed -i 's/^radius_m = 0.08 /radius_m = -0.08/' "$work/config/scenes/texture.toml"
sed -i 's|^visitor_protocol = ""|visitor_protocol = "study/visitor-room.toml"|' "$work/config/mallet.toml"
"$mallet" run --config "$work/config/mallet.toml" >"$work/log" 2>&1 & pid=$!
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
sleep 3
xdotool key ctrl+alt+o; sleep 1.5
import -window root "$out/operator-faults-$name.png"
xdotool key d; sleep 2
import -window root "$out/doctor-$name.png"
grep -i "skipped\|refused\|study off" "$work/log" >&2 || true
