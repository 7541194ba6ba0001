#!/usr/bin/env bash
# The display's start script (/usr/libexec/mallet/mallet-session, from the package) with a
# stand-in cage: it runs cage with the unit's runtime folder as XDG_RUNTIME_DIR (so the
# sandbox can hide /run/user), asks for wlroots' software renderer where /dev/dri has no
# render node and leaves an operator's WLR_RENDERER alone, writes the X display cage's
# Xwayland gives it for the kiosk, and `--wait` waits for that display's socket, giving up
# with status 1. cage, sleep and the DRM folder are stand-ins here; the package's system
# test (packaging/tests/system/) runs the real ones in a booted machine.
#   session_wrapper_test.sh DEB_DIR SCRATCH
set -euo pipefail
dir=$1 scratch=$2
shopt -s nullglob
debs=("$dir"/mallet_*.deb)
((${#debs[@]} == 1)) || { echo "package: expected one mallet_*.deb in $dir" >&2; exit 1; }
rm -rf "$scratch"
mkdir -p "$scratch/fakebin" "$scratch/run" "$scratch/dri" "$scratch/x11"
dpkg-deb --fsys-tarfile "${debs[0]}" | tar -x -C "$scratch" ./usr/libexec/mallet/mallet-session
session=$scratch/usr/libexec/mallet/mallet-session
failures=0
fail() {
  echo "package: $*" >&2
  failures=$((failures + 1))
}

# The stand-in cage: logs what it was given, then runs its client as cage does (with
# DISPLAY set to its Xwayland's display) and ends with it.
# FAKE_CAGE=abort-on-stop: it then stays up and, told to stop (SIGTERM), aborts as Debian 12's
# cage 0.1.4 does at the end of every stop; FAKE_CAGE=abort: it aborts by itself;
# FAKE_CAGE=wait-for-client: its client runs beside it and, told to stop, it waits for the
# client to end and ends with its status, as Debian 13's cage 0.2.0 does. `cage -v` says
# FAKE_CAGE_VERSION (default 0.1.4, Debian 12's).
cat >"$scratch/fakebin/cage" <<'CAGE'
#!/bin/sh
[ "$1" = -v ] && { echo "Cage version ${FAKE_CAGE_VERSION:-0.1.4}"; exit 0; }
echo "XDG_RUNTIME_DIR=$XDG_RUNTIME_DIR WLR_RENDERER=${WLR_RENDERER:-} args=$*" >> "$FAKE_LOG"
[ "$1" = -- ] && shift
if [ "${FAKE_CAGE:-}" = wait-for-client ]; then
  DISPLAY=:7 "$@" &
  client=$!
  trap 'wait "$client"; exit $?' TERM
  wait "$client"
  exit $?
fi
DISPLAY=:7 "$@"
case "${FAKE_CAGE:-}" in
abort-on-stop)
  trap 'trap - ABRT; kill -ABRT $$' TERM
  while :; do /bin/sleep 0.05; done ;;
abort) trap - ABRT; kill -ABRT $$ ;;
esac
CAGE
# The client sleeps until the session stops: here its sleep ends at once (FAKE_SLEEP=real: it
# does not).
printf '#!/bin/sh\necho "sleep $*" >> "$FAKE_LOG"\n[ "${FAKE_SLEEP:-}" = real ] && exec /bin/sleep "$@"\nexit 0\n' \
  >"$scratch/fakebin/sleep"
# `mallet doctor --print-renderer` says $FAKE_RENDERER, or fails when it is empty.
cat >"$scratch/fakebin/mallet" <<'MALLET'
#!/bin/sh
echo "mallet $*" >> "$FAKE_LOG"
[ -n "${FAKE_RENDERER:-}" ] || exit 1
echo "$FAKE_RENDERER"
MALLET
chmod +x "$scratch/fakebin/cage" "$scratch/fakebin/sleep" "$scratch/fakebin/mallet"
run() {  # ENV-OPTION... [-- ARG...]: mallet-session with the stand-ins, its output in $scratch/out
  local options=()
  while (($#)) && [[ $1 != -- ]]; do options+=("$1"); shift; done
  (($#)) && shift
  : >"$scratch/log"
  env "${options[@]}" PATH="$scratch/fakebin:$PATH" FAKE_LOG="$scratch/log" RUNTIME_DIRECTORY="$scratch/run" \
    MALLET_SESSION_DIR="$scratch/run" MALLET_DRI_DIR="$scratch/dri" MALLET_X11_DIR="$scratch/x11" "$session" "$@" >"$scratch/out" 2>&1
}

# The doctor says pixman: pixman, the runtime folder as XDG_RUNTIME_DIR, the display written.
run -u WLR_RENDERER FAKE_RENDERER=pixman || fail "mallet-session exits $? with a stand-in cage: $(cat "$scratch/out")"
grep -qx 'mallet doctor --print-renderer' "$scratch/log" || fail "the doctor was not asked: $(cat "$scratch/log")"
grep -qx "XDG_RUNTIME_DIR=$scratch/run WLR_RENDERER=pixman args=-- $session --display-ready" "$scratch/log" ||
  fail "with the doctor saying pixman cage got: $(cat "$scratch/log")"
grep -q 'compositor renderer: pixman' "$scratch/out" || fail "it did not say which renderer: $(cat "$scratch/out")"
[[ $(cat "$scratch/run/display" 2>/dev/null) == "DISPLAY=:7" ]] ||
  fail "the display file holds '$(cat "$scratch/run/display" 2>/dev/null)', expected DISPLAY=:7"
grep -qx 'sleep infinity' "$scratch/log" || fail "the client did not wait (sleep infinity): $(cat "$scratch/log")"

# The doctor says gles2: WLR_RENDERER left unset, for wlroots to use the GPU.
run -u WLR_RENDERER FAKE_RENDERER=gles2 || fail "mallet-session exits $? with the doctor saying gles2"
grep -q "WLR_RENDERER= args" "$scratch/log" || fail "with the doctor saying gles2 cage got: $(cat "$scratch/log")"
grep -q 'compositor renderer: gles2' "$scratch/out" || fail "it said: $(cat "$scratch/out")"

# The doctor fails: the render node decides (none: pixman; one: the GPU's).
run -u WLR_RENDERER -u FAKE_RENDERER || fail "mallet-session exits $? when the doctor fails"
grep -q "WLR_RENDERER=pixman args" "$scratch/log" || fail "no doctor, no render node: cage got $(cat "$scratch/log")"
touch "$scratch/dri/renderD128"
run -u WLR_RENDERER -u FAKE_RENDERER || fail "mallet-session exits $? with a render node"
grep -q "WLR_RENDERER= args" "$scratch/log" || fail "no doctor, a render node: cage got $(cat "$scratch/log")"
rm "$scratch/dri/renderD128"

# An operator's WLR_RENDERER (a drop-in) wins, and the doctor is not asked.
run WLR_RENDERER=gles2 FAKE_RENDERER=pixman || fail "mallet-session exits $? with WLR_RENDERER=gles2"
grep -q "WLR_RENDERER=gles2 args" "$scratch/log" || fail "the operator's WLR_RENDERER was overridden: $(cat "$scratch/log")"
! grep -q '^mallet doctor' "$scratch/log" || fail "the doctor was asked although WLR_RENDERER was set"

# cage 0.1.x aborting at the end of a stop (Debian 12's 0.1.4): a clean stop, said in a line;
# a later cage (Debian 13's 0.2.0, fixed) aborting at a stop, or any cage aborting with no stop
# asked: its status (134) is the unit's.
stop_aborting() {  # VERSION: mallet-session's status when a cage of VERSION aborts on its stop
  run -u WLR_RENDERER FAKE_RENDERER=pixman FAKE_CAGE=abort-on-stop FAKE_CAGE_VERSION="$1" &
  local runner=$!
  for _ in $(seq 100); do [[ -e $scratch/run/display ]] && break; /bin/sleep 0.05; done
  /bin/sleep 0.2
  pkill -TERM -f "^/bin/sh $session\$" || fail "no mallet-session to stop"
  wait "$runner" && status=0 || status=$?
}
stop_aborting 0.1.4
((status == 0)) || fail "mallet-session stopped while cage 0.1.4 aborts on its stop exits $status: $(cat "$scratch/out")"
grep -q 'cage 0.1.4 aborted while stopping' "$scratch/out" || fail "the stop's abort was not explained: $(cat "$scratch/out")"
stop_aborting 0.2.0
((status == 134)) || fail "mallet-session stopped while cage 0.2.0 aborts on its stop exits $status, expected 134"
grep -q 'cage 0.2.0 aborted while stopping' "$scratch/out" || fail "cage 0.2.0's abort was not said: $(cat "$scratch/out")"
run -u WLR_RENDERER FAKE_RENDERER=pixman FAKE_CAGE=abort && status=0 || status=$?
((status == 134)) || fail "cage aborting by itself: mallet-session exits $status, expected 134"

# cage 0.2.0 told to stop waits for its client: the session ends the client too, so the stop
# is clean and does not wait for systemd's kill (bounded here: 5 s).
run -u WLR_RENDERER FAKE_RENDERER=pixman FAKE_CAGE=wait-for-client FAKE_CAGE_VERSION=0.2.0 FAKE_SLEEP=real &
runner=$!
for _ in $(seq 100); do [[ -e $scratch/run/display ]] && break; /bin/sleep 0.05; done
/bin/sleep 0.2
pkill -TERM -f "^/bin/sh $session\$" || fail "no mallet-session to stop"
for _ in $(seq 100); do kill -0 "$runner" 2>/dev/null || break; /bin/sleep 0.05; done
if kill -0 "$runner" 2>/dev/null; then
  fail "mallet-session still runs 5 s after its stop while cage 0.2.0 waits for its client"
  pkill -KILL -f "^/bin/sleep infinity\$"
fi
wait "$runner" && status=0 || status=$?
((status == 0)) || fail "mallet-session stopped while cage 0.2.0 waits for its client exits $status: $(cat "$scratch/out")"

# --wait: the display's socket there → 0 at once; absent → 1 after the limit, with a line.
python3 -c 'import socket,sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' "$scratch/x11/X7"
run -u WLR_RENDERER -- --wait 5 && status=0 || status=$?
((status == 0)) || fail "--wait with the socket there exits $status: $(cat "$scratch/out")"
rm "$scratch/x11/X7"
run -u WLR_RENDERER -- --wait 1 && status=0 || status=$?
((status == 1)) || fail "--wait without the socket exits $status, expected 1"
grep -q 'no display from mallet-session.service after 1 s' "$scratch/out" || fail "--wait said: $(cat "$scratch/out")"

if ((failures > 0)); then
  exit 1
fi
echo "package: mallet-session runs cage with its own runtime folder, picks the renderer, hands the display to the kiosk and waits for it"
