/* SPDX-License-Identifier: BSD-3-Clause */
/* Arm semihosting calls (handled by qemu with -semihosting-config enable=on). */
#ifndef LADRC_SEMIHOST_H
#define LADRC_SEMIHOST_H

#include <stdint.h>

#define SEMIHOST_SYS_WRITE0 0x04u
#define SEMIHOST_SYS_EXIT 0x18u
#define SEMIHOST_SYS_EXIT_EXTENDED 0x20u
#define SEMIHOST_ADP_APPLICATION_EXIT 0x20026u /* ADP_Stopped_ApplicationExit */
#define SEMIHOST_ADP_RUNTIME_ERROR 0x20023u    /* ADP_Stopped_RunTimeErrorUnknown */

/* On M-profile the call is "bkpt 0xAB" with the operation in r0 and its
 * argument in r1; the result comes back in r0. */
static inline uint32_t semihost_call(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static inline void semihost_write0(const char *text)
{
    (void)semihost_call(SEMIHOST_SYS_WRITE0, text);
}

/* Ends qemu with `code` as its exit status. SYS_EXIT_EXTENDED carries the
 * code; plain SYS_EXIT (32-bit form) only tells success from failure and
 * is the fallback if the extended call is not supported. */
static inline void semihost_exit(int code)
{
    const uint32_t block[2] = {SEMIHOST_ADP_APPLICATION_EXIT, (uint32_t)code};
    (void)semihost_call(SEMIHOST_SYS_EXIT_EXTENDED, block);
    (void)semihost_call(SEMIHOST_SYS_EXIT, (const void *)(uintptr_t)(code == 0 ? SEMIHOST_ADP_APPLICATION_EXIT
                                                                               : SEMIHOST_ADP_RUNTIME_ERROR));
    for (;;) {
    }
}

#endif
