/*
 * test_clock.c - gmmrrtd's per-source clock model (planner/daemon/clock.h) against the ways a
 * sender once dragged the daemon's single clock: a ratchet of ever later stamps, a first
 * stamp near 2^53 us, a skew between two computers, and a clock step of a whole system. Each
 * case drives gmmrrtd_clock_judge with arrivals on the local time base, as the daemon does.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "clock.h"

#define S ((int64_t)1000000)
#define MS ((int64_t)1000)
#define T0 ((int64_t)1700000000000000) /* sender clocks: Unix time */
#define L0 ((int64_t)5000000000)       /* local time base: monotonic since boot */

static const gmmrrtd_clock_params_t k_p = {.max_off_us = 2 * S, .resync_count = 5, .resync_us = 1 * S,
                                           .slew_us_per_s = 10 * MS};

/* n messages every period_us from local l and stamp u (stamp = local + (u - l)); returns the
 * number accepted. */
static int stream(gmmrrtd_source_clock_t *s, int64_t l, int64_t u, int64_t period_us, int n)
{
    int ok = 0;
    for (int i = 0; i < n; ++i) {
        const gmmrrtd_stamp_t v = gmmrrtd_clock_judge(s, &k_p, u + i * period_us, l + i * period_us, NULL, NULL);
        ok += v == GMMRRTD_STAMP_OK || v == GMMRRTD_STAMP_FIRST || v == GMMRRTD_STAMP_RESYNC;
    }
    return ok;
}

static void test_ratchet_of_goal_resends_moves_nothing(void **state)
{
    (void)state;
    gmmrrtd_source_clock_t goal = {0};
    assert_int_equal(stream(&goal, L0, T0, 100 * MS, 3), 3);
    const int64_t l = L0 + 300 * MS, u = T0 + 300 * MS;
    int accepted = 0, resyncs = 0;
    for (int i = 1; i <= 60; ++i) { /* 60 re-sends in 0.13 s, each stamped 1.9 s later */
        const gmmrrtd_stamp_t v = gmmrrtd_clock_judge(&goal, &k_p, u + i * 1900 * MS, l + i * 2 * MS, NULL, NULL);
        accepted += v == GMMRRTD_STAMP_OK;
        resyncs += v == GMMRRTD_STAMP_RESYNC;
    }
    assert_int_equal(resyncs, 0);
    assert_true(accepted <= 1);
    /* The channel's order did not move into the future: a correct goal 0.2 s later is accepted. */
    assert_true(goal.last_utime <= u + 130 * MS);
    assert_int_equal(gmmrrtd_clock_judge(&goal, &k_p, u + 200 * MS, l + 200 * MS, NULL, NULL), GMMRRTD_STAMP_OK);
    assert_true(gmmrrtd_clock_age_us(&goal, l + 200 * MS) < 10 * MS);
}

static void test_slow_ratchet_never_resyncs(void **state)
{
    (void)state;
    gmmrrtd_source_clock_t s = {0};
    stream(&s, L0, T0, 100 * MS, 3);
    int resyncs = 0;
    for (int i = 1; i <= 100; ++i) /* one every 0.3 s, each 1.9 s later than the last */
        resyncs += gmmrrtd_clock_judge(&s, &k_p, T0 + 200 * MS + i * 2200 * MS, L0 + 200 * MS + i * 300 * MS, NULL,
                                       NULL) == GMMRRTD_STAMP_RESYNC;
    assert_int_equal(resyncs, 0);
}

static void test_far_future_first_stamp_is_replaced_by_the_next(void **state)
{
    (void)state;
    gmmrrtd_source_clock_t pose = {0};
    assert_int_equal(gmmrrtd_clock_judge(&pose, &k_p, GMMRRTD_MAX_UTIME - 1, L0, NULL, NULL), GMMRRTD_STAMP_FIRST);
    int64_t step = 0;
    assert_int_equal(gmmrrtd_clock_judge(&pose, &k_p, T0 + 100 * MS, L0 + 100 * MS, NULL, &step), GMMRRTD_STAMP_FIRST);
    assert_true(step < 0);
    assert_int_equal(stream(&pose, L0 + 200 * MS, T0 + 200 * MS, 100 * MS, 50), 50);
    assert_true(gmmrrtd_clock_age_us(&pose, L0 + 5100 * MS) <= 100 * MS);
    /* Once confirmed, one far-future stamp is refused and changes nothing. */
    assert_int_equal(gmmrrtd_clock_judge(&pose, &k_p, GMMRRTD_MAX_UTIME, L0 + 5200 * MS, NULL, NULL),
                     GMMRRTD_STAMP_AHEAD);
    assert_int_equal(gmmrrtd_clock_judge(&pose, &k_p, T0 + 5300 * MS, L0 + 5300 * MS, NULL, NULL), GMMRRTD_STAMP_OK);
}

