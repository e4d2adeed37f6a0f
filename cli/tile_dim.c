/* fracterra — cli/tile_dim.c: `dim map` and `dim surface` on a raster larger than memory, stripe by stripe,
 * and under mpiexec on several ranks, with the cells and the D of the whole-raster run (tile_cli.h).
 *
 * The decomposition is TauDEM's: stripes of whole rows. Rank r of P takes the r-th of P nearly equal shares of
 * the rows to compute and walks its share in stripes of --tile-rows rows (default: as many as half of
 * --max-memory holds), each read with the halo its operator needs (ft_io_grid_reader_read):
 *  - dim map: output rows [a, b) of the window-centre lattice need input rows [a S, (b - 1) S + W): windows
 *    start at multiples of the step S in global rows, so a stripe whose first row is a multiple of S holds
 *    exactly the windows the whole run measures there (halo W - S rows), and ft_surface_dim_map gives their
 *    cells bit for bit. Rank 0 writes its stripes as they come and then the other ranks' shares, in row
 *    order, into one tiled GeoTIFF (ft_io_grid_writer_*); the figures of the report are summed in the same
 *    order as the whole run's.
 *  - dim surface: rows [a, b) need rows [a, b + max_lag) (ft_surface_lag_stripes_*); every rank forms the
 *    per-row counters of its share, then the running totals pass from rank 0 to rank P - 1, each adding its
 *    rows in order, and back to rank 0, which fits: the additions happen in the order of the whole run.
 * The library computes; this file only moves stripes, counters and pieces between files and ranks.
 * docs/tiling.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "tile_cli.h"

#include "cli_geo.h"
#include "cli_ranks.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int tile_parse_rows(const cli_command *cmd, const char *arg, long *rows)
{
    int v = 0, rc = cli_parse_int(cmd, "--tile-rows", arg, 1, 100000000, &v);
    *rows = v;
    return rc;
}

int tile_wanted(long tile_rows, size_t nx, size_t ny, double bytes_per_cell)
{
    return tile_rows > 0 || cli_ranks_joined() ||
           (double)nx * (double)ny * bytes_per_cell > 0.5 * (double)ft_memory_limit();
}

int tile_is_mosaic(const char *out)
{
    size_t n = strlen(out);
    return n > 4 && strcasecmp(out + n - 4, ".vrt") == 0;
}

void tile_write_threads(ft_write_grid_opts *wo, tile_threads *t)
{
    if (!cli_ranks_joined())
        return;
    const char *user = getenv("GDAL_NUM_THREADS");
    if (user != NULL && user[0] != '\0')
        snprintf(t->opt, sizeof t->opt, "NUM_THREADS=%s", user);
    else
        snprintf(t->opt, sizeof t->opt, "NUM_THREADS=%d", cli_ranks_threads());
    t->co[0] = t->opt;
    t->co[1] = NULL;
    wo->co = t->co;
}

int tile_band_size(const cli_command *cmd, const char *path, int band, size_t *nx, size_t *ny)
{
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = band;
    ft_grid_reader *r = NULL;
    if (ft_io_grid_reader_open(path, &ro, &r) != FT_OK)
        return cli_fail(cmd);
    *nx = ft_io_grid_reader_header(r)->nx;
    *ny = ft_io_grid_reader_header(r)->ny;
    ft_io_grid_reader_close(r);
    return CLI_CONTINUE;
}

/* Opens the band and refuses a geographic one (the whole run warps it to a local projection first, which a
 * stripe cannot do). CLI_CONTINUE or CLI_FAIL (printed). */
static int open_band(const cli_command *cmd, const char *path, int band, ft_grid_reader **r, ft_crs_info *crs)
{
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = band;
    if (ft_io_grid_reader_open(path, &ro, r) != FT_OK)
        return cli_fail(cmd);
    /* the whole run's work bound (--max-work), on the band's size */
    int rc = cli_check_grid_work(cmd, path, ft_io_grid_reader_header(*r));
    if (rc == CLI_CONTINUE)
        rc = cli_geo_crs(cmd, path, ft_io_grid_reader_header(*r)->crs_wkt, crs);
    if (rc == CLI_CONTINUE && crs->geographic)
        rc = cli_geo_refuse(cmd, path, crs, "it cannot be measured stripe by stripe or on MPI ranks",
                            "gdalwarp -t_srs EPSG:<UTM zone>");
    return rc;
}

