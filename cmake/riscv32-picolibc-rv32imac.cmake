# SPDX-License-Identifier: BSD-3-Clause
# Cross toolchain: RV32IMAC (no FPU, ilp32 ABI) with Debian's
# riscv64-unknown-elf-gcc and picolibc (package picolibc-riscv64-unknown-elf).
# picolibc.specs supplies the C library's headers, so it goes on the compile
# line as well as the link line. Library builds (CI: the cross stage).
set(CMAKE_SYSTEM_PROCESSOR riscv32)
set(LADRC_TOOLCHAIN_PREFIX riscv64-unknown-elf-)
set(LADRC_CPU_FLAGS "-march=rv32imac -mabi=ilp32 --specs=picolibc.specs")
include("${CMAKE_CURRENT_LIST_DIR}/LadrcCrossToolchain.cmake")
