/*
 * objective.c - the planner's cost (paper Sect. 4): the cost of an edge is
 *     integral over the edge of (w_length + w_task c(f(x))) ds,
 * c the task cost of cfg.task_cost (gmm.h): the paper's delta / max(p(f), delta) (the
 * default) or the inward variant (gmmrrt_gmm_inward_task_cost; docs/planner.md gives the
 * evidence for both), f the features (d, theta) of x relative to the person the task is about. In
 * AVOID with several people that is, point by point, the person nearest x among the active
 * ones (those within person_influence_m of the start-goal segment): the person a walker at x
 * is passing is the one it is next to, and the demonstrations are of one person at a time.
 * With one person this is exactly the one-person cost. (The largest cost over the people
 * charges every point for the farthest person's empty far field and pulled paths into the
 * crowd's gaps; docs/planner.md.) Where no task applies c = 1, so the cost stays a positive
 * multiple of length. Quadrature: composite midpoint rule with
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

/* Task costs of the n points (x[i], y[i]) into c[i], each relative to the nearest active
 * person (the first of equally near ones). The people's cos/sin of yaw are taken once
 * (set_problem) instead of per point. */
static void task_costs(const struct gmmrrt_planner *p, const double *x, const double *y, int32_t n, double *c)
{
    double d[EDGE_CHUNK], theta[EDGE_CHUNK];
    const gmmrrt_pose_t *people = p->problem.obstacles.people;
    for (int32_t i = 0; i < n; ++i) {
        int32_t best = 0;
        if (p->num_active > 1) {
            double best_d2 = INFINITY;
            for (int32_t k = 0; k < p->num_active; ++k) {
                const double dx = x[i] - people[p->active[k]].x, dy = y[i] - people[p->active[k]].y;
                const double d2 = dx * dx + dy * dy;
                if (d2 < best_d2) {
                    best_d2 = d2;
                    best = k;
                }
            }
        }
        gmmrrt_features_from_xy_cs(&people[p->active[best]], p->active_cos[best], p->active_sin[best], x[i], y[i],
                                   &d[i], &theta[i]);
    }
    if (p->cfg.task_cost == GMMRRT_TASK_COST_INWARD) {
        gmmrrt_gmm_inward_task_cost_batch(p->problem.model, d, theta, n, p->delta, c);
    } else if (p->cfg.task_cost == GMMRRT_TASK_COST_BACKGROUND) {
        /* The share of the background at x: 0 where only the demonstrations go (people swerve
         * there), 1 where only the straight lines go (people keep away), 1/2 where both or
         * neither do (delta, the model's floor, stands for "no evidence"). */
        double pb[EDGE_CHUNK];
        gmmrrt_gmm_density_batch(p->problem.model, d, theta, n, c);
        gmmrrt_gmm_density_batch(p->problem.background_model, d, theta, n, pb);
        for (int32_t i = 0; i < n; ++i)
            c[i] = (pb[i] + p->delta) / (c[i] + pb[i] + 2.0 * p->delta);
    } else {
        gmmrrt_gmm_task_cost_batch(p->problem.model, d, theta, n, p->delta, c);
    }
}

static double standing_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1);

/* The edge cost; walking people (moving_people.c) add w_task times their social cost for
 * GMM-RRT*. The term is >= 0, so gmmrrt_edge_cost_lower_bound stays a lower bound. */
double gmmrrt_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    const double c = standing_edge_cost(p, x0, y0, x1, y1);
    if (p->walkers.count == 0 || !p->strategy.task_cost)
        return c;
    return c + p->cfg.w_task * gmmrrt_walkers_cost(&p->walkers, x0, y0, x1, y1, p->cfg.edge_resolution_m);
}

static double standing_edge_cost(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    const double dx = x1 - x0, dy = y1 - y0;
    const double len = sqrt(dx * dx + dy * dy); /* plain sqrt: hypot is far slower; inputs are map coordinates */
    if (!p->strategy.task_cost)
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
    if (!p->strategy.task_cost)
        return len_m;
    if (!p->task_active || p->num_active == 0)
        return (p->cfg.w_length + p->cfg.w_task) * len_m;
    return p->cfg.w_length * len_m;
}
