/*
 * grid.c - gmmrrtd's local occupancy grid (channel GRID, occupancy_grid_t; docs/world.md,
 * "A local grid"), for an integrator whose perception already makes a costmap. While grids
 * arrive, the latest one REPLACES the static map as the raster planned in (the integrator's
 * costmap is taken to hold the static layer too); scans then mark the grid until the next one.
 * The raster is allocated once at start-up at the wire's capacity (MAX_CELLS cells, sides up to
 * GMMRRT_MAX_RASTER_SIDE), so no grid the decoder accepts can need more, and a grid is written
 * into it only once it has been validated (lcmtypes' decoder, then the side check here): a
 * malformed grid is counted and the last good one stays. Cells: -1 unknown (blocks while
 * map_unknown_blocked), values >= grid_occupied occupied, lower values free (kept as map_server's
 * scale values, which do not block). A grid older than grid_timeout_ms stops the robot
 * (STALE_GRID, cycle.c).
 */
#include <stdio.h>
#include <stdlib.h>

#include "daemon.h"

#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

/* The grid raster's capacity: the wire's (a side is at most the raster's ceiling). */
#define GRID_MAX_CELLS GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS
#define GRID_MAX_SIDE (GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS < GMMRRT_MAX_RASTER_SIDE ? GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS \
                                                                                 : GMMRRT_MAX_RASTER_SIDE)

int gmmrrtd_grid_setup(gmmrrtd_t *d)
{
    const size_t size = gmmrrt_raster_mem_size(GRID_MAX_CELLS, GRID_MAX_SIDE);
    d->grid_mem = aligned_alloc(64, (size + 63u) / 64u * 64u);
    if (d->grid_mem == NULL || gmmrrt_raster_init(&d->grid, d->grid_mem, size, GRID_MAX_CELLS, GRID_MAX_SIDE) != GMMRRT_OK) {
        LOG_ERROR("cannot set up the grid raster (%zu bytes for %d cells)", size, (int)GRID_MAX_CELLS);
        free(d->grid_mem);
        d->grid_mem = NULL;
        return -1;
    }
    return 0;
}

int gmmrrtd_grid_check(gmmrrtd_t *d, const gmmrrt_occupancy_grid_t *g)
{
    if (d->grid_mem == NULL) {
        gmmrrtd_reject(d, GMMRRTD_IN_GRID, ST(REJECT_BAD_VALUE), "grid at %lld: no grid raster was set up",
                       (long long)g->utime);
        return 0;
    }
    if (g->width > GRID_MAX_SIDE || g->height > GRID_MAX_SIDE) {
        gmmrrtd_reject(d, GMMRRTD_IN_GRID, ST(REJECT_COUNT_OVER_BOUND),
                       "occupancy_grid_t: %d x %d cells: a side above %d cells", (int)g->width, (int)g->height,
                       (int)GRID_MAX_SIDE);
        return 0;
    }
    return 1;
}

void gmmrrtd_grid_apply(gmmrrtd_t *d)
{
    const gmmrrt_occupancy_grid_t *g = &d->staged.m.grid;
    gmmrrt_raster_t *r = &d->grid;
    /* Checked at decode (decoder and gmmrrtd_grid_check), so the raster takes it. */
    if (gmmrrt_raster_set_geometry(r, g->width, g->height, g->resolution_m, g->origin_x, g->origin_y, g->origin_yaw,
                                   d->set.map_unknown_blocked) != GMMRRT_OK) {
        gmmrrtd_reject(d, GMMRRTD_IN_GRID, ST(REJECT_BAD_VALUE),
                       "grid at %lld: the raster refused its geometry (the last good grid stays)", (long long)g->utime);
        return;
    }
    const int8_t occ = (int8_t)d->set.grid_occupied;
    for (int32_t k = 0; k < g->num_cells; ++k) {
        const int8_t v = g->data[k];
        r->cells[k] = v < 0 ? GMMRRT_RASTER_UNKNOWN : v >= occ ? GMMRRT_RASTER_OCCUPIED : (uint8_t)v;
    }
    (void)gmmrrt_raster_update_distance(r, 0, 0.0); /* no marks yet: O(cells), at most MAX_CELLS */
    if (!d->have_grid)
        LOG_INFO("grid: %d x %d cells at %g m, origin (%g, %g, %g): planning in the grid from now on",
                 (int)g->width, (int)g->height, g->resolution_m, g->origin_x, g->origin_y, g->origin_yaw);
    d->have_grid = 1;
    d->grid_version++;
}
