#!/usr/bin/env bash
# tools/debian_root.sh: a command run in a fresh clone of this checkout's HEAD inside a Debian
# root of another release (Debian 13 from a Debian 12 machine, or the reverse), as a newcomer
# on that release would run it. The root is made by mmdebstrap the first time (the buildd
# variant: a compiler and apt, nothing of Mallet's), then kept; each run clones HEAD afresh
# into ROOT/work/NAME (mallet unless --clone says) and runs COMMAND there with bash, as root, in a mount namespace of its
# own (/proc, /sys, /dev and a fresh /tmp, gone when it ends). Needs root and mmdebstrap.
#
#   tools/debian_root.sh [--suite trixie] [--root DIR] [--clone NAME] [--keep-clone] -- COMMAND
#   tools/debian_root.sh --help
#
#   --suite       the release (default trixie)
#   --root        where the root lives (default /var/tmp/mallet-root-SUITE)
#   --clone       the clone's folder under ROOT/work (default mallet): two at once in one root
#   --keep-clone  run in the clone the last run left (after a first command built in it)
#
# Example: the README's two commands on Debian 13
#   tools/debian_root.sh -- 'packaging/install-deps.sh && cmake --workflow --preset release && build/release/mallet run'
#   tools/debian_root.sh --keep-clone -- 'cmake --workflow --preset check'
set -euo pipefail
suite=trixie root= keep=0 clone=mallet
while (($#)); do
  case "$1" in
    --suite) suite=$2; shift ;;
    --root) root=$2; shift ;;
    --clone) clone=$2; shift ;;
    --keep-clone) keep=1 ;;
    --) shift; break ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "debian_root: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
(($# == 1)) || { echo "debian_root: one COMMAND after --" >&2; exit 2; }
[[ $(id -u) -eq 0 ]] || { echo "debian_root: needs root (mmdebstrap, chroot, mounts)" >&2; exit 1; }
root=${root:-/var/tmp/mallet-root-$suite}
checkout=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if [[ ! -x "$root/usr/bin/apt-get" ]]; then
  command -v mmdebstrap >/dev/null || { echo "debian_root: needs mmdebstrap (apt-get install mmdebstrap)" >&2; exit 1; }
  echo "debian_root: making a Debian $suite root in $root (mmdebstrap, the buildd variant)"
  mmdebstrap --variant=buildd --include=ca-certificates,git,locales "$suite" "$root"
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"  # apt inside reaches the same archive
if ((!keep)) || [[ ! -d "$root/work/$clone/.git" ]]; then
  rm -rf "${root:?}/work/$clone"
  mkdir -p "$root/work"
  git clone -q "$checkout" "$root/work/$clone"
  echo "debian_root: cloned $(git -C "$checkout" rev-parse --short HEAD) into $root/work/$clone"
fi
# shellcheck disable=SC2016
exec unshare --mount --propagation private env ROOT="$root" CLONE="$clone" COMMAND="$1" bash -c '
  set -e
  mount --rbind /dev "$ROOT/dev"
  mount -t proc proc "$ROOT/proc"
  mount -t sysfs sysfs "$ROOT/sys"
  mount -t tmpfs tmpfs "$ROOT/tmp"
  exec chroot "$ROOT" env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 TERM=dumb bash -c "cd /work/$CLONE && $COMMAND"'
