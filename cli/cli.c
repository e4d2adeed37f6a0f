/* fracterra — cli/cli.c: helpers shared by the commands (messages, option parsing, JSON, progress, CRS).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli.h"

#include <cpl_progress.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

static volatile sig_atomic_t interrupted;

/* The first Ctrl-C (or TERM) asks the running computation to stop at its next progress report, so that
 * it unwinds and removes its temporary files; a second one ends the process at once. */
static void on_interrupt(int sig)
{
    if (interrupted) {
        signal(sig, SIG_DFL);
        raise(sig);
    }
    interrupted = sig;
}

void cli_init(void)
{
    /* 15 significant digits: exact for every value a file stores in decimal, without 0.1 -> 0.1000000000001. */
    json_c_set_serialization_double_format("%.15g", JSON_C_OPTION_GLOBAL);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

int cli_interrupted(void)
{
    return interrupted != 0;
}

static void vmessage(const cli_command *cmd, const char *prefix, const char *fmt, va_list ap)
{
    fflush(stdout);
    fprintf(stderr, "fracterra: %s: %s", cmd ? cmd->name : "error", prefix);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

void cli_error(const cli_command *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(cmd, "", fmt, ap);
    va_end(ap);
}

void cli_warn(const cli_command *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(cmd, "warning: ", fmt, ap);
    va_end(ap);
}

int cli_fail(const cli_command *cmd)
{
    const char *msg = ft_last_error();
    if (msg == NULL || *msg == '\0')
        msg = ft_strerror(ft_last_error_code());
    if (interrupted && ft_last_error_code() == FT_E_CANCELLED)
        cli_error(cmd, "interrupted (%s): stopped, no output written (%s)", interrupted == SIGINT ? "Ctrl-C" : "TERM",
                  msg);
    else
        cli_error(cmd, "%s", msg);
    return CLI_FAIL;
}

int cli_usage_error(const cli_command *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(cmd, "", fmt, ap);
    va_end(ap);
    fprintf(stderr, "usage: %s\nTry 'fracterra %s --help' for more information.\n", cmd->usage, cmd->name);
    return CLI_USAGE;
}

void cli_print_help(const cli_command *cmd)
{
    printf("usage: %s\n\n%s", cmd->usage, cmd->help);
}

/* The option as the user wrote it, for messages: "--name" or "-x". After getopt_long returned '?' or ':',
 * argv[optind - 1] is the long option's own element when optopt is 0 (unknown long option) or when it
 * spells a long option whose value is optopt; otherwise the culprit is the short option optopt. */
static int option_name(char **argv, int after, const struct option *longopts, char *buf, size_t size)
{
    const char *el = after > 0 ? argv[after - 1] : "";
    size_t n = strcspn(el, "=");
    int is_long = strncmp(el, "--", 2) == 0 && optopt == 0;
    for (const struct option *o = longopts; !is_long && o && o->name; o++)
        is_long = strncmp(el, "--", 2) == 0 && o->val == optopt && n > 2 && strlen(o->name) >= n - 2 &&
                  strncmp(el + 2, o->name, n - 2) == 0; /* getopt_long accepts unambiguous prefixes */
    if (is_long)
        snprintf(buf, size, "%.*s", (int)n, el);
    else
        snprintf(buf, size, "-%c", optopt);
    return is_long;
}

int cli_parse_options(const cli_command *cmd, int argc, char **argv, const struct option *longopts,
                      const char *shortopts, cli_opt_fn fn, void *ctx, int *first_arg)
{
    char optstring[128];
    snprintf(optstring, sizeof optstring, ":h%s", shortopts ? shortopts : "");
    opterr = 0;
    optind = 0; /* glibc: 0 resets getopt's whole state, including a half-read cluster of a previous parse */
    int c;
    while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
        char name[96];
        if (c == 'h') {
            cli_print_help(cmd);
            return CLI_OK;
        }
        if (c == '?') {
            int is_long = option_name(argv, optind, longopts, name, sizeof name);
            if (is_long && optopt != 0)
                return cli_usage_error(cmd, "option '%s' takes no value", name);
            return cli_usage_error(cmd, "unknown option '%s'", name);
        }
        if (c == ':') {
            option_name(argv, optind, longopts, name, sizeof name);
            return cli_usage_error(cmd, "option '%s' needs a value", name);
        }
        int rc = fn ? fn(cmd, c, optarg, ctx) : CLI_USAGE;
        if (rc != CLI_CONTINUE)
            return rc;
    }
    *first_arg = optind;
    return CLI_CONTINUE;
}

int cli_parse_int(const cli_command *cmd, const char *option, const char *arg, long min, long max, int *out)
{
    char *end = NULL;
    errno = 0;
    long v = strtol(arg, &end, 10);
    if (errno != 0 || end == arg || *end != '\0' || v < min || v > max || v < INT_MIN || v > INT_MAX)
        return cli_usage_error(cmd, "%s must be an integer in [%ld,%ld], got '%s'", option, min, max, arg);
    *out = (int)v;
    return CLI_CONTINUE;
}

/* "in [1,2]", "in (0,1]", "> 0", ">= 0" or "> 0 (or inf)": the interval, as the messages show it. */
static void interval_text(double lo, double hi, int flags, char *buf, size_t size)
{
    const char *inf = (flags & CLI_ALLOW_INF) ? " (or inf)" : "";
    if (isinf(hi))
        snprintf(buf, size, "%s %g%s", (flags & CLI_OPEN_LO) ? ">" : ">=", lo, inf);
    else
        snprintf(buf, size, "in %c%g,%g%c", (flags & CLI_OPEN_LO) ? '(' : '[', lo, hi,
                 (flags & CLI_OPEN_HI) ? ')' : ']');
}

int cli_parse_double(const cli_command *cmd, const char *option, const char *arg, double lo, double hi, int flags,
                     double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(arg, &end);
    int ok = end != arg && *end == '\0' && !isnan(v) && (errno == 0 || isinf(v));
    if (ok && isinf(v))
        ok = v > 0 && (flags & CLI_ALLOW_INF) && isinf(hi);
    else if (ok)
        ok = ((flags & CLI_OPEN_LO) ? v > lo : v >= lo) && ((flags & CLI_OPEN_HI) ? v < hi : v <= hi);
    if (!ok) {
        char range[96];
        interval_text(lo, hi, flags, range, sizeof range);
        return cli_usage_error(cmd, "%s must be a number %s, got '%s'", option, range, arg);
    }
    *out = v;
    return CLI_CONTINUE;
}

/* "dim line" -> "line". */
static const char *last_word(const char *name)
{
    const char *space = strrchr(name, ' ');
    return space ? space + 1 : name;
}

int cli_run_subcommand(const cli_command *cmd, const cli_command *const *subs, size_t n, int argc, char **argv)
{
    if (argc < 2)
        return cli_usage_error(cmd, "missing SUBCOMMAND");
    const char *name = argv[1];
    if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0) {
        cli_print_help(cmd);
        return CLI_OK;
    }
    for (size_t i = 0; i < n; i++)
        if (strcmp(last_word(subs[i]->name), name) == 0)
            return subs[i]->run(subs[i], argc - 1, argv + 1);
    if (name[0] == '-')
        return cli_usage_error(cmd, "unknown option '%s' (options follow the SUBCOMMAND)", name);
    return cli_usage_error(cmd, "unknown subcommand '%s'", name);
}

