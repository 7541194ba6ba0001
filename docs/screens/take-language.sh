#!/bin/bash
# Takes OUT/attract-LANG.png and OUT/operator-LANG.png from the real kiosk showing one
# visitor language ([kiosk] language = LANG, through a drop-in folder): the attract screen
# with its invitation, then the operator page.
#   usage: take-language.sh MALLET OUT LANG, e.g. for every shipped language:
#   for l in en de fr ja; do
#     xvfb-run -a -s "-screen 0 1920x1080x24" docs/screens/take-language.sh build/release/mallet docs/screens $l
#   done
#   needs: xvfb-run (xvfb), xdotool, import (imagemagick)
set -eu
mallet=$1; out=$2; lang=$3
work=$(mktemp -d); export XDG_RUNTIME_DIR=$work/xdg MALLET_STATE_DIR=$work/state; mkdir -m 700 "$XDG_RUNTIME_DIR"
mkdir "$work/drop-ins"; printf '[kiosk]\nlanguage = "%s"\n' "$lang" >"$work/drop-ins/language.toml"
"$mallet" run --config-dir "$work/drop-ins" >"$work/log" 2>&1 & pid=$!
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
sleep 4
import -window root "$out/attract-$lang.png"
xdotool key ctrl+alt+o; sleep 1
import -window root "$out/operator-$lang.png"
grep "settings:\|language\|font" "$work/log" >&2 || true
