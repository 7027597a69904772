/*
 * test_rrtstar.c - planner.rrtstar: the RRT* of planner.h on problems with known answers
 * and its invariants (Karaman & Frazzoli 2011; OMPL-style checks):
 * free straight line, the disc detour converging to its closed-form length, best cost
 * never increasing, every tree edge collision-free (FCL oracle), cost-to-come consistent
 * after rewiring, same seed same path, pool exhaustion, and the statuses of bad problems.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "cluttered_problem.h"
#include "planner_fixtures.h"

static const int32_t kinds_without_model[] = {GMMRRT_PLANNER_RRT_STAR, GMMRRT_PLANNER_GMM_RRT_STAR,
                                              GMMRRT_PLANNER_GMM_RRT};

static void test_free_straight_line_is_found_and_straight(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof kinds_without_model / sizeof kinds_without_model[0]; ++k) {
        gmmrrt_planner_config_t cfg = point_robot_config(kinds_without_model[k]);
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 1.0, 4.0, -1.0);
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = {0.0, 20000, 0.0, 0};
        gmmrrt_plan_stats_t st;
        assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
        gmmrrt_path_t path;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
        const double straight = hypot(8.0, 2.0);
        assert_true(path.num_points >= 2);
        assert_true(path.x[0] == -4.0 && path.y[0] == 1.0);
        assert_true(path.x[path.num_points - 1] == 4.0 && path.y[path.num_points - 1] == -1.0);
        /* RRT (gmm-rrt) is not optimal; RRT* gets within 1 % of the straight line. */
        const double tol = kinds_without_model[k] == GMMRRT_PLANNER_GMM_RRT ? 0.5 : 0.01;
        assert_true(path.length_m >= straight - 1e-9);
        assert_true(path.length_m <= straight * (1.0 + tol));
        /* Every waypoint lies within 0.5 m of the straight segment's line for RRT*. */
        if (kinds_without_model[k] == GMMRRT_PLANNER_RRT_STAR) {
            for (int32_t i = 0; i < path.num_points; ++i) {
                const double dist = fabs(2.0 * path.x[i] + 8.0 * path.y[i] - 0.0) / straight;
                assert_true(dist < 0.5);
            }
        }
        test_planner_free(&t);
    }
}

static double run_disc(uint64_t seed, int64_t iterations, double *first_cost, int32_t *hist_n)
{
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.seed = seed;
    cfg.max_nodes = 60000;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t b = {0.0, iterations, 0.0, 0};
    gmmrrt_plan_stats_t st;
    assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
    static int64_t its[1024];
    static double costs[1024];
    const int32_t n = gmmrrt_planner_cost_history(t.p, its, costs, 1024);
    assert_true(n >= 1);
    *first_cost = costs[0];
    *hist_n = n;
    const double best = st.best_cost;
    test_planner_free(&t);
    return best;
}

static void test_disc_detour_converges_to_closed_form_length(void **state)
{
    (void)state;
    const double optimum = disc_detour_length(5.0, 2.0);
    assert_true(fabs(optimum - 10.811) < 5e-4); /* the figure */
    double first;
    int32_t n;
    const double best = run_disc(7, 40000, &first, &n);
    printf("disc: optimum %.4f best %.4f (first %.4f, %d improvements)\n", optimum, best, first, n);
    /* A valid path around the disc is never shorter than the optimum (grid is conservative). */
    assert_true(best >= optimum - 1e-6);
    assert_true(best <= optimum * 1.01);
    assert_true(first > best); /* it improved after the first solution */
}

static void test_best_cost_never_increases(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    double last = INFINITY;
    int improved = 0;
    for (int round = 0; round < 40; ++round) {
        gmmrrt_budget_t b = {0.0, 250, 0.0, 0};
        gmmrrt_plan_stats_t st;
        const gmmrrt_status_t s = gmmrrt_planner_run(t.p, &b, &st);
        assert_true(s == GMMRRT_OK || s == GMMRRT_NO_PATH_YET);
        assert_true(st.best_cost <= last);
        improved += st.best_cost < last;
        last = st.best_cost;
        gmmrrt_path_t path;
        if (gmmrrt_planner_best_path(t.p, &path) == GMMRRT_OK)
            assert_true(fabs(path.cost - st.best_cost) < 1e-12);
    }
    assert_true(improved >= 2);
    int64_t its[1024];
    double costs[1024];
    const int32_t n = gmmrrt_planner_cost_history(t.p, its, costs, 1024);
    assert_true(n >= 2);
    for (int32_t i = 1; i < n; ++i) {
        assert_true(costs[i] < costs[i - 1]);
        assert_true(its[i] >= its[i - 1]);
    }
    test_planner_free(&t);
}

