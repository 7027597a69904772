/*
 * config.c - defaults and validation of gmmrrt_planner_config_t (config.h). The reasons
 * behind each default are in docs/planner.md ("Defaults"); the paper fixes only the
 * mixture bias (95 %, Sect. 5.3) and delta (0.001, Sect. 5.1, taken from the model). The range
 * of each setting is its row of the settings table (config_keys.c); the rules across settings
 * are here.
 */
#include "gmmrrt/config.h"

#include <math.h>
#include <string.h>

#include "error_text.h"
#include "gmmrrt/config_keys.h"
#include "gmmrrt/limits.h"

/* Not a setting (each program sizes it for its own use): its bound stays here. */
#define GMMRRT_MAX_HISTORY (1 << 20)

void gmmrrt_planner_config_default(gmmrrt_planner_config_t *cfg)
{
    if (!cfg)
        return;
    memset(cfg, 0, sizeof *cfg); /* every byte known, padding included: configurations compare bytewise */
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
    cfg->connect_max_iterations = 4096; /* docs/planner.md, "Defaults" */
    cfg->connect_domains = 1;
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
    /* Each setting against its own range, the one in the table (config_keys.c). */
    for (int32_t i = 0; i < gmmrrt_config_key_count(); ++i) {
        const gmmrrt_status_t st = gmmrrt_config_key_check(cfg, gmmrrt_config_key_at(i), err, errcap);
        if (st != GMMRRT_OK)
            return st;
    }
    CHECK(cfg->history_capacity >= 1 && cfg->history_capacity <= GMMRRT_MAX_HISTORY, "history_capacity",
          "must be in 1..1048576");
    /* Rules across settings. */
    CHECK(cfg->w_length > 0.0 || cfg->w_task > 0.0, "w_length", "and w_task must not both be 0");
    return GMMRRT_OK;
}
