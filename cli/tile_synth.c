/* fracterra — cli/tile_synth.c: `mpiexec -n N fracterra synth --method fft` with FFTW's MPI transforms
 * (docs/tiling.md). The padded py x px synthesis grid is cut in FFTW's slabs of spectrum rows
 * (fftwf_mpi_local_size_2d: rank r holds rows [s0, s0 + n0)); each rank draws its rows
 * (ft_synth_fft_spectrum_rows: row ky from its own stream, so the spectrum is the one-process run's, bit for
 * bit), the ranks run the distributed c2r together (two global transposes inside FFTW), each crops its slab and
 * adds the plane (ft_synth_fft_surface_rows), the rows' sums are gathered in row order for the rescale to sigma
 * (ft_synth_rescale_rows). OUT.tif: rank 0 writes its rows and then the other ranks' into one tiled GeoTIFF.
 * OUT.vrt: the output rows are evened out between the ranks (balance_rows), every rank writes its share as its
 * own GeoTIFF part, OUT's stem + ".part-NNNN.tif" (in parallel, each with its share of the cores), and once
 * every part is whole rank 0 writes the VRT mosaic over them (ft_io_write_mosaic_vrt). The cells differ from
 * `synth` in one process by the transform's rounding only.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "tile_cli.h"

#include "cli_ranks.h"

#ifdef FT_HAVE_FFTW_MPI
#include <fftw3-mpi.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct {
    const cli_command *cmd;
    size_t nx, ny, px, py;
    ptrdiff_t n0, s0;      /* this rank's slab of grid rows */
    size_t nout;           /* of which output rows (below ny) */
    size_t alloc;          /* complex values in buf */
    fftwf_complex *buf;
    long long *spans;      /* every rank's (first output row, output rows), in rank order */
} synth_slab;

/* The slab's spectrum, the distributed inverse transform, crop and plane; the rows' sums into sums. */
static int slab_surface(synth_slab *s, const ft_synth_opts *so, double *sums)
{
    size_t ncx = s->px / 2 + 1;
    ptrdiff_t alloc = fftwf_mpi_local_size_2d((ptrdiff_t)s->py, (ptrdiff_t)ncx, MPI_COMM_WORLD, &s->n0, &s->s0);
    s->alloc = alloc > 0 ? (size_t)alloc : 1;
    s->buf = fftwf_alloc_complex(s->alloc);
    int ok = s->buf != NULL;
    if (!ok)
        cli_error(s->cmd, "out of memory for %td rows of the %zu x %zu spectrum", s->n0, s->py, ncx);
    if (!cli_ranks_all_ok(ok))
        return CLI_FAIL;
    /* collective; FFTW_ESTIMATE plans without touching the array */
    fftwf_plan p = fftwf_mpi_plan_dft_c2r_2d((ptrdiff_t)s->py, (ptrdiff_t)s->px, s->buf, (float *)s->buf,
                                             MPI_COMM_WORLD, FFTW_ESTIMATE);
    ok = p != NULL && ft_synth_fft_spectrum_rows(s->nx, s->ny, so, (size_t)s->s0, (size_t)s->n0,
                                                   (float *)s->buf) == FT_OK;
    if (p == NULL)
        cli_error(s->cmd, "FFTW could not plan the distributed %zu x %zu transform", s->py, s->px);
    else if (!ok)
        cli_fail(s->cmd);
    if (!cli_ranks_all_ok(ok)) {
        if (p)
            fftwf_destroy_plan(p);
        return CLI_FAIL;
    }
    fftwf_execute(p);
    fftwf_destroy_plan(p);
    size_t s0 = (size_t)s->s0;
    s->nout = s0 >= s->ny ? 0 : (s->ny - s0 < (size_t)s->n0 ? s->ny - s0 : (size_t)s->n0);
    ok = ft_synth_fft_surface_rows(s->nx, s->ny, so, s0, (size_t)s->n0, (float *)s->buf,
                                   s0 < s->ny ? sums + 2 * s0 : NULL) == FT_OK;
    if (!ok)
        cli_fail(s->cmd);
    return cli_ranks_all_ok(ok) ? CLI_OK : CLI_FAIL;
}

