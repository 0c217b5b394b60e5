# SPDX-License-Identifier: BSD-3-Clause
# ladrc_add_unit_test(<name> <source>...)
# Builds one Unity test program and registers it with ctest under <name>.
# Reusable by other suites (e.g. sim/). On the cross build the program is
# linked for the mps2-an386 board and run under qemu.
include_guard(GLOBAL)

set(LADRC_TEST_TIMEOUT 300 CACHE STRING "Seconds before a hung test is killed")

function(ladrc_add_unit_test name)
  if(NOT LADRC_BUILD_TESTS)
    return()
  endif()
  if(NOT ARGN)
    message(FATAL_ERROR "ladrc_add_unit_test(${name}): no sources given")
  endif()

  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE ladrc::ladrc ladrc_unity)
  if(TARGET ladrc_test_support)
    target_link_libraries(${name} PRIVATE ladrc_test_support)
  endif()
  if(NOT WIN32)
    target_link_libraries(${name} PRIVATE m)
  endif()
  ladrc_target_warnings(${name} TEST)

  if(CMAKE_CROSSCOMPILING)
    # Campaigns run a short form on the emulated target (tests read it).
    target_compile_definitions(${name} PRIVATE LADRC_TEST_ON_TARGET=1)
    ladrc_board_executable(${name})
    if(NOT LADRC_BOARD_CAN_RUN_TESTS)
      return()  # built, but nothing to run it on (warned at configure time)
    endif()
  endif()

  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES TIMEOUT ${LADRC_TEST_TIMEOUT})
  if(LADRC_SANITIZE)
    # Stop at the first report so the test fails, and keep the log readable.
    set_property(TEST ${name} PROPERTY ENVIRONMENT
      "ASAN_OPTIONS=halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1"
      "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1")
  endif()
endfunction()
