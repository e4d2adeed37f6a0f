/* fracterra — io/csv_tokenizer.c: the library's one CSV reader (points, the CLI's per-year tables).
 *
 * The header is the first line that is neither blank nor a # comment; the separator is the most frequent of
 * `,` `;` tab outside quotes in it. Fields may be double-quoted as RFC 4180 says ("" is a quote, a quoted
 * field may hold separators and line breaks); blanks around fields are dropped; blank lines and # comment
 * lines are skipped; a UTF-8 byte order mark and CR LF line ends are accepted. With `;` separators a
 * decimal comma ("2,5") reads as a decimal point (ft_io_csv_number). Records are read one at a time, so a
 * file of any length is read in the memory of its longest record.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "internal.h"
#include "io/io_internal.h"

struct ft_io_csv {
    const char *path;      /* for messages: the file, or "(stdin)" */
    FILE *f;
    char *line;            /* getline's buffer */
    size_t line_cap;
    char *rec;             /* the current record: one line, or several when a quoted field spans them */
    size_t rec_len, rec_cap;
    long line_no;          /* lines read so far */
    long rec_line;         /* line on which the current record starts */
    char sep;
    char **fields;         /* of the current record, pointing into rec */
    size_t n, cap;
    char *head_text;       /* the header record, kept while rec is reused */
    char **head;
    size_t nhead;
};

/* Reads one line into *buf (getline's), without its line end, into *len; 1 if there was one, 0 at the end
 * of the file, < 0 on error. */
static int read_line(ft_io_csv *c, char **buf, size_t *cap, size_t *len)
{
    errno = 0;
    ssize_t n = getline(buf, cap, c->f);
    if (n < 0) {
        if (ferror(c->f))
            return ft_error(FT_E_IO, "cannot read '%s': %s", c->path, strerror(errno ? errno : EIO));
        return 0;
    }
    c->line_no++;
    if (memchr(*buf, '\0', (size_t)n) != NULL)
        return ft_error(FT_E_FORMAT, "%s:%ld: a NUL byte: not a text table", c->path, c->line_no);
    while (n > 0 && ((*buf)[n - 1] == '\n' || (*buf)[n - 1] == '\r'))
        n--;
    (*buf)[n] = '\0';
    *len = (size_t)n;
    return 1;
}

/* Appends one more line to the record (after a line break inside quotes); 1, 0 at the end, < 0 on error. */
static int append_line(ft_io_csv *c)
{
    size_t len = 0;
    int rc = read_line(c, &c->line, &c->line_cap, &len);
    if (rc != 1)
        return rc;
    size_t need = c->rec_len + len + 2;
    if (need > c->rec_cap) {
        size_t cap = need > 2 * c->rec_cap ? need : 2 * c->rec_cap;
        char *r = ft_realloc_array(c->rec, cap, 1);
        if (r == NULL)
            return FT_E_NOMEM;
        c->rec = r;
        c->rec_cap = cap;
    }
    c->rec[c->rec_len++] = '\n';
    memcpy(c->rec + c->rec_len, c->line, len);
    c->rec_len += len;
    c->rec[c->rec_len] = '\0';
    return 1;
}

/* 1 if the record ends inside a quoted field (an odd number of quotes). */
static int quote_open(const char *s)
{
    int open = 0;
    while ((s = strchr(s, '"')) != NULL) {
        open ^= 1;
        s++;
    }
    return open;
}

static int is_skipped(const char *s)
{
    s += strspn(s, " \t");
    return *s == '\0' || *s == '#';
}

/* The next record that is not blank or a comment, quoted line breaks joined; 1, 0 at the end, < 0 on error. */
static int read_record(ft_io_csv *c)
{
    int rc;
    do {
        if ((rc = read_line(c, &c->rec, &c->rec_cap, &c->rec_len)) != 1)
            return rc;
        c->rec_line = c->line_no;
    } while (is_skipped(c->rec));
    while (quote_open(c->rec))
        if ((rc = append_line(c)) != 1)
            return rc < 0 ? rc
                          : ft_error(FT_E_FORMAT, "%s:%ld: a quoted field is not closed before the end of the file",
                                     c->path, c->rec_line);
    return 1;
}

static int push_field(ft_io_csv *c, char *s)
{
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 16;
        char **f = ft_realloc_array(c->fields, cap, sizeof *f);
        if (f == NULL)
            return FT_E_NOMEM;
        c->fields = f;
        c->cap = cap;
    }
    c->fields[c->n++] = s;
    return FT_OK;
}