/* Every rank's rows' sums on every rank, in row order (the slabs are consecutive in rank order). */
static int gather_sums(synth_slab *s, double *sums)
{
    int nr = cli_nranks();
    int *count = malloc((size_t)nr * sizeof *count), *displ = malloc((size_t)nr * sizeof *displ);
    long long mine[2] = {(long long)(s->nout ? (size_t)s->s0 : 0), (long long)s->nout}, *all = NULL;
    all = s->spans = malloc((size_t)nr * sizeof mine);
    int rc = CLI_FAIL;
    if (cli_ranks_all_ok(count && displ && all) && MPI_Allgather(mine, 2, MPI_LONG_LONG, all, 2, MPI_LONG_LONG, MPI_COMM_WORLD) ==
                                     MPI_SUCCESS) {
        for (int k = 0; k < nr; k++) {
            displ[k] = (int)(2 * all[2 * k]);
            count[k] = (int)(2 * all[2 * k + 1]);
        }
        /* in place: each rank's own sums already sit at their place in sums */
        rc = MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, sums, count, displ, MPI_DOUBLE, MPI_COMM_WORLD) ==
                     MPI_SUCCESS
                 ? CLI_OK
                 : CLI_FAIL;
    }
    if (rc != CLI_OK)
        cli_error(s->cmd, "cannot gather the rows' sums across ranks");
    free(count);
    free(displ);
    return rc;
}

/* Sends n bytes to rank `to` as cli_ranks_send does (1 GiB messages, tag 0), but waits for each to be taken
 * asleep (MPI_Test every 0.2 ms) rather than in Open MPI's busy poll: the core is left to rank 0's GeoTIFF
 * writer and its compression threads, which this rank would otherwise slow down while waiting its turn. */
