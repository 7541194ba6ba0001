#!/usr/bin/env bash
# sandbox_run.sh from a tree under /tmp, where people clone something to try it: the package
# and the scratch folder it is given both under /tmp, which the sandbox replaces with a
# private one. It must still run the kiosk, from a folder it made under /var/tmp itself, and
# leave nothing there. Status 77 (skipped) where sandbox_run.sh cannot make namespaces.
#   sandbox_from_tmp.sh DEB_DIR
set -euo pipefail
here=$(dirname "${BASH_SOURCE[0]}")
tree=$(mktemp -d /tmp/mallet-checkout.XXXXXX)
trap 'rm -rf "$tree"' EXIT
mkdir -p "$tree/deb" "$tree/build"
cp "$1"/mallet_*_"$(dpkg --print-architecture)".deb "$tree/deb/"
status=0
output=$(bash "$here/sandbox_run.sh" "$tree/deb" "$tree/build/sandbox" 2>&1) || status=$?
echo "$output"
((status != 77)) || exit 77
if ((status != 0)); then
  echo "sandbox_from_tmp: sandbox_run.sh exits $status with its scratch under /tmp" >&2
  exit 1
fi
used=$(sed -n 's/^sandbox_run: .* under \/tmp, which the sandbox hides: using \(.*\)$/\1/p' <<<"$output")
[[ $used == /var/tmp/mallet-test.* ]] || { echo "sandbox_from_tmp: no scratch folder under /var/tmp named" >&2; exit 1; }
[[ ! -e $used ]] || { echo "sandbox_from_tmp: $used is left behind" >&2; exit 1; }
[[ ! -e $tree/build/sandbox ]] || { echo "sandbox_from_tmp: $tree/build/sandbox was written" >&2; exit 1; }
grep -q '^sandbox_run: the headless kiosk ran' <<<"$output" || { echo "sandbox_from_tmp: the kiosk did not run" >&2; exit 1; }
echo "sandbox_from_tmp: from a tree under /tmp the sandbox ran the kiosk from $used, and removed it"
