/* fracterra — cli/tile_fill.c: `fill` stripe by stripe and on MPI ranks (tile_cli.h), with the cells and the
 * report of the whole-raster run.
 *
 * Rank r of P walks the r-th share of the rows in stripes; each stripe is read with a halo of H rows above
 * and below (--mask's window too) and ft_terrain_fill_rows fills every void that meets the stripe: a void
 * crossing a stripe border is filled by both stripes, identically (its seed is keyed by its first cell, its
 * model by the cells around it), so no cell travels between stripes. H starts at max_void + the ring + 1
 * rows, enough for every void the whole run fills; when a void meeting the stripe may go on beyond the
 * window (no --max-void, a wide void left nodata whose size is reported), the stripe is read again with H
 * doubled, up to the whole raster (bounded by --max-memory: then a clear error). Rank 0 writes its stripes
 * as they come and then the other ranks' shares in row order into one GeoTIFF; the voids are reported in
 * stripe order (= the whole run's raster order), and the output's figures are summed by re-reading it in
 * row order, as the whole run sums them. docs/tiling.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "tile_cli.h"

#include "cli_ranks.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Bytes per window cell while a stripe is filled: the cells and mask read (5), their copy filled (5), the
 * void flags and labels (5), the sd band (5) and --mask's window (6). */
#define FILL_BYTES_PER_CELL 26.0
#define RING_MAX_AUTO 64 /* fill.c's RING_MAX: the widest automatic ring */

typedef struct {
    const cli_command *cmd;
    const tile_fill_job *job;
    size_t nx, ny, nb;   /* nb: bands of the output (2 with the sd) */
    ft_grid_writer *w;   /* rank 0 */
    float *share;        /* other ranks: their rows of each band, NaN = nodata */
    size_t share_row0, share_rows;
    ft_fill_void *voids; /* this rank's voids, in row order */
    size_t nvoids, cap;
    uint64_t totals[3];  /* voids filled, cells filled, cells left */
    int any;             /* a valid cell in this rank's rows */
} fill_run;

static size_t fill_halo(const ft_fill_opts *fo)
{
    size_t ring = fo->ring > 0 ? (size_t)fo->ring : RING_MAX_AUTO;
    return (fo->max_void > 0.0 ? (size_t)ceil(fo->max_void) : 0) + ring + 1;
}

static int keep_voids(fill_run *f, const ft_fill_result *r)
{
    if (f->nvoids + r->nvoids > f->cap) {
        size_t cap = (f->nvoids + r->nvoids) * 2;
        ft_fill_void *v = realloc(f->voids, cap * sizeof *v);
        if (v == NULL) {
            cli_error(f->cmd, "out of memory for the report of %zu voids", cap);
            return CLI_FAIL;
        }
        f->voids = v;
        f->cap = cap;
    }
    if (r->nvoids > 0)
        memcpy(f->voids + f->nvoids, r->voids, r->nvoids * sizeof *r->voids);
    f->nvoids += r->nvoids;
    f->totals[0] += r->voids_filled;
    f->totals[1] += r->cells_filled;
    f->totals[2] += r->cells_left;
    return CLI_OK;
}

/* Rows [s, e) of a window grid (its row 0 at raster row lo) as a grid of their own. */
static ft_grid *rows_of(const ft_grid *g, size_t lo, size_t s, size_t e)
{
    ft_grid *p = ft_grid_create(g->nx, e - s);
    if (p == NULL || ft_grid_ensure_mask(p) != FT_OK) {
        ft_grid_free(p);
        return NULL;
    }
    memcpy(p->z, g->z + (s - lo) * g->nx, p->nx * p->ny * sizeof *p->z);
    if (g->mask)
        memcpy(p->mask, g->mask + (s - lo) * g->nx, p->nx * p->ny);
    else
        memset(p->mask, 1, p->nx * p->ny);
    return p;
}

/* Rows [s, e) of the filled bands to the file (rank 0) or the share buffer. */
static int put_rows(fill_run *f, ft_grid *const bands[2], size_t lo, size_t s, size_t e)
{
    for (size_t b = 0; b < f->nb; b++) {
        ft_grid *p = rows_of(bands[b], lo, s, e);
        if (p == NULL) {
            cli_error(f->cmd, "out of memory for rows %zu-%zu", s, e - 1);
            return CLI_FAIL;
        }
        int rc = CLI_OK;
        if (cli_rank() == 0) {
            rc = ft_io_grid_writer_write(f->w, b + 1, p, 0, s) == FT_OK ? CLI_OK : cli_fail(f->cmd);
        } else {
            float *dst = f->share + b * f->nx * f->share_rows + (s - f->share_row0) * f->nx;
            for (size_t i = 0; i < p->nx * p->ny; i++)
                dst[i] = p->mask[i] ? p->z[i] : NAN;
        }
        ft_grid_free(p);
        if (rc != CLI_OK)
            return rc;
    }
    return CLI_OK;
}

