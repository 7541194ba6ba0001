#!/usr/bin/env bash
# Builds the .deb from a build folder into a fresh scratch folder, as the README says
# (cpack -G DEB), and leaves exactly one mallet_*.deb there for the other package tests.
#   build_package.sh CPACK BUILD_DIR OUT_DIR
set -euo pipefail
cpack=$1 build=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
"$cpack" --config "$build/CPackConfig.cmake" -G DEB -B "$out"
shopt -s nullglob
debs=("$out"/mallet_*.deb)
if ((${#debs[@]} != 1)); then
  echo "package: expected one mallet_*.deb in $out, found ${#debs[@]}" >&2
  exit 1
fi
echo "package: built ${debs[0]}"
