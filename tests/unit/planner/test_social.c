/*
 * test_social.c - planner.social: GMM-RRT* with hand-built (d, theta) mixtures (paper
 * Sect. 4): a 'left' avoid model makes the path pass on the person's left (theta > 0) and
 * keep clear of them; a two-side model with an obstacle blocking one side takes the other
 * side (the paper's Fig. 5); the task cost alone (gmm_bias = 0) still picks the model's
 * side; a larger delta pulls the path towards the model's distance. Several people: each point
 * is costed by its nearest person, bit for bit the one-person cost with one person. The inward
 * cost leaves a wide pass straight where the paper's bends it in. A preferred side is kept
 * whatever the cost prefers, and is a status when it is blocked.
 * Tests with models learned from logs/demos/: test_learned.py (planner.learned_*).
 *
 * Scene: the person stands at the origin facing the robot's start (yaw = pi), the robot
 * goes from (-4, 0) to (4, 0). In that person's frame y' = -y, so their left is world y < 0.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "gmmrrt/features.h"
#include "gmmrrt/gmm.h"
#include "planner_fixtures.h"

static const gmmrrt_pose_t person = {0.0, 0.0, M_PI};

/* Signed side of the path where it crosses the person's x' = 0 line (world x = 0), and
 * the smallest distance of any waypoint to the person. */
static void path_side(const gmmrrt_path_t *path, double *y_at_cross, double *min_dist)
{
    *min_dist = INFINITY;
    *y_at_cross = NAN;
    for (int32_t i = 0; i < path->num_points; ++i) {
        const double d = hypot(path->x[i] - person.x, path->y[i] - person.y);
        if (d < *min_dist)
            *min_dist = d;
        if (i > 0 && path->x[i - 1] < 0.0 && path->x[i] >= 0.0) {
            const double u = -path->x[i - 1] / (path->x[i] - path->x[i - 1]);
            *y_at_cross = path->y[i - 1] + u * (path->y[i] - path->y[i - 1]);
        }
    }
}

static double delta_override = 0.0; /* 0: the model's delta */

static gmmrrt_status_t plan(const gmmrrt_model_t *m, uint64_t seed, double gmm_bias, double w_task, int block_left,
                            gmmrrt_path_t *path)
{
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.seed = seed;
    cfg.gmm_bias = gmm_bias;
    cfg.w_task = w_task;
    cfg.max_nodes = 20000;
    cfg.delta = delta_override;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
    pr.goal_tolerance_m = 0.1;
    pr.task = GMMRRT_TASK_AVOID;
    pr.model = m;
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = person;
    if (block_left) { /* a wall from just left of the person to the bounds (Fig. 5's shadow) */
        pr.obstacles.num_boxes = 1;
        pr.obstacles.boxes[0] = (gmmrrt_box_t){0.0, -2.9, 0.4, 4.2, 0.0};
    }
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t b = {0.0, 15000, 0.0, 0};
    gmmrrt_plan_stats_t st;
    const gmmrrt_status_t s = gmmrrt_planner_run(t.p, &b, &st);
    gmmrrt_planner_best_path(t.p, path);
    test_planner_free(&t);
    return s;
}

static void left_model(gmmrrt_model_t *m)
{
    const double theta[] = {M_PI / 6, M_PI / 3, M_PI / 2, 2 * M_PI / 3, 5 * M_PI / 6};
    assert_int_equal(make_features_model(m, theta, 5, 1.2, 0.2, 0.25), GMMRRT_OK);
}

static void two_side_model(gmmrrt_model_t *m)
{
    const double theta[] = {M_PI / 6,  M_PI / 3,  M_PI / 2,  2 * M_PI / 3,  5 * M_PI / 6,
                            -M_PI / 6, -M_PI / 3, -M_PI / 2, -2 * M_PI / 3, -5 * M_PI / 6};
    assert_int_equal(make_features_model(m, theta, 10, 1.2, 0.2, 0.25), GMMRRT_OK);
}

