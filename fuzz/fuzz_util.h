/* fracterra — fuzz/fuzz_util.h: what the libFuzzer harnesses share: the input bytes as a file the
 * readers can open (in /dev/shm, one per process), and a bound on the memory a reader may ask for.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_FUZZ_UTIL_H
#define FRACTERRA_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "fracterra/fracterra.h"

/* The readers refuse what would exceed this (libFuzzer's own limit is 2 GB of RSS). */
#define FUZZ_MEMORY_LIMIT ((size_t)256 << 20)

/* Writes the input to "/dev/shm/ft-fuzz-<pid><ext>" (or /tmp without /dev/shm) and returns that path. */
static inline const char *fuzz_file(const char *ext, const uint8_t *data, size_t size)
{
    static char path[128];
    const char *dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(path, sizeof path, "%s/ft-fuzz-%ld%s", dir, (long)getpid(), ext);
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        abort();
    if (size > 0 && fwrite(data, 1, size, f) != size)
        abort();
    if (fclose(f) != 0)
        abort();
    return path;
}

/* A reader that fails must say why: an empty message is itself a finding. */
static inline void fuzz_check_error(int rc)
{
    if (rc != FT_OK && (ft_last_error() == NULL || ft_last_error()[0] == '\0'))
        abort();
}

#endif /* FRACTERRA_FUZZ_UTIL_H */
