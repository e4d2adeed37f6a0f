/* fracterra — reconstruct_internal.h (private): what the reconstruction files of src/terrain/ share
 * (Arakawa & Krotkov §3, after Szeliski; docs/terrain-reconstruct.md).
 *
 *  - recon_binding.c: scattered points -> the nodes (cell centres) of the target grid;
 *  - recon_stencil.c: the discrete energy (data term + lambda [(1 - tension) thin plate + tension
 *    membrane], h = 1 node of the level) applied at a node, and 5-colour Gauss-Seidel sweeps;
 *  - recon_levels.c: the fractal method's multilevel prior (Szeliski's pyramid of energies, weights of D);
 *  - recon_multigrid.c: the level hierarchy (spacing 2^l), restriction and prolongation, and the T = 0
 *    solver (conjugate gradients preconditioned by a symmetric multigrid V-cycle);
 *  - recon_discrepancy.c: with soft data, the prior weight by Morozov's discrepancy principle;
 *  - recon_temperature.c: D from the data, Pentland's sigma0, T = k sigma0² (eq. 13), k;
 *  - recon_perturb.c: the fractal method (an exact posterior sample by perturbation-optimization);
 *  - recon_conditional.c: conditional simulation (fBm + smooth interpolation of the residuals);
 *  - recon_voids.c: DEM voids -> problems on the boxes around them;
 *  - reconstruct.c: options, dispatch, realizations (mean, sd), info, method names.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_RECONSTRUCT_INTERNAL_H
#define FRACTERRA_RECONSTRUCT_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fracterra/terrain.h"
#include "internal.h"

/** The T = 0 solver stops when the residual norm falls below this fraction of the initial one. */
#define FT_RECON_TOL 1e-6
#define FT_RECON_MAX_ITER 200
/** The coarsest level has at most this many nodes per side (solved by dense Cholesky). */
#define FT_RECON_COARSEST 12

/** Loops over fewer nodes than this run on one thread (a parallel region costs more than it saves, and
 *  on a busy machine waiting threads spin). */
#define FT_RECON_PARALLEL_MIN ((size_t)1 << 18)
static inline int ft_recon_threads(int nthreads, size_t nodes)
{
    return nodes >= FT_RECON_PARALLEL_MIN ? nthreads : 1;
}

/** Stream ids of the random numbers (mixed with the seed by ft_rng_fast_init). */
#define FT_RECON_STREAM_WHITE UINT64_C(0x7265637700000000)
#define FT_RECON_STREAM_PERTURB UINT64_C(0x7265637000000000)
/** The fractal sample's solve stops when its residual norm falls below this fraction of the initial one. */
#define FT_RECON_SAMPLE_TOL 1e-4

/** One level of the hierarchy: nodes at spacing 2^l fine nodes. */
typedef struct {
    size_t nx, ny;
    double tp, mem;   /**< coefficients of the thin-plate and membrane energies at this level */
    float *c;         /**< data weight per node (>= 0): fine data, or the lumped weights of coarse levels */
    uint8_t *fixed;   /**< 1: Dirichlet node (its value is not an unknown) */
    float *x, *b, *r; /**< coarse levels: correction, right-hand side, residual (NULL on level 0) */
    double *chol;     /**< coarsest level: Cholesky factor of its free-node matrix (NULL elsewhere) */
    size_t *chol_idx; /**< coarsest level: node index of each free unknown */
    size_t nchol;
} ft_recon_level;

/** A reconstruction problem on one grid: the data bound to its nodes and the level hierarchy. */
typedef struct {
    size_t nx, ny;
    float *d;          /**< datum per node: the value of fixed nodes, the weighted mean of soft data */
    ft_recon_level *lev; /**< lev[0] is the grid itself; lev[0].c and lev[0].fixed describe the data */
    int nlev;
    int nthreads;      /**< > 0 */
    double lambda;     /**< the prior weight of the hierarchy (set by ft_recon_hierarchy) */
    size_t ndata;      /**< soft data: the points bound to nodes (N of the discrepancy principle) */
    double scatter;    /**< soft data: sum over points of c_i (d_i - d_node)², the misfit that no surface
                            on these nodes can remove (several points on one node) */
    double prior_H;    /**< > 0: the multilevel prior of exponent H (recon_levels.c) joins level 0's energy
                            in every solve; 0: level 0's energy alone */
    ft_recon_level *pl; /**< the multilevel prior's levels 1 .. npl (tp, mem with their weights; x, b, r: work) */
    int npl;
} ft_recon_problem;

