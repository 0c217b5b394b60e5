# SPDX-License-Identifier: BSD-3-Clause
# What every cross toolchain file here shares. The including file sets
# CMAKE_SYSTEM_PROCESSOR, LADRC_TOOLCHAIN_PREFIX (e.g. arm-none-eabi-) and
# LADRC_CPU_FLAGS (the CPU and ABI flags; they go to the link line too, so gcc
# picks the matching C library multilib).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_C_COMPILER ${LADRC_TOOLCHAIN_PREFIX}gcc)

# No OS to link a test program against: compiler checks build a library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_C_FLAGS_INIT "${LADRC_CPU_FLAGS} -Os -fno-math-errno -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

find_program(CMAKE_SIZE NAMES ${LADRC_TOOLCHAIN_PREFIX}size)

# Host programs (qemu, size), target libraries and headers.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
