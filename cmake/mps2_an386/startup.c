/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Startup for test images on qemu mps2-an386: vector table, reset handler
 * and fault handlers.
 *
 * Built with -mgeneral-regs-only: the FPU is off after reset and any
 * floating-point instruction before Reset_Handler enables it would fault.
 */
#include <stdint.h>
#include <stdlib.h>

#include "semihost.h"

#define CPACR (*(volatile uint32_t *)0xE000ED88u)
#define CPACR_CP10_CP11_FULL (0xFu << 20)
#define FAULT_EXIT_CODE 255

extern uint32_t __data_start__[], __data_end__[], __data_load__[];
extern uint32_t __bss_start__[], __bss_end__[], __stack_top__[];

int main(void);
void __libc_init_array(void);
void _init(void);
void _fini(void);
void Reset_Handler(void);
void NMI_Handler(void);
void HardFault_Handler(void);
void MemManage_Handler(void);
void BusFault_Handler(void);
void UsageFault_Handler(void);
void Unexpected_Handler(void);

struct vector_table {
    uint32_t *initial_sp;
    void (*handler[15])(void);
};

/* Exceptions 1..15; no interrupt is ever enabled, so none are listed. */
__attribute__((section(".vectors"), used)) const struct vector_table ladrc_vector_table = {
    __stack_top__,
    {
        Reset_Handler, NMI_Handler, HardFault_Handler, MemManage_Handler, BusFault_Handler, UsageFault_Handler, 0, 0, 0,
        0, Unexpected_Handler, /* SVCall */
        Unexpected_Handler,    /* DebugMonitor */
        0, Unexpected_Handler, /* PendSV */
        Unexpected_Handler,    /* SysTick */
    },
};

void Reset_Handler(void)
{
    uint32_t *dst;
    const uint32_t *src;

    /* Full access to CP10/CP11 (the FPU), then make sure it took effect
     * before the first floating-point instruction (in C library or main). */
    CPACR |= CPACR_CP10_CP11_FULL;
    __asm__ volatile("dsb\n\tisb" ::: "memory");

    for (dst = __data_start__, src = __data_load__; dst < __data_end__;) {
        *dst++ = *src++;
    }
    for (dst = __bss_start__; dst < __bss_end__;) {
        *dst++ = 0u;
    }

    /* Constructors, if any; then exit() runs destructors, flushes stdio
     * and _exit() ends qemu with main's status. */
    __libc_init_array();
    exit(main());
}

/* newlib's init/fini helpers call these (crti.o is not linked). */
void _init(void)
{
}
void _fini(void)
{
}

/* A crashed test must fail, not hang: report and leave qemu. */
static void fault_exit(const char *what)
{
    semihost_write0("\n*** ");
    semihost_write0(what);
    semihost_write0(": test image crashed\n");
    semihost_exit(FAULT_EXIT_CODE);
}

void NMI_Handler(void)
{
    fault_exit("NMI");
}
void HardFault_Handler(void)
{
    fault_exit("HardFault");
}
void MemManage_Handler(void)
{
    fault_exit("MemManage fault");
}
void BusFault_Handler(void)
{
    fault_exit("BusFault");
}
void UsageFault_Handler(void)
{
    fault_exit("UsageFault");
}
void Unexpected_Handler(void)
{
    fault_exit("unexpected exception");
}
