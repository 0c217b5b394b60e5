# SPDX-License-Identifier: BSD-3-Clause
# Cross toolchain: Cortex-M4F (single-precision FPU, hard-float ABI),
# GNU Arm Embedded toolchain with newlib.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(LADRC_TOOLCHAIN_PREFIX arm-none-eabi-)
set(CMAKE_C_COMPILER ${LADRC_TOOLCHAIN_PREFIX}gcc)

# No OS to link a test program against: compiler checks build a library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# The CPU flags go to the link line too, so gcc picks the matching
# (thumb/v7e-m+fp/hard) newlib multilib.
set(CMAKE_C_FLAGS_INIT
    "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -Os -fno-math-errno -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

find_program(CMAKE_SIZE NAMES ${LADRC_TOOLCHAIN_PREFIX}size)

# Host programs (qemu, size), target libraries and headers.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
