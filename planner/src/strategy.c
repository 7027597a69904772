/*
 * strategy.c - the one place where the planner kind (config.h, gmmrrt_planner_kind_t) becomes
 * behaviour: which model the search needs, whether it rewires, whether the edge cost carries
 * the task cost, whether samples walk the GMM-RRT stages (planner_internal.h,
 * gmmrrt_strategy_t). The paper's planner is GMM-RRT* (Sect. 4); RRT* (Karaman & Frazzoli 2011)
 * and GMM-RRT (Claassens 2010, gmm_rrt.c) are its baselines (Sect. 5).
 */
#include "gmmrrt/model.h"
#include "planner_internal.h"

gmmrrt_strategy_t gmmrrt_strategy_of(int32_t planner)
{
    gmmrrt_strategy_t s = {0, 0, 1, 0, 0};
    switch ((gmmrrt_planner_kind_t)planner) {
    case GMMRRT_PLANNER_GMM_RRT_STAR: /* mixture samples over (d, theta), task cost, rewiring */
        s.model_kind = GMMRRT_MODEL_KIND_FEATURES;
        s.model_dim = 2;
        s.task_cost = 1;
        break;
    case GMMRRT_PLANNER_GMM_RRT: /* staged samples of the xy model, length cost, no rewiring */
        s.model_kind = GMMRRT_MODEL_KIND_XY;
        s.model_dim = 3;
        s.rewires = 0;
        s.stages = 1;
        break;
    case GMMRRT_PLANNER_RRT_STAR: /* uniform samples, length cost, rewiring */
    default:
        break;
    }
    return s;
}

int gmmrrt_planner_needs_background(const gmmrrt_planner_config_t *cfg)
{
    return cfg && gmmrrt_strategy_of(cfg->planner).task_cost && cfg->task_cost == GMMRRT_TASK_COST_BACKGROUND;
}