/* Every edge of the tree is checked against FCL's exact clearance every centimetre, and
 * every node's cost equals its parent's plus the edge length (rewiring kept subtrees right). */
static void check_tree(gmmrrt_planner_t *p, int check_cost)
{
    const gmmrrt_world_t *w = gmmrrt_planner_world(p);
    const int32_t n = gmmrrt_planner_node_count(p);
    assert_true(n > 1);
    for (int32_t i = 1; i < n; ++i) {
        double x, y, c, px, py, pc;
        int32_t parent, pp;
        assert_int_equal(gmmrrt_planner_node(p, i, &x, &y, &parent, &c), GMMRRT_OK);
        assert_true(parent >= 0 && parent < n && parent != i);
        assert_int_equal(gmmrrt_planner_node(p, parent, &px, &py, &pp, &pc), GMMRRT_OK);
        const double len = hypot(x - px, y - py);
        if (check_cost)
            assert_true(fabs(c - (pc + len)) < 1e-6 * (1.0 + c));
        const int steps = (int)ceil(len / 0.01);
        for (int s = 0; s <= steps; ++s) {
            const double u = steps ? (double)s / steps : 0.0;
            assert_true(gmmrrt_world_exact_clearance(w, px + u * (x - px), py + u * (y - py)) >= 0.0);
        }
    }
    assert_int_equal(gmmrrt_planner_node(p, n, NULL, NULL, NULL, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
}

static void test_every_tree_edge_is_collision_free(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof kinds_without_model / sizeof kinds_without_model[0]; ++k) {
        gmmrrt_planner_config_t cfg = point_robot_config(kinds_without_model[k]);
        cfg.robot_radius_m = 0.3;
        cfg.max_nodes = 3000;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = disc_problem();
        pr.obstacles.num_boxes = 2;
        pr.obstacles.boxes[0] = (gmmrrt_box_t){-3.0, 2.0, 0.4, 4.0, 0.3};
        pr.obstacles.boxes[1] = (gmmrrt_box_t){3.0, -2.0, 0.4, 4.0, -0.3};
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 3.5, 0.0};
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = {0.0, 2500, 0.0, 0};
        const gmmrrt_status_t s = gmmrrt_planner_run(t.p, &b, NULL);
        assert_true(s == GMMRRT_OK || s == GMMRRT_NO_PATH_YET);
        /* task NONE: gmm-rrt-star's cost is (w_length + w_task) x length */
        check_tree(t.p, kinds_without_model[k] != GMMRRT_PLANNER_GMM_RRT_STAR);
        test_planner_free(&t);
    }
}

static void test_same_seed_gives_same_path_other_seed_differs(void **state)
{
    (void)state;
    gmmrrt_path_t a, b, c;
    for (int run = 0; run < 3; ++run) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.seed = run == 2 ? 99 : 42;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = disc_problem();
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t bud = {0.0, 3000, 0.0, 0};
        assert_int_equal(gmmrrt_planner_run(t.p, &bud, NULL), GMMRRT_OK);
        assert_int_equal(gmmrrt_planner_best_path(t.p, run == 0 ? &a : run == 1 ? &b : &c), GMMRRT_OK);
        test_planner_free(&t);
    }
    assert_int_equal(a.num_points, b.num_points);
    assert_memory_equal(a.x, b.x, sizeof(double) * (size_t)a.num_points);
    assert_memory_equal(a.y, b.y, sizeof(double) * (size_t)a.num_points);
    assert_true(a.cost == b.cost);
    assert_true(a.cost != c.cost);
}

static void test_set_problem_restarts_the_same_tree(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    gmmrrt_budget_t bud = {0.0, 2000, 0.0, 0};
    gmmrrt_plan_stats_t s1, s2;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_run(t.p, &bud, &s1), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_run(t.p, &bud, &s2), GMMRRT_OK);
    assert_true(s1.best_cost == s2.best_cost);
    assert_int_equal(s1.nodes, s2.nodes);
    assert_int_equal(s2.iterations, 2000);
    test_planner_free(&t);
}

