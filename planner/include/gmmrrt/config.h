/*
 * config.h - the planner's configuration: everything fixed at init (memory sizing) and the
 * tuning of the search. Defaults (gmmrrt_planner_config_default) are documented in
 * docs/planner.md; every field is validated by gmmrrt_planner_config_validate.
 */
#ifndef GMMRRT_CONFIG_H
#define GMMRRT_CONFIG_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Values equal waypoints_t.PLANNER_* on the wire. */
typedef enum {
    GMMRRT_PLANNER_GMM_RRT_STAR = 1, /* the paper's planner: mixture sampling + task cost */
    GMMRRT_PLANNER_RRT_STAR = 2,     /* plain RRT*: uniform sampling, length cost only */
    GMMRRT_PLANNER_GMM_RRT = 3       /* baseline (Claassens 2010): RRT sampling the xy mixture */
} gmmrrt_planner_kind_t;

/* Which task cost c(f) GMM-RRT* integrates (docs/planner.md, "Task cost"). */
typedef enum {
    GMMRRT_TASK_COST_PAPER = 1,  /* c = delta / max(p, delta) (paper Sect. 4) */
    GMMRRT_TASK_COST_INWARD = 2, /* the same with each component's density held at its value on
                                    its ridge for points farther from the person than the ridge
                                    (gmm.h, gmmrrt_gmm_inward_task_cost): only the fall-off
                                    towards the person, where people keep away, is charged */
    GMMRRT_TASK_COST_BACKGROUND = 3 /* c = (p_bg + delta) / (p + p_bg + 2 delta), p_bg the density of
                                    problem.background_model (where the walkers would have been
                                    without the person): the share of "would be here anyway";
                                    1/2 where neither model has data (objective.c) */
} gmmrrt_task_cost_kind_t;

typedef struct {
    int32_t planner;           /* gmmrrt_planner_kind_t */
    uint64_t seed;             /* RNG seed; same seed, same problem -> same tree */

    /* Memory (fixes gmmrrt_planner_mem_size) */
    int32_t max_nodes;         /* tree node pool, 2..GMMRRT_MAX_NODES_CEILING */
    int32_t grid_max_cells;    /* clearance grid capacity, cells */
    int32_t history_capacity;  /* entries of the cost-vs-iteration history */

    /* Geometry */
    double robot_radius_m;     /* >= 0 */
    double person_radius_m;    /* >= 0, people are discs of this radius */
    double grid_resolution_m;  /* > 0, clearance grid cell size */
    double edge_resolution_m;  /* > 0, spacing of collision checks and cost quadrature on edges */

    /* Search */
    double step_m;             /* > 0, steering: longest new edge */
    double goal_bias;          /* [0, 1), probability of sampling the goal */
    double gmm_bias;           /* [0, 1], probability of a mixture sample (paper: 0.95) */
    double rewire_gamma;       /* > 0, near radius r = min(step, gamma (log n / n)^(1/2)), used when
                                  rewire_k_factor is 0 */
    double rewire_k_factor;    /* >= 0; > 0: choose-parent and rewire look at the k nearest nodes,
                                  k = ceil(rewire_k_factor ln(n + 1)) (k-nearest RRT*, Karaman &
                                  Frazzoli 2011; OMPL's default k_rrg = 1.1 e (1 + 1/2) = 4.485);
                                  0: the radius of rewire_gamma */
    int32_t informed_sampling; /* 1: once a path of cost c exists, uniform samples come from the
                                  ellipse with foci start and goal holding every point of a
                                  cheaper path (Informed RRT*, Gammell et al. 2014; bound in
                                  docs/planner.md), and mixture samples outside it are dropped;
                                  0: off */
    int32_t connect_first;     /* 1: until the first path exists, grow a tree from the start and one
                                  from the goal towards each sample and greedily towards each
                                  other (RRT-Connect, Kuffner & LaValle 2000), then hand the joined
                                  path to the RRT* tree, which goes on from it (connect.c;
                                  docs/planner.md); 0: RRT* from the first sample. Not used by gmm-rrt */
    int32_t connect_max_iterations; /* >= 1: the connect phase ends after this many iterations
                                  without a path and RRT* goes on alone from the root, so the
                                  phase's work (its trees' linear scans grow with them) is bounded */
    int32_t connect_domains;   /* 1: a connect-tree node whose step was once blocked is tried for a
                                  target beyond one step only as the nearest node (after the dynamic
                                  domains of Yershova et al. 2005; connect.c); 0: every try checks its edge */
    double w_length;           /* >= 0, weight of length in the edge cost */
    double w_task;             /* >= 0, weight of the task cost c(f) (paper Sect. 4) */
    int32_t task_cost;         /* gmmrrt_task_cost_kind_t (default PAPER; a model that is not over
                                  (d, theta) gets the paper's cost either way) */
    double delta;              /* > 0 overrides the model's delta; 0 uses the model's */
    double person_influence_m; /* > 0, avoid model applies to people within this distance of the segment start-goal */
    double waypoint_spacing_m; /* > 0, spacing of the output path */
} gmmrrt_planner_config_t;

/* Fills *cfg with the documented defaults (gmm-rrt-star, bias 0.95, delta from the model). */
void gmmrrt_planner_config_default(gmmrrt_planner_config_t *cfg);

/* GMMRRT_OK or GMMRRT_ERR_INVALID_ARGUMENT with the offending field named in err[errcap]. */
gmmrrt_status_t gmmrrt_planner_config_validate(const gmmrrt_planner_config_t *cfg, char *err, size_t errcap);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_CONFIG_H */
