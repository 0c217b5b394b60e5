/* SPDX-License-Identifier: BSD-3-Clause */
/* The command noise a loop predicts: white angle and rate noise on the
 * measurements through the closed loop to the torque command, its RMS above
 * a corner frequency (docs/margins.md, "Command noise"). */
#include "margins_internal.h"

#include <math.h>

int margins_noise_wanted(const ladrc_margins_request_t *req)
{
    return req->angle_noise_std_rad > 0.0 || req->rate_noise_std_rad_s > 0.0 || req->rate_noise_psd_bins > 0;
}

static int check_psd(const ladrc_margins_request_t *req)
{
    if (req->rate_noise_psd_bins == 0)
        return 0;
    if (req->rate_noise_psd_bins < 2 || req->rate_noise_psd_bins > LADRC_MARGINS_NOISE_PSD_BINS ||
        !(req->rate_noise_bin_hz > 0.0 && isfinite(req->rate_noise_bin_hz)))
        return -1;
    for (int k = 0; k < req->rate_noise_psd_bins; ++k)
        if (!(req->rate_noise_psd[k] >= 0.0 && isfinite(req->rate_noise_psd[k])))
            return -1;
    return 0;
}

int margins_check_noise(const ladrc_margins_request_t *req)
{
    if (!(req->angle_noise_std_rad >= 0.0 && isfinite(req->angle_noise_std_rad)) ||
        !(req->rate_noise_std_rad_s >= 0.0 && isfinite(req->rate_noise_std_rad_s)) || check_psd(req) != 0)
        return -1;
    if (margins_noise_wanted(req) && !(req->noise_corner_hz > 0.0 && req->noise_corner_hz < 0.5 / req->plant.dt_s))
        return -1;
    return 0;
}

/* |u / noise|^2 at grid bin m: the noise n enters the measurements, so
 * u = Ca (y + n_a) + Cr (r + n_r) with y, r the plant's answer to u (delay
 * included): u = -L u + Ca n_a + Cr n_r, u = S (Ca n_a + Cr n_r). The two
 * noises are independent: their powers add. */
static double power_at_bin(const loop_t *lp, int m, double var_a, double var_r)
{
    const ladrc_margins_workspace_t *ws = lp->ws;
    const cplx z = cexp(I * 2.0 * PI * m / N_FFT);
    const cplx ca = ws->grid_re[0][m] + I * ws->grid_im[0][m];
    const cplx cr = ws->has_rate ? ws->grid_re[1][m] + I * ws->grid_im[1][m] : 0.0;
    cplx gu[NX_MAX], gd[NX_MAX];
    margins_plant_solve(&lp->dp, z, gu, gd);
    const cplx late = 1.0 / cpow_int(z, lp->dp.delay);
    const cplx l = -(ca * gu[0] + cr * gu[1]) * late;
    const double s2 = 1.0 / (creal(1.0 + l) * creal(1.0 + l) + cimag(1.0 + l) * cimag(1.0 + l));
    const double ca2 = creal(ca) * creal(ca) + cimag(ca) * cimag(ca);
    const double cr2 = creal(cr) * creal(cr) + cimag(cr) * cimag(cr);
    return s2 * (var_a * ca2 + var_r * cr2);
}

/* The coloured rate noise at w (rad per tick) as the variance per sample of
 * a white noise of the same density there: a one-sided PSD p ((rad/s)^2/Hz)
 * is a white variance p fs / 2. */
static double psd_as_variance(const ladrc_margins_request_t *req, double w)
{
    if (req->rate_noise_psd_bins == 0)
        return 0.0;
    const double fs = 1.0 / req->plant.dt_s, x = w / (2.0 * PI) * fs / req->rate_noise_bin_hz;
    const int k = (int)floor(x);
    if (k + 1 >= req->rate_noise_psd_bins)
        return k + 1 == req->rate_noise_psd_bins && x == (double)k ? req->rate_noise_psd[k] * 0.5 * fs : 0.0;
    const double f = x - (double)k;
    return ((1.0 - f) * req->rate_noise_psd[k] + f * req->rate_noise_psd[k + 1]) * 0.5 * fs;
}

/* White noise of variance v per sample has the two-sided PSD v over
 * w in (-pi, pi] (rad per tick): a real signal's power in the band
 * [w0, pi] of both sides is (1 / pi) int_w0^pi |H|^2 v dw. The integral by
 * the trapezoid rule on the FFT grid (spacing 2 pi / N_FFT), the part bin
 * below w0 by its upper end's value. */
double margins_cmd_noise(const loop_t *lp, const ladrc_margins_request_t *req)
{
    if (!margins_noise_wanted(req) || lp->ws == NULL)
        return 0.0;
    const double var_a = req->angle_noise_std_rad * req->angle_noise_std_rad;
    const double var_r = req->rate_noise_std_rad_s * req->rate_noise_std_rad_s;
    const double step = 2.0 * PI / N_FFT;
    const double w0 = 2.0 * PI * req->noise_corner_hz * req->plant.dt_s;
    int m0 = (int)ceil(w0 / step);
    if (m0 < 1)
        m0 = 1;
    if (m0 > N_HALF)
        return 0.0;
    double prev = power_at_bin(lp, m0, var_a, var_r + psd_as_variance(req, m0 * step));
    double sum = (m0 * step - w0) * prev;
    for (int m = m0 + 1; m <= N_HALF; ++m) {
        const double p = power_at_bin(lp, m, var_a, var_r + psd_as_variance(req, m * step));
        sum += 0.5 * step * (prev + p);
        prev = p;
    }
    return sqrt(fmax(sum, 0.0) / PI);
}
