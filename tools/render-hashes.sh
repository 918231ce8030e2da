#!/usr/bin/env bash
# Renders every scene in scenes/ and reference/ (and grows every shipped species) with the given
# arbor, and prints one line per output: the SHA-1 of its pixels (EXR, PNG) or bytes (grow
# exports, statistics). Two builds that print the same lines make bit-identical images and trees.
#
#   tools/render-hashes.sh ARBOR OUTDIR [render options, e.g. --spp 4 --width 96 --height 72]
#
# Used to check that a refactoring changes no image: run it with the old and the new binary and
# diff the two outputs. Full-size renders of scenes/ take minutes; pass smaller options for a
# quick check (the same code runs, fewer pixels and samples).
set -euo pipefail
arbor=$(realpath "$1"); out=$2; shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
for scene in "$root"/scenes/*.toml "$root"/reference/*.toml; do
  name=$(basename "$(dirname "$scene")")_$(basename "$scene" .toml)
  "$arbor" render "$scene" -o "$out/$name.exr" --png "$out/$name.png" --threads 2 "$@" 2>>"$out/log"
  for f in "$out/$name.exr" "$out/$name.png"; do
    echo "$(basename "$f") $(iinfo --hash "$f" | sed -n 's/.*SHA-1: *//p')"
  done
done
# compare's metrics, heatmap and side-by-side, and the TREE-MAKER weight fit.
"$arbor" compare "$out/scenes_default.exr" "$out/scenes_default_treemaker.exr" --json \
  --heatmap "$out/heatmap.png" --side-by-side "$out/side.png" > "$out/compare.json" || true
"$arbor" compare "$out/scenes_default.exr" "$out/scenes_default_treemaker.exr" --fit-treemaker \
  > "$out/fit.txt" || true
# Paths and timings differ between runs: hashed without them.
strip() { sed -e "s|$out|OUT|g" -e 's/"\(geometry_\)\{0,1\}seconds": [0-9.e+-]*//g' "$1" | sha1sum | cut -d' ' -f1; }
echo "compare.json $(strip "$out/compare.json")"
echo "fit.txt $(strip "$out/fit.txt")"
for f in "$out/heatmap.png" "$out/side.png"; do
  echo "$(basename "$f") $(iinfo --hash "$f" | sed -n 's/.*SHA-1: *//p')"
done
# The pbrt-v4 export of every shipped scene: the scene text, its sky and its ground image.
for scene in "$root"/scenes/*.toml; do
  name=export_$(basename "$scene" .toml)
  "$arbor" export "$scene" -o "$out/$name.pbrt" --width 96 --height 72 --sky-resolution 64 2>>"$out/log"
  (cd "$out" && sed "s|$out|OUT|g" "$name.pbrt" | sha1sum | sed "s|-|$name.pbrt|")
  for f in "$out/$name".*.exr; do
    echo "$(basename "$f") $(iinfo --hash "$f" | sed -n 's/.*SHA-1: *//p')"
  done
done
for species in "$root"/species/*; do
  name=$(basename "$species")
  "$arbor" grow "$species" --seed 7 --json > "$out/$name.json"
  echo "$name.json $(strip "$out/$name.json")"
  for ext in obj pbrt skel; do
    "$arbor" grow "$species" --seed 7 -o "$out/$name.$ext" 2>>"$out/log"
  done
  (cd "$out" && sha1sum "$name.obj" "$name.pbrt" "$name.skel")
  # Hashed: the full-size tree exports (about 6 GB over all species) are not kept.
  rm -f "$out/$name.obj" "$out/$name.mtl" "$out/$name.pbrt" "$out/$name.skel"
done
