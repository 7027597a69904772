/*
 * test_connect.c - planner.connect: the connect phase of the planner (connect.c; RRT-Connect,
 * Kuffner & LaValle 2000) and its hand-over to RRT*: it finds the narrow passage of the
 * benchmark's problem C in fewer iterations than RRT* alone, the tree it hands over keeps the
 * tree's invariants (parents, cost-to-come = parent's + edge, every edge exactly free, the best
 * path's cost), the search then keeps improving to the problem's exact optimum, the task cost
 * stays consistent with the planner's own edge cost, a seed gives one result, the phase is
 * selectable (config connect_first), and at its iteration cap (connect_max_iterations) it hands
 * the search to RRT* alone, which still finds a path in a tree that keeps the invariants.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "planner_fixtures.h"
#include "planner_internal.h" /* gmmrrt_edge_cost: the oracle of the task cost */

/* ../shared/bench/problems/problem_C.txt: a 0.4 m wall at x = 0 with a 0.5 m gap centred at
 * y = 3, (-5, 0) -> (5, 0); its exact optimum from problems.json (corner visibility graph). */
#define PROBLEM_C_OPTIMUM 11.4639

static gmmrrt_problem_t narrow_passage(void)
{
    gmmrrt_problem_t pr = empty_problem(-5.0, 0.0, 5.0, 0.0);
    pr.goal_tolerance_m = 1e-6;
    pr.obstacles.bounds = (gmmrrt_bounds_t){-10.0, -10.0, 10.0, 10.0};
    pr.obstacles.num_boxes = 2;
    pr.obstacles.boxes[0] = (gmmrrt_box_t){0.0, -3.625, 0.4, 12.75, 0.0};
    pr.obstacles.boxes[1] = (gmmrrt_box_t){0.0, 6.625, 0.4, 6.75, 0.0};
    return pr;
}

/* Runs one iteration at a time until a path exists (or max_it); returns the iterations. */
static int64_t run_to_first_path(gmmrrt_planner_t *p, int64_t max_it)
{
    gmmrrt_plan_stats_t st;
    const gmmrrt_budget_t one = {0.0, 1, 0.0, 0};
    do {
        const gmmrrt_status_t s = gmmrrt_planner_run(p, &one, &st);
        assert_true(s == GMMRRT_OK || s == GMMRRT_NO_PATH_YET);
    } while (!isfinite(st.best_cost) && st.iterations < max_it);
    assert_true(isfinite(st.best_cost));
    assert_int_equal(st.first_solution_iteration, st.iterations);
    return st.iterations;
}

/* The tree's invariants: the root has no parent, every other node a parent among the nodes
 * whose chain reaches the root; cost-to-come = parent's + edge (length for rrt-star, the
 * planner's edge cost otherwise); every edge exactly free (FCL's clearance every centimetre);
 * the best path's cost is its goal node's cost-to-come plus the last edge. */
static void check_tree(gmmrrt_planner_t *p, int length_cost)
{
    const gmmrrt_world_t *w = gmmrrt_planner_world(p);
    const int32_t n = gmmrrt_planner_node_count(p);
    assert_true(n > 1);
    int32_t root_parent;
    double root_cost;
    assert_int_equal(gmmrrt_planner_node(p, 0, NULL, NULL, &root_parent, &root_cost), GMMRRT_OK);
    assert_int_equal(root_parent, -1);
    assert_true(root_cost == 0.0);
    for (int32_t i = 1; i < n; ++i) {
        double x, y, c, px, py, pc;
        int32_t parent, pp;
        assert_int_equal(gmmrrt_planner_node(p, i, &x, &y, &parent, &c), GMMRRT_OK);
        assert_true(parent >= 0 && parent < n && parent != i);
        assert_int_equal(gmmrrt_planner_node(p, parent, &px, &py, &pp, &pc), GMMRRT_OK);
        const double edge = length_cost ? hypot(x - px, y - py) : gmmrrt_edge_cost(p, px, py, x, y);
        assert_true(fabs(c - (pc + edge)) < 1e-9 * (1.0 + c));
        int32_t hops = 0, k = i;
        while (k > 0 && hops <= n) {
            assert_int_equal(gmmrrt_planner_node(p, k, NULL, NULL, &k, NULL), GMMRRT_OK);
            ++hops;
        }
        assert_int_equal(k, 0); /* no cycle: the chain ends at the root */
        const double len = hypot(x - px, y - py);
        const int steps = (int)ceil(len / 0.01);
        for (int s = 0; s <= steps; ++s) {
            const double u = steps ? (double)s / steps : 0.0;
            assert_true(gmmrrt_world_exact_clearance(w, px + u * (x - px), py + u * (y - py)) >= 0.0);
        }
    }
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(p, &path), GMMRRT_OK);
    assert_true(path.num_points >= 2);
    assert_true(isfinite(path.cost) && path.cost > 0.0);
}

