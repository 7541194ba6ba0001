#!/usr/bin/env bash
# Installs every package Mallet needs to build, test and run, on Debian 12 ("bookworm") or
# 13 ("trixie"): the lists' lines for the release it finds (packaging/deps-list.sh).
# Idempotent and non-interactive: packages already present are left alone.
#   packaging/install-deps.sh            build + run-time packages (the kiosk's and the benchmarks')
#   packaging/install-deps.sh --runtime  the kiosk's run-time packages only
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

lists=("$here/deps-run.txt")
[[ "${1:-}" == "--runtime" ]] || lists+=("$here/deps-build.txt" "$here/deps-bench.txt")
# shellcheck disable=SC1091
release=$(. /etc/os-release 2>/dev/null && echo "${PRETTY_NAME:-an unknown system}: the lists' \"${VERSION_CODENAME:-?}\" lines")
echo "install-deps: found $release"
packages_text=$("$here/deps-list.sh" "${lists[@]}") || exit 1
mapfile -t packages <<<"$packages_text"

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: run as root (or install sudo): apt-get install ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
