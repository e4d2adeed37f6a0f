/* fracterra — io/atomic_write.c: the one atomic-output service. A writer writes
 * "<dir>/.<stem>.ft-tmp-<pid>-<n><ext>" beside the destination; commit flushes it and its siblings
 * (".<stem>.ft-tmp-<pid>-<n>.shx", .dbf, .prj, .cpg, ...) to disk (fsync), renames them onto
 * "<dir>/<stem><suffix>" and syncs the folder; discard removes them. <ext> is the LAST extension of the
 * destination's name ("a.b.tif" -> stem "a.b", ext ".tif"). An existing output is replaced only by a
 * commit that got every byte to disk; a failed one leaves it untouched and removes the temporaries.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "io_internal.h"

#include <cpl_string.h>
#include <cpl_vsi.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
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

char *ft_io_atomic_tmp(const char *path)
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

/* Gets a written file's bytes onto the disk: an error the kernel kept back from write() (a full or
 * quota-limited file system, an NFS server gone) surfaces here at the latest. */
static int sync_file(const char *file, const char *path)
{
    int fd = open(file, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(errno));
    int err = 0;
    if (fsync(fd) != 0 && errno != EINVAL && errno != EROFS) /* EINVAL: a file system without fsync */
        err = errno;
    if (close(fd) != 0 && err == 0)
        err = errno;
    return err ? ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(err)) : FT_OK;
}

/* Makes the renames durable; best effort where a folder cannot be opened for reading. */
static void sync_dir(const char *path, split_path ps)
{
    char *dir = dir_of(path, ps);
    int fd = dir ? open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC) : -1;
    if (fd >= 0) {
        (void)fsync(fd);
        close(fd);
    }
    free(dir);
}

/* Every file synced first, then siblings renamed before the main file, so that a reader that sees the main
 * file finds its companions. */
int ft_io_atomic_commit(const char *tmp, const char *path)
{
    if (tmp == NULL || path == NULL)
        return ft_error(FT_E_INVALID, "ft_io_atomic_commit: NULL path");
    split_path ts = split(tmp), ps = split(path);
    size_t tstem = tmp_stem_len(ts.base);
    if (tstem == 0)
        return ft_error(FT_E_INVALID, "'%s' is not a temporary name made by ft_io_atomic_tmp", tmp);
    char *tdir = dir_of(tmp, ts);
    char **names = tdir ? list_siblings(tdir, ts.base, tstem) : NULL;
    if (names == NULL) {
        int err = tdir ? errno : ENOMEM;
        free(tdir);
        ft_io_atomic_discard(tmp);
        return ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(err));
    }
    free(tdir);
    int rc = sync_file(tmp, path);
    for (size_t i = 0; names[i] != NULL && rc == FT_OK; i++) {
        char *from = concat(tmp, ts.dir_len, names[i], strlen(names[i]), "");
        rc = from ? sync_file(from, path) : ft_error(FT_E_NOMEM, "out of memory writing '%s'", path);
        free(from);
    }
    for (size_t i = 0; names[i] != NULL && rc == FT_OK; i++) {
        const char *suffix = names[i] + tstem;
        char *from = concat(tmp, ts.dir_len, names[i], strlen(names[i]), "");
        char *to = concat(path, ps.dir_len + ps.stem_len, suffix, strlen(suffix), "");
        if (from == NULL || to == NULL)
            rc = ft_error(FT_E_NOMEM, "out of memory renaming '%s'", names[i]);
        else if (rename(from, to) != 0)
            rc = ft_error(FT_E_IO, "cannot write '%s': renaming '%s' failed: %s", to, from, strerror(errno));
        free(from);
        free(to);
    }
    free_names(names);
    if (rc == FT_OK && rename(tmp, path) != 0)
        rc = ft_error(FT_E_IO, "cannot write '%s': renaming '%s' failed: %s", path, tmp, strerror(errno));
    if (rc != FT_OK)
        ft_io_atomic_discard(tmp);
    else
        sync_dir(path, ps);
    return rc;
}

int ft_io_atomic_write(const char *path, ft_io_write_fn fn, const void *arg)
{
    if (fn == NULL)
        return ft_error(FT_E_INVALID, "ft_io_atomic_write: no writer for '%s'", path ? path : "(null)");
    char *tmp = ft_io_atomic_tmp(path);
    if (tmp == NULL)
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : FT_E_NOMEM;
    FILE *f = fopen(tmp, "w");
    if (f == NULL) {
        int rc = ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(errno));
        free(tmp);
        return rc;
    }
    errno = 0;
    int rc = fn(f, arg);
    int err = errno;
    if (fflush(f) != 0 || ferror(f)) {
        err = errno ? errno : err;
        rc = FT_E_IO;
    }
    if (fclose(f) != 0 && rc == FT_OK) {
        err = errno;
        rc = FT_E_IO;
    }
    if (rc != FT_OK) {
        const char *msg = ft_last_error();
        if (rc == FT_E_IO || msg == NULL || *msg == '\0')
            rc = ft_error(rc, "cannot write '%s': %s", path, strerror(err ? err : EIO));
        ft_io_atomic_discard(tmp);
    } else {
        rc = ft_io_atomic_commit(tmp, path);
    }
    free(tmp);
    return rc;
}

