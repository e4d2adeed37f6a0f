/* fracterra — core/version.c: the library's version string.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/core.h"

const char *ft_version(void)
{
    return FT_VERSION_STRING;
}
