# SPDX-License-Identifier: BSD-3-Clause
# Installs the hif build tree into a fresh prefix; builds the consumer project against it
# (with the README's examples, extracted from README.md as written) and runs its programs; then
# runs the installed apps from the prefix, with no library path set, on a short synthetic
# sequence (the default config must be found in the prefix).
# Variables: HIF_BUILD_DIR, CONSUMER_SRC, README, WORK_DIR.
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

# The README's examples: the first ```cpp block after each "readme-example <name>" marker.
file(READ "${README}" readme)
foreach(name offline online)
  string(FIND "${readme}" "<!-- readme-example ${name}:" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "no readme-example ${name} marker in ${README}")
  endif()
  string(SUBSTRING "${readme}" ${at} -1 rest)
  string(REGEX MATCH "```cpp\n(.*)" block "${rest}")
  string(FIND "${CMAKE_MATCH_1}" "```" end)
  string(SUBSTRING "${CMAKE_MATCH_1}" 0 ${end} example)
  file(WRITE "${WORK_DIR}/readme_${name}.cpp" "${example}")
endforeach()

set(bin "${prefix}/bin")
set(seq "${WORK_DIR}/seq")
set(run "${CMAKE_COMMAND};-E;env;--unset=LD_LIBRARY_PATH")
foreach(step
    "${CMAKE_COMMAND};--install;${HIF_BUILD_DIR};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${CONSUMER_SRC};-B;${WORK_DIR}/build;-DCMAKE_PREFIX_PATH=${prefix};-DREADME_EXAMPLES=${WORK_DIR}"
    "${CMAKE_COMMAND};--build;${WORK_DIR}/build"
    "${WORK_DIR}/build/hif_consumer"
    "${WORK_DIR}/build/ini_only"
    "${WORK_DIR}/build/readme_offline"
    "${WORK_DIR}/build/readme_online"
    "${run};${bin}/hif-clean;--help"
    "${run};${bin}/hif-synthetic-kitti;-o;${seq};-n;3"
    "${run};${bin}/kitti2rawlog;-i;${seq};-o;${WORK_DIR}/seq.rawlog"
    "${run};${bin}/hif-clean;-i;${WORK_DIR}/seq.rawlog;-o;${WORK_DIR}/out;-q"
    "${run};${bin}/hif-eval;--labels;${seq}/labels;--predictions;${WORK_DIR}/out/predictions")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer step failed (${rc}): ${step}\n${out}")
  endif()
  if(step MATCHES "hif-clean;-i")
    # The installed hif-clean uses the installed config, found beside it.
    if(NOT out MATCHES "config : ${prefix}/bin/../share/hif/config/kitti.ini" AND
       NOT out MATCHES "config : ${prefix}/share/hif/config/kitti.ini")
      message(FATAL_ERROR "the installed hif-clean did not use ${prefix}'s kitti.ini:\n${out}")
    endif()
  endif()
endforeach()
message(STATUS "installed hif: consumer built and run, installed apps run from ${prefix}")
