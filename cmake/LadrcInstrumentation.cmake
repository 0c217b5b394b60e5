# SPDX-License-Identifier: BSD-3-Clause
# Coverage and sanitizer flags apply to every target of the build, so the
# test executables link the matching runtimes. Host builds only.
if((LADRC_COVERAGE OR LADRC_SANITIZE) AND CMAKE_CROSSCOMPILING)
  message(FATAL_ERROR "LADRC_COVERAGE and LADRC_SANITIZE are for host builds only")
endif()
if(LADRC_COVERAGE AND LADRC_SANITIZE)
  message(FATAL_ERROR "LADRC_COVERAGE and LADRC_SANITIZE are separate builds")
endif()

if(LADRC_COVERAGE)
  if(NOT CMAKE_C_COMPILER_ID STREQUAL "GNU")
    message(FATAL_ERROR "LADRC_COVERAGE needs GCC (gcov data for gcovr)")
  endif()
  # -O0 comes last so it wins over the build type's level: branch counts
  # then map onto the source as written. The simulator runs the library on
  # several threads: atomic counter updates keep the counts exact.
  add_compile_options(--coverage -fprofile-update=atomic -O0)
  add_link_options(--coverage)
endif()

if(LADRC_SANITIZE)
  # float-cast-overflow is not part of gcc's "undefined": a float converted to
  # an integer it does not fit is undefined behaviour all the same.
  set(_ladrc_san -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options(${_ladrc_san})
  add_link_options(${_ladrc_san})
endif()
