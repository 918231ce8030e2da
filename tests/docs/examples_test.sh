#!/usr/bin/env bash
# The documentation's examples run: every line of a ```sh block in README.md, docs/*.md and
# scenes/README.md that starts with `arbor`, `build/app/arbor` or `$ arbor` is run as written (its
# `\` continuations joined, its trailing comment dropped) in a scratch directory holding copies of
# scenes/ and species/, and must exit 0 (`compare --reference-test` may also exit 1: it fails a
# test, not a usage). Renders are shrunk to 64x48 at 2 spp (a crop to the size its window needs)
# so the whole takes a minute; plans, merges, exports, grows and compares run unchanged. The files
# the examples name but do not make (big.toml, my_scene.toml, scene.toml, mine.exr,
# reference.exr) are made first from the default scene.
#
#   tests/docs/examples_test.sh ARBOR_EXECUTABLE SOURCE_DIR
set -euo pipefail

arbor=$(realpath "$1")
source_dir=$(realpath "$2")
scratch=$(mktemp -d "${TMPDIR:-/tmp}/arbor_examples.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

cp -r "$source_dir/scenes" "$source_dir/species" "$scratch/"
mkdir -p "$scratch/build/app" "$scratch/bin" "$scratch/farm"
ln -s "$arbor" "$scratch/build/app/arbor"
ln -s "$arbor" "$scratch/bin/arbor"
export PATH="$scratch/bin:$PATH"
cd "$scratch"

# The fixtures: the default scene, small; big.toml in 16 passes of one sample (for --passes 0:8
# and 8:16), and a reference with an unbiased variance (independent passes) to compare against.
small_scene() {  # $1 spp, $2 pass_spp, $3 extra [render] line: only [render]'s keys change
  awk -v spp="$1" -v pass="$2" -v extra="$3" '
    /^\[/ { render = ($0 == "[render]") }
    render && /^width = / { print "width = 64"; next }
    render && /^height = / { print "height = 48"; next }
    render && /^pass_spp = / { next }
    render && /^spp = / {
      print "spp = " spp; print "pass_spp = " pass; if (extra != "") print extra; next
    }
    { print }
  ' scenes/default.toml | sed 's|"\.\./species/|"species/|'
}
small_scene 16 1 "" >big.toml
small_scene 2 1 "" >my_scene.toml
small_scene 2 1 "" >scene.toml
small_scene 8 1 "independent_passes = true" >ref.toml
arbor render ref.toml -o reference.exr 2>/dev/null
arbor render ref.toml -o mine.exr --seed 2 2>/dev/null

# Every example, one per line.
mapfile -t examples < <(
  cd "$source_dir"
  awk '
    /^```sh/ { block = 1; next }
    /^```/ { block = 0; pending = ""; next }
    !block { next }
    {
      line = $0
      if (pending != "") { line = pending " " line; pending = "" }
      if (line ~ /\\$/) { pending = substr(line, 1, length(line) - 1); next }
      sub(/^\$ /, "", line)
      if (line !~ /^(build\/app\/)?arbor /) next
      sub(/[ \t]+# .*$/, "", line)
      print line
    }' README.md docs/*.md scenes/README.md
)
if ((${#examples[@]} < 25)); then
  echo "examples_test: found only ${#examples[@]} examples; the extraction is broken" >&2
  exit 1
fi

shrink() {  # a render example at a size a test affords
  local line=$1
  line=$(sed -E 's/ --(width|height|spp) [0-9]+//g' <<<"$line")
  if [[ $line == *" --crop "* ]]; then
    echo "$line --width 240 --height 360 --spp 1"
  elif [[ $line == *" --passes "* || $line == *" big.toml "* ]]; then
    echo "$line"  # big.toml is small already; its passes must stay as planned
  else
    echo "$line --width 64 --height 48 --spp 2"
  fi
}

failed=0
for example in "${examples[@]}"; do
  command=${example//\/farm\//farm\/}
  [[ $command =~ ^(build/app/)?arbor\ render ]] && command=$(shrink "$command")
  set +e
  bash -c "$command" >"$scratch/out.txt" 2>&1
  code=$?
  set -e
  allowed=0
  [[ $command == *"--reference-test"* && $code == 1 ]] && allowed=1
  if [[ $code != 0 && $allowed == 0 ]]; then
    echo "examples_test: exit $code from: $example" >&2
    echo "  ran: $command" >&2
    sed 's/^/  | /' "$scratch/out.txt" | tail -8 >&2
    failed=$((failed + 1))
  else
    echo "ok: $example"
  fi
done
echo "examples_test: ${#examples[@]} examples, $failed failed"
((failed == 0))
