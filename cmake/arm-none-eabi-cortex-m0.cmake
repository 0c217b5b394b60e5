# SPDX-License-Identifier: BSD-3-Clause
# Cross toolchain: Cortex-M0 (ARMv6-M, no FPU, soft-float ABI),
# GNU Arm Embedded toolchain with newlib. Library builds (CI: the cross stage
# of tools/run_tests.sh); the test images run on the Cortex-M4F only.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(LADRC_TOOLCHAIN_PREFIX arm-none-eabi-)
set(CMAKE_C_COMPILER ${LADRC_TOOLCHAIN_PREFIX}gcc)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_C_FLAGS_INIT "-mcpu=cortex-m0 -mthumb -mfloat-abi=soft -Os -fno-math-errno -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

find_program(CMAKE_SIZE NAMES ${LADRC_TOOLCHAIN_PREFIX}size)

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
