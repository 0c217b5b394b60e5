# SPDX-License-Identifier: BSD-3-Clause
# Target "docs": the HTML API reference of the public headers (and of the
# margins tool's), built by Doxygen into <build>/docs/html with warnings as
# errors (docs/Doxyfile.in). Without Doxygen there is no such target.
include_guard(GLOBAL)

find_package(Doxygen QUIET)
if(NOT DOXYGEN_FOUND)
  message(STATUS "ladrc: Doxygen not found: no 'docs' target (the API reference)")
  return()
endif()

set(LADRC_DOCS_OUTPUT_DIR "${PROJECT_BINARY_DIR}/docs")
# version.h is generated (configure_file in CMakeLists.txt) and installed.
set(_ladrc_docs_dirs "${PROJECT_SOURCE_DIR}/include/ladrc" "${PROJECT_SOURCE_DIR}/analysis/include/ladrc")
set(_ladrc_docs_version "${PROJECT_BINARY_DIR}/include/ladrc/version.h")
file(GLOB _ladrc_docs_headers CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/include/ladrc/*.h"
     "${PROJECT_SOURCE_DIR}/analysis/include/ladrc/*.h")
# Doxygen's lists: quoted, space-separated.
set(LADRC_DOCS_INPUT "")
foreach(_ladrc_path IN LISTS _ladrc_docs_dirs _ladrc_docs_version)
  string(APPEND LADRC_DOCS_INPUT " \"${_ladrc_path}\"")
endforeach()
set(LADRC_DOCS_STRIP "\"${PROJECT_SOURCE_DIR}/include\" \"${PROJECT_SOURCE_DIR}/analysis/include\" \"${PROJECT_BINARY_DIR}/include\"")
configure_file("${PROJECT_SOURCE_DIR}/docs/Doxyfile.in" "${LADRC_DOCS_OUTPUT_DIR}/Doxyfile" @ONLY)

# The stamp is touched only after a run without warnings, so a failed run
# is redone on the next build even though it wrote its HTML.
add_custom_command(
  OUTPUT "${LADRC_DOCS_OUTPUT_DIR}/docs.stamp"
  COMMAND "${CMAKE_COMMAND}" -E rm -rf "${LADRC_DOCS_OUTPUT_DIR}/html"
  COMMAND Doxygen::doxygen "${LADRC_DOCS_OUTPUT_DIR}/Doxyfile"
  COMMAND "${CMAKE_COMMAND}" -E touch "${LADRC_DOCS_OUTPUT_DIR}/docs.stamp"
  DEPENDS "${LADRC_DOCS_OUTPUT_DIR}/Doxyfile" ${_ladrc_docs_headers} "${_ladrc_docs_version}"
  WORKING_DIRECTORY "${LADRC_DOCS_OUTPUT_DIR}"
  COMMENT "Doxygen: API reference in ${LADRC_DOCS_OUTPUT_DIR}/html"
  VERBATIM)
add_custom_target(docs DEPENDS "${LADRC_DOCS_OUTPUT_DIR}/docs.stamp")
