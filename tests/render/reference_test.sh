#!/usr/bin/env bash
# A render test: renders reference/<NAME>.toml at its own low sample count and seed, and runs
# `arbor compare --reference-test` against reference/<NAME>.exr. With PERTURBATION (sun: the sun
# moved 15 degrees higher; albedo: a different ground albedo) the scene is changed first and the
# test expects the comparison to FAIL, showing the check can fail.
# Usage: reference_test.sh ARBOR SOURCE_DIR WORK_DIR NAME [sun|albedo]
set -euo pipefail
arbor="$1" src="$2" work="$3" name="$4" perturbation="${5:-}"
mkdir -p "$work"
scene="$src/reference/$name.toml"
tag="$name${perturbation:+-$perturbation}"
if [ -n "$perturbation" ]; then
  case "$perturbation" in
    sun) edit='s/^elevation = 40.0$/elevation = 55.0/' ;;
    albedo) edit='s/^albedo = \[0.16, 0.14, 0.10\]$/albedo = [0.30, 0.14, 0.10]/' ;;
    *) echo "reference_test.sh: unknown perturbation $perturbation" >&2; exit 2 ;;
  esac
  # The copy lives elsewhere: make its relative species paths absolute.
  sed -e "$edit" -e "s|\"\.\./species/|\"$src/species/|" "$scene" > "$work/$tag.toml"
  if cmp -s "$scene" "$work/$tag.toml" || ! grep -q "$src/species/" "$work/$tag.toml"; then
    echo "reference_test.sh: the $perturbation perturbation did not change $scene" >&2
    exit 2
  fi
  scene="$work/$tag.toml"
fi
"$arbor" render "$scene" -o "$work/$tag.exr"
set +e
"$arbor" compare "$work/$tag.exr" "$src/reference/$name.exr" --reference-test \
  --heatmap "$work/$tag-heatmap.png"
code=$?
set -e
if [ -z "$perturbation" ]; then
  [ "$code" -eq 0 ] || { echo "reference_test.sh: $name does not match its reference (exit $code)" >&2; exit 1; }
else
  [ "$code" -eq 1 ] || { echo "reference_test.sh: the $perturbation-perturbed $name was not rejected (exit $code)" >&2; exit 1; }
fi
echo "reference_test.sh: $tag as expected"
