#!/usr/bin/env bash
# The unit's main process (/usr/libexec/mallet/mallet-kiosk, from the package) passes the
# kiosk's exit status to systemd through a cage that, like Debian 12's cage 0.1.4, always
# exits 0 — so RestartPreventExitStatus=0 tells an operator's quit from a crash — and
# `--reload` sends SIGHUP to the kiosk. cage and mallet are stand-ins here.
#   kiosk_wrapper_test.sh DEB_DIR SCRATCH
set -euo pipefail
dir=$1 scratch=$2
shopt -s nullglob
debs=("$dir"/mallet_*.deb)
((${#debs[@]} == 1)) || { echo "package: expected one mallet_*.deb in $dir" >&2; exit 1; }
rm -rf "$scratch"
mkdir -p "$scratch/usr/bin" "$scratch/fakebin" "$scratch/run"
dpkg-deb --fsys-tarfile "${debs[0]}" | tar -x -C "$scratch" ./usr/libexec/mallet/mallet-kiosk
wrapper=$scratch/usr/libexec/mallet/mallet-kiosk
failures=0
fail() {
  echo "package: $*" >&2
  failures=$((failures + 1))
}

# The stand-in kiosk: logs its arguments, then does what $FAKE_KIOSK says.
cat >"$scratch/usr/bin/mallet" <<'EOF'
#!/bin/sh
echo "$*" >> "$FAKE_LOG"
case "$FAKE_KIOSK" in
exit:*) exit "${FAKE_KIOSK#exit:}" ;;
signal:*) kill -s "${FAKE_KIOSK#signal:}" $$ ;;
term)  # wait for SIGTERM, and stop cleanly as the real kiosk does
  trap 'echo stopped >> "$FAKE_LOG"; exit 0' TERM
  echo waiting > "$FAKE_LOG.waiting"
  while :; do sleep 0.05; done ;;
reload)  # wait for SIGHUP, as the real kiosk reloads its settings
  trap 'echo reloaded >> "$FAKE_LOG"; exit 7' HUP
  echo waiting > "$FAKE_LOG.waiting"
  while :; do sleep 0.05; done ;;
esac
exit 99
EOF
# The stand-in cage: runs its application and exits 0 whatever happened, as 0.1.4 does;
# FAKE_CAGE=broken: fails before starting anything (no display, no seat).
cat >"$scratch/fakebin/cage" <<'EOF'
#!/bin/sh
[ "${FAKE_CAGE:-}" = broken ] && { echo "cage: no DRM device" >&2; exit 1; }
[ "$1" = -- ] || exit 64
shift
"$@"
exit 0
EOF
chmod +x "$scratch/usr/bin/mallet" "$scratch/fakebin/cage"
export PATH="$scratch/fakebin:$PATH" RUNTIME_DIRECTORY="$scratch/run" FAKE_LOG="$scratch/log"

expect_status() {  # EXPECTED FAKE_KIOSK [ARGS...]
  local expected=$1 status=0
  : >"$FAKE_LOG"
  FAKE_KIOSK=$2 "$wrapper" "${@:3}" 2>"$scratch/stderr" || status=$?
  [[ $status == "$expected" ]] || fail "kiosk '$2' → mallet-kiosk exits $status, expected $expected"
}
expect_status 0 exit:0    # the operator's quit: systemd does not restart
expect_status 3 exit:3    # a failure: restarted
expect_status 2 exit:2
expect_status 134 signal:ABRT  # the watchdog's SIGABRT, a crash: 128 + signal
expect_status 139 signal:SEGV
[[ $(cat "$scratch/run/kiosk.status") == 139 ]] || fail "kiosk.status holds $(cat "$scratch/run/kiosk.status")"
expect_status 0 exit:0 --windowed --idle-after 5
[[ $(cat "$FAKE_LOG") == "run --windowed --idle-after 5" ]] || fail "the kiosk ran as: $(cat "$FAKE_LOG")"

# cage failing before the kiosk runs is a failure, never an operator's quit.
: >"$FAKE_LOG"
status=0
FAKE_CAGE=broken FAKE_KIOSK=exit:0 "$wrapper" 2>"$scratch/stderr" || status=$?
[[ $status != 0 ]] || fail "a cage that could not start gave status 0"
grep -q "cage ended" "$scratch/stderr" || fail "no line says cage ended first: $(cat "$scratch/stderr")"
[[ -s $FAKE_LOG ]] && fail "the kiosk ran although cage did not start"

# systemctl stop: SIGTERM to mallet-kiosk alone (KillMode=mixed) reaches the kiosk, which
# stops cleanly, and mallet-kiosk exits with its 0.
: >"$FAKE_LOG"
rm -f "$FAKE_LOG.waiting"
FAKE_KIOSK=term "$wrapper" 2>"$scratch/stderr" &
main=$!
for _ in $(seq 200); do [[ -f $FAKE_LOG.waiting ]] && break; sleep 0.05; done
[[ -f $FAKE_LOG.waiting ]] || fail "the stopping stand-in never started"
kill -TERM "$main"
status=0
wait "$main" || status=$?
[[ $status == 0 ]] || fail "after SIGTERM mallet-kiosk exits $status, expected the kiosk's clean 0"
grep -qx stopped "$FAKE_LOG" || fail "the kiosk did not get SIGTERM: $(cat "$FAKE_LOG")"

# systemctl reload: SIGHUP reaches the kiosk (not cage, not the wrapper).
: >"$FAKE_LOG"
rm -f "$FAKE_LOG.waiting"
FAKE_KIOSK=reload "$wrapper" 2>"$scratch/stderr" &
main=$!
for _ in $(seq 200); do [[ -f $FAKE_LOG.waiting ]] && break; sleep 0.05; done
[[ -f $FAKE_LOG.waiting ]] || fail "the reloading stand-in never started"
"$wrapper" --reload || fail "mallet-kiosk --reload failed"
status=0
wait "$main" || status=$?
[[ $status == 7 ]] || fail "after --reload mallet-kiosk exits $status, expected the kiosk's 7"
grep -qx reloaded "$FAKE_LOG" || fail "the kiosk did not get SIGHUP: $(cat "$FAKE_LOG")"
rm -f "$scratch/run/kiosk.pid"
"$wrapper" --reload 2>/dev/null && fail "--reload with no kiosk running succeeded"

if ((failures > 0)); then
  echo "package: $failures problem(s) with mallet-kiosk" >&2
  exit 1
fi
echo "package: mallet-kiosk passes the kiosk's exit status, SIGTERM and SIGHUP through cage"
