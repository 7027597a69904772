/*
 * raster_exact.hpp - exact collision tests of a robot disc against the blocked cells of an
 * occupancy raster (raster.h), for the OMPL side of the map scene of gmmrrt-bench-all and for
 * re-checking both sides' paths there.
 *
 * What "free" means (the same rule as the planner's raster layer, docs/world.md, "Maps"): a cell
 * blocks when it is OCCUPIED, or UNKNOWN while the raster's unknown_blocked is 1, or lies outside
 * the raster while unknown_blocked is 1; a blocked cell is its closed square. The disc of radius
 * r centred at a point is free when every blocked square is further than r from the point; a
 * straight motion is free when every blocked square is further than r from the segment (the
 * swept disc). These are exact (closed-form point/segment-to-square distances over every cell
 * the disc can reach), not sampled. The planner's own bound reads the distance field between
 * cell centres and is conservative by up to about a cell, so the planner's free space is a
 * subset of this one: OMPL gets the larger free space. Scan marks are not used here.
 */
#ifndef GMMRRT_BENCH_RASTER_EXACT_HPP
#define GMMRRT_BENCH_RASTER_EXACT_HPP

#include "gmmrrt/raster.h"

namespace gmmrrt_bench {

/* 1 when cell (i, j) blocks (outside the raster: unknown_blocked). */
bool raster_cell_blocks(const gmmrrt_raster_t &r, long i, long j);

/* True when the disc of radius_m at world (x, y) is further than radius_m from every blocked cell. */
bool raster_disc_free(const gmmrrt_raster_t &r, double radius_m, double x, double y);

/* True when the disc of radius_m swept along the world segment (x0, y0) -> (x1, y1) is free. */
bool raster_motion_free(const gmmrrt_raster_t &r, double radius_m, double x0, double y0, double x1, double y1);

} // namespace gmmrrt_bench

#endif
