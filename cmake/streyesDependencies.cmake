# The libraries streyes links (Debian 12 packages; see ../shared/DEPENDENCIES.md). Included by
# the project's CMakeLists.txt and by the installed streyesConfig.cmake, so that a program using
# the package finds the same targets.

# A library Debian ships without a usable CMake package, as an imported target: the folder that
# holds `header`, and the library file `name`.
function(streyes_import_library target header name)
  if(TARGET ${target})
    return()
  endif()
  string(MAKE_C_IDENTIFIER "${target}" id)
  find_path(${id}_INCLUDE_DIR ${header} REQUIRED)
  find_library(${id}_LIBRARY ${name} REQUIRED)
  add_library(${target} UNKNOWN IMPORTED)
  set_target_properties(${target} PROPERTIES IMPORTED_LOCATION "${${id}_LIBRARY}"
                                             INTERFACE_INCLUDE_DIRECTORIES "${${id}_INCLUDE_DIR}")
endfunction()

if(NOT TARGET TBB::tbb)
  find_package(TBB 2021 CONFIG REQUIRED COMPONENTS tbb)
endif()
find_package(hwy 1.0 CONFIG REQUIRED)  # Highway: the sampler's SIMD kernels
# Boost.Wave: the C preprocessor in front of the Shading Language compiler (src/shade/sl/preprocess.cpp).
find_package(Boost 1.74 CONFIG REQUIRED COMPONENTS wave)
find_package(Imath 3.1 CONFIG REQUIRED)
find_package(OpenEXR 3.1 CONFIG REQUIRED)
# nlohmann-json: every JSON file read or written (--stats, the farm's manifest, compare --json).
find_package(nlohmann_json 3.11 CONFIG REQUIRED)
# zlib: gzip-compressed RIB, read and written (src/scene/rib_gzip.cpp).
find_package(ZLIB REQUIRED)
# nanoflann (header only; Debian's 1.4.3 ships no CMake package): the k-d tree texture3d() finds a
# point cloud's nearest points with (src/shade/point_cloud.cpp).
find_path(NANOFLANN_INCLUDE_DIR nanoflann.hpp REQUIRED)
# libdeflate (Debian's 1.14 ships no CMake package): the frames' ZIP compression (src/io/exr_file.cpp).
streyes_import_library(libdeflate::libdeflate libdeflate.h deflate)
find_package(OpenImageIO 2.4 CONFIG REQUIRED)
# Debian's OIIO target lists /usr/include/opencv4, which exists only with libopencv-dev: drop it.
foreach(_prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
  get_target_property(_dirs OpenImageIO::OpenImageIO ${_prop})
  if(_dirs)
    list(FILTER _dirs EXCLUDE REGEX "opencv")
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${_prop} "${_dirs}")
  endif()
endforeach()
# Debian's OpenSubdivConfig.cmake fails (it names static libraries the package does not ship):
# import the CPU library by hand. Far (topology) and Bfr (limit evaluation) live in osdCPU.
streyes_import_library(OpenSubdiv::osdCPU opensubdiv/version.h osdCPU)
