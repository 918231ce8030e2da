#!/usr/bin/env bash
# What aerial perspective costs a render: SCENE (scenes/forest_10000.toml) at 320×180, 16 spp, two
# threads, rendered ROUNDS times interleaved with `[render] aerial_perspective` false and true (a
# copy of the scene with the key set; the sky map from a warm cache of its own, so the difference
# is the aerial table — the atmosphere model and its 64×32×32 entries — and the lookups at every
# camera hit), CPU seconds (user + system via /usr/bin/time). Prints the ranges and medians and
# writes bench/results/aerial.json.
#
#   bench/aerial.sh [ARBOR (build/app/arbor)] [ROUNDS (3)] [SCENE]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
arbor=${1:-$root/build/app/arbor} rounds=${2:-3} scene=${3:-$root/scenes/forest_10000.toml}
out=$root/bench/results/aerial.json
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d "$(dirname "$scene")/.aerial-bench.XXXXXX")  # beside the scene: its paths resolve
trap 'rm -rf "$tmp"' EXIT
for on in false true; do
  python3 - "$scene" "$tmp/$on.toml" "$on" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
text = re.sub(r"(?m)^aerial_perspective\s*=.*\n", "", text)
text = re.sub(r"(?m)^\[render\]\n", "[render]\naerial_perspective = " + sys.argv[3] + "\n", text, 1)
open(sys.argv[2], "w").write(text.replace('"../', '"../../'))
PY
done
run() {  # run false|true → CPU seconds
  ARBOR_CACHE_DIR=$tmp/cache /usr/bin/time -f "%U %S" -o "$tmp/t" "$arbor" render "$tmp/$1.toml" \
    --width 320 --height 180 --spp 16 --threads 2 -o "$tmp/$1.exr" 2> /dev/null
  awk '{printf "%.3f\n", $1 + $2}' "$tmp/t"
}
run false > /dev/null  # warm the sky cache
for r in $(seq "$rounds"); do
  echo "off $(run false)" >> "$tmp/runs"
  echo "on $(run true)" >> "$tmp/runs"
done
python3 "$root/bench/cpu_runs.py" "$tmp/runs" "$out"
