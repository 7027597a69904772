/*
 * planner.h - the anytime planner's API: GMM-RRT*, RRT* (Karaman & Frazzoli 2011) with the
 * paper's mixture sampling bias and task cost (Sect. 4), plain RRT*, and the GMM-RRT baseline
 * (gmm_rrt.c); the kind is cfg.planner, turned into behaviour in one place (strategy.c).
 *
 * Memory, like lcm-lite's lcmlite_init: gmmrrt_planner_mem_size(&cfg) says how many bytes;
 * gmmrrt_planner_init() places everything (planner state, node pool, spatial index,
 * collision world, history) inside that one caller-owned block. After init nothing is
 * allocated: set_problem, run and best_path only use the block.
 *
 * Cost of an edge (paper Sect. 4): integral over the edge of (w_length + w_task c(f(x))) ds,
 * c(f) the task cost of cfg.task_cost (gmm.h), f the features of x relative to the person the
 * task is about; with several people in avoid, relative to the one nearest x among those
 * within person_influence_m of the segment start-goal. Quadrature: docs/planner.md.
 */
#ifndef GMMRRT_PLANNER_H
#define GMMRRT_PLANNER_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/collision.h"
#include "gmmrrt/config.h"
#include "gmmrrt/limits.h"
#include "gmmrrt/model.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gmmrrt_planner gmmrrt_planner_t;

/* Walking people (moving_people.c). Below GMMRRT_STANDING_SPEED_M_S a person is standing and
 * planned exactly as with no velocity (trackers report ~0.1 m/s of jitter on a standing person;
 * people walk at 0.5-1.5 m/s). A velocity that is not finite or faster than
 * GMMRRT_MAX_PERSON_SPEED_M_S (a running person; faster is a tracking error) is refused. */
#define GMMRRT_STANDING_SPEED_M_S 0.2
#define GMMRRT_MAX_PERSON_SPEED_M_S 3.0
#define GMMRRT_DEFAULT_NOMINAL_SPEED_M_S 0.5
#define GMMRRT_DEFAULT_PREDICTION_HORIZON_S 5.0
/* Room the search keeps between the robot's and a walker's discs (m): a walker cannot stop
 * for the robot the way a standing person can step aside, and the prediction is only a guess. */
#define GMMRRT_WALKER_COMFORT_M 0.2
/* Which way round a person the path goes (problem.side). Counted by the bearing from the
 * person to the robot, as metrics.same_homotopy counts it: LEFT = the bearing turns
 * counterclockwise from start to goal (the person stays on the robot's left; for a person
 * facing the oncoming robot that is the person's left, the data's `left` homotopy), RIGHT =
 * clockwise. EITHER = no preference: the cheapest path, whichever side. */
typedef enum {
    GMMRRT_SIDE_EITHER = 0,
    GMMRRT_SIDE_LEFT = 1,
    GMMRRT_SIDE_RIGHT = 2
} gmmrrt_side_t;

/* One planning problem. Models are borrowed (not copied) and must outlive the run. */
typedef struct {
    double start_x, start_y;      /* m, world */
    double goal_x, goal_y;        /* m, world */
    double goal_tolerance_m;      /* > 0: a node this close to the goal reaches it */
    int32_t task;                 /* gmmrrt_task_t: NONE (length only), AVOID, APPROACH */
    int32_t target_person;        /* index into obstacles.people for APPROACH, else -1 */
    const gmmrrt_model_t *model;  /* FEATURES model for the task (GMM-RRT*), or the XY model
                                     (GMM-RRT); NULL for plain RRT* */
    gmmrrt_obstacle_set_t obstacles; /* bounds, obstacles, people (people are obstacles too) */
    /* Velocity of obstacles.people[i] (m/s, world). Zero (a zeroed problem) = standing. */
    double person_vx[GMMRRT_MAX_PEOPLE], person_vy[GMMRRT_MAX_PEOPLE];
    double nominal_speed_m_s;     /* robot speed that times the path against walkers, (0, 10];
                                     0: GMMRRT_DEFAULT_NOMINAL_SPEED_M_S */
    double prediction_horizon_s;  /* constant-velocity prediction horizon, (0, 60]; 0: default */
    int32_t side;                 /* gmmrrt_side_t: every edge keeps off the ray from side_person
                                     through the middle of the other side's arc (0: EITHER, so a
                                     zeroed problem has no preference); ignored without people */
    int32_t side_person;          /* index into obstacles.people the side is about; -1: the person
                                     nearest the segment start-goal */
    const gmmrrt_model_t *background_model; /* FEATURES model for cfg.task_cost BACKGROUND (else
                                     unused, may be NULL): where walkers would be without the
                                     person, e.g. fitted to the straight lines start-goal of the
                                     task model's episodes */
} gmmrrt_problem_t;

