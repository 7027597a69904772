/*
 * world.c - gmmrrtd's static map ([world] map, docs/world.md): a map_server YAML + PGM/PNG
 * read by gmmrrt_map_load_file into one raster whose memory is sized once at start-up from
 * [world] map_max_cells / map_max_side (a larger map is refused with the numbers, never cut).
 * Every cycle's problem borrows it (cycle.c); the collision world reads only the cells around
 * the points the search visits inside the problem's bounds. The loader changes the raster
 * only on success, so a bad or missing file on SIGHUP keeps the old map running, is counted
 * in planner_status_t.rejected[REJECT_MODEL_RELOAD] (the reload reason shared with the
 * models: an operator's reload that was refused) and logged every time, like a model.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon.h"
#include "gmmrrt/map_file.h"

static int setup(gmmrrtd_t *d)
{
    const size_t size = gmmrrt_raster_mem_size(d->set.map_max_cells, d->set.map_max_side);
    if (size == 0) {
        LOG_ERROR("map raster: capacity %d cells, %d a side is out of range", (int)d->set.map_max_cells,
                  (int)d->set.map_max_side);
        return -1;
    }
    d->map_mem = aligned_alloc(64, (size + 63u) / 64u * 64u);
    if (d->map_mem == NULL) {
        LOG_ERROR("cannot allocate the map raster (%zu bytes for %d cells)", size, (int)d->set.map_max_cells);
        return -1;
    }
    if (gmmrrt_raster_init(&d->map, d->map_mem, size, d->set.map_max_cells, d->set.map_max_side) != GMMRRT_OK) {
        LOG_ERROR("map raster init refused %d cells, %d a side", (int)d->set.map_max_cells, (int)d->set.map_max_side);
        return -1;
    }
    d->map_capacity_cells = d->set.map_max_cells;
    d->map_capacity_side = d->set.map_max_side;
    return 0;
}

int gmmrrtd_world_load(gmmrrtd_t *d, int reload)
{
    const char *path = d->set.map;
    if (path[0] == '\0') {
        if (d->have_map)
            LOG_INFO("map removed by the new configuration");
        d->have_map = 0;
        return 0;
    }
    if (d->map_mem == NULL) {
        if (reload) {
            /* Memory is sized at start-up only: a map first configured by a reload waits. */
            d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD]++;
            LOG_ERROR("reload rejected (total %lld): map %s: the daemon was started without a map, so no map raster "
                      "was allocated; restart to use one",
                      (long long)d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD], path);
            return -1;
        }
        if (setup(d) != 0)
            return -1;
    }
    char err[768];
    const gmmrrt_status_t st = gmmrrt_map_load_file(path, d->set.map_unknown_blocked, &d->map, err, sizeof err);
    if (st != GMMRRT_OK) {
        if (!reload) {
            if (st == GMMRRT_ERR_BUFFER_TOO_SMALL)
                LOG_ERROR("map: %s; the raster is sized by [world] map_max_cells = %d and map_max_side = %d",
                          err, (int)d->map_capacity_cells, (int)d->map_capacity_side);
            else
                LOG_ERROR("map: %s (%s)", err, gmmrrt_status_str(st));
            return -1;
        }
        d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD]++;
        d->status.last_error = (int32_t)st;
        LOG_ERROR("reload rejected (total %lld): map: %s (%s)%s",
                  (long long)d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD], err,
                  gmmrrt_status_str(st), d->have_map ? " (old map kept)" : "");
        return -1;
    }
    d->have_map = 1;
    d->last.valid = 0; /* the last plan was made in another world */
    LOG_INFO("map %s: %d x %d cells at %g m, origin (%g, %g, %g)", path, (int)d->map.width, (int)d->map.height,
             d->map.resolution_m, d->map.origin_x, d->map.origin_y, d->map.origin_yaw);
    return 0;
}
