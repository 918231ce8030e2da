#!/usr/bin/env bash
# Does the default frame read as daylight? (issue 28: the sky's mean luminance 1.4–2.5× the sunlit
# grass's). Renders scenes/default.toml at 240 × 180, 32 spp, and measures from its AOVs: sky
# pixels are those with no depth (Z = 0, what the depth AOV holds where a ray hits nothing);
# grass pixels those whose albedo is the scene's grass patch albedo (within 0.01 per channel);
# sunlit grass is the grass whose luminance over its albedo's is above half the 95th percentile of
# that ratio (sunlit and shaded ground differ by 3–5×). Prints JSON.
# Usage: bench/daylight.sh [BUILD_DIR]   (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
OCIO="${OCIO:-$root/imaging/ocio/config.ocio}" ARBOR_CACHE_DIR=off \
  "$build/app/arbor" render "$root/scenes/default.toml" --width 240 --height 180 --spp 32 \
  -o "$work/default.exr" >/dev/null 2>&1
/usr/bin/python3 - "$work/default.exr" <<'PY'
import json, sys
import numpy as np
import OpenImageIO as oiio
image = oiio.ImageBuf(sys.argv[1])
names = list(image.spec().channelnames)
pixels = image.get_pixels(oiio.FLOAT)
channel = lambda n: pixels[..., names.index(n)]
luminance = lambda r, g, b: 0.2126 * r + 0.7152 * g + 0.0722 * b
lum = luminance(channel("R"), channel("G"), channel("B"))
albedo = np.stack([channel("albedo." + c) for c in "RGB"], -1)
z = channel("Z")
sky = z <= 0.0
grass = np.all(np.abs(albedo - np.array([0.06, 0.11, 0.035])) < 0.01, -1) & ~sky
ratio = lum[grass] / luminance(*albedo[grass].T)
sunlit = ratio > 0.5 * np.percentile(ratio, 95)
sky_mean, grass_mean = float(lum[sky].mean()), float(lum[grass][sunlit].mean())
print(json.dumps({"sky_pixels": int(sky.sum()), "sunlit_grass_pixels": int(sunlit.sum()),
                  "sky_mean_luminance": sky_mean, "sunlit_grass_mean_luminance": grass_mean,
                  "sky_over_sunlit_grass": sky_mean / grass_mean}, indent=2))
PY