/* This rank's share [*a, *b) of n rows. */
void tile_rank_share(size_t n, size_t *a, size_t *b)
{
    size_t r = (size_t)cli_rank(), p = (size_t)cli_nranks();
    *a = n * r / p;
    *b = n * (r + 1) / p;
}

/* Rows of nx cells of bytes_per_cell that a quarter of --max-memory holds (at least min_rows): a stripe with
 * its halo. */
static size_t stripe_rows(size_t nx, double bytes_per_cell, size_t min_rows)
{
    double fit = 0.25 * (double)ft_memory_limit() / ((double)nx * bytes_per_cell);
    size_t rows = fit >= 1e9 ? (size_t)1e9 : (size_t)fit;
    return rows > min_rows ? rows : min_rows;
}

/* ---- dim map ---- */

/* Bytes per input cell while a stripe is measured: the float cells and mask read, the sanitized cells and
 * weights of the lag sums, and their block sums (about one more copy). */
#define MAP_BYTES_PER_CELL 18.0

typedef struct {
    const cli_command *cmd;
    const tile_map_job *job;
    size_t nx, ny, nox, noy;
    ft_grid_writer *w;  /* rank 0 */
    tile_map_stats *st; /* rank 0 */
    float *share;       /* other ranks: D then r2 of their share's lattice rows, NaN = nodata */
    size_t share_row0, share_rows;
    uint64_t nugget;    /* this rank's measured windows with white noise removed */
} map_run;

/* Rank 0: a piece of D and r2 (nox x rows, row0 of the lattice) to the file and the report's figures. */
static int map_put(map_run *m, const ft_grid *D, const ft_grid *r2, size_t row0)
{
    if (ft_io_grid_writer_write(m->w, 1, D, 0, row0) != FT_OK || ft_io_grid_writer_write(m->w, 2, r2, 0, row0) != FT_OK)
        return cli_fail(m->cmd);
    tile_map_stats *st = m->st;
    for (size_t i = 0; i < D->nx * D->ny; i++) {
        if ((D->mask != NULL && !D->mask[i]) || isnan(D->z[i]))
            continue;
        double v = D->z[i];
        st->lo = v < st->lo ? v : st->lo;
        st->hi = v > st->hi ? v : st->hi;
        st->sum += v;
        st->measured++;
    }
    return CLI_OK;
}

/* Other ranks: the piece into the share buffer, masked cells as NaN. */
static void map_keep(map_run *m, const ft_grid *D, const ft_grid *r2, size_t row0)
{
    size_t n = D->nx * D->ny, off = (row0 - m->share_row0) * m->nox, whole = m->nox * m->share_rows;
    for (size_t i = 0; i < n; i++) {
        int ok = D->mask == NULL || D->mask[i];
        m->share[off + i] = ok ? D->z[i] : NAN;
        m->share[whole + off + i] = ok ? r2->z[i] : NAN;
    }
}

/* Lattice rows [a, b) from one stripe; *any set when the stripe holds a valid cell. */
static int map_stripe(map_run *m, ft_grid_reader *r, size_t a, size_t b, int *any)
{
    const tile_map_job *j = m->job;
    size_t lo = a * j->step, hi = b == m->noy ? m->ny : (b - 1) * j->step + j->window;
    ft_grid *s = NULL, *D = NULL, *r2 = NULL, *N = NULL;
    if (ft_io_grid_reader_read(r, 0, lo, m->nx, hi - lo, &s) != FT_OK)
        return cli_fail(m->cmd);
    int rc = CLI_OK;
    if (ft_grid_count_valid(s) > 0) {
        *any = 1;
        if (ft_surface_dim_map_noise(s, j->window, j->step, j->method, &j->opts, &D, &r2, &N) != FT_OK)
            rc = cli_fail(m->cmd);
    } else { /* the whole run measures no window here: nodata */
        D = ft_grid_create(m->nox, b - a);
        r2 = ft_grid_create(m->nox, b - a);
        if (D == NULL || r2 == NULL || ft_grid_ensure_mask(D) != FT_OK || ft_grid_ensure_mask(r2) != FT_OK)
            rc = cli_fail(m->cmd);
        for (size_t i = 0; rc == CLI_OK && i < m->nox * (b - a); i++)
            D->mask[i] = r2->mask[i] = 0;
    }
    ft_grid_free(s);
    if (rc == CLI_OK && (D->nx != m->nox || D->ny < b - a)) {
        cli_error(m->cmd, "internal: a stripe gave %zu x %zu windows, expected %zu x %zu", D->nx, D->ny, m->nox, b - a);
        rc = CLI_FAIL;
    }
    if (rc == CLI_OK) {
        D->ny = r2->ny = b - a; /* the last stripe may hold windows past the lattice: none (checked above) */
        for (size_t i = 0; N != NULL && i < m->nox * (b - a); i++) /* N is nodata where D is */
            m->nugget += N->mask[i] && N->z[i] > 0.5f;
        if (cli_rank() == 0)
            rc = map_put(m, D, r2, a);
        else
            map_keep(m, D, r2, a);
    }
    ft_grid_free(D);
    ft_grid_free(r2);
    ft_grid_free(N);
    return rc;
}

