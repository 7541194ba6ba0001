#!/bin/bash
# The kiosk set to the Wii Remote (`[input] source = "wiimote"`) with none connected, in LANG:
# OUT/no-remote-NAME-LANG-1-attract.png (the visitors' line while the ghost plays) and
# OUT/no-remote-NAME-LANG-2-calibration.png (Ctrl+Alt+O, R: the calibration says that the
# remote is not connected and what to do, not "no light seen").
#   xvfb-run -a -s "-screen 0 1280x1024x24" docs/screens/take-no-remote.sh build/release/mallet OUT 5x4 de
#   needs: xvfb-run (xvfb), xdotool, import (imagemagick)
set -eu
mallet=$1; out=$2; name=$3; lang=$4
dropin="[kiosk]\nlanguage = \"$lang\"\n[input]\nsource = \"wiimote\"\n"
. "$(dirname "$0")/start-kiosk.sh"
sleep 4; import -window root "$out/no-remote-$name-$lang-1-attract.png"
xdotool key ctrl+alt+o; sleep 1; xdotool key r; sleep 2
import -window root "$out/no-remote-$name-$lang-2-calibration.png"
grep -i "calibration\|wii\|warning" "$work/log" >&2 || true