/* The absolute, symlink-free form of a path that may not exist yet: its folder resolved, its name kept. */
static char *resolve(const char *path)
{
    char *full = realpath(path, NULL);
    if (full != NULL)
        return full;
    split_path s = split(path);
    char *dir = dir_of(path, s);
    char *rdir = dir ? realpath(dir, NULL) : NULL;
    free(dir);
    if (rdir == NULL)
        return NULL;
    char *r = concat(rdir, strlen(rdir), "/", 1, s.base);
    free(rdir);
    return r;
}

int ft_io_same_file(const char *a, const char *b)
{
    if (a == NULL || b == NULL || ft_io_is_stdio(a) || ft_io_is_stdio(b))
        return 0;
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char *ra = resolve(a), *rb = resolve(b);
    int same = ra != NULL && rb != NULL && strcmp(ra, rb) == 0;
    free(ra);
    free(rb);
    return same;
}

/* Never sets the thread's error: it runs on failure paths whose message must survive. */
void ft_io_atomic_discard(const char *tmp)
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

/* ---- GDAL writers ------------------------------------------------------------------------------ */

/* Most drivers (GeoJSON, PNG, ...) may drop a short write without a word, so they write into memory and
 * the bytes are copied to the temporary with every write checked (and the system's reason reported).
 * GTiff (and COG, which writes through it) reports failed writes through libtiff, so a raster too large to
 * hold twice in memory is written by it directly. */
#define STAGE_IN_MEMORY_MAX 256e6

static int write_directly(GDALDriverH drv, double bytes)
{
    const char *name = drv ? GDALGetDriverShortName(drv) : "";
    return bytes > STAGE_IN_MEMORY_MAX && (strcmp(name, "GTiff") == 0 || strcmp(name, "COG") == 0);
}

int ft_io_stage_begin(const char *path, GDALDriverH drv, double bytes, ft_io_stage *s)
{
    memset(s, 0, sizeof *s);
    s->path = path;
    s->tmp = ft_io_atomic_tmp(path);
    if (s->tmp == NULL)
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : FT_E_NOMEM;
    if (write_directly(drv, bytes)) {
        s->target = ft_strdup(s->tmp);
    } else {
        char dir[96];
        snprintf(dir, sizeof dir, "/vsimem/ft-stage-%ld-%lu", (long)getpid(), atomic_fetch_add(&tmp_counter, 1) + 1);
        const char *base = split(s->tmp).base;
        s->mem_dir = ft_strdup(dir);
        s->target = s->mem_dir ? concat(dir, strlen(dir), "/", 1, base) : NULL;
    }
    if (s->target == NULL) {
        ft_io_stage_end(s, 0);
        return ft_error(FT_E_NOMEM, "out of memory writing '%s'", path);
    }
    return FT_OK;
}

/* Writes n bytes to fd, through short writes and interrupts. */
static int write_all(int fd, const unsigned char *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n > (size_t)INT_MAX ? (size_t)INT_MAX : n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return w < 0 ? errno : EIO;
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

/* Copies every file GDAL wrote in the memory folder to the temporary's folder under the same name. */
static int copy_out(ft_io_stage *s)
{
    char **names = VSIReadDir(s->mem_dir);
    split_path ts = split(s->tmp);
    int rc = FT_OK;
    for (int i = 0; names != NULL && names[i] != NULL && rc == FT_OK; i++) {
        if (strcmp(names[i], ".") == 0 || strcmp(names[i], "..") == 0)
            continue;
        char *mem = concat(s->mem_dir, strlen(s->mem_dir), "/", 1, names[i]);
        char *disk = concat(s->tmp, ts.dir_len, names[i], strlen(names[i]), "");
        vsi_l_offset len = 0;
        unsigned char *buf = mem ? VSIGetMemFileBuffer(mem, &len, FALSE) : NULL;
        int fd = disk && buf ? open(disk, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666) : -1;
        int err = fd < 0 ? (disk && buf ? errno : ENOMEM) : write_all(fd, buf, (size_t)len);
        if (fd >= 0 && close(fd) != 0 && err == 0)
            err = errno;
        if (err != 0)
            rc = ft_error(FT_E_IO, "cannot write '%s': %s", s->path, strerror(err));
        free(mem);
        free(disk);
    }
    CSLDestroy(names);
    return rc;
}

int ft_io_stage_end(ft_io_stage *s, int ok)
{
    int rc = FT_OK;
    if (ok && s->tmp != NULL) {
        rc = s->mem_dir ? copy_out(s) : FT_OK;
        if (rc == FT_OK)
            rc = ft_io_atomic_commit(s->tmp, s->path);
        else
            ft_io_atomic_discard(s->tmp);
    } else if (s->tmp != NULL) {
        ft_io_atomic_discard(s->tmp);
    }
    if (s->mem_dir != NULL)
        VSIRmdirRecursive(s->mem_dir);
    free(s->tmp);
    free(s->target);
    free(s->mem_dir);
    memset(s, 0, sizeof *s);
    return rc;
}
