/* SPDX-License-Identifier: BSD-3-Clause */
/* One axis tick as a torque, for the tests that follow the command (the
 * step returns the tick's flags: those tests read them with
 * ladrc_axis_get_faults, and these helpers check that both agree). */
#ifndef LADRC_TEST_AXIS_COMMAND_H
#define LADRC_TEST_AXIS_COMMAND_H

#include "ladrc/axis.h"

#include <stdlib.h>

static inline ladrc_real_t test_axis_tick(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                                          const ladrc_real_t *rate_rad_s)
{
    ladrc_real_t torque_Nm = LADRC_R(0.0);
    if (ladrc_axis_step(axis, ref_rad, angle_rad, rate_rad_s, &torque_Nm) != ladrc_axis_get_faults(axis)) {
        abort(); /* the returned flags are the tick's flags */
    }
    return torque_Nm;
}

/** The torque command of one tick without a rate (N m). */
static inline ladrc_real_t axis_command(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad)
{
    return test_axis_tick(axis, ref_rad, angle_rad, NULL);
}

/** The torque command of one tick with a measured rate (N m). */
static inline ladrc_real_t axis_command_with_rate(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                                                  ladrc_real_t rate_rad_s)
{
    return test_axis_tick(axis, ref_rad, angle_rad, &rate_rad_s);
}

#endif
