# Sourced by take-walkthrough.sh and take-no-remote.sh: starts "$mallet" run with one drop-in
# whose text is "$dropin" (printf's escapes), in a scratch state folder, and waits for its
# window. Sets work (the scratch folder; the kiosk's log is $work/log), pid, w and h (the
# screen's size); on exit the kiosk is stopped and the folder removed.
work=$(mktemp -d); export XDG_RUNTIME_DIR=$work/xdg MALLET_STATE_DIR=$work/state; mkdir -m 700 "$XDG_RUNTIME_DIR"
mkdir "$work/drop-ins"; printf "$dropin" >"$work/drop-ins/screens.toml"
"$mallet" run --config-dir "$work/drop-ins" >"$work/log" 2>&1 & pid=$!
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 60); do win=$(xdotool search --class mallet 2>/dev/null | tail -1) && [ -n "$win" ] && break; sleep 0.5; done
read -r w h < <(xdotool getdisplaygeometry)
