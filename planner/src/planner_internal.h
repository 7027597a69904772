/*
 * planner_internal.h - internal: the planner state that gmmrrt_planner_init lays out in the
 * caller's block, shared by rrtstar.c (the loop), sampler.c (where samples come from),
 * objective.c (edge costs) and path.c (output). Not a public header.
 */
#ifndef GMMRRT_PLANNER_INTERNAL_H
#define GMMRRT_PLANNER_INTERNAL_H

#include <stdint.h>

#include "gmmrrt/rng.h"
#include "gmmrrt/planner.h"
#include "nn.h"

/* Two points closer than this are the same point (no edge between them). */
#define GMMRRT_SAME_POINT_M 1e-9

/* Near-set scratch: choose-parent and rewire look at no more than this many nodes; when the
 * rewiring disc holds more, the radius is halved until they fit (rrtstar.c). */
#define GMMRRT_NEAR_CAP 256
/* Scratch of the k-nearest query (>= 2 GMMRRT_NEAR_CAP): candidates gathered before selection. */
#define GMMRRT_KNN_SCRATCH 1024
/* Nodes within goal tolerance that are remembered as solution candidates; when full, a
 * new candidate replaces the worst one if it is better. */
#define GMMRRT_GOAL_CAP 1024

/* What a planner kind does: chosen once, at init, by the one switch over gmmrrt_planner_kind_t
 * (strategy.c); the loop, the sampler and the objective read these fields, never cfg.planner. */
typedef struct {
    int32_t model_kind; /* GMMRRT_MODEL_KIND_* the task model must be; 0: no model is used */
    int32_t model_dim;  /* its dimension */
    int32_t rewires;    /* 1: RRT* (choose-parent and rewire); 0: RRT's extend to the nearest node */
    int32_t task_cost;  /* 1: the edge cost integrates the task cost and walkers' lane cost; 0: length */
    int32_t stages;     /* 1: the GMM-RRT baseline's staged sampling of the xy model (gmm_rrt.c) */
} gmmrrt_strategy_t;

/* The GMM-RRT baseline's state (gmm_rrt.c): the model's components in order of mean progress s,
 * the current stage, and the inverse of each component's (x', y') marginal covariance. */
typedef struct {
    int32_t stage;
    int32_t order[GMMRRT_MAX_K];
    double xy_mean[GMMRRT_MAX_K][2];
    double xy_inv_cov[GMMRRT_MAX_K][3]; /* a, b, c of [[a, b], [b, c]] */
} gmmrrt_gmm_rrt_t;

/* strategy.c: the strategy of planner kind `planner` (a validated gmmrrt_planner_kind_t). */
gmmrrt_strategy_t gmmrrt_strategy_of(int32_t planner);

/* Walking people (moving_people.c): the planner's copy of each person faster than
 * GMMRRT_STANDING_SPEED_M_S; standing people stay in the collision world as before. */
typedef struct {
    int32_t count;
    int32_t person[GMMRRT_MAX_PEOPLE];  /* index into problem.obstacles.people */
    double x[GMMRRT_MAX_PEOPLE], y[GMMRRT_MAX_PEOPLE];   /* m, at t = 0 */
    double vx[GMMRRT_MAX_PEOPLE], vy[GMMRRT_MAX_PEOPLE]; /* m/s */
    double speed_m_s;                   /* robot's nominal speed */
    double horizon_s;                   /* prediction horizon */
    double reach_m;                     /* robot + person radius + the edge margin (contact) */
    double root_x, root_y;              /* where the robot is at t = 0 (the tree's root) */
} gmmrrt_walkers_t;

/* Escape from a start in collision (escape.c). */
typedef struct {
    int32_t active;                     /* 1: the tree is rooted at (exit_x, exit_y) */
    double start_x, start_y;            /* the robot's real start */
    double exit_x, exit_y;
    double length_m;
    double start_clearance_m;           /* exact signed clearance at the start (< 0: penetration) */
    char freeze_reason[192];            /* why it escapes, or why no escape exists */
} gmmrrt_escape_t;

/* The connect phase (connect.c): two trees, the start's and the goal's, in one fixed array
 * of GMMRRT_CONNECT_MAX_NODES entries (the start's from entry 0 up, the goal's from the last
 * entry down), and room for the joined path. */
