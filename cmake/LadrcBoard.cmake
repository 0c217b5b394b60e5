# SPDX-License-Identifier: BSD-3-Clause
# Board support for running test images on qemu's mps2-an386 (Cortex-M4
# with FPU). Only executables get it; the library stays board-free.
include_guard(GLOBAL)

set(_ladrc_bsp "${CMAKE_CURRENT_LIST_DIR}/mps2_an386")
set(LADRC_BOARD_LINKER_SCRIPT "${_ladrc_bsp}/mps2_an386.ld")

# Startup and newlib syscalls as object files, so the vector table is
# always linked in. Startup runs before the FPU is on: general registers only.
add_library(ladrc_board OBJECT "${_ladrc_bsp}/startup.c" "${_ladrc_bsp}/syscalls.c")
set_source_files_properties("${_ladrc_bsp}/startup.c" PROPERTIES
  COMPILE_OPTIONS "-mgeneral-regs-only;-ffreestanding;-fno-tree-loop-distribute-patterns")
# Own startup instead of crt0; full newlib (not nano): tests may print floats.
target_link_options(ladrc_board INTERFACE
  -nostartfiles "-T${LADRC_BOARD_LINKER_SCRIPT}")

find_program(LADRC_QEMU qemu-system-arm)
find_program(LADRC_TIMEOUT timeout)
if(LADRC_QEMU)
  set(LADRC_BOARD_CAN_RUN_TESTS ON)
  # ctest runs "<emulator...> <image>". Semihosting gives the image a
  # console (on qemu's stderr) and its exit status; the serial port and the
  # monitor are off so qemu never waits for a terminal.
  set(CMAKE_CROSSCOMPILING_EMULATOR
    "${LADRC_QEMU};-machine;mps2-an386;-cpu;cortex-m4;-nographic;-monitor;none;-serial;none;-semihosting-config;enable=on,target=native;-kernel")
  if(LADRC_TIMEOUT)
    # Outer guard for a hung qemu; ctest's TIMEOUT also applies.
    list(PREPEND CMAKE_CROSSCOMPILING_EMULATOR "${LADRC_TIMEOUT}" "${LADRC_TEST_TIMEOUT}")
  endif()
else()
  set(LADRC_BOARD_CAN_RUN_TESTS OFF)
  message(WARNING "qemu-system-arm not found: the cortex-m4f test images are built "
                  "but NOT registered with ctest. Install qemu-system-arm to run them.")
endif()

# Makes <target> a bootable mps2-an386 image and prints its size.
function(ladrc_board_executable target)
  target_link_libraries(${target} PRIVATE ladrc_board)
  set_property(TARGET ${target} APPEND PROPERTY LINK_DEPENDS "${LADRC_BOARD_LINKER_SCRIPT}")
  set_target_properties(${target} PROPERTIES SUFFIX ".elf")
  ladrc_print_image_size(${target})
endfunction()
