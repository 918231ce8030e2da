#!/usr/bin/env bash
# Installs the Debian 12 packages arbor needs: exactly those missing, nothing when all are present.
# --fuzz: what `make fuzz` needs instead (clang and its libFuzzer and sanitizer runtimes).
# --farm: what the farm test (`ctest -L farm`) needs instead: a single-node Slurm and munge.
# --clients: what the clients test (`ctest -L clients`, `make test-clients`) needs instead: Blender
#   (headless) and OpenImageIO's Python binding, which Blender's Python imports.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libembree-dev          # Embree 3.13: ray tracing of curves, grids, triangles
  libopenimageio-dev     # OpenImageIO 2.4: textures, environment maps, compare (libarbor_oiio.so)
  openimageio-tools      # oiiotool / idiff, used by checks
  libopenexr-dev         # OpenEXR 3.1
  libpng-dev             # libpng: the PNG a render writes (without loading OpenImageIO)
  python3-imath          # Debian's Imath CMake targets name its Python binding library
  libopencolorio-dev     # OpenColorIO 2.1
  libglm-dev             # GLM 0.9.9
  libtbb-dev             # oneTBB
  libtomlplusplus-dev    # toml++: species and scene files
  libcli11-dev           # CLI11: the command line
  libpugixml-dev         # pugixml: Arbaro XML species
  libtinyobjloader-dev   # tinyobjloader: an independent OBJ reader for the export tests
  libgtest-dev libgmock-dev  # GoogleTest
  libbenchmark-dev       # Google Benchmark
  fonts-dejavu-core      # the font of the scale bar in compare heatmaps
  clang-format           # the layout check (ctest layout.format, .clang-format)
  universal-ctags        # the function-length check parses the sources (tools/function-lengths.sh)
)

if [ "${1:-}" = "--fuzz" ]; then
  packages=(clang libclang-rt-14-dev)
fi
if [ "${1:-}" = "--clients" ]; then
  packages=(blender python3-openimageio python3-numpy)
fi
if [ "${1:-}" = "--farm" ]; then
  packages=(slurmctld slurmd slurm-client munge openimageio-tools)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "arbor: installing missing packages: ${missing[*]}" >&2
if [ "$(id -u)" -ne 0 ]; then
  echo "arbor: these Debian packages are missing and installing them needs root:" >&2
  echo "  apt-get install ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
