/* fracterra — cli/cli_geo.h: what the commands do with the CRS of their input (docs/geographic.md). The CRS
 * service (ft_io_crs_info) says whether coordinates are degrees; lines are then walked on the ellipsoid
 * (ft_line_dim_opts.ellipsoid), and what needs a plane (boxes, grids, points, tolerances) is measured in a
 * local projection centred on the data, named in the output.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_GEO_H
#define FRACTERRA_CLI_GEO_H

#include "cli.h"

/** The CRS of path (its WKT): CLI_CONTINUE, or CLI_FAIL with the message printed. */
int cli_geo_crs(const cli_command *cmd, const char *path, const char *wkt, ft_crs_info *crs);
/** Sets r's units from the CRS ("m" for geographic input and metre CRSs, "ft", ...); without a CRS adds the
 *  warning that the scales are in the data's own, unknown unit. Nothing if r already has units. */
void cli_geo_units(ft_dim_result *r, const ft_crs_info *crs);
/** The WKT (malloc'd) of a local projection centred on (lon0, lat0) on the datum of wkt. CLI_CONTINUE or
 *  CLI_FAIL (printed). */
int cli_geo_local_crs(const cli_command *cmd, const char *wkt, ft_local_projection kind, double lon0, double lat0,
                      char **local);
/** A copy of a layer in degrees projected to a local projection of the given kind centred on its extent
 *  (on the antimeridian for data crossing it; refused, printed, beyond 180 degrees of longitude).
 *  CLI_CONTINUE or CLI_FAIL (printed). */
int cli_geo_layer_local(const cli_command *cmd, const char *path, const ft_layer *l, ft_local_projection kind,
                        ft_layer **out);
/** The CRS of a layer read from path; a layer in degrees is reprojected in place to a local projection of
 *  the given kind centred on its extent (its CRS becomes that projection; crs keeps the input's).
 *  CLI_CONTINUE or CLI_FAIL (printed). */
int cli_geo_layer_ground(const cli_command *cmd, const char *path, ft_layer *l, ft_local_projection kind,
                         ft_crs_info *crs);
/** The same for points: in degrees they are projected in place to a local transverse Mercator centred on
 *  their extent. CLI_CONTINUE or CLI_FAIL (printed). */
int cli_geo_points_ground(const cli_command *cmd, const char *path, ft_points *p, ft_crs_info *crs);
/** A grid in degrees warped to a local transverse Mercator centred on it, square cells of the geometric mean
 *  of its ground cell sizes at its centre (bilinear). CLI_CONTINUE or CLI_FAIL (printed). */
int cli_geo_grid_local(const cli_command *cmd, const ft_grid *g, ft_grid **out);
/** The CRS of a grid read from path; a grid in degrees is replaced by its warp to a local transverse
 *  Mercator in metres (cli_geo_grid_local), so that lags, wavelengths, directions and trends are on the
 *  ground. CLI_CONTINUE or CLI_FAIL (printed). */
int cli_geo_grid_ground(const cli_command *cmd, const char *path, ft_grid **g, ft_crs_info *crs);
/** Warns that a lon/lat grid's voids are filled in its own cells (reconstruct, fill): "PATH is in
 *  longitude/latitude (CRS): its cells are DX m x DY m on the ground, and the voids are filled as if they were
 *  square ...", DX and DY at the grid's middle latitude. */
void cli_geo_warn_square_cells(const cli_command *cmd, const char *path, const ft_grid *g, const ft_crs_info *crs);
/** A JSON description of how a geographic input was measured: {"crs", "ellipsoid", "projection"} (projection
 *  may be NULL: walked on the ellipsoid). */
json_object *cli_geo_json(const ft_crs_info *crs, const char *projection_wkt);
/** Refuses a geographic input: "PATH is in longitude/latitude (CRS): WHY; reproject it first (HOW)". Returns
 *  CLI_FAIL. */
int cli_geo_refuse(const cli_command *cmd, const char *path, const ft_crs_info *crs, const char *why,
                   const char *how);

#endif /* FRACTERRA_CLI_GEO_H */
