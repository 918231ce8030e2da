#!/usr/bin/env bash
# Interleaved comparison of two grow_bench binaries (e.g. an old commit's and this one's) on the
# four appendix species of Weber & Penn 1995: A B A B … for ROUNDS rounds, each run a fresh
# process, CPU milliseconds per tree from Google Benchmark's cpu_time (one thread). Prints one
# line per species with both ranges and the ratio of medians, and writes the runs as JSON.
#
#   bench/grow_compare.sh OLD_GROW_BENCH NEW_GROW_BENCH [ROUNDS (5)] [OUT.json]
set -euo pipefail
old=$1 new=$2 rounds=${3:-5}
out=${4:-$(cd "$(dirname "$0")" && pwd)/results/grow_compare.json}
mkdir -p "$(dirname "$out")"
filter='grow_species/(quaking_aspen|black_tupelo|ca_black_oak|weeping_willow)$'
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$rounds"); do
  for side in old new; do
    bin=$old; [ "$side" = new ] && bin=$new
    "$bin" --benchmark_filter="$filter" --benchmark_min_time=0.5 \
      --benchmark_out="$tmp/$side.$r.json" --benchmark_out_format=json > /dev/null
  done
done
python3 - "$tmp" "$rounds" "$out" "$(uname -n)" "$(nproc)" <<'PY'
import json, statistics, sys
tmp, rounds, out, host, cores = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
runs = {"old": {}, "new": {}}
for side in runs:
    for r in range(1, rounds + 1):
        for b in json.load(open(f"{tmp}/{side}.{r}.json"))["benchmarks"]:
            runs[side].setdefault(b["name"].split("/")[1], []).append(b["cpu_time"])
json.dump({"machine": host, "cores": int(cores), "rounds": rounds, "unit": "ms CPU per tree",
           "runs": runs}, open(out, "w"), indent=1)
for species in runs["new"]:
    o, n = runs["old"][species], runs["new"][species]
    print(f"{species:16s} old {min(o):8.1f}-{max(o):8.1f} ms  new {min(n):8.1f}-{max(n):8.1f} ms  "
          f"old/new {statistics.median(o) / statistics.median(n):5.2f}x")
print(f"(interleaved, {rounds} rounds, {host}, {cores} cores; runs in {out})")
PY
