/* fracterra — cli/fracterra.c: the `fracterra` tool: global options and dispatch to the commands.
 *
 *   fracterra COMMAND [OPTIONS] ARGS...     run a command (`fracterra COMMAND --help` for its options)
 *   fracterra --help | help [COMMAND]       list the commands, or one command's help
 *   fracterra --version                     print the version
 *
 * Exit status: 0 success, 1 failure while running, 2 bad usage.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli.h"
#include "cli_ranks.h"

#include <cairo.h>
#include <errno.h>
#include <gdal.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The dispatch table: one entry per cmd_<name>.c, in the order `fracterra --help` lists them. */
static const cli_command *const commands[] = {
    &cli_cmd_info,
    &cli_cmd_dim,
    &cli_cmd_enhance,
    &cli_cmd_simplify,
    &cli_cmd_weed,
    &cli_cmd_smooth,
    &cli_cmd_boundary,
    &cli_cmd_urban,
    &cli_cmd_synth,
    &cli_cmd_model,
    &cli_cmd_reconstruct,
    &cli_cmd_fill,
    &cli_cmd_mountain,
    &cli_cmd_hillshade,
    &cli_cmd_render,
    &cli_cmd_demo,
};
#define NCOMMANDS (sizeof commands / sizeof commands[0])

static void print_usage(FILE *f)
{
    fprintf(f, "usage: fracterra COMMAND [OPTIONS] ARGS...\n"
               "       fracterra --help | --version\n\n"
               "fracterra measures the fractal dimension of lines, polygons, grids and scattered elevations,\n"
               "and uses it to enhance, simulate and synthesize map features.\n\n"
               "Commands:\n");
    for (size_t i = 0; i < NCOMMANDS; i++)
        fprintf(f, "  %-12s %s\n", commands[i]->name, commands[i]->summary);
    fprintf(f, "\nRun 'fracterra COMMAND --help' for a command's options and an example.\n"
               "Exit status: 0 success, 1 failure while running, 2 bad usage.\n\n"
               "Every command also takes:\n"
               "  --max-memory SIZE  the memory a command may plan to use (e.g. 2G, 512M; default: half the\n"
               "                     machine's memory): larger work is refused before it starts\n"
               "  --max-work N       the elementary steps it may plan (default %.0e: rulers, pairs or cells)\n"
               "Ctrl-C stops a command cleanly: no output file is left behind.\n\n"
               "Example:\n  fracterra info tests/data/dem_volcano_maunga_whau_10m.tif\n",
            FT_WORK_LIMIT_DEFAULT);
}

static void print_version(void)
{
    printf("fracterra %s\n", ft_version());
    printf("built with GDAL %s, cairo %s, json-c %s\n", GDALVersionInfo("RELEASE_NAME"), cairo_version_string(),
           json_c_version());
}

/* Exit status after printing help or version: 1 if stdout could not be written (a full disk, a closed pipe). */
static int stdout_status(void)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "fracterra: cannot write to standard output\n");
        return CLI_FAIL;
    }
    return CLI_OK;
}

static const cli_command *find_command(const char *name)
{
    for (size_t i = 0; i < NCOMMANDS; i++)
        if (strcmp(commands[i]->name, name) == 0)
            return commands[i];
    return NULL;
}

static int unknown_command(const char *name)
{
    fprintf(stderr, "fracterra: %s: unknown command\nTry 'fracterra --help' for the list of commands.\n", name);
    return CLI_USAGE;
}

/* `fracterra help [COMMAND]`. */
static int help_command(int argc, char **argv)
{
    if (argc < 3) {
        print_usage(stdout);
        return stdout_status();
    }
    const cli_command *cmd = find_command(argv[2]);
    if (cmd == NULL)
        return unknown_command(argv[2]);
    cli_print_help(cmd);
    return stdout_status();
}

static int run_command(const cli_command *cmd, int argc, char **argv)
{
    /* The CLI is the host: GDAL messages the library does not catch (raised on GDAL's own worker threads)
     * stay off stderr, where fracterra's one-line errors go; CPL_DEBUG output still prints. */
    CPLSetErrorHandler(CPLQuietErrorHandler);
    ft_io_init();
    int rc = cmd->run(cmd, argc, argv);
    if ((fflush(stdout) != 0 || ferror(stdout)) && rc == CLI_OK) {
        cli_error(cmd, "cannot write to standard output");
        rc = CLI_FAIL;
    }
    ft_io_cleanup();
    return rc;
}