/* The median of n values, n odd (sorts v). */
static int64_t median_of(int64_t *v, int n)
{
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
            if (v[b] < v[a]) {
                const int64_t t = v[a];
                v[a] = v[b];
                v[b] = t;
            }
    return v[n / 2];
}

static void test_narrow_passage_is_found_in_fewer_iterations(void **state)
{
    (void)state;
    enum { SEEDS = 9 };
    int64_t with[SEEDS], without[SEEDS];
    for (int on = 0; on <= 1; ++on)
        for (int s = 0; s < SEEDS; ++s) {
            gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
            cfg.seed = (uint64_t)s + 1;
            cfg.connect_first = on;
            test_planner_t t;
            assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
            gmmrrt_problem_t pr = narrow_passage();
            assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
            (on ? with : without)[s] = run_to_first_path(t.p, 200000);
            test_planner_free(&t);
        }
    const int64_t med_with = median_of(with, SEEDS), med_without = median_of(without, SEEDS);
    printf("narrow passage: iterations to the first path, median of %d seeds: connect %lld, RRT* alone %lld\n",
           SEEDS, (long long)med_with, (long long)med_without);
    assert_true(med_with < med_without);
}

static void test_handed_over_tree_keeps_the_invariants_and_converges(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.seed = 3;
    cfg.max_nodes = 50000;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = narrow_passage();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    run_to_first_path(t.p, 200000);
    /* Right after the hand-over the tree is the root and the joined path. */
    check_tree(t.p, 1);
    gmmrrt_path_t first;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &first), GMMRRT_OK);
    assert_true(first.x[0] == pr.start_x && first.y[0] == pr.start_y);
    assert_true(first.x[first.num_points - 1] == pr.goal_x && first.y[first.num_points - 1] == pr.goal_y);
    assert_true(first.cost >= PROBLEM_C_OPTIMUM - 1e-6);
    /* RRT* goes on from it: the best cost never rises and reaches the exact optimum. */
    double last = first.cost;
    for (int round = 0; round < 40; ++round) {
        gmmrrt_budget_t b = {0.0, 2500, 0.0, 0};
        gmmrrt_plan_stats_t st;
        assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
        assert_true(st.best_cost <= last);
        last = st.best_cost;
    }
    check_tree(t.p, 1);
    printf("narrow passage: first path %.4f, after 100000 iterations %.4f, optimum %.4f\n", first.cost, last,
           PROBLEM_C_OPTIMUM);
    assert_true(last < first.cost);
    assert_true(last >= PROBLEM_C_OPTIMUM - 1e-6); /* the grid is conservative: never below it */
    assert_true(last <= PROBLEM_C_OPTIMUM * 1.01);
    test_planner_free(&t);
}