static void skew_case(int64_t skew_us)
{
    gmmrrtd_source_clock_t pose = {0}, people = {0};
    int ok_pose = 0, ok_people = 0;
    int64_t worst_age = 0;
    for (int i = 0; i < 600; ++i) { /* 60 s at 10 Hz, with up to 30 ms of transport jitter */
        const int64_t sent = L0 + i * 100 * MS;
        const int64_t jitter = (i * 7919 % 31) * MS;
        ok_pose += gmmrrtd_clock_judge(&pose, &k_p, T0 + (sent - L0), sent + jitter, NULL, NULL) <= GMMRRTD_STAMP_FIRST;
        ok_people += gmmrrtd_clock_judge(&people, &k_p, T0 + (sent - L0) + skew_us, sent + 50 * MS + jitter, NULL,
                                         NULL) <= GMMRRTD_STAMP_FIRST;
        const int64_t age = gmmrrtd_clock_age_us(&pose, sent + 60 * MS);
        worst_age = age > worst_age ? age : worst_age;
    }
    assert_int_equal(ok_pose, 600);
    assert_int_equal(ok_people, 600);
    assert_true(worst_age < 200 * MS); /* the pose is never judged by the tracker's clock */
    assert_true(gmmrrtd_clock_age_us(&people, L0 + 59960 * MS) < 200 * MS);
}

static void test_tracker_0_6_s_ahead_of_localisation(void **state)
{
    (void)state;
    skew_case(600 * MS);
}

static void test_tracker_1_9_s_ahead_of_localisation(void **state)
{
    (void)state;
    skew_case(1900 * MS);
}

static void step_case(int64_t step_us)
{
    gmmrrtd_source_clock_t s = {0};
    assert_int_equal(stream(&s, L0, T0, 100 * MS, 20), 20);
    int rejected = 0, resynced_at = -1;
    for (int i = 0; i < 40; ++i) {
        const gmmrrtd_stamp_t v =
            gmmrrtd_clock_judge(&s, &k_p, T0 + step_us + (20 + i) * 100 * MS, L0 + (20 + i) * 100 * MS, NULL, NULL);
        rejected += v == GMMRRTD_STAMP_AHEAD || v == GMMRRTD_STAMP_BACKWARDS;
        if (v == GMMRRTD_STAMP_RESYNC)
            resynced_at = i;
        if (resynced_at >= 0 && i > resynced_at)
            assert_int_equal(v, GMMRRTD_STAMP_OK);
    }
    /* Refused until the run is resync_count long and spans resync_us (1 s at 10 Hz: 11 messages). */
    assert_int_equal(resynced_at, 10);
    assert_int_equal(rejected, 10);
    assert_true(gmmrrtd_clock_age_us(&s, L0 + 5900 * MS) <= 100 * MS);
}

static void test_system_clock_stepped_an_hour_ahead(void **state)
{
    (void)state;
    step_case(3600 * S);
}

static void test_system_clock_stepped_an_hour_back(void **state)
{
    (void)state;
    step_case(-3600 * S);
}

static void test_drift_of_100_ppm_is_followed(void **state)
{
    (void)state;
    gmmrrtd_source_clock_t s = {0};
    for (int i = 0; i < 36000; ++i) { /* an hour at 10 Hz; the sender's clock gains 100 us per s */
        const int64_t l = L0 + i * 100 * MS;
        const gmmrrtd_stamp_t v = gmmrrtd_clock_judge(&s, &k_p, T0 + (l - L0) + (l - L0) / 10000, l, NULL, NULL);
        assert_true(v == GMMRRTD_STAMP_OK || v == GMMRRTD_STAMP_FIRST);
    }
    assert_true(gmmrrtd_clock_age_us(&s, L0 + 3600 * S) <= 100 * MS);
}

static void test_out_of_order_message_is_refused(void **state)
{
    (void)state;
    gmmrrtd_source_clock_t s = {0};
    stream(&s, L0, T0, 100 * MS, 10);
    assert_int_equal(gmmrrtd_clock_judge(&s, &k_p, T0 + 500 * MS, L0 + 1000 * MS, NULL, NULL), GMMRRTD_STAMP_BACKWARDS);
    assert_int_equal(gmmrrtd_clock_judge(&s, &k_p, T0 + 1000 * MS, L0 + 1000 * MS, NULL, NULL), GMMRRTD_STAMP_OK);
}

static void test_range(void **state)
{
    (void)state;
    gmmrrtd_source_clock_t s = {0};
    assert_int_equal(gmmrrtd_clock_judge(&s, &k_p, -1, L0, NULL, NULL), GMMRRTD_STAMP_RANGE);
    assert_int_equal(gmmrrtd_clock_judge(&s, &k_p, GMMRRTD_MAX_UTIME + 1, L0, NULL, NULL), GMMRRTD_STAMP_RANGE);
    assert_int_equal(gmmrrtd_clock_judge(&s, &k_p, T0, -5, NULL, NULL), GMMRRTD_STAMP_RANGE);
    assert_false(s.have);
    assert_true(gmmrrtd_clock_age_us(&s, L0) == INT64_MAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ratchet_of_goal_resends_moves_nothing),
        cmocka_unit_test(test_slow_ratchet_never_resyncs),
        cmocka_unit_test(test_far_future_first_stamp_is_replaced_by_the_next),
        cmocka_unit_test(test_tracker_0_6_s_ahead_of_localisation),
        cmocka_unit_test(test_tracker_1_9_s_ahead_of_localisation),
        cmocka_unit_test(test_system_clock_stepped_an_hour_ahead),
        cmocka_unit_test(test_system_clock_stepped_an_hour_back),
        cmocka_unit_test(test_drift_of_100_ppm_is_followed),
        cmocka_unit_test(test_out_of_order_message_is_refused),
        cmocka_unit_test(test_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