/** Progress over a whole job: fraction base + span * f (Core's scaled progress, src/internal.h). */
typedef ft_progress_range ft_recon_progress;
static inline int ft_recon_report(const ft_recon_progress *p, double f, const char *msg)
{
    return ft_progress_range_report(p, f, msg);
}

/* ---- recon_binding.c ---- */
/** Allocates a problem of nx x ny nodes (data arrays zeroed, no hierarchy yet). NULL if out of memory. */
ft_recon_problem *ft_recon_problem_create(size_t nx, size_t ny, int nthreads);
/** Frees the arrays one level owns (not the level itself; pointers left dangling: the caller resets them). */
void ft_recon_level_free_arrays(ft_recon_level *L);
void ft_recon_problem_free(ft_recon_problem *p);
/** Binds each point to its nearest node of target (cell centres; several points on one node: their
 *  confidence-weighted mean, confidences added). Fixed nodes when sigma == 0 and p has no weights,
 *  otherwise weights c = w² (w = 1/sigma or the point's own). Checks finiteness, >= 3 nodes with data
 *  not on a line. *outside receives the points outside the grid. */
int ft_recon_bind_points(const ft_points *p, const ft_grid *target, double sigma, int nthreads,
                         ft_recon_problem **out, size_t *outside);

/* ---- recon_stencil.c ---- */
/** (A x)_i at node (col, row) of level L and the diagonal a_ii (prior + data weight). */
double ft_recon_apply(const ft_recon_level *L, const float *x, size_t col, size_t row, double *diag);
/** One Gauss-Seidel sweep over the free nodes in 5 colours (0..4, or 4..0 if reverse), x_i += (b_i -
 *  (A x)_i) / a_ii (b NULL = 0). Nodes of one colour do not interact, so rows run in parallel with the
 *  same result. */
int ft_recon_sweep(const ft_recon_level *L, float *x, const float *b, int reverse, int nthreads);
/** r = b - A x on free nodes, 0 on fixed ones (b NULL = 0). Returns sum r² (rows reduced in order). */
double ft_recon_residual(const ft_recon_level *L, const float *x, const float *b, float *r, int nthreads);
/** Interior diagonal of the prior at a level (20 tp + 4 mem). */
double ft_recon_prior_diag(const ft_recon_level *L);

/* ---- recon_levels.c ---- */
/** The multilevel prior's levels 1 .. npl of p for exponent H (none if H <= 0): tp_l = 2^(-2Hl) tp_0,
 *  mem_l = 2^(-2Hl) FT_RECON_LEVEL_MEMBRANE^l mem_0 (so after level 0's coefficients are set). */
int ft_recon_prior_levels(ft_recon_problem *p, double H);
void ft_recon_prior_levels_free(ft_recon_problem *p);
/** The membrane's share of level l is FT_RECON_LEVEL_MEMBRANE^l times level 0's (thin plate: 1). */
#define FT_RECON_LEVEL_MEMBRANE 0.5
/** y += sum_(l >= 1) w_l R_l' A_l R_l x on every fine node (nothing when p has no prior levels). */
void ft_recon_prior_levels_add(const ft_recon_problem *p, const float *x, float *y);
/** c = r f (normalized full weighting, nodes 2I of f) and f += r' c; tmp holds ncx x nfy floats. */
void ft_recon_restrict_mean(const float *f, size_t nfx, size_t nfy, float *c, size_t ncx, size_t ncy, float *tmp,
                            int nthreads);
void ft_recon_restrict_mean_t(const float *c, size_t ncx, size_t ncy, float *f, size_t nfx, size_t nfy, float *tmp,
                              int nthreads);

/* ---- recon_multigrid.c ---- */
/** Builds (or rebuilds) the coarse levels of p (lumped data weights, fixed nodes by injection) and the
 *  coarsest Cholesky factor. */
int ft_recon_hierarchy(ft_recon_problem *p, double lambda, double tension);
/** fine (nx x ny) += bilinear prolongation of coarse (nx/2+1 x ny/2+1); fixed fine nodes untouched. */
void ft_recon_prolong_add(const ft_recon_level *fine, const ft_recon_level *coarse, const float *xc, float *xf,
                          int nthreads);
/** Solves A u = c d (the T = 0 minimum, eq. 9 with T_p = 0) for the free nodes of p, starting from the
 *  data's weighted mean; fixed nodes of u are set to d. */