static void test_left_model_passes_on_the_left_and_keeps_clear(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    left_model(&m);
    /* the model's left really is world y < 0 here */
    double x, y;
    gmmrrt_features_to_xy(&person, 1.2, M_PI / 2, &x, &y);
    assert_true(y < -1.0);
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        gmmrrt_path_t path;
        assert_int_equal(plan(&m, seed, 0.95, 2.0, 0, &path), GMMRRT_OK);
        double cross, dmin;
        path_side(&path, &cross, &dmin);
        printf("left model, seed %d: crosses x = 0 at y = %.2f, closest %.2f m\n", (int)seed, cross, dmin);
        /* left of the person, and never within collision distance (0.25 + 0.3 m) plus 0.1 m */
        assert_true(cross < -0.65);
        assert_true(dmin > 0.65);
    }
}

/* With the paper's delta = 0.001 the cost is flat wherever p >> delta, so the path runs
 * along the inner edge of the model's support; a larger delta grades the support and pulls
 * the path towards the model's distance (1.2 m here). */
static void test_larger_delta_pulls_the_path_to_the_model_distance(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    left_model(&m);
    const double deltas[] = {0.001, 0.05, 0.2};
    double closest[3];
    for (int i = 0; i < 3; ++i) {
        delta_override = deltas[i];
        gmmrrt_path_t path;
        assert_int_equal(plan(&m, 1, 0.95, 2.0, 0, &path), GMMRRT_OK);
        double cross;
        path_side(&path, &cross, &closest[i]);
        printf("left model, delta %.3f: crosses x = 0 at y = %.2f, closest %.2f m\n", deltas[i], cross, closest[i]);
        assert_true(cross < 0.0);
    }
    delta_override = 0.0;
    assert_true(closest[1] > closest[0] + 0.1);
    assert_true(closest[2] >= closest[1] - 0.02);
    assert_true(closest[2] > 1.0 && closest[2] < 1.4);
}

static void test_task_cost_alone_picks_the_model_side(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    left_model(&m);
    gmmrrt_path_t path;
    assert_int_equal(plan(&m, 4, 0.0, 2.0, 0, &path), GMMRRT_OK);
    double cross, dmin;
    path_side(&path, &cross, &dmin);
    printf("left model, uniform sampling: crosses at y = %.2f\n", cross);
    assert_true(cross < 0.0);
}

static void test_mirrored_model_passes_on_the_right(void **state)
{
    (void)state;
    const double theta[] = {-M_PI / 6, -M_PI / 3, -M_PI / 2, -2 * M_PI / 3, -5 * M_PI / 6};
    gmmrrt_model_t m;
    assert_int_equal(make_features_model(&m, theta, 5, 1.2, 0.2, 0.25), GMMRRT_OK);
    gmmrrt_path_t path;
    assert_int_equal(plan(&m, 2, 0.95, 2.0, 0, &path), GMMRRT_OK);
    double cross, dmin;
    path_side(&path, &cross, &dmin);
    printf("mirrored model, seed 2: crosses x = 0 at y = %.2f, closest %.2f m\n", cross, dmin);
    /* the mirror image of the left model's contract */
    assert_true(cross > 0.65);
    assert_true(dmin > 0.65);
}

static void test_two_side_model_takes_the_free_side_when_one_is_blocked(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    two_side_model(&m);
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        gmmrrt_path_t path;
        assert_int_equal(plan(&m, seed, 0.95, 2.0, 1, &path), GMMRRT_OK);
        double cross, dmin;
        path_side(&path, &cross, &dmin);
        printf("two-side model, left blocked, seed %d: crosses at y = %.2f, closest %.2f m\n", (int)seed, cross,
               dmin);
        assert_true(cross > 0.7);
        assert_true(dmin > 0.7);
    }
}

/* A person beyond person_influence_m of the start-goal segment does not shape the plan:
 * same seed, same path with or without them; one near the path does. */
