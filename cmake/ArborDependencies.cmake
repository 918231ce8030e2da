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
arbor_require(PNG libpng-dev)
# Debian 12's OpenColorIOConfig.cmake (in /usr/share/cmake) computes a wrong install prefix, so
# the target is defined here from the header and the library.
find_path(ARBOR_OCIO_INCLUDE_DIR OpenColorIO/OpenColorIO.h)
find_library(ARBOR_OCIO_LIBRARY OpenColorIO)
if(NOT ARBOR_OCIO_INCLUDE_DIR OR NOT ARBOR_OCIO_LIBRARY)
  message(FATAL_ERROR
    "arbor needs OpenColorIO, which was not found.\n"
    "On Debian 12 install it with:  apt-get install libopencolorio-dev\n"
    "(or run tools/install-deps.sh, which installs everything arbor needs).")
endif()
add_library(OpenColorIO::OpenColorIO UNKNOWN IMPORTED)
set_target_properties(OpenColorIO::OpenColorIO PROPERTIES
  IMPORTED_LOCATION "${ARBOR_OCIO_LIBRARY}"
  INTERFACE_INCLUDE_DIRECTORIES "${ARBOR_OCIO_INCLUDE_DIR}")
if(ARBOR_BUILD_TESTS)
  arbor_require(GTest "libgtest-dev libgmock-dev" CONFIG)
endif()
if(ARBOR_BUILD_BENCH)
  arbor_require(benchmark libbenchmark-dev CONFIG)
endif()

# Debian 12's OpenImageIO targets list /usr/include/opencv4 (from libopencv-dev, which arbor does
# not need); keep only the include directories that exist.
foreach(target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${target})
    get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
    if(dirs)
      set(existing "")
      foreach(dir IN LISTS dirs)
        if(EXISTS "${dir}")
          list(APPEND existing "${dir}")
        endif()
      endforeach()
      set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${existing}")
    endif()
  endif()
endforeach()
