#!/usr/bin/env bash
# The system test's disk: Debian 12 as a museum installs it (mmdebstrap, Debian's own tool),
# with the mallet package installed by dpkg over a base that holds exactly its Depends and
# what a booted test machine needs (a kernel, systemd, the guest agent, python3 for the
# emulated Wii Remote). The base is cached by the hash of its package list, so a second run
# only unpacks it and installs the new .deb.
#   build_image.sh DEB CACHE_DIR OUT_DIR
# writes OUT_DIR/disk.raw (ext4, the root file system), OUT_DIR/vmlinuz, OUT_DIR/initrd.img.
set -euo pipefail
deb=$(realpath "$1") cache=$2 out=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$cache" "$out"

# What the machine needs besides the package: boot (systemd as init, udev, a kernel and its
# initramfs), the guest agent the test talks through, python3 for guest/wiimote_uhid.py.
infra=(systemd-sysv udev linux-image-amd64 qemu-guest-agent python3 kmod procps)
# The package's own Depends, alternatives reduced to their first choice, versions dropped.
mapfile -t depends < <(dpkg-deb -f "$deb" Depends | tr ',' '\n' | sed -e 's/|.*//' -e 's/(.*)//' -e 's/[[:space:]]//g' | grep -v '^$')
mapfile -t packages < <(printf '%s\n' "${infra[@]}" "${depends[@]}" | sort -u)
key=$( (printf '%s\n' "${packages[@]}"; sed -n '/^# base-image-recipe/,$p' "$0") | sha256sum | cut -c1-16)
base=$cache/base-$key.tar
# base-image-recipe: everything below this line is part of the cache key.
if [[ ! -s $base ]]; then
  echo "image: building the base ($key: ${#packages[@]} packages) with mmdebstrap"
  mkdir -p "$cache/apt-archives"
  # The host's apt sources, read from standard input (no mirror is named here).
  sources=$(cat /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null || true)
  [[ -n $sources ]] || { echo "image: no apt sources on this machine (/etc/apt/sources.list*)" >&2; exit 1; }
  mmdebstrap --variant=minbase --mode=root --format=tar \
      --include="$(IFS=,; echo "${packages[*]}")" \
      --skip=essential/unlink \
      --setup-hook='mkdir -p "$1"/var/cache/apt/archives/' \
      --setup-hook="sync-in '$cache/apt-archives' /var/cache/apt/archives/" \
      --customize-hook="sync-out /var/cache/apt/archives '$cache/apt-archives'" \
      --customize-hook='rm -f "$1"/var/cache/apt/archives/*.deb' \
      --customize-hook='echo mallet-vm > "$1"/etc/hostname' \
      --customize-hook='printf "/dev/vda / ext4 rw,errors=remount-ro 0 1\n" > "$1"/etc/fstab' \
      --customize-hook='mkdir -p "$1"/var/log/journal' \
      --customize-hook='passwd --root "$1" -d root' \
      bookworm "$base.part" - <<<"$sources" >"$cache/mmdebstrap.log" 2>&1 ||
    { tail -n 30 "$cache/mmdebstrap.log" >&2; echo "image: mmdebstrap failed (log: $cache/mmdebstrap.log)" >&2; exit 1; }
  mv "$base.part" "$base"
else
  echo "image: base $key cached ($base)"
fi

root=$out/root
rm -rf "$root"
mkdir -p "$root"
tar -C "$root" -xf "$base"
# The package, as `apt install ./mallet_*.deb` would put it on a machine that has its
# Depends: dpkg in the image (its postinst makes the user and enables the unit).
cp "$deb" "$root/tmp/mallet.deb"
mount -t proc proc "$root/proc"
trap 'umount "$root/proc" 2>/dev/null || true' EXIT
chroot "$root" dpkg -i /tmp/mallet.deb >"$out/dpkg.log" 2>&1 ||
  { cat "$out/dpkg.log" >&2; echo "image: dpkg -i mallet.deb failed in the image" >&2; exit 1; }
umount "$root/proc"
trap - EXIT
rm -f "$root/tmp/mallet.deb"
# The test's own tools in the guest (not part of any museum machine).
mkdir -p "$root/opt/mallet-test"
cp -r "$here/guest/." "$root/opt/mallet-test/" 2>/dev/null || true
# GUEST_EXTRA: a folder of more test files (run.sh: the newer package for the update).
if [[ -n ${GUEST_EXTRA:-} ]]; then
  mkdir -p "$root/opt/mallet-test/newer"
  cp -r "$GUEST_EXTRA/." "$root/opt/mallet-test/newer/"
fi
cp "$root"/boot/vmlinuz-* "$out/vmlinuz"
cp "$root"/boot/initrd.img-* "$out/initrd.img"
rm -f "$out/disk.raw"
mke2fs -q -t ext4 -L root -d "$root" "$out/disk.raw" 4G
rm -rf "$root"
echo "image: $out/disk.raw ($(du -h "$out/disk.raw" | cut -f1) used), kernel $(basename "$(ls "$out"/vmlinuz)")"
