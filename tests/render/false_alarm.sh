#!/usr/bin/env bash
# The false-alarm rate of `compare --reference-test` on real renders: reference/NAME.toml
# rendered with seeds 2 .. COUNT+1 (each independent of the reference's seed 1000) must pass; the
# script prints how many did not and fails when more than MAX of them did not (the test's alpha
# is 0.01 per test, about 0.02 for the three together: 20 renders fail more than 2 with
# probability under 1 %). ctest label long (not run by make test).
# Usage: false_alarm.sh ARBOR SOURCE_DIR WORK_DIR NAME [COUNT] [MAX]
set -euo pipefail
arbor="$1" src="$2" work="$3" name="$4" count="${5:-20}" max="${6:-2}"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$work"
failed=0
for seed in $(seq 2 $((count + 1))); do
  if ! bash "$here/reference_test.sh" "$arbor" "$src" "$work" "$name" "seed:$seed" > "$work/$name-seed$seed.log" 2>&1; then
    failed=$((failed + 1))
    echo "false_alarm.sh: seed $seed failed:" >&2
    grep -E "pixels:|image mean|blocks:|noisy" "$work/$name-seed$seed.log" >&2 || true
  fi
  grep -E "pixels:|image mean|blocks:" "$work/$name-seed$seed.log" | tr -s ' ' | sed "s/^/seed $seed: /"
done
echo "false_alarm.sh: $name: $failed of $count independent renders failed the reference test"
[ "$failed" -le "$max" ]
