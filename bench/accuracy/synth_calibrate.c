/* fracterra — bench/accuracy/synth_calibrate.c: measures the calibration tables of the sra and midpoint
 * synthesizers (src/terrain/synth/synth_calibration.c, docs/terrain-synthesis.md).
 *
 * For every raw D_param on a grid, synthesizes `seeds` surfaces of n x n with the paper's raw method
 * (ft_synth_sra_fill / ft_synth_midpoint_fill with H = 3 - D_param, D_param may leave (2, 3) where the
 * algorithm allows it) and prints the median over the seeds of the variogram D over lags 1..16 cells:
 * mean squared difference along rows and columns at every integer lag, least squares of its log on log
 * lag, D = 3 - slope / 2. The (D_param, D_measured) pairs are the tables of synth_calibration.c.
 *
 * usage: fracterra_accuracy_synth_calibrate [sra|midpoint] [n] [seeds]
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"
#include "terrain/synth/synth_internal.h"
#include "accuracy_util.h"

int main(int argc, char **argv)
{
    const char *m = argc > 1 ? argv[1] : "sra";
    size_t n = argc > 2 ? (size_t)atoi(argv[2]) : 512;
    int seeds = argc > 3 ? atoi(argv[3]) : 9;
    int sra = strcmp(m, "sra") == 0;
    if (!sra && strcmp(m, "midpoint") != 0) {
        fprintf(stderr, "usage: %s [sra|midpoint] [n] [seeds]\n", argv[0]);
        return 2;
    }
    if (seeds < 1 || seeds > 64 || n < 64) {
        fprintf(stderr, "%s: n >= 64 and 1 <= seeds <= 64\n", argv[0]);
        return 2;
    }
    float *z = malloc(n * n * sizeof *z);
    double d[64];
    /* midpoint needs H < 1 (its displacement variance has the factor 1 - 2^(2H - 2)) */
    double lo = sra ? 1.70 : 2.01, hi = 3.0;
    printf("# %s, %zux%zu, median of %d seeds, variogram D over lags 1-16\n# D_param  D_measured\n", m, n, n, seeds);
    for (double Dp = lo; Dp <= hi + 1e-9; Dp += 0.025) {
        double Dq = Dp > 2.99 ? 2.99 : Dp;
        for (int s = 0; s < seeds; s++) {
            ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
            o.seed = (uint64_t)s + 101;
            int rc = sra ? ft_synth_sra_fill(n, n, 3.0 - Dq, &o, z) : ft_synth_midpoint_fill(n, n, 3.0 - Dq, &o, z);
            if (rc != FT_OK) {
                fprintf(stderr, "%s\n", ft_last_error());
                return 1;
            }
            double v[ACCURACY_LAGS + 1];
            accuracy_variogram16(z, n, v);
            d[s] = accuracy_fit_variogram16(v);
        }
        qsort(d, (size_t)seeds, sizeof d[0], accuracy_cmp_double);
        printf("%.3f %.4f\n", Dq, seeds % 2 ? d[seeds / 2] : 0.5 * (d[seeds / 2 - 1] + d[seeds / 2]));
        fflush(stdout);
    }
    free(z);
    return 0;
}