/* The window of rows [lo, hi): the DEM, and --mask's validity flags (NULL without --mask). */
static int read_window(fill_run *f, ft_grid_reader *r, ft_grid_reader *mr, size_t lo, size_t hi, ft_grid **dem,
                       uint8_t **valid)
{
    *valid = NULL;
    if (ft_io_grid_reader_read(r, 0, lo, f->nx, hi - lo, dem) != FT_OK)
        return CLI_FAIL;
    if (mr == NULL)
        return CLI_OK;
    ft_grid *m = NULL;
    if (ft_io_grid_reader_read(mr, 0, lo, f->nx, hi - lo, &m) != FT_OK)
        return CLI_FAIL;
    size_t n = f->nx * (hi - lo);
    *valid = malloc(n);
    if (*valid == NULL) {
        ft_grid_free(m);
        return CLI_FAIL;
    }
    /* gdal_fillnodata's -mask: zero (or nodata) is invalid, to be filled (cmd_fill.c's read_mask) */
    for (size_t i = 0; i < n; i++)
        (*valid)[i] = (m->mask == NULL || m->mask[i]) && m->z[i] != 0.0f;
    ft_grid_free(m);
    return CLI_OK;
}

/* Stripe [s, e): filled with a halo that grows until every void meeting it lies whole in the window. */
static int fill_stripe(fill_run *f, ft_grid_reader *r, ft_grid_reader *mr, size_t s, size_t e, size_t *halo)
{
    const tile_fill_job *j = f->job;
    char why[512] = "";
    for (;;) {
        size_t lo = s > *halo ? s - *halo : 0, hi = e + *halo < f->ny ? e + *halo : f->ny;
        ft_grid *dem = NULL, *bands[2] = {NULL, NULL};
        uint8_t *valid = NULL;
        ft_fill_result *res = NULL;
        if (read_window(f, r, mr, lo, hi, &dem, &valid) != CLI_OK) {
            ft_grid_free(dem);
            if (why[0])
                cli_error(f->cmd, "%s; the window of rows %zu-%zu that would hold it: %s", why, lo, hi - 1,
                          ft_last_error());
            return why[0] ? CLI_FAIL : cli_fail(f->cmd);
        }
        for (size_t y = s; y < e && !f->any; y++)
            for (size_t x = 0; x < f->nx && !f->any; x++) {
                size_t i = (y - lo) * f->nx + x;
                f->any = (dem->mask == NULL || dem->mask[i]) && isfinite(dem->z[i]) && (!valid || valid[i]);
            }
        int lib = ft_terrain_fill_rows(dem, valid, lo, f->ny, s, e, &j->fo, &bands[0], f->nb > 1 ? &bands[1] : NULL,
                                       &res);
        ft_grid_free(dem);
        free(valid);
        int rc = CLI_OK;
        if (lib == FT_OK) {
            rc = put_rows(f, bands, lo, s, e);
            if (rc == CLI_OK)
                rc = keep_voids(f, res);
        } else if (lib == FT_E_UNSUPPORTED && (lo > 0 || hi < f->ny)) {
            snprintf(why, sizeof why, "%s", ft_last_error());
            *halo *= 2;
            continue;
        } else {
            rc = cli_fail(f->cmd);
        }
        ft_grid_free(bands[0]);
        ft_grid_free(bands[1]);
        ft_fill_result_free(res);
        return rc;
    }
}

