/* fracterra — cli/cli_ranks.h: the processes of an MPI run (`mpiexec -n N fracterra dim map ...`), or the one
 * process of an ordinary run. Built with MPI (FT_HAVE_MPI) the tool joins MPI when a launcher started it;
 * otherwise, and without MPI, there is one rank and every exchange below is a no-op that is never called.
 * Ranks other than 0 print nothing on standard output. docs/tiling.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_RANKS_H
#define FRACTERRA_CLI_RANKS_H

#include <stddef.h>
#include <stdint.h>

/** Joins MPI when built with it and started by mpiexec (Open MPI, PMIx or PMI environment); sends the
 *  standard output of ranks > 0 to /dev/null. Returns 0, or -1 if MPI could not start. */
int cli_ranks_init(int *argc, char ***argv);
/** Leaves MPI (when joined). */
void cli_ranks_finalize(void);
/** 1 if this process joined MPI (started by mpiexec, even with one rank). */
int cli_ranks_joined(void);
/** This process's rank and the number of ranks (0 and 1 without MPI). */
int cli_rank(void);
int cli_nranks(void);
/** The threads this rank should run: the first number of OMP_NUM_THREADS when set, else the online cores
 *  divided by the ranks on this node (MPI_COMM_TYPE_SHARED; 1 rank without MPI), 1 at least. */
int cli_ranks_threads(void);
/** 1 if every rank passed ok != 0 (a collective: every rank must call it at the same point). */
int cli_ranks_all_ok(int ok);
/** The sum over ranks of v, on every rank (collective). */
uint64_t cli_ranks_sum(uint64_t v);
/** Point-to-point transfers of n bytes (blocking; any size). 0 on success. */
int cli_ranks_send(int to, const void *buf, size_t n);
int cli_ranks_recv(int from, void *buf, size_t n);

#endif /* FRACTERRA_CLI_RANKS_H */
