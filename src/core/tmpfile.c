/* fracterra — core/tmpfile.c: atomic output. A writer writes "<dir>/.<stem>.ft-tmp-<pid>-<n><ext>"
 * beside the destination; commit renames it and its siblings (".<stem>.ft-tmp-<pid>-<n>.shx", .dbf,
 * .prj, .cpg, ...) onto "<dir>/<stem><suffix>"; discard removes them. <ext> is the LAST extension of
 * the destination's name ("a.b.tif" -> stem "a.b", ext ".tif").
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <dirent.h>
#include <errno.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define TMP_MARK ".ft-tmp-"

static atomic_ulong tmp_counter;

/* A path split into its folder ("" for the current one, else up to and including the last '/'),
 * its stem and its last extension (with the dot; "" if none; a leading dot is part of the stem). */
typedef struct {
    size_t dir_len;   /* path[0 .. dir_len) */
    const char *base; /* basename */
    size_t stem_len;  /* base[0 .. stem_len) */
    const char *ext;  /* base + stem_len */
} split_path;

static split_path split(const char *path)
{
    split_path s;
    const char *slash = strrchr(path, '/');
    s.base = slash ? slash + 1 : path;
    s.dir_len = (size_t)(s.base - path);
    const char *dot = strrchr(s.base, '.');
    s.stem_len = (dot != NULL && dot != s.base) ? (size_t)(dot - s.base) : strlen(s.base);
    s.ext = s.base + s.stem_len;
    return s;
}

/* Plain malloc'd printf: these helpers also serve ft_tmp_discard, which must not touch the error. */
static char *concat(const char *a, size_t alen, const char *b, size_t blen, const char *c)
{
    size_t clen = strlen(c);
    char *s = malloc(alen + blen + clen + 1);
    if (s == NULL)
        return NULL;
    memcpy(s, a, alen);
    memcpy(s + alen, b, blen);
    memcpy(s + alen + blen, c, clen + 1);
    return s;
}

/* The folder of a path for opendir()/stat(): "." when it has none. */
static char *dir_of(const char *path, split_path s)
{
    if (s.dir_len == 0)
        return concat(".", 1, "", 0, "");
    return concat(path, s.dir_len, "", 0, "");
}

char *ft_tmp_path(const char *path)
{
    if (path == NULL || *path == '\0') {
        ft_error(FT_E_INVALID, "output path is empty");
        return NULL;
    }
    split_path s = split(path);
    if (*s.base == '\0' || strcmp(s.base, ".") == 0 || strcmp(s.base, "..") == 0) {
        ft_error(FT_E_INVALID, "output path '%s' names a folder, not a file", path);
        return NULL;
    }
    char *dir = dir_of(path, s);
    if (dir == NULL) {
        ft_error(FT_E_NOMEM, "out of memory for the path '%s'", path);
        return NULL;
    }
    struct stat st;
    const char *why = NULL;
    if (stat(dir, &st) != 0)
        why = errno == ENOENT ? "does not exist" : strerror(errno);
    else if (!S_ISDIR(st.st_mode))
        why = "is not a folder";
    if (why != NULL) {
        ft_error(FT_E_IO, "cannot write '%s': folder '%s' %s", path, dir, why);
        free(dir);
        return NULL;
    }
    free(dir);
    char mid[64];
    snprintf(mid, sizeof mid, TMP_MARK "%ld-%lu", (long)getpid(), atomic_fetch_add(&tmp_counter, 1) + 1);
    size_t len = s.dir_len + 1 + s.stem_len + strlen(mid) + strlen(s.ext) + 1;
    char *tmp = ft_malloc(len);
    if (tmp == NULL)
        return NULL;
    snprintf(tmp, len, "%.*s.%.*s%s%s", (int)s.dir_len, path, (int)s.stem_len, s.base, mid, s.ext);
    return tmp;
}

/* Length of the temporary stem ".<stem>.ft-tmp-<pid>-<n>" at the start of the temp's basename, or 0
 * if the name is not one made by ft_tmp_path. */
