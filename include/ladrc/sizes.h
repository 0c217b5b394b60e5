/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file sizes.h
 * @brief The library's own sizes of its types, for bindings (ctypes, FFI)
 *        that allocate states and fill configs without a C compiler.
 *
 * Each function returns sizeof the type as the library was compiled, so a
 * binding can check its mirror of a struct against the real one and allocate
 * opaque states of the right size. Firmware has no use for them: they sit in
 * their own object (src/sizes.c), which a linker with --gc-sections, or a
 * static link that never calls them, leaves out.
 */
#ifndef LADRC_SIZES_H
#define LADRC_SIZES_H

#include "ladrc/types.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** @return sizeof(ladrc_real_t) in the library's build (bytes): 4 (float) or 8 (LADRC_REAL_DOUBLE) */
size_t ladrc_sizeof_real(void);
/** @return sizeof(ladrc_axis_t) in the library's build (bytes) */
size_t ladrc_sizeof_axis_t(void);
/** @return sizeof(ladrc_axis_config_t) in the library's build (bytes) */
size_t ladrc_sizeof_axis_config_t(void);
/** @return sizeof(ladrc_attitude_t) in the library's build (bytes) */
size_t ladrc_sizeof_attitude_t(void);
/** @return sizeof(ladrc_attitude_config_t) in the library's build (bytes) */
size_t ladrc_sizeof_attitude_config_t(void);
/** @return sizeof(ladrc_mixer_t) in the library's build (bytes) */
size_t ladrc_sizeof_mixer_t(void);
/** @return sizeof(ladrc_mixer_config_t) in the library's build (bytes) */
size_t ladrc_sizeof_mixer_config_t(void);
/** @return sizeof(ladrc_mixer_output_t) in the library's build (bytes) */
size_t ladrc_sizeof_mixer_output_t(void);
/** @return sizeof(ladrc_ref_t) in the library's build (bytes) */
size_t ladrc_sizeof_ref_t(void);
/** @return sizeof(ladrc_gyro_filter_t) in the library's build (bytes) */
size_t ladrc_sizeof_gyro_filter_t(void);
/** @return sizeof(ladrc_gyro_filter_config_t) in the library's build (bytes) */
size_t ladrc_sizeof_gyro_filter_config_t(void);
/** @return LADRC_HP_MAX_TONES of the library's build: the length of
 *          ladrc_axis_config_t's hp_freq_rad_s */
size_t ladrc_hp_max_tones(void);
/** The variant and shaper set and the online search the library was built
 *  with, as the suffix its axis and attitude symbols carry after the real
 *  type (types.h, ABI guard).
 *  @return the suffix, e.g. "_v1111111_s11_o1_t2" with everything built and
 *          the default most tones; never NULL */
const char *ladrc_abi_set(void);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_SIZES_H */
