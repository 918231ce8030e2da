#!/usr/bin/env bash
# Installs arbor into a fresh prefix with `cmake --install`, then renders a shipped scene with the
# installed binary from an unrelated folder, with no $OCIO: the installed arbor must find its own
# OCIO config, species and scenes beside itself.
# Usage: install_test.sh BUILD_DIR WORK_DIR
set -euo pipefail
build="$1" work="$2"
rm -rf "$work" && mkdir -p "$work/prefix" "$work/elsewhere"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
for f in bin/arbor bin/arbor-slurm share/arbor/ocio/config.ocio share/arbor/species/quaking_aspen.toml \
         share/arbor/scenes/default.toml share/bash-completion/completions/arbor; do
  [ -e "$work/prefix/$f" ] || { echo "install_test.sh: $f was not installed" >&2; exit 1; }
done
cd "$work/elsewhere"
env -u OCIO "$work/prefix/bin/arbor" render "$work/prefix/share/arbor/scenes/default.toml" \
  -o out.exr --png out.png --spp 1 --width 32 --height 24
[ -s out.exr ] && [ -s out.png ] || { echo "install_test.sh: no image written" >&2; exit 1; }
# Without -o, an installed scene's own outputs (out/default.exr, relative to the scene) go under
# the current folder, not into <prefix>/share/arbor/.
env -u OCIO "$work/prefix/bin/arbor" render "$work/prefix/share/arbor/scenes/default.toml" \
  --spp 1 --width 32 --height 24 2> own.log
[ -s out/default.exr ] || { echo "install_test.sh: the installed scene's output is not under the current folder" >&2; cat own.log >&2; exit 1; }
if [ -e "$work/prefix/share/arbor/scenes/out" ]; then
  echo "install_test.sh: the installed scene wrote into the installed share folder" >&2; exit 1
fi
grep -q "is an installed scene" own.log || { echo "install_test.sh: no note of where the outputs went" >&2; exit 1; }
# The installed binary must not lean on the source or build tree's config.
if strings "$work/prefix/bin/arbor" | grep -q "$(dirname "$build")/imaging/ocio"; then
  echo "install_test.sh: the binary names the source tree's OCIO config" >&2
  exit 1
fi
# The bash completion: subcommands, options from the subcommand's own --help, files by kind.
complete_words() {  # prints what completing the last word of "$@" offers
  bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(( $# - 1 )); _arbor; printf "%s\n" "${COMPREPLY[@]}"' \
    _ "$work/prefix/share/bash-completion/completions/arbor" "$@"
}
touch tree.toml notes.txt
complete_words "$work/prefix/bin/arbor" ren | grep -qx render || { echo "install_test.sh: no subcommand completion" >&2; exit 1; }
complete_words "$work/prefix/bin/arbor" render --sp | grep -qx -- --spp || { echo "install_test.sh: no option completion" >&2; exit 1; }
complete_words "$work/prefix/bin/arbor" render t | grep -qx tree.toml || { echo "install_test.sh: no scene file completion" >&2; exit 1; }
if complete_words "$work/prefix/bin/arbor" render n | grep -q notes.txt; then
  echo "install_test.sh: render completes a file that is not a scene" >&2; exit 1
fi
echo "install_test.sh: the installed arbor rendered from $work/elsewhere, and its completion works"
