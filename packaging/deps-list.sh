#!/usr/bin/env bash
# The one reader of packaging/deps-*.txt: prints the packages the lists name for one Debian
# release, one per line, sorted, each once.
#   packaging/deps-list.sh [--release CODENAME] LIST...
# A list holds one package a line; `#` starts a comment. A line "bookworm: NAME" or
# "trixie: NAME" names a package of that release only (a library whose package name carries
# its soname, or a t64 rename, differs between Debian 12 and 13); other lines are every
# release's. The release is --release's, else this machine's (VERSION_CODENAME in
# /etc/os-release). A release no line names is refused: exit 2, one line saying which ones
# the lists know.
set -euo pipefail
release=
if [[ "${1:-}" == --release ]]; then
  release=${2:?--release needs a codename}
  shift 2
fi
if [[ -z "$release" ]]; then
  # shellcheck disable=SC1091
  release=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
fi
(($# > 0)) || { echo "deps-list: which lists? (packaging/deps-run.txt ...)" >&2; exit 2; }
known=$(sed -n -e 's/#.*//' -e 's/^[[:space:]]*\([a-z]*\):.*/\1/p' "$@" | sort -u | tr '\n' ' ')
if [[ -n "$known" && " $known" != *" $release "* ]]; then
  echo "deps-list: Debian '${release:-unknown}' is not a release the package lists know (${known% }):" \
    "add its lines to ${*}" >&2
  exit 2
fi
sed -e 's/#.*//' "$@" | awk -v release="$release" '
  { gsub(/[[:space:]]/, "") }
  $0 == "" { next }
  /:/ { split($0, part, ":"); if (part[1] == release) print part[2]; next }
  { print }' | sort -u
