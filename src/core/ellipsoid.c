/* fracterra — src/core/ellipsoid.c: points of an ellipsoid of revolution as Earth-centred Cartesian
 * coordinates, and the ground length of a degree of longitude and of latitude.
 *
 * Geodetic to ECEF at height 0 (e.g. Hofmann-Wellenhof, Lichtenegger & Wasle 2008, GNSS, eq. 2.25):
 *   N = a / sqrt(1 - e^2 sin^2 phi),  X = N cos phi cos lambda,  Y = N cos phi sin lambda,
 *   Z = N (1 - e^2) sin phi,  with e^2 = f (2 - f).
 * Radius of the parallel N cos phi and of the meridian M = a (1 - e^2) / (1 - e^2 sin^2 phi)^(3/2);
 * a degree of longitude is N cos phi pi/180 metres, a degree of latitude M pi/180 (to first order in the
 * degree, which is what a cell size needs).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/core.h"

#define DEG (3.14159265358979323846 / 180.0)

void ft_ellipsoid_to_ecef(const ft_ellipsoid *e, double lon, double lat, double *X, double *Y, double *Z)
{
    double e2 = e->f * (2.0 - e->f);
    double sp = sin(lat * DEG), cp = cos(lat * DEG);
    double n = e->a / sqrt(1.0 - e2 * sp * sp);
    *X = n * cp * cos(lon * DEG);
    *Y = n * cp * sin(lon * DEG);
    *Z = n * (1.0 - e2) * sp;
}

void ft_ellipsoid_metres_per_degree(const ft_ellipsoid *e, double lat, double *per_lon, double *per_lat)
{
    double e2 = e->f * (2.0 - e->f);
    double sp = sin(lat * DEG), w2 = 1.0 - e2 * sp * sp;
    double n = e->a / sqrt(w2);
    if (per_lon)
        *per_lon = n * cos(lat * DEG) * DEG;
    if (per_lat)
        *per_lat = e->a * (1.0 - e2) / (w2 * sqrt(w2)) * DEG;
}
