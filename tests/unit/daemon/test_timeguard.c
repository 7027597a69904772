/*
 * test_timeguard.c - gmmrrtd's inputs through its seam gmmrrtd_handle_message (the function
 * behind the LCM handlers), log mode, with a real planner: no sender can drag the daemon's
 * time (a ratchet of goal re-sends, a far-future first stamp, a tracker whose clock is ahead),
 * each input goes stale on its own timeout (a stale people list is dropped, a stale obstacle
 * list stops), every stop is counted by reason, and a goal whose planning box does not fit the
 * clearance grid gets its own counted reason. Arrivals are passed explicitly (the recorder's
 * receive time of a log), so each case says when a message came and what it claimed.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

#include <cmocka.h>

#include "daemon.h"
#include "daemon_fixture.h"

#define S ((int64_t)1000000)
#define MS ((int64_t)1000)
#define T0 DAEMON_FIXTURE_T0
#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

static gmmrrtd_t g_d;

static int setup(void **state)
{
    /* plain RRT*: no model needed: these cases are about inputs */
    daemon_fixture_setup(&g_d, 200, 1024, 7);
    *state = &g_d;
    return 0;
}

static int teardown(void **state)
{
    daemon_fixture_teardown(*state);
    return 0;
}

static void send_pose(gmmrrtd_t *d, int64_t recv, int64_t utime, double x)
{
    const gmmrrt_pose2d_t m = daemon_fixture_pose(utime, x, 0.0, 0.0);
    daemon_fixture_send_pose(d, recv, &m);
}

static void send_people(gmmrrtd_t *d, int64_t recv, int64_t utime, int n_people)
{
    gmmrrt_people_t *m = daemon_fixture_people(utime);
    m->num_people = n_people;
    for (int i = 0; i < n_people; ++i) {
        m->people[i].id = i + 1;
        m->people[i].x = 2.0;
        m->people[i].y = 1.5 + i;
    }
    daemon_fixture_send_people(d, recv, m);
}

static void send_goal(gmmrrtd_t *d, int64_t recv, int64_t utime, double x, double y)
{
    const gmmrrt_nav_goal_t m = daemon_fixture_goal(utime, 1, x, y, GMMRRT_NAV_GOAL_T_TASK_AVOID, 0);
    daemon_fixture_send_goal(d, recv, &m);
}

static void send_obstacles(gmmrrtd_t *d, int64_t recv, int64_t utime)
{
    gmmrrt_obstacles_t *m = daemon_fixture_obstacles(utime);
    m->num_circles = 1;
    m->circle_x[0] = 2.0;
    m->circle_y[0] = -1.5;
    m->circle_radius[0] = 0.3;
    daemon_fixture_send_obstacles(d, recv, m);
}

/* Poses at 10 Hz for n messages from local time l (stamps T0 + l); the plans that follow. */
static void drive(gmmrrtd_t *d, int64_t l, int n)
{
    for (int i = 0; i < n; ++i)
        send_pose(d, l + i * 100 * MS, T0 + l + i * 100 * MS, 0.01 * i);
}

static void test_ratchet_of_goal_resends_stops_nothing(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, T0, 4.0, 0.0);
    drive(d, 0, 20);
    const int64_t cycles_before = d->cycles;
    for (int i = 1; i <= 60; ++i) /* the same goal, each re-send stamped 1.9 s later, 2 ms apart */
        send_goal(d, 1950 * MS + i * 2 * MS, T0 + 1950 * MS + i * 1900 * MS, 4.0, 0.0);
    drive(d, 2100 * MS, 100);
    /* 10 s of log: 100 cycles, each with a plan; no stop of any kind. */
    assert_int_equal(d->cycles - cycles_before, 101);
    for (int i = 0; i < ST(NUM_STOP_REASONS); ++i)
        assert_int_equal(d->status.stops[i], 0);
    assert_int_equal(d->status.rejected[ST(REJECT_CLOCK_RESYNC)], 0);
    assert_true(d->status.rejected[ST(REJECT_TIME_FUTURE)] >= 55);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
    /* The set-up is reported apart from the run: measured (finite, not negative) and below the
     * cycle's whole time. Lazily built collision structures make it a few microseconds, which the
     * daemon's microsecond clock may read as 0, so 0 is a valid reading. */
    assert_true(isfinite(d->status.setup_time_ms) && d->status.setup_time_ms >= 0.0);
    /* A new correctly stamped goal on the attacked channel is taken at once. */
    send_goal(d, 12100 * MS, T0 + 12100 * MS, 3.0, 0.5);
    drive(d, 12150 * MS, 3);
    assert_true(d->goal.x == 3.0);
}

static void test_far_future_first_goal_stops_nothing(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, GMMRRTD_MAX_UTIME - 1, 4.0, 0.0);
    drive(d, 50 * MS, 50);
    assert_int_equal(d->status.stops[ST(STOP_POSE_STALE)], 0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
}

