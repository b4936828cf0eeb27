# SPDX-License-Identifier: BSD-3-Clause
# Configures hif with MRPT hidden (CMAKE_DISABLE_FIND_PACKAGE_MRPT), builds what remains
# (hif_core, hif_io and the core tests) and runs the core tests. Variables: SOURCE_DIR,
# WORK_DIR, BUILD_TYPE.
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE_DIR};-B;${WORK_DIR};-DCMAKE_BUILD_TYPE=${BUILD_TYPE};-DCMAKE_DISABLE_FIND_PACKAGE_MRPT=ON;-DHIF_WARNINGS_AS_ERRORS=ON"
    "${CMAKE_COMMAND};--build;${WORK_DIR};--target;hif_core_tests"
    "${WORK_DIR}/tests/hif_core_tests;--gtest_brief=1")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "core-only step failed (${rc}): ${step}\n${out}")
  endif()
endforeach()
# What was built: no MRPT target may be there.
if(EXISTS "${WORK_DIR}/libs/hif_mrpt/Makefile")
  message(FATAL_ERROR "hif_mrpt was configured although MRPT was hidden")
endif()
message(STATUS "hif_core and its tests built and passed without MRPT")
