#!/usr/bin/env bash
# The kiosk run from the package unpacked into a scratch root (`dpkg -x`: the installed
# tree without root rights): --version, a headless frame whose log names the scene under
# ROOT/etc/mallet, and proofs that the models come from ROOT/usr/share/mallet and the
# settings from ROOT/etc/mallet/mallet.toml — never from the source tree this binary was
# built from. Run outside the source tree, with no MALLET_DATA_DIR and no display. Then the
# benchmarks: `mallet bench` naming their package while only mallet is unpacked, and running
# mallet-bench from the same root once its package is unpacked beside.
#   run_installed.sh DEB_DIR SCRATCH VERSION [VAR=VALUE...]
# The VAR=VALUEs are set for mallet only (under ASan: the Vulkan driver's preload).
set -euo pipefail
dir=$1 scratch=$2 version=$3
shift 3
deb=$dir/mallet_${version}_$(dpkg --print-architecture).deb
rm -rf "$scratch"
mkdir -p "$scratch"
root=$scratch/root
dpkg -x "$deb" "$root"
cd "$scratch"
failures=0
fail() {
  echo "package: $*" >&2
  failures=$((failures + 1))
}
env_vars=("$@")
run() {  # ARGS...: mallet's output in $output, its status in $status
  status=0
  output=$(env -u MALLET_DATA_DIR -u DISPLAY -u WAYLAND_DISPLAY "${env_vars[@]}" "$root/usr/bin/mallet" "$@" 2>&1) ||
    status=$?
}

run --version
[[ $status == 0 && $output == *"$version"* ]] || fail "mallet --version: status $status: $output"

# One headless frame from the installed paths.
out=$scratch/out
run run --headless --seconds 0.3 --size 160x90 --out "$out"
[[ $status == 0 ]] || fail "mallet run --headless: status $status: $output"
for f in screenshot.png audio.wav log.txt; do
  [[ -s $out/$f ]] || fail "mallet run --headless wrote no $out/$f"
done
if [[ -f $out/log.txt ]]; then
  grep -qx "scene: $root/etc/mallet/scenes/percussion.toml" "$out/log.txt" ||
    fail "log.txt does not name the scene under $root/etc/mallet: $(cat "$out/log.txt")"
fi

# The models are the unpacked root's: without one, the kiosk stops naming that file.
model=$root/usr/share/mallet/models/wood_bar.glb
mv "$model" "$model.away"
run run --headless --seconds 0.1 --size 160x90 --out "$scratch/no-model"
[[ $status == 2 && $output == *"$model"* ]] ||
  fail "without $model: status $status (expected 2, naming it): $output"
mv "$model.away" "$model"

# The kiosk's settings are ROOT/etc/mallet/mallet.toml: a mistake there is reported.
settings=$root/etc/mallet/mallet.toml
cp "$settings" "$settings.orig"
printf 'no_such_setting = 1\n' | cat - "$settings.orig" >"$settings"
run run --headless --seconds 0.1 --size 160x90 --out "$scratch/bad-settings"
[[ $status == 2 && $output == *"$settings:1"* ]] ||
  fail "with a bad $settings: status $status (expected 2, naming it): $output"
mv "$settings.orig" "$settings"

# The udev rule the package ships is the one `mallet wiimote list` tells to install. The
# package has it in /lib/udev/rules.d on Debian 12 (dh_installudev), which is
# /usr/lib/udev/rules.d on its merged /usr, and in /usr/lib/udev/rules.d on Debian 13: the
# path the hint names.
rule_file=
for f in "$root/lib/udev/rules.d/70-mallet-wiimote.rules" "$root/usr/lib/udev/rules.d/70-mallet-wiimote.rules"; do
  [[ -f $f ]] && rule_file=$f
done
[[ -n $rule_file ]] || fail "the package has no /lib/udev/rules.d/70-mallet-wiimote.rules (nor /usr/lib/udev/rules.d/...)"
rule=$(grep -v '^#' "${rule_file:-/dev/null}" | grep -v '^$' || true)
[[ -n $rule ]] || fail "the packaged udev rule file holds no rule"
[[ $(wc -l <<<"$rule") == 1 ]] || fail "the udev rule file holds $(wc -l <<<"$rule") rules"
run wiimote list
if [[ $output == *"No Wii Remote found"* ]]; then
  [[ $output == *"$rule"* ]] || fail "mallet wiimote list does not print the packaged rule $rule: $output"
  [[ $output == *"/usr/lib/udev/rules.d/70-mallet-wiimote.rules"* ]] ||
    fail "mallet wiimote list does not name the packaged rule's file: $output"
else
  echo "package: a Wii Remote is connected: the hint is not printed, not compared"
fi

# The benchmarks are their own package. Without it, `mallet bench` names it in one line and
# exits 1 (PATH emptied: an installed mallet-bench elsewhere must not answer).
status=0
output=$(env -u MALLET_DATA_DIR -u DISPLAY PATH=/nonexistent "${env_vars[@]}" "$root/usr/bin/mallet" bench prediction 2>&1) ||
  status=$?
[[ $status == 1 && $(wc -l <<<"$output") == 1 && $output == *"install the Debian package mallet-bench"* ]] ||
  fail "mallet bench without mallet-bench: status $status (expected 1 and one line naming the package): $output"
# With it unpacked beside, `mallet bench` runs /usr/bin/mallet-bench: its help, its refusal of a
# bad flag (status 2), its scene found in the unpacked root, and a whole benchmark (1 s).
dpkg -x "$dir/mallet-bench_${version}_$(dpkg --print-architecture).deb" "$root"
run bench --help
[[ $status == 0 && $output == *"Usage: mallet bench"* && $output == *"latency"* && $output == *"soak"* ]] ||
  fail "mallet bench --help: status $status: $output"
run bench prediction --bogus
[[ $status == 2 && $output == *"--bogus"* ]] || fail "mallet bench prediction --bogus: status $status (expected 2): $output"
run bench prediction --help
[[ $status == 0 && $output == *"$root/etc/mallet/scenes/percussion.toml"* ]] ||
  fail "mallet bench prediction --help: status $status (its scene must default to $root's): $output"
run bench prediction
[[ $status == 0 && $output == *"contact prediction on"* ]] || fail "mallet bench prediction: status $status: $output"

if ((failures > 0)); then
  echo "package: $failures problem(s) running the kiosk unpacked in $root" >&2
  exit 1
fi
echo "package: the kiosk runs from $root with its settings from $root/etc/mallet, and mallet bench runs mallet-bench beside it"
