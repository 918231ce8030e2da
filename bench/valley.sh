#!/usr/bin/env bash
# What scenes/valley.toml costs (issue 44's targets: grow + build ≤ 60 s CPU, peak RSS ≤ 4 GB,
# 1280×720 at 64 spp on 2 cores in ≤ 20 minutes wall). Per round, interleaved: `arbor inspect`
# (the build alone: trees grown, community simulated, meadow and rocks placed; its CPU seconds,
# peak RSS and the simulation's share) and `arbor render` at WIDTH×HEIGHT and SPP (its wall, CPU
# seconds and peak RSS, and the build and render seconds it reports). /usr/bin/time measures; the
# machine's name and cores go into bench/results/valley.json with every run.
#
#   bench/valley.sh [ARBOR (build/app/arbor)] [ROUNDS (1)] [WIDTH (1280)] [HEIGHT (720)] [SPP (64)]
#
# With VALLEY_PNG=path, the last round's render is also written there as a PNG (docs/images/
# valley.png is made so, at the full size).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
arbor=${1:-$root/build/app/arbor} rounds=${2:-1} width=${3:-1280} height=${4:-720} spp=${5:-64}
out=$root/bench/results/valley.json
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$root/scenes/valley.toml
: > "$tmp/runs"
for r in $(seq "$rounds"); do
  /usr/bin/time -f "%e %U %S %M" -o "$tmp/t" "$arbor" inspect "$scene" --json > "$tmp/inspect.json" 2> /dev/null
  python3 - "$tmp/t" "$tmp/inspect.json" >> "$tmp/runs" <<'PY'
import json, sys
wall, user, sys_, rss = open(sys.argv[1]).read().split()
j = json.load(open(sys.argv[2]))
print(json.dumps({"run": "inspect", "wall_s": float(wall), "cpu_s": float(user) + float(sys_),
                  "peak_rss_mb": int(rss) / 1024, "build_s": j["build_seconds"],
                  "simulation_s": j["simulation_seconds"], "instances": len(j["instances"]),
                  "rocks": j["rocks"]["rocks"], "blades": j["meadow"]["blades"]}))
PY
  /usr/bin/time -f "%e %U %S %M" -o "$tmp/t" "$arbor" render "$scene" --width "$width" \
    --height "$height" --spp "$spp" -o "$tmp/valley.exr" ${VALLEY_PNG:+--png "$VALLEY_PNG"} 2> "$tmp/log"
  python3 - "$tmp/t" "$tmp/log" "$width" "$height" "$spp" >> "$tmp/runs" <<'PY'
import json, re, sys
wall, user, sys_, rss = open(sys.argv[1]).read().split()
log = open(sys.argv[2]).read()
m = re.search(r"in ([0-9.]+) s \(.*built in ([0-9.]+) s\)", log)
print(json.dumps({"run": "render", "size": f"{sys.argv[3]}x{sys.argv[4]}", "spp": int(sys.argv[5]),
                  "wall_s": float(wall), "cpu_s": float(user) + float(sys_),
                  "peak_rss_mb": int(rss) / 1024, "render_s": float(m.group(1)),
                  "build_s": float(m.group(2))}))
PY
done
python3 - "$tmp/runs" "$out" <<'PY'
import json, os, sys
runs = [json.loads(l) for l in open(sys.argv[1])]
json.dump({"machine": os.uname().nodename, "cores": os.cpu_count(), "runs": runs},
          open(sys.argv[2], "w"), indent=1)
for r in runs:
    print(" ".join(f"{k}={v}" for k, v in r.items()))
PY
