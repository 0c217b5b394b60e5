# SPDX-License-Identifier: BSD-3-Clause
# Cross toolchain: Cortex-M0 (ARMv6-M, no FPU, soft-float ABI),
# GNU Arm Embedded toolchain with newlib. Library builds (CI: the cross stage
# of tools/run_tests.sh); the test images run on the Cortex-M4F only.
set(CMAKE_SYSTEM_PROCESSOR arm)
set(LADRC_TOOLCHAIN_PREFIX arm-none-eabi-)
set(LADRC_CPU_FLAGS "-mcpu=cortex-m0 -mthumb -mfloat-abi=soft")
include("${CMAKE_CURRENT_LIST_DIR}/LadrcCrossToolchain.cmake")