int cli_expect_args(const cli_command *cmd, int argc, char **argv, int first, const char *const *names, int n)
{
    int have = argc - first;
    if (have < n)
        return cli_usage_error(cmd, "missing %s", names[have]);
    if (have > n)
        return cli_usage_error(cmd, "unexpected argument '%s'", argv[first + n]);
    return CLI_CONTINUE;
}

int cli_json_fput(json_object *o, FILE *f)
{
    const int flags = JSON_C_TO_STRING_PRETTY | JSON_C_TO_STRING_SPACED | JSON_C_TO_STRING_NOSLASHESCAPE;
    return fputs(json_object_to_json_string_ext(o, flags), f) < 0 || fputc('\n', f) == EOF ? FT_E_IO : FT_OK;
}

int cli_check_grid_work(const cli_command *cmd, const char *path, const ft_grid *g)
{
    double cells = (double)g->nx * (double)g->ny, side = (double)(g->nx > g->ny ? g->nx : g->ny);
    double levels = fmax(1.0, log2(side));
    char what[PATH_MAX + 96];
    snprintf(what, sizeof what, "'%s' (%zu x %zu cells, %.0f levels)", path, g->nx, g->ny, ceil(levels));
    return ft_check_work(cells * levels, what) == FT_OK ? CLI_CONTINUE : cli_fail(cmd);
}

