/*
 * gmm.h - density, log-density, sampling and the task cost of a mixture (paper eq. 1, Sect. 4).
 *
 * Seam-safe angles: a dimension j with bit j of model->angle_mask set is a wrapped normal:
 *   N_w(f) = sum_{n in {-1,0,1}} N(f + 2 pi n e_j)  (each angle dimension independently,
 * 3^A terms for A angle dimensions), evaluated on the wrapped difference f_j - mu_j in
 * (-pi, pi]. With sigma_theta <= pi/2 the truncation error is below 1e-7 relative.
 * Samples are drawn from the unwrapped normal and wrapped into (-pi, pi].
 *
 * All functions are pure apart from the rng, take a prepared model (model.h), allocate
 * nothing and do no I/O. The feature vector f has model->dim entries.
 */
#ifndef GMMRRT_GMM_H
#define GMMRRT_GMM_H

#include <stdint.h>

#include "gmmrrt/model.h"
#include "gmmrrt/rng.h"

#ifdef __cplusplus
extern "C" {
#endif

/* log p(f); -INFINITY only where every component underflows. A NaN in f gives NaN
 * (and gmmrrt_gmm_task_cost gives 1 there). */
double gmmrrt_gmm_log_density(const gmmrrt_model_t *model, const double *f);

/* p(f) = exp(log p(f)). */
double gmmrrt_gmm_density(const gmmrrt_model_t *model, const double *f);

/* log of component i's weighted density, log w_i + log N_w(f; mu_i, Sigma_i). */
double gmmrrt_gmm_component_log_density(const gmmrrt_model_t *model, int32_t i, const double *f);

/* The paper's task cost (Sect. 4): c(f) = delta / max(p(f), delta), in (0, 1].
 * 1 where the model finds f unlikely, small where it is typical. delta > 0. */
double gmmrrt_gmm_task_cost(const gmmrrt_model_t *model, const double *f, double delta);

/* The inward task cost: c~(f) = delta / max(p~(f), delta) for a (d, theta) model (dim 2, d
 * linear, theta an angle: angle_mask 2; other models get the paper's cost), with
 *     p~(d, theta) = max(p(d, theta), max_i w_i N_w,i(min(d, d_i*(theta)), theta)),
 * d_i*(theta) = argmax_d N_i(d, theta), component i's ridge (the conditional mean of d given
 * theta); the inner max runs over components and the images of theta.
 * Why: the demonstrations' density falls off in two directions from where people walk. Towards
 * the person it falls because people keep away (behaviour, to be charged); away from the
 * person it falls because recordings end a few metres out and people far away do not swerve
 * (no behaviour at all). The paper's cost charges both the same, so a path that passes wide
 * is charged as much as one that hits the person and is bent in towards the model's support.
 * Here a point farther out than a component's ridge, at a bearing that component covers, costs
 * no more than that component's best point: the outward fall-off is not charged. One component
 * at a time, not their sum: a sum of held components would be largest beyond every ridge and
 * push paths out past the widest one; each single held term is at most the mixture's density
 * on that component's ridge, so far out is never cheaper than the best distance at that bearing.
 * Equals gmmrrt_gmm_task_cost where p is at least every held term (inside the ridges); never
 * larger than it. */
double gmmrrt_gmm_inward_task_cost(const gmmrrt_model_t *model, const double *f, double delta);

/* The task cost of n points of a D = 2 model at once: cost[i] = c((f0[i], f1[i])), what the
 * planner's edge quadrature uses. Vectorised (2 or 4 points per instruction, the same bits
 * either way, with its own exp); agrees with gmmrrt_gmm_task_cost (scalar, libm's exp) and
 * with delta / exp(gmmrrt_gmm_log_density) to about 1e-14 relative. NaN or infinite features cost 1. model->dim == 2, delta > 0, arrays of n >= 0 entries. */
void gmmrrt_gmm_task_cost_batch(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n,
                                double delta, double *cost);

/* p(f) of n points of a D = 2 model at once into p[i], through the task-cost kernel (p = d / c
 * with a floor d = 1e-280: below it p is 0). Agrees with gmmrrt_gmm_density to about 1e-13
 * relative above the floor; the same bits on every vector width. */
void gmmrrt_gmm_density_batch(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n, double *p);

/* gmmrrt_gmm_inward_task_cost of n points at once (same kernel, same contract as
 * gmmrrt_gmm_task_cost_batch; agrees with the one-point call to about 1e-14 relative). */
void gmmrrt_gmm_inward_task_cost_batch(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n,
                                       double delta, double *cost);

/* Draws a component by weight, then f = mu + L z (z standard normal); angles wrapped.
 * Returns the component index. */
int32_t gmmrrt_gmm_sample(const gmmrrt_model_t *model, gmmrrt_rng_t *rng, double *f_out);

/* Draws from component i only (the GMM-RRT baseline walks components in order). */
void gmmrrt_gmm_sample_component(const gmmrrt_model_t *model, int32_t i, gmmrrt_rng_t *rng, double *f_out);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_GMM_H */
