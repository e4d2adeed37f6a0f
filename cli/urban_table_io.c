/* fracterra — cli/urban_table_io.c: reading two numeric columns of a per-year table for `urban regress`
 * (urban_cli.h): CSV through the library's CSV tokenizer (ft_io_csv_*: header row, `,` `;` or tab separators,
 * RFC 4180 quoting, blank and # lines skipped, decimal comma with `;`), or the JSON `urban table` writes.
 * Empty, "NA" and null values are missing (the row is skipped); anything else must be a number.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "urban_cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define CSV_MAX_BYTES ((size_t)1 << 30)

void urban_csv_field(FILE *f, const char *s)
{
    size_t n = strlen(s);
    int quote = strpbrk(s, ",\"\r\n") != NULL || (n > 0 && (s[0] == ' ' || s[n - 1] == ' '));
    if (!quote) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

void urban_columns_free(urban_columns *c)
{
    if (c == NULL)
        return;
    free(c->v[0]);
    free(c->v[1]);
    c->v[0] = c->v[1] = NULL;
}

/* ---- values ---- */

typedef enum { VALUE_OK, VALUE_MISSING, VALUE_BAD } value_state;

/* csv: the CSV being read (its decimal comma), NULL for JSON. */
static value_state parse_value(const ft_io_csv *csv, const char *s, double *v)
{
    while (*s == ' ' || *s == '\t')
        s++;
    if (*s == '\0' || strcasecmp(s, "NA") == 0 || strcasecmp(s, "null") == 0)
        return VALUE_MISSING;
    return ft_io_csv_number(csv, s, v) && isfinite(*v) ? VALUE_OK : VALUE_BAD;
}

/* Grows both columns to hold row n. */
static int columns_reserve(urban_columns *c, size_t *cap)
{
    if (c->n < *cap)
        return FT_OK;
    size_t want = *cap ? 2 * *cap : 16;
    for (int k = 0; k < 2; k++) {
        double *p = realloc(c->v[k], want * sizeof *p);
        if (p == NULL)
            return ft_error(FT_E_NOMEM, "out of memory");
        c->v[k] = p;
    }
    *cap = want;
    return FT_OK;
}

/* Adds a row of two parsed values; where names the row in messages ("line 4", "row 2"). */
static int columns_add(urban_columns *c, size_t *cap, const ft_io_csv *csv, const char *path, const char *where,
                       const char *const cols[2], const char *const text[2])
{
    double v[2];
    value_state st[2];
    c->rows++;
    for (int k = 0; k < 2; k++) {
        st[k] = parse_value(csv, text[k], &v[k]);
        if (st[k] == VALUE_BAD)
            return ft_error(FT_E_FORMAT, "%s, %s, column '%s': '%s' is not a number", path, where, cols[k], text[k]);
    }
    if (st[0] == VALUE_MISSING || st[1] == VALUE_MISSING) {
        c->skipped++;
        return FT_OK;
    }
    int rc = columns_reserve(c, cap);
    if (rc == FT_OK) {
        c->v[0][c->n] = v[0];
        c->v[1][c->n++] = v[1];
    }
    return rc;
}

/* ---- CSV ---- */

static int read_csv(const char *path, const char *const cols[2], urban_columns *out)
{
    ft_io_csv *csv = NULL;
    int rc = ft_io_csv_open(path, &csv);
    size_t idx[2] = {0, 0}, n = 0, cap = 0;
    for (int k = 0; rc == FT_OK && k < 2; k++)
        rc = ft_io_csv_find(csv, cols[k], &idx[k]);
    char *const *f = NULL;
    while (rc == FT_OK && (rc = ft_io_csv_next(csv, &n, &f)) == 1) {
        char where[32];
        snprintf(where, sizeof where, "line %ld", ft_io_csv_line(csv));
        const char *text[2] = {idx[0] < n ? f[idx[0]] : "", idx[1] < n ? f[idx[1]] : ""};
        rc = columns_add(out, &cap, csv, path, where, cols, text);
    }
    ft_io_csv_close(csv);
    return rc;
}

/* ---- JSON ---- */

/* The value of a column in a row object: classes[cls][measure], or the member "cls.measure" / "measure".
 * *found tells whether the row has it at all. */
static json_object *json_cell(json_object *row, const char *cls, const char *measure, const char *col, int *found)
{
    json_object *classes = NULL, *c = NULL, *v = NULL;
    *found = 1;
    if (cls && json_object_object_get_ex(row, "classes", &classes) && json_object_object_get_ex(classes, cls, &c))
        if (json_object_object_get_ex(c, measure, &v))
            return v;
    if (json_object_object_get_ex(row, col, &v))
        return v;
    *found = 0;
    return NULL;
}

