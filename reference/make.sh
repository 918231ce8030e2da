#!/usr/bin/env bash
# Re-renders the reference images: each reference/<name>.toml at 1024 samples per pixel with
# seed 1000 (independent of the tests' seed 1), in the scene's passes (pass_spp = 4: 256 passes), to
# reference/<name>.exr (half RGB, float variance of the pixel mean across the passes). Usage: reference/make.sh [BUILD_DIR] [NAME...]
# Run it after a change that is meant to change images, look at the images, then commit them.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
shift || true
names=("$@")
[ ${#names[@]} -eq 0 ] && names=(weber_penn lsystem fractal treemaker skeleton forest)
arbor="$build/app/arbor"
[ -x "$arbor" ] || { echo "make.sh: no arbor at $arbor (build first: make build)" >&2; exit 2; }
for name in "${names[@]}"; do
  start=$(date +%s)
  "$arbor" render "$here/$name.toml" --spp 1024 --seed 1000 -o "$here/$name.exr"
  echo "make.sh: $name.exr in $(( $(date +%s) - start )) s" >&2
done
