/* fracterra — fractal geometry of maps. Includes every public header.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_H
#define FRACTERRA_H

#include "contour.h"
#include "core.h"
#include "io.h"
#include "line.h"
#include "render.h"
#include "surface.h"
#include "terrain.h"
#include "urban.h"

#endif /* FRACTERRA_H */
