#!/usr/bin/env bash
# Renders every shipped scene at full quality into docs/images/<scene>.png (the pictures the README
# and the docs show). Usage: docs/gallery.sh [BUILD_DIR] [SCENE...]   (default: build, all scenes)
# About fifteen minutes on a 2-core machine; the images are deterministic for a given binary.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
shift || true
arbor="$build/app/arbor"
[ -x "$arbor" ] || { echo "gallery.sh: no arbor at $arbor (build first: make build)" >&2; exit 2; }
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(default autumn default_treemaker dogwood fractal lsystem forest forest_10000 hillside valley)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for name in "${scenes[@]}"; do
  spp=256
  [ "$name" = forest_10000 ] && spp=64   # 640×360 over 10,000 trees: the scale test, not a still
  # The landscapes at their own 64 spp (1280×720; the valley about 6 minutes here).
  if [ "$name" = hillside ] || [ "$name" = valley ]; then
    "$arbor" render "$root/scenes/$name.toml" -o "$work/$name.exr" --png "$root/docs/images/$name.png"
    continue
  fi
  "$arbor" render "$root/scenes/$name.toml" --spp "$spp" -o "$work/$name.exr" --png "$root/docs/images/$name.png"
done
