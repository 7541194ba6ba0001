#!/usr/bin/env bash
# Builds the Debian package as the operators' guide says (`dpkg-buildpackage -us -uc -b`),
# from a copy of the source tree (the build writes debian/mallet/, obj-*/ and ../*.deb, never
# into the checkout), and leaves exactly one mallet_*.deb (the kiosk) and one mallet-bench_*.deb
# (the benchmarks) in OUT_DIR for the other package tests. A full release build of the product, with every core (-j: dh passes ninja -j1
# without it): minutes on a small machine.
#
# The same code as a release build, with less debug information: `-g1` (line tables, which a
# backtrace needs) appended to dpkg-buildflags' `-g`, and no -dbgsym package (`noddebs`). GCC's
# debug level never changes the code it generates; the two builds' `mallet` had the same
# .text, 2,758,255 bytes, differing only in 300 string addresses one byte apart (their trees'
# paths differ by a character). It took 211 s here instead of 304 s: the 87 MB of full debug
# information, and the 46 MB dbgsym package xz-compressed, were most of the difference.
#   build_package.sh SOURCE_DIR OUT_DIR
set -euo pipefail
src=$1 out=$2
export DEB_BUILD_OPTIONS="${DEB_BUILD_OPTIONS:+$DEB_BUILD_OPTIONS }noddebs"
export DEB_CXXFLAGS_APPEND="${DEB_CXXFLAGS_APPEND:+$DEB_CXXFLAGS_APPEND }-g1"
rm -rf "$out"
mkdir -p "$out/src"
tar -C "$src" --exclude=./build --exclude=./.git --exclude='./obj-*' --exclude=./debian/mallet \
  --exclude=./debian/mallet-bench --exclude=./debian/tmp --exclude=./debian/.debhelper --exclude=./debian/files --exclude='./debian/*.substvars' \
  --exclude='./debian/*debhelper*' -cf - . | tar -C "$out/src" -xf -
if ! (cd "$out/src" && dpkg-buildpackage -us -uc -b -j"$(nproc)") >"$out/build.log" 2>&1; then
  tail -n 60 "$out/build.log" >&2
  echo "package: dpkg-buildpackage failed (whole log: $out/build.log)" >&2
  exit 1
fi
shopt -s nullglob
for name in mallet mallet-bench; do
  debs=("$out/${name}"_*.deb)
  if ((${#debs[@]} != 1)); then
    echo "package: expected one ${name}_*.deb in $out, found ${#debs[@]}" >&2
    exit 1
  fi
  echo "package: built ${debs[0]}"
done