#define GMMRRT_CONNECT_MAX_NODES 4096
typedef enum {
    GMMRRT_CONNECT_OFF = 0,     /* not configured, not applicable, or over for this problem */
    GMMRRT_CONNECT_GROWING = 1  /* no path yet: run() iterates the connect phase */
} gmmrrt_connect_state_t;
typedef struct {
    gmmrrt_xy_t *xy;            /* GMMRRT_CONNECT_MAX_NODES, in the planner block */
    int32_t *parent;            /* same index space; -1 for the two roots */
    uint8_t *blocked_once;      /* same index space: 1 once a step from the node was blocked
                                   (a boundary node of the dynamic domains, connect.c) */
    double *path_x, *path_y;    /* GMMRRT_CONNECT_MAX_NODES: the joined path, start first */
    int32_t state;              /* gmmrrt_connect_state_t */
    int32_t n_start, n_goal;    /* nodes of each tree */
    int32_t turn;               /* 0: the start tree extends towards the next sample, 1: the goal tree */
    int64_t iterations;         /* of this phase since gmmrrt_connect_reset (cfg.connect_max_iterations) */
    int64_t edge_tests;         /* edges this phase has tested since gmmrrt_connect_reset */
} gmmrrt_connect_t;

/* Set by collision.c's internal hook: segment walk step. */
void gmmrrt_world_set_edge_resolution(gmmrrt_world_t *world, double edge_resolution_m);
/* Set by collision.c's internal hook: 1 (a new world) lets the map's bound take the union of its
 * corners' discs where the four-corner bound cannot decide (raster.h), 0 not: only the search's
 * extensions before the first path run without it (rrtstar.c, gmmrrt_planner_run). */
void gmmrrt_world_set_raster_union(gmmrrt_world_t *world, int on);

struct gmmrrt_planner {
    gmmrrt_planner_config_t cfg;
    gmmrrt_strategy_t strategy;    /* of cfg.planner */
    gmmrrt_rng_t rng;

    /* Block layout (all inside the caller's memory). */
    gmmrrt_pool_t pool;            /* cfg.max_nodes of each array */
    gmmrrt_nn_t nn;                /* heads: gmmrrt_nn_capacity(max_nodes) */
    void *world_mem;
    size_t world_size;
    gmmrrt_world_t *world;         /* NULL until set_problem succeeds */
    gmmrrt_connect_t connect;      /* connect phase (connect.c) */
    int64_t *hist_iter;            /* cfg.history_capacity */
    double *hist_cost;

    /* Problem */
    int has_problem;
    gmmrrt_escape_t escape;
    double delta;                  /* task-cost delta in use */
    int task_active;               /* task cost and mixture sampling apply */
    int32_t num_active;            /* people the task is about */
    int32_t active[GMMRRT_MAX_PEOPLE];
    double active_cos[GMMRRT_MAX_PEOPLE]; /* cos / sin of the active people's yaw (objective.c) */
    double active_sin[GMMRRT_MAX_PEOPLE];
    int32_t focus_person;          /* GMM-RRT: the person whose frame the xy model lives in */
    /* Preferred side (problem.side): no edge may cross the ray from (side_px, side_py) along
     * the unit vector (side_ux, side_uy), the middle of the other side's arc (rrtstar.c). */
    int side_active;
    double side_px, side_py, side_ux, side_uy;

    /* Informed sampling (sampler.c): the ellipse's centre, axis direction and focal distance. */
    double inf_cx, inf_cy, inf_cos, inf_sin, inf_cmin;

    /* Tree and search state */
    int32_t num_nodes;
    int32_t num_goal;
    int32_t best_goal;             /* slot in goal_idx of the best solution, -1 none */
    double best_cost;
    int32_t hist_count;
    int64_t iterations;
    int64_t first_solution_iteration;
    double first_solution_ms;
    double time_ms;
    double run_t0_ms;              /* monotonic ms at the start of the current run(), -1 outside */
    double run_base_ms;            /* time_ms when that run started */
    double conv_ref_cost;
    int64_t conv_ref_iter;
    double setup_ms;               /* duration of the last successful set_problem */
    int64_t pruned;                /* nodes recycled by pruning since set_problem */

