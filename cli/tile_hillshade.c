/* fracterra — cli/tile_hillshade.c: `hillshade` stripe by stripe and on MPI ranks (tile_cli.h). Each stripe
 * of rows is shaded by ft_io_hillshade_rows from the stripe plus one row above and below (Horn's 3 x 3
 * window), so its cells are those of the whole-DEM run; rank 0 writes its stripes as they come, then the
 * other ranks' shares in row order, into one Byte GeoTIFF (0 = nodata). docs/tiling.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "tile_cli.h"

#include "cli_ranks.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define OUT_TYPE_BYTE 1 /* GDALDataType GDT_Byte */
/* Bytes per cell while a stripe is shaded (ft_io_hillshade_rows): the window read (z and mask: 5) and the
 * engine's shade of it (5); the stripe's copy (5) is made once the window is freed. */
#define SHADE_BYTES_PER_CELL 10.0

typedef struct {
    const cli_command *cmd;
    const char *in;
    const ft_io_hillshade_opts *o;
    size_t nx, ny;
    ft_grid_writer *w;   /* rank 0 */
    unsigned char *share; /* other ranks: their rows' shade */
    size_t share_row0;
} shade_run;

/* Rows [a, b): the shade written (rank 0) or kept; *any set if the DEM has a valid cell there, read off the
 * shade itself (the DEM is read once): a valid cell shades 1..255 (its window takes the centre's value for
 * nodata neighbours, so it is never nodata), a nodata cell 0. */
static int shade_stripe(shade_run *s, size_t a, size_t b, int *any)
{
    ft_grid *sh = NULL;
    if (ft_io_hillshade_rows(s->in, s->o, a, b - a, &sh) != FT_OK)
        return cli_fail(s->cmd);
    for (size_t i = 0; i < s->nx * (b - a) && !*any; i++)
        *any = sh->z[i] > 0.0f;
    int rc = CLI_OK;
    if (cli_rank() == 0)
        rc = ft_io_grid_writer_write(s->w, 1, sh, 0, a) == FT_OK ? CLI_OK : cli_fail(s->cmd);
    else
        for (size_t i = 0; i < s->nx * (b - a); i++)
            s->share[(a - s->share_row0) * s->nx + i] = (unsigned char)sh->z[i];
    ft_grid_free(sh);
    return rc;
}

static int shade_gather(shade_run *s)
{
    for (int k = 1; k < cli_nranks(); k++) {
        size_t a = s->ny * (size_t)k / (size_t)cli_nranks(), b = s->ny * (size_t)(k + 1) / (size_t)cli_nranks();
        if (b == a)
            continue;
        size_t n = s->nx * (b - a);
        unsigned char *buf = malloc(n);
        ft_grid *g = ft_grid_create(s->nx, b - a);
        int rc = buf && g ? CLI_OK : (cli_error(s->cmd, "out of memory for rows %zu-%zu", a, b - 1), CLI_FAIL);
        if (rc == CLI_OK && cli_ranks_recv(k, buf, n) != 0) {
            cli_error(s->cmd, "cannot receive rows %zu-%zu of the shade from rank %d", a, b - 1, k);
            rc = CLI_FAIL;
        }
        for (size_t i = 0; rc == CLI_OK && i < n; i++)
            g->z[i] = (float)buf[i];
        if (rc == CLI_OK && ft_io_grid_writer_write(s->w, 1, g, 0, a) != FT_OK)
            rc = cli_fail(s->cmd);
        free(buf);
        ft_grid_free(g);
        if (rc != CLI_OK)
            return rc;
    }
    return CLI_OK;
}

static int shade_rank(shade_run *s, ft_grid_reader *r, const char *out, long tile_rows, int *any)
{
    const ft_grid *h = ft_io_grid_reader_header(r);
    char what[PATH_MAX + 64];
    snprintf(what, sizeof what, "shading '%s' (%zu x %zu cells)", s->in, h->nx, h->ny);
    if (h->nx < 2 || h->ny < 2) {
        cli_error(s->cmd, "%s has %zu x %zu cells; a hillshade needs at least 2 x 2", s->in, h->nx, h->ny);
        return CLI_FAIL;
    }
    if (ft_check_work(4.0 * (double)h->nx * (double)h->ny, what) != FT_OK) /* the whole run's bound */
        return cli_fail(s->cmd);
    size_t a, b;
    tile_rank_share(s->ny, &a, &b);
    s->share_row0 = a;
    if (cli_rank() == 0) {
        ft_grid hdr = *h;
        hdr.has_nodata = 1;
        hdr.nodata_value = 0.0;
        ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
        tile_threads th;
        wo.type = OUT_TYPE_BYTE;
        tile_write_threads(&wo, &th);
        if (ft_io_grid_writer_create(out, &hdr, 1, &wo, &s->w) != FT_OK)
            return cli_fail(s->cmd);
    } else if (b > a && (s->share = malloc(s->nx * (b - a))) == NULL) {
        cli_error(s->cmd, "out of memory for %zu rows of the shade", b - a);
        return CLI_FAIL;
    }
    double fit = 0.25 * (double)ft_memory_limit() / ((double)s->nx * SHADE_BYTES_PER_CELL);
    size_t k = tile_rows > 0 ? (size_t)tile_rows : fit >= 1e9 ? (size_t)1e9 : fit >= 1.0 ? (size_t)fit : 1;
    int rc = CLI_OK;
    for (size_t y = a; y < b && rc == CLI_OK; y += k)
        rc = shade_stripe(s, y, y + k < b ? y + k : b, any);
    return rc;
}

int tile_hillshade(const cli_command *cmd, const char *in, const char *out, const ft_io_hillshade_opts *o,
                   long tile_rows)
{
    shade_run s = {.cmd = cmd, .in = in, .o = o};
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = o->band;
    ft_grid_reader *r = NULL;
    int any = 0, rc = CLI_FAIL;
    if (o->color) {
        cli_error(cmd, "--color: the colour relief spans the whole DEM's range and is not made stripe by stripe "
                  "(--tile-rows, MPI)");
    } else if (ft_io_grid_reader_open(in, &ro, &r) != FT_OK) {
        rc = cli_fail(cmd);
    } else {
        s.nx = ft_io_grid_reader_header(r)->nx;
        s.ny = ft_io_grid_reader_header(r)->ny;
        rc = shade_rank(&s, r, out, tile_rows, &any);
    }
    int ok = cli_ranks_all_ok(rc == CLI_OK);
    if (ok && cli_ranks_sum((uint64_t)any) == 0) {
        cli_error(cmd, "%s has no valid cell (all %zu are nodata): nothing to shade", in, s.nx * s.ny);
        ok = 0;
    }
    rc = ok ? CLI_OK : CLI_FAIL;
    if (ok && cli_rank() == 0) {
        rc = shade_gather(&s);
        rc = rc == CLI_OK && ft_io_grid_writer_commit(s.w) != FT_OK ? cli_fail(cmd) : rc;
        s.w = rc == CLI_OK ? NULL : s.w;
    } else if (ok) {
        size_t a, b;
        tile_rank_share(s.ny, &a, &b);
        if (b > a && cli_ranks_send(0, s.share, s.nx * (b - a)) != 0) {
            cli_error(cmd, "cannot send the shade's rows to rank 0");
            rc = CLI_FAIL;
        }
    }
    ft_io_grid_writer_abort(s.w);
    free(s.share);
    ft_io_grid_reader_close(r);
    return rc;
}
