# SPDX-License-Identifier: BSD-3-Clause
# One place for the compile settings of every hif target (kiss-icp / mola_common pattern).
function(hif_set_target_options target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wconversion
      -Wno-sign-conversion)
    if(HIF_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
endfunction()

# A test program's compile settings. Its sources compiled four at a time (CMake's unity build):
# they share the parsing of gtest's, MRPT's and Eigen's headers, which is most of a test file's
# compile time, and the tests build in half the time. The library and the apps, what users run,
# are compiled one source at a time as before. And in a Release build, the test code itself at
# -O1: what the tests run is mostly the library's and the apps' code, built at -O3; the test
# programs compile in 90 s of CPU instead of 146 s, and the suite takes as long (2026-12-06,
# doc/testing.md).
function(hif_test_program target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-O1>)
  if(HIF_UNITY_TESTS)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 4)
    # GCC takes a source included into the batch for a header, and warns when a class there
    # (a gtest fixture) uses a type of the file's anonymous namespace; compiled alone, it does
    # not warn.
    target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-Wno-subobject-linkage>)
  endif()
endfunction()

# Precompiled headers for the libraries with many sources: the standard and third-party
# headers most of their sources include, parsed once per target instead of once per source
# (`core`: the standard library and Eigen, and the extra headers given; `mrpt`: those and
# MRPT's maps, observations, poses, serialization and configuration; `reuse <other>`: the
# header of a target compiled with the same flags, as one with GCC is 100-200 MB on disk).
# Only third-party headers: a change to hif's own headers rebuilds what includes them, as
# before. A clean build 8-15 % faster (doc/testing.md, "Precompiled headers for the libraries").
option(HIF_PRECOMPILE_HEADERS
  "Precompile the third-party headers of the targets with many sources" ON)
set(HIF_PCH_CORE <algorithm> <array> <atomic> <cmath> <cstdint> <cstring> <limits> <memory>
  <optional> <string> <utility> <vector> <Eigen/Core> <Eigen/Geometry>)
set(HIF_PCH_MRPT ${HIF_PCH_CORE} <fstream> <sstream> <stdexcept> <filesystem>
  <mrpt/maps/CMetricMap.h> <mrpt/maps/CMultiMetricMap.h> <mrpt/maps/CPointsMap.h>
  <mrpt/maps/CSimplePointsMap.h> <mrpt/maps/CPointsMapXYZI.h> <mrpt/obs/CObservationPointCloud.h>
  <mrpt/obs/CSensoryFrame.h> <mrpt/poses/CPose3D.h> <mrpt/serialization/CArchive.h>
  <mrpt/config/CConfigFileBase.h> <mrpt/config/CLoadableOptions.h>)
function(hif_precompile_headers target kind)
  if(NOT HIF_PRECOMPILE_HEADERS)
    return()
  endif()
  if(kind STREQUAL "core")
    set(headers ${HIF_PCH_CORE})
  elseif(kind STREQUAL "mrpt")
    set(headers ${HIF_PCH_MRPT})
  elseif(kind STREQUAL "reuse")
    target_precompile_headers(${target} REUSE_FROM ${ARGN})
    return()
  else()
    message(FATAL_ERROR "hif_precompile_headers(${target} ${kind}): kind is core, mrpt or reuse")
  endif()
  list(APPEND headers ${ARGN})
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()