static void test_only_people_near_the_path_count(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    left_model(&m);
    gmmrrt_path_t paths[3];
    for (int extra = 0; extra < 3; ++extra) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.max_nodes = 6000;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
        pr.goal_tolerance_m = 0.1;
        pr.task = GMMRRT_TASK_AVOID;
        pr.model = &m;
        pr.obstacles.num_people = extra ? 2 : 1;
        pr.obstacles.people[0] = person;
        /* extra 1: 4.5 m off the segment (influence 3 m), in a corner no sample reaches first;
         * extra 2: 2.5 m off it, within influence */
        pr.obstacles.people[1] = extra == 1 ? (gmmrrt_pose_t){6.5, 4.5, 0.0} : (gmmrrt_pose_t){2.5, 2.5, 0.0};
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = {0.0, 3000, 0.0, 0};
        assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
        assert_int_equal(gmmrrt_planner_best_path(t.p, &paths[extra]), GMMRRT_OK);
        test_planner_free(&t);
    }
    assert_true(paths[1].cost == paths[0].cost);
    assert_int_equal(paths[1].num_points, paths[0].num_points);
    assert_memory_equal(paths[1].x, paths[0].x, sizeof(double) * (size_t)paths[0].num_points);
    assert_true(paths[2].cost != paths[0].cost);
}

/* ---------------------------------------------------------------- several people */

/* The edge cost by definition (objective.c's contract), point by point: midpoint rule with
 * n = ceil(len / res), each point costed through a one-point batch (lanes never mix, so a
 * point gets the same bits alone as in a chunk) relative to the nearest of people[0..np). */
static double oracle_edge_cost(const gmmrrt_planner_config_t *cfg, const gmmrrt_model_t *m, const gmmrrt_model_t *bg,
                               double delta, const gmmrrt_pose_t *people, int np, double x0, double y0, double x1,
                               double y1)
{
    const double dx = x1 - x0, dy = y1 - y0;
    const double len = sqrt(dx * dx + dy * dy);
    double n = ceil(len / cfg->edge_resolution_m);
    if (n < 1.0)
        n = 1.0;
    const double h = len / n;
    double sum = 0.0;
    for (int32_t i = 0; i < (int32_t)n; ++i) {
        const double t = ((double)i + 0.5) / n;
        const double x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
        int best = 0;
        for (int k = 1; k < np; ++k)
            if (hypot(x - people[k].x, y - people[k].y) < hypot(x - people[best].x, y - people[best].y))
                best = k;
        double d, theta, c;
        gmmrrt_features_from_xy_cs(&people[best], cos(people[best].yaw), sin(people[best].yaw), x, y, &d, &theta);
        if (cfg->task_cost == GMMRRT_TASK_COST_INWARD) {
            gmmrrt_gmm_inward_task_cost_batch(m, &d, &theta, 1, delta, &c);
        } else if (cfg->task_cost == GMMRRT_TASK_COST_BACKGROUND) {
            double p, pb;
            gmmrrt_gmm_density_batch(m, &d, &theta, 1, &p);
            gmmrrt_gmm_density_batch(bg, &d, &theta, 1, &pb);
            c = (pb + delta) / (p + pb + 2.0 * delta);
        } else
            gmmrrt_gmm_task_cost_batch(m, &d, &theta, 1, delta, &c);
        sum += c;
    }
    return cfg->w_length * len + cfg->w_task * h * sum;
}

/* The cost of the edge start -> (x, y) as the planner charges it: node 1 of a tree seeded
 * with that one point (the root costs 0). */
static double planner_edge_cost(const gmmrrt_planner_config_t *cfg, const gmmrrt_problem_t *pr, double x, double y)
{
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, cfg), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, pr), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_seed_path(t.p, &x, &y, 1), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_node_count(t.p), 2);
    double c;
    assert_int_equal(gmmrrt_planner_node(t.p, 1, NULL, NULL, NULL, &c), GMMRRT_OK);
    test_planner_free(&t);
    return c;
}

/* One person: the cost is the one-person cost, bit for bit. Two people: every point is costed
 * by its nearest person (so an edge that stays nearer the first one costs exactly what it
 * costs with the first one alone), and the edge past the second one is charged by it. Both
 * task costs. */
