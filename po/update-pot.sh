#!/usr/bin/env bash
# po/mallet.pot from the texts marked in src/ (tr and N_), then each po/<lang>.po merged with
# it (new texts appear untranslated there: the po.complete test fails until they are).
#   po/update-pot.sh [XGETTEXT [MSGMERGE]]      run from the source tree's root
#   po/update-pot.sh --check                    print the fresh .pot to stdout, change nothing
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
check=0
if [[ "${1:-}" == "--check" ]]; then check=1; shift; fi
xgettext="${1:-xgettext}"
msgmerge="${2:-msgmerge}"
args=(--language=C++ --from-code=UTF-8 --keyword=tr --keyword=N_ --add-comments=TRANSLATORS:
      --package-name=mallet --sort-output --no-location --no-wrap --omit-header)
mapfile -t sources < <(git ls-files 'src/*.cpp' 'src/*.hpp' 2>/dev/null || find src -name '*.[ch]pp' | sort)
if ((check)); then
  "$xgettext" "${args[@]}" -o - "${sources[@]}"
  exit 0
fi
"$xgettext" "${args[@]}" -o po/mallet.pot "${sources[@]}"
while read -r lang; do
  [[ "$lang" =~ ^[a-z] ]] || continue
  "$msgmerge" --quiet --update --backup=none --no-wrap --sort-output --no-location "po/$lang.po" po/mallet.pot
done < po/LINGUAS
