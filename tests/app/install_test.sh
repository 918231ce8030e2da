#!/usr/bin/env bash
# Installs arbor into a fresh prefix with `cmake --install`, then renders a shipped scene with the
# installed binary from an unrelated folder, with no $OCIO: the installed arbor must find its own
# OCIO config, species and scenes beside itself.
# Usage: install_test.sh BUILD_DIR WORK_DIR
set -euo pipefail
build="$1" work="$2"
rm -rf "$work" && mkdir -p "$work/prefix" "$work/elsewhere"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
for f in bin/arbor share/arbor/ocio/config.ocio share/arbor/species/quaking_aspen.toml \
         share/arbor/scenes/default.toml; do
  [ -e "$work/prefix/$f" ] || { echo "install_test.sh: $f was not installed" >&2; exit 1; }
done
cd "$work/elsewhere"
env -u OCIO "$work/prefix/bin/arbor" render "$work/prefix/share/arbor/scenes/default.toml" \
  -o out.exr --png out.png --spp 1 --width 32 --height 24
[ -s out.exr ] && [ -s out.png ] || { echo "install_test.sh: no image written" >&2; exit 1; }
# The installed binary must not lean on the source or build tree's config.
if strings "$work/prefix/bin/arbor" | grep -q "$(dirname "$build")/imaging/ocio"; then
  echo "install_test.sh: the binary names the source tree's OCIO config" >&2
  exit 1
fi
echo "install_test.sh: the installed arbor rendered from $work/elsewhere"
