/*
 * collision.h - the world the robot moves in: a disc robot among circles, oriented boxes
 * and people (discs). FCL does the geometry when the world changes; the planning loop
 * queries what was built from it (see docs/planner.md for what is kept and why).
 *
 * Memory: a gmmrrt_world_t lives inside the planner's block (rrtstar.h); the functions
 * here are also usable standalone with gmmrrt_world_mem_size() bytes of caller memory.
 */
#ifndef GMMRRT_COLLISION_H
#define GMMRRT_COLLISION_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/features.h"
#include "gmmrrt/limits.h"
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
} gmmrrt_obstacle_set_t;

typedef struct gmmrrt_world gmmrrt_world_t;

/* Bytes a world needs for the given clearance-grid capacity (cells). */
size_t gmmrrt_world_mem_size(int32_t grid_max_cells);

/* Builds the collision world in mem[size]: robot disc of robot_radius_m (>= 0), people as
 * discs of person_radius_m (>= 0), grid at resolution_m. Validates every number. */
gmmrrt_status_t gmmrrt_world_build(gmmrrt_world_t **out, void *mem, size_t size, int32_t grid_max_cells,
                                   double resolution_m, double robot_radius_m, double person_radius_m,
                                   const gmmrrt_obstacle_set_t *obstacles);

/* 1 when the robot centred at (x, y) is free (inside bounds, touching nothing), else 0. */
int gmmrrt_world_point_free(const gmmrrt_world_t *world, double x, double y);

/* 1 when the straight segment is free, checked at the world's resolution (docs/planner.md). */
int gmmrrt_world_segment_free(const gmmrrt_world_t *world, double x0, double y0, double x1, double y1);

/* Exact clearance (m) from the robot disc at (x, y) to the nearest obstacle or person,
 * computed by FCL; negative when penetrating. Not for the planning loop. */
double gmmrrt_world_exact_clearance(const gmmrrt_world_t *world, double x, double y);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_COLLISION_H */