int cli_refuse_overwrite(const cli_command *cmd, const char *what, const char *out, ...)
{
    if (out == NULL)
        return CLI_CONTINUE;
    va_list ap;
    va_start(ap, out);
    const char *in;
    int rc = CLI_CONTINUE;
    while (rc == CLI_CONTINUE && (in = va_arg(ap, const char *)) != NULL)
        if (*in != '\0' && ft_io_same_file(in, out))
            rc = cli_usage_error(cmd, "%s '%s' is the input file '%s': it would be overwritten; choose another name",
                                 what, out, in);
    va_end(ap);
    return rc;
}

int cli_write_file(const char *path, cli_write_fn fn, const void *arg)
{
    return ft_io_atomic_write(path, fn, arg);
}

int cli_print_json(const cli_command *cmd, json_object *o)
{
    int ok = cli_json_fput(o, stdout) == FT_OK && fflush(stdout) == 0;
    json_object_put(o);
    if (!ok) {
        cli_error(cmd, "cannot write to standard output: %s", strerror(errno));
        return CLI_FAIL;
    }
    return CLI_OK;
}

json_object *cli_json_double(double v)
{
    return isfinite(v) ? json_object_new_double(v) : NULL;
}

static int progress_tty(double frac, const char *msg, void *arg)
{
    return interrupted ? 0 : GDALTermProgress(frac, msg, arg);
}

static int progress_quiet(double frac, const char *msg, void *arg)
{
    return !interrupted;
}

ft_progress_fn cli_progress(void)
{
    return isatty(STDERR_FILENO) ? progress_tty : progress_quiet;
}

int cli_read_layer(const cli_command *cmd, const char *path, const char *layer, const char *where, ft_layer **out)
{
    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    lo.layer = layer;
    lo.where = where;
    int rc = ft_io_read_layer(path, &lo, out);
    if (rc == FT_OK)
        rc = ft_layer_check_finite(*out);
    double x0, y0, x1, y1;
    /* Lengths and areas square the coordinates' differences: beyond 1e150 they overflow to inf. */
    if (rc == FT_OK && ft_layer_bbox(*out, &x0, &y0, &x1, &y1) == FT_OK &&
        !(fmax(x1 - x0, y1 - y0) <= 1e150 && fmax(fmax(fabs(x0), fabs(x1)), fmax(fabs(y0), fabs(y1))) <= 1e150))
        rc = ft_error(FT_E_NUMERIC, "%s: coordinates reach %g x %g: lengths and areas would overflow double "
                      "precision (rescale or reproject the data)", path, fmax(fabs(x0), fabs(x1)),
                      fmax(fabs(y0), fabs(y1)));
    if (rc != FT_OK) {
        ft_layer_free(*out);
        *out = NULL;
    }
    if (rc == FT_E_INVALID)
        return cli_usage_error(cmd, "%s", ft_last_error());
    return rc == FT_OK ? CLI_CONTINUE : cli_fail(cmd);
}
