# SPDX-License-Identifier: BSD-3-Clause
# Cross toolchain: Cortex-M4F (single-precision FPU, hard-float ABI),
# GNU Arm Embedded toolchain with newlib.
set(CMAKE_SYSTEM_PROCESSOR arm)
set(LADRC_TOOLCHAIN_PREFIX arm-none-eabi-)
set(LADRC_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
include("${CMAKE_CURRENT_LIST_DIR}/LadrcCrossToolchain.cmake")
