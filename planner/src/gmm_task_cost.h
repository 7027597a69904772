/*
 * gmm_task_cost.h (private to planner/src and its tests) - gmmrrt_gmm_task_cost_batch with
 * the vector width chosen by the caller, so tests can check that the widths agree bit for bit.
 */
#ifndef GMMRRT_GMM_TASK_COST_H
#define GMMRRT_GMM_TASK_COST_H

#include <stdint.h>

#include "gmmrrt/model.h"

/* lanes: 0 the widest this CPU runs (what gmmrrt_gmm_task_cost_batch uses), 2 the baseline
 * kernel, 4 the AVX2 kernel. inward: 0 the paper's cost, 1 the inward cost (gmm.h). Returns 0 when that width is not available here (nothing
 * written), 1 otherwise. Contract otherwise that of gmmrrt_gmm_task_cost_batch (gmm.h). */
int gmmrrt_gmm_task_cost_batch_lanes(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n,
                                     double delta, double *cost, int lanes, int inward);

#endif /* GMMRRT_GMM_TASK_COST_H */