int ft_recon_solve(const ft_recon_problem *p, float *u, const ft_recon_progress *prog, int *iterations);
/** The data's right-hand side of ft_recon_solve (c d on free nodes, 0 on fixed ones) and its initial
 *  guess (the data's weighted mean on free nodes, d on fixed ones). */
void ft_recon_data_rhs(const ft_recon_problem *p, float *rhs, float *u);
/** sum over the free nodes of (rhs - A u)² (NaN if out of memory). */
double ft_recon_residual_norm2(const ft_recon_problem *p, const float *rhs, const float *u);
/** Same with any right-hand side: A u = rhs on free nodes, u = fixed_values on fixed ones. */
int ft_recon_solve_rhs(const ft_recon_problem *p, const float *rhs, float *u, const ft_recon_progress *prog,
                       int *iterations);
/** Same from u until the squared residual norm (free nodes) is <= rr_stop (an absolute threshold). */
int ft_recon_solve_to(const ft_recon_problem *p, const float *rhs, float *u, double rr_stop,
                      const ft_recon_progress *prog, int *iterations);

/* ---- recon_discrepancy.c ---- */
/** The T = 0 solution for soft data (p->ndata > 0) with Morozov's discrepancy principle: given p's
 *  hierarchy at *lambda, solves A u = c d there; if that misses the data by more than their sigmas
 *  (chi² = sum_points c_i (u - d_i)² > N = p->ndata), lowers *lambda to the largest value found with
 *  (1 - FT_RECON_CHI2_TOL) N <= chi² <= N. u receives the solution at the returned *lambda (to
 *  FT_RECON_TOL), p's hierarchy is left at that lambda, *chi2 (may be NULL) receives its chi². */
int ft_recon_discrepancy(ft_recon_problem *p, double tension, double *lambda, float *u,
                         const ft_recon_progress *prog, double *chi2);
/** The acceptance band of ft_recon_discrepancy: chi² in [(1 - tol) N, N]. */
#define FT_RECON_CHI2_TOL 0.06

/* ---- recon_temperature.c ---- */
/** A fitted log-log line: log10 value = a + b log10 scale, scale in ground units, fitted over [lo, hi]. */
typedef struct {
    double D;      /**< the estimator's dimension */
    double a, b;
    double lo, hi;
} ft_recon_line;
/** Yokoya's (pentland = 0) points estimator with its default range, or Pentland's (1) over the data's
 *  shortest lags (0.5-1.5 x the mean spacing; the default range when those have too few pairs): sigma0's
 *  line. Errors name the estimate that failed. */
int ft_recon_fit_points(const ft_points *p, int pentland, ft_recon_line *out);
/** The same on a grid's valid cells (grid estimators, default range). */
int ft_recon_fit_grid(const ft_grid *g, int pentland, ft_recon_line *out);
/** The line's value at a scale (ground units). */
double ft_recon_line_at(const ft_recon_line *l, double scale);
/** Mean absolute elevation difference at one cell (ground size `cell`): Yokoya's fitted E|dz|
 *  extrapolated to one cell. The conditional method's amplitude when the data have too few close pairs. */
double ft_recon_amplitude(const ft_recon_line *yokoya, double cell);
/** The conditional method's small scales measured on the data nodes (has[i] != 0) of an nx x ny grid:
 *  *m1 = mean |dz| of the node pairs 1 apart along rows and columns, *nugget = the white share of the
 *  one-cell increment variance from the pairs 1 and 2 apart (0 if lag 2 has too few). Returns 0 (and
 *  leaves both) when lag 1 has fewer than FT_RECON_PAIR_MIN pairs. */
int ft_recon_small_scales(const float *z, const uint8_t *has, size_t nx, size_t ny, double H, double *m1,
                          double *nugget);
#define FT_RECON_PAIR_MIN 64
#define FT_RECON_NUGGET_MAX 0.9
/** The fractal method's temperature, T = k sigma0² (eq. 13 at the finest level; one k for every D). */
double ft_recon_temperature0(double k, double sigma0);
/** The prior's blend for dimension D (Szeliski's eq. 7 crossover, Arakawa & Krotkov): the tension tau
 *  whose spline-under-tension spectrum has the fBm's log-log slope -(8 - 2D) at a wavelength of
 *  FT_RECON_TENSION_WAVELENGTH cells, tau / (1 - tau) = M (1 - H) / H, M = 2 - 2 cos(2 pi / wavelength). */
