#!/usr/bin/env bash
# A render test: renders reference/<NAME>.toml at its own low sample count and seed, and runs
# `arbor compare --reference-test` against reference/<NAME>.exr. With PERTURBATION the scene is
# changed first and the test expects the comparison to FAIL, showing the check can fail:
#   sun: the sun 15 degrees higher;  albedo: the ground albedo 0.16 -> 0.30 (red);
#   ground2 / leaf2: the ground's albedo, or the leaves' reflectance and transmittance, 2 % lower;
#   bark8: the bark's albedo 8 % lower (the weber_penn scene's aspen; its trunk covers too few
#   pixels for 2 % to show at the test's 32 spp, and 5 % is at the edge: blocks p = 0.005).
# With seed:N the scene is rendered with --seed N instead of its own and must PASS.
# Usage: reference_test.sh ARBOR SOURCE_DIR WORK_DIR NAME [sun|albedo|ground2|leaf2|bark8|seed:N]
set -euo pipefail
arbor="$1" src="$2" work="$3" name="$4" perturbation="${5:-}"
mkdir -p "$work"
scene="$src/reference/$name.toml"
tag="$name${perturbation:+-${perturbation/:/}}"
options=()
case "$perturbation" in
  seed:*) options=(--seed "${perturbation#seed:}"); perturbation="" ;;
esac
if [ -n "$perturbation" ]; then
  append=""
  edit='s/^$//'
  case "$perturbation" in
    sun) edit='s/^elevation = 40.0$/elevation = 55.0/' ;;
    albedo) edit='s/^albedo = \[0.16, 0.14, 0.10\]$/albedo = [0.30, 0.14, 0.10]/' ;;
    ground2) edit='s/^albedo = \[0.16, 0.14, 0.10\]$/albedo = [0.1568, 0.1372, 0.098]/' ;;
    # The aspen's own looks (species/quaking_aspen.toml) times 0.92 or 0.98, as [tree] overrides.
    bark8) append=$'\n[tree.bark]\nalbedo = [0.5336, 0.5244, 0.4784]\n' ;;
    # Into the scene's own (matte) [tree.leaf] table.
    leaf2) edit='s/^cuticle_ior = 1.0$/cuticle_ior = 1.0\nreflectance = [0.0686, 0.2156, 0.0392]\nback_reflectance = [0.1078, 0.2548, 0.0784]\ntransmittance = [0.0588, 0.196, 0.0294]/' ;;
    *) echo "reference_test.sh: unknown perturbation $perturbation" >&2; exit 2 ;;
  esac
  # The copy lives elsewhere: make its relative species paths absolute.
  { sed -e "$edit" -e "s|\"\.\./species/|\"$src/species/|" "$scene"; printf '%s' "$append"; } > "$work/$tag.toml"
  if cmp -s "$scene" "$work/$tag.toml" || ! grep -q "$src/species/" "$work/$tag.toml"; then
    echo "reference_test.sh: the $perturbation perturbation did not change $scene" >&2
    exit 2
  fi
  scene="$work/$tag.toml"
fi
"$arbor" render "$scene" -o "$work/$tag.exr" "${options[@]}"
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
