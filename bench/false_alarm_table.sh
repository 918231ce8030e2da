#!/usr/bin/env bash
# The false-alarm table of `arbor compare --reference-test` (docs/rendering.md, "False alarms by
# the reference's passes"): SCENE rendered as references of P passes (seed 1000, independent
# passes of 16 samples, P in PASSES), and as SEEDS test renders as the README's recipe makes them
# (TEST_SPP samples in 8 independent passes, seeds 2, 3, ...); every test render compared with
# every reference. Prints one line per (P, seed): the per-pixel pass fraction, the image-mean and
# block parts, and whether the whole test passed; then a summary per P. Every test render renders
# the same scene as the references: each failure is a false alarm.
#   [SCENE=file.toml] [SIZE="--width W --height H"] [TEST_SPP=N] \
#     bench/false_alarm_table.sh ARBOR [WORK_DIR] [SEEDS] [PASSES...]   (default 4 seeds; 8 16 64)
# Defaults: reference/weber_penn.toml at its size, TEST_SPP 32.
set -euo pipefail
arbor=$1 work=${2:-out/false_alarm} seeds=${3:-4}
shift $(( $# >= 3 ? 3 : $# ))
passes=("$@")
[ ${#passes[@]} -gt 0 ] || passes=(8 16 64)
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$work"
scene=${SCENE:-$src/reference/weber_penn.toml}
test_spp=${TEST_SPP:-32}
read -r -a size <<< "${SIZE:-}"
# Copies of the scene with independent passes, of 16 samples (references) and of TEST_SPP / 8
# (test renders), its relative paths made absolute.
copy() {  # copy PASS_SPP OUT
  sed -e '/^pass_spp *=/d' -e '/^independent_passes *=/d' -e "s|\"\.\./|\"$(dirname "$scene")/../|" "$scene" |
    sed -e "0,/^\[render\]/s//[render]\npass_spp = $1\nindependent_passes = true/" > "$2"
  grep -q '^aovs.*variance' "$2" || sed -i 's/^\[output\]/[output]\naovs = ["variance"]/' "$2"
  grep -q '^\[output\]' "$2" || printf '[output]\naovs = ["variance"]\n' >> "$2"
}
copy 16 "$work/reference.toml"
copy $((test_spp / 8)) "$work/test.toml"
for p in "${passes[@]}"; do
  ref="$work/ref-$p.exr"
  [ -s "$ref" ] || "$arbor" render "$work/reference.toml" "${size[@]}" --seed 1000 --spp $((16 * p)) -o "$ref" 2>/dev/null
done
for s in $(seq 2 $((seeds + 1))); do
  [ -s "$work/test-$s.exr" ] || "$arbor" render "$work/test.toml" "${size[@]}" --spp "$test_spp" --seed "$s" -o "$work/test-$s.exr" 2>/dev/null
done
for p in "${passes[@]}"; do
  fails=0
  for s in $(seq 2 $((seeds + 1))); do
    json=$("$arbor" compare "$work/test-$s.exr" "$work/ref-$p.exr" --reference-test --json || true)
    line=$(printf '%s' "$json" | python3 -c 'import json, sys
j = json.load(sys.stdin)
print("%.4f (%d pixels) mean %s blocks p=%.3g passed=%s" % (j["z_test_pass_fraction"], j["failed_pixels"],
      j["mean_passed"], j["block_p"], j["passed"]))')
    case $line in *passed=False*) fails=$((fails + 1)) ;; esac
    echo "passes $p seed $s: pixel pass fraction $line"
  done
  echo "passes $p: $fails of $seeds test renders failed"
done