static void test_pool_exhaustion_gives_pool_full_and_keeps_best(void **state)
{
    (void)state;
    /* No path can exist (a wall across the bounds), so nothing can be pruned: the pool fills. */
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.max_nodes = 300;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    pr.obstacles.num_boxes = 1;
    pr.obstacles.boxes[0] = (gmmrrt_box_t){2.5, 0.0, 0.2, 20.0, 0.0};
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t b = {0.0, 1000000, 0.0, 0};
    gmmrrt_plan_stats_t st;
    assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_POOL_FULL);
    assert_int_equal(st.nodes, 300);
    assert_int_equal(st.pruned, 0);
    assert_true(st.iterations < 1000000);
    /* Calling again does no harm. */
    assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_POOL_FULL);
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_NO_PATH_YET);
    test_planner_free(&t);
}

/* A full pool with a path is pruned and the search goes on in the same memory: on the
 * cluttered problem with a pool of 1500 nodes, many more iterations than the pool holds keep
 * improving the cost, the tree stays a tree of free edges with consistent costs, and the best
 * path at the end is the cheapest ever seen. */
static void test_full_pool_is_pruned_and_the_search_keeps_improving(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.max_nodes = 1500;
    cfg.grid_resolution_m = 0.05;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = cluttered_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    /* Up to the first time the pool is full. */
    gmmrrt_budget_t fill = {0.0, 0, 0.0, 0};
    gmmrrt_plan_stats_t st;
    double at_full = INFINITY;
    for (int i = 0; i < 1000 && gmmrrt_planner_node_count(t.p) < cfg.max_nodes - 1; ++i) {
        fill.max_iterations = 50;
        (void)gmmrrt_planner_run(t.p, &fill, &st);
        at_full = st.best_cost;
    }
    assert_true(isfinite(at_full));
    gmmrrt_budget_t b = {0.0, 60000, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
    assert_true(st.pruned > cfg.max_nodes); /* the pool was recycled more than once over */
    assert_true(st.nodes <= cfg.max_nodes);
    assert_true(st.best_cost < at_full * 0.999);
    /* Every node's parent edge is free and its cost is the parent's plus the edge's length. */
    const gmmrrt_world_t *w = gmmrrt_planner_world(t.p);
    for (int32_t i = 1; i < st.nodes; ++i) {
        double x, y, c, px, py, pc;
        int32_t parent, pp;
        assert_int_equal(gmmrrt_planner_node(t.p, i, &x, &y, &parent, &c), GMMRRT_OK);
        assert_true(parent >= 0 && parent < st.nodes);
        assert_int_equal(gmmrrt_planner_node(t.p, parent, &px, &py, &pp, &pc), GMMRRT_OK);
        assert_true(gmmrrt_world_segment_free(w, px, py, x, y));
        assert_true(fabs(c - (pc + hypot(x - px, y - py))) < 1e-9 * (1.0 + c));
    }
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
    assert_true(path.cost == st.best_cost);
    static int64_t it[1024]; /* the default history capacity: its last entry is the latest */
    static double hc[1024];
    const int32_t nh = gmmrrt_planner_cost_history(t.p, it, hc, 1024);
    assert_true(nh > 0 && hc[nh - 1] == st.best_cost);
    test_planner_free(&t);
}

/* The background cost reads problem.background_model only where the planner carries the task
 * cost (GMM-RRT*): gmmrrt_planner_needs_background says so for every kind and cost, and
 * set_problem applies the same rule (no background: refused under GMM-RRT*, planned under RRT*). */
static void test_only_the_task_cost_planner_needs_a_background(void **state)
{
    (void)state;
    const int32_t kinds[] = {GMMRRT_PLANNER_GMM_RRT_STAR, GMMRRT_PLANNER_RRT_STAR, GMMRRT_PLANNER_GMM_RRT};
    const int32_t costs[] = {GMMRRT_TASK_COST_PAPER, GMMRRT_TASK_COST_INWARD, GMMRRT_TASK_COST_BACKGROUND};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            gmmrrt_planner_config_t cfg = point_robot_config(kinds[i]);
            cfg.task_cost = costs[j];
            assert_int_equal(gmmrrt_planner_needs_background(&cfg), i == 0 && j == 2);
        }
    assert_int_equal(gmmrrt_planner_needs_background(NULL), 0);
    gmmrrt_model_t m;
    const double theta[1] = {1.0};
    assert_int_equal(make_features_model(&m, theta, 1, 1.2, 0.2, 0.3), GMMRRT_OK);
    for (int i = 0; i < 2; ++i) {
        gmmrrt_planner_config_t cfg = point_robot_config(kinds[i]);
        cfg.task_cost = GMMRRT_TASK_COST_BACKGROUND;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        const gmmrrt_problem_t pr = avoid_problem(&m); /* background_model NULL */
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), i == 0 ? GMMRRT_ERR_MODEL_MISMATCH : GMMRRT_OK);
        test_planner_free(&t);
    }
}

