/* fracterra — core/version.c: the library's version string, CMake's project() version (passed in as
 * FT_BUILD_VERSION_*; the same values generate the installed fracterra/version.h). The FT_VERSION_*
 * macros that core.h declares must agree with it: a compile-time check, so the two cannot drift.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/core.h"

#ifndef FT_BUILD_VERSION_STRING
#error "FT_BUILD_VERSION_* are set by CMakeLists.txt from project(fracterra VERSION ...)"
#endif

_Static_assert(FT_VERSION_MAJOR == FT_BUILD_VERSION_MAJOR && FT_VERSION_MINOR == FT_BUILD_VERSION_MINOR &&
                   FT_VERSION_PATCH == FT_BUILD_VERSION_PATCH,
               "FT_VERSION_* in fracterra/core.h differ from project(fracterra VERSION ...) in CMakeLists.txt");

const char *ft_version(void)
{
    return FT_BUILD_VERSION_STRING;
}
