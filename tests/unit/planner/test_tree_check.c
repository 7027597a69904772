/*
 * planner.tree_check: the search tree's invariants (planner/src/tree_check.h) hold on trees of
 * every planner kind, with a task model, after rewiring, after pruning a full pool and after a
 * warm-start seed; and the check finds each invariant broken on purpose (so it can fail).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "planner_fixtures.h"
#include "planner_internal.h"
#include "tree_check.h"

static void assert_tree_holds(const gmmrrt_planner_t *p)
{
    char why[256] = "";
    if (!gmmrrt_tree_check(p, why, sizeof why))
        fail_msg("tree invariant broken: %s", why);
}

/* A point-robot planner of `kind` (pool of max_nodes; 0: the fixture's) on the disc problem. */
static void make_disc_planner(test_planner_t *t, int32_t kind, int32_t max_nodes)
{
    gmmrrt_planner_config_t cfg = point_robot_config(kind);
    if (max_nodes > 0)
        cfg.max_nodes = max_nodes;
    assert_int_equal(test_planner_make(t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t->p, &pr), GMMRRT_OK);
}

static void run_iterations(gmmrrt_planner_t *p, int64_t n)
{
    gmmrrt_budget_t budget = {0.0, n, 0.0, 0};
    const gmmrrt_status_t st = gmmrrt_planner_run(p, &budget, NULL);
    assert_true(st == GMMRRT_OK || st == GMMRRT_NO_PATH_YET || st == GMMRRT_POOL_FULL);
}

static void test_every_planner_kind_keeps_the_invariants(void **state)
{
    (void)state;
    const int32_t kinds[] = {GMMRRT_PLANNER_RRT_STAR, GMMRRT_PLANNER_GMM_RRT_STAR, GMMRRT_PLANNER_GMM_RRT};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; ++k) {
        test_planner_t t;
        make_disc_planner(&t, kinds[k], 0);
        assert_tree_holds(t.p);
        for (int round = 0; round < 4; ++round) { /* the check between runs, as Debug builds do */
            run_iterations(t.p, 1500);
            assert_tree_holds(t.p);
        }
        test_planner_free(&t);
    }
}

/* GMM-RRT* with a task model: edge costs with the task term, rewiring by them. */
static void test_task_cost_tree_keeps_the_invariants(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_GMM_RRT_STAR);
    static gmmrrt_model_t model;
    const double theta[] = {1.2, -1.2};
    assert_int_equal(make_features_model(&model, theta, 2, 1.2, 0.2, 0.25), GMMRRT_OK);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = avoid_problem(&model);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    run_iterations(t.p, 4000);
    assert_true(gmmrrt_planner_node_count(t.p) > 100);
    assert_tree_holds(t.p);
    test_planner_free(&t);
}

/* A small pool fills and is pruned (nodes recycled, subtrees kept); a seed path warm-starts. */
static void test_pruning_and_seeding_keep_the_invariants(void **state)
{
    (void)state;
    test_planner_t t;
    make_disc_planner(&t, GMMRRT_PLANNER_RRT_STAR, 600);
    gmmrrt_plan_stats_t stats;
    gmmrrt_budget_t budget = {0.0, 20000, 0.0, 0};
    gmmrrt_planner_run(t.p, &budget, &stats);
    assert_true(stats.pruned > 0);
    assert_tree_holds(t.p);

    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    const double sx[] = {-5.0, -3.0, 0.0, 3.0, 5.0}, sy[] = {0.0, 2.5, 2.5, 2.5, 0.0};
    assert_int_equal(gmmrrt_planner_seed_path(t.p, sx, sy, 5), GMMRRT_OK);
    assert_tree_holds(t.p);
    run_iterations(t.p, 500);
    assert_tree_holds(t.p);
    test_planner_free(&t);
}

/* Each invariant broken on purpose is found and named. */
static void test_a_broken_tree_is_found(void **state)
{
    (void)state;
    test_planner_t t;
    make_disc_planner(&t, GMMRRT_PLANNER_RRT_STAR, 0);
    run_iterations(t.p, 800);
    struct gmmrrt_planner *p = t.p;
    assert_tree_holds(p);
    /* A leaf with a parent that is not the root (grandchild of the root at least). */
    int32_t leaf = -1;
    for (int32_t i = 1; i < p->num_nodes && leaf < 0; ++i)
        if (p->pool.link[i].first_child < 0 && p->pool.link[i].parent > 0)
            leaf = i;
    assert_true(leaf > 0);
    const int32_t parent = p->pool.link[leaf].parent;
    char why[256];

    const double cost = p->pool.cost[leaf];
    p->pool.cost[leaf] = cost + 0.5;
    assert_false(gmmrrt_tree_check(p, why, sizeof why));
    assert_non_null(strstr(why, "parent's cost plus the edge's"));
    p->pool.cost[leaf] = cost;

    p->pool.link[leaf].parent = leaf; /* its own parent */
    assert_false(gmmrrt_tree_check(p, why, sizeof why));
    assert_non_null(strstr(why, "parent"));
    p->pool.link[leaf].parent = parent;

    /* A cycle: the parent's parent becomes the leaf (the leaf's list is empty, so it is also
     * missing from the leaf's child list, which the check names first or the cycle). */
    const int32_t grand = p->pool.link[parent].parent;
    p->pool.link[parent].parent = leaf;
    assert_false(gmmrrt_tree_check(p, why, sizeof why));
    p->pool.link[parent].parent = grand;

    /* Dropped from its parent's child list. */
    const int32_t first = p->pool.link[parent].first_child;
    const int32_t next = p->pool.link[leaf].next_sibling;
    if (first == leaf)
        p->pool.link[parent].first_child = next;
    else
        for (int32_t c = first; c >= 0; c = p->pool.link[c].next_sibling)
            if (p->pool.link[c].next_sibling == leaf) {
                p->pool.link[c].next_sibling = next;
                break;
            }
    assert_false(gmmrrt_tree_check(p, why, sizeof why));
    assert_non_null(strstr(why, "missing from its parent's child list"));
    test_planner_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_planner_kind_keeps_the_invariants),
        cmocka_unit_test(test_task_cost_tree_keeps_the_invariants),
        cmocka_unit_test(test_pruning_and_seeding_keep_the_invariants),
        cmocka_unit_test(test_a_broken_tree_is_found),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