/* Splits s in place into c->fields: quotes removed, "" turned into ", blanks around fields dropped. */
static int split(ft_io_csv *c, char *s)
{
    const char *blanks = c->sep == '\t' ? " " : " \t";
    const char stop[] = {c->sep, '\0'};
    c->n = 0;
    for (;;) {
        s += strspn(s, blanks);
        char *start = s, *dst = s;
        if (*s == '"') {
            for (s++; *s && !(*s == '"' && s[1] != '"'); s++) {
                s += *s == '"';
                *dst++ = *s;
            }
            if (*s == '"')
                s++;
            s += strspn(s, blanks);
            if (*s != c->sep && *s != '\0')
                return ft_error(FT_E_FORMAT, "%s:%ld: text after the closing quote of field %zu", c->path,
                                c->rec_line, c->n + 1);
        } else {
            s += strcspn(s, stop);
            for (dst = s; dst > start && (dst[-1] == ' ' || (dst[-1] == '\t' && c->sep != '\t')); dst--)
                ;
        }
        int more = *s == c->sep;
        *dst = '\0';
        if (push_field(c, start) != FT_OK)
            return FT_E_NOMEM;
        if (!more)
            return FT_OK;
        s++;
    }
}

static char guess_separator(const char *header)
{
    size_t comma = 0, semi = 0, tab = 0;
    int quoted = 0;
    for (const char *s = header; *s; s++) {
        if (*s == '"')
            quoted = !quoted;
        else if (!quoted && *s == ',')
            comma++;
        else if (!quoted && *s == ';')
            semi++;
        else if (!quoted && *s == '\t')
            tab++;
    }
    if (semi > comma && semi >= tab)
        return ';';
    return tab > comma ? '\t' : ',';
}

/* Reads the header record: the separator, and the column names kept in a copy of their own. */
static int read_header(ft_io_csv *c)
{
    int rc = read_record(c);
    if (rc != 1)
        return rc < 0 ? rc : ft_error(FT_E_EMPTY, "'%s' is empty (no header row)", c->path);
    char *text = c->rec;
    if ((unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB && (unsigned char)text[2] == 0xBF)
        text += 3;
    c->sep = guess_separator(text);
    if ((c->head_text = ft_strdup(text)) == NULL)
        return FT_E_NOMEM;
    if ((rc = split(c, c->head_text)) != FT_OK)
        return rc;
    c->head = c->fields;
    c->nhead = c->n;
    c->fields = NULL;
    c->n = c->cap = 0;
    return FT_OK;
}

int ft_io_csv_open(const char *path, ft_io_csv **out)
{
    if (path == NULL || out == NULL)
        return ft_error(FT_E_INVALID, "ft_io_csv_open: NULL path or out");
    *out = NULL;
    int rc = ft_io_check_readable(path);
    if (rc != FT_OK)
        return rc;
    ft_io_csv *c = ft_calloc(1, sizeof *c);
    if (c == NULL)
        return FT_E_NOMEM;
    c->path = ft_io_is_stdio(path) ? "(stdin)" : path;
    if ((c->f = ft_io_fopen_read(path)) == NULL) {
        rc = ft_error(FT_E_IO, "cannot open '%s': %s", path, strerror(errno));
        free(c);
        return rc;
    }
    if ((rc = read_header(c)) != FT_OK) {
        ft_io_csv_close(c);
        return rc;
    }
    *out = c;
    return FT_OK;
}

size_t ft_io_csv_header(const ft_io_csv *c, char *const **names)
{
    *names = c->head;
    return c->nhead;
}

int ft_io_csv_find(const ft_io_csv *c, const char *name, size_t *col)
{
    for (size_t i = 0; i < c->nhead; i++)
        if (strcasecmp(c->head[i], name) == 0) {
            *col = i;
            return FT_OK;
        }
    char list[1024] = "";
    size_t used = 0;
    for (size_t i = 0; i < c->nhead && used < sizeof list - 1; i++) {
        int k = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", c->head[i]);
        if (k < 0)
            break;
        used += (size_t)k;
    }
    return ft_error(FT_E_FORMAT, "'%s' has no column '%s' (columns: %s)", c->path, name, list);
}

int ft_io_csv_next(ft_io_csv *c, size_t *n, char *const **fields)
{
    int rc = read_record(c);
    if (rc != 1)
        return rc;
    if ((rc = split(c, c->rec)) != FT_OK)
        return rc;
    *n = c->n;
    *fields = c->fields;
    return 1;
}

long ft_io_csv_line(const ft_io_csv *c)
{
    return c->rec_line;
}

char ft_io_csv_separator(const ft_io_csv *c)
{
    return c->sep;
}

int ft_io_csv_number(const ft_io_csv *c, const char *field, double *v)
{
    const char *comma = c != NULL && c->sep == ';' ? strchr(field, ',') : NULL;
    if (comma == NULL || strchr(field, '.') != NULL || strchr(comma + 1, ',') != NULL)
        return ft_io_parse_double(field, v);
    char buf[64];
    size_t len = strlen(field);
    if (len >= sizeof buf)
        return 0;
    memcpy(buf, field, len + 1);
    buf[comma - field] = '.';
    return ft_io_parse_double(buf, v);
}

void ft_io_csv_close(ft_io_csv *c)
{
    if (c == NULL)
        return;
    if (c->f != NULL && c->f != stdin)
        fclose(c->f);
    free(c->line);
    free(c->rec);
    free(c->fields);
    free(c->head_text);
    free(c->head);
    free(c);
}
