# SPDX-License-Identifier: BSD-3-Clause
# Cross toolchain: RV32IMAC (no FPU, ilp32 ABI) with Debian's
# riscv64-unknown-elf-gcc and picolibc (package picolibc-riscv64-unknown-elf).
# picolibc.specs supplies the C library's headers, so it goes on the compile
# line as well as the link line. Library builds (CI: the cross stage).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR riscv32)

set(LADRC_TOOLCHAIN_PREFIX riscv64-unknown-elf-)
set(CMAKE_C_COMPILER ${LADRC_TOOLCHAIN_PREFIX}gcc)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_C_FLAGS_INIT "-march=rv32imac -mabi=ilp32 --specs=picolibc.specs -Os -fno-math-errno -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

find_program(CMAKE_SIZE NAMES ${LADRC_TOOLCHAIN_PREFIX}size)

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