static void test_far_future_first_pose_costs_no_stop(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, T0, 4.0, 0.0);
    send_pose(d, 10 * MS, GMMRRTD_MAX_UTIME - 1, 0.0);
    drive(d, 100 * MS, 30); /* the next correct pose replaces the unconfirmed first offset */
    assert_int_equal(d->status.stops[ST(STOP_POSE_STALE)], 0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
}

static void skew_case(gmmrrtd_t *d, int64_t skew_us)
{
    send_goal(d, 0, T0, 4.0, 0.0);
    for (int i = 0; i < 100; ++i) { /* tracker on a second computer, its clock skew_us ahead */
        send_pose(d, i * 100 * MS, T0 + i * 100 * MS, 0.01 * i);
        send_people(d, i * 100 * MS + 30 * MS, T0 + i * 100 * MS + 30 * MS + skew_us, 1);
    }
    for (int i = 0; i < ST(NUM_REJECT_REASONS); ++i)
        assert_int_equal(d->status.rejected[i], 0);
    for (int i = 0; i < ST(NUM_STOP_REASONS); ++i)
        assert_int_equal(d->status.stops[i], 0);
    assert_int_equal(d->status.stale_inputs, 0);
    assert_int_equal(d->problem.obstacles.num_people, 1); /* the people are planned around */
}

static void test_tracker_0_6_s_ahead(void **state) { skew_case(*state, 600 * MS); }
static void test_tracker_1_9_s_ahead(void **state) { skew_case(*state, 1900 * MS); }

static void test_stale_people_are_dropped_and_counted_once(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, T0, 4.0, 0.0);
    for (int i = 0; i < 10; ++i) {
        send_pose(d, i * 100 * MS, T0 + i * 100 * MS, 0.0);
        send_people(d, i * 100 * MS + 10 * MS, T0 + i * 100 * MS + 10 * MS, 1);
    }
    assert_int_equal(d->problem.obstacles.num_people, 1);
    drive(d, 1000 * MS, 30); /* the tracker went quiet: after people_timeout_ms (1 s) it is forgotten */
    assert_int_equal(d->problem.obstacles.num_people, 0);
    assert_true(d->status.stale_inputs & ST(STALE_PEOPLE));
    assert_int_equal(d->status.rejected[ST(REJECT_PEOPLE_STALE)], 1);
    assert_int_equal(d->status.state, ST(STATE_PLANNING)); /* people gone is no reason to stop */
    send_people(d, 4000 * MS, T0 + 4000 * MS, 1);
    drive(d, 4010 * MS, 3);
    assert_int_equal(d->problem.obstacles.num_people, 1);
    assert_int_equal(d->status.stale_inputs, 0);
}

static void test_stale_obstacles_stop_when_a_timeout_is_set(void **state)
{
    gmmrrtd_t *d = *state;
    d->set.obstacles_timeout_ms = 1500.0;
    send_goal(d, 0, T0, 4.0, 0.0);
    send_obstacles(d, 0, T0);
    drive(d, 0, 40);
    assert_true(d->status.stops[ST(STOP_OBSTACLES_STALE)] > 0);
    assert_int_equal(d->status.rejected[ST(REJECT_OBSTACLES_STALE)], 1);
    assert_true(d->status.stale_inputs & ST(STALE_OBSTACLES));
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_OBSTACLES_STALE);
}

static void test_stale_pose_stops_are_counted(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, T0, 4.0, 0.0);
    drive(d, 0, 5);
    send_people(d, 2000 * MS, T0 + 2000 * MS, 0); /* time passes, no pose */
    assert_true(d->status.stops[ST(STOP_POSE_STALE)] >= 10);
    assert_int_equal(d->status.rejected[ST(REJECT_POSE_STALE)], 1);
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_POSE_STALE);
}

static void test_goal_beyond_the_grid_has_a_counted_reason(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, T0, 46.0, 0.0); /* 52 x 6 m at 0.05 m: more than the default 2^20 cells? */
    d->set.cfg.grid_max_cells = 1000; /* the planner block keeps its size; only the check changes */
    assert_int_equal(gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg), GMMRRT_OK);
    drive(d, 0, 10);
    assert_int_equal(d->status.rejected[ST(REJECT_PLANNING_BOX)], 1);
    assert_true(d->status.stops[ST(STOP_PLANNING_BOX)] >= 9);
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_PLANNING_BOX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_ratchet_of_goal_resends_stops_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_far_future_first_goal_stops_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_far_future_first_pose_costs_no_stop, setup, teardown),
        cmocka_unit_test_setup_teardown(test_tracker_0_6_s_ahead, setup, teardown),
        cmocka_unit_test_setup_teardown(test_tracker_1_9_s_ahead, setup, teardown),
        cmocka_unit_test_setup_teardown(test_stale_people_are_dropped_and_counted_once, setup, teardown),
        cmocka_unit_test_setup_teardown(test_stale_obstacles_stop_when_a_timeout_is_set, setup, teardown),
        cmocka_unit_test_setup_teardown(test_stale_pose_stops_are_counted, setup, teardown),
        cmocka_unit_test_setup_teardown(test_goal_beyond_the_grid_has_a_counted_reason, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
