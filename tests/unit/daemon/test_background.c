/*
 * test_background.c - gmmrrtd with [planner] task_cost = background (config.h,
 * GMMRRT_TASK_COST_BACKGROUND; docs/daemon.md, "Models"): each model file's background model is
 * loaded with it (models.c) and passed with the chosen model as problem.background_model
 * (cycle.c). Cases: a daemon with an avoid model and its background plans (and the planner
 * would refuse the same problem without the background, so the plan did use it); a file
 * without a background is refused at start-up, and loads under task_cost = paper or under RRT*
 * (which never reads the task cost, so needs no background); on reload a
 * file without one is refused (REJECT_MODEL_RELOAD) and the old model and background both stay,
 * while a good file replaces both; the models in use are checked against new planner settings
 * (what a reload does before taking them); the approach model set brings each direction's own
 * background and refuses the set when one direction has none. Real files (written by the core's
 * gmmrrt_model_save_file_background) in a scratch directory, a real GMM-RRT* planner with an
 * iteration budget and a fixed seed.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "daemon.h"
#include "daemon_fixture.h"
#include "gmmrrt/model_file.h"

#define MS ((int64_t)1000)
#define T0 DAEMON_FIXTURE_T0
#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

static gmmrrtd_t g_d;
static int64_t g_t; /* the log time of the last message, us after T0 */
static char g_dir[256];

/* A (d, theta) model for `task`: K components, the first mean's distance mean_d (which tells
 * models apart in the cases). */
static void features_model(gmmrrt_model_t *m, int32_t task, int32_t k, double mean_d)
{
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_FEATURES;
    m->task = task;
    m->homotopy = GMMRRT_HOMOTOPY_ALL;
    m->dim = 2;
    m->k = k;
    m->angle_mask = 0x2u;
    m->delta = GMMRRT_MODEL_DEFAULT_DELTA;
    for (int32_t i = 0; i < k; ++i) {
        m->weight[i] = 1.0 / (double)k;
        m->mean[i][0] = mean_d + 0.5 * (double)i;
        m->mean[i][1] = -1.0 + 1.0 * (double)i;
        m->chol[i][0] = 0.5;
        m->chol[i][1] = 0.0;
        m->chol[i][2] = 0.6;
    }
}

/* Writes `name` in the scratch directory: the task model and, when bg_k > 0, a background of
 * bg_k components whose first distance is bg_d. The path goes to path[cap]. */
static void write_model(const char *name, int32_t task, int32_t k, double mean_d, int32_t bg_k, double bg_d,
                        char *path, size_t cap)
{
    snprintf(path, cap, "%s/%s", g_dir, name);
    gmmrrt_model_t m, bg;
    features_model(&m, task, k, mean_d);
    features_model(&bg, task, bg_k > 0 ? bg_k : 1, bg_d);
    char err[512];
    if (gmmrrt_model_save_file_background(path, &m, bg_k > 0 ? &bg : NULL, NULL, 0, err, sizeof err) != GMMRRT_OK)
        fail_msg("cannot write %s: %s", path, err);
}

/* The planner of the cases: `planner` with the given task cost, in a block of its own size. */
static void use_planner_of(gmmrrtd_t *d, int32_t planner, int32_t task_cost)
{
    free(d->mem);
    d->set.cfg.planner = planner;
    d->set.cfg.task_cost = task_cost;
    d->mem_size = gmmrrt_planner_mem_size(&d->set.cfg);
    d->mem = aligned_alloc(64, (d->mem_size + 63u) / 64u * 64u);
    assert_non_null(d->mem);
    assert_int_equal(gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg), GMMRRT_OK);
}

/* GMM-RRT*, the planner that carries the task cost. */
static void use_planner(gmmrrtd_t *d, int32_t task_cost) { use_planner_of(d, GMMRRT_PLANNER_GMM_RRT_STAR, task_cost); }

