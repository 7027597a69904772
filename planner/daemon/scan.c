/*
 * scan.c - gmmrrtd's laser scans (channel SCAN, planar_scan_t; docs/world.md, "Scans in
 * gmmrrtd"). A scan is stamped when it was taken, usually a little before the pose that
 * brackets it arrives, so the daemon keeps a ring of the last GMMRRTD_POSE_RING robot poses
 * and places each scan with the pose interpolated at its utime (position linearly, heading
 * along the shorter arc), composed with the sensor's mount on the robot. A scan stamped before
 * every pose in the ring is refused (REJECT_TIME_BACKWARDS), and so is one stamped more than
 * scan_pose_gap_ms after the newest pose (REJECT_TIME_FUTURE); one within that gap is placed at
 * the newest pose. Scans and poses are compared on their own stamps: both come from the robot's
 * clock (as tf compares stamps).
 *
 * A placed scan marks and clears the raster planned in (gmmrrt_raster_apply_scan: cells along
 * each beam cleared of marks, the end cell marked, as a costmap's obstacle layer; NaN, inf and
 * out-of-range ranges do nothing). At most scan_max_per_cycle scans are integrated between two
 * cycles; the rest of a flood is dropped, counted as REJECT_COUNT_OVER_BOUND (the count of
 * one cycle's scans over its bound) and logged. The field is not computed per
 * scan but once per cycle, over the problem's bounds only (gmmrrtd_world_prepare), so a cycle's
 * extra work depends on the bounds and scan_reach_m, not on the map's size or the scan rate.
 */
#include <math.h>
#include <stdio.h>

#include "daemon.h"

#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

void gmmrrtd_scan_add_pose(gmmrrtd_t *d, const gmmrrt_pose2d_t *pose)
{
    /* The ring stays sorted by stamp: a pose stamped before the newest (accepted only when its
     * source's clock stepped back, clock.h) starts a new history. */
    if (d->pose_ring_n > 0 &&
        pose->utime < d->pose_ring[(d->pose_ring_next + GMMRRTD_POSE_RING - 1) % GMMRRTD_POSE_RING].utime)
        d->pose_ring_n = 0;
    d->pose_ring[d->pose_ring_next] = (gmmrrtd_pose_sample_t){pose->utime, pose->x, pose->y, pose->yaw};
    d->pose_ring_next = (d->pose_ring_next + 1) % GMMRRTD_POSE_RING;
    if (d->pose_ring_n < GMMRRTD_POSE_RING)
        d->pose_ring_n++;
}

/* The k-th oldest pose of the ring (k = 0 the oldest); sorted by stamp (above). */
static const gmmrrtd_pose_sample_t *ring_at(const gmmrrtd_t *d, int32_t k)
{
    const int32_t oldest = (d->pose_ring_next - d->pose_ring_n + GMMRRTD_POSE_RING) % GMMRRTD_POSE_RING;
    return &d->pose_ring[(oldest + k) % GMMRRTD_POSE_RING];
}

gmmrrt_raster_t *gmmrrtd_world_raster(gmmrrtd_t *d)
{
    if (d->have_grid)
        return &d->grid;
    return d->have_map ? &d->map : NULL;
}

int gmmrrtd_scan_place(gmmrrtd_t *d, const gmmrrt_planar_scan_t *scan)
{
    if (gmmrrtd_world_raster(d) == NULL) {
        gmmrrtd_reject(d, GMMRRTD_IN_SCAN, ST(REJECT_BAD_VALUE),
                       "scan at %lld: no map or grid to mark it in ([world] map, or a GRID message first)",
                       (long long)scan->utime);
        return 0;
    }
    if (d->pose_ring_n == 0 || scan->utime < ring_at(d, 0)->utime) {
        gmmrrtd_reject(d, GMMRRTD_IN_SCAN, ST(REJECT_TIME_BACKWARDS),
                       "scan at %lld is stamped before every robot pose kept (%s %lld): cannot place it",
                       (long long)scan->utime, d->pose_ring_n ? "oldest" : "none yet",
                       d->pose_ring_n ? (long long)ring_at(d, 0)->utime : 0LL);
        return 0;
    }
    const gmmrrtd_pose_sample_t *newest = ring_at(d, d->pose_ring_n - 1);
    double x, y, yaw;
    if (scan->utime >= newest->utime) {
        const double ahead_ms = (double)(scan->utime - newest->utime) * 1e-3;
        if (ahead_ms > d->set.scan_pose_gap_ms) {
            gmmrrtd_reject(d, GMMRRTD_IN_SCAN, ST(REJECT_TIME_FUTURE),
                           "scan at %lld is %.1f ms after the newest robot pose (limit scan_pose_gap_ms = %g): "
                           "cannot place it",
                           (long long)scan->utime, ahead_ms, d->set.scan_pose_gap_ms);
            return 0;
        }
        x = newest->x;
        y = newest->y;
        yaw = newest->yaw;
    } else {
        /* The newest pose at or before the stamp and the one after it (a short ring: linear). */
        int32_t k = d->pose_ring_n - 2;
        while (k > 0 && ring_at(d, k)->utime > scan->utime)
            --k;
        const gmmrrtd_pose_sample_t *a = ring_at(d, k), *b = ring_at(d, k + 1);
        const double span = (double)(b->utime - a->utime);
        const double t = span > 0.0 ? (double)(scan->utime - a->utime) / span : 1.0;
        x = a->x + t * (b->x - a->x);
        y = a->y + t * (b->y - a->y);
        yaw = a->yaw + t * remainder(b->yaw - a->yaw, 2.0 * M_PI);
    }
    const double c = cos(yaw), s = sin(yaw);
    d->staged.sensor_x = x + c * scan->sensor_x - s * scan->sensor_y;
    d->staged.sensor_y = y + s * scan->sensor_x + c * scan->sensor_y;
    d->staged.sensor_yaw = yaw + scan->sensor_yaw;
    return 1;
}