/* Rank 0: the other ranks' shares, in rank (= row) order, to the file. */
static int map_gather(map_run *m)
{
    int rc = CLI_OK;
    for (int k = 1; k < cli_nranks(); k++) {
        size_t a = m->noy * (size_t)k / (size_t)cli_nranks(), b = m->noy * (size_t)(k + 1) / (size_t)cli_nranks();
        if (b == a)
            continue;
        ft_grid *D = ft_grid_create(m->nox, b - a), *r2 = ft_grid_create(m->nox, b - a);
        if (D == NULL || r2 == NULL) {
            ft_grid_free(D);
            ft_grid_free(r2);
            return cli_fail(m->cmd);
        }
        size_t n = m->nox * (b - a) * sizeof(float);
        if (cli_ranks_recv(k, D->z, n) != 0 || cli_ranks_recv(k, r2->z, n) != 0) {
            cli_error(m->cmd, "cannot receive rows %zu-%zu of the map from rank %d", a, b - 1, k);
            rc = CLI_FAIL;
        }
        if (rc == CLI_OK)
            rc = map_put(m, D, r2, a);
        ft_grid_free(D);
        ft_grid_free(r2);
        if (rc != CLI_OK)
            break;
    }
    return rc;
}

/* The lattice's georeferencing: the input's scaled by the step and shifted by (W - S) / 2 cells, as
 * ft_surface_dim_map places its output (src/surface/dim_map.c). */
static void lattice_header(const ft_grid *h, size_t w, size_t s, size_t nox, size_t noy, ft_grid *out)
{
    memset(out, 0, sizeof *out);
    out->nx = nox;
    out->ny = noy;
    out->crs_wkt = h->crs_wkt;
    double a = 0.5 * ((double)w - (double)s);
    out->gt[0] = h->gt[0] + a * h->gt[1] + a * h->gt[2];
    out->gt[3] = h->gt[3] + a * h->gt[4] + a * h->gt[5];
    out->gt[1] = (double)s * h->gt[1];
    out->gt[2] = (double)s * h->gt[2];
    out->gt[4] = (double)s * h->gt[4];
    out->gt[5] = (double)s * h->gt[5];
}

/* This rank's stripes; CLI_OK or CLI_FAIL (printed). */
static int map_rank(map_run *m, ft_grid_reader *r, const char *out, int *any)
{
    const tile_map_job *j = m->job;
    size_t a, b;
    tile_rank_share(m->noy, &a, &b);
    m->share_row0 = a;
    m->share_rows = b - a;
    if (cli_rank() == 0) {
        ft_grid h;
        lattice_header(ft_io_grid_reader_header(r), j->window, j->step, m->nox, m->noy, &h);
        ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
        tile_threads th;
        wo.driver = j->driver;
        tile_write_threads(&wo, &th);
        if (ft_io_grid_writer_create(out, &h, 2, &wo, &m->w) != FT_OK)
            return cli_fail(m->cmd);
    } else if (b > a && (m->share = malloc(2 * m->nox * (b - a) * sizeof *m->share)) == NULL) {
        cli_error(m->cmd, "out of memory for %zu rows of the map", b - a);
        return CLI_FAIL;
    }
    /* the stripe computes `core` rows of the DEM and reads W - S rows more (its halo) */
    size_t rows = stripe_rows(m->nx, MAP_BYTES_PER_CELL, j->window);
    size_t halo = j->window > j->step ? j->window - j->step : 0;
    size_t core = j->tile_rows > 0 ? (size_t)j->tile_rows : rows - halo;
    size_t k = core / j->step > 0 ? core / j->step : 1; /* lattice rows per stripe */
    int rc = CLI_OK;
    for (size_t s = a; s < b && rc == CLI_OK; s += k)
        rc = map_stripe(m, r, s, s + k < b ? s + k : b, any);
    return rc;
}

