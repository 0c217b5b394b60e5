// SPDX-License-Identifier: BSD-3-Clause
// Every public header compiled as C++17 with -Wall -Wextra -Wpedantic
// -Wold-style-cast -Werror (the cxx stage of tools/run_tests.sh), then linked
// against the C library and run: the extern "C" declarations must match.
#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/estimator.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/leso.h"
#include "ladrc/levant.h"
#include "ladrc/mixer.h"
#include "ladrc/pid.h"
#include "ladrc/rls.h"
#include "ladrc/sizes.h"
#include "ladrc/td.h"
#include "ladrc/tuning.h"
#include "ladrc/types.h"
#include "ladrc/version.h"

#include <cstdio>
#include <cstring>

int main()
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, LADRC_R(0.001), LADRC_R(5.445e-3));
    ladrc_axis_t axis;
    const ladrc_status_t st = ladrc_axis_init(&axis, &cfg);
    if (st != LADRC_OK) {
        std::printf("init: %s\n", ladrc_status_str(st));
        return 1;
    }
    ladrc_real_t u = LADRC_R(0.0);
    const ladrc_fault_t faults = ladrc_axis_step(&axis, LADRC_R(0.1), LADRC_R(0.0), nullptr, &u);
    if (faults != LADRC_FAULT_NONE || !(u > LADRC_R(0.0)) || ladrc_sizeof_axis_t() != sizeof(ladrc_axis_t) ||
        !ladrc_is_positive(u)) {
        std::printf("unexpected: u = %g\n", static_cast<double>(u));
        return 1;
    }
    std::printf("C++17: ladrc %s headers, axis step %g N m\n", LADRC_VERSION_STRING, static_cast<double>(u));
    return std::strlen(LADRC_VERSION_STRING) > 0 ? 0 : 1;
}
