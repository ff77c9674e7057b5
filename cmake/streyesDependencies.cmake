# The libraries streyes links (Debian 12 packages; see ../shared/DEPENDENCIES.md). Included by
# the project's CMakeLists.txt and by the installed streyesConfig.cmake, so that a program using
# the package finds the same targets.
if(NOT TARGET TBB::tbb)
  find_package(TBB 2021 CONFIG REQUIRED COMPONENTS tbb)
endif()
find_package(hwy 1.0 CONFIG REQUIRED)  # Highway: the sampler's SIMD kernels
find_package(Imath 3.1 CONFIG REQUIRED)
find_package(OpenEXR 3.1 CONFIG REQUIRED)
# libdeflate (Debian's 1.14 ships no CMake package): the frames' ZIP compression (src/io/exr_file.cpp).
find_path(LIBDEFLATE_INCLUDE_DIR libdeflate.h REQUIRED)
find_library(LIBDEFLATE_LIBRARY deflate REQUIRED)
if(NOT TARGET libdeflate::libdeflate)
  add_library(libdeflate::libdeflate UNKNOWN IMPORTED)
  set_target_properties(libdeflate::libdeflate PROPERTIES
    IMPORTED_LOCATION "${LIBDEFLATE_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LIBDEFLATE_INCLUDE_DIR}")
endif()
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
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/version.h REQUIRED)
find_library(OPENSUBDIV_OSDCPU_LIBRARY osdCPU REQUIRED)
if(NOT TARGET OpenSubdiv::osdCPU)
  add_library(OpenSubdiv::osdCPU UNKNOWN IMPORTED)
  set_target_properties(OpenSubdiv::osdCPU PROPERTIES
    IMPORTED_LOCATION "${OPENSUBDIV_OSDCPU_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OPENSUBDIV_INCLUDE_DIR}")
endif()