static void test_task_cost_of_the_handed_over_path_is_the_planners(void **state)
{
    (void)state;
    static gmmrrt_model_t model;
    const double theta[] = {1.2, -1.2};
    assert_int_equal(make_features_model(&model, theta, 2, 1.5, 0.3, 0.3), GMMRRT_OK);
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_GMM_RRT_STAR);
    cfg.robot_radius_m = 0.3;
    cfg.seed = 5;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
    pr.task = GMMRRT_TASK_AVOID;
    pr.model = &model;
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, M_PI};
    pr.obstacles.num_boxes = 1;
    pr.obstacles.boxes[0] = (gmmrrt_box_t){2.0, 0.0, 0.3, 4.0, 0.0};
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    run_to_first_path(t.p, 200000);
    check_tree(t.p, 0);
    gmmrrt_budget_t b = {0.0, 3000, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
    check_tree(t.p, 0);
    test_planner_free(&t);
}

static void test_same_seed_same_path_and_the_phase_is_selectable(void **state)
{
    (void)state;
    gmmrrt_path_t path[3];
    int64_t first_it[3];
    for (int run = 0; run < 3; ++run) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.seed = 11;
        cfg.connect_first = run < 2;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = narrow_passage();
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = {0.0, 4000, 0.0, 0};
        gmmrrt_plan_stats_t st;
        assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
        first_it[run] = st.first_solution_iteration;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &path[run]), GMMRRT_OK);
        test_planner_free(&t);
    }
    assert_int_equal(path[0].num_points, path[1].num_points);
    assert_memory_equal(path[0].x, path[1].x, sizeof(double) * (size_t)path[0].num_points);
    assert_memory_equal(path[0].y, path[1].y, sizeof(double) * (size_t)path[0].num_points);
    assert_true(path[0].cost == path[1].cost);
    assert_int_equal(first_it[0], first_it[1]);
    /* Off: RRT* from the first sample, another search. */
    assert_true(first_it[2] != first_it[0] || path[2].cost != path[0].cost);

    gmmrrt_planner_config_t bad = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    bad.connect_first = 2;
    char err[128];
    assert_int_equal(gmmrrt_planner_config_validate(&bad, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err, "connect_first"));
    /* The phase's arrays are in the block only when it is on. */
    gmmrrt_planner_config_t off = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    gmmrrt_planner_config_t on = off;
    off.connect_first = 0;
    assert_true(gmmrrt_planner_mem_size(&on) > gmmrrt_planner_mem_size(&off));
}

/* Three rooms of 0.2 m walls in [-10, 10] x [-6, 6]: a long room below y = 0, two above it
 * split at x = 0; 1 m doors at x in [-7, -6] (below to the upper left) and y in [4, 5] (upper
 * left to upper right). (-8, -3) -> (8, 3): through both doors, as on a floor plan. */
static gmmrrt_problem_t three_rooms(void)
{
    gmmrrt_problem_t pr = empty_problem(-8.0, -3.0, 8.0, 3.0);
    pr.goal_tolerance_m = 1e-6;
    pr.obstacles.bounds = (gmmrrt_bounds_t){-10.0, -6.0, 10.0, 6.0};
    pr.obstacles.num_boxes = 4;
    pr.obstacles.boxes[0] = (gmmrrt_box_t){-8.5, 0.0, 3.0, 0.2, 0.0};
    pr.obstacles.boxes[1] = (gmmrrt_box_t){2.0, 0.0, 16.0, 0.2, 0.0};
    pr.obstacles.boxes[2] = (gmmrrt_box_t){0.0, 2.0, 0.2, 4.0, 0.0};
    pr.obstacles.boxes[3] = (gmmrrt_box_t){0.0, 5.5, 0.2, 1.0, 0.0};
    return pr;
}

/* Dynamic domains (connect.c): a node whose step was blocked is not tested again as a further
 * try towards a target beyond one step. In rooms that spares most of the edge tests to the first
 * path; the path still comes, in a tree with the invariants; the switch turns it off. */
