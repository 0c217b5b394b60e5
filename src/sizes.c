/* SPDX-License-Identifier: BSD-3-Clause */
/* sizeof of the public types as compiled (see sizes.h). */
#include "ladrc/sizes.h"

#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/mixer.h"
#include "ladrc/td.h"

size_t ladrc_sizeof_real(void)
{
    return sizeof(ladrc_real_t);
}
size_t ladrc_sizeof_axis_t(void)
{
    return sizeof(ladrc_axis_t);
}
size_t ladrc_sizeof_axis_config_t(void)
{
    return sizeof(ladrc_axis_config_t);
}
size_t ladrc_sizeof_attitude_t(void)
{
    return sizeof(ladrc_attitude_t);
}
size_t ladrc_sizeof_attitude_config_t(void)
{
    return sizeof(ladrc_attitude_config_t);
}
size_t ladrc_sizeof_mixer_t(void)
{
    return sizeof(ladrc_mixer_t);
}
size_t ladrc_sizeof_mixer_config_t(void)
{
    return sizeof(ladrc_mixer_config_t);
}
size_t ladrc_sizeof_mixer_output_t(void)
{
    return sizeof(ladrc_mixer_output_t);
}
size_t ladrc_sizeof_ref_t(void)
{
    return sizeof(ladrc_ref_t);
}
size_t ladrc_sizeof_gyro_filter_t(void)
{
    return sizeof(ladrc_gyro_filter_t);
}
size_t ladrc_sizeof_gyro_filter_config_t(void)
{
    return sizeof(ladrc_gyro_filter_config_t);
}
size_t ladrc_hp_max_tones(void)
{
    return LADRC_HP_MAX_TONES;
}

#define SIZES_STRING_(x) #x
#define SIZES_STRING(x) SIZES_STRING_(x)
const char *ladrc_abi_set(void)
{
    return SIZES_STRING(LADRC_ABI_SET_);
}