static void test_each_point_is_costed_by_its_nearest_person(void **state)
{
    (void)state;
    gmmrrt_model_t m, bg;
    two_side_model(&m);
    left_model(&bg); /* any features model will do as the background here */
    const gmmrrt_pose_t people[2] = {person, {1.5, 2.2, -M_PI / 2}};
    const double ends[4][2] = {{-1.0, -1.5}, {0.0, 1.2}, {1.0, 3.2}, {2.8, 2.0}};
    for (int kind = GMMRRT_TASK_COST_PAPER; kind <= GMMRRT_TASK_COST_BACKGROUND; ++kind) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.task_cost = kind;
        cfg.max_nodes = 100;
        gmmrrt_problem_t pr = empty_problem(-3.0, -0.3, 4.0, 0.0);
        pr.task = GMMRRT_TASK_AVOID;
        pr.model = &m;
        pr.background_model = &bg;
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = people[0];
        int changed = 0;
        for (int e = 0; e < 4; ++e) {
            pr.obstacles.num_people = 1;
            const double alone = planner_edge_cost(&cfg, &pr, ends[e][0], ends[e][1]);
            assert_true(alone == oracle_edge_cost(&cfg, &m, &bg, m.delta, people, 1, -3.0, -0.3, ends[e][0], ends[e][1]));
            pr.obstacles.num_people = 2;
            pr.obstacles.people[1] = people[1];
            const double both = planner_edge_cost(&cfg, &pr, ends[e][0], ends[e][1]);
            assert_true(both == oracle_edge_cost(&cfg, &m, &bg, m.delta, people, 2, -3.0, -0.3, ends[e][0], ends[e][1]));
            /* the first edge never comes nearer the second person than the first */
            if (e == 0)
                assert_true(both == alone);
            changed += both != alone;
        }
        assert_true(changed >= 2);
    }
    /* The background cost without a background model is a model mismatch. */
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.task_cost = GMMRRT_TASK_COST_BACKGROUND;
    cfg.max_nodes = 100;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-3.0, -0.3, 4.0, 0.0);
    pr.task = GMMRRT_TASK_AVOID;
    pr.model = &m;
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = person;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_MODEL_MISMATCH);
    pr.background_model = &bg;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    test_planner_free(&t);
}

/* ---------------------------------------------------------------- the inward cost */

/* Start and goal 2.5 m to the side of the person, the model's support at 1.2 m: a walker this
 * far out does not swerve. The paper's cost charges the straight line the most (it lies
 * beyond the support) and bends the path in towards the person; the inward cost leaves it
 * (nearly) straight. */
static void test_inward_cost_leaves_a_wide_pass_straight(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    two_side_model(&m);
    double closest[2] = {0.0, 0.0}, length[2] = {0.0, 0.0};
    for (int kind = GMMRRT_TASK_COST_PAPER; kind <= GMMRRT_TASK_COST_INWARD; ++kind) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.task_cost = kind;
        cfg.max_nodes = 20000;
        cfg.seed = 5;
        cfg.gmm_bias = 0.5; /* the mixture's samples lie on the support: leave room for the straight line */
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 2.5, 4.0, 2.5);
        pr.goal_tolerance_m = 0.1;
        pr.task = GMMRRT_TASK_AVOID;
        pr.model = &m;
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = person;
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = {0.0, 8000, 0.0, 0};
        assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
        gmmrrt_path_t path;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
        test_planner_free(&t);
        double dmin = INFINITY;
        for (int32_t i = 0; i < path.num_points; ++i)
            dmin = fmin(dmin, hypot(path.x[i], path.y[i]));
        closest[kind - 1] = dmin;
        length[kind - 1] = path.length_m;
        printf("wide pass, %s cost: closest %.2f m, length %.2f m (straight 8.00)\n",
               kind == GMMRRT_TASK_COST_PAPER ? "paper" : "inward", dmin, path.length_m);
    }
    assert_true(closest[0] < 2.0);                        /* the paper's cost bends the path in */
    assert_true(closest[1] > 2.3 && length[1] < 8.2);     /* the inward cost does not */
}

/* ---------------------------------------------------------------- the preferred side */

static gmmrrt_status_t plan_side(const gmmrrt_model_t *m, int side, int block_left, gmmrrt_path_t *path)
{
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.max_nodes = 10000;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
    pr.goal_tolerance_m = 0.1;
    pr.task = GMMRRT_TASK_AVOID;
    pr.model = m;
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = person;
    pr.side = side;
    pr.side_person = -1;
    if (block_left) {
        pr.obstacles.num_boxes = 1;
        pr.obstacles.boxes[0] = (gmmrrt_box_t){0.0, -2.9, 0.4, 4.2, 0.0};
    }
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t b = {0.0, 6000, 0.0, 0};
    const gmmrrt_status_t s = gmmrrt_planner_run(t.p, &b, NULL);
    path->num_points = 0;
    gmmrrt_planner_best_path(t.p, path);
    test_planner_free(&t);
    return s;
}

