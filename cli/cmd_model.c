/* fracterra — cli/cmd_model.c: `fracterra model fit|simulate`: Clarke's scale-based model z = T + cF + H
 * (Clarke 1987, "Scale-based simulation of topography"; docs/terrain-clarke.md).
 *
 *   model fit DEM.tif [--cutoff PCT] [--no-taper] [-o MODEL.json] [--json]   calibrate on a DEM
 *   model simulate MODEL.json OUT.tif [--refine K] [--extent E] [--seed N]   invert: a new DEM
 *
 * The model file is the library's (ft_io_write_clarke_model, src/io/clarke_model_json.c); `model simulate` reads exactly what `model fit -o`
 * writes.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "terrain_cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- model fit ---- */

typedef struct {
    ft_clarke_opts co;
    const char *out;
    int json;
} fit_args;

static int on_fit_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    fit_args *a = ctx;
    switch (opt) {
    case 'c': return cli_parse_double(cmd, "--cutoff", arg, 0.0, 100.0, CLI_OPEN_LO, &a->co.cutoff);
    case 'T': a->co.taper = 0; return CLI_CONTINUE;
    case 'n':
        if (strcmp(arg, "spectrum") == 0)
            a->co.noise = FT_CLARKE_NOISE_SPECTRUM;
        else if (strcmp(arg, "power-law") == 0)
            a->co.noise = FT_CLARKE_NOISE_POWER_LAW;
        else
            return cli_usage_error(cmd, "--noise must be spectrum or power-law, got '%s'", arg);
        return CLI_CONTINUE;
    case 'w': return cli_parse_double(cmd, "--min-wavelength", arg, 0.0, INFINITY, CLI_CLOSED, &a->co.min_wavelength);
    case 'o': a->out = arg; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* Harmonic directions from true north: the fitted grid's azimuths are from its grid north, which turns by
 * the meridian convergence at the grid's centre (2.2 deg for UTM 32N in Luxembourg; 0 for the local TM
 * a lon/lat DEM is fitted on). *north: grid azimuth of true north, NAN without a CRS (grid north kept). */
static int directions_from_true_north(const cli_command *cmd, const char *dem, ft_clarke_model *m, double *north)
{
    *north = NAN;
    if (m->crs_wkt == NULL || m->crs_wkt[0] == '\0')
        return CLI_CONTINUE;
    double hx = 0.5 * (double)m->nx, hy = 0.5 * (double)m->ny;
    double x = m->gt[0] + hx * m->gt[1] + hy * m->gt[2], y = m->gt[3] + hx * m->gt[4] + hy * m->gt[5];
    if (ft_io_crs_grid_north(m->crs_wkt, x, y, north) != FT_OK) {
        cli_error(cmd, "%s: %s", dem, ft_last_error());
        return CLI_FAIL;
    }
    for (size_t i = 0; i < m->nharmonics; i++) {
        double d = fmod(m->harmonics[i].direction - *north + 360.0, 180.0);
        m->harmonics[i].direction = d >= 180.0 ? 0.0 : d;
    }
    return CLI_CONTINUE;
}

static void print_model(const char *dem, const ft_clarke_model *m)
{
    printf("Clarke model of %s (%zu x %zu cells, %zu valid, %zu nodata filled with the trend)\n", dem, m->nx, m->ny,
           m->valid, m->nodata_filled);
    printf("  trend     z = %.6g + %.6g x + %.6g y   (r2 %.3f)\n", m->beta0, m->beta1, m->beta2, m->trend_r2);
    printf("  harmonics %zu at or above %g%% of the detrended variance, %.1f%% together\n", m->nharmonics,
           m->cutoff, 100.0 * m->harmonic_share);
    for (size_t i = 0; i < m->nharmonics; i++) {
        const ft_clarke_harmonic *h = &m->harmonics[i];
        printf("    (%3d,%4d)  wavelength %10.4g  direction %5.1f deg  amplitude %9.4g  share %5.2f%%\n", h->k, h->l,
               h->wavelength, h->direction, hypot(h->a, h->b), 100.0 * h->share);
    }
    printf("  spectrum  log10 P = %.4f + %.4f log10 wavelength over %zu waves of %g cells or more (r2 %.3f)\n",
           m->intercept, m->slope, m->npairs, m->min_wavelength, m->r2);
    printf("  D = (8 - beta)/2 = %.3f   (Clarke's eq. viii, 3 - beta/2: %.3f)   c = %.4g\n", m->D, m->D_clarke_eq8,
           m->c);
    double cell = fmin(hypot(m->gt[1], m->gt[4]), hypot(m->gt[2], m->gt[5]));
    printf("  regimes   %zu of the radial spectrum (%zu rings) over wavelengths of %g cells or more\n", m->nregimes,
           m->nspectrum, m->min_wavelength);
    for (size_t i = 0; i < m->nregimes; i++) {
        const ft_clarke_regime *g = &m->regimes[i];
        printf("    %zu: D %.3f over wavelengths %.4g-%.4g (%.1f-%.1f cells), %zu rings, r2 %.3f\n", i + 1, g->D,
               g->wavelength_lo, g->wavelength_hi, g->wavelength_lo / cell, g->wavelength_hi / cell, g->bins, g->r2);
        if (i + 1 < m->nregimes)
            printf("       break at wavelength %.4g (%.1f cells)\n", m->breaks[i], m->breaks[i] / cell);
    }
    printf("  noise F   %s\n", m->noise == FT_CLARKE_NOISE_SPECTRUM ? "the measured radial spectrum"
                                                                    : "the one power law (Clarke)");
}

