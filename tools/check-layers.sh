#!/usr/bin/env bash
# Checks the layout's invariants (docs/architecture.md): every #include of an arbor header goes to
# a folder its own folder may use (directly or through the headers it includes), Embree is included only in tracer/embree/, tracer/ and imaging/
# include no tree model, every folder declares in its own namespace (arbor::FOLDER), the command line (CLI11, the commands) lives only in app/, no source file
# is over 600 lines, and no function outside tests is over 80 lines unless it is listed, with its
# reason, in tools/long-functions.txt. Prints each violation; exits 1 when there is any.
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
  [imaging]="common"
  [spec]="common generator imaging"
  [formats]="common generator imaging spec"
  [scene]="common materials generator imaging spec formats"
  [tracer]="common materials generator imaging spec scene"
  [app]="common materials generator imaging spec formats scene tracer"
)
layers=(common materials generator imaging spec formats scene tracer app)
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
# Through headers too: what a header includes, and so on, must be in a layer the including file's
# folder may use (tracer/ reaches formats/ through no scene/ header).
declare -A direct
for f in $sources; do
  direct[$f]=$(grep -E '^#include "[a-z]+/' "$f" | sed -E 's/^#include "([^"]*)".*/\1/' | tr '\n' ' ')
done
for f in $sources; do
  own=${f%%/*}
  declare -A seen=()
  todo=${direct[$f]}
  while [ -n "${todo// /}" ]; do
    next=""
    for inc in $todo; do
      [ -n "${seen[$inc]+x}" ] && continue
      seen[$inc]=1
      next+=" ${direct[$inc]-}"
    done
    todo=$next
  done
  for inc in "${!seen[@]}"; do
    top=${inc%%/*}
    [ "$top" = "$own" ] || [ "$top" = arbor ] || [ -z "${may[$top]+x}" ] && continue
    if [[ " ${may[$own]} " != *" $top "* ]] && ! grep -qE "^#include \"$inc\"" "$f"; then
      fail "$f reaches \"$inc\" through its headers: $own/ may not use $top/"
    fi
  done
  unset seen
done
# A folder is a namespace: what folder F declares is in arbor::F (common/: arbor), or in a
# namespace nested in it. A file may reopen the namespace of a folder it may use only to declare
# that folder's names ahead (class Progress;).
ns_of() { [ "$1" = common ] && echo arbor || echo "arbor::$1"; }
for f in $sources; do
  own=${f%%/*}
  mine=$(ns_of "$own")
  while IFS= read -r ns; do
    [[ $ns == "$mine" || $ns == "$mine"::* || $ns != arbor* ]] && continue  # or nested
    ok=0
    for used in ${may[$own]}; do [ "$ns" = "$(ns_of "$used")" ] && ok=1; done
    [ "$ok" -eq 1 ] || fail "$f opens namespace $ns; $own/ declares in $mine"
  done < <(grep -oE '^namespace [A-Za-z_:]+ \{' "$f" | awk '{print $2}')
done
# The command line is app/'s: commands in app/commands/, CLI11 nowhere else.
for f in $sources; do
  [[ $f == app/* ]] && continue
  [[ $f == *_command.* ]] && fail "$f is a command outside app/commands/"
  grep -qE '^#include <CLI/' "$f" && fail "$f includes CLI11 outside app/"
done
# Functions over 80 lines (found by a parser: methods defined in a class and headers count), unless
# listed (FILE NAME: reason) in tools/long-functions.txt.
while read -r where name length; do
  file=${where%%:*}
  grep -qE "^$file $name:" tools/long-functions.txt 2>/dev/null ||
    fail "$where: $name is $length lines (at most 80, or listed in tools/long-functions.txt)"
done < <(echo "$sources" | xargs bash tools/function-lengths.sh 80)
# A listed function that is short now comes off the list.
while IFS= read -r entry; do
  [[ -z $entry || $entry == \#* ]] && continue
  file=${entry%% *}; rest=${entry#* }; name=${rest%%: *}
  [ -f "$file" ] && bash tools/function-lengths.sh 80 "$file" | grep -q " $name " ||
    fail "tools/long-functions.txt lists $file $name, which is not over 80 lines (take it off)"
done < tools/long-functions.txt
[ "$status" -eq 0 ] && echo "check-layers: the layout's invariants hold"
exit "$status"
