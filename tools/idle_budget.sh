#!/usr/bin/env bash
# tools/idle_budget.sh: the kiosk's running cost on a PC without a GPU, this tree against the
# last recorded one, in one run on one machine.
#
# The figure is `mallet bench render`'s kiosk CPU: the real kiosk fullscreen at 1920x1080 on
# its own Xvfb (lavapipe), its sound on its own JACK server, % of one core in the attract mode
# (nobody there), in play and still, with the frame budget (docs/researchers.md, "The kiosk's
# CPU"). docs/bench-report/idle-budget.tsv records it with the commit it was measured at.
# This script builds this tree's `mallet` with the Debian package's compiler flags
# (dpkg-buildflags with debian/rules' hardening=+all, CMake build type None, as
# dh_auto_configure: the code a museum runs), runs the benchmark, and prints its figures and
# their ratio to the recorded ones. Only when a ratio crosses the flag (1.5), where the
# machine rather than the code may be to blame, does it build the recorded commit the same way
# (in its own folder) and measure it here too, and the ratio is then to that measurement
# (--rebuild: always). A commit whose code is the recorded one's is measured twice instead.
# It is a benchmark that prints, never a test that fails: a ratio of 1.5 or more is said on a
# line of its own beginning "idle budget: REGRESSION", which .ci/run repeats as its last line. It exits 0 whatever it measured; 2 when it could not measure.
#
#   tools/idle_budget.sh            compare (needs Xvfb, jackd, git, dpkg-buildflags, the
#                                   recorded commit)
#   tools/idle_budget.sh --record   also append this tree's figures to the record (commit first)
#   tools/idle_budget.sh --rebuild  build and measure the recorded commit whatever the ratio
#   tools/idle_budget.sh --no-rebuild
#                                   never build it: a crossing of the flag is then said
#                                   against the recorded figures, with the verdict "unsure"
#                                   (the machine or the code?); .ci/run passes it when too
#                                   little of CI's time is left for a build (about 500 s)
#   tools/idle_budget.sh --package-build DIR
#                                   this tree's `mallet` is the one packaging/tests/
#                                   build_package.sh built in DIR (the package tests'
#                                   build/asan/packaging/package-test/deb, as .ci/run passes
#                                   it): the same flags, not built again; taken only when its
#                                   copy of the code is this tree's
#
# IDLE_BUDGET_SECONDS (10): seconds per phase; IDLE_BUDGET_RUNS (1): runs of each build, taken
# in turn (this, recorded, this, ...) and averaged.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
record_file=$root/docs/bench-report/idle-budget.tsv
seconds=${IDLE_BUDGET_SECONDS:-10}
runs=${IDLE_BUDGET_RUNS:-1}
record=0
rebuild=0
no_rebuild=0
package_build=
say() { echo "idle budget: $*"; }
fail() { say "$*" >&2; exit 2; }
while (($#)); do
  case "$1" in
    --record) record=1 ;;
    --rebuild) rebuild=1 ;;
    --no-rebuild) no_rebuild=1 ;;
    --package-build)
      [[ $# -ge 2 ]] || fail "--package-build needs the folder build_package.sh wrote"
      package_build=$2
      shift
      ;;
    *) fail "unknown argument: $1 (see the head of $0)" ;;
  esac
  shift
done
((rebuild && no_rebuild)) && fail "--rebuild and --no-rebuild contradict each other"

for program in Xvfb jackd git cmake dpkg-buildflags awk diff; do
  command -v "$program" >/dev/null || fail "needs $program"
done
[[ -f "$record_file" ]] || fail "no record: $record_file"
# The last record: commit, attract, play, still (tab-separated, after the comments).
read -r recorded_date recorded_commit recorded_attract recorded_play recorded_still < <(
  awk -F'\t' '!/^#/ && NF >= 6 { d = $1; c = $2; a = $4; p = $5; s = $6 } END { print d, c, a, p, s }' "$record_file")
[[ -n "$recorded_commit" ]] || fail "$record_file has no record"

work=$(mktemp -d /var/tmp/mallet-idle-budget.XXXXXX)
cleanup() {
  git -C "$root" worktree remove --force "$work/recorded" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT

# Each build in a folder of its own, never the developer's build/release, with the package's
# flags: dpkg-buildflags' CXXFLAGS and CPPFLAGS (-O2, the stack protector, _FORTIFY_SOURCE)
# and LDFLAGS (relro, now), build type None, as dh_auto_configure passes them. Without debug
# information (-g0: the package's -g1 changes no instruction, only what a debugger reads).
deb_flags() { DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get "$1"; }
build() {  # build SOURCE_DIR BUILD_DIR: prints the built mallet
  CXXFLAGS="$(deb_flags CXXFLAGS) $(deb_flags CPPFLAGS) -g0" LDFLAGS="$(deb_flags LDFLAGS)" \
    cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=None -DMALLET_BUILD_TESTS=OFF >"$work/cmake.log" 2>&1 ||
    { cat "$work/cmake.log" >&2; fail "cannot configure $1"; }
  # The kiosk, and the benchmarks' own program where the tree has one (`mallet bench` runs it;
  # before it, the benchmarks were inside mallet).
  local targets=(mallet)
  grep -q 'add_executable(mallet-bench' "$1/src/CMakeLists.txt" && targets+=(mallet-bench)
  cmake --build "$2" --target "${targets[@]}" >"$work/build.log" 2>&1 ||
    { tail -n 30 "$work/build.log" >&2; fail "cannot build $1"; }
  echo "$2/mallet"
}
program_in() {  # program_in OUT: the mallet build_package.sh built in OUT (OUT/src/obj-<triplet>/)
  local obj
  for obj in "$1"/src/obj-*/; do
    [[ -x "$obj/mallet" ]] && { echo "${obj%/}/mallet"; return 0; }
  done
  return 1
}
# The code that makes the kiosk: sources, shaders, build files, shipped settings and models.
code_paths=(src shaders cmake CMakeLists.txt config models)
same_code() {  # same_code DIR: DIR holds this tree's code (a copy build_package.sh made)
  local path
  for path in "${code_paths[@]}"; do diff -rq "$root/$path" "$1/$path" >/dev/null 2>&1 || return 1; done
}
started=$SECONDS
this_bin=
if [[ -n "$package_build" ]]; then
  if ! this_bin=$(program_in "$package_build"); then
    say "no package build in $package_build: building this tree"
  elif ! same_code "$package_build/src"; then
    say "the package build in $package_build is not of this tree's code: building this tree"
    this_bin=
  else
    say "this tree's mallet: the package tests' build, $this_bin"
  fi
fi
[[ -n "$this_bin" ]] || this_bin=$(build "$root" "$work/this")
recorded_bin=
if git -C "$root" cat-file -e "$recorded_commit^{commit}" 2>/dev/null &&
  git -C "$root" diff --quiet "$recorded_commit" -- "${code_paths[@]}"; then
  say "this tree's code is the recorded commit's ($recorded_commit): one build, run twice"
  recorded_bin=$this_bin
fi
say "built in $((SECONDS - started)) s"

# bench render's table rows: "| capped (max_fps = refresh) | attract | 21.3 | 58.7 | 1.8 |".
measure() {  # measure BINARY LOG: prints "attract play still" (% of a core, the frame budget on)
  "$1" bench render --frames 10 --sizes 1920x1080 --kiosk-cpu-seconds "$seconds" >"$2" 2>&1 ||
    { tail -n 20 "$2" >&2; fail "bench render failed with $1"; }
  awk -F'|' '$2 ~ /^ capped/ { gsub(/ /, "", $3); gsub(/ /, "", $4); v[$3] = $4 }
             END { print v["attract"], v["play"], v["still"] }' "$2"
}
for ((run = 1; run <= runs; ++run)); do
  measure "$this_bin" "$work/this-$run.log" >>"$work/this.txt"
  [[ -n "$recorded_bin" ]] && measure "$recorded_bin" "$work/recorded-$run.log" >>"$work/recorded.txt"
done
mean() { awk '{ a += $1; p += $2; s += $3 } END { printf "%.1f %.1f %.1f\n", a / NR, p / NR, s / NR }' "$1"; }
read -r -a this < <(mean "$work/this.txt")
above() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 >= b + 0) }'; }  # above A B: A >= B
crosses_flag() {  # this tree's attract or play at 1.5x the recorded figures or more
  local i
  for i in 0 1; do
    [[ "${recorded_figures[$i]}" =~ ^[0-9.]+$ ]] || continue
    above "$(awk -v a="${this[$i]}" -v b="${recorded_figures[$i]}" 'BEGIN { print a / (b + 1e-4) }')" 1.5 && return 0
  done
  return 1
}
recorded_figures=("$recorded_attract" "$recorded_play" "$recorded_still")
unsure=0
if [[ -z "$recorded_bin" ]] && ((no_rebuild)) && crosses_flag; then
  say "at 1.5x the recorded figures or more, recorded on $recorded_date, perhaps on another machine: the code is not told from the machine here (--no-rebuild); tools/idle_budget.sh --rebuild measures the recorded commit beside this tree"
  unsure=1
