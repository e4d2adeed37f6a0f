/* fracterra — io/text_chains.c: GMT-style plain-text chains.
 *
 * Reading: `x y` per line (separated by blanks, tabs or commas; extra columns ignored), a line starting
 * with `>` ends a segment (text after it ignored), `#` comments and blank lines are skipped. Each
 * segment becomes a feature of type FT_GEOM_LINE with one chain; a segment of 3 or more vertices whose
 * last vertex equals its first is a ring (closed = 1, repeated vertex dropped).
 * Writing: one segment per part, `> fid=<id>` before each (`> -Ph` marks a hole, as GMT does), rings
 * closed again, numbers as the shortest text that reads back to the same double. "-" is stdin/stdout.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "io/io_internal.h"

typedef struct {
    const char *path;
    ft_layer *out;
    ft_chain *seg;   /* segment being read, NULL between segments */
} text_reader;

static int end_segment(text_reader *t)
{
    ft_chain *c = t->seg;
    t->seg = NULL;
    if (c == NULL)
        return FT_OK;
    if (c->n >= 3 && c->x[0] == c->x[c->n - 1] && c->y[0] == c->y[c->n - 1]) {
        c->n--;
        c->closed = 1;
    }
    int64_t fi = ft_layer_add_feature(t->out, (int64_t)t->out->nfeatures, FT_GEOM_LINE, 0);
    if (fi < 0) {
        ft_chain_free(c);
        return (int)fi;
    }
    return ft_layer_add_part(t->out, c, FT_ROLE_LINE, 0);
}

/* Next field of a line: skips separators, returns its start and NUL-terminates it (NULL if none). */
static char *next_token(char **cursor)
{
    char *s = *cursor + strspn(*cursor, " \t,\r\n");
    if (*s == '\0')
        return NULL;
    char *e = s + strcspn(s, " \t,\r\n");
    if (*e != '\0')
        *e++ = '\0';
    *cursor = e;
    return s;
}

static int parse_coordinate(const text_reader *t, long line, char *tok, const char *axis, double *v)
{
    if (tok == NULL)
        return ft_error(FT_E_FORMAT, "%s:%ld: missing %s value (expected 'x y')", t->path, line, axis);
    if (!ft_io_parse_double(tok, v))
        return ft_error(FT_E_FORMAT, "%s:%ld: %s value '%s' is not a number", t->path, line, axis, tok);
    if (!isfinite(*v))
        return ft_error(FT_E_NUMERIC, "%s:%ld: %s value '%s' is not finite", t->path, line, axis, tok);
    return FT_OK;
}

static int read_line(text_reader *t, char *s, long line)
{
    s += strspn(s, " \t");
    if (*s == '\0' || *s == '\n' || *s == '\r' || *s == '#')
        return FT_OK;
    if (*s == '>')
        return end_segment(t);
    double x, y;
    char *cursor = s;
    int rc = parse_coordinate(t, line, next_token(&cursor), "x", &x);
    if (rc == FT_OK)
        rc = parse_coordinate(t, line, next_token(&cursor), "y", &y);
    if (rc != FT_OK)
        return rc;
    if (t->seg == NULL && (t->seg = ft_chain_create(16, 0)) == NULL)
        return FT_E_NOMEM;
    return ft_chain_push(t->seg, x, y);
}

static int read_stream(text_reader *t, FILE *f)
{
    char *buf = NULL;
    size_t cap = 0;
    long line = 0;
    int rc = FT_OK;
    errno = 0;
    while (rc == FT_OK && getline(&buf, &cap, f) >= 0)
        rc = read_line(t, buf, ++line);
    if (rc == FT_OK && ferror(f))
        rc = ft_error(FT_E_IO, "cannot read '%s': %s", t->path, strerror(errno ? errno : EIO));
    free(buf);
    if (rc == FT_OK)
        rc = end_segment(t);
    ft_chain_free(t->seg);
    t->seg = NULL;
    return rc;
}

int ft_io_read_text_chains(const char *path, ft_layer **out)
{
    *out = NULL;
    int rc = ft_io_check_readable(path);
    if (rc != FT_OK)
        return rc;
    FILE *f = ft_io_fopen_read(path);
    if (f == NULL)
        return ft_error(FT_E_IO, "cannot open '%s': %s", path, strerror(errno));
    char *stem = ft_io_is_stdio(path) ? ft_strdup("stdin") : ft_io_stem(path);
    text_reader t = {.path = ft_io_is_stdio(path) ? "(stdin)" : path};
    t.out = ft_layer_create(stem, NULL);
    free(stem);
    rc = t.out ? read_stream(&t, f) : FT_E_NOMEM;
    if (f != stdin)
        fclose(f);
    if (rc == FT_OK && t.out->nparts == 0)
        rc = ft_error(FT_E_EMPTY, "'%s' holds no vertex", t.path);
    if (rc != FT_OK) {
        ft_layer_free(t.out);
        return rc;
    }
    *out = t.out;
    return FT_OK;
}

/* ---- writing ----------------------------------------------------------------------------------- */

static void put_vertex(FILE *f, double x, double y)
{
    ft_io_put_double(f, x);
    fputc(' ', f);
    ft_io_put_double(f, y);
    fputc('\n', f);
}

static void put_layer(FILE *f, const ft_layer *l)
{
    for (size_t i = 0; i < l->nfeatures; i++) {
        const ft_feature *ft = &l->features[i];
        for (size_t p = ft->first; p < ft->first + ft->count; p++) {
            const ft_part *part = &l->parts[p];
            const ft_chain *c = part->chain;
            fprintf(f, "> fid=%lld%s\n", (long long)ft->fid, part->role == FT_ROLE_INNER ? " -Ph" : "");
            for (size_t k = 0; k < c->n; k++)
                put_vertex(f, c->x[k], c->y[k]);
            if (c->closed && c->n > 0)
                put_vertex(f, c->x[0], c->y[0]);
        }
    }
}

static int put_layer_fn(FILE *f, const void *layer)
{
    put_layer(f, layer);
    return FT_OK;
}

int ft_io_write_text_chains(const char *path, const ft_layer *layer)
{
    if (layer == NULL)
        return ft_error(FT_E_INVALID, "no layer to write to '%s'", path ? path : "(null)");
    int rc = ft_io_check_writable(path);
    if (rc != FT_OK)
        return rc;
    if (ft_io_is_stdio(path)) {
        put_layer(stdout, layer);
        if (fflush(stdout) != 0 || ferror(stdout))
            return ft_error(FT_E_IO, "cannot write to stdout: %s", strerror(errno));
        return FT_OK;
    }
    return ft_io_atomic_write(path, put_layer_fn, layer);
}
