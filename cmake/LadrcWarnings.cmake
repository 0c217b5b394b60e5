# SPDX-License-Identifier: BSD-3-Clause
# Warning sets.
#   LIBRARY: strict, the flight code must be free of implicit conversions
#            and float->double promotions (they cost cycles on a single
#            precision FPU).
#   TEST:    no -Wconversion/-Wdouble-promotion, because the tests
#            deliberately compute their reference values in double.
# Unity's own sources (real or compat) get none of these.
function(ladrc_target_warnings target kind)
  if(NOT CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
    return()
  endif()
  set(flags -Wall -Wextra -Wpedantic -Wshadow)
  if(kind STREQUAL "LIBRARY")
    list(APPEND flags -Wdouble-promotion -Wconversion -Wcast-qual -Wstrict-prototypes
                      -Wmissing-prototypes -Wundef)
  elseif(NOT kind STREQUAL "TEST")
    message(FATAL_ERROR "ladrc_target_warnings: kind must be LIBRARY or TEST")
  endif()
  if(LADRC_WERROR)
    list(APPEND flags -Werror)
  endif()
  target_compile_options(${target} PRIVATE ${flags})
endfunction()