/* The robot goes +x past the person at the origin: LEFT (counterclockwise seen from the
 * person, the person on the robot's left) is world y < 0, RIGHT y > 0. Each side is kept with
 * a model of the other side, and with a model of both. */
static void test_preferred_side_is_kept_against_the_cost(void **state)
{
    (void)state;
    gmmrrt_model_t left, both;
    left_model(&left); /* prefers world y < 0 */
    two_side_model(&both);
    const gmmrrt_model_t *models[2] = {&left, &both};
    for (int mi = 0; mi < 2; ++mi) {
        for (int side = GMMRRT_SIDE_LEFT; side <= GMMRRT_SIDE_RIGHT; ++side) {
            gmmrrt_path_t path;
            assert_int_equal(plan_side(models[mi], side, 0, &path), GMMRRT_OK);
            double cross, dmin;
            path_side(&path, &cross, &dmin);
            printf("model %d, side %s: crosses x = 0 at y = %.2f\n", mi, side == GMMRRT_SIDE_LEFT ? "left" : "right",
                   cross);
            assert_true(side == GMMRRT_SIDE_LEFT ? cross < -0.55 : cross > 0.55);
            assert_true(dmin > 0.55);
        }
    }
}

/* A wall closes the y < 0 side: LEFT has no path (a status, not an error), RIGHT has one,
 * and an invalid side or side person is refused. */
static void test_blocked_preferred_side_is_a_status(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    two_side_model(&m);
    gmmrrt_path_t path;
    assert_int_equal(plan_side(&m, GMMRRT_SIDE_LEFT, 1, &path), GMMRRT_NO_PATH_ON_SIDE);
    assert_int_equal(path.num_points, 0);
    assert_int_equal(plan_side(&m, GMMRRT_SIDE_RIGHT, 1, &path), GMMRRT_OK);
    assert_string_equal(gmmrrt_status_str(GMMRRT_NO_PATH_ON_SIDE), "no path on the preferred side");

    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.max_nodes = 100;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
    pr.task = GMMRRT_TASK_AVOID;
    pr.model = &m;
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = person;
    pr.side = 3;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr.side = GMMRRT_SIDE_LEFT;
    pr.side_person = 1;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr.side_person = 0;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    test_planner_free(&t);
}

/* GMM-RRT (the baseline) with an xy model of a pass on the person's left. */
static void test_gmm_rrt_follows_its_xy_model(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    memset(&m, 0, sizeof m);
    m.kind = GMMRRT_MODEL_KIND_XY;
    m.task = GMMRRT_TASK_AVOID;
    m.homotopy = GMMRRT_HOMOTOPY_LEFT;
    m.dim = 3;
    m.k = 7;
    m.delta = GMMRRT_MODEL_DEFAULT_DELTA;
    for (int32_t i = 0; i < m.k; ++i) {
        const double s = (i + 0.5) / m.k;
        const int32_t slot = m.k - 1 - i; /* stored out of order: the planner sorts by s */
        m.weight[slot] = 1.0 / m.k;
        m.mean[slot][0] = s;
        m.mean[slot][1] = 3.5 - 7.0 * s;           /* x': from the person's front to behind */
        m.mean[slot][2] = 1.3 * sin(M_PI * s);     /* y' > 0: their left */
        m.chol[slot][0] = 0.05;
        m.chol[slot][2] = 0.25;
        m.chol[slot][5] = 0.25;
    }
    double sum = 0.0;
    for (int32_t i = 1; i < m.k; ++i)
        sum += m.weight[i];
    m.weight[0] = 1.0 - sum;
    assert_int_equal(gmmrrt_model_prepare(&m, NULL, 0), GMMRRT_OK);
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.planner = GMMRRT_PLANNER_GMM_RRT;
        cfg.seed = seed;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
        pr.goal_tolerance_m = 0.1;
        pr.task = GMMRRT_TASK_AVOID;
        pr.model = &m;
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = person;
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = {0.0, 20000, 0.0, 0};
        gmmrrt_plan_stats_t st;
        assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
        gmmrrt_path_t path;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
        double cross, dmin;
        path_side(&path, &cross, &dmin);
        printf("gmm-rrt, left xy model, seed %d: crosses at y = %.2f after %lld iterations, %d nodes\n",
               (int)seed, cross, (long long)st.first_solution_iteration, st.nodes);
        assert_true(cross < -0.65);
        test_planner_free(&t);
    }
}

