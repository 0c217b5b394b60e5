# SPDX-License-Identifier: BSD-3-Clause
# Coverage gate (gcovr 5.2) over the library sources only, after ctest:
#   cmake --build --preset coverage --target coverage
# Fails when line coverage < 95 % or branch coverage < 85 %.
include_guard(GLOBAL)

set(LADRC_COVERAGE_MIN_LINE 95 CACHE STRING "Minimum line coverage (%) of src/")
set(LADRC_COVERAGE_MIN_BRANCH 85 CACHE STRING "Minimum branch coverage (%) of src/")

find_program(LADRC_GCOVR gcovr)
if(NOT LADRC_GCOVR)
  message(WARNING "gcovr not found: the coverage target will fail")
  set(LADRC_GCOVR gcovr)
endif()

# gcov must match the compiler version that wrote the notes files.
get_filename_component(_ladrc_cc_dir "${CMAKE_C_COMPILER}" DIRECTORY)
string(REGEX MATCH "[0-9]+" _ladrc_cc_major "${CMAKE_C_COMPILER_VERSION}")
find_program(LADRC_GCOV NAMES gcov-${_ladrc_cc_major} gcov HINTS "${_ladrc_cc_dir}")

# gcovr's relative filters are relative to the working directory, so it
# runs from the repository root and searches this build tree only.
# --exclude-unreachable-branches drops the branches GCC attaches to lines
# without code (closing braces, declarations), which no test can take.
# (--exclude-throw-branches would be a no-op: C has no exceptions.)
add_custom_target(coverage
  COMMAND "${LADRC_GCOVR}"
          --root "${PROJECT_SOURCE_DIR}"
          --gcov-executable "${LADRC_GCOV}"
          --filter "src/"
          --exclude-unreachable-branches
          --print-summary
          --txt
          --fail-under-line ${LADRC_COVERAGE_MIN_LINE}
          --fail-under-branch ${LADRC_COVERAGE_MIN_BRANCH}
          "${PROJECT_BINARY_DIR}"
  WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
  COMMENT "gcovr: line/branch coverage of src/ (gate: ${LADRC_COVERAGE_MIN_LINE}% / ${LADRC_COVERAGE_MIN_BRANCH}%)"
  VERBATIM)

