/* fracterra — io/points_text.c: scattered points from CSV and whitespace XYZ text.
 *
 * CSV through the library's CSV tokenizer (csv_tokenizer.c: header, separator `,` `;` or tab, quoting,
 * decimal comma with `;`); columns are found by name, case-insensitive (x, y, z by default, plus an
 * optional weight column). XYZ: `x y z [w]` per line separated by blanks, tabs or commas, `#` comments, one
 * optional header line. Errors name the file, the line and the column of the bad value.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "internal.h"
#include "io/io_internal.h"

typedef struct {
    const char *path;
    FILE *f;             /* XYZ only: CSV is read through its tokenizer */
    char *buf;
    size_t cap;
    long line;
    ft_points *p;
    double *w;           /* weights, parallel to p */
    size_t wcap;
    char **fields;       /* XYZ: fields of the current line (point into buf) */
    size_t nfields, fcap;
} text_in;

static int next_line(text_in *t)
{
    errno = 0;
    if (getline(&t->buf, &t->cap, t->f) < 0) {
        if (ferror(t->f))
            return ft_error(FT_E_IO, "cannot read '%s': %s", t->path, strerror(errno ? errno : EIO));
        return 0;
    }
    t->line++;
    t->buf[strcspn(t->buf, "\r\n")] = '\0';
    return 1;
}

static int push_field(text_in *t, char *s)
{
    if (t->nfields == t->fcap) {
        size_t cap = t->fcap ? 2 * t->fcap : 16;
        char **f = ft_realloc_array(t->fields, cap, sizeof *f);
        if (f == NULL)
            return FT_E_NOMEM;
        t->fields = f;
        t->fcap = cap;
    }
    t->fields[t->nfields++] = s;
    return FT_OK;
}

/* Splits a whitespace (or comma) separated line in place. */
static int split_blanks(text_in *t, char *s)
{
    t->nfields = 0;
    for (;;) {
        s += strspn(s, " \t,");
        if (*s == '\0')
            return FT_OK;
        char *start = s;
        s += strcspn(s, " \t,");
        int more = *s != '\0';
        *s = '\0';
        if (push_field(t, start) != FT_OK)
            return FT_E_NOMEM;
        if (!more)
            return FT_OK;
        s++;
    }
}

/* The fields of one line and where they come from: csv is the CSV tokenizer (NULL for XYZ), for the decimal
 * comma of `;`-separated files. */
typedef struct {
    char *const *f;
    size_t n;
    long line;
    const ft_io_csv *csv;
} line_fields;

/* Parses field col of the line as a finite number, naming file, line and column otherwise. */
static int field_value(const text_in *t, const line_fields *lf, size_t col, const char *name, double *v)
{
    if (col >= lf->n)
        return ft_error(FT_E_FORMAT, "%s:%ld: column '%s' (%zu) is missing: the line has %zu field%s", t->path,
                        lf->line, name, col + 1, lf->n, lf->n == 1 ? "" : "s");
    const char *s = lf->f[col];
    if (s[0] == '\0')
        return ft_error(FT_E_FORMAT, "%s:%ld: column '%s' (%zu) is empty", t->path, lf->line, name, col + 1);
    if (!ft_io_csv_number(lf->csv, s, v))
        return ft_error(FT_E_FORMAT, "%s:%ld: column '%s' (%zu): '%s' is not a number", t->path, lf->line, name,
                        col + 1, s);
    if (!isfinite(*v))
        return ft_error(FT_E_NUMERIC, "%s:%ld: column '%s' (%zu): '%s' is not finite", t->path, lf->line, name,
                        col + 1, s);
    return FT_OK;
}

/* Appends a point read from columns col[0..2] (x, y, z) and col[3] (weight, if >= 0). */
static int add_point(text_in *t, const line_fields *lf, const size_t *col, const long weight_col,
                     const char *const *names)
{
    double v[4] = {0, 0, 0, 1};
    for (int k = 0; k < 4; k++) {
        if (k == 3 && weight_col < 0)
            break;
        int rc = field_value(t, lf, k == 3 ? (size_t)weight_col : col[k], names[k], &v[k]);
        if (rc != FT_OK)
            return rc;
    }
    if (ft_points_push(t->p, v[0], v[1], v[2]) != FT_OK)
        return FT_E_NOMEM;
    if (weight_col < 0)
        return FT_OK;
    if (t->p->n > t->wcap) {
        size_t cap = t->wcap ? 2 * t->wcap : 256;
        double *w = ft_realloc_array(t->w, cap, sizeof *w);
        if (w == NULL)
            return FT_E_NOMEM;
        t->w = w;
        t->wcap = cap;
    }
    t->w[t->p->n - 1] = v[3];
    return FT_OK;
}