/* Budget of one run: stops at whichever comes first. */
typedef struct {
    double time_ms;              /* wall-clock budget (CLOCK_MONOTONIC); <= 0: no time limit */
    int64_t max_iterations;      /* samples drawn, kept or not (as OMPL counts); <= 0: none */
    double converge_rel;         /* > 0: stop when the best cost improved by less than this
                                    fraction over converge_window iterations; 0: off */
    int64_t converge_window;
} gmmrrt_budget_t;

typedef struct {
    int64_t iterations;           /* samples drawn in total since set_problem */
    int32_t nodes;                /* nodes in the tree */
    int64_t first_solution_iteration; /* -1 until a path exists */
    double first_solution_ms;     /* -1 until a path exists */
    double best_cost;             /* INFINITY until a path exists */
    double time_ms;               /* wall-clock time spent in run() calls since set_problem */
    double setup_ms;              /* wall-clock time of the last set_problem (validation, collision
                                     world, tree reset): the set-up before the first iteration */
    int64_t pruned;               /* nodes recycled by pruning since set_problem (see run) */
} gmmrrt_plan_stats_t;

typedef struct {
    int32_t num_points;                     /* 0 when there is no path */
    double x[GMMRRT_MAX_WAYPOINTS];         /* m, world; x[0], y[0] = start */
    double y[GMMRRT_MAX_WAYPOINTS];
    double yaw[GMMRRT_MAX_WAYPOINTS];       /* direction of travel */
    double length_m;
    double cost;
} gmmrrt_path_t;

size_t gmmrrt_planner_mem_size(const gmmrrt_planner_config_t *cfg);

/* Validates cfg and lays the planner out in mem[size] (8-byte aligned). *out points into mem. */
gmmrrt_status_t gmmrrt_planner_init(gmmrrt_planner_t **out, void *mem, size_t size,
                                    const gmmrrt_planner_config_t *cfg);

/* Validates the problem (finite numbers, start and goal inside bounds and free, model kind
 * fits the planner kind, people's velocities), builds the collision world and resets the tree
 * to the start.
 * A start inside a person's disc or an inflated obstacle is not refused: GMMRRT_ESCAPE, the
 * tree is rooted at the end of the shortest straight motion out along which the exact clearance
 * never falls (escape.c; gmmrrt_planner_best_path then starts there, gmmrrt_planner_drivable_path
 * at the real start), and the planner is ready to run as after GMMRRT_OK. GMMRRT_ERR_FROZEN when
 * no such motion exists (gmmrrt_planner_escape_reason says why).
 * Other statuses: GMMRRT_ERR_INVALID_ARGUMENT, GMMRRT_ERR_START_IN_COLLISION (kept for callers;
 * no longer returned),
 * GMMRRT_ERR_GOAL_IN_COLLISION, GMMRRT_ERR_START/GOAL_OUT_OF_BOUNDS, GMMRRT_ERR_MODEL_MISMATCH,
 * GMMRRT_ERR_BUFFER_TOO_SMALL (world larger than grid_max_cells). */
gmmrrt_status_t gmmrrt_planner_set_problem(gmmrrt_planner_t *p, const gmmrrt_problem_t *problem);

