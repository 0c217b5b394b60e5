/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Inlining the compiler is told about (not installed), the one place of the
 * library's GNU attributes. LADRC_FORCE_INLINE inlines a static function
 * even at -Os; LADRC_NOINLINE keeps one out of line. Each use carries its
 * reason and the figure measured for it (tools/bench, Cortex-M4F -Os); on
 * compilers without the GNU attributes they are a plain inline and nothing.
 */
#ifndef LADRC_COMPILER_H
#define LADRC_COMPILER_H

#if defined(__GNUC__)
#define LADRC_FORCE_INLINE __attribute__((always_inline)) inline
#define LADRC_NOINLINE __attribute__((noinline))
#else
#define LADRC_FORCE_INLINE inline
#define LADRC_NOINLINE
#endif

#endif /* LADRC_COMPILER_H */