/* APPROACH: the model of the target person (components on their front axis, theta = 0,
 * at 1.3-3.1 m) bends the arrival towards that axis: 2 m of path before the goal the
 * bearing from the person is smaller than plain RRT*'s straight-line arrival. Person 0
 * stands far off and is not the target. */
static void test_approach_arrives_along_the_model(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    memset(&m, 0, sizeof m);
    m.kind = GMMRRT_MODEL_KIND_FEATURES;
    m.task = GMMRRT_TASK_APPROACH;
    m.dim = 2;
    m.k = 4;
    m.angle_mask = 0x2u;
    m.delta = GMMRRT_MODEL_DEFAULT_DELTA;
    for (int32_t i = 0; i < 4; ++i) {
        m.weight[i] = 0.25;
        m.mean[i][0] = 1.3 + 0.6 * i;
        m.mean[i][1] = 0.0;
        m.chol[i][0] = 0.3;
        m.chol[i][2] = 0.15;
    }
    assert_int_equal(gmmrrt_model_prepare(&m, NULL, 0), GMMRRT_OK);
    const gmmrrt_pose_t target = {0.0, 0.0, 0.0}; /* faces +x: the goal is 1 m in front */
    double bearing[2];
    for (int plain = 0; plain < 2; ++plain) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.planner = plain ? GMMRRT_PLANNER_RRT_STAR : GMMRRT_PLANNER_GMM_RRT_STAR;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(4.0, 3.0, 1.0, 0.0);
        pr.goal_tolerance_m = 0.1;
        pr.task = GMMRRT_TASK_APPROACH;
        pr.target_person = 1;
        pr.model = &m;
        pr.obstacles.num_people = 2;
        pr.obstacles.people[0] = (gmmrrt_pose_t){-6.0, -4.0, 0.0};
        pr.obstacles.people[1] = target;
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = {0.0, 15000, 0.0, 0};
        assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
        gmmrrt_path_t path;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
        const int32_t back = (int32_t)(2.0 / cfg.waypoint_spacing_m);
        assert_true(path.num_points > back + 1);
        const int32_t i = path.num_points - 1 - back;
        double d;
        gmmrrt_features_from_xy(&target, path.x[i], path.y[i], &d, &bearing[plain]);
        printf("approach, %s: 2 m before the goal at (%.2f, %.2f), d = %.2f, theta = %.2f\n",
               plain ? "rrt-star" : "gmm-rrt-star", path.x[i], path.y[i], d, bearing[plain]);
        test_planner_free(&t);
    }
    assert_true(bearing[0] < bearing[1] - 0.08);
    assert_true(fabs(bearing[0]) < 0.45);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_left_model_passes_on_the_left_and_keeps_clear),
        cmocka_unit_test(test_larger_delta_pulls_the_path_to_the_model_distance),
        cmocka_unit_test(test_task_cost_alone_picks_the_model_side),
        cmocka_unit_test(test_mirrored_model_passes_on_the_right),
        cmocka_unit_test(test_two_side_model_takes_the_free_side_when_one_is_blocked),
        cmocka_unit_test(test_only_people_near_the_path_count),
        cmocka_unit_test(test_each_point_is_costed_by_its_nearest_person),
        cmocka_unit_test(test_inward_cost_leaves_a_wide_pass_straight),
        cmocka_unit_test(test_preferred_side_is_kept_against_the_cost),
        cmocka_unit_test(test_blocked_preferred_side_is_a_status),
        cmocka_unit_test(test_gmm_rrt_follows_its_xy_model),
        cmocka_unit_test(test_approach_arrives_along_the_model),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