static void test_bad_problems_get_their_status(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.robot_radius_m = 0.2;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    pr.start_x = 0.5; /* inside the disc: escapes (test_drivable.c and test_escape.c have the details) */
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ESCAPE);
    pr = disc_problem();
    pr.obstacles.circles[0].radius_m = 6.0; /* 6.2 m to the nearest free point: frozen */
    pr.start_x = 0.0;
    pr.goal_x = -6.5;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_FROZEN);
    assert_non_null(strstr(gmmrrt_planner_escape_reason(t.p), "circle obstacle 0"));
    pr = disc_problem();
    pr.goal_x = 2.1; /* outside the disc but the robot's radius touches it */
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_GOAL_IN_COLLISION);
    pr = disc_problem();
    pr.start_x = -8.0;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_START_OUT_OF_BOUNDS);
    pr = disc_problem();
    pr.goal_y = 5.5;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_GOAL_OUT_OF_BOUNDS);
    pr = disc_problem();
    pr.start_x = NAN;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr = disc_problem();
    pr.obstacles.circles[0].radius_m = NAN;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr = disc_problem();
    pr.obstacles.bounds.xmax = INFINITY;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr = disc_problem();
    pr.goal_tolerance_m = 0.0;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr = disc_problem();
    pr.task = GMMRRT_TASK_APPROACH;
    pr.target_person = 0; /* there is nobody */
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr = disc_problem();
    pr.obstacles.bounds = (gmmrrt_bounds_t){-500.0, -500.0, 500.0, 500.0}; /* grid too large */
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_BUFFER_TOO_SMALL);
    /* After a failed set_problem there is nothing to run. */
    gmmrrt_budget_t b = {0.0, 10, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    /* Budgets that cannot stop or hold NaN are refused. */
    pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t forever = {0.0, 0, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &forever, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    gmmrrt_budget_t nan_budget = {NAN, 10, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &nan_budget, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    test_planner_free(&t);
}

static void test_gmm_planners_need_a_model_of_their_kind(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    const double theta[] = {M_PI / 2.0};
    assert_int_equal(make_features_model(&m, theta, 1, 1.2, 0.2, 0.3), GMMRRT_OK);
    const int32_t kinds[] = {GMMRRT_PLANNER_GMM_RRT_STAR, GMMRRT_PLANNER_GMM_RRT};
    for (int k = 0; k < 2; ++k) {
        gmmrrt_planner_config_t cfg = point_robot_config(kinds[k]);
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, M_PI};
        pr.task = GMMRRT_TASK_AVOID;
        pr.model = NULL;
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_MODEL_MISMATCH);
        pr.model = &m; /* a features model: right for gmm-rrt-star, wrong for gmm-rrt */
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr),
                         kinds[k] == GMMRRT_PLANNER_GMM_RRT_STAR ? GMMRRT_OK : GMMRRT_ERR_MODEL_MISMATCH);
        test_planner_free(&t);
    }
}

