#!/usr/bin/env bash
# The package's system test: builds the Debian package, installs it into a Debian 12 or 13
# disk image made by mmdebstrap, boots that in QEMU with a display (virtio-vga), a sound card
# (Intel HDA into a WAV file), a USB mouse and keyboard and the guest agent, and checks each
# deployment scenario there (system_test.py lists them). One line per scenario, `ok` or
# `FAIL: why`, then the timings. Needs root (mmdebstrap, chroot), qemu-system-x86,
# qemu-utils, mmdebstrap and e2fsprogs (packaging/deps-build.txt).
#
#   packaging/tests/system/run.sh [--keep] [--only SCENARIO[,SCENARIO…]] [--suite bookworm|trixie]
#       [--deb-dir DIR] [--out DIR] [--cache DIR] [--accel auto|kvm|tcg] [--screens DIR]
#
#   --keep      keep the machine's disk (out/disk.qcow2) and image for a look afterwards
#   --only      run these scenarios (first-boot always runs first)
#   --suite     the guest's Debian: bookworm (12, the default) or trixie (13); the package
#               must be built on the same release (--deb-dir's, or this machine's when built here)
#   --deb-dir   take mallet_*.deb from DIR instead of building it (CTest passes the one
#               the package tests built)
#   --out       logs, screens, the WAV, the disk (default: build/system-test)
#   --cache     the base images and downloaded packages (default: /var/cache/mallet-system-test)
#   --accel     kvm where it works (auto tries it for 20 s), else tcg
#   --screens   also write the screens (vm-*.png) here, e.g. docs/screens
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
src=$(cd "$here/../../.." && pwd)
keep=0 only="" suite=bookworm deb_dir="" out="$src/build/system-test" cache=/var/cache/mallet-system-test accel=auto screens=""
while (($#)); do
  case $1 in
  --keep) keep=1 ;;
  --only) only=$2; shift ;;
  --suite) suite=$2; shift ;;
  --deb-dir) deb_dir=$2; shift ;;
  --out) out=$2; shift ;;
  --cache) cache=$2; shift ;;
  --accel) accel=$2; shift ;;
  --screens) screens=$2; shift ;;
  -h | --help) sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "system: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
case $suite in
bookworm | trixie) ;;
*) echo "system: unknown suite '$suite' (bookworm or trixie)" >&2; exit 2 ;;
esac
[[ $(id -u) -eq 0 ]] || { echo "system: run as root (mmdebstrap and the image's chroot need it)" >&2; exit 1; }
for tool in qemu-system-x86_64 qemu-img mmdebstrap mke2fs python3 dpkg-deb; do
  command -v "$tool" >/dev/null || { echo "system: $tool not found (packaging/install-deps.sh installs it)" >&2; exit 1; }
done
mkdir -p "$out"
out=$(cd "$out" && pwd)
begin=$(date +%s)
stamp() { echo "system: $1 ($(($(date +%s) - begin)) s so far)"; }

# 1. The package.
if [[ -z $deb_dir ]]; then
  host_suite=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
  if [[ $host_suite != "$suite" ]]; then
    echo "system: a package built here is Debian ${host_suite:-?}'s, not $suite's: build it on $suite" \
      "(tools/debian_root.sh --suite $suite) and pass its folder with --deb-dir" >&2
    exit 2
  fi
  deb_dir=$out/deb
  stamp "building the package (dpkg-buildpackage)"
  bash "$src/packaging/tests/build_package.sh" "$src" "$deb_dir"
fi
shopt -s nullglob
debs=("$deb_dir"/mallet_*.deb)
((${#debs[@]} == 1)) || { echo "system: expected one mallet_*.deb in $deb_dir, found ${#debs[@]}" >&2; exit 1; }
deb=${debs[0]}

# 2. A newer build of the same package, for the update scenario: the same files under a
#    higher version, as the next release would arrive.
newer_dir=$here/guest/newer
work=$out/work
rm -rf "$work" && mkdir -p "$work"
dpkg-deb -R "$deb" "$work/newer"
version=$(dpkg-deb -f "$deb" Version)
sed -i "s/^Version: .*/Version: ${version}+update1/" "$work/newer/DEBIAN/control"
mkdir -p "$work/guest-newer"
dpkg-deb -Zgzip -b "$work/newer" "$work/guest-newer/mallet_${version}+update1_$(dpkg --print-architecture).deb" >/dev/null
rm -rf "$work/newer"

# 3. The image (the base cached by its package list).
stamp "making the disk image (Debian $suite)"
GUEST_EXTRA="$work/guest-newer" bash "$here/build_image.sh" "$deb" "$cache" "$out/image" "$suite"

# 4. kvm where it works: a kernel that prints its banner within 20 s. On some machines
#    /dev/kvm exists but a guest hangs in it, so the probe is never waited for: it is killed
#    and left behind.
if [[ $accel == auto ]]; then
  accel=tcg
  if [[ -w /dev/kvm ]]; then
    qemu-system-x86_64 -accel kvm -m 256 -display none -nic none -no-reboot \
      -kernel "$out/image/vmlinuz" -append "console=ttyS0 panic=-1" -serial "file:$work/kvm-probe.log" \
      >/dev/null 2>&1 &
    probe=$!
    for _ in $(seq 20); do
      grep -q 'Linux version' "$work/kvm-probe.log" 2>/dev/null && { accel=kvm; break; }
      sleep 1
    done
    kill -KILL "$probe" 2>/dev/null || true
    disown "$probe" 2>/dev/null || true
  fi
  echo "system: accelerator $accel"
fi

# 5. The machine and its scenarios.
stamp "booting the image"
rm -f "$out/disk.qcow2" "$out/audio.wav" "$out/console.log" "$out/qemu.log"
args=(--image "$out/image" --out "$out" --accel "$accel" --suite "$suite" --reference "$here/first-boot.signature.json")
[[ -n $only ]] && args+=(--only "$only")
[[ -n $screens ]] && args+=(--screens "$screens")
status=0
python3 "$here/system_test.py" "${args[@]}" || status=$?
stamp "done"
if ((keep == 0)); then
  rm -rf "$out/disk.qcow2" "$out/image" "$work" "$out"/*.ppm
else
  echo "system: kept $out (disk.qcow2 over image/disk.raw; console.log, qemu.log, audio.wav)"
fi
exit "$status"