/* Opens the points and, for XYZ (open_file), the file; the caller runs the body, then finish() hands the
 * result over. */
static int start(text_in *t, const char *path, int open_file)
{
    memset(t, 0, sizeof *t);
    t->path = ft_io_is_stdio(path) ? "(stdin)" : path;
    int rc = ft_io_check_readable(path);
    if (rc != FT_OK || !open_file)
        return rc != FT_OK ? rc : ((t->p = ft_points_create(256)) ? FT_OK : FT_E_NOMEM);
    t->f = ft_io_fopen_read(path);
    if (t->f == NULL)
        return ft_error(FT_E_IO, "cannot open '%s': %s", path, strerror(errno));
    t->p = ft_points_create(256);
    return t->p ? FT_OK : FT_E_NOMEM;
}

static int finish(text_in *t, int rc, ft_points **out)
{
    if (rc == FT_OK && t->p->n == 0)
        rc = ft_error(FT_E_EMPTY, "'%s' holds no point", t->path);
    if (rc == FT_OK && t->w != NULL) {
        rc = ft_points_ensure_weights(t->p);
        if (rc == FT_OK)
            memcpy(t->p->w, t->w, t->p->n * sizeof *t->w);
    }
    if (t->f != NULL && t->f != stdin)
        fclose(t->f);
    free(t->buf);
    free(t->fields);
    free(t->w);
    if (rc != FT_OK) {
        ft_points_free(t->p);
        return rc;
    }
    *out = t->p;
    return FT_OK;
}

static int read_csv_body(text_in *t, const char *path, const ft_read_points_opts *o)
{
    ft_io_csv *csv = NULL;
    int rc = ft_io_csv_open(path, &csv);
    const char *names[4] = {o->x ? o->x : "x", o->y ? o->y : "y", o->z ? o->z : "z", o->weight};
    size_t col[4] = {0, 0, 0, 0};
    for (int k = 0; rc == FT_OK && k < 4; k++)
        if (names[k] != NULL)
            rc = ft_io_csv_find(csv, names[k], &col[k]);
    long wcol = o->weight ? (long)col[3] : -1;
    char *const *head = NULL;
    size_t nheader = rc == FT_OK ? ft_io_csv_header(csv, &head) : 0;
    line_fields lf = {NULL, 0, 0, csv};
    char delim = rc == FT_OK ? ft_io_csv_separator(csv) : ',';
    while (rc == FT_OK && (rc = ft_io_csv_next(csv, &lf.n, &lf.f)) == 1) {
        lf.line = ft_io_csv_line(csv);
        /* More fields than the header names: columns would shift; with ',' separators the usual cause is a
         * decimal comma ("2,5"). */
        if (lf.n > nheader)
            rc = ft_error(FT_E_FORMAT, "%s:%ld: %zu fields but the header names %zu%s", t->path, lf.line, lf.n,
                          nheader,
                          delim == ',' ? ": decimal commas with ',' separators? Use ';' between the fields or "
                                         "quote the numbers (\"2,5\")"
                                       : "");
        else
            rc = add_point(t, &lf, col, wcol, names);
    }
    ft_io_csv_close(csv);
    return rc;
}

static int read_xyz_body(text_in *t, const ft_read_points_opts *o)
{
    static const char *const names[4] = {"x", "y", "z", "weight"};
    static const size_t col[3] = {0, 1, 2};
    long wcol = o->weight ? 3 : -1;
    int rc, first = 1;
    double v;
    while ((rc = next_line(t)) == 1) {
        char *s = t->buf + strspn(t->buf, " \t");
        if (*s == '\0' || *s == '#')
            continue;
        if (split_blanks(t, s) != FT_OK)
            return FT_E_NOMEM;
        if (first && t->nfields > 0 && !ft_io_parse_double(t->fields[0], &v)) {
            first = 0;  /* a header line such as "x y z" */
            continue;
        }
        first = 0;
        line_fields lf = {t->fields, t->nfields, t->line, NULL};
        if ((rc = add_point(t, &lf, col, wcol, names)) != FT_OK)
            return rc;
    }
    return rc;
}

int ft_io_read_points_csv(const char *path, const ft_read_points_opts *o, ft_points **out)
{
    text_in t;
    int rc = start(&t, path, 0);
    if (rc == FT_OK)
        rc = read_csv_body(&t, path, o);
    return finish(&t, rc, out);
}

int ft_io_read_points_xyz(const char *path, const ft_read_points_opts *o, ft_points **out)
{
    text_in t;
    int rc = start(&t, path, 1);
    if (rc == FT_OK)
        rc = read_xyz_body(&t, o);
    return finish(&t, rc, out);
}
