/*
 * sampler.c - where the planner's samples come from (paper Sect. 4, item 2; Sect. 5.3).
 *
 * Every planner: with probability goal_bias the goal itself.
 * gmm-rrt-star: otherwise, with probability gmm_bias, a feature sample f = (d, theta) from
 *   the FEATURES mixture mapped to x-y around one person (gmmrrt_features_to_xy): in AVOID
 *   a person drawn uniformly among those near the start-goal segment, in APPROACH the
 *   target person; else uniform in the bounds. gmm_bias = 0 is plain RRT*.
 * rrt-star: uniform in the bounds.
 * gmm-rrt (Claassens 2010): with probability gmm_bias a sample of the current stage of the XY
 *   mixture (gmm_rrt.c, the baseline's own file).
 * A mixture sample outside the bounds is discarded: the iteration is spent.
 *
 * Informed sampling (cfg.informed_sampling; Gammell, Srinivasa & Barfoot 2014): once a path
 * of cost c exists, a cheaper path has length L < c / u, u = gmmrrt_edge_cost_lower_bound
 * per metre (every edge costs at least u times its length), so all its points lie in the
 * ellipse { x : |x - start| + |x - goal| < c / u }. Uniform draws then come from that
 * ellipse (when it is smaller than the bounds), and mixture draws outside it are dropped
 * (the iteration is spent): no node outside it can be on a cheaper path, nor make one by
 * rewiring, since a path through it costs at least u times its length.
 */
#include <math.h>

#include "gmmrrt/features.h"
#include "gmmrrt/gmm.h"
#include "planner_internal.h"


static int in_bounds(const struct gmmrrt_planner *p, double x, double y)
{
    const gmmrrt_bounds_t *b = &p->problem.obstacles.bounds;
    return x >= b->xmin && x <= b->xmax && y >= b->ymin && y <= b->ymax;
}

static void uniform(struct gmmrrt_planner *p, double *x, double *y)
{
    const gmmrrt_bounds_t *b = &p->problem.obstacles.bounds;
    *x = b->xmin + gmmrrt_rng_uniform(&p->rng) * (b->xmax - b->xmin);
    *y = b->ymin + gmmrrt_rng_uniform(&p->rng) * (b->ymax - b->ymin);
}

/* Transverse diameter of the informed ellipse (m), or INFINITY while there is no path or
 * informed sampling is off. */
static double informed_diameter(const struct gmmrrt_planner *p)
{
    if (!p->cfg.informed_sampling || !isfinite(p->best_cost))
        return INFINITY;
    const double u = gmmrrt_edge_cost_lower_bound(p, 1.0);
    return u > 0.0 ? p->best_cost / u : INFINITY;
}

static int in_ellipse(const struct gmmrrt_planner *p, double diameter, double x, double y)
{
    const double ax = x - p->problem.start_x, ay = y - p->problem.start_y;
    const double bx = x - p->problem.goal_x, by = y - p->problem.goal_y;
    return sqrt(ax * ax + ay * ay) + sqrt(bx * bx + by * by) <= diameter;
}

/* Semi-minor axis (m) of the informed ellipse of the given transverse diameter. */
static double informed_semi_minor(const struct gmmrrt_planner *p, double diameter)
{
    return 0.5 * sqrt(fmax(diameter * diameter - p->inf_cmin * p->inf_cmin, 0.0));
}

/* Uniform in the informed ellipse of semi-axes a (along start -> goal) and b: a uniform point
 * of the unit disc, scaled to the semi-axes, turned along start -> goal, moved to the centre.
 * Returns 0 when it falls outside the bounds. */
static int informed_uniform(struct gmmrrt_planner *p, double a, double b, double *x, double *y)
{
    const double r = sqrt(gmmrrt_rng_uniform(&p->rng));
    const double phi = 2.0 * M_PI * gmmrrt_rng_uniform(&p->rng);
    const double ex = a * r * cos(phi), ey = b * r * sin(phi);
    *x = p->inf_cx + p->inf_cos * ex - p->inf_sin * ey;
    *y = p->inf_cy + p->inf_sin * ex + p->inf_cos * ey;
    return in_bounds(p, *x, *y);
}

void gmmrrt_sampler_prepare(struct gmmrrt_planner *p)
{
    const double gx = p->problem.goal_x - p->problem.start_x, gy = p->problem.goal_y - p->problem.start_y;
    p->inf_cmin = sqrt(gx * gx + gy * gy);
    p->inf_cx = 0.5 * (p->problem.start_x + p->problem.goal_x);
    p->inf_cy = 0.5 * (p->problem.start_y + p->problem.goal_y);
    p->inf_cos = p->inf_cmin > 0.0 ? gx / p->inf_cmin : 1.0;
    p->inf_sin = p->inf_cmin > 0.0 ? gy / p->inf_cmin : 0.0;
    p->gmm_rrt.stage = 0;
    if (p->strategy.stages && p->problem.model)
        gmmrrt_gmm_rrt_prepare(p);
}

int gmmrrt_sample(struct gmmrrt_planner *p, double *x, double *y)
{
    const gmmrrt_problem_t *pr = &p->problem;
    if (p->cfg.goal_bias > 0.0 && gmmrrt_rng_uniform(&p->rng) < p->cfg.goal_bias) {
        *x = pr->goal_x;
        *y = pr->goal_y;
        return 1;
    }
    const int use_model = p->task_active && p->cfg.gmm_bias > 0.0 &&
                          (p->cfg.gmm_bias >= 1.0 || gmmrrt_rng_uniform(&p->rng) < p->cfg.gmm_bias);
    const double diameter = informed_diameter(p);
    if (!use_model) {
        if (isfinite(diameter)) {
            const gmmrrt_bounds_t *b = &pr->obstacles.bounds;
            const double a = 0.5 * diameter, bb = informed_semi_minor(p, diameter);
            if (M_PI * a * bb < (b->xmax - b->xmin) * (b->ymax - b->ymin))
                return informed_uniform(p, a, bb, x, y);
        }
        uniform(p, x, y);
        return 1;
    }
    if (p->strategy.stages) {
        if (!gmmrrt_gmm_rrt_sample(p, x, y))
            return 1; /* the stages are done: the goal */
    } else {
        double f[GMMRRT_MAX_DIM];
        int32_t who = 0;
        if (p->num_active > 1) {
            who = (int32_t)(gmmrrt_rng_uniform(&p->rng) * (double)p->num_active);
            if (who >= p->num_active)
                who = p->num_active - 1;
        }
        gmmrrt_gmm_sample(pr->model, &p->rng, f);
        gmmrrt_features_to_xy(&pr->obstacles.people[p->active[who]], f[0], f[1], x, y);
    }
    if (isfinite(diameter) && !in_ellipse(p, diameter, *x, *y))
        return 0;
    return in_bounds(p, *x, *y);
}