int tile_dim_map(const cli_command *cmd, const char *in, const char *out, const tile_map_job *job,
                 tile_map_stats *st)
{
    map_run m = {.cmd = cmd, .job = job, .st = st};
    *st = (tile_map_stats){0, 0, 0, INFINITY, -INFINITY, 0.0, 0};
    ft_grid_reader *r = NULL;
    ft_crs_info crs;
    int any = 0, rc = open_band(cmd, in, job->band, &r, &crs);
    if (rc == CLI_CONTINUE) {
        const ft_grid *h = ft_io_grid_reader_header(r);
        m.nx = h->nx;
        m.ny = h->ny;
        if (job->window > h->nx || job->window > h->ny) {
            cli_error(cmd, "dim map: window %zu cells is larger than the %zux%zu grid", job->window, h->nx, h->ny);
            rc = CLI_FAIL;
        } else {
            m.nox = st->nox = (h->nx - job->window) / job->step + 1;
            m.noy = st->noy = (h->ny - job->window) / job->step + 1;
            rc = map_rank(&m, r, out, &any);
        }
    }
    int ok = cli_ranks_all_ok(rc == CLI_OK || rc == CLI_CONTINUE);
    uint64_t anywhere = ok ? cli_ranks_sum((uint64_t)any) : 0;
    if (ok && anywhere == 0) {
        cli_error(cmd, "dim map: the %zux%zu grid has no valid cell (all nodata)", m.nx, m.ny);
        ok = 0;
    }
    uint64_t nugget = ok ? cli_ranks_sum(m.nugget) : 0; /* every rank's windows with noise removed */
    st->nugget = (size_t)nugget;
    rc = ok ? CLI_OK : CLI_FAIL;
    if (ok && cli_rank() == 0) {
        rc = map_gather(&m);
        rc = rc == CLI_OK && ft_io_grid_writer_commit(m.w) != FT_OK ? cli_fail(cmd) : rc;
        m.w = rc == CLI_OK ? NULL : m.w;
    } else if (ok && m.share_rows > 0) {
        size_t n = m.nox * m.share_rows * sizeof(float);
        if (cli_ranks_send(0, m.share, n) != 0 || cli_ranks_send(0, m.share + m.nox * m.share_rows, n) != 0) {
            cli_error(cmd, "cannot send the map's rows to rank 0");
            rc = CLI_FAIL;
        }
    }
    ft_io_grid_writer_abort(m.w);
    free(m.share);
    ft_io_grid_reader_close(r);
    return rc;
}

/* ---- dim surface ---- */

/* Bytes per input cell of a stripe: the float cells and mask read, the sanitized cells and weights. */
/* (the stripe holds k rows, near <= k rows below them, and the k partner rows of one longer lag at a time) */
#define SURFACE_BYTES_PER_CELL 13.0

/* Counts the valid cells of rows [first, first + rows) of g. */
static uint64_t count_rows(const ft_grid *g, size_t first, size_t rows)
{
    ft_grid v = *g;
    v.z += first * g->nx;
    v.mask = g->mask ? g->mask + first * g->nx : NULL;
    v.ny = rows;
    return ft_grid_count_valid(&v);
}

/* The rows the lag sums of stripe [a, b) ask for (ft_rows_fn); the valid cells of [a, b) counted once, from
 * the first window (which starts at a). */
typedef struct {
    ft_grid_reader *r;
    size_t a, b;
    uint64_t *valid;
    int counted;
} surface_reads;

static int surface_read(void *arg, size_t row0, size_t nrows, ft_grid **out)
{
    surface_reads *sr = arg;
    int rc = ft_io_grid_reader_read(sr->r, 0, row0, ft_io_grid_reader_header(sr->r)->nx, nrows, out);
    if (rc == FT_OK && !sr->counted && row0 == sr->a) {
        *sr->valid += count_rows(*out, 0, sr->b - sr->a < nrows ? sr->b - sr->a : nrows);
        sr->counted = 1;
    }
    return rc;
}

/* Rows [a, b) of this rank's share into sums (rank 0: added at once); the lags up to near from the stripe
 * and near rows below it, each longer lag from the stripe's partner rows (ft_surface_lag_stripes_rows_read). */
static int surface_rows(const cli_command *cmd, ft_grid_reader *r, ft_lag_stripes *ls, size_t a, size_t b,
                        size_t near, double *sums, uint64_t *valid)
{
    surface_reads sr = {r, a, b, valid, 0};
    int rc = ft_surface_lag_stripes_rows_read(ls, surface_read, &sr, a, b, near, sums) == FT_OK ? CLI_OK
                                                                                                 : cli_fail(cmd);
    if (rc == CLI_OK && cli_rank() == 0 && ft_surface_lag_stripes_add(ls, a, b, sums) != FT_OK)
        rc = cli_fail(cmd);
    return rc;
}