static void test_dynamic_domains_spare_edge_tests_in_rooms(void **state)
{
    (void)state;
    enum { SEEDS = 9 };
    int64_t tests[2][SEEDS], iterations[2][SEEDS];
    for (int on = 0; on <= 1; ++on)
        for (int s = 0; s < SEEDS; ++s) {
            gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
            cfg.seed = (uint64_t)s + 1;
            cfg.step_m = 0.2 * hypot(20.0, 12.0); /* the benchmark's: OMPL's range, 0.2 x the extent */
            cfg.goal_bias = 0.05;
            cfg.connect_domains = on;
            test_planner_t t;
            assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
            gmmrrt_problem_t pr = three_rooms();
            assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
            iterations[on][s] = run_to_first_path(t.p, 200000);
            tests[on][s] = t.p->connect.edge_tests;
            /* The first path came from the connect phase: within its iteration cap, which hands
             * over to RRT* alone. */
            assert_true(iterations[on][s] < cfg.connect_max_iterations);
            if (on && s == 0)
                check_tree(t.p, 1);
            test_planner_free(&t);
        }
    const int64_t tests_off = median_of(tests[0], SEEDS), tests_on = median_of(tests[1], SEEDS);
    printf("three rooms: edge tests to the first path, median of %d seeds: domains %lld, without %lld "
           "(iterations %lld, %lld)\n",
           SEEDS, (long long)tests_on, (long long)tests_off, (long long)median_of(iterations[1], SEEDS),
           (long long)median_of(iterations[0], SEEDS));
    assert_true(tests_on < tests_off);

    gmmrrt_planner_config_t bad = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    bad.connect_domains = 2;
    char err[128];
    assert_int_equal(gmmrrt_planner_config_validate(&bad, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err, "connect_domains"));
}

static void test_the_iteration_cap_hands_over_to_rrt_star(void **state)
{
    (void)state;
    enum { CAP = 40 };
    int checked = 0;
    for (uint64_t seed = 1; seed <= 20 && checked < 3; ++seed) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.seed = seed;
        cfg.connect_max_iterations = CAP;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = narrow_passage();
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_plan_stats_t st;
        const gmmrrt_budget_t cap = {0.0, CAP, 0.0, 0};
        (void)gmmrrt_planner_run(t.p, &cap, &st);
        if (isfinite(st.best_cost)) { /* joined within the cap: not the case under test */
            test_planner_free(&t);
            continue;
        }
        ++checked;
        /* The phase spent exactly its cap, and the RRT* tree is still the root alone. */
        const gmmrrt_planner_t *p = t.p;
        assert_int_equal(p->connect.iterations, CAP);
        assert_int_equal(p->connect.state, GMMRRT_CONNECT_GROWING);
        assert_int_equal(gmmrrt_planner_node_count(t.p), 1);
        /* The next iterations are RRT*'s: the phase is over and the tree grows from the root. */
        const gmmrrt_budget_t more = {0.0, 200, 0.0, 0};
        (void)gmmrrt_planner_run(t.p, &more, &st);
        assert_int_equal(p->connect.state, GMMRRT_CONNECT_OFF);
        assert_int_equal(p->connect.iterations, CAP);
        assert_true(gmmrrt_planner_node_count(t.p) > 1);
        /* RRT* alone still finds the passage, in a tree with the invariants. */
        const int64_t first = run_to_first_path(t.p, 200000);
        assert_true(first > CAP);
        check_tree(t.p, 1);
        test_planner_free(&t);
    }
    assert_int_equal(checked, 3); /* problem C takes the phase more than 40 iterations for most seeds */

    gmmrrt_planner_config_t bad = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    bad.connect_max_iterations = 0;
    char err[128];
    assert_int_equal(gmmrrt_planner_config_validate(&bad, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err, "connect_max_iterations"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_narrow_passage_is_found_in_fewer_iterations),
        cmocka_unit_test(test_handed_over_tree_keeps_the_invariants_and_converges),
        cmocka_unit_test(test_task_cost_of_the_handed_over_path_is_the_planners),
        cmocka_unit_test(test_same_seed_same_path_and_the_phase_is_selectable),
        cmocka_unit_test(test_the_iteration_cap_hands_over_to_rrt_star),
        cmocka_unit_test(test_dynamic_domains_spare_edge_tests_in_rooms),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