elif [[ -z "$recorded_bin" ]] && { ((rebuild)) || crosses_flag; }; then
  # The recorded commit built and measured here: is it the code or this machine?
  if ! git -C "$root" cat-file -e "$recorded_commit^{commit}" 2>/dev/null; then
    say "the recorded commit $recorded_commit is not in this clone: only the recorded figures are compared"
  else
    ((rebuild)) || say "at 1.5x the recorded figures or more: measuring the recorded commit ($recorded_commit) here too"
    started=$SECONDS
    git -C "$root" worktree add --detach "$work/recorded" "$recorded_commit" >/dev/null 2>&1 ||
      fail "cannot check out $recorded_commit"
    recorded_bin=$(build "$work/recorded" "$work/recorded-build")
    say "built the recorded commit in $((SECONDS - started)) s"
    for ((run = 1; run <= runs; ++run)); do
      measure "$recorded_bin" "$work/recorded-$run.log" >>"$work/recorded.txt"
    done
  fi
elif [[ -z "$recorded_bin" ]]; then
  say "under 1.5x the recorded figures: the recorded commit is not built (--rebuild builds it)"
fi
if [[ -n "$recorded_bin" ]]; then
  read -r -a then_ < <(mean "$work/recorded.txt")
  then_what="the recorded commit's build, measured now"
