/*
 * test_timeguard.c - unit tests of gmmrrtd's time guard (planner/daemon/inputs.c,
 * docs/daemon.md "Clock steps"): the bounded-future
 * rule (REJECT_TIME_FUTURE) and the resynchronisation after time_resync_count consecutive
 * messages of one channel off the clock in the same direction (REJECT_CLOCK_RESYNC), driven
 * through gmmrrtd_inputs_handle with encoded pose2d_t / people_t messages. No goal is ever
 * sent, so the cycles that fall due are idle and need no model or planner.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "daemon.h"

#define T0 ((int64_t)1700000000000000)
#define HOUR_US ((int64_t)3600000000)
#define RESYNC 10

enum {
    FUTURE = GMMRRT_PLANNER_STATUS_T_REJECT_TIME_FUTURE,
    BACKWARDS = GMMRRT_PLANNER_STATUS_T_REJECT_TIME_BACKWARDS,
    RESYNCS = GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC,
};

static gmmrrtd_t g_d;

static int setup(void **state)
{
    gmmrrtd_t *d = &g_d;
    memset(d, 0, sizeof *d);
    gmmrrtd_log_set_level(GMMRRTD_LOG_ERROR);
    gmmrrtd_settings_default(&d->set);
    d->set.time_resync_count = RESYNC;
    d->clock_mode = GMMRRTD_CLOCK_LOG;
    d->lcm_in = d->lcm_out = lcm_create("file:///dev/null?mode=w");
    assert_non_null(d->lcm_out);
    *state = d;
    return 0;
}

static int teardown(void **state)
{
    gmmrrtd_t *d = *state;
    lcm_destroy(d->lcm_out);
    return 0;
}

static void send_pose(gmmrrtd_t *d, int64_t utime, double x)
{
    gmmrrt_pose2d_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.x = x;
    uint8_t buf[256];
    const int n = gmmrrt_pose2d_t_encode(buf, 0, (int)sizeof buf, &m);
    assert_true(n > 0);
    gmmrrtd_inputs_handle(d, GMMRRTD_IN_POSE, buf, (size_t)n);
}

static void send_people(gmmrrtd_t *d, int64_t utime)
{
    static gmmrrt_people_t m;
    static uint8_t buf[8192];
    memset(&m, 0, sizeof m);
    m.utime = utime;
    const int n = gmmrrt_people_t_encode(buf, 0, (int)sizeof buf, &m);
    assert_true(n > 0);
    gmmrrtd_inputs_handle(d, GMMRRTD_IN_PEOPLE, buf, (size_t)n);
}

/* Poses every 100 ms from T0 for n messages; returns the last utime. */
static int64_t good_poses(gmmrrtd_t *d, int64_t from, int n)
{
    for (int i = 0; i < n; ++i)
        send_pose(d, from + (int64_t)i * 100000, (double)i);
    return from + (int64_t)(n - 1) * 100000;
}

static void test_one_future_pose_changes_nothing(void **state)
{
    gmmrrtd_t *d = *state;
    const int64_t last = good_poses(d, T0, 10);
    send_pose(d, last + HOUR_US, 99.0);
    assert_int_equal(d->status.rejected[FUTURE], 1);
    assert_true(d->clock_utime == last);
    assert_true(d->pose.utime == last && d->pose.x != 99.0);
    good_poses(d, last + 100000, 10); /* the next good poses are all accepted */
    assert_int_equal(d->status.rejected[FUTURE], 1);
    assert_int_equal(d->status.rejected[BACKWARDS], 0);
    assert_int_equal(d->status.rejected[RESYNCS], 0);
    assert_true(d->pose.utime == last + 1000000);
}

static void test_log_bound_allows_silence(void **state)
{
    gmmrrtd_t *d = *state;
    const int64_t last = good_poses(d, T0, 5);
    /* A 50 s silence in a log is within log_max_future_ms (60 s): accepted at once. */
    send_pose(d, last + 50 * (int64_t)1000000, 1.0);
    assert_int_equal(d->status.rejected[FUTURE], 0);
    assert_true(d->clock_utime == last + 50 * (int64_t)1000000);
    /* With the bound at 1 s the same jump is refused. */
    d->set.log_max_future_ms = 1000.0;
    send_pose(d, d->clock_utime + 2 * (int64_t)1000000, 2.0);
    assert_int_equal(d->status.rejected[FUTURE], 1);
}

