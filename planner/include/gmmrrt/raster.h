/*
 * raster.h - an occupancy raster of the robot's world (a static map as 2-D SLAM tools write
 * it, plus what range scans mark and clear) and its Euclidean distance field, which the
 * collision world (collision.h) reads as one more static layer. docs/world.md.
 *
 * Frame: cell (i, j) (i along x, j along y, row-major j * width + i) is the square whose lower
 * left corner is at (i res, j res) in the raster frame; the raster frame's origin is the
 * world pose (origin_x, origin_y, origin_yaw) (as map_server's `origin`: the pose of the
 * lower-left corner of cell (0, 0); an image's top row is the raster's row height - 1).
 *
 * A cell blocks when it is occupied (GMMRRT_RASTER_OCCUPIED), unknown (GMMRRT_RASTER_UNKNOWN)
 * while unknown_blocked is 1, or marked by a scan within the decay time. Everything outside the
 * raster is unknown. Values 1..99 (map_server's scale mode between its thresholds) do not block.
 *
 * Memory: caller-owned, sized once (gmmrrt_raster_mem_size) from the largest raster the
 * configuration allows; a larger one is refused (GMMRRT_ERR_BUFFER_TOO_SMALL), never cut.
 * Nothing here allocates. The distance field (Felzenszwalb & Huttenlocher 2012, "Distance
 * Transforms of Sampled Functions", exact squared Euclidean distance in two 1-D passes) is
 * O(width x height). It is sampled at the cells' corners, where the distance to the blocked
 * cells' squares is the distance to the nearest corner of a blocked cell (raster.c says why),
 * so it is exact there, not only to the cell.
 */
#ifndef GMMRRT_RASTER_H
#define GMMRRT_RASTER_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/limits.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GMMRRT_RASTER_FREE 0
#define GMMRRT_RASTER_OCCUPIED 100
#define GMMRRT_RASTER_UNKNOWN 255

/* Fields are read-only for the caller except through the functions below. */
typedef struct gmmrrt_raster {
    int32_t max_cells, max_side; /* capacity fixed at init */
    int32_t width, height;       /* cells */
    double resolution_m;         /* cell edge, m */
    double inv_resolution_m;     /* 1 / resolution_m, set with it: world to cells by a product */
    double origin_x, origin_y, origin_yaw; /* m, m, rad: world pose of cell (0, 0)'s lower-left corner */
    double cos_yaw, sin_yaw;
    int32_t unknown_blocked;     /* 1: unknown cells (and the outside) block; 0: they are free */
    int32_t distance_ready;      /* 1 when dist[] describes cells[] and the marks */
    uint32_t generation;         /* changes with every edit of cells, marks or the field */
    int64_t mark_epoch_utime;    /* utime of mark value 1; -1 before the first scan */
    double field_now_ms, field_decay_ms; /* the time (ms since the epoch) and decay of the field */
    int32_t valid_i0, valid_i1, valid_j0, valid_j1; /* corners where dist[] holds (exclusive ends) */
    uint8_t *cells;              /* width x height: FREE, OCCUPIED, UNKNOWN or 1..99 */
    uint32_t *marks;             /* scan marks: ms since the epoch + 1 of the last hit, 0 none */
    float *dist;                 /* (width + 1) x (height + 1), row-major j * (width + 1) + i: m
                                    from corner (i, j) (raster-frame point (i res, j res)) to the
                                    nearest blocked cell's square, the outside's too when it
                                    blocks (rounded down); a huge value when nothing blocks */
    double *scratch_f, *scratch_d, *scratch_z; /* max_side + 2 each (z one more): the 1-D transform */
    int32_t *scratch_v;
} gmmrrt_raster_t;

/* Bytes for a raster of at most max_cells cells and max_side cells a side (the cells, their
 * scan marks, the field at every corner of the largest such raster, and the transform's
 * scratch); 0 when either is < 1, max_side > GMMRRT_MAX_RASTER_SIDE or max_cells >
 * GMMRRT_MAX_RASTER_CELLS. */
size_t gmmrrt_raster_mem_size(int32_t max_cells, int32_t max_side);

/* Bytes the cells, marks and field of one width x height raster take (the figure a refusal of
 * an oversize map names); doubles, so sides from a file's header that overflow any integer
 * still give a figure. */
double gmmrrt_raster_bytes(double width, double height);

/* Lays an empty raster (0 x 0, nothing blocks, distance not ready) in mem[size] (8-byte
 * aligned). GMMRRT_ERR_INVALID_ARGUMENT: NULL, misaligned or a capacity out of range;
 * GMMRRT_ERR_BUFFER_TOO_SMALL: size < gmmrrt_raster_mem_size. */
gmmrrt_status_t gmmrrt_raster_init(gmmrrt_raster_t *r, void *mem, size_t size, int32_t max_cells, int32_t max_side);

/* Sets the raster's size and pose and makes every cell unknown, the marks empty and the field
 * not ready; the caller then writes r->cells (width x height) and calls
 * gmmrrt_raster_update_distance. GMMRRT_ERR_INVALID_ARGUMENT: width or height < 1, a resolution
 * not finite or <= 0, an origin not finite, unknown_blocked not 0 or 1;
 * GMMRRT_ERR_BUFFER_TOO_SMALL: width x height > max_cells or a side > max_side (r unchanged). */