static size_t tmp_stem_len(const char *base)
{
    const char *mark = NULL;
    for (const char *p = strstr(base, TMP_MARK); p != NULL; p = strstr(p + 1, TMP_MARK))
        mark = p;
    if (base[0] != '.' || mark == NULL)
        return 0;
    const char *p = mark + strlen(TMP_MARK);
    size_t digits = strspn(p, "0123456789");
    if (digits == 0 || p[digits] != '-')
        return 0;
    p += digits + 1;
    digits = strspn(p, "0123456789");
    if (digits == 0)
        return 0;
    return (size_t)(p + digits - base);
}

/* Names in the temp's folder that start with the temp stem followed by '.', excluding the temp itself;
 * NULL-terminated, malloc'd. NULL on failure (errno set). */
static char **list_siblings(const char *dir, const char *tbase, size_t tstem)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return NULL;
    size_t n = 0, cap = 8;
    char **names = malloc(cap * sizeof *names);
    struct dirent *e = NULL;
    while (names != NULL && (e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, tbase, tstem) != 0 || e->d_name[tstem] != '.' || strcmp(e->d_name, tbase) == 0)
            continue;
        if (n + 1 == cap) {
            char **more = realloc(names, 2 * cap * sizeof *names);
            if (more == NULL)
                break;
            names = more;
            cap *= 2;
        }
        if ((names[n] = strdup(e->d_name)) == NULL)
            break;
        n++;
    }
    int failed = names == NULL || e != NULL;
    closedir(d);
    if (names != NULL)
        names[n] = NULL;
    if (failed) {
        for (size_t i = 0; names != NULL && i < n; i++)
            free(names[i]);
        free(names);
        errno = ENOMEM;
        return NULL;
    }
    return names;
}

static void free_names(char **names)
{
    for (size_t i = 0; names != NULL && names[i] != NULL; i++)
        free(names[i]);
    free(names);
}

/* Siblings first, the main file last, so that a reader that sees the main file finds its companions. */
int ft_tmp_commit(const char *tmp, const char *path)
{
    if (tmp == NULL || path == NULL)
        return ft_error(FT_E_INVALID, "ft_tmp_commit: NULL path");
    split_path ts = split(tmp), ps = split(path);
    size_t tstem = tmp_stem_len(ts.base);
    if (tstem == 0)
        return ft_error(FT_E_INVALID, "'%s' is not a temporary name made by ft_tmp_path", tmp);
    char *tdir = dir_of(tmp, ts);
    char **names = tdir ? list_siblings(tdir, ts.base, tstem) : NULL;
    if (names == NULL) {
        int err = tdir ? errno : ENOMEM;
        free(tdir);
        ft_tmp_discard(tmp);
        return ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(err));
    }
    free(tdir);
    int rc = FT_OK;
    for (size_t i = 0; names[i] != NULL && rc == FT_OK; i++) {
        const char *suffix = names[i] + tstem;
        char *from = concat(tmp, ts.dir_len, names[i], strlen(names[i]), "");
        char *to = concat(path, ps.dir_len + ps.stem_len, suffix, strlen(suffix), "");
        if (from == NULL || to == NULL)
            rc = ft_error(FT_E_NOMEM, "out of memory renaming '%s'", names[i]);
        else if (rename(from, to) != 0)
            rc = ft_error(FT_E_IO, "cannot rename '%s' to '%s': %s", from, to, strerror(errno));
        free(from);
        free(to);
    }
    free_names(names);
    if (rc == FT_OK && rename(tmp, path) != 0)
        rc = ft_error(FT_E_IO, "cannot rename '%s' to '%s': %s", tmp, path, strerror(errno));
    if (rc != FT_OK)
        ft_tmp_discard(tmp);
    return rc;
}

/* Never sets the thread's error: it runs on failure paths whose message must survive. */
void ft_tmp_discard(const char *tmp)
{
    if (tmp == NULL)
        return;
    int saved = errno;
    split_path ts = split(tmp);
    size_t tstem = tmp_stem_len(ts.base);
    char *tdir = tstem ? dir_of(tmp, ts) : NULL;
    char **names = tdir ? list_siblings(tdir, ts.base, tstem) : NULL;
    for (size_t i = 0; names != NULL && names[i] != NULL; i++) {
        char *p = concat(tmp, ts.dir_len, names[i], strlen(names[i]), "");
        if (p != NULL)
            remove(p);
        free(p);
    }
    free_names(names);
    free(tdir);
    remove(tmp);
    errno = saved;
}
