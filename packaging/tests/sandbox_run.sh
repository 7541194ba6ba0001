#!/usr/bin/env bash
# The kiosk inside mallet.service's sandbox, as far as it can be built without systemd: a
# private network namespace (PrivateNetwork=), a private mount namespace with the whole file
# system read-only (ProtectSystem=strict) but a private /tmp (PrivateTmp=), /proc showing
# only processes, and only this user's (ProcSubset=pid, ProtectProc=invisible), no new
# privileges and an empty capability bounding set (NoNewPrivileges=, CapabilityBoundingSet=).
# It runs the packaged kiosk (unpacked with dpkg -x) headless there and expects its three
# files. Needs root for the namespaces; where they cannot be made (a container without
# CAP_SYS_ADMIN) it says so and is skipped (status 77), since nothing would have been tried.
# The kiosk must be reachable inside the sandbox, whose /tmp is private: a SCRATCH under /tmp
# (a build tree in a checkout under /tmp) is replaced by a folder made under /var/tmp, removed
# at the end.
#   sandbox_run.sh DEB_DIR SCRATCH
set -euo pipefail
dir=$1 scratch=$2
case $(realpath -m "$scratch") in
/tmp | /tmp/*)
  scratch=$(mktemp -d /var/tmp/mallet-test.XXXXXX)
  trap 'rm -rf "$scratch"' EXIT
  echo "sandbox_run: $2 is under /tmp, which the sandbox hides: using $scratch"
  ;;
esac
deb=$(ls "$dir"/mallet_*_"$(dpkg --print-architecture)".deb | head -n 1)
rm -rf "$scratch"
mkdir -p "$scratch"
dpkg -x "$deb" "$scratch/root"
mallet=$scratch/root/usr/bin/mallet
if ! unshare --net --mount --pid --fork true 2>/dev/null; then
  echo "sandbox_run: cannot make namespaces here (unshare refused): nothing tried" >&2
  exit 77
fi
inner=$scratch/inner.sh
cat >"$inner" <<'INNER'
set -euo pipefail
mallet=$1
mount --bind -o remount,ro /
mount -t tmpfs tmpfs /tmp
mount -t proc -o subset=pid,hidepid=invisible proc /proc
if touch /usr/.mallet-sandbox-probe 2>/dev/null; then echo "sandbox_run: / is still writable" >&2; exit 1; fi
[[ ! -e /proc/cpuinfo ]] || { echo "sandbox_run: /proc is not restricted" >&2; exit 1; }
# /proc/self/net/dev: two header lines, then one per interface; the namespace has lo alone.
(($(wc -l </proc/self/net/dev) == 3)) || { echo "sandbox_run: a network interface besides lo" >&2; exit 1; }
mkdir -p /tmp/state /tmp/cache /tmp/out /tmp/runtime && chmod 700 /tmp/runtime
env -u MALLET_DATA_DIR -u DISPLAY -u WAYLAND_DISPLAY MALLET_STATE_DIR=/tmp/state XDG_CACHE_HOME=/tmp/cache XDG_RUNTIME_DIR=/tmp/runtime \
  setpriv --no-new-privs --bounding-set=-all --inh-caps=-all \
  "$mallet" run --headless --seconds 1 --size 160x90 --out /tmp/out
for f in screenshot.png audio.wav log.txt; do
  [[ -s /tmp/out/$f ]] || { echo "sandbox_run: the kiosk wrote no $f" >&2; exit 1; }
done
grep -q '^strike t=' /tmp/out/log.txt || { echo "sandbox_run: no strike in the log" >&2; exit 1; }
echo "sandbox_run: the headless kiosk ran and struck with no network, a read-only system, a pid-only /proc, no privileges"
INNER
unshare --net --mount --pid --fork --propagation private bash "$inner" "$mallet"
