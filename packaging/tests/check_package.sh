#!/usr/bin/env bash
# The .debs that dpkg-buildpackage built, looked at as dpkg sees them. The kiosk's, mallet: its
# files and their modes, its control fields (Depends: every package of packaging/deps-run.txt
# for the release it is built on,
# and no library only the benchmarks use), its conffiles (every file under /etc), its
# maintainer scripts (run against stubs: they must survive a machine with no running systemd or
# udev) and its systemd unit. The benchmarks', mallet-bench: its files, and Depends on this
# very mallet and on every package of packaging/deps-bench.txt.
#   check_package.sh DEB_DIR SOURCE_DIR VERSION
set -euo pipefail
dir=$1 src=$2 version=$3
arch=$(dpkg --print-architecture)
deb=$dir/mallet_${version}_${arch}.deb
if [[ ! -f $deb ]]; then
  echo "package: no $deb (the name must be mallet_VERSION_ARCH.deb); $dir holds: $(ls "$dir")" >&2
  exit 1
fi
failures=0
fail() {
  echo "package: $*" >&2
  failures=$((failures + 1))
}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# --- Files -------------------------------------------------------------------------------
declare -A mode owner
while read -r perms who path; do
  path=${path#.}
  [[ $perms == d* ]] && continue
  mode[$path]=$perms
  owner[$path]=$who
done < <(dpkg-deb -c "$deb" | awk '{print $1, $2, $6}')

expect_file() {  # PATH [MODE]
  if [[ -z ${mode[$1]+x} ]]; then
    fail "missing $1"
  elif [[ -n ${2:-} && ${mode[$1]} != "$2" ]]; then
    fail "$1 has mode ${mode[$1]}, expected $2"
  fi
}
# The udev rule and the units: under /lib on Debian 12 (its debhelper's places), under /usr/lib
# on Debian 13 (udev's udevdir moved there, and debian/rules runs dh_movetousr). Either is
# taken, exactly one of the two must be there; its path is in located[NAME].
declare -A located
expect_lib_file() {  # NAME (lib/... without the leading /) MODE
  local at=()
  [[ -n ${mode[/$1]+x} ]] && at+=("/$1")
  [[ -n ${mode[/usr/$1]+x} ]] && at+=("/usr/$1")
  if ((${#at[@]} == 0)); then
    fail "missing /$1 (nor /usr/$1)"
  elif ((${#at[@]} == 2)); then
    fail "both /$1 and /usr/$1"
  else
    located[$1]=${at[0]}
    expect_file "${at[0]}" "$2"
  fi
}
expect_file /usr/bin/mallet -rwxr-xr-x
expect_file /usr/libexec/mallet/mallet-session -rwxr-xr-x
expect_lib_file lib/udev/rules.d/70-mallet-wiimote.rules -rw-r--r--
expect_lib_file lib/systemd/system/mallet.service -rw-r--r--
expect_lib_file lib/systemd/system/mallet-session.service -rw-r--r--
expect_file /etc/pam.d/mallet -rw-r--r--
expect_file /usr/share/man/man1/mallet.1.gz -rw-r--r--
expect_file /usr/share/doc/mallet/copyright -rw-r--r--
mapfile -t models < <(cd "$src/models" && find . -name '*.glb' -printf '%P\n' | sort)
mapfile -t shaders < <(cd "$src/shaders" && find . -type f -printf '%P\n' | sort)
mapfile -t configs < <(cd "$src/config" && find . -type f -printf '%P\n' | sort)
((${#models[@]} > 0 && ${#shaders[@]} > 0 && ${#configs[@]} > 0)) || fail "the source tree's models/shaders/config look empty"
for f in "${models[@]}"; do expect_file "/usr/share/mallet/models/$f" -rw-r--r--; done
for f in "${shaders[@]}"; do expect_file "/usr/share/mallet/shaders/$f" -rw-r--r--; done
for f in "${configs[@]}"; do
  expect_file "/usr/share/mallet/config/$f" -rw-r--r--
  expect_file "/etc/mallet/$f" -rw-r--r--
done
# The visitor languages' catalogues (po/LINGUAS), where gettext looks for them.
mapfile -t languages < <(grep -E '^[a-z]' "$src/po/LINGUAS")
((${#languages[@]} > 0)) || fail "po/LINGUAS names no language"
for l in "${languages[@]}"; do expect_file "/usr/share/locale/$l/LC_MESSAGES/mallet.mo" -rw-r--r--; done
for f in /etc/mallet/mallet.toml /etc/mallet/materials.toml /etc/mallet/instruments.toml \
  /etc/mallet/scenes/percussion.toml /etc/mallet/trajectories/demo.csv; do
  expect_file "$f"
done
for path in "${!mode[@]}"; do
  [[ ${owner[$path]} == root/root ]] || fail "$path is owned by ${owner[$path]}, not root/root"
  case $path in
  /usr/bin/mallet | /usr/libexec/mallet/* | /usr/share/mallet/* | /etc/mallet/* | /etc/pam.d/mallet | \
    /lib/udev/rules.d/70-mallet-wiimote.rules | /lib/systemd/system/mallet.service | \
    /lib/systemd/system/mallet-session.service | \
    /usr/lib/udev/rules.d/70-mallet-wiimote.rules | /usr/lib/systemd/system/mallet.service | \
    /usr/lib/systemd/system/mallet-session.service | \
    /usr/share/man/man1/mallet.1.gz | /usr/share/doc/mallet/* | /usr/share/lintian/overrides/mallet | \
    /usr/share/locale/*/LC_MESSAGES/mallet.mo) ;;
  *) fail "unexpected file $path" ;;
  esac
done

# The data are the source tree's, byte for byte.
dpkg-deb -x "$deb" "$work/root"
diff -r "$src/config" "$work/root/etc/mallet" >&2 || fail "/etc/mallet differs from config/"
diff -r "$src/config" "$work/root/usr/share/mallet/config" >&2 || fail "/usr/share/mallet/config differs from config/"
for f in "${models[@]}"; do
  cmp -s "$src/models/$f" "$work/root/usr/share/mallet/models/$f" || fail "models/$f differs"
done

# --- Control fields ----------------------------------------------------------------------
field() { dpkg-deb -f "$deb" "$1"; }
[[ $(field Package) == mallet ]] || fail "Package: $(field Package)"
[[ $(field Version) == "$version" ]] || fail "Version: $(field Version), expected $version"
[[ $(field Architecture) == "$arch" ]] || fail "Architecture: $(field Architecture), expected $arch"
[[ $(field Maintainer) =~ ^[^\<\>]+\ \<[^\<\>@\ ]+@[^\<\>\ ]+\>$ ]] || fail "Maintainer is not 'Name <address>': $(field Maintainer)"
description=$(field Description)
synopsis=$(head -n 1 <<<"$description")
[[ -n ${synopsis// /} ]] || fail "Description has no synopsis"
(($(wc -l <<<"$description") >= 3)) || fail "Description has no extended description: $description"
declare -A depends
IFS=',' read -ra items <<<"$(field Depends)"
for item in "${items[@]}"; do
  name=${item%%(*}
  name=${name// /}
  depends[$name]=1
done
mapfile -t wanted < <("$src/packaging/deps-list.sh" "$src/packaging/deps-run.txt")
((${#wanted[@]} > 5)) || fail "deps-run.txt read as ${#wanted[@]} packages"
for p in "${wanted[@]}"; do
  [[ -n ${depends[$p]+x} ]] || fail "Depends lacks $p (from deps-run.txt): $(field Depends)"
done
# The kiosk carries nothing only a benchmark uses (the package mallet-bench does).
for name in "${!depends[@]}"; do
  case $name in
  libjack* | libxtst* | libstk*) fail "Depends names $name, which only the benchmarks use: $(field Depends)" ;;
  esac
done

# --- Conffiles: exactly the files under /etc ---------------------------------------------
dpkg-deb -e "$deb" "$work/control"
diff <(sort "$work/control/conffiles") <(printf '%s\n' "${!mode[@]}" | grep '^/etc/' | sort) >&2 ||
  fail "conffiles is not the list of files under /etc"
grep -qx /etc/mallet/mallet.toml "$work/control/conffiles" || fail "/etc/mallet/mallet.toml is not a conffile"

# --- Maintainer scripts, against stubs ---------------------------------------------------
# Every command they may run is a stub logging its arguments; systemctl and udevadm fail,
# as where systemd or udev is not running: the scripts must still succeed. Nothing on this
# machine is touched (no purge: it removes /var/lib/mallet).
mkdir -p "$work/stubs"
stub() {  # NAME SHELL-CODE
  printf '#!/bin/sh\necho "%s $*" >> "%s"\n%s\n' "$1" "$work/calls" "$2" >"$work/stubs/$1"
  chmod +x "$work/stubs/$1"
}
stub adduser 'exit 0'
stub deb-systemd-helper 'exit 0'
stub deb-systemd-invoke 'exit 0'
stub systemctl 'exit 1'
stub udevadm 'exit 1'
# shellcheck disable=SC2016 # the stub's own $1
stub getent '[ "$1" = passwd ] && exit 2; exit 0'  # no user mallet yet; every group exists
for script in postinst prerm postrm; do
  [[ -x $work/control/$script ]] || fail "no executable $script"
  [[ $(head -n 1 "$work/control/$script") == '#!/bin/sh' ]] || fail "$script is not a /bin/sh script"
  sh -n "$work/control/$script" || fail "$script: syntax error"
done
run_script() {  # SCRIPT ARGS...
  PATH="$work/stubs:$PATH" "$work/control/$1" "${@:2}" >>"$work/script-output" 2>&1 ||
    fail "$* exits $? where systemd and udev are not running: $(cat "$work/script-output")"
}
: >"$work/calls"
run_script postinst configure ""
grep -q '^adduser --system --group --home /var/lib/mallet mallet$' "$work/calls" || fail "postinst made no system user"
grep -q '^adduser --quiet mallet audio$' "$work/calls" || fail "postinst did not add mallet to audio"
grep -q '^deb-systemd-helper enable mallet.service$' "$work/calls" || fail "postinst did not enable mallet.service"
if [[ -d /run/systemd/system ]]; then
  grep -q '^systemctl.* daemon-reload$' "$work/calls" || fail "postinst did not reload systemd"
elif grep -q '^systemctl' "$work/calls"; then
  fail "postinst called systemctl with no systemd running"
fi
if [[ -d /run/udev ]]; then
  grep -q '^udevadm control --reload-rules$' "$work/calls" || fail "postinst did not reload the udev rules"
  grep -q '^udevadm trigger' "$work/calls" || fail "postinst did not trigger udev"
fi
run_script postinst configure 0.0.1
run_script prerm remove
run_script prerm upgrade 0.0.1
run_script postrm remove
for command in 'daemon-reload' 'deb-systemd-helper enable' 'udevadm control --reload-rules' 'udevadm trigger'; do
  grep -q "$command" "$work/control/postinst" || fail "postinst never runs '$command'"
done
# An update: nothing stops the kiosk before the postinst, whose try-restart then brings it
# back on the new files (a stop in the preinst left try-restart nothing to restart: the kiosk
# stayed dark after every update, found by the VM system test).
if [[ -e $work/control/preinst ]] && grep -q 'deb-systemd-invoke stop' "$work/control/preinst"; then
  fail "preinst stops the units on upgrade; postinst's try-restart would then leave the kiosk stopped"
fi
grep -q 'deb-systemd-invoke try-restart mallet.service' "$work/control/postinst" ||
  fail "postinst does not restart the kiosk after an update"

# --- The units ------------------------------------------------------------------------------
# mallet.service is the kiosk itself (its main process, so that its sd_notify and its lines
# are the unit's); mallet-session.service is its display, the seat's session with cage.
unit=$work/root${located[lib/systemd/system/mallet.service]:-/lib/systemd/system/mallet.service}
session=$work/root${located[lib/systemd/system/mallet-session.service]:-/lib/systemd/system/mallet-session.service}
setting() { sed -n "s/^$1=//p" "${2:-$unit}"; }
[[ $(setting ExecStart) == "/usr/bin/mallet run" ]] || fail "ExecStart=$(setting ExecStart)"
[[ $(setting ExecStartPre) == "/usr/libexec/mallet/mallet-session --wait 120" ]] ||
  fail "ExecStartPre=$(setting ExecStartPre) (the kiosk waits for its display)"
[[ $(setting Restart) == always ]] || fail "Restart=$(setting Restart)"
if ! [[ $(setting RestartSec) =~ ^[0-9]+$ ]] || (($(setting RestartSec) < 2)); then
  fail "RestartSec=$(setting RestartSec), expected at least 2"
fi
[[ $(setting StartLimitIntervalSec) == 0 ]] || fail "StartLimitIntervalSec=$(setting StartLimitIntervalSec)"
[[ $(setting RestartPreventExitStatus) == 0 ]] || fail "RestartPreventExitStatus=$(setting RestartPreventExitStatus)"
[[ $(setting WatchdogSec) =~ ^[1-9][0-9]*$ ]] || fail "WatchdogSec=$(setting WatchdogSec)"
[[ $(setting NotifyAccess) == main ]] || fail "NotifyAccess=$(setting NotifyAccess) (the kiosk is the main process)"
[[ $(setting User) == mallet ]] || fail "User=$(setting User)"
[[ -z $(setting PAMName) ]] || fail "mallet.service has PAMName=: its processes would leave the unit's cgroup"
[[ $(setting Wants) == mallet-session.service ]] || fail "Wants=$(setting Wants)"
[[ $(setting JoinsNamespaceOf) == mallet-session.service ]] || fail "JoinsNamespaceOf=$(setting JoinsNamespaceOf)"
[[ $(setting WantedBy) == graphical.target ]] || fail "WantedBy=$(setting WantedBy)"
[[ $(setting ExecStart "$session") == /usr/libexec/mallet/mallet-session ]] ||
  fail "mallet-session.service: ExecStart=$(setting ExecStart "$session")"
[[ $(setting PAMName "$session") == mallet ]] ||
  fail "mallet-session.service: PAMName=$(setting PAMName "$session") (the package ships /etc/pam.d/mallet)"
[[ $(setting TTYPath "$session") == /dev/tty1 ]] || fail "mallet-session.service: TTYPath=$(setting TTYPath "$session")"
[[ $(setting BindsTo "$session") == mallet.service ]] ||
  fail "mallet-session.service: BindsTo=$(setting BindsTo "$session") (it stops with the kiosk)"
[[ -z $(setting WantedBy "$session") ]] || fail "mallet-session.service is enabled on its own (WantedBy=)"
if command -v systemd-analyze >/dev/null; then
  # systemd's own parser, with the units' programs pointing into the unpacked root.
  for u in "$unit" "$session"; do
    sed -e "s|=/usr/libexec/|=$work/root/usr/libexec/|" -e "s|=/usr/bin/mallet|=$work/root/usr/bin/mallet|" "$u" \
      >"$work/$(basename "$u")"
  done
  verdict=$(cd "$work" && systemd-analyze verify --man=no "$work/mallet.service" "$work/mallet-session.service" 2>&1) ||
    fail "systemd-analyze verify failed: $verdict"
  [[ -z $verdict ]] || fail "systemd-analyze verify: $verdict"
else
  echo "package: systemd-analyze not installed: the units were not given to systemd's parser"
fi

# --- The benchmarks' package ------------------------------------------------------------
bench=$dir/mallet-bench_${version}_${arch}.deb
if [[ ! -f $bench ]]; then
  fail "no $bench; $dir holds: $(ls "$dir")"
else
  bench_files=0
  bench_listing=$(dpkg-deb -c "$bench")
  while read -r perms who path; do
    path=${path#.}
    [[ $perms == d* ]] && continue
    bench_files=$((bench_files + 1))
    [[ $who == root/root ]] || fail "mallet-bench: $path is owned by $who, not root/root"
    case $path in
    /usr/bin/mallet-bench) [[ $perms == -rwxr-xr-x ]] || fail "mallet-bench: $path has mode $perms" ;;
    /usr/share/man/man1/mallet-bench.1.gz | /usr/share/doc/mallet-bench/*) ;;
    *) fail "mallet-bench: unexpected file $path" ;;
    esac
  done < <(awk '{print $1, $2, $6}' <<<"$bench_listing")
  grep -q ' ./usr/bin/mallet-bench$' <<<"$bench_listing" || fail "mallet-bench: no /usr/bin/mallet-bench"
  grep -q ' ./usr/share/man/man1/mallet-bench.1.gz$' <<<"$bench_listing" || fail "mallet-bench: no man page"
  [[ $(dpkg-deb -f "$bench" Package) == mallet-bench ]] || fail "mallet-bench: Package: $(dpkg-deb -f "$bench" Package)"
  [[ $(dpkg-deb -f "$bench" Version) == "$version" ]] || fail "mallet-bench: Version: $(dpkg-deb -f "$bench" Version)"
  bench_depends=$(dpkg-deb -f "$bench" Depends)
  grep -Eq "(^|, )mallet \(= $version\)(,|$)" <<<"$bench_depends" ||
    fail "mallet-bench does not depend on mallet (= $version): $bench_depends"
  mapfile -t bench_wanted < <("$src/packaging/deps-list.sh" "$src/packaging/deps-bench.txt")
  ((${#bench_wanted[@]} >= 3)) || fail "deps-bench.txt read as ${#bench_wanted[@]} packages"
  for p in "${bench_wanted[@]}"; do
    grep -Eq "(^|, )$p( |,|$)" <<<"$bench_depends" || fail "mallet-bench: Depends lacks $p (from deps-bench.txt): $bench_depends"
  done
  for p in jackd2 xvfb; do
    grep -Eq "(^|, )$p(,|$)" <<<"$(dpkg-deb -f "$bench" Recommends)" || fail "mallet-bench: Recommends lacks $p"
  done
fi

if ((failures > 0)); then
  echo "package: $failures problem(s) in $deb" >&2
  exit 1
fi
echo "package: $deb: ${#mode[@]} files, control fields, conffiles, scripts and unit as expected"
echo "package: $bench: $bench_files files; Depends on mallet (= $version) and the benchmarks' libraries, which mallet's Depends name none of"
