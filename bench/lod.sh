#!/usr/bin/env bash
# What level of detail at range does to a render (issue 30; docs/rendering.md, "Level of
# detail"): scenes/forest_10000.toml (10,000 Black Tupelos at 180 to 600 m) and
# scenes/forest_far.toml (40,000 Quaking Aspens at 1.4 to 5 km, Weber & Penn's Plate 4 setting),
# each rendered with [render] lod off and on at a fixed exposure (2.5 stops), two threads.
# Timing: ROUNDS rounds at SPP samples per pixel, the scenes and settings interleaved (A B A B):
# arbor's scene and BVH build ("built in"), the render's rays per second, wall and CPU seconds
# (user + system) and peak RSS (/usr/bin/time). Image error: one pair at ERROR_SPP (256) per
# scene, the LOD render against the full one by bench/image_blocks (image means per channel,
# 16 × 16 block means z-tested against their variance; `arbor compare --side-by-side` of the pair
# in bench/results/lod-SCENE.png: LOD, full, difference). Prints a table and writes
# bench/results/lod.json.
#
#   bench/lod.sh [BUILD (build)] [ROUNDS (2)] [SPP (16)] [ERROR_SPP (256)]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build} rounds=${2:-2} spp=${3:-16} error_spp=${4:-256}
arbor=$build/app/arbor blocks=$build/bench/image_blocks
out=$root/bench/results/lod.json
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OCIO=${OCIO:-$root/imaging/ocio/config.ocio} ARBOR_CACHE_DIR=$tmp/cache
scenes=(forest_10000 forest_far)
for s in "${scenes[@]}"; do
  for lod in off on; do
    sed -e '/^lod = /d' -e "s#\\.\\./species#$root/species#" -e "s#\\.\\./out/$s#$tmp/$s-$lod#" \
      -e 's/^exposure = "auto"/exposure = 2.5/' -e "s/^\\[render\\]/[render]\\nlod = $([ $lod = on ] && echo true || echo false)/" \
      "$root/scenes/$s.toml" > "$tmp/$s-$lod.toml"
  done
  "$arbor" render "$tmp/$s-off.toml" --spp 1 --width 64 --height 36 --force 2> /dev/null  # warm caches
done
run() {  # scene lod spp
  /usr/bin/time -f "%e %U %S %M" -o "$tmp/t" "$arbor" render "$tmp/$1-$2.toml" --spp "$3" \
    --threads 2 --force 2> "$tmp/log"
  python3 - "$1" "$2" "$3" "$tmp/t" "$tmp/log" <<'PY'
import json, re, sys
scene, lod, spp, tfile, log = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], open(sys.argv[5]).read()
wall, user, system, rss_kb = open(tfile).read().split()
m = re.search(r"in ([0-9.]+) s \(([0-9.e+]+) samples/s, ([0-9.e+]+) rays/s; .*built in ([0-9.]+) s\)", log)
print(json.dumps({"scene": scene, "lod": lod, "spp": spp, "render_s": float(m.group(1)),
                  "rays_per_s": float(m.group(3)), "build_s": float(m.group(4)),
                  "wall_s": float(wall), "cpu_s": float(user) + float(system),
                  "peak_rss_MB": int(rss_kb) / 1024}))
PY
}
for r in $(seq "$rounds"); do
  for s in "${scenes[@]}"; do
    for lod in off on; do run "$s" "$lod" "$spp" >> "$tmp/runs.jsonl"; done
  done
done
for s in "${scenes[@]}"; do
  for lod in off on; do
    run "$s" "$lod" "$error_spp" > /dev/null
    cp "$tmp/$s-$lod.exr" "$tmp/$s-$lod-error.exr"
  done
  echo "{\"scene\": \"$s\", \"spp\": $error_spp, \"error\": $("$blocks" "$tmp/$s-on-error.exr" "$tmp/$s-off-error.exr")}" >> "$tmp/errors.jsonl"
  "$arbor" compare "$tmp/$s-on-error.exr" "$tmp/$s-off-error.exr" \
    --side-by-side "$root/bench/results/lod-$s.png" > /dev/null
done
python3 - "$tmp/runs.jsonl" "$tmp/errors.jsonl" "$out" <<'PY'
import json, os, sys
runs = [json.loads(l) for l in open(sys.argv[1])]
errors = [json.loads(l) for l in open(sys.argv[2])]
json.dump({"machine": os.uname().nodename, "cores": os.cpu_count(), "runs": runs, "errors": errors},
          open(sys.argv[3], "w"), indent=1)
print(f"{'scene':>13} {'lod':>4} {'build s':>11} {'Mrays/s':>11} {'render s':>13} {'CPU s':>13} {'RSS MB':>11}")
for s in dict.fromkeys(r["scene"] for r in runs):
    for lod in ("off", "on"):
        rs = [r for r in runs if r["scene"] == s and r["lod"] == lod]
        rng = lambda k, f, scale=1: f"{min(r[k] for r in rs) * scale:{f}}-{max(r[k] for r in rs) * scale:{f}}"
        print(f"{s:>13} {lod:>4} {rng('build_s', '.2f'):>11} {rng('rays_per_s', '.2f', 1e-6):>11} "
              f"{rng('render_s', '.1f'):>13} {rng('cpu_s', '.1f'):>13} {rng('peak_rss_MB', '.0f'):>11}")
for e in errors:
    x = e["error"]
    print(f"{e['scene']}: LOD/full image mean - 1 = {', '.join(f'{v:+.2%}' for v in x['mean_rel_diff'])} "
          f"(R, G, B); {x['beyond_3_sigma']} of {x['block_channels']} block means beyond 3 sigma, "
          f"max |z| {x['max_abs_z']:.1f} at {e['spp']} spp")
PY
