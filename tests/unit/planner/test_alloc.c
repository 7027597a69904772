/*
 * test_alloc.c - planner.alloc: proves that planning allocates nothing (STYLE.md
 * rule 1). This executable defines malloc, calloc, realloc, free, aligned_alloc and
 * posix_memalign, forwarding to glibc's __libc_* entry points and counting calls while
 * `counting` is set (C++ operator new in libstdc++ ends in malloc, so FCL is covered too).
 * For each planner kind: zero allocations across gmmrrt_planner_run and best_path, and
 * across set_problem (which builds the collision world through FCL).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "gmmrrt/drivable.h"
#include "cluttered_problem.h"
#include "planner_fixtures.h"

#ifndef GMMRRT_ALLOC_TEST_SKIP
#include "alloc_counter.h" /* defines malloc & co. and the counters `counting`, `alloc_calls` */
#else
static volatile int counting;
static volatile long alloc_calls;
#endif

static void make_xy_model(gmmrrt_model_t *m)
{
    /* GMM-RRT's model: (s, x', y') components along a pass on the person's left. */
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_XY;
    m->task = GMMRRT_TASK_AVOID;
    m->dim = 3;
    m->k = 5;
    m->delta = GMMRRT_MODEL_DEFAULT_DELTA;
    for (int32_t i = 0; i < m->k; ++i) {
        const double s = (i + 0.5) / m->k;
        m->weight[i] = 1.0 / m->k;
        m->mean[i][0] = s;
        m->mean[i][1] = 3.0 - 6.0 * s; /* from in front (x' > 0) to behind */
        m->mean[i][2] = 1.2 * sin(M_PI * s);
        m->chol[i][0] = 0.1;
        m->chol[i][2] = 0.3;
        m->chol[i][5] = 0.3;
    }
    m->weight[m->k - 1] = 1.0 - 4.0 / m->k;
    assert_int_equal(gmmrrt_model_prepare(m, NULL, 0), GMMRRT_OK);
}

static void test_planning_allocates_nothing(void **state)
{
    (void)state;
    gmmrrt_model_t features, xy;
    const double theta[] = {M_PI / 2.0, -M_PI / 2.0};
    assert_int_equal(make_features_model(&features, theta, 2, 1.2, 0.2, 0.3), GMMRRT_OK);
    make_xy_model(&xy);
    const int32_t kinds[] = {GMMRRT_PLANNER_GMM_RRT_STAR, GMMRRT_PLANNER_RRT_STAR, GMMRRT_PLANNER_GMM_RRT};
    for (int k = 0; k < 3; ++k) {
        gmmrrt_planner_config_t cfg = point_robot_config(kinds[k]);
        cfg.robot_radius_m = 0.3;
        cfg.max_nodes = 3000;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
        pr.obstacles.num_people = 2;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, M_PI};
        pr.obstacles.people[1] = (gmmrrt_pose_t){1.0, -2.5, 0.0};
        pr.obstacles.num_boxes = 1;
        pr.obstacles.boxes[0] = (gmmrrt_box_t){-1.5, -1.5, 1.0, 0.5, 0.4};
        pr.obstacles.num_circles = 1;
        pr.obstacles.circles[0] = (gmmrrt_circle_t){2.0, 2.0, 0.5};
        pr.task = kinds[k] == GMMRRT_PLANNER_RRT_STAR ? GMMRRT_TASK_NONE : GMMRRT_TASK_AVOID;
        pr.model = kinds[k] == GMMRRT_PLANNER_GMM_RRT ? &xy : &features;

        alloc_calls = 0;
        counting = 1;
        const gmmrrt_status_t set = gmmrrt_planner_set_problem(t.p, &pr);
        counting = 0;
        assert_int_equal(set, GMMRRT_OK);
        const long set_allocs = alloc_calls;

        gmmrrt_budget_t b = {0.0, 4000, 0.0, 0};
        gmmrrt_plan_stats_t st;
        gmmrrt_path_t path;
        alloc_calls = 0;
        counting = 1;
        const gmmrrt_status_t run = gmmrrt_planner_run(t.p, &b, &st);
        const gmmrrt_status_t got = gmmrrt_planner_best_path(t.p, &path);
        gmmrrt_budget_t timed = {5.0, 0, 0.0, 0};
        const gmmrrt_status_t run2 = gmmrrt_planner_run(t.p, &timed, &st);
        counting = 0;
        printf("planner %d: set_problem %ld allocations, run + best_path %ld; %d nodes, status %d/%d\n",
               kinds[k], set_allocs, alloc_calls, st.nodes, run, got);
        assert_true(run == GMMRRT_OK || run == GMMRRT_POOL_FULL || run == GMMRRT_NO_PATH_YET);
        assert_true(run2 == GMMRRT_OK || run2 == GMMRRT_POOL_FULL || run2 == GMMRRT_NO_PATH_YET);
        assert_true(st.nodes > 100); /* the loop really ran */
        assert_int_equal(alloc_calls, 0);
        assert_int_equal(set_allocs, 0);
        test_planner_free(&t);
    }
}

