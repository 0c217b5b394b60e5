/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The entry point of a libFuzzer target (tests/fuzz/fuzz_*.c), and how a
 * target reports a broken property: a message on stderr, then abort(),
 * which libFuzzer (and the corpus replay in ctest) count as a crash.
 */
#ifndef LADRC_FUZZ_H
#define LADRC_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Aborts with the message when cond is false. */
#define FUZZ_CHECK(cond, ...) ((cond) ? (void)0 : fuzz_fail(__FILE__, __LINE__, #cond, __VA_ARGS__))

#if defined(__GNUC__)
__attribute__((noreturn, format(printf, 4, 5)))
#endif
void fuzz_fail(const char *file, int line, const char *cond, const char *format, ...);

/* The text's line count, and the length (bytes) of its line `line`
 * (1-based; 0 when there is none): where a refused input's error may lie. */
void fuzz_measure_lines(const uint8_t *data, size_t size, int line, int *lines, size_t *line_len);

#endif
