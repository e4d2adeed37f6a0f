/* fracterra — core/error.c: the thread-local last error (code + message) and generic code descriptions.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/core.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define FT_ERROR_MSG_SIZE 1024

static _Thread_local int tl_code = FT_OK;
static _Thread_local char tl_msg[FT_ERROR_MSG_SIZE];

const char *ft_last_error(void)
{
    return tl_msg;
}

int ft_last_error_code(void)
{
    return tl_code;
}

const char *ft_strerror(int code)
{
    switch (code) {
    case FT_OK: return "success";
    case FT_E_INVALID: return "invalid argument";
    case FT_E_NOMEM: return "out of memory";
    case FT_E_IO: return "input/output error";
    case FT_E_FORMAT: return "unexpected file content";
    case FT_E_EMPTY: return "no data";
    case FT_E_CANCELLED: return "cancelled";
    case FT_E_NUMERIC: return "non-finite value or numerically degenerate case";
    case FT_E_UNSUPPORTED: return "not supported by this build";
    default: return "unknown error";
    }
}

/* Formats into a local buffer first, so that callers may pass ft_last_error() as an argument to add
 * context to the previous message ("reading x.tif: %s"). */
int ft_error(int code, const char *fmt, ...)
{
    char buf[FT_ERROR_MSG_SIZE];
    if (fmt == NULL) {
        snprintf(buf, sizeof buf, "%s", ft_strerror(code));
    } else {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(buf, sizeof buf, fmt, ap);
        va_end(ap);
        if (n < 0)
            snprintf(buf, sizeof buf, "%s", ft_strerror(code));
    }
    memcpy(tl_msg, buf, sizeof buf);
    tl_code = code;
    return code;
}

void ft_clear_error(void)
{
    tl_code = FT_OK;
    tl_msg[0] = '\0';
}
