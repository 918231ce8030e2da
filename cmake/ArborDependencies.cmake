# Finds every dependency; a missing one names the Debian 12 package that provides it.

macro(arbor_require package debian_package)
  find_package(${package} ${ARGN} QUIET)
  if(NOT ${package}_FOUND)
    message(FATAL_ERROR
      "arbor needs ${package}, which was not found.\n"
      "On Debian 12 install it with:  apt-get install ${debian_package}\n"
      "(or run tools/install-deps.sh, which installs everything arbor needs).")
  endif()
endmacro()

arbor_require(glm libglm-dev CONFIG)
arbor_require(tomlplusplus libtomlplusplus-dev CONFIG)
arbor_require(CLI11 libcli11-dev CONFIG)
arbor_require(pugixml libpugixml-dev CONFIG)
arbor_require(tinyobjloader libtinyobjloader-dev CONFIG)
arbor_require(TBB libtbb-dev CONFIG)
arbor_require(embree libembree-dev 3.13 CONFIG)
arbor_require(OpenImageIO libopenimageio-dev CONFIG)
arbor_require(OpenEXR "libopenexr-dev python3-imath" CONFIG)
# Debian 12 installs OpenColorIOConfig.cmake straight into /usr/share/cmake.
arbor_require(OpenColorIO libopencolorio-dev CONFIG PATHS /usr/share/cmake)
if(ARBOR_BUILD_TESTS)
  arbor_require(GTest "libgtest-dev libgmock-dev" CONFIG)
endif()
if(ARBOR_BUILD_BENCH)
  arbor_require(benchmark libbenchmark-dev CONFIG)
endif()
