#!/usr/bin/env bash
# Checks the layout's invariants (README "Layout"): every #include of an arbor header goes to a
# folder its own folder may use, Embree is included only in tracer/embree/, tracer/ and imaging/ include no tree
# model, no source file is over 600 lines and app/ is under 300. Prints each violation; exits 1
# when there is any.
#
#   tools/check-layers.sh [SOURCE_DIR]
set -uo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root" || exit 2
# What each folder may include besides itself (README "Layout"). materials/ and generator/ do
# not know each other: scene/ turns a species' looks into materials.
declare -A may=(
  [common]=""
  [materials]="common"
  [generator]="common"
  [formats]="common generator"
  [imaging]="common formats"
  [scene]="common materials generator formats"
  [tracer]="common materials generator formats imaging scene"
  [app]="common materials generator formats imaging scene tracer"
)
layers=(common materials generator formats imaging scene tracer app)
status=0
fail() { echo "check-layers: $*"; status=1; }

sources=$(git ls-files "${layers[@]}" | grep -E '\.(h|cpp)$')
for f in $sources; do
  own=${f%%/*}
  while IFS= read -r line; do
    inc=${line#*\"}; inc=${inc%\"*}
    top=${inc%%/*}
    [ "$top" = arbor ] && continue  # the generated version header
    [ "$top" = "$own" ] && continue
    if [ -z "${may[$top]+x}" ]; then fail "$f includes \"$inc\", which is in no layer"; continue; fi
    [[ " ${may[$own]} " == *" $top "* ]] || fail "$f includes \"$inc\": $own/ may not use $top/"
  done < <(grep -E '^#include "' "$f")
  if grep -qE '^#include <embree3/' "$f" && [[ $f != tracer/embree/* ]]; then
    fail "$f includes Embree outside tracer/embree/"
  fi
  if [[ $f == tracer/* || $f == imaging/* ]] && grep -qE '^#include "generator/models/' "$f"; then
    fail "$f includes a tree model"
  fi
  lines=$(wc -l < "$f")
  [ "$lines" -gt 600 ] && fail "$f has $lines lines (at most 600)"
done
app_lines=$(cat $(git ls-files app | grep -E '\.(h|cpp)$') | wc -l)
[ "$app_lines" -ge 300 ] && fail "app/ has $app_lines lines (under 300)"
[ "$status" -eq 0 ] && echo "check-layers: the layout's invariants hold"
exit "$status"