static void test_live_bound(void **state)
{
    gmmrrtd_t *d = *state;
    d->clock_mode = GMMRRTD_CLOCK_LIVE;
    const int64_t last = good_poses(d, T0, 3);
    send_pose(d, last + 3 * (int64_t)1000000, 1.0); /* 3 s ahead, limit 2 s */
    assert_int_equal(d->status.rejected[FUTURE], 1);
    assert_true(d->clock_utime == last);
    send_pose(d, last + 1 * (int64_t)1000000, 2.0); /* 1 s ahead: a late clock, accepted */
    assert_int_equal(d->status.rejected[FUTURE], 1);
    assert_true(d->clock_utime == last + 1000000);
}

static void test_forward_step_resyncs(void **state)
{
    gmmrrtd_t *d = *state;
    const int64_t last = good_poses(d, T0, 10);
    const int64_t stepped = last + HOUR_US;
    for (int i = 1; i < RESYNC; ++i) {
        send_pose(d, stepped + (int64_t)i * 100000, 0.0);
        assert_int_equal(d->status.rejected[RESYNCS], 0);
    }
    assert_int_equal(d->status.rejected[FUTURE], RESYNC - 1);
    assert_true(d->clock_utime == last);
    send_pose(d, stepped + (int64_t)RESYNC * 100000, 5.0);
    assert_int_equal(d->status.rejected[FUTURE], RESYNC - 1);
    assert_int_equal(d->status.rejected[RESYNCS], 1);
    assert_true(d->clock_utime == stepped + (int64_t)RESYNC * 100000);
    assert_true(d->pose.x == 5.0);
    /* Other channels on the new time line are accepted right away. */
    send_people(d, stepped + (int64_t)RESYNC * 100000 + 50000);
    assert_true(d->last_utime[GMMRRTD_IN_PEOPLE] == stepped + (int64_t)RESYNC * 100000 + 50000);
    assert_int_equal(d->status.rejected[FUTURE], RESYNC - 1);
}

static void test_backward_step_resyncs(void **state)
{
    gmmrrtd_t *d = *state;
    const int64_t last = good_poses(d, T0 + HOUR_US, 10);
    send_people(d, last);
    for (int i = 1; i < RESYNC; ++i)
        send_pose(d, T0 + (int64_t)i * 100000, 0.0);
    assert_int_equal(d->status.rejected[BACKWARDS], RESYNC - 1);
    assert_int_equal(d->status.rejected[RESYNCS], 0);
    send_pose(d, T0 + (int64_t)RESYNC * 100000, 7.0);
    assert_int_equal(d->status.rejected[RESYNCS], 1);
    assert_true(d->clock_utime == T0 + (int64_t)RESYNC * 100000);
    assert_true(d->pose.x == 7.0);
    /* The people channel's order restarts with the clock: its next message (on the new time
     * line, hence older than its last one) is accepted. */
    send_people(d, T0 + (int64_t)RESYNC * 100000 + 50000);
    assert_int_equal(d->status.rejected[BACKWARDS], RESYNC - 1);
    assert_true(d->last_utime[GMMRRTD_IN_PEOPLE] == T0 + (int64_t)RESYNC * 100000 + 50000);
}

static void test_good_messages_break_the_run(void **state)
{
    gmmrrtd_t *d = *state;
    int64_t t = good_poses(d, T0, 5);
    for (int round = 0; round < 3; ++round) {
        for (int i = 0; i < RESYNC - 1; ++i)
            send_pose(d, t + HOUR_US, 0.0); /* a stray run one short of a resync */
        t += 100000;
        send_pose(d, t, 1.0); /* one good pose in between */
    }
    assert_int_equal(d->status.rejected[FUTURE], 3 * (RESYNC - 1));
    assert_int_equal(d->status.rejected[RESYNCS], 0);
    assert_true(d->clock_utime == t);
}

static void test_directions_do_not_add_up(void **state)
{
    gmmrrtd_t *d = *state;
    const int64_t last = good_poses(d, T0 + HOUR_US, 5);
    for (int i = 0; i < 2 * RESYNC; ++i)
        send_pose(d, i % 2 ? last + HOUR_US : T0, 0.0); /* future, backwards, future, ... */
    assert_int_equal(d->status.rejected[FUTURE] + d->status.rejected[BACKWARDS], 2 * RESYNC);
    assert_int_equal(d->status.rejected[RESYNCS], 0);
    assert_true(d->clock_utime == last);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_one_future_pose_changes_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_log_bound_allows_silence, setup, teardown),
        cmocka_unit_test_setup_teardown(test_live_bound, setup, teardown),
        cmocka_unit_test_setup_teardown(test_forward_step_resyncs, setup, teardown),
        cmocka_unit_test_setup_teardown(test_backward_step_resyncs, setup, teardown),
        cmocka_unit_test_setup_teardown(test_good_messages_break_the_run, setup, teardown),
        cmocka_unit_test_setup_teardown(test_directions_do_not_add_up, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