/* A JSON value as text for columns_add: numbers printed exactly, null and missing as "". */
static const char *json_text(json_object *v, char *buf, size_t size)
{
    if (v == NULL)
        return "";
    if (json_object_is_type(v, json_type_double) || json_object_is_type(v, json_type_int)) {
        snprintf(buf, size, "%.17g", json_object_get_double(v));
        return buf;
    }
    return json_object_get_string(v);
}

/* The table's rows: {"rows": [...]} or a bare array. */
static json_object *json_rows(json_object *o)
{
    json_object *rows = NULL;
    if (json_object_is_type(o, json_type_array))
        return o;
    if (json_object_object_get_ex(o, "rows", &rows) && json_object_is_type(rows, json_type_array))
        return rows;
    return NULL;
}

static int read_json_row(json_object *row, size_t i, const char *path, const char *cls,
                         const char *const measures[2], const char *const cols[2], urban_columns *out, size_t *cap)
{
    char where[32], buf[2][40];
    const char *text[2];
    snprintf(where, sizeof where, "row %zu", i + 1);
    if (!json_object_is_type(row, json_type_object))
        return ft_error(FT_E_FORMAT, "%s, %s: not an object", path, where);
    for (int k = 0; k < 2; k++) {
        int found = 0;
        json_object *v = json_cell(row, cls, measures[k], cols[k], &found);
        if (!found && i == 0)
            return ft_error(FT_E_FORMAT, "%s has no column '%s' (%s has no member of that name)", path, cols[k],
                            where);
        text[k] = json_text(v, buf[k], sizeof buf[k]);
    }
    return columns_add(out, cap, NULL, path, where, cols, text);
}

static int read_json(const char *text, const char *path, const char *cls, const char *const measures[2],
                     const char *const cols[2], urban_columns *out)
{
    json_object *o = json_tokener_parse(text);
    json_object *rows = o ? json_rows(o) : NULL;
    int rc = rows ? FT_OK : ft_error(FT_E_FORMAT, "%s is not a table: JSON with a \"rows\" array expected", path);
    size_t n = rows ? json_object_array_length(rows) : 0, cap = 0;
    if (rc == FT_OK && n == 0)
        rc = ft_error(FT_E_EMPTY, "%s has no rows", path);
    for (size_t i = 0; rc == FT_OK && i < n; i++)
        rc = read_json_row(json_object_array_get_idx(rows, i), i, path, cls, measures, cols, out, &cap);
    json_object_put(o);
    return rc;
}

/* ---- files ---- */

static int read_text(const char *path, char **out)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return ft_error(FT_E_IO, "cannot open %s: %s", path, strerror(errno));
    size_t n = 0, cap = 4096;
    char *s = malloc(cap);
    int rc = s ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
    while (rc == FT_OK) {
        if (n + 1 == cap) {
            char *t = cap < CSV_MAX_BYTES ? realloc(s, 2 * cap) : NULL;
            rc = t ? FT_OK : ft_error(FT_E_NOMEM, "%s is too large to read", path);
            s = t ? t : s;
            cap *= 2;
            continue;
        }
        size_t k = fread(s + n, 1, cap - 1 - n, f);
        n += k;
        if (k == 0)
            break;
    }
    if (rc == FT_OK && ferror(f))
        rc = ft_error(FT_E_IO, "cannot read %s: %s", path, strerror(errno));
    fclose(f);
    if (rc == FT_OK && memchr(s, '\0', n))
        rc = ft_error(FT_E_FORMAT, "%s is not a text table (it holds a NUL byte)", path);
    if (rc != FT_OK) {
        free(s);
        return rc;
    }
    s[n] = '\0';
    *out = s;
    return FT_OK;
}

/* 1 for JSON, 0 for CSV by extension, -1 when the text must tell. */
static int json_by_extension(const char *path)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(slash ? slash : path, '.');
    if (dot && strcasecmp(dot, ".json") == 0)
        return 1;
    if (dot && strcasecmp(dot, ".csv") == 0)
        return 0;
    return -1;
}

/* JSON when the text starts with { or [. */
static int starts_like_json(const char *text)
{
    text += strspn(text, " \t\r\n");
    return *text == '{' || *text == '[';
}

int urban_columns_read(const char *path, const char *cls, const char *const measures[2], urban_columns *out)
{
    char cols[2][256], *text = NULL;
    const char *const names[2] = {cols[0], cols[1]};
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 2; k++)
        urban_column_name(cls, measures[k], cols[k], sizeof cols[k]);
    int json = json_by_extension(path), rc = FT_OK;
    if (json != 0)
        rc = read_text(path, &text);
    if (rc == FT_OK && json < 0)
        json = starts_like_json(text);
    if (rc == FT_OK)
        rc = json ? read_json(text, path, cls, measures, names, out) : read_csv(path, names, out);
    free(text);
    if (rc != FT_OK)
        urban_columns_free(out);
    return rc;
}