static int fit_report(const cli_command *cmd, const fit_args *a, const char *dem, const ft_clarke_model *m,
                      const ft_crs_info *crs, double north)
{
    if (!(m->D > 2.0 && m->D < 3.0))
        cli_warn(cmd, "%s: the spectrum (beta = %.2f) is %s than any fractional Brownian surface's: D = %.2f is "
                 "outside (2,3); %s", dem, m->slope, m->D <= 2.0 ? "steeper" : "flatter", m->D,
                 m->noise == FT_CLARKE_NOISE_SPECTRUM ? "the model simulates the measured spectrum, see its regimes"
                                                      : "the model still simulates with the fitted power");
    for (size_t i = 0; i < m->nregimes; i++)
        if (!(m->regimes[i].D >= 2.0 && m->regimes[i].D <= 3.0))
            cli_warn(cmd, "%s: spectrum regime %zu (wavelengths %.4g-%.4g) has D = %.2f, outside [2,3]", dem, i + 1,
                     m->regimes[i].wavelength_lo, m->regimes[i].wavelength_hi, m->regimes[i].D);
    if (a->out && ft_io_write_clarke_model(a->out, m) != FT_OK)
        return cli_fail(cmd);
    const char *from = isnan(north) ? "grid north" : "true north";
    if (!a->json) {
        print_model(dem, m);
        printf("  directions: azimuths of the wave vectors, degrees clockwise from %s\n", from);
        if (a->out)
            printf("wrote %s\n", a->out);
        return CLI_OK;
    }
    char *text = ft_io_clarke_model_to_json(m);
    json_object *o = text ? json_tokener_parse(text) : NULL;
    free(text);
    if (o == NULL)
        return cli_fail(cmd);
    json_object_object_add(o, "input", json_object_new_string(dem));
    json_object_object_add(o, "output", a->out ? json_object_new_string(a->out) : NULL);
    /* wavelengths and the range in this unit, trend per unit; lon/lat input was fitted on its local TM warp */
    json_object *hs = NULL;
    if (json_object_object_get_ex(o, "harmonics", &hs)) {
        json_object_object_add(hs, "direction_from", json_object_new_string(from));
        json_object_object_add(hs, "grid_north_azimuth", isnan(north) ? NULL : json_object_new_double(north));
    }
    json_object_object_add(o, "units", crs->scale_unit[0] ? json_object_new_string(crs->scale_unit) : NULL);
    if (crs->geographic)
        json_object_object_add(o, "geographic", cli_geo_json(crs, m->crs_wkt));
    return cli_print_json(cmd, o);
}

static int run_fit(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {{"cutoff", required_argument, NULL, 'c'},
                                             {"no-taper", no_argument, NULL, 'T'},
                                             {"noise", required_argument, NULL, 'n'},
                                             {"min-wavelength", required_argument, NULL, 'w'},
                                             {"output", required_argument, NULL, 'o'},
                                             {"json", no_argument, NULL, 'j'},
                                             CLI_OPT_HELP,
                                             CLI_OPT_END};
    static const char *const names[] = {"DEM"};
    fit_args a = {.co = FT_CLARKE_OPTS_DEFAULT};
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "o:j", on_fit_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc == CLI_CONTINUE)
        rc = cli_refuse_overwrite(cmd, "--output", a.out, argv[first], (const char *)NULL);
    if (rc != CLI_CONTINUE)
        return rc;
    if (a.out && ft_io_check_writable(a.out) != FT_OK)
        return cli_fail(cmd);
    ft_grid *g = NULL;
    ft_crs_info crs;
    if (terrain_read_dem(cmd, argv[first], &g) != CLI_CONTINUE)
        return CLI_FAIL;
    if (cli_geo_grid_ground(cmd, argv[first], &g, &crs) != CLI_CONTINUE) { /* lon/lat: fitted in metres */
        ft_grid_free(g);
        return CLI_FAIL;
    }
    ft_clarke_model *m = NULL;
    a.co.progress = cli_progress();
    double north = NAN;
    if (ft_clarke_fit(g, &a.co, &m) != FT_OK)
        rc = cli_fail(cmd);
    else if ((rc = directions_from_true_north(cmd, argv[first], m, &north)) == CLI_CONTINUE)
        rc = fit_report(cmd, &a, argv[first], m, &crs, north);
    ft_clarke_model_free(m);
    ft_grid_free(g);
    return rc;
}

