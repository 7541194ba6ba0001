#!/usr/bin/env bash
# Builds the Debian package as the operators' guide says (`dpkg-buildpackage -us -uc -b`),
# from a copy of the source tree (the build writes debian/mallet/, obj-*/ and ../*.deb, never
# into the checkout), and leaves exactly one mallet_*.deb in OUT_DIR for the other package
# tests. A full release build of the product, with every core (-j: dh passes ninja -j1
# without it): minutes on a small machine.
#   build_package.sh SOURCE_DIR OUT_DIR
set -euo pipefail
src=$1 out=$2
rm -rf "$out"
mkdir -p "$out/src"
tar -C "$src" --exclude=./build --exclude=./.git --exclude='./obj-*' --exclude=./debian/mallet \
  --exclude=./debian/.debhelper --exclude=./debian/files --exclude='./debian/*.substvars' \
  --exclude='./debian/*debhelper*' -cf - . | tar -C "$out/src" -xf -
if ! (cd "$out/src" && dpkg-buildpackage -us -uc -b -j"$(nproc)") >"$out/build.log" 2>&1; then
  tail -n 60 "$out/build.log" >&2
  echo "package: dpkg-buildpackage failed (whole log: $out/build.log)" >&2
  exit 1
fi
shopt -s nullglob
debs=("$out"/mallet_*.deb)
if ((${#debs[@]} != 1)); then
  echo "package: expected one mallet_*.deb in $out, found ${#debs[@]}" >&2
  exit 1
fi
echo "package: built ${debs[0]}"
