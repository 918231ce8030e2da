#!/usr/bin/env bash
# Re-makes docs/images/buttresses.png: the Black Tupelo with `[roots] buttresses = 7` added to
# its species file, the trunk's base seen close up. Usage: docs/buttresses.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
{ cat "$here/../species/black_tupelo.toml"; printf '\n[roots]\nbuttresses = 7\n'; } > "$work/tupelo_roots.toml"
cat > "$work/scene.toml" <<SCENE
[render]
width = 480
height = 360
spp = 64
max_depth = 6

[camera]
position = [2.6, -3.6, 1.1]
look_at = [0.0, 0.0, 0.7]
fov = 45.0
exposure = 0.75

[sun]
elevation = 35.0
azimuth = -40.0
irradiance = 3.0

[sky]
model = "nishita"          # the default scene's look (issue 14): a clear day with a little haze
dust_density = 3.0

[ground]
albedo = [0.16, 0.14, 0.10]
patch_albedo = [0.06, 0.11, 0.035]
patch_cover = 0.6
patch_scale = 2.5

[[tree]]
species = "$work/tupelo_roots.toml"
seed = 5

[output]
png = "$here/images/buttresses.png"
SCENE
"$build/app/arbor" render "$work/scene.toml"
