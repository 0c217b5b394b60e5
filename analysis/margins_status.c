/* SPDX-License-Identifier: BSD-3-Clause */
/* The texts of the stability-margin analysis's status codes (margins.h). */
#include "ladrc/margins.h"

const char *ladrc_margins_status_str(ladrc_margins_status_t status)
{
    switch (status) {
    case LADRC_MARGINS_OK:
        return "LADRC_MARGINS_OK: success";
    case LADRC_MARGINS_ERR_NULL:
        return "LADRC_MARGINS_ERR_NULL: a required pointer is NULL";
    case LADRC_MARGINS_ERR_DT_S:
        return "LADRC_MARGINS_ERR_DT_S: plant dt_s not > 0 or not the controller's";
    case LADRC_MARGINS_ERR_INERTIA:
        return "LADRC_MARGINS_ERR_INERTIA: inertia or inertia factor not finite and > 0";
    case LADRC_MARGINS_ERR_DRAG:
        return "LADRC_MARGINS_ERR_DRAG: drag_Nm_s not finite and >= 0";
    case LADRC_MARGINS_ERR_MOTOR_TAU:
        return "LADRC_MARGINS_ERR_MOTOR_TAU: motor_tau_s not finite and >= 0";
    case LADRC_MARGINS_ERR_DELAY:
        return "LADRC_MARGINS_ERR_DELAY: delay_ticks outside 0..512";
    case LADRC_MARGINS_ERR_CONTROLLER:
        return "LADRC_MARGINS_ERR_CONTROLLER: the controller config is refused";
    case LADRC_MARGINS_ERR_REQUEST:
        return "LADRC_MARGINS_ERR_REQUEST: invalid tone, response length or grid";
    case LADRC_MARGINS_ERR_NOT_SETTLED:
        return "LADRC_MARGINS_ERR_NOT_SETTLED: the controller's response did not settle within response_s";
    case LADRC_MARGINS_ERR_NOT_MEASURED:
        return "LADRC_MARGINS_ERR_NOT_MEASURED: no controller measured";
    case LADRC_MARGINS_ERR_TARGETS_NOT_MET:
        return "LADRC_MARGINS_ERR_TARGETS_NOT_MET: no setting meets the targets";
    }
    return "LADRC_MARGINS_ERR_?: unknown status";
}
