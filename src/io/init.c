/* fracterra — io/init.c: one-time GDAL/OGR registration and the error handler of a fracterra call.
 *
 * GDAL must not print to stderr on its own: fracterra's errors name the file and quote GDAL's reason.
 * fracterra is a guest in the host's process: it never replaces the process-wide handler (a QGIS or
 * Python host keeps its own). Every public io function that reaches GDAL runs between ft_io_enter and
 * ft_io_leave, which push and pop a handler on the calling thread's GDAL handler stack (CPLPushErrorHandler,
 * thread-local in GDAL). That handler keeps the last failure (else warning) message of the thread; readers
 * and writers reset it before a GDAL call and append it to their own message on failure, so the host's
 * handler receives no failure or warning of a fracterra call: it gets them through ft_last_error().
 * Debug messages (CPL_DEBUG) are not caught: they pass to the host's handler (or GDAL's default).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include <cpl_error.h>
#include <gdal.h>

#include "io/io_internal.h"

static pthread_once_t io_once = PTHREAD_ONCE_INIT;

static _Thread_local char tl_msg[1024];
static _Thread_local int tl_msg_is_failure;
static _Thread_local int tl_failed;

/* Stores msg on one line: GDAL's multi-line messages (SQL errors) would break "fracterra: cmd: ..." lines. */
static void keep_message(const char *msg)
{
    size_t n = 0;
    for (const char *s = msg; *s && n + 1 < sizeof tl_msg; s++) {
        char c = (*s == '\n' || *s == '\r' || *s == '\t') ? ' ' : *s;
        if (c == ' ' && (n == 0 || tl_msg[n - 1] == ' '))
            continue;
        tl_msg[n++] = c;
    }
    while (n > 0 && tl_msg[n - 1] == ' ')
        n--;
    tl_msg[n] = '\0';
}

static void CPL_STDCALL quiet_handler(CPLErr cls, CPLErrorNum num, const char *msg)
{
    (void)num;
    if (cls == CE_None || cls == CE_Debug || msg == NULL)
        return;
    int failure = cls >= CE_Failure;
    if (failure)
        tl_failed = 1;
    if (failure || !tl_msg_is_failure) {
        keep_message(msg);
        tl_msg_is_failure = failure;
    }
}

static void io_register(void)
{
    GDALAllRegister();
}

void ft_io_init(void)
{
    pthread_once(&io_once, io_register);
}

/* Final: GDAL's driver manager cannot be brought back once destroyed, so no I/O call may follow. */
void ft_io_cleanup(void)
{
    ft_io_init();
    GDALDestroyDriverManager();
    OSRCleanup();
}

void ft_io_enter(void)
{
    ft_io_init();
    CPLPushErrorHandler(quiet_handler);
    CPLSetCurrentErrorHandlerCatchDebug(FALSE);
}

int ft_io_leave(int rc)
{
    CPLPopErrorHandler();
    return rc;
}

void ft_io_gdal_reset(void)
{
    tl_msg[0] = '\0';
    tl_msg_is_failure = 0;
    tl_failed = 0;
    CPLErrorReset();
}

const char *ft_io_gdal_msg(void)
{
    return tl_msg;
}

int ft_io_gdal_failed(void)
{
    return tl_failed;
}

int ft_io_fail(int code, const char *fmt, ...)
{
    char head[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(head, sizeof head, fmt, ap);
    va_end(ap);
    const char *g = tl_msg;
    if (g[0] != '\0' && strstr(head, g) == NULL)
        return ft_error(code, "%s: %s", head, g);
    return ft_error(code, "%s", head);
}
