/* fracterra — cli/cli_ranks.c: MPI for the tiled commands (cli_ranks.h), or one rank without it.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_ranks.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* The first number of OMP_NUM_THREADS ("4" or a nested "4,2"), or 0 when unset or not a count. */
static int omp_threads(void)
{
    const char *s = getenv("OMP_NUM_THREADS");
    char *end = NULL;
    long n = s ? strtol(s, &end, 10) : 0;
    return end != s && n >= 1 && n <= 65536 && (*end == '\0' || *end == ',') ? (int)n : 0;
}

/* The share of the node's cores of each of its `ranks` ranks (1 at least). */
static int core_share(int ranks)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    long n = cores > 0 && ranks > 0 ? cores / ranks : 1;
    return n >= 1 ? (int)(n < 65536 ? n : 65536) : 1;
}

#ifdef FT_HAVE_MPI
#include <mpi.h>

static int joined = 0, rank = 0, nranks = 1, node_ranks = 1;

/* Started by a launcher: Open MPI's mpiexec sets OMPI_COMM_WORLD_SIZE, PMIx and PMI launchers their own. */
static int launched(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") != NULL || getenv("PMIX_RANK") != NULL || getenv("PMI_RANK") != NULL;
}

int cli_ranks_init(int *argc, char ***argv)
{
    if (!launched())
        return 0;
    int provided = 0;
    /* OpenMP threads inside a rank; only the main thread calls MPI */
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
        return -1;
    joined = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    MPI_Comm node; /* the ranks sharing this rank's node (and its cores) */
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node) == MPI_SUCCESS) {
        MPI_Comm_size(node, &node_ranks);
        MPI_Comm_free(&node);
    }
    if (rank > 0 && freopen("/dev/null", "w", stdout) == NULL)
        return -1;
    return 0;
}

void cli_ranks_finalize(void)
{
    if (joined)
        MPI_Finalize();
    joined = 0;
}

int cli_ranks_joined(void)
{
    return joined;
}

int cli_rank(void)
{
    return rank;
}

int cli_nranks(void)
{
    return nranks;
}

int cli_ranks_threads(void)
{
    int n = omp_threads();
    return n > 0 ? n : core_share(node_ranks);
}

int cli_ranks_all_ok(int ok)
{
    if (!joined)
        return ok != 0;
    int mine = ok != 0, all = 0;
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all;
}

uint64_t cli_ranks_sum(uint64_t v)
{
    if (!joined)
        return v;
    uint64_t all = 0;
    MPI_Allreduce(&v, &all, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    return all;
}

#define CHUNK ((size_t)1 << 30)

int cli_ranks_send(int to, const void *buf, size_t n)
{
    const char *p = buf;
    size_t off = 0;
    do { /* MPI counts are ints: 1 GiB at a time */
        int len = (int)(n - off < CHUNK ? n - off : CHUNK);
        if (MPI_Send(p + off, len, MPI_BYTE, to, 0, MPI_COMM_WORLD) != MPI_SUCCESS)
            return -1;
        off += (size_t)len;
    } while (off < n);
    return 0;
}

int cli_ranks_recv(int from, void *buf, size_t n)
{
    char *p = buf;
    size_t off = 0;
    do { /* MPI counts are ints: 1 GiB at a time */
        int len = (int)(n - off < CHUNK ? n - off : CHUNK);
        if (MPI_Recv(p + off, len, MPI_BYTE, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE) != MPI_SUCCESS)
            return -1;
        off += (size_t)len;
    } while (off < n);
    return 0;
}

#else /* one process */

int cli_ranks_init(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

void cli_ranks_finalize(void)
{
}

int cli_ranks_joined(void)
{
    return 0;
}

int cli_rank(void)
{
    return 0;
}

int cli_nranks(void)
{
    return 1;
}

int cli_ranks_threads(void)
{
    int n = omp_threads();
    return n > 0 ? n : core_share(1);
}

int cli_ranks_all_ok(int ok)
{
    return ok != 0;
}

uint64_t cli_ranks_sum(uint64_t v)
{
    return v;
}

int cli_ranks_send(int to, const void *buf, size_t n)
{
    (void)to;
    (void)buf;
    (void)n;
    return -1;
}

int cli_ranks_recv(int from, void *buf, size_t n)
{
    (void)from;
    (void)buf;
    (void)n;
    return -1;
}

#endif
