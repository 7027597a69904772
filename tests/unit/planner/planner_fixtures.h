/*
 * planner_fixtures.h - shared problem builders for the planner tests: the disc problem
 * (start (-5, 0), goal (5, 0), disc of radius 2 at the origin, point robot; the
 * shortest path wraps the disc: 2 sqrt(21) + 2 (pi - 2 acos(2/5)) = 10.8110 m) and
 * hand-built (d, theta) mixtures for the social tests.
 */
#ifndef GMMRRT_TEST_PLANNER_FIXTURES_H
#define GMMRRT_TEST_PLANNER_FIXTURES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gmmrrt/gmm.h"
#include "gmmrrt/model.h"
#include "gmmrrt/planner.h"

/* Closed form of the disc detour, so the tests do not carry a magic number. */
static inline double disc_detour_length(double half_span_m, double radius_m)
{
    const double tangent = sqrt(half_span_m * half_span_m - radius_m * radius_m);
    const double arc = radius_m * (M_PI - 2.0 * acos(radius_m / half_span_m));
    return 2.0 * tangent + arc;
}

static inline gmmrrt_problem_t empty_problem(double sx, double sy, double gx, double gy)
{
    gmmrrt_problem_t pr;
    memset(&pr, 0, sizeof pr);
    pr.start_x = sx;
    pr.start_y = sy;
    pr.goal_x = gx;
    pr.goal_y = gy;
    pr.goal_tolerance_m = 0.05;
    pr.task = GMMRRT_TASK_NONE;
    pr.target_person = -1;
    pr.model = NULL;
    pr.obstacles.bounds = (gmmrrt_bounds_t){-7.0, -5.0, 7.0, 5.0};
    return pr;
}

static inline gmmrrt_problem_t disc_problem(void)
{
    gmmrrt_problem_t pr = empty_problem(-5.0, 0.0, 5.0, 0.0);
    pr.obstacles.num_circles = 1;
    pr.obstacles.circles[0] = (gmmrrt_circle_t){0.0, 0.0, 2.0};
    return pr;
}

/* Avoid one person standing at the origin facing -x, from (-4, 0) to (4, 0), with `model`. */
static inline gmmrrt_problem_t avoid_problem(const gmmrrt_model_t *model)
{
    gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
    pr.task = GMMRRT_TASK_AVOID;
    pr.model = model;
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, M_PI};
    return pr;
}

static inline gmmrrt_planner_config_t point_robot_config(int32_t kind)
{
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.planner = kind;
    cfg.robot_radius_m = 0.0;
    cfg.grid_resolution_m = 0.02;
    cfg.max_nodes = 20000;
    return cfg;
}

/* Planner in a heap block owned by the test (allocation before init is allowed). */
typedef struct {
    void *mem;
    gmmrrt_planner_t *p;
} test_planner_t;

static inline gmmrrt_status_t test_planner_make(test_planner_t *t, const gmmrrt_planner_config_t *cfg)
{
    const size_t size = gmmrrt_planner_mem_size(cfg);
    t->mem = size ? aligned_alloc(8, (size + 7u) & ~(size_t)7u) : NULL;
    t->p = NULL;
    if (!t->mem)
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    return gmmrrt_planner_init(&t->p, t->mem, size, cfg);
}

static inline void test_planner_free(test_planner_t *t)
{
    free(t->mem);
    t->mem = NULL;
    t->p = NULL;
}

/* A (d, theta) mixture with components along the bearings theta[i] at distance d_m:
 * sigma_d, sigma_theta standard deviations; equal weights. */
static inline gmmrrt_status_t make_features_model(gmmrrt_model_t *m, const double *theta, int32_t k, double d_m,
                                                  double sigma_d, double sigma_theta)
{
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_FEATURES;
    m->task = GMMRRT_TASK_AVOID;
    m->homotopy = GMMRRT_HOMOTOPY_ALL;
    m->dim = 2;
    m->k = k;
    m->angle_mask = 1u << 1;
    m->delta = GMMRRT_MODEL_DEFAULT_DELTA;
    for (int32_t i = 0; i < k; ++i) {
        m->weight[i] = 1.0 / (double)k;
        m->mean[i][0] = d_m;
        m->mean[i][1] = theta[i];
        m->chol[i][0] = sigma_d;
        m->chol[i][1] = 0.0;
        m->chol[i][2] = sigma_theta;
    }
    double sum = 0.0;
    for (int32_t i = 0; i < k - 1; ++i)
        sum += m->weight[i];
    m->weight[k - 1] = 1.0 - sum;
    return gmmrrt_model_prepare(m, NULL, 0);
}

#endif /* GMMRRT_TEST_PLANNER_FIXTURES_H */
