/* fracterra — harness.c: `make bench`. Runs every registered workload N times, each repetition in a
 * forked child (so wait4() gives that repetition's own peak RSS), prints the median wall time, the
 * throughput and the peak memory, and runs the peer command doing the same work when it is on PATH.
 *
 * Timing: in-process workloads time the library call alone inside the child (driver registration and
 * untimed preparation excluded); command workloads and peers are timed from fork to exit in the
 * harness, start-up included, and each program's start-up (`PROGRAM --version`) is reported beside.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <gdal.h>
#include <json-c/json.h>

#include "fracterra/fracterra.h"

/* The suites, in the order they run. A new bench/workloads_<domain>.c adds its suite here. */
static const ft_bench_suite *const bench_suites[] = {
    &ft_bench_suite_io,
    &ft_bench_suite_terrain,
    &ft_bench_suite_clarke,
    &ft_bench_suite_line_dim,
    &ft_bench_suite_line_enhance,
    &ft_bench_suite_surface,
    &ft_bench_suite_urban,
    &ft_bench_suite_points,
    &ft_bench_suite_reconstruct,
    &ft_bench_suite_fill,
    &ft_bench_suite_contour,
    &ft_bench_suite_tiles,
};
#define N_SUITES (sizeof bench_suites / sizeof bench_suites[0])

#define MAX_REPEAT 1000
#define MAX_FILES 64
#define MAX_PROGRAMS 16
#define ERR_LEN 512

/* ------------------------------------------------------------------------------------------------
 * Small helpers
 * --------------------------------------------------------------------------------------------- */

char *ft_bench_strdup(const char *s)
{
    if (s == NULL)
        return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d != NULL)
        memcpy(d, s, n);
    return d;
}

