/* fracterra — export.h: FT_API marks the functions the shared library exports. The library is built with
 * hidden visibility by default, so only what the public headers declare with FT_API is part of the ABI;
 * scripts/check-exports.sh checks that the exported symbols and the FT_API declarations are the same set.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_EXPORT_H
#define FRACTERRA_EXPORT_H

#if defined(_WIN32) || defined(__CYGWIN__)
#  if defined(FT_BUILDING_LIBRARY)
#    define FT_API __declspec(dllexport)
#  elif defined(FT_STATIC)
#    define FT_API
#  else
#    define FT_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) || defined(__clang__)
#  define FT_API __attribute__((visibility("default")))
#else
#  define FT_API
#endif

#endif /* FRACTERRA_EXPORT_H */
