#!/usr/bin/env bash
# What path regularisation (`[render] regularize`, `--regularize`) removes and what it costs in
# bias (issue 29): SCENE (scenes/default.toml) rendered at WIDTH×HEIGHT, SPP samples, without and
# with --regularize (the same seed), and once more without it at REF_SPP with another seed, the
# converged image. For each: fireflies — pixels whose luminance exceeds 10× the median of their
# 3×3 neighbourhood — and the image's mean luminance against the converged one's (its standard
# error from the variance AOV), and CPU seconds. Writes bench/results/regularize.json.
#
#   bench/regularize.sh [ARBOR (build/app/arbor)] [SCENE] [WIDTH (320)] [HEIGHT (240)] [SPP (256)] [REF_SPP (1024)]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
arbor=${1:-$root/build/app/arbor} scene=${2:-$root/scenes/default.toml}
w=${3:-320} h=${4:-240} spp=${5:-256} ref=${6:-1024}
out=$root/bench/results/regularize.json
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {  # name extra-args...
  local name=$1
  shift
  /usr/bin/time -f "%U %S" -o "$tmp/$name.time" "$arbor" render "$scene" --width "$w" --height "$h" \
    --threads 2 -o "$tmp/$name.exr" "$@" 2> "$tmp/$name.log"
}
run off --spp "$spp" --seed 1
run on --spp "$spp" --seed 1 --regularize
run ref --spp "$ref" --seed 2
/usr/bin/python3 - "$tmp" "$out" "$w" "$h" "$spp" "$ref" <<'PY'
import json, os, sys
import numpy as np
import OpenImageIO as oiio
tmp, out = sys.argv[1], sys.argv[2]

def load(name):
    img = oiio.ImageBuf(f"{tmp}/{name}.exr")
    spec = img.spec()
    px = img.get_pixels(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)
    rgb = px[..., [names.index(c) for c in ("R", "G", "B")]]
    lum = rgb @ np.array([0.2126, 0.7152, 0.0722])
    var = None
    if "variance.R" in names:
        v = px[..., [names.index(c) for c in ("variance.R", "variance.G", "variance.B")]]
        var = v @ (np.array([0.2126, 0.7152, 0.0722]) ** 2)
    user, system = map(float, open(f"{tmp}/{name}.time").read().split())
    return lum, var, user + system, spec.get_string_attribute("arbor:regularize")

def fireflies(lum):
    p = np.pad(lum, 1, mode="edge")
    stack = np.stack([p[1 + dy:1 + dy + lum.shape[0], 1 + dx:1 + dx + lum.shape[1]]
                      for dy in (-1, 0, 1) for dx in (-1, 0, 1)])
    med = np.median(stack, axis=0)
    return int(np.count_nonzero(lum > 10.0 * np.maximum(med, 1e-6)))

ref_lum, ref_var, ref_cpu, _ = load("ref")
ref_mean = float(ref_lum.mean())
ref_se = float(np.sqrt(ref_var.sum()) / ref_var.size) if ref_var is not None else None
result = {"machine": os.uname().nodename, "cores": os.cpu_count(), "size": [int(sys.argv[3]), int(sys.argv[4])],
          "spp": int(sys.argv[5]), "ref_spp": int(sys.argv[6]), "ref_mean": ref_mean, "ref_se": ref_se,
          "ref_fireflies": fireflies(ref_lum), "ref_cpu_s": ref_cpu}
for name in ("off", "on"):
    lum, var, cpu, attr = load(name)
    m = float(lum.mean())
    result[name] = {"fireflies": fireflies(lum), "mean": m, "bias": m / ref_mean - 1.0,
                    "cpu_s": cpu, "arbor:regularize": attr,
                    "top_pixels": [float(x) for x in np.sort(lum.ravel())[-5:]]}
json.dump(result, open(out, "w"), indent=1)
print(json.dumps(result, indent=1))
PY
