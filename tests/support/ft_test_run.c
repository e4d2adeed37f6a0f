/* fracterra — tests/support/ft_test_run.c: fork/exec of the fracterra binary with captured output, and
 * small file-system helpers for the end-to-end tests.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "ft_test_run.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef FT_BIN
#error "FT_BIN (path of the built fracterra binary) must be defined"
#endif

#define FT_RUN_MAX_ARGS 64

typedef struct {
    char *data;
    size_t len, cap;
} buffer;

static int buffer_read(buffer *b, int fd)
{
    if (b->cap - b->len < 4096) {
        size_t cap = b->cap ? b->cap * 2 : 8192;
        char *p = realloc(b->data, cap);
        if (p == NULL)
            return -1;
        b->data = p;
        b->cap = cap;
    }
    ssize_t n = read(fd, b->data + b->len, b->cap - b->len - 1);
    if (n > 0)
        b->len += (size_t)n;
    return (int)n;
}

static void buffer_finish(buffer *b, char **s, size_t *len)
{
    if (b->data == NULL)
        b->data = calloc(1, 1);
    else
        b->data[b->len] = '\0';
    *s = b->data;
    *len = b->len;
}

/* Reads both pipes until they close (poll, so that a full stderr pipe cannot block stdout). */
static void drain(int out_fd, int err_fd, buffer *out, buffer *err)
{
    struct pollfd fds[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
    int open_fds = 2;
    while (open_fds > 0) {
        if (poll(fds, 2, -1) < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        for (int i = 0; i < 2; i++) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            if (buffer_read(i == 0 ? out : err, fds[i].fd) <= 0) {
                close(fds[i].fd);
                fds[i].fd = -1;
                open_fds--;
            }
        }
    }
}

static void child(const char *const *argv, int out_fd, int err_fd)
{
    char *args[FT_RUN_MAX_ARGS + 2];
    size_t n = 0;
    args[n++] = (char *)FT_BIN;
    for (; argv[n - 1] && n <= FT_RUN_MAX_ARGS; n++)
        args[n] = (char *)argv[n - 1];
    args[n] = NULL;
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0)
        dup2(devnull, STDIN_FILENO);
    dup2(out_fd, STDOUT_FILENO);
    dup2(err_fd, STDERR_FILENO);
    execv(FT_BIN, args);
    _exit(127);
}

int ft_run_argv(ft_run_result *r, const char *const *argv)
{
    int po[2], pe[2];
    memset(r, 0, sizeof *r);
    if (pipe(po) != 0)
        return -1;
    if (pipe(pe) != 0) {
        close(po[0]);
        close(po[1]);
        return -1;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        close(po[0]);
        close(pe[0]);
        child(argv, po[1], pe[1]);
    }
    close(po[1]);
    close(pe[1]);
    buffer out = {0}, err = {0};
    drain(po[0], pe[0], &out, &err);
    buffer_finish(&out, &r->out, &r->out_len);
    buffer_finish(&err, &r->err, &r->err_len);
    int st = 0;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
        ;
    if (WIFSIGNALED(st)) {
        r->signaled = 1;
        r->status = 128 + WTERMSIG(st);
    } else {
        r->status = WEXITSTATUS(st);
    }
    return 0;
}

int ft_run(ft_run_result *r, ...)
{
    const char *argv[FT_RUN_MAX_ARGS + 1];
    size_t n = 0;
    va_list ap;
    va_start(ap, r);
    const char *a;
    while ((a = va_arg(ap, const char *)) != NULL && n < FT_RUN_MAX_ARGS)
        argv[n++] = a;
    va_end(ap);
    argv[n] = NULL;
    return ft_run_argv(r, argv);
}

void ft_run_free(ft_run_result *r)
{
    free(r->out);
    free(r->err);
    memset(r, 0, sizeof *r);
}

json_object *ft_run_json(const ft_run_result *r)
{
    if (r->out == NULL)
        return NULL;
    json_tokener *tok = json_tokener_new();
    json_object *o = json_tokener_parse_ex(tok, r->out, (int)r->out_len);
    size_t used = (size_t)json_tokener_get_parse_end(tok);
    json_tokener_free(tok);
    if (o == NULL || !json_object_is_type(o, json_type_object)) {
        json_object_put(o);
        return NULL;
    }
    for (size_t i = used; i < r->out_len; i++) {
        if (r->out[i] != ' ' && r->out[i] != '\n' && r->out[i] != '\t' && r->out[i] != '\r') {
            json_object_put(o); /* more than one object, or trailing text */
            return NULL;
        }
    }
    return o;
}

char *ft_test_mkdtemp(void)
{
    char *d = strdup("/tmp/fracterra-test-XXXXXX");
    if (d && mkdtemp(d) == NULL) {
        free(d);
        return NULL;
    }
    return d;
}

char *ft_test_path(const char *dir, const char *name)
{
    size_t size = strlen(dir) + strlen(name) + 2;
    char *p = malloc(size);
    if (p)
        snprintf(p, size, "%s/%s", dir, name);
    return p;
}

void ft_test_rmtree(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL) {
        unlink(dir);
        return;
    }
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char *p = ft_test_path(dir, e->d_name);
        struct stat st;
        if (p && lstat(p, &st) == 0 && S_ISDIR(st.st_mode))
            ft_test_rmtree(p);
        else if (p)
            unlink(p);
        free(p);
    }
    closedir(d);
    rmdir(dir);
}

int ft_test_write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        return -1;
    int bad = fwrite(data, 1, size, f) != size;
    bad |= fclose(f) != 0;
    return bad ? -1 : 0;
}

int ft_test_write_text(const char *path, const char *text)
{
    return ft_test_write_file(path, text, strlen(text));
}

char *ft_test_read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    buffer b = {0};
    int n;
    while ((n = buffer_read(&b, fileno(f))) > 0)
        ;
    fclose(f);
    char *s;
    size_t len;
    buffer_finish(&b, &s, &len);
    if (size)
        *size = len;
    return s;
}

int ft_test_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

int ft_test_count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    closedir(d);
    return n;
}