/* The drivable path, an escape from a start in a person's disc and a walking person: set_problem,
 * run and gmmrrt_planner_drivable_path allocate nothing either. */
static void test_escape_walkers_and_drivable_path_allocate_nothing(void **state)
{
    (void)state;
    gmmrrt_model_t features;
    const double theta[] = {0.0, 0.5};
    assert_int_equal(make_features_model(&features, theta, 2, 1.2, 0.2, 0.3), GMMRRT_OK);
    features.task = GMMRRT_TASK_APPROACH;
    /* rrt-star, and gmm-rrt-star with the walker's lane cost in the objective */
    for (int kind = GMMRRT_PLANNER_GMM_RRT_STAR; kind <= GMMRRT_PLANNER_RRT_STAR; ++kind) {
        gmmrrt_planner_config_t cfg = point_robot_config(kind);
        cfg.robot_radius_m = 0.3;
        cfg.max_nodes = 3000;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.5);
        pr.model = kind == GMMRRT_PLANNER_GMM_RRT_STAR ? &features : NULL;
        pr.task = GMMRRT_TASK_APPROACH;
        pr.target_person = 1;
        pr.obstacles.num_people = 2;
        pr.obstacles.people[0] = (gmmrrt_pose_t){-3.7, 0.1, 0.0}; /* inside the robot's disc */
        pr.obstacles.people[1] = (gmmrrt_pose_t){5.0, 0.5, M_PI};
        pr.obstacles.num_circles = 1;
        pr.obstacles.circles[0] = (gmmrrt_circle_t){0.0, 1.5, 0.8};
        pr.obstacles.num_people = 3;
        pr.obstacles.people[2] = (gmmrrt_pose_t){1.0, 3.0, -M_PI / 2.0};
        pr.person_vy[2] = -0.6; /* walking */
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        opt.arrival = GMMRRT_ARRIVAL_FACE_TARGET;
        gmmrrt_budget_t b = {0.0, 3000, 0.0, 0};
        gmmrrt_path_t path;
        gmmrrt_drive_report_t rep;
        alloc_calls = 0;
        counting = 1;
        const gmmrrt_status_t set = gmmrrt_planner_set_problem(t.p, &pr);
        const gmmrrt_status_t run = gmmrrt_planner_run(t.p, &b, NULL);
        const gmmrrt_status_t got = gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep);
        counting = 0;
        printf("planner %d, escape + walker + drivable path: %ld allocations, status %d/%d/%d, %d waypoints\n", kind,
               alloc_calls, set, run, got, path.num_points);
        assert_int_equal(set, GMMRRT_ESCAPE);
        assert_int_equal(run, GMMRRT_OK);
        assert_int_equal(got, GMMRRT_ESCAPE);
        assert_true(path.num_points > 10);
        assert_int_equal(alloc_calls, 0);
        test_planner_free(&t);
    }
}

/* A pool that fills and is pruned again and again allocates nothing either. */
static void test_pruning_a_full_pool_allocates_nothing(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.max_nodes = 1000;
    cfg.grid_resolution_m = 0.05;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = cluttered_problem();
    gmmrrt_budget_t b = {0.0, 40000, 0.0, 0};
    gmmrrt_plan_stats_t st;
    alloc_calls = 0;
    counting = 1;
    const gmmrrt_status_t set = gmmrrt_planner_set_problem(t.p, &pr);
    const gmmrrt_status_t run = gmmrrt_planner_run(t.p, &b, &st);
    counting = 0;
    assert_int_equal(set, GMMRRT_OK);
    assert_int_equal(run, GMMRRT_OK);
    assert_true(st.pruned > cfg.max_nodes);
    assert_int_equal(alloc_calls, 0);
    test_planner_free(&t);
}

static void test_counter_sees_allocations(void **state)
{
    (void)state;
    /* The interposition works: a malloc while counting is seen. */
    alloc_calls = 0;
    counting = 1;
    void *volatile p = malloc(64);
    free(p);
    counting = 0;
    assert_int_equal(alloc_calls, 2);
}

int main(void)
{
#ifdef GMMRRT_ALLOC_TEST_SKIP
    /* Sanitizers bring their own malloc; replacing it would break them. */
    printf("planner.alloc skipped: built with GMMRRT_SANITIZE (the Release build runs it)\n");
    return 77;
#endif
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counter_sees_allocations),
        cmocka_unit_test(test_pruning_a_full_pool_allocates_nothing),
        cmocka_unit_test(test_planning_allocates_nothing),
        cmocka_unit_test(test_escape_walkers_and_drivable_path_allocate_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