/* "2G", "512M", "1.5g", "4096" (bytes): > 0 bytes, or -1. */
static double parse_size(const char *s)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || errno != 0 || !(v > 0.0) || !isfinite(v))
        return -1.0;
    const char *units = "KMGT";
    if (*end != '\0') {
        const char *u = strchr(units, *end >= 'a' && *end <= 'z' ? *end - 32 : *end);
        if (u == NULL || *u == '\0' || (end[1] != '\0' && strcmp(end + 1, "B") != 0 && strcmp(end + 1, "b") != 0))
            return -1.0;
        v *= pow(1024.0, (double)(u - units + 1));
    }
    return v >= 1.0 && v < 1.8e19 ? v : -1.0;
}

/* Takes --max-memory SIZE and --max-work N (or --opt=VALUE) out of argv, wherever they stand, and sets the
 * library's bounds. CLI_CONTINUE, or CLI_USAGE after a message. */
static int take_global_options(int *argc, char **argv)
{
    int out = 0;
    for (int i = 0; i < *argc; i++) {
        const char *a = argv[i];
        int mem = strncmp(a, "--max-memory", 12) == 0 && (a[12] == '\0' || a[12] == '=');
        int work = strncmp(a, "--max-work", 10) == 0 && (a[10] == '\0' || a[10] == '=');
        if (!mem && !work) {
            argv[out++] = argv[i];
            continue;
        }
        const char *eq = strchr(a, '='), *name = mem ? "--max-memory" : "--max-work";
        const char *val = eq ? eq + 1 : (i + 1 < *argc ? argv[++i] : NULL);
        double v = val ? parse_size(val) : -1.0;
        if (v < 0.0 || (work && strpbrk(val, "KMGTkmgtBb") != NULL)) {
            fprintf(stderr, "fracterra: %s needs %s, got '%s'\n", name,
                    mem ? "a size such as 2G, 512M or 1048576 (bytes)" : "a number of steps such as 1e12",
                    val ? val : "nothing");
            return CLI_USAGE;
        }
        if (mem)
            ft_set_memory_limit((size_t)v);
        else
            ft_set_work_limit(v);
    }
    argv[out] = NULL;
    *argc = out;
    return CLI_CONTINUE;
}

/* Under mpiexec only the commands that decompose into stripes run; the others would all write the same file. */
static int runs_on_ranks(const cli_command *cmd, int argc, char **argv)
{
    if (cli_nranks() == 1 || cmd == &cli_cmd_hillshade || cmd == &cli_cmd_fill)
        return 1;
#ifdef FT_HAVE_FFTW_MPI
    if (cmd == &cli_cmd_synth) /* --method fft only: cmd_synth.c says so */
        return 1;
#endif
    if (cmd == &cli_cmd_dim && argc > 1 && (strcmp(argv[1], "map") == 0 || strcmp(argv[1], "surface") == 0))
        return 1;
    return 0;
}

static int fracterra_main(int argc, char **argv)
{
    cli_init();
    if (take_global_options(&argc, argv) != CLI_CONTINUE)
        return CLI_USAGE;
    if (argc < 2) {
        print_usage(stderr);
        return CLI_USAGE;
    }
    const char *arg = argv[1];
    if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
        print_usage(stdout);
        return stdout_status();
    }
    if (strcmp(arg, "--version") == 0 || strcmp(arg, "-V") == 0) {
        print_version();
        return stdout_status();
    }
    if (strcmp(arg, "help") == 0)
        return help_command(argc, argv);
    if (arg[0] == '-') {
        fprintf(stderr, "fracterra: unknown option '%s'\nTry 'fracterra --help' for more information.\n", arg);
        return CLI_USAGE;
    }
    const cli_command *cmd = find_command(arg);
    if (cmd == NULL)
        return unknown_command(arg);
    if (!runs_on_ranks(cmd, argc - 1, argv + 1)) {
        if (cli_rank() == 0)
            fprintf(stderr, "fracterra: %s: does not run on several MPI ranks; only dim map, dim surface, hillshade, "
                    "fill%s do (docs/tiling.md)\n", cmd->name,
#ifdef FT_HAVE_FFTW_MPI
                    " and synth --method fft"
#else
                    " (and synth --method fft when built with FFTW's MPI transforms)"
#endif
                    );
        return CLI_USAGE;
    }
    return run_command(cmd, argc - 1, argv + 1);
}

int main(int argc, char **argv)
{
    if (cli_ranks_init(&argc, &argv) != 0) {
        fprintf(stderr, "fracterra: MPI could not start\n");
        return CLI_FAIL;
    }
    int rc = fracterra_main(argc, argv);
    cli_ranks_finalize();
    return rc;
}
