/* fracterra — the library's copy of a caller's options struct (FT_OPTS in core.h).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <string.h>

#include "fracterra/core.h"
#include "internal.h"

int ft_opts_take(void *lib, size_t lib_size, const void *user, const char *type)
{
    if (user == NULL)
        return FT_OK;
    size_t user_size;
    memcpy(&user_size, user, sizeof user_size);
    if (user_size < sizeof(size_t))
        return ft_error(FT_E_INVALID,
                        "%s: struct_size is %zu; initialise the options from the FT_*_OPTS_DEFAULT macro", type,
                        user_size);
    if (user_size > lib_size)
        return ft_error(FT_E_INVALID,
                        "%s: struct_size is %zu bytes, this library's struct has %zu: the caller was built "
                        "against a newer fracterra",
                        type, user_size, lib_size);
    memcpy(lib, user, user_size);
    memcpy(lib, &lib_size, sizeof lib_size);
    return FT_OK;
}
