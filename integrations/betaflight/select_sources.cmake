# SPDX-License-Identifier: BSD-3-Clause
# The library's sources and definitions for a RATE-ADRC-only build (no
# shaper, no HP search), from the library's own selection
# (cmake/LadrcVariants.cmake), for apply.sh:
#   cmake -DLADRC_ROOT=<repo> -P select_sources.cmake
# prints "ladrc-source: <file>" and "ladrc-define: <NAME>=<value>" lines.
cmake_minimum_required(VERSION 3.16)
if(NOT DEFINED LADRC_ROOT)
  message(FATAL_ERROR "select_sources.cmake: LADRC_ROOT not set (-DLADRC_ROOT=<the ladrc repository>)")
endif()
include("${LADRC_ROOT}/cmake/LadrcVariants.cmake")
file(GLOB all_sources "${LADRC_ROOT}/src/*.c")
ladrc_select_variants(sources definitions "${all_sources}" VARIANTS RATE_ADRC HP_ONLINE OFF)
foreach(source IN LISTS sources)
  get_filename_component(base "${source}" NAME)
  message(NOTICE "ladrc-source: ${base}")
endforeach()
foreach(definition IN LISTS definitions)
  message(NOTICE "ladrc-define: ${definition}")
endforeach()
