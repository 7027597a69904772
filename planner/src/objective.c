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

double gmmrrt_task_cost_at(const struct gmmrrt_planner *p, double x, double y)
{
    if (!p->task_active || p->num_active == 0)
        return 1.0;
    double c = 0.0;
    for (int32_t k = 0; k < p->num_active; ++k) {
        double f[2];
        gmmrrt_features_from_xy(&p->problem.obstacles.people[p->active[k]], x, y, &f[0], &f[1]);
        const double ck = gmmrrt_gmm_task_cost(p->problem.model, f, p->delta);
        if (ck > c)
            c = ck;
    }
    return c;
}

double gmmrrt_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
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
    for (int32_t i = 0; i < steps; ++i) {
        const double t = ((double)i + 0.5) / n;
        sum_c += gmmrrt_task_cost_at(p, x0 + t * (x1 - x0), y0 + t * (y1 - y0));
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
