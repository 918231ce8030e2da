#!/usr/bin/env bash
# Start-up of a render: the default scene at 1×1 pixel, 1 spp, one thread — loading, building and
# the sky — run ROUNDS times interleaved with and without the sky map cache (a warm cache in a
# folder of its own; ARBOR_CACHE_DIR=off), CPU seconds (user + system, getrusage of the child via
# /usr/bin/time). Prints both ranges and medians and writes bench/results/startup.json.
#
#   bench/startup.sh [ARBOR (build/app/arbor)] [ROUNDS (5)]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
arbor=${1:-$root/build/app/arbor} rounds=${2:-5}
out=$root/bench/results/startup.json
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {  # run CACHE_DIR → CPU seconds
  ARBOR_CACHE_DIR=$1 /usr/bin/time -f "%U %S" -o "$tmp/t" "$arbor" render "$root/scenes/default.toml" \
    --width 1 --height 1 --spp 1 --threads 1 -o "$tmp/one.exr" 2> /dev/null
  awk '{printf "%.3f\n", $1 + $2}' "$tmp/t"
}
run "$tmp/cache" > /dev/null  # warm the cache
for r in $(seq "$rounds"); do
  echo "off $(run off)" >> "$tmp/runs"
  echo "cached $(run "$tmp/cache")" >> "$tmp/runs"
done
python3 "$root/bench/cpu_runs.py" "$tmp/runs" "$out"
