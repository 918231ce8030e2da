#!/usr/bin/env bash
# Runs every benchmark and writes JSON results to bench/results/<name>.json.
# Usage: bench/run.sh [BUILD_DIR]   (default: build; build it with `make build` first)
# Peak memory of one species alone: bench/run.sh measures it per species in a fresh process.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
out="$root/bench/results"
mkdir -p "$out"
"$build/bench/grow_bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/grow_bench.json" --benchmark_out_format=json
# Peak RSS per species in its own process (a shared process would report the largest so far).
for species in quaking_aspen black_tupelo ca_black_oak weeping_willow; do
  "$build/bench/grow_bench" --benchmark_filter="/$species\$" --benchmark_min_time=0.2 \
    --benchmark_out="$out/grow_bench_$species.json" --benchmark_out_format=json > /dev/null
done
"$build/bench/reader_bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/reader_bench.json" --benchmark_out_format=json
"$build/bench/geometry_bench" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/geometry_bench.json" --benchmark_out_format=json
"$build/bench/render_bench" --benchmark_filter='raw_embree_rays|path_tracer|frame|world_build' \
  --benchmark_out="$out/render_bench.json" --benchmark_out_format=json
# The approximate integrator's speed-up over the path tracer on the same frame.
python3 - "$out/render_bench.json" <<'PY'
import json, sys
runs = {b["name"]: b["real_time"] for b in json.load(open(sys.argv[1]))["benchmarks"]}
path, tm = runs["frame/path_64spp/iterations:3"], runs["frame/treemaker"]
print(f"bench: default-scene frame, path 64 spp / treemaker = {path / tm:.1f}x")
PY
# The path tracer's efficiency on whole scenes (issue 13's default as curves, with glossy leaves and
# as triangles, the willow, the 10,000-tree forest), each in its own process so that its peak RSS is its own.
for scene in default_curves default_glossy default_triangles willow forest_10000; do
  "$build/bench/efficiency_bench" --benchmark_filter="scene/$scene/" \
    --benchmark_out="$out/efficiency_bench_$scene.json" --benchmark_out_format=json
done
"$build/bench/adaptive_bench" --benchmark_out="$out/adaptive_bench.json" --benchmark_out_format=json
# Adaptive sampling's time against uniform sampling's at the same 95th-percentile error.
python3 - "$out/adaptive_bench.json" <<'PY'
import json, math, sys
runs = json.load(open(sys.argv[1]))["benchmarks"]
uni = sorted((b["p95_error"], b["real_time"]) for b in runs if b["name"].startswith("uniform/"))
for b in runs:
    if not b["name"].startswith("adaptive/"):
        continue
    e = b["p95_error"]
    pts = [(math.log(x), math.log(t)) for x, t in uni]
    lo = max((p for p in pts if p[0] <= math.log(e)), default=None)
    hi = min((p for p in pts if p[0] >= math.log(e)), default=None)
    if lo is None or hi is None:
        print(f"bench: {b['name']}: p95 error {e:.3f} outside the uniform renders' range")
        continue
    f = 0 if hi[0] == lo[0] else (math.log(e) - lo[0]) / (hi[0] - lo[0])
    t = math.exp(lo[1] + f * (hi[1] - lo[1]))
    print(f"bench: {b['name']}: p95 error {e:.3f} in {b['real_time']:.0f} ms, uniform {t:.0f} ms: "
          f"{t / b['real_time']:.2f}x")
PY
"$build/bench/render_bench" --benchmark_filter='forest_1000' \
  --benchmark_out="$out/render_bench_forest.json" --benchmark_out_format=json
# Farm units: their summed time over the single render (docs/farm.md).
"$build/bench/farm_bench" --benchmark_out="$out/farm_bench.json" --benchmark_out_format=json
python3 - "$out/farm_bench.json" <<'PY'
import json, sys
runs = {b["name"].split("/")[0] + ("/" + b["name"].split("/")[1] if b["name"].startswith("units") else ""): b
        for b in json.load(open(sys.argv[1]))["benchmarks"]}
whole = runs["whole"]["real_time"]
for n in ("4", "16", "64"):
    b = runs["units/" + n]
    print(f"bench: {n} units sum {b['real_time']:.1f} s over one render {whole:.1f} s: "
          f"{b['real_time'] / whole:.2f}x (+{b['merge_seconds']:.1f} s merge)")
PY
echo "bench: results in $out"