static int fill_rank(fill_run *f, ft_grid_reader *r, ft_grid_reader *mr, const ft_grid *hdr)
{
    const tile_fill_job *j = f->job;
    size_t a, b;
    tile_rank_share(f->ny, &a, &b);
    f->share_row0 = a;
    f->share_rows = b - a;
    if (cli_rank() == 0) {
        ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
        tile_threads th;
        tile_write_threads(&wo, &th);
        if (ft_io_grid_writer_create(j->out, hdr, f->nb, &wo, &f->w) != FT_OK)
            return cli_fail(f->cmd);
    } else if (b > a && (f->share = malloc(f->nb * f->nx * (b - a) * sizeof *f->share)) == NULL) {
        cli_error(f->cmd, "out of memory for %zu rows of the output", b - a);
        return CLI_FAIL;
    }
    size_t halo = fill_halo(&j->fo);
    double fit = 0.25 * (double)ft_memory_limit() / ((double)f->nx * FILL_BYTES_PER_CELL);
    /* automatic: the stripe and its halo fill a quarter of --max-memory, but a stripe is never thinner than
     * its halo (thinner stripes would read and label the halo over and over for a few rows each) */
    size_t k = j->tile_rows > 0 ? (size_t)j->tile_rows : fit >= 1e9 ? (size_t)1e9 : fit > 3.0 * (double)halo
                                                                                    ? (size_t)fit - 2 * halo
                                                                                    : halo;
    int rc = CLI_OK;
    for (size_t y = a; y < b && rc == CLI_OK; y += k)
        rc = fill_stripe(f, r, mr, y, y + k < b ? y + k : b, &halo);
    return rc;
}

/* Rank 0: the other ranks' rows and voids, in rank (= row) order. */
static int fill_gather(fill_run *f)
{
    for (int k = 1; k < cli_nranks(); k++) {
        size_t a = f->ny * (size_t)k / (size_t)cli_nranks(), b = f->ny * (size_t)(k + 1) / (size_t)cli_nranks();
        uint64_t head[4] = {0, 0, 0, 0}; /* voids, filled, cells filled, cells left */
        int rc = cli_ranks_recv(k, head, sizeof head) == 0 ? CLI_OK : CLI_FAIL;
        ft_fill_result part = {.nvoids = (size_t)head[0], .voids_filled = (size_t)head[1],
                               .cells_filled = (size_t)head[2], .cells_left = (size_t)head[3]};
        part.voids = rc == CLI_OK && head[0] > 0 ? malloc((size_t)head[0] * sizeof *part.voids) : NULL;
        if (rc == CLI_OK && head[0] > 0)
            rc = part.voids != NULL && cli_ranks_recv(k, part.voids, part.nvoids * sizeof *part.voids) == 0
                     ? CLI_OK
                     : CLI_FAIL;
        if (rc == CLI_OK)
            rc = keep_voids(f, &part);
        free(part.voids);
        for (size_t band = 0; band < f->nb && rc == CLI_OK && b > a; band++) {
            ft_grid *g = ft_grid_create(f->nx, b - a);
            rc = g != NULL && cli_ranks_recv(k, g->z, f->nx * (b - a) * sizeof *g->z) == 0 ? CLI_OK : CLI_FAIL;
            if (rc == CLI_OK && ft_io_grid_writer_write(f->w, band + 1, g, 0, a) != FT_OK) {
                ft_grid_free(g);
                return cli_fail(f->cmd);
            }
            ft_grid_free(g);
        }
        if (rc != CLI_OK) {
            cli_error(f->cmd, "cannot receive rows %zu-%zu of the fill from rank %d", a, b - 1, k);
            return rc;
        }
    }
    return CLI_OK;
}

static int fill_send(fill_run *f)
{
    uint64_t head[4] = {f->nvoids, f->totals[0], f->totals[1], f->totals[2]};
    int bad = cli_ranks_send(0, head, sizeof head) != 0 ||
              (f->nvoids > 0 && cli_ranks_send(0, f->voids, f->nvoids * sizeof *f->voids) != 0);
    for (size_t band = 0; band < f->nb && !bad && f->share_rows > 0; band++)
        bad = cli_ranks_send(0, f->share + band * f->nx * f->share_rows, f->nx * f->share_rows * sizeof *f->share);
    if (bad) {
        cli_error(f->cmd, "cannot send the fill's rows to rank 0");
        return CLI_FAIL;
    }
    return CLI_OK;
}

/* The figures of band 1 of the written file, summed in row order in two passes as ft_grid_compute_stats sums
 * the whole run's output (the same doubles in the same order). */
