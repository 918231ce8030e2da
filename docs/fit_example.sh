#!/usr/bin/env bash
# The README's worked example of `arbor compare --fit-treemaker`: the default scene rendered
# exactly (path tracer) and approximately (TREE-MAKER's shading), the weights fitted, the
# approximate image rendered again with them, and the pictures of both comparisons.
# Usage: docs/fit_example.sh [OUT_DIR]   (default out/fit_example; build first: make build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
arbor="$root/build/app/arbor"
out="${1:-$root/out/fit_example}"
mkdir -p "$out"
size=(--width 320 --height 240)

"$arbor" render "$root/scenes/default.toml" "${size[@]}" --spp 256 \
  -o "$out/exact.exr" --png "$out/exact.png"
"$arbor" render "$root/scenes/default_treemaker.toml" "${size[@]}" \
  -o "$out/treemaker.exr" --png "$out/treemaker.png"
"$arbor" compare "$out/treemaker.exr" "$out/exact.exr" --fit-treemaker \
  --side-by-side "$out/treemaker_vs_exact.png" | tee "$out/fit.txt"
"$arbor" compare "$out/treemaker.exr" "$out/exact.exr" --fit-treemaker --json > "$out/fit.json"

# The same scene with the fitted weights as its [tree.treemaker] table (species path made
# absolute, since the scene now lives in OUT_DIR).
python3 - "$root" "$out" <<'PY'
import json, sys
root, out = sys.argv[1], sys.argv[2]
weights = json.load(open(f"{out}/fit.json"))["treemaker_fit"]["weights"]
scene = open(f"{root}/scenes/default_treemaker.toml").read()
scene = scene.replace('"../species/', f'"{root}/species/')
scene += "\n[tree.treemaker]\n" + "".join(f"{k} = {v:.6f}\n" for k, v in weights.items())
open(f"{out}/fitted.toml", "w").write(scene)
PY
"$arbor" render "$out/fitted.toml" "${size[@]}" -o "$out/fitted.exr" --png "$out/fitted.png"
"$arbor" compare "$out/fitted.exr" "$out/exact.exr" --side-by-side "$out/fitted_vs_exact.png"
echo "fit_example: pictures in $out"