gmmrrt_status_t gmmrrt_raster_set_geometry(gmmrrt_raster_t *r, int32_t width, int32_t height, double resolution_m,
                                           double origin_x, double origin_y, double origin_yaw,
                                           int32_t unknown_blocked);

/* Computes the distance field from the cells and the scan marks younger than mark_decay_ms
 * at now_utime (a mark is active while now - its time <= decay). O(width x height).
 * GMMRRT_ERR_INVALID_ARGUMENT: NULL, an empty raster, decay not finite or < 0. */
gmmrrt_status_t gmmrrt_raster_update_distance(gmmrrt_raster_t *r, int64_t now_utime, double mark_decay_ms);

/* The field only where a planning problem can read it, for a raster that scans change every
 * cycle: the corners of the cells meeting the world box [xmin, xmax] x [ymin, ymax] (a problem's
 * bounds) and one more each side, computed from the blocked cells within reach_m (m) around them and capped at
 * about reach_m (so it stays a lower bound). Cost O((window + 2 reach / res)^2) cells, whatever the
 * raster's size. Everywhere else the field is invalid and the bound below calls points blocked;
 * reach_m should exceed the robot's radius by a few cells (a smaller one blocks points near
 * nothing; a larger one lets the edges' tracing take longer steps). GMMRRT_ERR_INVALID_ARGUMENT:
 * NULL, an empty raster, a non-finite or inverted box, reach_m not finite or <= 0, decay as above. */
gmmrrt_status_t gmmrrt_raster_update_distance_window(gmmrrt_raster_t *r, int64_t now_utime, double mark_decay_ms,
                                                     double xmin, double ymin, double xmax, double ymax,
                                                     double reach_m);

/* 1 when the field is ready for the collision world. */
int gmmrrt_raster_distance_ready(const gmmrrt_raster_t *r);

/* A lower bound (m) of the distance from world point q = (x, y) to the nearest blocked cell's
 * square (the outside's too when it blocks): max over the four corners v of q's cell (clamped to
 * the raster, and inside the field's valid window) of dist(v) - |q - v| (the distance is
 * 1-Lipschitz, so each term is a lower bound); -inf when none of them is valid. Exact at the
 * corners (to float rounding); elsewhere short by at most twice the distance to the nearest
 * corner (a cell's diagonal at its centre). 1-Lipschitz inside a cell, not across its edges
 * (the four corners change there, and so may the maximum): a caller that steps by it relies
 * on the clearance it bounds being 1-Lipschitz, not on the bound. Four loads; for the planning
 * loop. */
double gmmrrt_raster_clearance_bound(const gmmrrt_raster_t *r, double x, double y);

/* A lower bound (m) of the same distance, at least gmmrrt_raster_clearance_bound and mostly
 * much nearer the distance: the disc of radius dist(v) around each corner v of the point's cell
 * (valid ones, as above) holds nothing blocked, so neither does their union, and the point's
 * distance to the union's outside is a bound. That distance is the least over the union's
 * boundary of the distance to the point, taken at each circle's nearest point to it and at the
 * circles' crossings that no other disc covers. The same four loads as the four-corner bound
 * and several times its arithmetic; for where that bound cannot decide. */
double gmmrrt_raster_clearance_union(const gmmrrt_raster_t *r, double x, double y);

/* Exact distance (m) from world point (x, y) to the nearest blocked cell's square (0 inside
 * one), looking only at cells within max_m; max_m when none is that close. Brute force over
 * those cells: an oracle for tests, not for the loop. */
double gmmrrt_raster_distance_to_blocked(const gmmrrt_raster_t *r, double x, double y, double max_m);

/* One planar range scan, in the style of libbot2's planar_lidar_t. Beam k points at
 * rad0 + k radstep (rad) in the sensor frame and measured ranges_m[k]. A range is a return
 * when it is finite and range_min_m <= range < range_max_m; anything else (NaN, +-inf, out of
 * range) is "no return": it neither marks nor clears. */
typedef struct {
    double rad0, radstep;       /* rad */
    double range_min_m, range_max_m;
    int32_t num_ranges;         /* 0..GMMRRT_MAX_SCAN_RANGES */
    const float *ranges_m;
} gmmrrt_scan_t;

/* Integrates a scan taken at utime by a sensor at world pose (sensor_x, sensor_y,
 * sensor_yaw) (the caller places it: robot pose at utime composed with the sensor's mount):
 * for every return, the cells the beam crosses before its end are cleared of marks (the map's
 * own occupied cells stay) and the end cell is marked at utime, like a costmap's obstacle
 * layer. Beams are cut where they leave the raster. Cost: at most
 * num_ranges x (2 range_max_m / res + 2) cell visits. The field is no longer ready afterwards.
 * *marked / *cleared (may be NULL) get the numbers of cells marked and cleared.
 * GMMRRT_ERR_INVALID_ARGUMENT: NULL r or scan, an empty raster, num_ranges outside
 * 0..GMMRRT_MAX_SCAN_RANGES (or ranges NULL with num_ranges > 0), a non-finite pose, angle or
 * limit, range_min < 0, range_max <= range_min, utime < 0 or more than 2^32 ms after the
 * first scan's (the marks' clock; set the geometry again to start a new one). r unchanged then. */
gmmrrt_status_t gmmrrt_raster_apply_scan(gmmrrt_raster_t *r, const gmmrrt_scan_t *scan, double sensor_x,
                                         double sensor_y, double sensor_yaw, int64_t utime, int32_t *marked,
                                         int32_t *cleared);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_RASTER_H */