static void test_config_validation_names_the_field(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    char err[128];
    assert_int_equal(gmmrrt_planner_config_validate(&cfg, err, sizeof err), GMMRRT_OK);
    assert_true(gmmrrt_planner_mem_size(&cfg) > 0);
    cfg.step_m = NAN;
    assert_int_equal(gmmrrt_planner_config_validate(&cfg, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err, "step_m"));
    assert_int_equal(gmmrrt_planner_mem_size(&cfg), 0);
    gmmrrt_planner_config_default(&cfg);
    cfg.goal_bias = 1.0;
    assert_int_equal(gmmrrt_planner_config_validate(&cfg, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err, "goal_bias"));
    gmmrrt_planner_config_default(&cfg);
    cfg.max_nodes = 1;
    assert_int_equal(gmmrrt_planner_config_validate(&cfg, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err, "max_nodes"));
    gmmrrt_planner_config_default(&cfg);
    cfg.planner = 7;
    assert_int_equal(gmmrrt_planner_config_validate(&cfg, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    /* init refuses a short or misaligned block */
    gmmrrt_planner_config_default(&cfg);
    cfg.max_nodes = 100;
    cfg.grid_max_cells = 100;
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    void *mem = aligned_alloc(8, (size + 15u) & ~(size_t)7u);
    gmmrrt_planner_t *p;
    assert_int_equal(gmmrrt_planner_init(&p, mem, size - 8, &cfg), GMMRRT_ERR_BUFFER_TOO_SMALL);
    assert_int_equal(gmmrrt_planner_init(&p, (char *)mem + 4, size, &cfg), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_planner_init(&p, mem, size, &cfg), GMMRRT_OK);
    free(mem);
}

static void test_path_is_resampled_with_heading(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.waypoint_spacing_m = 0.25;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_NO_PATH_YET);
    assert_int_equal(path.num_points, 0);
    gmmrrt_budget_t b = {0.0, 5000, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
    /* At least one point per 0.25 m of path (more where tree corners are kept). */
    assert_true(path.num_points >= (int32_t)ceil(path.length_m / 0.25 - 1e-9) + 1);
    double along = 0.0;
    for (int32_t i = 1; i < path.num_points; ++i) {
        const double step = hypot(path.x[i] - path.x[i - 1], path.y[i] - path.y[i - 1]);
        along += step;
        assert_true(step <= 0.25 + 1e-9);
        /* heading points along the path: the next point is ahead */
        const double hx = cos(path.yaw[i - 1]), hy = sin(path.yaw[i - 1]);
        assert_true((path.x[i] - path.x[i - 1]) * hx + (path.y[i] - path.y[i - 1]) * hy >= -1e-9);
        /* the published chords are as safe as the tree: each passes the tree's own edge check */
        assert_true(gmmrrt_world_segment_free(gmmrrt_planner_world(t.p), path.x[i - 1], path.y[i - 1], path.x[i],
                                              path.y[i]));
    }
    assert_true(along <= path.length_m + 1e-9);
    /* no waypoint is inside the disc */
    for (int32_t i = 0; i < path.num_points; ++i)
        assert_true(hypot(path.x[i], path.y[i]) >= 2.0 - 1e-9);
    test_planner_free(&t);
}

/* A tree path bending tightly under a person's disc (checked exactly, not on the grid): the
 * corner is 4 mm below the disc and each edge clears it by 2.4 mm, so the tree is valid, but a
 * chord across the corner passes up to about 6 mm inside the disc. Resampling by arc length
 * alone published such chords; now, whatever the spacing, every published chord passes the
 * check the tree's edges passed and stays outside the disc. */
static void test_published_chords_are_as_safe_as_the_tree(void **state)
{
    (void)state;
    int cut_before = 0;
    for (int k = 0; k <= 20; ++k) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.person_radius_m = 0.5;
        cfg.waypoint_spacing_m = 0.2 + 0.01 * k;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-1.5, -0.304, 3.5, -0.304);
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){1.0, 0.0, 0.0};
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        const double sx[3] = {-1.5, 1.0, 3.5}, sy[3] = {-0.304, -0.504, -0.304};
        assert_int_equal(gmmrrt_planner_seed_path(t.p, sx, sy, 3), GMMRRT_OK);
        const gmmrrt_budget_t b = {0.0, 1, 0.0, 0}; /* one sample: the seeded path is the solution */
        (void)gmmrrt_planner_run(t.p, &b, NULL);
        gmmrrt_path_t path;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
        /* would plain arc-length points have cut the corner? (the case this test is about) */
        const double sp = path.length_m / ceil(path.length_m / cfg.waypoint_spacing_m);
        const double before = fmod(hypot(2.5, 0.2), sp); /* arc length from the last point to the corner */
        cut_before += before > 0.02 && sp - before > 0.02;
        for (int32_t i = 1; i < path.num_points; ++i) {
            assert_true(gmmrrt_world_segment_free(gmmrrt_planner_world(t.p), path.x[i - 1], path.y[i - 1], path.x[i],
                                                  path.y[i]));
            const double ax = path.x[i - 1] - 1.0, ay = path.y[i - 1], dx = path.x[i] - path.x[i - 1],
                         dy = path.y[i] - path.y[i - 1];
            const double l2 = dx * dx + dy * dy;
            const double u = l2 > 0.0 ? fmin(1.0, fmax(0.0, -(ax * dx + ay * dy) / l2)) : 0.0;
            assert_true(hypot(ax + u * dx, ay + u * dy) >= 0.5);
        }
        test_planner_free(&t);
    }
    assert_true(cut_before > 5);
}