static const cli_command cmd_model_fit = {
    "model fit",
    "fit Clarke's model to a DEM",
    "fracterra model fit DEM [--cutoff PCT] [--no-taper] [--min-wavelength CELLS] [--noise KIND] [-o MODEL.json]\n"
    "                    [--json]",
    "Fits z = T + cF + H (Clarke 1987): T the least-squares plane, H the harmonics of the detrended DEM\n"
    "holding at least PCT percent of its variance, F fractal noise. Clarke's F follows one log-log\n"
    "regression of harmonic power on wavelength; D = (8 - beta)/2 for the 2-D spectrum (Clarke's eq. viii\n"
    "value, 3 - beta/2, is printed as well, labelled). Real DEMs bend: by default F is the DEM's measured\n"
    "radial spectrum of z - T - H (quarter-octave rings), so a simulation has the DEM's roughness at every\n"
    "scale; its regimes (straight runs, each with D and a wavelength range) and the breaks between them\n"
    "are found by the log-log regime search and reported. Nodata cells are filled\n"
    "with the trend before the Fourier analysis (counted in \"nodata_filled\"). A harmonic is one of the\n"
    "grid's Fourier modes (k, l); its wavelength (ground units) and direction (clockwise from true north,\n"
    "or grid north without a CRS) are those of the plane wave of continuous frequency fitting the detrended\n"
    "DEM best near that mode: a property of the terrain, not of the grid's extent.\n\n"
    "Options:\n"
    "  --cutoff PCT        share of the detrended variance a harmonic must reach, in (0,100] (default 2.5)\n"
    "  --no-taper          regress on the raw periodogram (Clarke) instead of a Hann-tapered one\n"
    "  --min-wavelength N  regress over the waves of at least N cells (default 4: aliasing flattens the\n"
    "                      band near the Nyquist frequency); 0 = every wave, as Clarke\n"
    "  --noise KIND        the F the model simulates: spectrum (default, the measured radial spectrum) or\n"
    "                      power-law (Clarke's one law)\n"
    "  -o, --output FILE   write the model (JSON) for `fracterra model simulate`\n"
    "  -j, --json          print the model: \"method\", \"D\", \"D_clarke_eq8\", \"r2\", \"stderr\", \"range\",\n"
    "                      \"c\", \"grid\", \"original\", \"trend\", \"harmonics\", \"regression\", \"format_version\",\n"
    "                      \"noise\", \"regimes\" (D, wavelength, wavelength_cells, frequency, slope, r2, bins),\n"
    "                      \"breaks\" (wavelengths), \"spectrum\", \"warnings\", \"input\", \"output\"\n"
    "  -h, --help          print this help\n\n"
    "Example:\n"
    "  fracterra model fit dem.tif --cutoff 2.5 -o dem-model.json\n",
    run_fit,
};

/* ---- model simulate ---- */

typedef struct {
    ft_clarke_sim_opts so;
    const char *driver;
    int json;
} sim_args;