static int setup(void **state)
{
    daemon_fixture_setup(&g_d, 600, 4096, 23);
    use_planner(&g_d, GMMRRT_TASK_COST_BACKGROUND);
    g_t = 0;
    snprintf(g_dir, sizeof g_dir, "%s/gmmrrtd-bg-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    assert_non_null(mkdtemp(g_dir));
    *state = &g_d;
    return 0;
}

static int teardown(void **state)
{
    daemon_fixture_teardown(*state);
    char cmd[300]; /* the scratch directory and the model files in it */
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    assert_int_equal(system(cmd), 0);
    return 0;
}

static void send_pose(gmmrrtd_t *d, double x, double y)
{
    const gmmrrt_pose2d_t m = daemon_fixture_pose(T0 + g_t, x, y, 0.0);
    daemon_fixture_send_pose(d, g_t, &m);
}

/* A pose every 50 ms for `ms`: one cycle per 100 ms of log time (dispatch.c). */
static void hold_pose(gmmrrtd_t *d, double x, double y, int64_t ms)
{
    for (int64_t k = 0; k < ms / 50; ++k) {
        g_t += 50 * MS;
        send_pose(d, x, y);
    }
}

static void send_person(gmmrrtd_t *d, double x, double y, double yaw)
{
    daemon_fixture_send_person(d, g_t, T0 + g_t, x, y, yaw);
}

static void send_goal(gmmrrtd_t *d, int64_t id, double x, double y, int8_t task, int32_t target)
{
    const gmmrrt_nav_goal_t m = daemon_fixture_goal(T0 + g_t, id, x, y, task, target);
    daemon_fixture_send_goal(d, g_t, &m);
}

/* Avoid a person standing off the straight line from (0, 0) to (6, 0). */
static void plan_avoid(gmmrrtd_t *d)
{
    send_pose(d, 0.0, 0.0);
    send_person(d, 3.0, 0.8, -M_PI / 2.0);
    send_goal(d, 1, 6.0, 0.0, GMMRRT_NAV_GOAL_T_TASK_AVOID, -1);
    hold_pose(d, 0.0, 0.0, 200);
}

static void test_a_daemon_with_the_background_cost_plans_with_the_files_background(void **state)
{
    gmmrrtd_t *d = *state;
    write_model("avoid.gmm", GMMRRT_TASK_AVOID, 3, 1.5, 2, 4.0, d->set.model_avoid, sizeof d->set.model_avoid);
    assert_int_equal(gmmrrtd_models_load(d, 0), 0);
    assert_true(d->have_avoid && d->has_bg_avoid);
    assert_int_equal(d->model_avoid.k, 3);
    assert_int_equal(d->bg_avoid.k, 2);
    assert_true(d->bg_avoid.mean[0][0] == 4.0);
    plan_avoid(d);
    assert_true(d->cycles >= 1);
    assert_int_equal(d->status.rejected[ST(REJECT_SETUP)], 0);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_ptr_equal(d->problem.model, &d->model_avoid);
    assert_ptr_equal(d->problem.background_model, &d->bg_avoid);
    /* The background is what the cost needs: the same problem without it is refused. */
    gmmrrt_problem_t without = d->problem;
    without.background_model = NULL;
    assert_int_equal(gmmrrt_planner_set_problem(d->planner, &without), GMMRRT_ERR_MODEL_MISMATCH);
}

static void test_a_file_without_background_is_refused_at_start_up(void **state)
{
    gmmrrtd_t *d = *state;
    write_model("plain.gmm", GMMRRT_TASK_AVOID, 3, 1.5, 0, 0.0, d->set.model_avoid, sizeof d->set.model_avoid);
    assert_int_equal(gmmrrtd_models_load(d, 0), -1);
    assert_false(d->have_avoid);
    assert_false(d->has_bg_avoid);
    /* The same file is good for the paper's cost, which needs no background; none is passed. */
    use_planner(d, GMMRRT_TASK_COST_PAPER);
    assert_int_equal(gmmrrtd_models_load(d, 0), 0);
    assert_true(d->have_avoid);
    assert_false(d->has_bg_avoid);
    plan_avoid(d);
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_null(d->problem.background_model);
}

/* RRT* costs length only and never reads the background: under task_cost = background a file
 * without one loads and plans (the core's rule, gmmrrt_planner_needs_background); the new
 * settings GMM-RRT* + background are then refused against it, the background named. */
static void test_a_file_without_background_serves_a_planner_without_the_task_cost(void **state)
{
    gmmrrtd_t *d = *state;
    use_planner_of(d, GMMRRT_PLANNER_RRT_STAR, GMMRRT_TASK_COST_BACKGROUND);
    write_model("plain.gmm", GMMRRT_TASK_AVOID, 3, 1.5, 0, 0.0, d->set.model_avoid, sizeof d->set.model_avoid);
    assert_int_equal(gmmrrtd_models_load(d, 0), 0);
    assert_true(d->have_avoid);
    assert_false(d->has_bg_avoid);
    char why[256] = "";
    assert_int_equal(gmmrrtd_models_fit_config(d, &d->set.cfg, why, sizeof why), 1);
    plan_avoid(d);
    assert_int_equal(d->status.rejected[ST(REJECT_SETUP)], 0);
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_null(d->problem.background_model);
    gmmrrt_planner_config_t cfg = d->set.cfg;
    cfg.planner = GMMRRT_PLANNER_GMM_RRT_STAR;
    assert_int_equal(gmmrrtd_models_fit_config(d, &cfg, why, sizeof why), 0);
    assert_non_null(strstr(why, "avoid model has no background"));
}

static void test_reload_replaces_model_and_background_together_or_not_at_all(void **state)
{
    gmmrrtd_t *d = *state;
    char path[GMMRRTD_PATH_MAX];
    write_model("avoid.gmm", GMMRRT_TASK_AVOID, 3, 1.5, 2, 4.0, path, sizeof path);
    strcpy(d->set.model_avoid, path);
    assert_int_equal(gmmrrtd_models_load(d, 0), 0);
    /* A new model without a background: refused, counted, the old pair kept. */
    write_model("avoid.gmm", GMMRRT_TASK_AVOID, 2, 2.5, 0, 0.0, path, sizeof path);
    assert_int_equal(gmmrrtd_models_load(d, 1), -1);
    assert_int_equal(d->status.rejected[ST(REJECT_MODEL_RELOAD)], 1);
    assert_true(d->have_avoid && d->has_bg_avoid);
    assert_int_equal(d->model_avoid.k, 3);
    assert_true(d->model_avoid.mean[0][0] == 1.5);
    assert_int_equal(d->bg_avoid.k, 2);
    assert_true(d->bg_avoid.mean[0][0] == 4.0);
    /* ...and still plans. */
    plan_avoid(d);
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_ptr_equal(d->problem.background_model, &d->bg_avoid);
    /* A new model with its background: both replaced. */
    write_model("avoid.gmm", GMMRRT_TASK_AVOID, 2, 2.5, 1, 3.5, path, sizeof path);
    assert_int_equal(gmmrrtd_models_load(d, 1), 0);
    assert_int_equal(d->status.rejected[ST(REJECT_MODEL_RELOAD)], 1);
    assert_int_equal(d->model_avoid.k, 2);
    assert_true(d->model_avoid.mean[0][0] == 2.5);
    assert_int_equal(d->bg_avoid.k, 1);
    assert_true(d->bg_avoid.mean[0][0] == 3.5);
}

/* What a reload checks before it takes new planner settings (main.c): the models in use must fit
 * them, a background included for the background cost. */
static void test_the_models_in_use_are_checked_against_new_planner_settings(void **state)
{
    gmmrrtd_t *d = *state;
    char path[GMMRRTD_PATH_MAX], why[256] = "";
    use_planner(d, GMMRRT_TASK_COST_PAPER);
    write_model("plain.gmm", GMMRRT_TASK_AVOID, 3, 1.5, 0, 0.0, path, sizeof path);
    strcpy(d->set.model_avoid, path);
    assert_int_equal(gmmrrtd_models_load(d, 0), 0);
    gmmrrt_planner_config_t cfg = d->set.cfg;
    assert_int_equal(gmmrrtd_models_fit_config(d, &cfg, why, sizeof why), 1);
    cfg.task_cost = GMMRRT_TASK_COST_BACKGROUND;
    assert_int_equal(gmmrrtd_models_fit_config(d, &cfg, why, sizeof why), 0);
    assert_non_null(strstr(why, "avoid model has no background"));
    cfg = d->set.cfg;
    cfg.planner = GMMRRT_PLANNER_GMM_RRT; /* wants an x-y model */
    assert_int_equal(gmmrrtd_models_fit_config(d, &cfg, why, sizeof why), 0);
    assert_non_null(strstr(why, "does not fit the gmm-rrt planner"));
    /* With its background the model fits the background cost. */
    use_planner(d, GMMRRT_TASK_COST_BACKGROUND);
    write_model("plain.gmm", GMMRRT_TASK_AVOID, 3, 1.5, 1, 2.0, path, sizeof path);
    assert_int_equal(gmmrrtd_models_load(d, 1), 0);
    assert_int_equal(gmmrrtd_models_fit_config(d, &d->set.cfg, why, sizeof why), 1);
}

static void test_the_approach_set_brings_each_directions_background(void **state)
{
    gmmrrtd_t *d = *state;
    char path[GMMRRTD_PATH_MAX];
    for (int32_t k = 0; k < GMMRRT_APPROACH_DIRECTIONS; ++k) { /* direction 5 without a background */
        char name[64];
        snprintf(name, sizeof name, "%s.gmm", gmmrrt_approach_direction_name(k));
        write_model(name, GMMRRT_TASK_APPROACH, 2, 1.0, k == 5 ? 0 : 1, 1.0 + (double)k, path, sizeof path);
    }
    strcpy(d->set.approach_set, g_dir);
    assert_int_equal(gmmrrtd_models_load(d, 0), -1);
    assert_false(d->have_approach_set);
    /* Direction 5 rewritten with its background: the whole set loads. */
    char name[64];
    snprintf(name, sizeof name, "%s.gmm", gmmrrt_approach_direction_name(5));
    write_model(name, GMMRRT_TASK_APPROACH, 2, 1.0, 1, 6.0, path, sizeof path);
    assert_int_equal(gmmrrtd_models_load(d, 0), 0);
    assert_true(d->have_approach_set);
    for (int32_t k = 0; k < GMMRRT_APPROACH_DIRECTIONS; ++k) {
        assert_true(d->approach_set_has_bg[k]);
        assert_true(d->approach_set_bg[k].mean[0][0] == 1.0 + (double)k);
    }
    /* Approach a person at (4, 0) facing the robot: the cycle takes the robot's direction's pair. */
    send_pose(d, 0.0, 0.0);
    send_person(d, 4.0, 0.0, M_PI);
    send_goal(d, 2, 3.0, 0.0, GMMRRT_NAV_GOAL_T_TASK_APPROACH, 1);
    hold_pose(d, 0.0, 0.0, 200);
    assert_int_equal(d->status.rejected[ST(REJECT_SETUP)], 0);
    assert_true(d->plan_msg.num_waypoints >= 2);
    const int32_t dir = d->status.approach_model;
    assert_true(dir >= 0 && dir < GMMRRT_APPROACH_DIRECTIONS);
    assert_ptr_equal(d->problem.model, &d->approach_set[dir]);
    assert_ptr_equal(d->problem.background_model, &d->approach_set_bg[dir]);
    assert_true(d->problem.background_model->mean[0][0] == 1.0 + (double)dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_a_daemon_with_the_background_cost_plans_with_the_files_background,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(test_a_file_without_background_is_refused_at_start_up, setup, teardown),
        cmocka_unit_test_setup_teardown(test_a_file_without_background_serves_a_planner_without_the_task_cost, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_reload_replaces_model_and_background_together_or_not_at_all, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_the_models_in_use_are_checked_against_new_planner_settings, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_the_approach_set_brings_each_directions_background, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