    /* Per-problem copies, not cleared by gmmrrt_planner_init (14.5 KB that a one-shot plan would
     * otherwise write twice on a cold cache): set_problem writes each part before anything reads
     * it (the problem with its obstacle arrays up to their counts, the walkers, the walkers'
     * world only when someone walks, the GMM-RRT stages only for gmm-rrt), and nothing reads
     * them before a problem is set (has_problem). */
    gmmrrt_walkers_t walkers;
    gmmrrt_problem_t problem;
    gmmrrt_obstacle_set_t world_obstacles; /* the statics and standing people, when some walk */
    gmmrrt_gmm_rrt_t gmm_rrt;      /* the GMM-RRT baseline's own state (gmm_rrt.c) */

    /* Scratch, last and not cleared by gmmrrt_planner_init (30 KB: clearing it was most of a
     * one-shot plan's set-up on a cold cache); every entry is written before it is read (the
     * near set per iteration, the solution candidates up to num_goal). */
    int32_t near_idx[GMMRRT_KNN_SCRATCH];  /* near set (first GMMRRT_NEAR_CAP + 1); k-nearest scratch */
    double near_edge[GMMRRT_NEAR_CAP + 1]; /* exact edge cost, NAN until needed */
    double near_len[GMMRRT_NEAR_CAP + 1];  /* m */
    double near_d2[GMMRRT_KNN_SCRATCH];    /* m^2, squared distances of near_idx */
    double near_cost[GMMRRT_NEAR_CAP + 1]; /* their cost-to-come when the iteration's near set was taken */
    int8_t near_free[GMMRRT_NEAR_CAP + 1];
    int32_t goal_idx[GMMRRT_GOAL_CAP];
    double goal_edge[GMMRRT_GOAL_CAP];
};

/* objective.c: the edge cost, integral of (w_length + w_task c) ds by the midpoint rule at
 * cfg.edge_resolution_m, c the task cost (1 where no task applies; plain length for rrt-star
 * and gmm-rrt). */
double gmmrrt_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1);
/* A lower bound of gmmrrt_edge_cost for an edge of len_m (c > 0 is bounded below by 0), so
 * the loop can skip the quadrature for candidates that cannot win. Linear in len_m (the
 * loop and informed sampling rely on it: bound(len) = len * bound(1)). */
double gmmrrt_edge_cost_lower_bound(const struct gmmrrt_planner *p, double len_m);

/* moving_people.c: prepares p->walkers from the problem (GMMRRT_ERR_INVALID_ARGUMENT for a
 * velocity that is not finite or faster than GMMRRT_MAX_PERSON_SPEED_M_S) and returns the
 * obstacle set the collision world is built from: pr->obstacles itself when nobody walks, else
 * p->world_obstacles without the walkers. */
gmmrrt_status_t gmmrrt_walkers_prepare(struct gmmrrt_planner *p, const gmmrrt_problem_t *pr,
                                       const gmmrrt_obstacle_set_t **world_set);
/* 1 when the robot disc on the point / segment keeps clear of every walker's predicted
 * positions over the time it can be there (moving_people.c). */
int gmmrrt_walkers_point_free(const gmmrrt_walkers_t *w, double x, double y);
int gmmrrt_walkers_segment_free(const gmmrrt_walkers_t *w, double x0, double y0, double x1, double y1);
/* Integral over the segment of the walkers' social cost (largest over the walkers; in [0, 1],
 * higher in the lane ahead of a walker than behind them), midpoint rule at resolution_m. */
double gmmrrt_walkers_cost(const gmmrrt_walkers_t *w, double x0, double y0, double x1, double y1, double resolution_m);
/* Clearance (m) of the robot disc at (x, y) at time t_s to the nearest walker there; +inf without walkers. */
double gmmrrt_walkers_clearance_at(const gmmrrt_walkers_t *w, double x, double y, double t_s);

/* The planner's free tests: the world's, and the walkers' when there are any. Every check of
 * the search goes through these two. */