static int on_sim_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    sim_args *a = ctx;
    switch (opt) {
    case 'r': return cli_parse_int(cmd, "--refine", arg, 1, 64, &a->so.refine);
    case 'e': return cli_parse_int(cmd, "--extent", arg, 1, 16, &a->so.extent);
    case 'S': return terrain_parse_seed(cmd, arg, &a->so.seed);
    case 'f': a->driver = arg; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int sim_report(const cli_command *cmd, const sim_args *a, const char *out, const ft_grid *g, double c)
{
    if (!a->json) {
        printf("wrote %s: %zu x %zu cells, c = %.4g, seed %llu\n", out, g->nx, g->ny, c,
               (unsigned long long)a->so.seed);
        return CLI_OK;
    }
    json_object *o = json_object_new_object();
    json_object_object_add(o, "output", json_object_new_string(out));
    json_object_object_add(o, "seed", json_object_new_uint64(a->so.seed));
    json_object_object_add(o, "refine", json_object_new_int(a->so.refine));
    json_object_object_add(o, "extent", json_object_new_int(a->so.extent));
    json_object_object_add(o, "c", cli_json_double(c));
    json_object_object_add(o, "grid", terrain_grid_figures(g));
    return cli_print_json(cmd, o);
}

static int simulate(const cli_command *cmd, sim_args *a, const char *model_path, const char *out)
{
    ft_clarke_model *m = NULL;
    ft_grid *g = NULL;
    ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
    double c = 0.0;
    wo.driver = a->driver;
    a->so.c_used = &c;
    a->so.progress = cli_progress();
    int rc = ft_io_check_writable(out);
    if (rc == FT_OK)
        rc = ft_io_read_clarke_model(model_path, &m);
    if (rc == FT_OK)
        rc = ft_clarke_simulate(m, &a->so, &g);
    if (rc == FT_OK)
        rc = ft_io_write_grid(out, g, &wo);
    int status = rc == FT_OK ? sim_report(cmd, a, out, g, c) : cli_fail(cmd);
    ft_grid_free(g);
    ft_clarke_model_free(m);
    return status;
}

static int run_simulate(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {{"refine", required_argument, NULL, 'r'},
                                             {"extent", required_argument, NULL, 'e'},
                                             {"seed", required_argument, NULL, 'S'},
                                             {"format", required_argument, NULL, 'f'},
                                             {"json", no_argument, NULL, 'j'},
                                             CLI_OPT_HELP,
                                             CLI_OPT_END};
    static const char *const names[] = {"MODEL.json", "OUT"};
    sim_args a = {.so = FT_CLARKE_SIM_OPTS_DEFAULT};
    a.so.seed = TERRAIN_DEFAULT_SEED;
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "f:j", on_sim_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 2);
    if (rc == CLI_CONTINUE)
        rc = cli_refuse_overwrite(cmd, "OUT", argv[first + 1], argv[first], (const char *)NULL);
    if (rc != CLI_CONTINUE)
        return rc;
    return simulate(cmd, &a, argv[first], argv[first + 1]);
}

static const cli_command cmd_model_simulate = {
    "model simulate",
    "simulate a DEM from a Clarke model",
    "fracterra model simulate MODEL.json OUT [--refine K] [--extent E] [--seed N] [-f DRIVER] [--json]",
    "Inverts a model written by `fracterra model fit -o`: the trend T and the kept harmonics H are rebuilt,\n"
    "fractal noise F with the model's power per harmonic and random phases is added, and a shift gives the\n"
    "original's mean. With the measured spectrum (the default) F already has the DEM's variogram (c = 1);\n"
    "with a power-law model c is chosen so that the cells over the fitted extent have the original's\n"
    "standard deviation (Clarke's procedure).\n"
    "The output keeps the model's CRS; its cells are K times smaller with --refine K.\n\n"
    "Options:\n"
    "  --refine K        K times more cells along each axis over the same extent, in [1,64] (default 1)\n"
    "  --extent E        E times the extent along each axis from the same corner, in [1,16] (default 1)\n"
    "  --seed N          phases of F (default 1; printed in the JSON)\n"
    "  -f, --format DRV  GDAL driver of the output (default from the extension)\n"
    "  -j, --json        print {\"output\", \"seed\", \"refine\", \"extent\", \"c\", \"grid\"}\n"
    "  -h, --help        print this help\n\n"
    "Example:\n"
    "  fracterra model simulate dem-model.json finer.tif --refine 4 --seed 7\n",
    run_simulate,
};

/* ---- dispatch ---- */

static const cli_command *const subcommands[] = {&cmd_model_fit, &cmd_model_simulate};

static int run_model(const cli_command *cmd, int argc, char **argv)
{
    return cli_run_subcommand(cmd, subcommands, sizeof subcommands / sizeof subcommands[0], argc, argv);
}

const cli_command cli_cmd_model = {
    "model",
    "Clarke's scale-based terrain model: fit it to a DEM, simulate from it",
    "fracterra model fit|simulate [OPTIONS] ARGS...",
    "Clarke (1987): terrain = linear trend + significant Fourier harmonics + scaled fractal noise.\n\n"
    "Subcommands:\n"
    "  fit DEM [-o MODEL.json]           calibrate the model on a DEM\n"
    "  simulate MODEL.json OUT [--refine K]  a new DEM from the model\n\n"
    "Run 'fracterra model SUBCOMMAND --help' for its options.\n\n"
    "Example:\n"
    "  fracterra model fit dem.tif -o m.json && fracterra model simulate m.json sim.tif --refine 2\n",
    run_model,
};
