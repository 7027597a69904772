/*
 * collision.h - the world the robot moves in: a disc robot among circles, oriented boxes
 * and people (discs). FCL does the geometry when the world changes; the planning loop
 * queries what was built from it (see docs/planner.md for what is kept and why).
 *
 * Memory: a gmmrrt_world_t lives inside the planner's block (planner.h); the functions
 * here are also usable standalone with gmmrrt_world_mem_size() bytes of caller memory.
 * Static obstacles go into a clearance grid whose tiles (8 x 8 cells) are computed on the
 * first query that reads them, so building or updating a world costs no distance computation
 * at all (O(obstacles + tiles) bytes written, independent of where the obstacles are and how
 * big); a map (raster.h) is read through its distance field; people are checked exactly at
 * query time.
 *
 * With at most 8 circles and boxes the grid is not used: every query takes the closed forms
 * over all of them. With more, the first 4096 queries of each world do the same (a first path
 * needs few queries, and the tiles they would fill cost more), the rest read the grid.
 *
 * Cost bound: set-up writes O(obstacles + tiles) bytes and computes nothing; a closed-form query
 * costs at most circles + boxes (<= 128) distances; one tile costs at most (circles + boxes) x
 * (1 + 64) closed-form distances (<= 8 320 with the wire's limits), and a grid query reads at
 * most four tiles, so no query pays more than 4 such fills, and a whole run no more than the
 * tiles its queries reach.
 *
 * Queries write into the world (the tiles they fill): one world must not be queried from two
 * threads at once.
 */
#ifndef GMMRRT_COLLISION_H
#define GMMRRT_COLLISION_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/features.h"
#include "gmmrrt/limits.h"
#include "gmmrrt/raster.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    double x, y;     /* m, centre, world frame */
    double radius_m; /* > 0 */
} gmmrrt_circle_t;

typedef struct {
    double x, y;     /* m, centre, world frame */
    double width_m;  /* full extent along the box's own x axis, > 0 */
    double height_m; /* full extent along the box's own y axis, > 0 */
    double yaw;      /* rad, box x axis from world x */
} gmmrrt_box_t;

typedef struct {
    double xmin, ymin, xmax, ymax; /* m, world frame, xmin < xmax, ymin < ymax */
} gmmrrt_bounds_t;

/* Obstacles and people as the planner sees them for one problem. */
typedef struct {
    gmmrrt_bounds_t bounds;
    int32_t num_circles;
    gmmrrt_circle_t circles[GMMRRT_MAX_CIRCLES];
    int32_t num_boxes;
    gmmrrt_box_t boxes[GMMRRT_MAX_BOXES];
    int32_t num_people;
    gmmrrt_pose_t people[GMMRRT_MAX_PEOPLE];
    /* A static map (raster.h), borrowed: NULL for none. Its distance field must be ready
     * (gmmrrt_raster_update_distance) and must not change while the world is in use; a world
     * built with it reads it at every query, so only the part the search touches is read. */
    const gmmrrt_raster_t *raster;
} gmmrrt_obstacle_set_t;

typedef struct gmmrrt_world gmmrrt_world_t;

/* Bytes a world needs for the given clearance-grid capacity (cells). */
size_t gmmrrt_world_mem_size(int32_t grid_max_cells);

/* Builds the collision world in mem[size]: robot disc of robot_radius_m (>= 0), people as
 * discs of person_radius_m (>= 0; 0: people are not obstacles), grid at resolution_m.
 * Validates every number. GMMRRT_ERR_INVALID_ARGUMENT: a NULL pointer, mem not 8-byte aligned,
 * a number out of range or not finite, or bounds further than 2^50 cells from the origin;
 * GMMRRT_ERR_BUFFER_TOO_SMALL: size < gmmrrt_world_mem_size(grid_max_cells), or the bounds
 * need more than grid_max_cells cells at resolution_m. */
gmmrrt_status_t gmmrrt_world_build(gmmrrt_world_t **out, void *mem, size_t size, int32_t grid_max_cells,
                                   double resolution_m, double robot_radius_m, double person_radius_m,
                                   const gmmrrt_obstacle_set_t *obstacles);

