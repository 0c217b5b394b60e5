/* SPDX-License-Identifier: BSD-3-Clause */
/* The [excitation] chirp (excitation.h). */
#include "excitation.h"

#include <math.h>

#define TWO_PI 6.283185307179586476925286766559

double sim_chirp_value(double amplitude, double f0_hz, double f1_hz, double duration_s, double t_since_start_s)
{
    if (!(t_since_start_s >= 0.0 && t_since_start_s < duration_s)) {
        return 0.0;
    }
    const double log_ratio = log(f1_hz / f0_hz);
    const double phase = TWO_PI * f0_hz * duration_s / log_ratio * expm1(t_since_start_s * log_ratio / duration_s);
    return amplitude * sin(phase);
}

double sim_chirp_frequency_hz(double f0_hz, double f1_hz, double duration_s, double t_since_start_s)
{
    return f0_hz * exp(t_since_start_s * log(f1_hz / f0_hz) / duration_s);
}

int sim_excitation_axes(const sim_scenario_t *sc)
{
    return sc->excite_axis == SIM_EXCITE_ALL ? 3 : 1;
}

double sim_excitation_end_s(const sim_scenario_t *sc)
{
    return sc->excite_start_s + sim_excitation_axes(sc) * sc->excite_duration_s;
}

void sim_excitation_at(const sim_scenario_t *sc, double t_s, double command[3])
{
    command[0] = command[1] = command[2] = 0.0;
    if (!sc->excite_on) {
        return;
    }
    const int all = sc->excite_axis == SIM_EXCITE_ALL;
    for (int k = 0; k < sim_excitation_axes(sc); ++k) {
        const double start_s = sc->excite_start_s + k * sc->excite_duration_s;
        const int axis = all ? k : sc->excite_axis;
        const double amplitude = sc->excite_amplitude[sc->excite_n_amplitudes == 3 ? axis : 0];
        command[axis] =
            sim_chirp_value(amplitude, sc->excite_f0_hz, sc->excite_f1_hz, sc->excite_duration_s, t_s - start_s);
    }
}