else
  then_=("$recorded_attract" "$recorded_play" "$recorded_still")
  then_what="as recorded"
fi
commit=$(git -C "$root" rev-parse --short=12 HEAD)
dirty=$(git -C "$root" diff --quiet HEAD -- "${code_paths[@]}" || echo " (with changes)")
say "kiosk CPU, % of a core at 1920x1080, frame budget on, $seconds s a phase, $runs run(s) each:"
printf 'idle budget: %-34s attract %5s  play %5s  still %5s\n' "this tree ($commit$dirty)" "${this[@]}"
printf 'idle budget: %-34s attract %5s  play %5s  still %5s\n' "recorded ($recorded_commit)" "${then_[@]}"
say "($then_what; recorded on its day: attract $recorded_attract, play $recorded_play, still $recorded_still)"
verdict=ok
names=(attract play)
for i in 0 1; do  # the still scene is too small a figure for a ratio: it has its own 2 % budget
  [[ "${then_[$i]}" =~ ^[0-9.]+$ ]] || { say "${names[$i]}: no recorded figure to compare with"; continue; }
  ratio=$(awk -v a="${this[$i]}" -v b="${then_[$i]}" 'BEGIN { printf "%.2f", a / (b + 1e-4) }')
  say "${names[$i]} ${ratio}x the recorded commit's"
  if above "$ratio" 1.5 && ((unsure)); then
    say "unsure: ${names[$i]} costs ${ratio}x the recorded figures (${this[$i]} % of a core against ${then_[$i]} %), this machine or the code"
    verdict=unsure
  elif above "$ratio" 1.5; then
    say "REGRESSION: ${names[$i]} costs ${ratio}x the recorded commit's (${this[$i]} % of a core against ${then_[$i]} %)"
    verdict=regression
  fi
done
above "${this[0]}" 25.05 && say "over budget: the attract mode costs ${this[0]} % of a core (its budget: 25 %)"
above "${this[1]}" 25.05 && say "over budget: play costs ${this[1]} % of a core (its budget: 25 %)"
above "${this[2]}" 2.05 && say "over budget: a still scene costs ${this[2]} % of a core (its budget: 2 %)"
if ((record)); then
  [[ -z "$dirty" ]] || fail "commit the code first: a record names the commit it measured"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%F)" "$commit" "$(nproc)-core $(uname -m)" "${this[@]}" \
    "$runs run(s) of $seconds s a phase" >>"$record_file"
  say "recorded in $record_file"
fi
say "verdict: $verdict"
