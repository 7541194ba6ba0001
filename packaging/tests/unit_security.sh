#!/usr/bin/env bash
# The shipped unit's sandbox, as systemd rates it: `systemd-analyze security --offline=yes`
# on the unit made from packaging/mallet.service.in, whose overall exposure must stay at or
# below the score the unit reached (a new setting that opens the sandbox fails this test).
#   unit_security.sh UNIT_FILE MAX_EXPOSURE
set -euo pipefail
unit=$1 max=$2
command -v systemd-analyze >/dev/null || { echo "unit_security: systemd-analyze not found (Debian: systemd)" >&2; exit 1; }
report=$(systemd-analyze security --offline=yes --no-pager "$unit" 2>&1) || true
line=$(grep -o 'Overall exposure level for [^:]*: [0-9.]* [A-Z]*' <<<"$report" || true)
if [[ -z $line ]]; then
  echo "unit_security: systemd-analyze gave no overall exposure for $unit:" >&2
  echo "$report" >&2
  exit 1
fi
score=${line#*: }
score=${score%% *}
echo "$line (at most $max allowed)"
if awk -v s="$score" -v m="$max" 'BEGIN { exit !(s > m) }'; then
  echo "unit_security: $unit is rated $score, above $max; what is open:" >&2
  grep '^✗' <<<"$report" >&2 || true
  exit 1
fi