double ft_recon_tension_for_dim(double D);
#define FT_RECON_TENSION_WAVELENGTH 4.0
/** The fractal method's multilevel prior: the finest level's blend for dimension D (opts->tension from D)
 *  and the factor g(D) of its temperature, T = g k sigma0², both calibrated on the structure function. */
double ft_recon_fractal_tension(double D);
double ft_recon_fractal_gain(double D);
/** The blend the fractal method's k was calibrated with (its tension when opts->tension is from D). */
#define FT_RECON_FRACTAL_TENSION 0.1

/* ---- recon_perturb.c ---- */
/** The fractal method: u = ustar + delta, delta an exact draw of N(0, lambda T0 A_ff^-1) (the prior at
 *  temperature T0 conditioned on delta = 0 at the fixed nodes) by perturbation and optimization.
 *  Deviates from streams of (seed, term type, row). ustar NULL: u* (the T = 0 solution of p's data) and
 *  delta in one solve, to FT_RECON_TOL of u*'s initial residual (one realization: two thirds of the
 *  iterations of solving them apart). */
int ft_recon_fractal(const ft_recon_problem *p, const float *ustar, double T0, uint64_t seed, float *u,
                     const ft_recon_progress *prog);

/* ---- recon_conditional.c ---- */
/** Conditional simulation: s = unconditional fBm (exponent H, seed) plus white noise carrying the share
 *  `nugget` of its one-cell increment variance, e = s - the T = 0 interpolation of s's values at the data
 *  nodes, u = ustar + kappa e with kappa such that u's mean |dz| at one cell along rows and columns is m1. */
int ft_recon_conditional(const ft_recon_problem *p, const float *ustar, double H, double m1, double nugget,
                         uint64_t seed, float *u, const ft_recon_progress *prog);

/* ---- reconstruct.c ---- */
/** What one problem needs to be reconstructed. */
typedef struct {
    ft_recon_method method;
    double H;           /**< 3 - D */
    double T0;          /**< fractal: the temperature */
    double amp;         /**< conditional: mean |dz| at one cell of the result */
    double nugget;      /**< conditional: white share of the one-cell increment variance */
    double tension;     /**< the prior's blend (opts->tension or ft_recon_tension_for_dim(D)) */
    int realizations;
    uint64_t seed;      /**< realization r uses seed + r */
} ft_recon_params;
/** Builds p's hierarchy, solves u* (soft data: at the discrepancy principle's lambda, at most `lambda`),
 *  then runs the realizations: mean (nx x ny, row stride `stride`,
 *  written at mean[y * stride + x]) and, if sd is not NULL, the per-cell standard deviation (Welford,
 *  double accumulators; 0 with one realization). */
int ft_recon_run(ft_recon_problem *p, double lambda, double tension, const ft_recon_params *par, float *mean,
                 float *sd, size_t stride, const ft_recon_progress *prog);

/** Checks the options (*o = opts or the defaults, threads resolved), clears info and the outputs. */
int ft_recon_begin(const ft_recon_opts *opts, ft_recon_opts *o, ft_recon_info *info, ft_grid **out,
                   ft_grid **sd_out);
/** D, T_0 and the fBm amplitude of the job from the options and the data (pts, or dem's valid cells);
 *  bound (may be NULL): pts bound to the target's nodes, whose fixed nodes give the conditional method's
 *  amplitude (ft_recon_amplitude_pairs); cell = the ground size of one cell. Fills info's dim,
 *  dim_estimated, sigma0, k, temperature. */
int ft_recon_job_params(const ft_recon_opts *o, const ft_points *pts, const ft_grid *dem,
                        const ft_recon_problem *bound, double cell, ft_recon_params *par, ft_recon_info *info);
/** The end of a job begun by ft_recon_begin: on success (rc == FT_OK) hands *inf to info (may be NULL);
 *  otherwise frees and clears the outputs. Returns rc. */
int ft_recon_end(int rc, const ft_recon_info *inf, ft_recon_info *info, ft_grid **out, ft_grid **sd_out);
/** New output grids shaped like `like` (size, geotransform, CRS, no mask); sd_out only if want_sd. */
int ft_recon_outputs(const ft_grid *like, int want_sd, ft_grid **out, ft_grid **sd_out);

#endif /* FRACTERRA_RECONSTRUCT_INTERNAL_H */