/* Whether `model` can drive a planner configured by `cfg` (the rule set_problem applies to a
 * task's model): GMM-RRT* needs a features model (D = 2), GMM-RRT an xy model (D = 3), and a
 * usable delta when the config gives none; RRT* uses no model (always GMMRRT_OK).
 * GMMRRT_OK, GMMRRT_ERR_MODEL_MISMATCH, or GMMRRT_ERR_INVALID_ARGUMENT for a NULL cfg.
 * Lets a caller refuse a model when it is loaded instead of at every planning call. */
gmmrrt_status_t gmmrrt_planner_model_fits(const gmmrrt_planner_config_t *cfg, const gmmrrt_model_t *model);

/* 1 when a planner configured by `cfg` divides by a background model (problem.background_model):
 * cfg->task_cost is GMMRRT_TASK_COST_BACKGROUND and cfg->planner is one whose edge cost carries
 * the task cost (GMM-RRT*; RRT* and GMM-RRT cost length only and never read it). 0 otherwise,
 * and for a NULL cfg. The rule set_problem applies; callers refuse a model file without a
 * background by it when the file is loaded. */
int gmmrrt_planner_needs_background(const gmmrrt_planner_config_t *cfg);

/* Warm start: inserts a previous path (world x-y points, start first) into the fresh tree
 * where its edges are still free. Call right after set_problem. */
gmmrrt_status_t gmmrrt_planner_seed_path(gmmrrt_planner_t *p, const double *x, const double *y, int32_t n);

/* Grows the tree within budget; may be called again to continue (anytime). When the pool is
 * full and a path exists, the nodes whose branch cannot lead to a cheaper path are pruned and
 * their slots reused (informed pruning, as OMPL's RRTstar prune with the tree's cost-to-come:
 * a node whose cost-to-come plus the lower bound of its cost-to-go, gmmrrt_edge_cost_lower_bound
 * of its distance to the goal, is at least the best cost; that bound never decreases along a
 * branch, so whole subtrees go; when that frees less than a quarter of the pool, the quarter of
 * the nodes with the largest such bound go) and the search goes on in the same memory; the best
 * path stays. Returns GMMRRT_OK when a path to the goal exists,
 * GMMRRT_NO_PATH_YET when not, GMMRRT_POOL_FULL when the pool ran out and pruning could not
 * free at least 1/64 of it (the best path so far is kept). When problem.side asked for a side and no
 * path exists on it, GMMRRT_NO_PATH_ON_SIDE instead of GMMRRT_NO_PATH_YET (the caller may re-plan
 * with EITHER). Fills *stats when non-NULL. */
gmmrrt_status_t gmmrrt_planner_run(gmmrrt_planner_t *p, const gmmrrt_budget_t *budget,
                                   gmmrrt_plan_stats_t *stats);

/* The best path so far resampled at cfg.waypoint_spacing_m (at most GMMRRT_MAX_WAYPOINTS
 * points; the spacing grows if needed to fit), start and goal included. */
gmmrrt_status_t gmmrrt_planner_best_path(const gmmrrt_planner_t *p, gmmrrt_path_t *out);

/* Cost history: up to cap (iteration, best cost) pairs recorded when the best cost
 * improved; returns the number written. */
int32_t gmmrrt_planner_cost_history(const gmmrrt_planner_t *p, int64_t *iterations, double *costs, int32_t cap);

/* Tree inspection for tests and plots: node i's position, parent (-1 for the root) and cost. */
int32_t gmmrrt_planner_node_count(const gmmrrt_planner_t *p);
gmmrrt_status_t gmmrrt_planner_node(const gmmrrt_planner_t *p, int32_t i, double *x, double *y,
                                    int32_t *parent, double *cost);

/* Why the current problem escapes (GMMRRT_ESCAPE) or is frozen (GMMRRT_ERR_FROZEN); "" otherwise.
 * Static text inside the planner, valid until the next set_problem. */
const char *gmmrrt_planner_escape_reason(const gmmrrt_planner_t *p);

/* The collision world of the current problem (for checks outside the loop; walking people are
 * not in it, the planner tests them against their prediction). */
const gmmrrt_world_t *gmmrrt_planner_world(const gmmrrt_planner_t *p);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_PLANNER_H */
