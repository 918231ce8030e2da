#!/usr/bin/env bash
# Re-makes docs/images/ramiform.png: scenes/ramiform.toml (a leafless Quaking Aspen's first forks
# with Bloomenthal's ramiform, left) beside the same view without it (right: the species file
# with `ramiform = true` taken out). Usage: docs/ramiform.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OCIO="${OCIO:-$here/../imaging/ocio/config.ocio}" ARBOR_CACHE_DIR=off
grep -v '^ramiform = true' "$here/../species/quaking_aspen_ramiform.toml" > "$work/off.toml"
sed -e "s#\.\./species/quaking_aspen_ramiform.toml#$work/off.toml#" -e "s#\.\./out/#$work/#" \
  "$here/../scenes/ramiform.toml" > "$work/scene_off.toml"
"$build/app/arbor" render "$here/../scenes/ramiform.toml" -o "$work/on.exr" --png "$work/on.png" --force
"$build/app/arbor" render "$work/scene_off.toml" -o "$work/off.exr" --png "$work/off.png" --force
oiiotool "$work/on.png" "$work/off.png" --mosaic:pad=8 2x1 -o "$here/images/ramiform.png"
echo "wrote $here/images/ramiform.png"
