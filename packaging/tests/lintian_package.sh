#!/usr/bin/env bash
# Debian's own checker on the built packages, mallet and mallet-bench: no error and no warning
# (the tags overridden in debian/mallet.lintian-overrides say why there).
#   lintian_package.sh DEB_DIR
set -euo pipefail
shopt -s nullglob
debs=("$1"/mallet_*.deb "$1"/mallet-bench_*.deb)
((${#debs[@]} == 2)) || { echo "package: expected one mallet_*.deb and one mallet-bench_*.deb in $1" >&2; exit 1; }
if ! command -v lintian >/dev/null; then
  echo "package: lintian is not installed (packaging/install-deps.sh installs it)" >&2
  exit 1
fi
status=0
lintian --fail-on error,warning --display-level '>=warning' "${debs[@]}" || status=$?
if ((status != 0)); then
  echo "package: lintian found errors or warnings in ${debs[*]}" >&2
  exit 1
fi
# The overridden tags, for the record (each with its reason in debian/mallet.lintian-overrides).
lintian --display-level '>=info' --show-overrides "${debs[@]}" 2>/dev/null | grep '^O:' || true
echo "package: lintian: no error, no warning in ${debs[*]}"