int tile_output_stats(const cli_command *cmd, const char *path, size_t rows, ft_grid_stats *st)
{
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ft_grid_reader *r = NULL;
    if (ft_io_grid_reader_open(path, &ro, &r) != FT_OK)
        return cli_fail(cmd);
    size_t nx = ft_io_grid_reader_header(r)->nx, ny = ft_io_grid_reader_header(r)->ny, n = 0;
    double s = 0.0, ss = 0.0, zmin = INFINITY, zmax = -INFINITY, mean = NAN;
    int rc = CLI_OK;
    for (int pass = 0; pass < 2 && rc == CLI_OK; pass++)
        for (size_t y = 0; y < ny && rc == CLI_OK; y += rows) {
            ft_grid *g = NULL;
            if (ft_io_grid_reader_read(r, 0, y, nx, y + rows < ny ? rows : ny - y, &g) != FT_OK) {
                rc = cli_fail(cmd);
                break;
            }
            for (size_t i = 0; i < g->nx * g->ny; i++) {
                if ((g->mask && !g->mask[i]) || !isfinite(g->z[i]))
                    continue;
                double z = g->z[i];
                if (pass == 0) {
                    s += z;
                    zmin = fmin(zmin, z);
                    zmax = fmax(zmax, z);
                    n++;
                } else {
                    ss += (z - mean) * (z - mean);
                }
            }
            ft_grid_free(g);
            if (pass == 0 && y + rows >= ny)
                mean = n ? s / (double)n : NAN;
        }
    ft_io_grid_reader_close(r);
    st->n = n;
    st->mean = mean;
    st->sd = n ? sqrt(ss / (double)n) : NAN;
    st->min = n ? zmin : NAN;
    st->max = n ? zmax : NAN;
    return rc;
}

static int open_inputs(fill_run *f, ft_grid_reader **r, ft_grid_reader **mr)
{
    const tile_fill_job *j = f->job;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = j->band;
    if (ft_io_grid_reader_open(j->in, &ro, r) != FT_OK)
        return cli_fail(f->cmd);
    f->nx = ft_io_grid_reader_header(*r)->nx;
    f->ny = ft_io_grid_reader_header(*r)->ny;
    if (cli_check_grid_work(f->cmd, j->in, ft_io_grid_reader_header(*r)) != CLI_CONTINUE)
        return CLI_FAIL;
    if (j->mask == NULL)
        return CLI_OK;
    ft_read_grid_opts mo = FT_READ_GRID_OPTS_DEFAULT;
    if (ft_io_grid_reader_open(j->mask, &mo, mr) != FT_OK)
        return cli_fail(f->cmd);
    const ft_grid *m = ft_io_grid_reader_header(*mr);
    if (m->nx != f->nx || m->ny != f->ny) {
        cli_error(f->cmd, "--mask %s is %zu x %zu cells, the DEM %s %zu x %zu", j->mask, m->nx, m->ny, j->in, f->nx,
                  f->ny);
        return CLI_FAIL;
    }
    return CLI_OK;
}

int tile_fill(const cli_command *cmd, const tile_fill_job *job, ft_fill_result *res, ft_grid_stats *st)
{
    fill_run f = {.cmd = cmd, .job = job, .nb = job->fo.realizations > 1 ? 2 : 1};
    ft_grid_reader *r = NULL, *mr = NULL;
    memset(res, 0, sizeof *res);
    int rc = open_inputs(&f, &r, &mr);
    if (rc == CLI_OK)
        rc = fill_rank(&f, r, mr, ft_io_grid_reader_header(r));
    int ok = cli_ranks_all_ok(rc == CLI_OK);
    if (ok && cli_ranks_sum((uint64_t)f.any) == 0) {
        cli_error(cmd, "fill: the DEM %s (%zu x %zu) has no valid cell", job->in, f.nx, f.ny);
        ok = 0;
    }
    rc = ok ? CLI_OK : CLI_FAIL;
    if (ok && cli_rank() == 0) {
        rc = fill_gather(&f);
        rc = rc == CLI_OK && ft_io_grid_writer_commit(f.w) != FT_OK ? cli_fail(cmd) : rc;
        f.w = NULL; /* commit frees it whatever the outcome */
        if (rc == CLI_OK)
            rc = tile_output_stats(cmd, job->out, 1024, st);
    } else if (ok) {
        rc = fill_send(&f);
    }
    if (rc == CLI_OK && cli_rank() == 0) {
        res->voids = f.voids;
        res->nvoids = f.nvoids;
        res->voids_filled = (size_t)f.totals[0];
        res->cells_filled = (size_t)f.totals[1];
        res->cells_left = (size_t)f.totals[2];
        f.voids = NULL;
    }
    ft_io_grid_writer_abort(f.w);
    free(f.share);
    free(f.voids);
    ft_io_grid_reader_close(r);
    ft_io_grid_reader_close(mr);
    return rc;
}