static int send_idle(int to, const void *buf, size_t n)
{
    const char *p = buf;
    size_t off = 0, chunk = (size_t)1 << 30;
    do {
        int len = (int)(n - off < chunk ? n - off : chunk), done = 0;
        MPI_Request rq;
        if (MPI_Isend(p + off, len, MPI_BYTE, to, 0, MPI_COMM_WORLD, &rq) != MPI_SUCCESS)
            return -1;
        while (!done) {
            if (MPI_Test(&rq, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS)
                return -1;
            struct timespec ts = {0, 200000};
            if (!done)
                nanosleep(&ts, NULL);
        }
        off += (size_t)len;
    } while (off < n);
    return 0;
}

/* Rank 0: its rows, then each other rank's (row0, rows) and cells, written in rank order into w. The cells
 * come into rank 0's own slab (FFTW's first block is the largest) or, should one not fit, a buffer of theirs.
 * After a failed write the other ranks' rows are still taken (and dropped), so that no rank waits forever. */
static int write_slabs(synth_slab *s, ft_grid_writer *w)
{
    ft_grid piece = {.nx = s->nx, .ny = s->nout, .z = (float *)s->buf, .gt = {0, 1, 0, 0, 0, 1}};
    int rc = CLI_OK;
    if (s->nout > 0 && ft_io_grid_writer_write(w, 1, &piece, 0, (size_t)s->s0) != FT_OK)
        rc = cli_fail(s->cmd);
    for (int k = 1; k < cli_nranks(); k++) {
        uint64_t hdr[2];
        if (cli_ranks_recv(k, hdr, sizeof hdr) != 0) {
            cli_error(s->cmd, "cannot receive the surface's rows from rank %d", k);
            return CLI_FAIL;
        }
        size_t n = (size_t)hdr[1] * s->nx;
        float *own = n <= 2 * s->alloc ? (float *)s->buf : NULL, *cells = own ? own : malloc(n * sizeof *cells);
        if (cells == NULL) {
            cli_error(s->cmd, "out of memory for rank %d's rows", k);
            return CLI_FAIL;
        }
        if (n > 0 && cli_ranks_recv(k, cells, n * sizeof(float)) != 0) {
            cli_error(s->cmd, "cannot receive the surface's rows from rank %d", k);
            rc = CLI_FAIL;
        }
        piece.ny = (size_t)hdr[1];
        piece.z = cells;
        if (rc == CLI_OK && n > 0 && ft_io_grid_writer_write(w, 1, &piece, 0, (size_t)hdr[0]) != FT_OK)
            rc = cli_fail(s->cmd);
        if (cells != own)
            free(cells);
    }
    return rc;
}

/* Part k of the mosaic out: out without ".vrt" + ".part-NNNN.tif" (malloc'd); its name relative to the .vrt's
 * folder starts at *rel. */
static char *part_path(const char *out, int k, const char **rel)
{
    size_t stem = strlen(out) - 4;
    char *p = malloc(stem + 32);
    if (p == NULL)
        return NULL;
    snprintf(p, stem + 32, "%.*s.part-%04d.tif", (int)stem, out, k);
    const char *slash = strrchr(p, '/');
    *rel = slash ? slash + 1 : p;
    return p;
}

/* OUT.vrt: the output rows moved so that rank r writes rows [ny r / P, ny (r + 1) / P). FFTW's slabs are of the
 * padded grid, whose padding rows (not written) fall on the last ranks, so the slabs' output rows are uneven
 * (16384², 2 ranks: 10,240 and 6,144) and the parts' compression would be too. Each rank sends the rows it
 * holds of another's share and receives the rows of its own share that another holds, one MPI row type of
 * nx floats (counts stay ints); then the slab is freed. *out: the share's rows (malloc'd). Collective. */
static int balance_rows(synth_slab *s, float **out)
{
    int nr = cli_nranks(), me = cli_rank();
    size_t a = s->ny * (size_t)me / (size_t)nr, b = s->ny * (size_t)(me + 1) / (size_t)nr;
    size_t h0 = s->nout ? (size_t)s->s0 : 0, h1 = h0 + s->nout;
    float *mine = b > a ? malloc((b - a) * s->nx * sizeof *mine) : NULL;
    MPI_Request *rq = malloc(2 * (size_t)nr * sizeof *rq);
    MPI_Datatype row;
    int ok = (b == a || mine != NULL) && rq != NULL, nrq = 0;
    if (!cli_ranks_all_ok(ok)) {
        cli_error(s->cmd, "out of memory for %zu rows of the surface", b - a);
        free(mine);
        free(rq);
        return CLI_FAIL;
    }
    MPI_Type_contiguous((int)s->nx, MPI_FLOAT, &row);
    MPI_Type_commit(&row);
    const float *held = (const float *)s->buf;
    for (int q = 0; q < nr && ok; q++) {
        size_t qa = s->ny * (size_t)q / (size_t)nr, qb = s->ny * (size_t)(q + 1) / (size_t)nr;
        size_t g0 = (size_t)s->spans[2 * q], g1 = g0 + (size_t)s->spans[2 * q + 1];
        size_t lo = h0 > qa ? h0 : qa, hi = h1 < qb ? h1 : qb; /* rows I hold of q's share */
        if (q == me && hi > lo)
            memcpy(mine + (lo - a) * s->nx, held + (lo - h0) * s->nx, (hi - lo) * s->nx * sizeof *mine);
        else if (hi > lo)
            ok = MPI_Isend(held + (lo - h0) * s->nx, (int)(hi - lo), row, q, 1, MPI_COMM_WORLD, &rq[nrq++]) ==
                 MPI_SUCCESS;
        lo = g0 > a ? g0 : a;
        hi = g1 < b ? g1 : b; /* rows q holds of my share */
        if (q != me && hi > lo && ok)
            ok = MPI_Irecv(mine + (lo - a) * s->nx, (int)(hi - lo), row, q, 1, MPI_COMM_WORLD, &rq[nrq++]) ==
                 MPI_SUCCESS;
    }
    ok = ok && MPI_Waitall(nrq, rq, MPI_STATUSES_IGNORE) == MPI_SUCCESS;
    MPI_Type_free(&row);
    free(rq);
    if (!ok)
        cli_error(s->cmd, "cannot exchange the surface's rows between ranks");
    if (!cli_ranks_all_ok(ok)) {
        free(mine);
        return CLI_FAIL;
    }
    fftwf_free(s->buf);
    s->buf = NULL;
    s->s0 = (ptrdiff_t)a;
    s->nout = b - a;
    for (int q = 0; q < nr; q++) {
        s->spans[2 * q] = (long long)(s->ny * (size_t)q / (size_t)nr);
        s->spans[2 * q + 1] = (long long)(s->ny * (size_t)(q + 1) / (size_t)nr) - s->spans[2 * q];
    }
    *out = mine;
    return CLI_OK;
}

/* OUT.vrt: this rank's share of the rows into a temporary beside its part; once every rank's is whole, each renames its
 * own onto the part's name; once every part is there, rank 0 writes the VRT. On any failure every rank
 * removes what it wrote, so neither parts nor the mosaic are left (earlier files of the same names stay as they
 * were unless the renames had begun). Collective. */
static int write_parts(synth_slab *s, const float *rows, const ft_grid *hdr, const char *out)
{
    const char *rel = NULL;
    char *part = part_path(out, cli_rank(), &rel), *tmp = NULL;
    int ok = part != NULL;
    if (ok && s->nout > 0) {
        ft_grid g = {.nx = s->nx, .ny = s->nout, .z = (float *)rows, .crs_wkt = hdr->crs_wkt};
        memcpy(g.gt, hdr->gt, sizeof g.gt);
        g.gt[3] = hdr->gt[3] + (double)s->s0 * hdr->gt[5];
        ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
        tile_threads th;
        wo.driver = "GTiff";
        tile_write_threads(&wo, &th);
        ok = (tmp = ft_io_atomic_tmp(part)) != NULL && ft_io_write_grid(tmp, &g, &wo) == FT_OK;
    }
    if (!ok && part == NULL)
        cli_error(s->cmd, "out of memory");
    else if (!ok)
        cli_fail(s->cmd);
    int committed = 0;
    if (cli_ranks_all_ok(ok) && tmp != NULL) {
        ok = ft_io_atomic_commit(tmp, part) == FT_OK;
        committed = ok;
        if (!ok)
            cli_fail(s->cmd);
    } else {
        ok = tmp == NULL && ok;
    }
    ft_io_atomic_discard(committed ? NULL : tmp);
    ok = cli_ranks_all_ok(ok);
    if (ok && cli_rank() == 0) {
        int nr = cli_nranks(), n = 0;
        char **paths = calloc((size_t)nr, sizeof *paths);
        const char **names = calloc((size_t)nr, sizeof *names);
        ok = paths != NULL && names != NULL;
        for (int k = 0; ok && k < nr; k++)
            if (s->spans[2 * k + 1] > 0)
                ok = (paths[n] = part_path(out, k, &names[n])) != NULL && (n++, 1);
        if (!ok)
            cli_error(s->cmd, "out of memory");
        else if (ft_io_write_mosaic_vrt(out, hdr, (size_t)n, names) != FT_OK) {
            cli_fail(s->cmd);
            ok = 0;
        }
        for (int k = 0; paths != NULL && k < nr; k++)
            free(paths[k]);
        free(paths);
        free(names);
    }
    ok = cli_ranks_all_ok(ok);
    if (!ok && committed)
        remove(part);
    free(tmp);
    free(part);
    return ok ? CLI_OK : CLI_FAIL;
}

int tile_synth(const cli_command *cmd, size_t nx, size_t ny, const ft_synth_opts *so, const char *wkt,
               const char *out, ft_grid_stats *st)
{
    synth_slab s = {.cmd = cmd, .nx = nx, .ny = ny};
    if (ft_synth_fft_grid_size(nx, ny, so, &s.px, &s.py) != FT_OK)
        return cli_fail(cmd);
    int mosaic = tile_is_mosaic(out);
    ft_grid_writer *w = NULL;
    ft_grid hdr = {.nx = nx, .ny = ny, .crs_wkt = (char *)wkt,
                   .gt = {so->origin_x, so->cell, 0.0, so->origin_y, 0.0, -so->cell}};
    ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
    tile_threads th;
    tile_write_threads(&wo, &th);
    int ok = mosaic || cli_rank() != 0 || ft_io_grid_writer_create(out, &hdr, 1, &wo, &w) == FT_OK;
    if (ok && mosaic) { /* every rank writes its part beside the .vrt */
        const char *rel = NULL;
        char *part = part_path(out, cli_rank(), &rel);
        ok = part != NULL && ft_io_check_writable(part) == FT_OK;
        free(part);
    }
    if (!ok)
        cli_fail(cmd);
    double *sums = malloc(2 * ny * sizeof *sums);
    if (ok && sums == NULL) {
        cli_error(cmd, "out of memory for the sums of %zu rows", ny);
        ok = 0;
    }
    fftwf_mpi_init();
    int rc = cli_ranks_all_ok(ok) ? slab_surface(&s, so, sums) : CLI_FAIL;
    if (rc == CLI_OK)
        rc = gather_sums(&s, sums);
    if (rc == CLI_OK && ft_synth_rescale_rows(nx, ny, so, sums, s.nout, (float *)s.buf) != FT_OK)
        rc = cli_fail(cmd);
    rc = cli_ranks_all_ok(rc == CLI_OK) ? CLI_OK : CLI_FAIL;
    if (rc == CLI_OK && mosaic) {
        float *rows = NULL;
        rc = balance_rows(&s, &rows);
        rc = rc == CLI_OK ? write_parts(&s, rows, &hdr, out) : rc;
        free(rows);
    } else if (rc == CLI_OK && cli_rank() == 0) {
        rc = write_slabs(&s, w);
        rc = rc == CLI_OK && ft_io_grid_writer_commit(w) != FT_OK ? cli_fail(cmd) : rc;
        w = rc == CLI_OK ? NULL : w;
    } else if (rc == CLI_OK) {
        uint64_t h[2] = {s.nout ? (uint64_t)s.s0 : 0, (uint64_t)s.nout};
        if (cli_ranks_send(0, h, sizeof h) != 0 ||
            (s.nout > 0 && send_idle(0, s.buf, s.nout * nx * sizeof(float)) != 0)) {
            cli_error(cmd, "cannot send the surface's rows to rank 0");
            rc = CLI_FAIL;
        }
    }
    ft_io_grid_writer_abort(w);
    fftwf_free(s.buf);
    free(s.spans);
    free(sums);
    fftwf_mpi_cleanup();
    /* OUT.tif: no collective after the write, a rank done sending leaves (rank 0's failure is the run's exit
     * status) */
    if (rc == CLI_OK && cli_rank() == 0 && st != NULL)
        rc = tile_output_stats(cmd, out, 1024, st);
    return rc;
}
#endif
