# SPDX-License-Identifier: BSD-3-Clause
# Cross toolchain: Cortex-M7 with the double-precision FPU (fpv5-d16,
# hard-float ABI; the preset builds with LADRC_REAL_DOUBLE), GNU Arm Embedded
# toolchain with newlib. Library builds (CI: the cross stage
# of tools/run_tests.sh); the test images run on the Cortex-M4F only.
set(CMAKE_SYSTEM_PROCESSOR arm)
set(LADRC_TOOLCHAIN_PREFIX arm-none-eabi-)
set(LADRC_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard")
include("${CMAKE_CURRENT_LIST_DIR}/LadrcCrossToolchain.cmake")