static void test_seed_path_warm_starts_the_tree(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    const double x[] = {-5.0, -2.0, 0.0, 2.0, 5.0};
    const double y[] = {0.0, 2.5, 2.5, 2.5, 0.0};
    assert_int_equal(gmmrrt_planner_seed_path(t.p, x, y, 5), GMMRRT_OK);
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
    const double seeded = hypot(3.0, 2.5) * 2.0 + 4.0;
    assert_true(fabs(path.length_m - seeded) < 1e-9);
    /* A path through the disc stops at its first blocked edge: no solution from it. */
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    const double bx[] = {-5.0, 0.0, 5.0}, by[] = {0.0, 0.0, 0.0};
    assert_int_equal(gmmrrt_planner_seed_path(t.p, bx, by, 3), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_node_count(t.p), 1);
    const double nx[] = {NAN};
    assert_int_equal(gmmrrt_planner_seed_path(t.p, nx, nx, 1), GMMRRT_ERR_INVALID_ARGUMENT);
    test_planner_free(&t);
}

static void test_convergence_and_time_budgets_stop_the_run(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.max_nodes = 200000;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    /* converged: less than 0.1 % better over 3000 iterations, long before the cap */
    gmmrrt_budget_t conv = {0.0, 150000, 0.001, 3000};
    gmmrrt_plan_stats_t st;
    assert_int_equal(gmmrrt_planner_run(t.p, &conv, &st), GMMRRT_OK);
    printf("converged after %lld iterations at %.4f\n", (long long)st.iterations, st.best_cost);
    assert_true(st.iterations < 150000);
    assert_true(st.iterations % 3000 == 0);
    assert_true(st.best_cost < disc_detour_length(5.0, 2.0) * 1.05);
    /* a time budget alone stops too; the run continues the same tree */
    const int64_t before = st.iterations;
    gmmrrt_budget_t timed = {20.0, 0, 0.0, 0};
    const gmmrrt_status_t s = gmmrrt_planner_run(t.p, &timed, &st);
    assert_true(s == GMMRRT_OK || s == GMMRRT_POOL_FULL);
    assert_true(st.iterations > before);
    assert_true(st.time_ms > 0.0);
    test_planner_free(&t);
}

static void test_start_within_goal_tolerance_is_solved_at_once(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(1.0, 1.0, 1.03, 1.0);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
    assert_int_equal(path.num_points, 2);
    assert_true(path.x[0] == 1.0 && path.x[1] == 1.03);
    assert_true(fabs(path.length_m - 0.03) < 1e-12);
    gmmrrt_budget_t b = {0.0, 10, 0.0, 0};
    gmmrrt_plan_stats_t st;
    assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
    assert_int_equal(st.first_solution_iteration, 0);
    test_planner_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_straight_line_is_found_and_straight),
        cmocka_unit_test(test_disc_detour_converges_to_closed_form_length),
        cmocka_unit_test(test_best_cost_never_increases),
        cmocka_unit_test(test_every_tree_edge_is_collision_free),
        cmocka_unit_test(test_same_seed_gives_same_path_other_seed_differs),
        cmocka_unit_test(test_set_problem_restarts_the_same_tree),
        cmocka_unit_test(test_pool_exhaustion_gives_pool_full_and_keeps_best),
        cmocka_unit_test(test_full_pool_is_pruned_and_the_search_keeps_improving),
        cmocka_unit_test(test_only_the_task_cost_planner_needs_a_background),
        cmocka_unit_test(test_bad_problems_get_their_status),
        cmocka_unit_test(test_gmm_planners_need_a_model_of_their_kind),
        cmocka_unit_test(test_config_validation_names_the_field),
        cmocka_unit_test(test_path_is_resampled_with_heading),
        cmocka_unit_test(test_published_chords_are_as_safe_as_the_tree),
        cmocka_unit_test(test_seed_path_warm_starts_the_tree),
        cmocka_unit_test(test_convergence_and_time_budgets_stop_the_run),
        cmocka_unit_test(test_start_within_goal_tolerance_is_solved_at_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
