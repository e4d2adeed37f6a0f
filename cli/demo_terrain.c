/* fracterra — cli/demo_terrain.c: the demo's terrain step: a synthetic DEM (fft synthesis, D = 2.3, 512²,
 * seeded) and the Maunga Whau DEM, each as a GDAL hillshade with colour relief and as a perspective view,
 * and Clarke's model (Clarke 1987, z = T + cF + H) fitted to the volcano, its figures in the caption.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "demo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define DEMO_VOLCANO_FILE "dem_volcano_maunga_whau_10m.tif"
#define SYNTH_SIDE 512
#define SYNTH_SEED 2024

static char synth_caption[512], model_caption[1024];

static int shade(demo_ctx *ctx, const char *dem, const char *file, const char *title, const char *caption)
{
    ft_io_hillshade_opts ho = FT_IO_HILLSHADE_OPTS_DEFAULT;
    ho.color = 1;
    ho.z_factor = 2.0;
    const char *out = demo_add_output(ctx, file, title, caption, 1);
    return out ? ft_io_hillshade(dem, out, &ho) : ft_last_error_code();
}

static int view(demo_ctx *ctx, const ft_grid *g, const char *file, const char *title, const char *caption)
{
    ft_perspective_opts po = FT_PERSPECTIVE_OPTS_DEFAULT;
    po.width = 900;
    const char *out = demo_add_output(ctx, file, title, caption, 1);
    return out ? ft_render_perspective(g, out, &po) : ft_last_error_code();
}

static int synthetic(demo_ctx *ctx)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
    ft_grid *g = NULL;
    so.dim = 2.3;
    so.sigma = 60.0;
    so.cell = 10.0;
    so.seed = SYNTH_SEED;
    snprintf(synth_caption, sizeof synth_caption,
             "A fractional Brownian surface of D = 2.3 (spectral synthesis on a padded grid), %d &times; %d cells "
             "of 10 m, standard deviation 60 m, seed %d: <code>fracterra synth terrain_synth.tif --dim 2.3 "
             "--size %dx%d --cell 10 --sigma 60 --seed %d</code>.",
             SYNTH_SIDE, SYNTH_SIDE, SYNTH_SEED, SYNTH_SIDE, SYNTH_SIDE, SYNTH_SEED);
    const char *tif = demo_add_output(ctx, "terrain_synth.tif", "Synthetic terrain (GeoTIFF)", synth_caption, 0);
    int rc = tif ? ft_terrain_synth(SYNTH_SIDE, SYNTH_SIDE, &so, &g) : ft_last_error_code();
    if (rc == FT_OK)
        rc = ft_io_write_grid(tif, g, &wo);
    if (rc == FT_OK)
        rc = shade(ctx, tif, "terrain_synth_hillshade.png", "Synthetic terrain, shaded relief",
                   "GDAL's hillshade (light from the north-west at 45&deg;, z-factor 2) times its colour relief "
                   "with fracterra's hypsometric ramp: <code>fracterra hillshade terrain_synth.tif "
                   "terrain_synth_hillshade.png --z-factor 2 --color</code>.");
    if (rc == FT_OK)
        rc = view(ctx, g, "terrain_synth_perspective.png", "Synthetic terrain, perspective view",
                  "The same surface seen from the south-south-west, 35&deg; down, z-buffered and lit: "
                  "<code>fracterra render terrain_synth.tif terrain_synth_perspective.png --view perspective</code>.");
    ft_grid_free(g);
    return rc;
}

static void describe_model(const ft_clarke_model *m)
{
    snprintf(model_caption, sizeof model_caption,
                     "Clarke's model z = T + cF + H fitted to Maunga Whau: trend r&sup2; %.2f; %zu harmonics above "
                     "%.1f%% of the detrended variance (%.0f%% together; the strongest: wavelength %.0f m, "
                     "%.0f%%); spectral slope &beta; = %.2f (r&sup2; %.2f) over %zu harmonics, so D = (8 &minus; "
                     "&beta;)/2 = %.2f (Clarke's eq. viii would give %.2f); c = %.2f. "
                     "<code>fracterra model fit %s -o volcano_clarke_model.json</code>.",
                     m->trend_r2, m->nharmonics, m->cutoff, 100.0 * m->harmonic_share,
                     m->nharmonics ? m->harmonics[0].wavelength : NAN,
                     m->nharmonics ? 100.0 * m->harmonics[0].share : NAN, m->slope, m->r2, m->npairs, m->D,
                     m->D_clarke_eq8, m->c, DEMO_VOLCANO_FILE);
}

static int volcano(demo_ctx *ctx)
{
    char *dem = demo_join_path(ctx->data, DEMO_VOLCANO_FILE);
    if (dem == NULL)
        return ft_error(FT_E_NOMEM, "demo: out of memory");
    int rc = shade(ctx, dem, "volcano_gdal_hillshade.png", "Maunga Whau, GDAL hillshade with colour relief",
                   "<code>fracterra hillshade dem_volcano_maunga_whau_10m.tif volcano_gdal_hillshade.png --z-factor 2 "
                   "--color</code>: GDAL's own DEM processing, 61 &times; 87 cells.");
    free(dem);
    if (rc == FT_OK)
        rc = view(ctx, ctx->volcano, "volcano_perspective.png", "Maunga Whau, perspective view",
                  "The 10 m DEM seen from the south-south-west, 35&deg; down, true vertical scale: "
                  "<code>fracterra render dem_volcano_maunga_whau_10m.tif volcano_perspective.png</code>.");
    ft_clarke_model *m = NULL;
    if (rc == FT_OK)
        rc = ft_clarke_fit(ctx->volcano, NULL, &m);
    if (rc == FT_OK) {
        describe_model(m);
        const char *out = demo_add_output(ctx, "volcano_clarke_model.json", "Maunga Whau, Clarke model",
                                          model_caption, 0);
        rc = out ? ft_io_write_clarke_model(out, m) : ft_last_error_code();
    }
    ft_clarke_model_free(m);
    return rc;
}

int demo_step_terrain(demo_ctx *ctx)
{
    int rc = synthetic(ctx);
    return rc == FT_OK ? volcano(ctx) : rc;
}