void gmmrrtd_scan_apply(gmmrrtd_t *d)
{
    const gmmrrt_planar_scan_t *m = &d->staged.m.scan;
    gmmrrt_raster_t *r = gmmrrtd_world_raster(d);
    if (r == NULL)
        return; /* placed against a raster that a reload has since removed */
    if (d->scans_this_cycle >= d->set.scan_max_per_cycle) {
        /* A count over its bound: the scans of one cycle. The newest scans get through next cycle. */
        d->scans_dropped++;
        gmmrrtd_reject(d, GMMRRTD_IN_SCAN, ST(REJECT_COUNT_OVER_BOUND),
                       "scan at %lld dropped: more than scan_max_per_cycle = %d scans since the last cycle (a flood)",
                       (long long)m->utime, (int)d->set.scan_max_per_cycle);
        return;
    }
    const gmmrrt_scan_t scan = {m->rad0, m->radstep, m->range_min_m, m->range_max_m, m->num_ranges, m->ranges};
    int32_t marked = 0, cleared = 0;
    const gmmrrt_status_t st = gmmrrt_raster_apply_scan(r, &scan, d->staged.sensor_x, d->staged.sensor_y,
                                                        d->staged.sensor_yaw, m->utime, &marked, &cleared);
    if (st != GMMRRT_OK) {
        /* The marks' 32-bit millisecond clock (raster.h): a scan before the first mark or 49
         * days after it. The raster is unchanged. */
        gmmrrtd_reject(d, GMMRRTD_IN_SCAN, ST(REJECT_BAD_VALUE), "scan at %lld refused by the raster: %s",
                       (long long)m->utime, gmmrrt_status_str(st));
        return;
    }
    d->scans_this_cycle++;
    d->scans_applied++;
    if (marked == 0 && cleared == 0) {
        /* Valid ("no return" is what a lidar says of open space), but a lidar that says nothing
         * else for long is blind: worth a line. It marks and clears nothing. */
        d->scans_blind++;
        gmmrrtd_log_limited(&d->rl[GMMRRTD_IN_SCAN][ST(REJECT_NOT_FINITE)], gmmrrtd_mono_us() / 1000,
                            (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_WARN,
                            "scan at %lld has no return (%lld such scans): every range NaN, inf or out of range; "
                            "the marks stay as they were",
                            (long long)m->utime, (long long)d->scans_blind);
    }
    d->scan_cells_marked += marked;
    d->scan_cells_cleared += cleared;
    if (m->utime > d->scan_last_utime)
        d->scan_last_utime = m->utime;
}

gmmrrt_status_t gmmrrtd_world_prepare(gmmrrtd_t *d, int64_t now_us)
{
    gmmrrt_raster_t *r = gmmrrtd_world_raster(d);
    d->scans_this_cycle = 0;
    if (r == NULL)
        return GMMRRT_OK;
    if (r->mark_epoch_utime < 0)
        return GMMRRT_OK; /* no scan yet: the field of the last load (map or grid) covers all */
    /* The marks' time: the newest scan's stamp plus the local time since it arrived. Stale scans
     * with scan_stale_stop = 0: a time after every mark's decay, so none counts. */
    int64_t now_scan;
    if ((d->stale_mask & ST(STALE_SCAN)) && !d->set.scan_stale_stop)
        now_scan = GMMRRTD_MAX_UTIME;
    else {
        int64_t age = gmmrrtd_clock_age_us(&d->src[GMMRRTD_IN_SCAN], now_us);
        if (age > GMMRRTD_MAX_UTIME)
            age = GMMRRTD_MAX_UTIME;
        now_scan = d->scan_last_utime + age;
    }
    const gmmrrt_bounds_t *b = &d->problem.obstacles.bounds;
    return gmmrrt_raster_update_distance_window(r, now_scan, d->set.scan_decay_ms, b->xmin, b->ymin, b->xmax, b->ymax,
                                                d->set.scan_reach_m);
}
