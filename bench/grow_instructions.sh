#!/usr/bin/env bash
# Instructions executed growing the four appendix species of Weber & Penn 1995 (seed 1, one
# thread), counted by valgrind's callgrind inside grow_tree only: deterministic, so small changes
# show on a shared, noisy machine where CPU time does not. One or more arbor builds, each as
# NAME=PATH_TO_ARBOR[:SPECIES_DIR] (an old build may need its own commit's species files, e.g.
# bench/grow_instructions.sh old=/tmp/old/build/app/arbor:/tmp/old/species new=build/app/arbor).
# Needs valgrind (apt install valgrind). Prints a table and writes bench/results/grow_instructions.json.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$here/results/grow_instructions.json
mkdir -p "$here/results"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
species="quaking_aspen black_tupelo ca_black_oak weeping_willow"
echo "{" > "$tmp/json"
first=1
for build in "$@"; do
  name=${build%%=*}
  rest=${build#*=}
  arbor=${rest%%:*}
  dir=$here/../species
  [[ $rest == *:* ]] && dir=${rest#*:}
  # The grow_tree of any namespace (arbor::generator:: now, arbor::gen:: in older builds).
  symbol=$(nm -C "$arbor" | grep -o 'arbor::[a-z]*::grow_tree(' | head -1 | tr -d '(')
  [ "$first" = 1 ] || echo "," >> "$tmp/json"
  first=0
  printf '"%s": {' "$name" >> "$tmp/json"
  sep=""
  for s in $species; do
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" --toggle-collect="$symbol*" \
      "$arbor" grow "$dir/$s.toml" --seed 1 -o "$tmp/tree.skel" > /dev/null 2>&1
    ir=$(callgrind_annotate "$tmp/cg" | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
    printf '%s"%s": %s' "$sep" "$s" "$ir" >> "$tmp/json"
    sep=", "
    printf '%-8s %-16s %14s instructions\n' "$name" "$s" "$ir"
  done
  echo "}" >> "$tmp/json"
done
echo "}" >> "$tmp/json"
cp "$tmp/json" "$out"
echo "(callgrind, grow_tree only, seed 1; $out)"
