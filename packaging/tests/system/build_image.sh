#!/usr/bin/env bash
# The system test's disk: Debian as a museum installs it (mmdebstrap, Debian's own tool),
# Debian 12 ("bookworm", the default) or 13 ("trixie"), with the mallet package installed by
# dpkg over a base that holds exactly its Depends and what a booted test machine needs (a
# kernel, systemd, the guest agent, python3 for the emulated Wii Remote). The base is cached
# by its release and the hash of its package list, so a second run only unpacks it and
# installs the new .deb. The .deb must be built on the same release (its Depends name that
# release's libraries).
#   build_image.sh DEB CACHE_DIR OUT_DIR [SUITE]
# SUITE: bookworm or trixie (default: $SUITE, else bookworm).
# writes OUT_DIR/disk.raw (ext4, the root file system), OUT_DIR/vmlinuz, OUT_DIR/initrd.img.
set -euo pipefail
deb=$(realpath "$1") cache=$2 out=$3 suite=${4:-${SUITE:-bookworm}}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
case $suite in
bookworm | trixie) ;;
*) echo "image: unknown suite '$suite' (bookworm or trixie)" >&2; exit 2 ;;
esac
mkdir -p "$cache" "$out"

# What the machine needs besides the package: boot (systemd as init, udev, a kernel and its
# initramfs), the guest agent the test talks through, python3 for guest/wiimote_uhid.py.
infra=(systemd-sysv udev linux-image-amd64 qemu-guest-agent python3 kmod procps)
# The package's own Depends, alternatives reduced to their first choice, versions dropped.
mapfile -t depends < <(dpkg-deb -f "$deb" Depends | tr ',' '\n' | sed -e 's/|.*//' -e 's/(.*)//' -e 's/[[:space:]]//g' | grep -v '^$')
mapfile -t packages < <(printf '%s\n' "${infra[@]}" "${depends[@]}" | sort -u)
key=$( (printf 'suite %s\n' "$suite"; printf '%s\n' "${packages[@]}"; sed -n '/^# base-image-recipe/,$p' "$0") | sha256sum | cut -c1-16)
base=$cache/base-$suite-$key.tar
# base-image-recipe: everything below this line is part of the cache key.
if [[ ! -s $base ]]; then
  echo "image: building the $suite base ($key: ${#packages[@]} packages) with mmdebstrap"
  # The downloaded packages, kept per release for the next base (a new package list, a new
  # .deb's Depends); the folder of before the releases were two is bookworm's.
  archives=$cache/apt-archives-$suite
  if [[ $suite == bookworm && -d $cache/apt-archives && ! -e $archives ]]; then
    mv "$cache/apt-archives" "$archives"
  fi
  mkdir -p "$archives"
  # The host's apt sources (no mirror is named here): its sources.list and
  # sources.list.d/*.sources, each handed to mmdebstrap as a file of its own format. For
  # another release than the host's, each entry of the host's release is rewritten to the
  # other's (bookworm → trixie, bookworm-updates → trixie-updates, bookworm-security →
  # trixie-security; in one-line and deb822 files alike) and any other entry (a third party's
  # repository, named by its own suite) is left out.
  host_suite=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
  sources_dir=$(mktemp -d)
  trap 'rm -rf "$sources_dir"' EXIT
  source_args=()
  for file in /etc/apt/sources.list /etc/apt/sources.list.d/*.sources; do
    [[ -s $file ]] || continue
    derived=$sources_dir/host-$(basename "$file")
    [[ $file == */sources.list ]] && derived=$sources_dir/host.list
    python3 - "$file" "$derived" "${host_suite:-unknown}" "$suite" <<'PY'
import re, sys
path, out, host, suite = sys.argv[1:]
def renamed(s):
    if s == host or s.startswith(host + "-") or s.startswith(host + "/"):
        return suite + s[len(host):]
    return None
text = open(path).read()
kept = []
if host == suite:
    kept = [text.rstrip("\n")]
    text = kept[0]
elif path.endswith(".sources"):
    for paragraph in re.split(r"\n[ \t]*\n", text):
        lines = paragraph.splitlines()
        for i, line in enumerate(lines):
            field = re.match(r"(?i)suites:(.*)", line)
            if field:
                # a field's value may go on over lines that begin with a blank
                words, j = field.group(1).split(), i + 1
                while j < len(lines) and lines[j][:1] in (" ", "\t"):
                    words += lines[j].split()
                    j += 1
                words = [w for w in map(renamed, words) if w]
                if words:
                    kept.append("\n".join(lines[:i] + ["Suites: " + " ".join(words)] + lines[j:]))
                break
    text = "\n\n".join(kept)
else:
    for line in text.splitlines():
        entry = re.match(r"(\s*deb(?:-src)?\s+(?:\[[^\]]*\]\s+)?\S+\s+)(\S+)(.*)", line)
        if entry and renamed(entry.group(2)):
            kept.append(entry.group(1) + renamed(entry.group(2)) + entry.group(3))
    text = "\n".join(kept)
if kept:
    open(out, "w").write(text + "\n")
PY
    if [[ -s $derived ]]; then source_args+=("$derived"); fi
  done
  ((${#source_args[@]})) || { echo "image: no apt sources of Debian ${host_suite:-?} on this machine to take $suite's from (/etc/apt/sources.list*)" >&2; exit 1; }
  log=$cache/mmdebstrap-$suite.log
  mmdebstrap --variant=minbase --mode=root --format=tar \
      --include="$(IFS=,; echo "${packages[*]}")" \
      --skip=essential/unlink \
      --setup-hook='mkdir -p "$1"/var/cache/apt/archives/' \
      --setup-hook="sync-in '$archives' /var/cache/apt/archives/" \
      --customize-hook="sync-out /var/cache/apt/archives '$archives'" \
      --customize-hook='rm -f "$1"/var/cache/apt/archives/*.deb' \
      --customize-hook='echo mallet-vm > "$1"/etc/hostname' \
      --customize-hook='printf "/dev/vda / ext4 rw,errors=remount-ro 0 1\n" > "$1"/etc/fstab' \
      --customize-hook='mkdir -p "$1"/var/log/journal' \
      --customize-hook='passwd --root "$1" -d root' \
      "$suite" "$base.part" "${source_args[@]}" </dev/null >"$log" 2>&1 ||
    { tail -n 30 "$log" >&2
      echo "image: mmdebstrap failed (log: $log); a package it cannot find may be one of another release: was $(basename "$deb") built on Debian $suite?" >&2
      exit 1; }
  rm -rf "$sources_dir"
  trap - EXIT
  mv "$base.part" "$base"
else
  echo "image: $suite base $key cached ($base)"
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
kernel=$(basename "$(ls "$root"/boot/vmlinuz-*)")
cp "$root"/boot/vmlinuz-* "$out/vmlinuz"
cp "$root"/boot/initrd.img-* "$out/initrd.img"
rm -f "$out/disk.raw"
mke2fs -q -t ext4 -L root -d "$root" "$out/disk.raw" 4G
rm -rf "$root"
echo "image: Debian $suite, $out/disk.raw ($(du -h "$out/disk.raw" | cut -f1) used), kernel $kernel"