static inline int gmmrrt_planner_point_free(const struct gmmrrt_planner *p, double x, double y)
{
    return gmmrrt_world_point_free(p->world, x, y) &&
           (p->walkers.count == 0 || gmmrrt_walkers_point_free(&p->walkers, x, y));
}
static inline int gmmrrt_planner_segment_free(const struct gmmrrt_planner *p, double x0, double y0, double x1,
                                              double y1)
{
    return gmmrrt_world_segment_free(p->world, x0, y0, x1, y1) &&
           (p->walkers.count == 0 || gmmrrt_walkers_segment_free(&p->walkers, x0, y0, x1, y1));
}

/* escape.c: exact signed clearance of the robot disc at (x, y) to the set's shapes and p's map
 * (what: the nearest, circles 0.., boxes 1000.., people 2000.., the map 3000); bound_m, a value
 * the clearance is known not to exceed (INFINITY: none), only narrows the map's search; and the way out of a start in collision:
 * GMMRRT_ESCAPE with the exit point, or GMMRRT_ERR_FROZEN with p->escape.freeze_reason. */
double gmmrrt_escape_signed_clearance(const struct gmmrrt_planner *p, const gmmrrt_obstacle_set_t *o, double x,
                                      double y, double bound_m, int32_t *what);
gmmrrt_status_t gmmrrt_escape_find(struct gmmrrt_planner *p, const gmmrrt_problem_t *pr, double *exit_x,
                                   double *exit_y);

/* rrtstar.c: an edge the tree may use: collision-free (walkers included) and on the preferred
 * side (problem.side). The one predicate of every tree edge, the connect phase's too. */
int gmmrrt_planner_edge_allowed(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1);

/* connect.c: bytes of the connect phase's arrays for cfg (0 when cfg->connect_first is 0 or the
 * planner is gmm-rrt); gmmrrt_connect_bind points p->connect into mem (that many bytes, 8-byte
 * aligned). gmmrrt_connect_reset arms the phase for a new problem (set_problem's tree reset).
 * gmmrrt_connect_iterate is one iteration of it (one sample drawn: p->iterations + 1): when the
 * trees join, the path is inserted into the RRT* tree (as gmmrrt_planner_seed_path) and the
 * phase ends; it also ends, leaving the RRT* tree as it was, when its array is full. */
size_t gmmrrt_connect_mem_size(const gmmrrt_planner_config_t *cfg);
void gmmrrt_connect_bind(struct gmmrrt_planner *p, void *mem);
void gmmrrt_connect_reset(struct gmmrrt_planner *p);
void gmmrrt_connect_iterate(struct gmmrrt_planner *p);

/* sampler.c: draws one sample; returns 0 when the draw fell outside the bounds (the
 * iteration is spent, as OMPL counts). Prepares informed sampling and the GMM-RRT stages. */
int gmmrrt_sample(struct gmmrrt_planner *p, double *x, double *y);
void gmmrrt_sampler_prepare(struct gmmrrt_planner *p);

/* gmm_rrt.c, the GMM-RRT baseline (Claassens 2010): the stage tables of the xy model (components
 * by mean progress, their (x', y') marginals), a mixture sample of the current stage (the goal
 * after the last), and the stage's advance when a node at (x, y) reached the current component. */
void gmmrrt_gmm_rrt_prepare(struct gmmrrt_planner *p);
/* gmmrrt_gmm_rrt_sample: 1 for a mixture draw (the caller checks it against the informed ellipse
 * and the bounds), 0 when the stages are done and (x, y) is the goal, taken as it is. */
int gmmrrt_gmm_rrt_sample(struct gmmrrt_planner *p, double *x, double *y);
void gmmrrt_gmm_rrt_node_added(struct gmmrrt_planner *p, double x, double y);

/* path.c: the number of waypoints of a published path total_m long at *spacing_m (the
 * configured waypoint_spacing_m): ceil(total / spacing) + 1, at least 2 (start and end) and
 * at most GMMRRT_MAX_WAYPOINTS; when capped, *spacing_m widens so that the waypoints still
 * reach the end. The one rule for the plain and the drivable path (smooth.c). */
int32_t gmmrrt_waypoint_count(double total_m, double *spacing_m);

#endif /* GMMRRT_PLANNER_INTERNAL_H */