/* The running totals through the ranks in order: each receives them from the previous rank, adds its
 * share's rows and passes them on; rank 0 gets them back from the last. */
static int surface_chain(const cli_command *cmd, ft_lag_stripes *ls, size_t a, size_t b, const double *share)
{
    int me = cli_rank(), p = cli_nranks();
    size_t ns = ft_surface_lag_stripes_nsums(ls);
    double *state = malloc((ns + 1) * sizeof *state);
    if (state == NULL)
        return cli_fail(cmd);
    int rc = CLI_OK;
    if (me > 0) {
        rc = cli_ranks_recv(me - 1, state, (ns + 1) * sizeof *state) == 0 ? CLI_OK : CLI_FAIL;
        if (rc == CLI_OK && ft_surface_lag_stripes_resume(ls, state, (size_t)state[ns]) != FT_OK)
            rc = cli_fail(cmd);
        if (rc == CLI_OK && b > a && ft_surface_lag_stripes_add(ls, a, b, share) != FT_OK)
            rc = cli_fail(cmd);
    }
    state[ns] = (double)ft_surface_lag_stripes_state(ls, state);
    if (cli_ranks_send((me + 1) % p, state, (ns + 1) * sizeof *state) != 0)
        rc = CLI_FAIL;
    if (me == 0 && cli_ranks_recv(p - 1, state, (ns + 1) * sizeof *state) == 0)
        rc = ft_surface_lag_stripes_resume(ls, state, (size_t)state[ns]) == FT_OK ? rc : cli_fail(cmd);
    free(state);
    return rc;
}

int tile_dim_surface(const cli_command *cmd, const char *in, int band, ft_surface_method m,
                     const ft_surface_dim_opts *o, long tile_rows, ft_dim_result **out, size_t *nx, size_t *ny,
                     uint64_t *valid, ft_crs_info *crs)
{
    *out = NULL;
    *valid = 0;
    ft_grid_reader *r = NULL;
    ft_lag_stripes *ls = NULL;
    double *sums = NULL;
    size_t a = 0, b = 0;
    int rc = open_band(cmd, in, band, &r, crs);
    if (rc == CLI_CONTINUE) {
        const ft_grid *h = ft_io_grid_reader_header(r);
        *nx = h->nx;
        *ny = h->ny;
        rc = ft_surface_lag_stripes_create(h, m, o, &ls) == FT_OK ? CLI_OK : cli_fail(cmd);
    }
    if (rc == CLI_OK) {
        tile_rank_share(*ny, &a, &b);
        size_t halo = ft_surface_lag_stripes_halo(ls), ns = ft_surface_lag_stripes_nsums(ls);
        /* a stripe of k rows holds k + near rows sanitized and k partner rows of a longer lag: 3k rows at most */
        size_t rows = stripe_rows(*nx, SURFACE_BYTES_PER_CELL, 3);
        size_t k = tile_rows > 0 ? (size_t)tile_rows : rows / 3; /* rows computed per stripe */
        size_t near = k < halo ? k : halo;
        /* rank 0 adds each stripe at once; the others keep their share's counters until the totals come */
        size_t held = cli_rank() == 0 ? (k < b - a ? k : b - a) : b - a;
        if (b > a && (sums = malloc((held ? held : 1) * ns * sizeof *sums)) == NULL)
            rc = cli_fail(cmd);
        for (size_t s = a; s < b && rc == CLI_OK; s += k) {
            size_t e = s + k < b ? s + k : b;
            rc = surface_rows(cmd, r, ls, s, e, near, cli_rank() == 0 ? sums : sums + (s - a) * ns, valid);
        }
    }
    int ok = cli_ranks_all_ok(rc == CLI_OK);
    *valid = ok ? cli_ranks_sum(*valid) : 0;
    rc = ok ? CLI_OK : CLI_FAIL;
    if (ok && cli_nranks() > 1)
        rc = surface_chain(cmd, ls, a, b, sums);
    if (cli_nranks() > 1 && !cli_ranks_all_ok(rc == CLI_OK))
        rc = CLI_FAIL;
    if (rc == CLI_OK && cli_rank() == 0 && ft_surface_lag_stripes_fit(ls, out) != FT_OK)
        rc = cli_fail(cmd);
    free(sums);
    ft_surface_lag_stripes_free(ls);
    ft_io_grid_reader_close(r);
    return rc;
}
