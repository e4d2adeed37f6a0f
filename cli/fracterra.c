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

#include <cairo.h>
#include <gdal.h>
#include <stdio.h>
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
               "Exit status: 0 success, 1 failure while running, 2 bad usage.\n"
               "Example:\n  fracterra info tests/data/dem_volcano_maunga_whau_10m.tif\n");
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
    ft_io_init();
    int rc = cmd->run(cmd, argc, argv);
    if ((fflush(stdout) != 0 || ferror(stdout)) && rc == CLI_OK) {
        cli_error(cmd, "cannot write to standard output");
        rc = CLI_FAIL;
    }
    ft_io_cleanup();
    return rc;
}

int main(int argc, char **argv)
{
    cli_init();
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
    return run_command(cmd, argc - 1, argv + 1);
}