/* Updates the world that gmmrrt_world_build or this function last built in mem for a new
 * problem, keeping as much of the clearance grid as is still valid. The grid holds only the
 * bounds' area and the static obstacles (circles, boxes); people are tested exactly at query
 * time, so moving people never touch the grid. Cells sit on a lattice fixed in the world frame
 * (cell (I, J) centred at ((I + 0.5) res, (J + 0.5) res)), so a cell's value depends only on its
 * place and the static obstacles:
 *   - same circles, boxes, robot_radius_m, resolution_m and grid_max_cells (bit for bit) and the
 *     bounds cover the same tiles: the grid is kept as it is (GMMRRT_GRID_KEPT);
 *   - the same, but the bounds moved or changed size: the tiles still covered are moved in place
 *     (computed or not) and the newly covered ones marked not computed (GMMRRT_GRID_SHIFTED);
 *   - anything else: every tile marked not computed (GMMRRT_GRID_BUILT).
 * No call computes a cell: the queries do, tile by tile (see above). The raster is not part of
 * the grid: changing it (or its generation) costs nothing here.
 * In every case the world answers every query exactly as a fresh gmmrrt_world_build would.
 * world: in, NULL (then this is gmmrrt_world_build) or the world last returned for this mem;
 * out, the world (== mem) on success, NULL on error. Other parameters, validation and statuses
 * as gmmrrt_world_build; a *world that is neither NULL nor mem is GMMRRT_ERR_INVALID_ARGUMENT.
 * On error mem is left as it was. Allocates nothing. */
gmmrrt_status_t gmmrrt_world_update(gmmrrt_world_t **world, void *mem, size_t size, int32_t grid_max_cells,
                                    double resolution_m, double robot_radius_m, double person_radius_m,
                                    const gmmrrt_obstacle_set_t *obstacles);

typedef enum {
    GMMRRT_GRID_BUILT = 0,   /* every tile to be computed again */
    GMMRRT_GRID_KEPT = 1,    /* every tile kept */
    GMMRRT_GRID_SHIFTED = 2, /* tiles still covered kept, the new ones to be computed */
} gmmrrt_grid_update_t;

/* What the grid cost, for logs, tests and benchmarks. Counts run from the last call that
 * started from no world (gmmrrt_world_build, or gmmrrt_world_update with *world == NULL). */
typedef struct {
    gmmrrt_grid_update_t last; /* what the last build / update did */
    int64_t last_cells;        /* cells the last call computed: always 0 (the queries compute them) */
    int64_t built, kept, shifted;
} gmmrrt_world_grid_stats_t;

/* Fills *out; GMMRRT_ERR_INVALID_ARGUMENT when world or out is NULL. */
gmmrrt_status_t gmmrrt_world_grid_stats(const gmmrrt_world_t *world, gmmrrt_world_grid_stats_t *out);

/* Cells the queries computed since the last build / update (tiles x 64): the set-up work the
 * search actually needed; -1 when world is NULL. */
int64_t gmmrrt_world_lazy_cells(const gmmrrt_world_t *world);

/* 1 when the robot centred at (x, y) is free (inside bounds, touching nothing), else 0.
 * Conservative near static obstacles (may block points within about a cell of one), exact
 * for people. */
int gmmrrt_world_point_free(const gmmrrt_world_t *world, double x, double y);

/* Margin (m) every edge keeps from every obstacle and person. A point closer than this to one is
 * free, but no edge can leave it: the planner treats such a start as one in contact (escape). */
#define GMMRRT_EDGE_MIN_CLEARANCE_M 1e-3

/* 1 when (x, y) is free (gmmrrt_world_point_free) and keeps more than GMMRRT_EDGE_MIN_CLEARANCE_M
 * from every obstacle and person by the segment test's own bounds, so that edges can leave it. */
int gmmrrt_world_point_leavable(const gmmrrt_world_t *world, double x, double y);

/* 1 when the straight segment is free (docs/planner.md, "Collision checking"): the grid part by
 * sphere tracing, people exactly; a segment of positive length that comes within
 * GMMRRT_EDGE_MIN_CLEARANCE_M of an obstacle or person is refused. */
int gmmrrt_world_segment_free(const gmmrrt_world_t *world, double x0, double y0, double x1, double y1);

/* Exact clearance (m) from the robot disc at (x, y) to the nearest obstacle or person,
 * computed by FCL, and to the nearest blocked cell of the raster (a square; brute force over
 * the cells within reach); negative when penetrating. Not for the planning loop. */
double gmmrrt_world_exact_clearance(const gmmrrt_world_t *world, double x, double y);

/* Exact signed clearance (m) of the robot disc at (x, y) from the world's map (raster.h): the
 * distance to the nearest blocked cell's square (the outside too when unknown cells block) less
 * the robot's radius, so negative when the disc overlaps the map (-robot radius when (x, y) is in
 * a blocked cell); +INFINITY without a raster, NAN for a NULL world or a non-finite point.
 * Values above cap_m - robot radius come back as that (the cells looked at lie within cap_m > 0;
 * NAN for cap_m <= 0 or NaN). Brute force over those cells and no allocation: for set-up work such as the
 * escape from a start in collision, not for the planning loop. The same cells block here as in
 * gmmrrt_world_point_free, which is stricter (it reads the raster's bound, exact at the cells'
 * corners and short by up to a cell's diagonal between them). */
double gmmrrt_world_map_clearance(const gmmrrt_world_t *world, double x, double y, double cap_m);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_COLLISION_H */