char *ft_bench_strf(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return NULL;
    char *s = malloc((size_t)n + 1);
    if (s == NULL)
        return NULL;
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return s;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(const double *v, size_t n)
{
    double tmp[MAX_REPEAT];
    if (n == 0)
        return 0.0;
    memcpy(tmp, v, n * sizeof *v);
    qsort(tmp, n, sizeof *tmp, cmp_double);
    return n % 2 ? tmp[n / 2] : 0.5 * (tmp[n / 2 - 1] + tmp[n / 2]);
}

/* Moves all n bytes through fd with read (writing = 0) or write (writing = 1), retrying short transfers
 * and EINTR; -1 on error or end of file. */
static int transfer_all(int fd, void *buf, size_t n, int writing)
{
    char *p = buf;
    while (n > 0) {
        ssize_t k = writing ? write(fd, p, n) : read(fd, p, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

static pid_t wait_child(pid_t pid, int *status, struct rusage *ru)
{
    pid_t r;
    do {
        r = wait4(pid, status, 0, ru);
    } while (r < 0 && errno == EINTR);
    return r;
}

/* ------------------------------------------------------------------------------------------------
 * Temporary folder and files removed at exit (also on SIGINT/SIGTERM/SIGHUP)
 * --------------------------------------------------------------------------------------------- */

static char bench_dir[PATH_MAX];
static char *reg_files[MAX_FILES];
static char *reg_aux[MAX_FILES];
static volatile sig_atomic_t reg_count;

/* Async-signal-safe: unlink and rmdir only. */
static void remove_registered(void)
{
    for (sig_atomic_t i = 0; i < reg_count; i++) {
        unlink(reg_files[i]);
        unlink(reg_aux[i]);
    }
    if (bench_dir[0] != '\0')
        rmdir(bench_dir);
}

static void on_signal(int sig)
{
    remove_registered();
    signal(sig, SIG_DFL);
    raise(sig);
}

static void install_signal_handlers(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

/* In every forked child: the harness's cleanup is not the child's business. */
static void child_default_signals(void)
{
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGHUP, SIG_DFL);
}

static void cleanup_at_exit(void)
{
    remove_registered();
    if (bench_dir[0] != '\0') {
        struct stat st;
        if (stat(bench_dir, &st) == 0)
            fprintf(stderr, "fracterra_bench: warning: %s is not empty and was left in place\n", bench_dir);
    }
}

const char *ft_bench_dir(void)
{
    if (bench_dir[0] != '\0')
        return bench_dir;
    const char *base = getenv("FT_BENCH_DIR");
    if (base == NULL || base[0] == '\0')
        base = "/tmp";
    char tmpl[PATH_MAX];
    int n = snprintf(tmpl, sizeof tmpl, "%s/fracterra-bench-XXXXXX", base);
    if (n < 0 || (size_t)n >= sizeof tmpl) {
        ft_error(FT_E_INVALID, "FT_BENCH_DIR is too long: %s", base);
        return NULL;
    }
    if (mkdtemp(tmpl) == NULL) {
        ft_error(FT_E_IO, "cannot create a temporary folder in %s: %s", base, strerror(errno));
        return NULL;
    }
    memcpy(bench_dir, tmpl, (size_t)n + 1);
    return bench_dir;
}

char *ft_bench_path(const char *name)
{
    const char *dir = ft_bench_dir();
    if (dir == NULL)
        return NULL;
    char *path = ft_bench_strf("%s/%s", dir, name);
    if (path == NULL) {
        ft_error(FT_E_NOMEM, "out of memory");
        return NULL;
    }
    for (sig_atomic_t i = 0; i < reg_count; i++)
        if (strcmp(reg_files[i], path) == 0)
            return path;
    if (reg_count >= MAX_FILES) {
        free(path);
        ft_error(FT_E_INVALID, "more than %d bench files", MAX_FILES);
        return NULL;
    }
    char *f = ft_bench_strdup(path), *aux = ft_bench_strf("%s.aux.xml", path);
    if (f == NULL || aux == NULL) {
        free(f);
        free(aux);
        free(path);
        ft_error(FT_E_NOMEM, "out of memory");
        return NULL;
    }
    reg_files[reg_count] = f;
    reg_aux[reg_count] = aux;
    reg_count++;
    return path;
}

static void unlink_scratch(const char *path)
{
    if (path == NULL)
        return;
    unlink(path);
    char aux[PATH_MAX];
    if ((size_t)snprintf(aux, sizeof aux, "%s.aux.xml", path) < sizeof aux)
        unlink(aux);
    /* ENVI's header replaces the extension: "out.envi" -> "out.hdr" */
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (dot != NULL && (slash == NULL || dot > slash) &&
        (size_t)snprintf(aux, sizeof aux, "%.*s.hdr", (int)(dot - path), path) < sizeof aux)
        unlink(aux);
}

const char *ft_bench_fracterra_program(void)
{
    static char prog[PATH_MAX];
    static int looked;
    if (!looked) {
        looked = 1;
        char self[PATH_MAX];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        if (n > 0) {
            self[n] = '\0';
            char *slash = strrchr(self, '/');
            if (slash != NULL) {
                *slash = '\0';
                int k = snprintf(prog, sizeof prog, "%s/fracterra", self);
                if (k < 0 || (size_t)k >= sizeof prog || access(prog, X_OK) != 0)
                    prog[0] = '\0';
            }
        }
    }
    return prog[0] != '\0' ? prog : NULL;
}

int ft_bench_in_child(int (*fn)(void *arg), void *arg)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return ft_error(FT_E_IO, "fork: %s", strerror(errno));
    if (pid == 0) {
        child_default_signals();
        int rc = fn(arg);
        if (rc != 0)
            fprintf(stderr, "fracterra_bench: %s\n", ft_last_error());
        _exit(rc == 0 ? 0 : (-rc) & 0x7f);
    }
    int status;
    if (wait_child(pid, &status, NULL) < 0)
        return ft_error(FT_E_IO, "wait: %s", strerror(errno));
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        return FT_OK;
    if (WIFSIGNALED(status))
        return ft_error(FT_E_IO, "input generation killed by signal %d", WTERMSIG(status));
    int code = -(int)WEXITSTATUS(status);
    return ft_error(code < FT_E_UNSUPPORTED ? FT_E_IO : code, "input generation failed (see above)");
}

/* ------------------------------------------------------------------------------------------------
 * Programs: PATH look-up, display, start-up cost
 * --------------------------------------------------------------------------------------------- */

static int on_path(const char *prog)
{
    if (strchr(prog, '/') != NULL)
        return access(prog, X_OK) == 0;
    const char *path = getenv("PATH");
    if (path == NULL)
        path = "/usr/local/bin:/usr/bin:/bin";
    while (*path != '\0') {
        const char *end = strchr(path, ':');
        size_t len = end ? (size_t)(end - path) : strlen(path);
        char full[PATH_MAX];
        if (len > 0 && (size_t)snprintf(full, sizeof full, "%.*s/%s", (int)len, path, prog) < sizeof full &&
            access(full, X_OK) == 0)
            return 1;
        path += len;
        if (*path == ':')
            path++;
    }
    return 0;
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* A command line for display: program by its base name, bench files relative to the bench folder. */
static void format_argv(char *const argv[], char *out, size_t size)
{
    size_t used = 0;
    size_t dirlen = strlen(bench_dir);
    out[0] = '\0';
    for (int i = 0; argv[i] != NULL && used < size; i++) {
        const char *a = argv[i];
        if (i == 0)
            a = base_name(a);
        else if (dirlen > 0 && strncmp(a, bench_dir, dirlen) == 0 && a[dirlen] == '/')
            a += dirlen + 1;
        int quote = a[0] == '\0' || strpbrk(a, " \t'\"") != NULL;
        int n = snprintf(out + used, size - used, quote ? "%s'%s'" : "%s%s", i ? " " : "", a);
        if (n < 0)
            break;
        used += (size_t)n;
    }
}

/* ------------------------------------------------------------------------------------------------
 * One repetition
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    int ok;
    double seconds;
    double sys_seconds; /* in-process runs: kernel time of the timed call (page faults, ...); else 0 */
    double work;
    double rss_mb;
    char err[ERR_LEN];
} rep_result;

typedef struct {
    int rc;
    double seconds;
    double sys_seconds;
    double work;
    char err[ERR_LEN];
} child_msg;

static double sys_time_s(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0.0;
    return (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static double rss_mb_of(const struct rusage *ru)
{
    return (double)ru->ru_maxrss / 1024.0; /* Linux: kilobytes */
}

static void describe_status(int status, char *err, size_t size)
{
    if (WIFSIGNALED(status))
        snprintf(err, size, "killed by signal %d (%s)", WTERMSIG(status), strsignal(WTERMSIG(status)));
    else if (WIFEXITED(status))
        snprintf(err, size, "exit status %d", WEXITSTATUS(status));
    else
        snprintf(err, size, "stopped");
}

/* Waits for the child pid: its status in *status, its peak memory in r->rss_mb; -1 (r->err set) if the
 * wait fails. */
static int wait_rep(pid_t pid, int *status, rep_result *r)
{
    struct rusage ru;
    memset(&ru, 0, sizeof ru);
    if (wait_child(pid, status, &ru) < 0) {
        snprintf(r->err, sizeof r->err, "wait: %s", strerror(errno));
        return -1;
    }
    r->rss_mb = rss_mb_of(&ru);
    return 0;
}

/* An in-process workload (or peer): prepare (untimed) and run (timed) in a forked child. */
static void run_inprocess(int (*prepare)(ft_bench_case *), int (*run)(ft_bench_case *), ft_bench_case *c,
                          rep_result *r)
{
    memset(r, 0, sizeof *r);
    int fd[2];
    if (pipe(fd) != 0) {
        snprintf(r->err, sizeof r->err, "pipe: %s", strerror(errno));
        return;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(r->err, sizeof r->err, "fork: %s", strerror(errno));
        close(fd[0]);
        close(fd[1]);
        return;
    }
    if (pid == 0) {
        child_default_signals();
        close(fd[0]);
        child_msg m;
        memset(&m, 0, sizeof m);
        ft_io_init();
        int rc = prepare ? prepare(c) : FT_OK;
        if (rc == FT_OK) {
            double s0 = sys_time_s(), t0 = now_seconds();
            rc = run(c);
            m.seconds = now_seconds() - t0;
            m.sys_seconds = sys_time_s() - s0;
        }
        m.rc = rc;
        m.work = c->work;
        if (rc != FT_OK)
            snprintf(m.err, sizeof m.err, "%s", ft_last_error()[0] ? ft_last_error() : ft_strerror(rc));
        int wrote = transfer_all(fd[1], &m, sizeof m, 1);
        _exit(rc == FT_OK && wrote == 0 ? 0 : 1);
    }
    close(fd[1]);
    child_msg m;
    int got = transfer_all(fd[0], &m, sizeof m, 0);
    close(fd[0]);
    int status = 0;
    if (wait_rep(pid, &status, r) < 0)
        return;
    if (got != 0) {
        describe_status(status, r->err, sizeof r->err);
        return;
    }
    if (m.rc != FT_OK) {
        m.err[sizeof m.err - 1] = '\0';
        snprintf(r->err, sizeof r->err, "%s", m.err);
        return;
    }
    r->ok = 1;
    r->seconds = m.seconds;
    r->sys_seconds = m.sys_seconds;
    r->work = m.work;
}

/* First line of a file, for the reason a command failed. */
static void first_line(const char *path, char *out, size_t size)
{
    out[0] = '\0';
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return;
    if (fgets(out, (int)size, f) != NULL)
        out[strcspn(out, "\r\n")] = '\0';
    fclose(f);
}

/* A command, timed from fork to exit; stdout discarded, stderr kept in errpath for the error message. */
static void run_command(char *const argv[], const char *errpath, rep_result *r)
{
    memset(r, 0, sizeof *r);
    fflush(NULL);
    double t0 = now_seconds();
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(r->err, sizeof r->err, "fork: %s", strerror(errno));
        return;
    }
    if (pid == 0) {
        child_default_signals();
        int in = open("/dev/null", O_RDONLY);
        int out = open("/dev/null", O_WRONLY);
        int err = errpath ? open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644) : -1;
        if (in >= 0)
            dup2(in, STDIN_FILENO);
        if (out >= 0)
            dup2(out, STDOUT_FILENO);
        if (err >= 0)
            dup2(err, STDERR_FILENO);
        execvp(argv[0], argv);
        fprintf(stderr, "cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    int status = 0;
    if (wait_rep(pid, &status, r) < 0)
        return;
    r->seconds = now_seconds() - t0;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        r->ok = 1;
        return;
    }
    char why[128], line[ERR_LEN / 2];
    describe_status(status, why, sizeof why);
    first_line(errpath, line, sizeof line);
    snprintf(r->err, sizeof r->err, "%s%s%s", why, line[0] ? ": " : "", line);
}

/* ------------------------------------------------------------------------------------------------
 * Start-up cost of the programs used (median of `PROGRAM --version`)
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    char name[64];
    double seconds;
    int ok;
} program_startup;

static program_startup startups[MAX_PROGRAMS];
static size_t n_startups;

static void measure_startup(const char *prog, int repeat, const char *errpath)
{
    const char *name = base_name(prog);
    for (size_t i = 0; i < n_startups; i++)
        if (strcmp(startups[i].name, name) == 0)
            return;
    if (n_startups >= MAX_PROGRAMS)
        return;
    program_startup *p = &startups[n_startups++];
    snprintf(p->name, sizeof p->name, "%s", name);
    char *argv[] = {(char *)prog, (char *)"--version", NULL};
    double t[MAX_REPEAT];
    int n = 0;
    for (int i = 0; i < repeat; i++) {
        rep_result r;
        run_command(argv, errpath, &r);
        if (!r.ok)
            break;
        t[n++] = r.seconds;
    }
    p->ok = n == repeat;
    p->seconds = p->ok ? median(t, (size_t)n) : 0.0;
}

/* ------------------------------------------------------------------------------------------------
 * Workload results
 * --------------------------------------------------------------------------------------------- */

enum { PEER_NONE = 0, PEER_MISSING, PEER_OK, PEER_FAILED };

typedef struct {
    const ft_bench_workload *w;
    int ok;
    char err[ERR_LEN];
    char command[1024];      /* our command line (command workloads) or "" */
    double times[MAX_REPEAT];
    int ntimes;
    double median_s, work, rss_mb;
    int peer;
    char peer_command[1024];
    char peer_note[256];
    char peer_err[ERR_LEN];
    double peer_times[MAX_REPEAT];
    int npeer;
    double peer_median_s, peer_rss_mb;
    int inprocess;                 /* ours ran in process: sys_max is meaningful */
    double sys_max, peer_sys_max;  /* largest kernel time of one timed call (in-process runs) */
} wl_result;

static const char *unit_name(ft_bench_unit u)
{
    switch (u) {
    case FT_BENCH_CELLS: return "cells/s";
    case FT_BENCH_VERTICES: return "vertices/s";
    case FT_BENCH_BYTES: return "bytes/s";
    }
    return "?";
}

static void format_throughput(ft_bench_unit u, double per_s, char *out, size_t size)
{
    switch (u) {
    case FT_BENCH_CELLS: snprintf(out, size, "%.1f Mcells/s", per_s / 1e6); return;
    case FT_BENCH_VERTICES: snprintf(out, size, "%.2f Mvert/s", per_s / 1e6); return;
    case FT_BENCH_BYTES: snprintf(out, size, "%.1f MB/s", per_s / 1e6); return;
    }
    snprintf(out, size, "%g", per_s);
}

static void free_case(ft_bench_case *c)
{
    for (int i = 0; i < FT_BENCH_MAX_ARGV; i++) {
        free(c->argv[i]);
        free(c->peer_argv[i]);
    }
    free(c->scratch);
    memset(c, 0, sizeof *c);
}

static int tty_progress;

static void progress(const char *name, const char *who, int i, int n)
{
    if (!tty_progress)
        return;
    fprintf(stderr, "\r\033[K  %s: %s %d/%d", name, who, i, n);
    fflush(stderr);
}

static void progress_clear(void)
{
    if (tty_progress)
        fprintf(stderr, "\r\033[K");
}

/* The repetitions of an in-process peer (a library, e.g. GEOS), timed like our in-process workloads. */
static void run_inprocess_peer(const ft_bench_workload *w, ft_bench_case *c, int repeat, int peers, wl_result *res)
{
    snprintf(res->peer_command, sizeof res->peer_command, "%s", c->peer_label ? c->peer_label : "in-process peer");
    if (!peers) {
        res->peer = PEER_NONE;
        snprintf(res->peer_note, sizeof res->peer_note, "skipped (--no-peers)");
        return;
    }
    res->peer = PEER_OK;
    for (int i = 0; i < repeat; i++) {
        rep_result r;
        progress(w->name, "peer", i + 1, repeat);
        run_inprocess(c->peer_prepare, c->peer_run, c, &r);
        if (r.rss_mb > res->peer_rss_mb)
            res->peer_rss_mb = r.rss_mb;
        if (!r.ok) {
            res->peer = PEER_FAILED;
            snprintf(res->peer_err, sizeof res->peer_err, "%s", r.err);
            return;
        }
        res->peer_times[res->npeer++] = r.seconds;
        if (r.sys_seconds > res->peer_sys_max)
            res->peer_sys_max = r.sys_seconds;
    }
    res->peer_median_s = median(res->peer_times, (size_t)res->npeer);
}

static void run_workload(const ft_bench_workload *w, int repeat, int peers, const char *errpath,
                         wl_result *res)
{
    memset(res, 0, sizeof *res);
    res->w = w;
    ft_bench_case c;
    memset(&c, 0, sizeof c);
    progress(w->name, "setup", 0, 1);
    ft_clear_error();
    int rc = w->setup ? w->setup(&c) : FT_OK;
    if (rc != FT_OK) {
        progress_clear();
        snprintf(res->err, sizeof res->err, "setup: %s", ft_last_error()[0] ? ft_last_error() : ft_strerror(rc));
        free_case(&c);
        return;
    }
    if (c.min_repeat > repeat) /* a row whose spread matters */
        repeat = c.min_repeat < MAX_REPEAT ? c.min_repeat : MAX_REPEAT;
    if (w->run == NULL && c.argv[0] == NULL) {
        snprintf(res->err, sizeof res->err, "setup gave neither a run function nor a command");
    } else {
        if (w->run == NULL) {
            format_argv(c.argv, res->command, sizeof res->command);
            measure_startup(c.argv[0], repeat, errpath);
        }
        res->ok = 1;
        for (int i = 0; i < repeat; i++) {
            rep_result r;
            progress(w->name, "ours", i + 1, repeat);
            unlink_scratch(c.scratch);
            if (w->run != NULL)
                run_inprocess(w->prepare, w->run, &c, &r);
            else
                run_command(c.argv, errpath, &r);
            unlink_scratch(c.scratch);
            if (r.rss_mb > res->rss_mb)
                res->rss_mb = r.rss_mb;
            if (!r.ok) {
                res->ok = 0;
                snprintf(res->err, sizeof res->err, "%s", r.err);
                break;
            }
            res->times[res->ntimes++] = r.seconds;
            res->work = w->run != NULL ? r.work : c.work;
            res->inprocess = w->run != NULL;
            if (r.sys_seconds > res->sys_max)
                res->sys_max = r.sys_seconds;
        }
        if (res->ok)
            res->median_s = median(res->times, (size_t)res->ntimes);
    }

    if (c.peer_argv[0] == NULL && c.peer_run != NULL) {
        run_inprocess_peer(w, &c, repeat, peers, res);
    } else if (c.peer_argv[0] == NULL) {
        res->peer = PEER_NONE;
        snprintf(res->peer_note, sizeof res->peer_note, "%s", c.peer_none ? c.peer_none : "none");
    } else {
        format_argv(c.peer_argv, res->peer_command, sizeof res->peer_command);
        if (!on_path(c.peer_argv[0])) {
            res->peer = PEER_MISSING;
            snprintf(res->peer_note, sizeof res->peer_note, "%s: not installed", base_name(c.peer_argv[0]));
        } else if (!peers) {
            res->peer = PEER_NONE;
            snprintf(res->peer_note, sizeof res->peer_note, "skipped (--no-peers)");
        } else {
            measure_startup(c.peer_argv[0], repeat, errpath);
            res->peer = PEER_OK;
            for (int i = 0; i < repeat; i++) {
                rep_result r;
                progress(w->name, "peer", i + 1, repeat);
                unlink_scratch(c.scratch);
                run_command(c.peer_argv, errpath, &r);
                unlink_scratch(c.scratch);
                if (r.rss_mb > res->peer_rss_mb)
                    res->peer_rss_mb = r.rss_mb;
                if (!r.ok) {
                    res->peer = PEER_FAILED;
                    snprintf(res->peer_err, sizeof res->peer_err, "%s", r.err);
                    break;
                }
                res->peer_times[res->npeer++] = r.seconds;
            }
            if (res->peer == PEER_OK)
                res->peer_median_s = median(res->peer_times, (size_t)res->npeer);
        }
    }
    progress_clear();
    if (w->teardown)
        w->teardown(&c);
    free_case(&c);
}

/* Peak RSS of a forked child that does nothing: the floor under every in-process figure. */
static double idle_child_rss_mb(void)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return 0.0;
    if (pid == 0)
        _exit(0);
    int status;
    struct rusage ru;
    memset(&ru, 0, sizeof ru);
    if (wait_child(pid, &status, &ru) < 0)
        return 0.0;
    return rss_mb_of(&ru);
}

/* ------------------------------------------------------------------------------------------------
 * Output
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    const char *fracterra;
    const char *gdal;
    long cores;
    char cpu[128];
    char date[64];
    int repeat;
    double floor_rss_mb;
} header_info;

static void cpu_model(char *out, size_t size)
{
    snprintf(out, size, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f == NULL)
        return;
    char line[512];
    while (fgets(line, sizeof line, f) != NULL) {
        if (strncmp(line, "model name", 10) == 0) {
            char *colon = strchr(line, ':');
            if (colon != NULL) {
                colon++;
                while (*colon == ' ' || *colon == '\t')
                    colon++;
                colon[strcspn(colon, "\r\n")] = '\0';
                snprintf(out, size, "%s", colon);
            }
            break;
        }
    }
    fclose(f);
}

static void print_header(const header_info *h)
{
    printf("fracterra bench: fracterra %s, GDAL %s\n", h->fracterra, h->gdal);
    printf("machine: %ld cores online, %s\n", h->cores, h->cpu);
    printf("date:    %s\n", h->date);
    printf("method:  %d repetitions per workload, each in its own process; median wall time; peak RSS is the\n"
           "         largest ru_maxrss of those processes (an idle forked child of the harness peaks at %.1f MB)\n",
           h->repeat, h->floor_rss_mb);
    printf("inputs:  %s\n\n", bench_dir[0] ? bench_dir : "(none generated)");
    printf("%-22s %10s %16s %10s | %10s %10s %9s\n", "workload", "median", "throughput", "peak RSS", "peer", "peer RSS",
           "ours/peer");
    fflush(stdout);
}

static double min_of(const double *v, int n)
{
    double m = v[0];
    for (int i = 1; i < n; i++)
        m = v[i] < m ? v[i] : m;
    return m;
}

static double max_of(const double *v, int n)
{
    double m = v[0];
    for (int i = 1; i < n; i++)
        m = v[i] > m ? v[i] : m;
    return m;
}

static void print_row(const wl_result *r)
{
    char tp[64] = "";
    if (r->ok && r->median_s > 0)
        format_throughput(r->w->unit, r->work / r->median_s, tp, sizeof tp);
    if (r->ok)
        printf("%-22s %8.3f s %16s %7.1f MB | ", r->w->name, r->median_s, tp, r->rss_mb);
    else
        printf("%-22s %10s %16s %10s | ", r->w->name, "FAILED", "", "");
    if (r->peer == PEER_OK && r->ok && r->peer_median_s > 0)
        printf("%8.3f s %7.1f MB %9.2f\n", r->peer_median_s, r->peer_rss_mb, r->median_s / r->peer_median_s);
    else if (r->peer == PEER_OK)
        printf("%8.3f s %7.1f MB %9s\n", r->peer_median_s, r->peer_rss_mb, "-");
    else
        printf("%10s %10s %9s\n", "-", "-", "-");
    printf("    ours: %s\n", r->command[0] ? r->command : r->w->summary);
    if (r->ok && r->ntimes > 1) {
        printf("    spread: ours min %.3f, median %.3f, max %.3f s over %d runs", min_of(r->times, r->ntimes),
               r->median_s, max_of(r->times, r->ntimes), r->ntimes);
        if (r->peer == PEER_OK && r->npeer > 1)
            printf("; peer min %.3f, median %.3f, max %.3f s", min_of(r->peer_times, r->npeer), r->peer_median_s,
                   max_of(r->peer_times, r->npeer));
        printf("\n");
        if (r->inprocess) /* kernel time inside the timed call: first touch of fresh memory shows here */
            printf("    system time of one call: ours max %.3f s%s", r->sys_max,
                   r->peer == PEER_OK && r->npeer > 1 ? "" : "\n");
        if (r->inprocess && r->peer == PEER_OK && r->npeer > 1)
            printf(", peer max %.3f s\n", r->peer_sys_max);
    }
    if (!r->ok)
        printf("    error: %s\n", r->err);
    switch (r->peer) {
    case PEER_OK: printf("    peer: %s\n", r->peer_command); break;
    case PEER_FAILED: printf("    peer: %s\n    peer failed: %s\n", r->peer_command, r->peer_err); break;
    case PEER_MISSING: printf("    peer: %s (would run: %s)\n", r->peer_note, r->peer_command); break;
    default: printf("    peer: %s\n", r->peer_note); break;
    }
    fflush(stdout);
}

static void print_footer(void)
{
    printf("\nours/peer < 1: fracterra is faster. In-process workloads time the library call alone; command\n"
           "workloads and peers are whole processes, start-up included.\n");
    if (n_startups > 0)
        printf("start-up of each program (median of PROGRAM --version):\n");
    for (size_t i = 0; i < n_startups; i++) {
        if (startups[i].ok)
            printf("  %-18s %.3f s\n", startups[i].name, startups[i].seconds);
        else
            printf("  %-18s (--version failed)\n", startups[i].name);
    }
}

static json_object *json_times(const double *t, int n)
{
    json_object *a = json_object_new_array();
    for (int i = 0; i < n; i++)
        json_object_array_add(a, json_object_new_double(t[i]));
    return a;
}

static void print_json(const header_info *h, const wl_result *res, size_t n)
{
    json_c_set_serialization_double_format("%.10g", JSON_C_OPTION_GLOBAL);
    json_object *root = json_object_new_object();
    json_object_object_add(root, "fracterra", json_object_new_string(h->fracterra));
    json_object_object_add(root, "gdal", json_object_new_string(h->gdal));
    json_object_object_add(root, "cores", json_object_new_int64(h->cores));
    json_object_object_add(root, "cpu", json_object_new_string(h->cpu));
    json_object_object_add(root, "date", json_object_new_string(h->date));
    json_object_object_add(root, "repeat", json_object_new_int(h->repeat));
    json_object_object_add(root, "idle_child_rss_mb", json_object_new_double(h->floor_rss_mb));
    json_object *st = json_object_new_object();
    for (size_t i = 0; i < n_startups; i++)
        json_object_object_add(st, startups[i].name,
                               startups[i].ok ? json_object_new_double(startups[i].seconds) : NULL);
    json_object_object_add(root, "startup_s", st);
    json_object *arr = json_object_new_array();
    for (size_t i = 0; i < n; i++) {
        const wl_result *r = &res[i];
        json_object *o = json_object_new_object();
        json_object_object_add(o, "name", json_object_new_string(r->w->name));
        json_object_object_add(o, "summary", json_object_new_string(r->w->summary));
        if (r->command[0])
            json_object_object_add(o, "command", json_object_new_string(r->command));
        json_object_object_add(o, "status", json_object_new_string(r->ok ? "ok" : "failed"));
        if (!r->ok)
            json_object_object_add(o, "error", json_object_new_string(r->err));
        json_object_object_add(o, "unit", json_object_new_string(unit_name(r->w->unit)));
        json_object_object_add(o, "work", json_object_new_double(r->work));
        json_object_object_add(o, "times_s", json_times(r->times, r->ntimes));
        if (r->ok) {
            json_object_object_add(o, "median_s", json_object_new_double(r->median_s));
            if (r->ntimes > 0) {
                json_object_object_add(o, "min_s", json_object_new_double(min_of(r->times, r->ntimes)));
                json_object_object_add(o, "max_s", json_object_new_double(max_of(r->times, r->ntimes)));
                json_object_object_add(o, "runs", json_object_new_int(r->ntimes));
            }
            if (r->inprocess)
                json_object_object_add(o, "sys_max_s", json_object_new_double(r->sys_max));
            json_object_object_add(o, "throughput",
                                   json_object_new_double(r->median_s > 0 ? r->work / r->median_s : 0.0));
        }
        json_object_object_add(o, "peak_rss_mb", json_object_new_double(r->rss_mb));
        json_object *p = json_object_new_object();
        static const char *const peer_status[] = {"none", "not installed", "ok", "failed"};
        json_object_object_add(p, "status", json_object_new_string(peer_status[r->peer]));
        if (r->peer_command[0])
            json_object_object_add(p, "command", json_object_new_string(r->peer_command));
        if (r->peer == PEER_NONE)
            json_object_object_add(p, "note", json_object_new_string(r->peer_note));
        if (r->peer == PEER_FAILED)
            json_object_object_add(p, "error", json_object_new_string(r->peer_err));
        if (r->peer == PEER_OK || r->peer == PEER_FAILED) {
            json_object_object_add(p, "times_s", json_times(r->peer_times, r->npeer));
            json_object_object_add(p, "peak_rss_mb", json_object_new_double(r->peer_rss_mb));
        }
        if (r->peer == PEER_OK) {
            json_object_object_add(p, "median_s", json_object_new_double(r->peer_median_s));
            if (r->ok && r->peer_median_s > 0)
                json_object_object_add(p, "ratio", json_object_new_double(r->median_s / r->peer_median_s));
        }
        json_object_object_add(o, "peer", p);
        json_object_array_add(arr, o);
    }
    json_object_object_add(root, "workloads", arr);
    printf("%s\n", json_object_to_json_string_ext(root, JSON_C_TO_STRING_PRETTY | JSON_C_TO_STRING_NOSLASHESCAPE));
    json_object_put(root);
}

/* ------------------------------------------------------------------------------------------------
 * main
 * --------------------------------------------------------------------------------------------- */

static void usage(FILE *f)
{
    fprintf(f,
            "usage: fracterra_bench [--repeat N] [--filter SUBSTRING] [--json] [--no-peers] [--list]\n"
            "\n"
            "Runs fracterra's named workloads N times each (default 5), every repetition in its own process,\n"
            "and prints the median wall time, the throughput and the peak memory; runs the peer tool doing\n"
            "the same work (GDAL, GRASS GIS, GEOS command-line tools) when it is on PATH and prints the ratio.\n"
            "\n"
            "  --repeat N           repetitions per workload (1..%d)\n"
            "  --filter SUBSTRING   only workloads whose name contains SUBSTRING\n"
            "  --json               one JSON object on stdout instead of the table\n"
            "  --no-peers           do not run peer commands\n"
            "  --list               list the workloads and exit\n"
            "\n"
            "Inputs are generated once in a temporary folder under $FT_BENCH_DIR (default /tmp) and removed\n"
            "at the end.\n"
            "Example: fracterra_bench --filter geotiff --repeat 3\n",
            MAX_REPEAT);
}

int main(int argc, char **argv)
{
    int repeat = 5, json = 0, peers = 1, list = 0;
    const char *filter = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "--repeat") == 0 && i + 1 < argc) {
            char *end;
            errno = 0;
            long v = strtol(argv[++i], &end, 10);
            if (errno != 0 || *end != '\0' || v < 1 || v > MAX_REPEAT) {
                fprintf(stderr, "fracterra_bench: --repeat must be an integer in [1,%d], got %s\n", MAX_REPEAT,
                        argv[i]);
                return 2;
            }
            repeat = (int)v;
        } else if (strcmp(a, "--filter") == 0 && i + 1 < argc) {
            filter = argv[++i];
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "--no-peers") == 0) {
            peers = 0;
        } else if (strcmp(a, "--list") == 0) {
            list = 1;
        } else {
            fprintf(stderr, "fracterra_bench: unknown or incomplete option %s\n", a);
            usage(stderr);
            return 2;
        }
    }

    size_t total = 0;
    for (size_t s = 0; s < N_SUITES; s++)
        total += bench_suites[s]->count;
    const ft_bench_workload **selected = calloc(total ? total : 1, sizeof *selected);
    wl_result *results = calloc(total ? total : 1, sizeof *results);
    if (selected == NULL || results == NULL) {
        fprintf(stderr, "fracterra_bench: out of memory\n");
        return 1;
    }
    size_t nsel = 0;
    for (size_t s = 0; s < N_SUITES; s++)
        for (size_t k = 0; k < bench_suites[s]->count; k++) {
            const ft_bench_workload *w = &bench_suites[s]->workloads[k];
            if (filter == NULL || strstr(w->name, filter) != NULL)
                selected[nsel++] = w;
        }
    if (list) {
        for (size_t i = 0; i < nsel; i++)
            printf("%-22s %-10s %s\n", selected[i]->name, unit_name(selected[i]->unit), selected[i]->summary);
        free(selected);
        free(results);
        return 0;
    }
    if (nsel == 0) {
        fprintf(stderr, "fracterra_bench: no workload matches --filter %s (see --list)\n", filter ? filter : "");
        free(selected);
        free(results);
        return 2;
    }

    install_signal_handlers();
    atexit(cleanup_at_exit);
    tty_progress = isatty(STDERR_FILENO);

    header_info h;
    memset(&h, 0, sizeof h);
    h.fracterra = ft_version();
    h.gdal = GDALVersionInfo("RELEASE_NAME");
    h.cores = sysconf(_SC_NPROCESSORS_ONLN);
    cpu_model(h.cpu, sizeof h.cpu);
    time_t t = time(NULL);
    struct tm tm;
    localtime_r(&t, &tm);
    strftime(h.date, sizeof h.date, "%Y-%m-%d %H:%M:%S %z", &tm);
    h.repeat = repeat;
    h.floor_rss_mb = idle_child_rss_mb();

    char *errpath = ft_bench_path("command.stderr");
    if (errpath == NULL) {
        fprintf(stderr, "fracterra_bench: %s\n", ft_last_error());
        free(selected);
        free(results);
        return 1;
    }
    if (!json)
        print_header(&h);

    int failed = 0;
    for (size_t i = 0; i < nsel; i++) {
        run_workload(selected[i], repeat, peers, errpath, &results[i]);
        failed |= !results[i].ok;
        if (!json)
            print_row(&results[i]);
    }
    if (json)
        print_json(&h, results, nsel);
    else
        print_footer();

    free(errpath);
    free(selected);
    free(results);
    return failed ? 1 : 0;
}
