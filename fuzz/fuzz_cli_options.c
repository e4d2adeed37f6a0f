/* fracterra — fuzz/fuzz_cli_options.c: option parsing of every command that reads an input file. The
 * input is split at newlines into argv (first line: which command); the harness runs in an empty folder
 * and refuses arguments naming anything that exists there or elsewhere ('/', '..', '-' for stdin), so each
 * command parses its options, then fails to open its input. It must never crash, never leave a file behind
 * and never exit 0. synth and demo (no input file) are left out: they would do real work.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fuzz_util.h"

#include <dirent.h>
#include <string.h>

#include "cli.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

#define MAX_ARGS 24

static const cli_command *const commands[] = {
    &cli_cmd_info,      &cli_cmd_model,  &cli_cmd_reconstruct, &cli_cmd_mountain, &cli_cmd_hillshade,
    &cli_cmd_render,    &cli_cmd_dim,    &cli_cmd_enhance,     &cli_cmd_simplify, &cli_cmd_weed,
    &cli_cmd_smooth,    &cli_cmd_urban,  &cli_cmd_boundary,
};

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    char dir[] = "/tmp/ft-fuzz-cli-XXXXXX";
    if (mkdtemp(dir) == NULL || chdir(dir) != 0)
        abort();
    cli_init();
    ft_io_init();
    return 0;
}

/* 1 if the folder holds nothing but . and .. */
static int folder_empty(void)
{
    DIR *d = opendir(".");
    struct dirent *e;
    int empty = 1;
    while (d && (e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
            empty = 0;
    if (d)
        closedir(d);
    return empty;
}

static int harmless(const char *a)
{
    return strchr(a, '/') == NULL && strstr(a, "..") == NULL && strcmp(a, "-") != 0 && strcmp(a, ".") != 0 &&
           access(a, F_OK) != 0;
}

/* -h (alone or in a cluster of short options) or an abbreviation of --help: the help, exit 0. */
static int asks_help(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if ((argv[i][0] == '-' && argv[i][1] != '-' && strchr(argv[i], 'h')) || strncmp(argv[i], "--h", 3) == 0)
            return 1;
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 4096)
        return 0;
    ft_set_memory_limit(FUZZ_MEMORY_LIMIT);
    char *text = malloc(size);
    if (text == NULL)
        return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    char *argv[MAX_ARGS + 1];
    int argc = 0;
    const cli_command *cmd = commands[data[0] % (sizeof commands / sizeof *commands)];
    argv[argc++] = (char *)cmd->name;
    int ok = 1;
    for (char *s = text, *nl; argc < MAX_ARGS && s != NULL && ok; s = nl ? nl + 1 : NULL) {
        nl = strchr(s, '\n');
        if (nl)
            *nl = '\0';
        ok = harmless(s);
        argv[argc++] = s;
    }
    argv[argc] = NULL;
    if (ok) {
        int rc = cmd->run(cmd, argc, argv);
        if (rc == CLI_OK && !asks_help(argc, argv))
            abort(); /* every input file is missing: success would be a lie */
        if (!folder_empty())
            abort(); /* a failed run left a file */
    }
    free(text);
    return 0;
}
