/* fracterra — fill_variogram.c: the power-variogram model of a void, fitted on the valid cells of a ring
 * around it (docs/terrain-fill.md).
 *
 * For lags h = 1..FT_FILL_LAG_MAX cells, v(h) = mean of (z(x + h e) - z(x))² over the pairs along rows
 * and columns (e a unit step) with both cells in the ring. The model v(h) = v1 h^(2H) of a fractional
 * Brownian surface (Mandelbrot & Van Ness 1968; D = 3 - H, Arakawa & Krotkov eq. 2 in squared form) is
 * fitted by least squares of log v on log h; a DEM's roughness varies from place to place, so each void
 * gets the model of its own surroundings.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <string.h>

#include "internal.h"
#include "terrain/fill/fill_internal.h"

int ft_fill_fit_model(const float *z, const uint8_t *use, size_t nx, size_t ny, double H_fixed,
                      ft_fill_model *m)
{
    double sum[FT_FILL_LAG_MAX + 1], cnt[FT_FILL_LAG_MAX + 1];
    memset(sum, 0, sizeof sum);
    memset(cnt, 0, sizeof cnt);
    memset(m, 0, sizeof *m);
    m->r2 = NAN;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            size_t i = y * nx + x;
            if (!use[i])
                continue;
            double v = z[i];
            for (size_t h = 1; h <= FT_FILL_LAG_MAX; h++) {
                if (x + h < nx && use[i + h]) {
                    double d = (double)z[i + h] - v;
                    sum[h] += d * d;
                    cnt[h] += 1.0;
                }
                if (y + h < ny && use[i + h * nx]) {
                    double d = (double)z[i + h * nx] - v;
                    sum[h] += d * d;
                    cnt[h] += 1.0;
                }
            }
        }
    m->pairs1 = (size_t)cnt[1];
    double lx[FT_FILL_LAG_MAX], ly[FT_FILL_LAG_MAX];
    int n = 0, zero = 0;
    for (int h = 1; h <= FT_FILL_LAG_MAX; h++) {
        if (cnt[h] < FT_FILL_MIN_PAIRS)
            continue;
        if (!(sum[h] > 0.0)) {
            zero++;
            continue;
        }
        lx[n] = log((double)h);
        ly[n] = log(sum[h] / cnt[h]);
        n++;
    }
    if (n == 0 && zero > 0)
        return FT_E_NUMERIC; /* flat: m->v1 = 0 */
    if (n < (H_fixed > 0.0 ? 1 : 3))
        return FT_E_EMPTY;
    double mx = 0.0, my = 0.0;
    for (int i = 0; i < n; i++) {
        mx += lx[i];
        my += ly[i];
    }
    mx /= n;
    my /= n;
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (int i = 0; i < n; i++) {
        sxx += (lx[i] - mx) * (lx[i] - mx);
        sxy += (lx[i] - mx) * (ly[i] - my);
        syy += (ly[i] - my) * (ly[i] - my);
    }
    double slope;
    if (H_fixed > 0.0) {
        slope = 2.0 * H_fixed;
        m->H = H_fixed;
    } else {
        slope = sxy / sxx;
        m->r2 = syy > 0.0 ? sxy * sxy / (sxx * syy) : 1.0;
        double H = slope / 2.0, Hmax = 3.0 - FT_FILL_D_MIN, Hmin = 3.0 - FT_FILL_D_MAX;
        if (H > Hmax || H < Hmin) {
            m->clamped = 1;
            H = H > Hmax ? Hmax : Hmin;
        }
        m->H = H;
        slope = 2.0 * H;
    }
    /* v1: the measured mean square at one cell (the one-cell increments across the border are the seam
     * users see); the fitted line's value there only when lag 1 has too few pairs */
    m->v1 = cnt[1] >= FT_FILL_MIN_PAIRS && sum[1] > 0.0 ? sum[1] / cnt[1] : exp(my - slope * mx);
    return FT_OK;
}
