/*
 * objective.c - the planner's cost (paper Sect. 4): the cost of an edge is
 *     integral over the edge of (w_length + w_task c(f(x))) ds,
 *     c(f) = delta / max(p(f), delta)  (gmm.h, gmmrrt_gmm_task_cost),
 * f the features (d, theta) of x relative to the person the task is about; in AVOID with
 * several people, c is the largest over the people near the start-goal segment. Where no
 * task applies c = 1, the value the cost takes far from any person, so the cost stays a
 * positive multiple of length. Quadrature: composite midpoint rule with
 * n = ceil(length / edge_resolution_m) equal sub-intervals (exact for the length term,
 * symmetric in the edge's direction). rrt-star and gmm-rrt use plain length.
 */
#include <math.h>

#include "gmmrrt/features.h"
#include "gmmrrt/gmm.h"
#include "planner_internal.h"

/* Quadrature points weighed per kernel call (edges of more points go in chunks, summed in
 * the same order, so the chunking does not change the result). */
#define EDGE_CHUNK 64

/* Task costs of the n points (x[i], y[i]) into c[i]: the largest over the active people.
 * The person's cos/sin of yaw are taken once (set_problem) instead of per point. */
static void task_costs(const struct gmmrrt_planner *p, const double *x, const double *y, int32_t n, double *c)
{
    double d[EDGE_CHUNK], theta[EDGE_CHUNK], ck[EDGE_CHUNK];
    for (int32_t i = 0; i < n; ++i)
        c[i] = 0.0;
    for (int32_t k = 0; k < p->num_active; ++k) {
        const gmmrrt_pose_t *person = &p->problem.obstacles.people[p->active[k]];
        for (int32_t i = 0; i < n; ++i)
            gmmrrt_features_from_xy_cs(person, p->active_cos[k], p->active_sin[k], x[i], y[i], &d[i], &theta[i]);
        gmmrrt_gmm_task_cost_batch(p->problem.model, d, theta, n, p->delta, ck);
        for (int32_t i = 0; i < n; ++i)
            if (ck[i] > c[i])
                c[i] = ck[i];
    }
}

static double standing_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1);

/* The edge cost; walking people (moving_people.c) add w_task times their social cost for
 * GMM-RRT*. The term is >= 0, so gmmrrt_edge_cost_lower_bound stays a lower bound. */
double gmmrrt_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    const double c = standing_edge_cost(p, x0, y0, x1, y1);
    if (p->walkers.count == 0 || p->cfg.planner != GMMRRT_PLANNER_GMM_RRT_STAR)
        return c;
    return c + p->cfg.w_task * gmmrrt_walkers_cost(&p->walkers, x0, y0, x1, y1, p->cfg.edge_resolution_m);
}

static double standing_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    const double dx = x1 - x0, dy = y1 - y0;
    const double len = sqrt(dx * dx + dy * dy); /* plain sqrt: hypot is far slower; inputs are map coordinates */
    if (p->cfg.planner != GMMRRT_PLANNER_GMM_RRT_STAR)
        return len;
    if (!p->task_active || p->num_active == 0)
        return (p->cfg.w_length + p->cfg.w_task) * len;
    if (len == 0.0)
        return 0.0;
    double n = ceil(len / p->cfg.edge_resolution_m);
    if (n < 1.0)
        n = 1.0;
    const int32_t steps = (int32_t)n;
    const double h = len / n;
    double sum_c = 0.0;
    for (int32_t start = 0; start < steps; start += EDGE_CHUNK) {
        const int32_t count = steps - start < EDGE_CHUNK ? steps - start : EDGE_CHUNK;
        double x[EDGE_CHUNK], y[EDGE_CHUNK], c[EDGE_CHUNK];
        for (int32_t i = 0; i < count; ++i) {
            const double t = ((double)(start + i) + 0.5) / n;
            x[i] = x0 + t * (x1 - x0);
            y[i] = y0 + t * (y1 - y0);
        }
        task_costs(p, x, y, count, c);
        for (int32_t i = 0; i < count; ++i)
            sum_c += c[i];
    }
    return p->cfg.w_length * len + p->cfg.w_task * h * sum_c;
}

double gmmrrt_edge_cost_lower_bound(const struct gmmrrt_planner *p, double len_m)
{
    if (p->cfg.planner != GMMRRT_PLANNER_GMM_RRT_STAR)
        return len_m;
    if (!p->task_active || p->num_active == 0)
        return (p->cfg.w_length + p->cfg.w_task) * len_m;
    return p->cfg.w_length * len_m;
}
