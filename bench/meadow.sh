#!/usr/bin/env bash
# What a meadow costs (issue 29): a [meadow] of BLADES grass blades placed (10⁵, 10⁶, 10⁷ by
# default; density 2000 per m² over a square of the matching side, 4 tiles of 1 m), seen from 1.6
# m over it at 320×180, 4 spp, two threads, under the atmosphere's sky; and the same scene with no
# meadow. For each: the blades (placed and distinct) and the tiles' bytes as arbor reports them,
# the scene and BVH build time (arbor's "built in"), the render's wall seconds, CPU seconds (user
# + system) and peak RSS (/usr/bin/time). Runs ROUNDS rounds, the sizes interleaved; prints a
# table and writes bench/results/meadow.json.
#
#   bench/meadow.sh [ARBOR (build/app/arbor)] [ROUNDS (2)] [BLADES...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
arbor=${1:-$root/build/app/arbor} rounds=${2:-2}
shift $(( $# > 2 ? 2 : $# ))
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(0 100000 1000000 10000000)
out=$root/bench/results/meadow.json
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for n in "${sizes[@]}"; do
  half=$(python3 -c "import math; print(f'{max(1.0, math.sqrt($n / 2000.0)) / 2:.3f}')")
  meadow=""
  [ "$n" -gt 0 ] && meadow="[meadow]
density = 2000.0
area = [[-$half, -$half], [$half, $half]]"
  cat > "$tmp/$n.toml" <<TOML
[render]
width = 320
height = 180
spp = 4

[camera]
position = [0.0, -$half, 1.6]
look_at = [0.0, 0.0, 0.0]
fov = 50.0
[sun]
elevation = 35.0
azimuth = 60.0
[sky]
model = "atmosphere"
$meadow
[output]
exr = "$tmp/$n.exr"
TOML
done
ARBOR_CACHE_DIR=$tmp/cache "$arbor" render "$tmp/0.toml" 2> /dev/null  # warm the sky cache
for r in $(seq "$rounds"); do
  for n in "${sizes[@]}"; do
    ARBOR_CACHE_DIR=$tmp/cache /usr/bin/time -f "%e %U %S %M" -o "$tmp/t" \
      "$arbor" render "$tmp/$n.toml" --threads 2 2> "$tmp/log"
    python3 - "$n" "$tmp/t" "$tmp/log" >> "$tmp/runs.jsonl" <<'PY'
import json, re, sys
n, tfile, log = sys.argv[1], sys.argv[2], open(sys.argv[3]).read()
wall, user, system, rss_kb = open(tfile).read().split()
built = re.search(r"built in ([0-9.]+) s", log)
meadow = re.search(r"meadow of (\d+) grass blades \((\d+) distinct, in (\d+) tiles: ([0-9.]+) MB", log)
print(json.dumps({"blades_asked": int(n), "blades": int(meadow.group(1)) if meadow else 0,
                  "distinct": int(meadow.group(2)) if meadow else 0,
                  "tile_MB": float(meadow.group(4)) if meadow else 0.0,
                  "build_s": float(built.group(1)) if built else None, "wall_s": float(wall),
                  "cpu_s": float(user) + float(system), "peak_rss_MB": int(rss_kb) / 1024}))
PY
  done
done
python3 - "$tmp/runs.jsonl" "$out" <<'PY'
import json, os, sys
runs = [json.loads(l) for l in open(sys.argv[1])]
json.dump({"machine": os.uname().nodename, "cores": os.cpu_count(), "runs": runs},
          open(sys.argv[2], "w"), indent=1)
print(f"{'blades':>10} {'distinct':>9} {'tile MB':>8} {'build s':>12} {'CPU s':>12} {'peak RSS MB':>14}")
for n in dict.fromkeys(r["blades_asked"] for r in runs):
    rs = [r for r in runs if r["blades_asked"] == n]
    rng = lambda k, f: f"{min(r[k] for r in rs):{f}}-{max(r[k] for r in rs):{f}}"
    print(f"{rs[0]['blades']:>10} {rs[0]['distinct']:>9} {rs[0]['tile_MB']:>8.1f} "
          f"{rng('build_s', '.2f'):>12} {rng('cpu_s', '.1f'):>12} {rng('peak_rss_MB', '.0f'):>14}")
PY
