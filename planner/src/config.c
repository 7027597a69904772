/*
 * config.c - defaults and validation of gmmrrt_planner_config_t (config.h). The reasons
 * behind each default are in docs/planner.md ("Defaults"); the paper fixes only the
 * mixture bias (95 %, Sect. 5.3) and delta (0.001, Sect. 5.1, taken from the model).
 */
#include "gmmrrt/config.h"

#include <math.h>

#include "error_text.h"
#include "gmmrrt/limits.h"

/* Upper bounds that keep the block size and the loops sane; not paper values. */
#define GMMRRT_MAX_GRID_CELLS (1 << 26)    /* 256 MB of float clearances */
#define GMMRRT_MAX_HISTORY (1 << 20)

void gmmrrt_planner_config_default(gmmrrt_planner_config_t *cfg)
{
    if (!cfg)
        return;
    cfg->planner = GMMRRT_PLANNER_GMM_RRT_STAR;
    cfg->seed = 1;
    cfg->max_nodes = GMMRRT_DEFAULT_MAX_NODES;
    cfg->grid_max_cells = 1 << 20; /* 4 MB: 51 x 51 m at 5 cm */
    cfg->history_capacity = 1024;
    cfg->robot_radius_m = 0.3;
    cfg->person_radius_m = 0.25;
    cfg->grid_resolution_m = 0.05;
    cfg->edge_resolution_m = 0.05;
    cfg->step_m = 0.5;
    cfg->goal_bias = 0.05;
    cfg->gmm_bias = 0.95;
    cfg->rewire_gamma = 15.0;
    cfg->rewire_k_factor = 4.485; /* OMPL's k_rrg, 1.1 e (1 + 1/d), d = 2 */
    cfg->informed_sampling = 1;
    cfg->connect_first = 1;
    cfg->w_length = 1.0;
    cfg->w_task = 2.0;
    cfg->task_cost = GMMRRT_TASK_COST_PAPER; /* measured better on the real splits (docs/planner.md) */
    cfg->delta = 0.0;
    cfg->person_influence_m = 3.0;
    cfg->waypoint_spacing_m = 0.1;
}

/* Returns INVALID_ARGUMENT with "config.<field> <why>" in err when cond is false. */
#define CHECK(cond, field, why)                                                                    \
    do {                                                                                           \
        if (!(cond))                                                                               \
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config.%s %s",      \
                                    field, why);                                                   \
    } while (0)

gmmrrt_status_t gmmrrt_planner_config_validate(const gmmrrt_planner_config_t *cfg, char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (!cfg)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config.(null) is NULL");
    CHECK(cfg->planner == GMMRRT_PLANNER_GMM_RRT_STAR || cfg->planner == GMMRRT_PLANNER_RRT_STAR ||
              cfg->planner == GMMRRT_PLANNER_GMM_RRT,
          "planner", "must be 1 (gmm-rrt-star), 2 (rrt-star) or 3 (gmm-rrt)");
    CHECK(cfg->max_nodes >= 2 && cfg->max_nodes <= GMMRRT_MAX_NODES_CEILING, "max_nodes",
          "must be in 2..GMMRRT_MAX_NODES_CEILING (4194304)");
    CHECK(cfg->grid_max_cells >= 1 && cfg->grid_max_cells <= GMMRRT_MAX_GRID_CELLS, "grid_max_cells",
          "must be in 1..67108864");
    CHECK(cfg->history_capacity >= 1 && cfg->history_capacity <= GMMRRT_MAX_HISTORY, "history_capacity",
          "must be in 1..1048576");
    CHECK(isfinite(cfg->robot_radius_m) && cfg->robot_radius_m >= 0.0, "robot_radius_m",
          "must be finite and >= 0");
    CHECK(isfinite(cfg->person_radius_m) && cfg->person_radius_m >= 0.0, "person_radius_m",
          "must be finite and >= 0");
    CHECK(isfinite(cfg->grid_resolution_m) && cfg->grid_resolution_m > 0.0, "grid_resolution_m",
          "must be finite and > 0");
    CHECK(isfinite(cfg->edge_resolution_m) && cfg->edge_resolution_m > 0.0, "edge_resolution_m",
          "must be finite and > 0");
    CHECK(isfinite(cfg->step_m) && cfg->step_m > 0.0, "step_m", "must be finite and > 0");
    CHECK(isfinite(cfg->goal_bias) && cfg->goal_bias >= 0.0 && cfg->goal_bias < 1.0, "goal_bias",
          "must be in [0, 1)");
    CHECK(isfinite(cfg->gmm_bias) && cfg->gmm_bias >= 0.0 && cfg->gmm_bias <= 1.0, "gmm_bias",
          "must be in [0, 1]");
    CHECK(isfinite(cfg->rewire_gamma) && cfg->rewire_gamma > 0.0, "rewire_gamma", "must be finite and > 0");
    CHECK(isfinite(cfg->rewire_k_factor) && cfg->rewire_k_factor >= 0.0 && cfg->rewire_k_factor <= 64.0,
          "rewire_k_factor", "must be in [0, 64] (0: radius rewiring)");
    CHECK(cfg->informed_sampling == 0 || cfg->informed_sampling == 1, "informed_sampling", "must be 0 or 1");
    CHECK(cfg->connect_first == 0 || cfg->connect_first == 1, "connect_first", "must be 0 or 1");
    CHECK(isfinite(cfg->w_length) && cfg->w_length >= 0.0 && cfg->w_length <= GMMRRT_MAX_COST_WEIGHT, "w_length",
          "must be in [0, 1e6] (GMMRRT_MAX_COST_WEIGHT)");
    CHECK(isfinite(cfg->w_task) && cfg->w_task >= 0.0 && cfg->w_task <= GMMRRT_MAX_COST_WEIGHT, "w_task",
          "must be in [0, 1e6] (GMMRRT_MAX_COST_WEIGHT)");
    CHECK(cfg->w_length > 0.0 || cfg->w_task > 0.0, "w_length", "and w_task must not both be 0");
    CHECK(cfg->task_cost == GMMRRT_TASK_COST_PAPER || cfg->task_cost == GMMRRT_TASK_COST_INWARD ||
              cfg->task_cost == GMMRRT_TASK_COST_BACKGROUND,
          "task_cost", "must be 1 (paper), 2 (inward) or 3 (background)");
    CHECK(isfinite(cfg->delta) && cfg->delta >= 0.0, "delta", "must be finite and >= 0 (0: the model's)");
    CHECK(isfinite(cfg->person_influence_m) && cfg->person_influence_m > 0.0, "person_influence_m",
          "must be finite and > 0");
    CHECK(isfinite(cfg->waypoint_spacing_m) && cfg->waypoint_spacing_m > 0.0, "waypoint_spacing_m",
          "must be finite and > 0");
    return GMMRRT_OK;
}
