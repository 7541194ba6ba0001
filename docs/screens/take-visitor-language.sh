#!/bin/bash
# The kiosk's visitor-study offer and consent with the kiosk set to LANG (a visual-only copy
# of the shipped visitor protocol: a machine without a sound card is offered no study whose
# actuator cues it cannot deliver): OUT/visitor-offer-LANG.png, OUT/visitor-consent-LANG.png.
#   xvfb-run -a -s "-screen 0 1280x720x24" docs/screens/take-visitor-language.sh build/release/mallet docs/screens de
# (any shape: 16:9 or 9:16 by the screen's; the files are named by LANG only). NOTE_NAMES=1
# turns the bars' note names on ([visual] note_names), to see the offer's "Yes" sign beside them.
#   needs: xvfb-run (xvfb), xdotool, import (imagemagick)
set -eu
mallet=$1; out=$2; lang=$3
work=$(mktemp -d); export XDG_RUNTIME_DIR=$work/xdg MALLET_STATE_DIR=$work/state; mkdir -m 700 "$XDG_RUNTIME_DIR"
sed 's/^conditions = .*/conditions = ["visual_only", "none"]/' "$(dirname "$0")/../../config/study/visitor.toml" > $work/v.toml
grep -q 'conditions = \["visual_only"' $work/v.toml
printf '[input]\nsource = "mouse"\nmouse = "window"\n[kiosk]\nlanguage = "%s"\n[study]\nvisitor_protocol = "%s"\noffer_every_s = 10\noffer_for_s = 60\nresults_dir = "%s"\n' "$lang" "$work/v.toml" "$work/r" > $work/mallet.toml
if [ "${NOTE_NAMES:-0}" = 1 ]; then printf '[visual]\nnote_names = true\n' >> $work/mallet.toml; fi
"$mallet" run --config $work/mallet.toml >"$work/log" 2>&1 & pid=$!
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
read -r w h < <(xdotool getdisplaygeometry)
for _ in $(seq 60); do grep -q "visitor study: offered" $work/log && break; sleep 0.5; done
sleep 1; import -window root "$out/visitor-offer-$lang.png"
# Down onto "Yes", the last glockenspiel bar: at 92 % of a 16:9 screen's width and 59 % of its
# height; on a portrait screen (instruments stacked) at 72 % and 80 %.
# Wider than 16:9 (21:9) the scene is framed by its height, with room left and right: the
# bar's place is moved towards the middle by the ratio of the two widths.
if [ "$h" -gt "$w" ]; then x=$(( w * 72 / 100 )); from=62; to=84
elif [ $(( w * 9 )) -gt $(( h * 16 )) ]; then x=$(( w / 2 + 418 * 16 * h / 9000 )); from=40; to=66
else x=$(( w * 918 / 1000 )); from=40; to=66; fi
for y in $(seq $(( h * from / 100 )) $(( h / 60 )) $(( h * to / 100 ))); do xdotool mousemove "$x" "$y"; sleep 0.03; done
for _ in $(seq 20); do grep -q "consent screen" $work/log && break; sleep 0.5; done
sleep 1.5; import -window root "$out/visitor-consent-$lang.png"
grep -E "visitor study|consent|refused" $work/log >&2 || true
