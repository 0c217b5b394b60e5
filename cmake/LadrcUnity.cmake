# SPDX-License-Identifier: BSD-3-Clause
# Picks the unit-test framework and exposes it as the INTERFACE target
# `ladrc_unity`, first match wins:
#   a) FETCHCONTENT_SOURCE_DIR_UNITY: a local Unity source tree
#   b) LADRC_FETCH_UNITY=ON: Unity v2.6.1 downloaded with FetchContent
#   c) an installed Unity package (unity::framework)
#   d) the small Unity-compatible runner in tests/unity_compat
include_guard(GLOBAL)
include(FetchContent)

add_library(ladrc_unity INTERFACE)
set(LADRC_UNITY_IS_COMPAT OFF)

# The full commit hash pins the content: it is release v2.6.1 and, unlike
# a tag, cannot be moved. A set FETCHCONTENT_SOURCE_DIR_UNITY overrides it.
FetchContent_Declare(unity
  GIT_REPOSITORY https://github.com/ThrowTheSwitch/Unity.git
  GIT_TAG cbcd08fa7de711053a3deec6339ee89cad5d2697)

if(FETCHCONTENT_SOURCE_DIR_UNITY)
  FetchContent_MakeAvailable(unity)
  target_link_libraries(ladrc_unity INTERFACE unity::framework)
  set(_ladrc_unity_used "Unity from ${FETCHCONTENT_SOURCE_DIR_UNITY}")
elseif(LADRC_FETCH_UNITY)
  FetchContent_MakeAvailable(unity)
  target_link_libraries(ladrc_unity INTERFACE unity::framework)
  set(_ladrc_unity_used "Unity v2.6.1 (downloaded)")
else()
  # A host-installed Unity cannot be linked into target images, so a cross
  # build only looks inside its find root.
  if(NOT CMAKE_CROSSCOMPILING OR CMAKE_FIND_ROOT_PATH)
    find_package(unity CONFIG QUIET)
  endif()
  if(TARGET unity::framework)
    target_link_libraries(ladrc_unity INTERFACE unity::framework)
    set(_ladrc_unity_used "installed Unity package ${unity_VERSION} (${unity_DIR})")
  else()
    add_subdirectory("${PROJECT_SOURCE_DIR}/tests/unity_compat"
                     "${PROJECT_BINARY_DIR}/unity_compat")
    target_link_libraries(ladrc_unity INTERFACE ladrc_unity_compat)
    set(LADRC_UNITY_IS_COMPAT ON)
    set(_ladrc_unity_used "bundled Unity-compatible runner (tests/unity_compat)")
  endif()
endif()

message(STATUS "ladrc tests use: ${_ladrc_unity_used}")
