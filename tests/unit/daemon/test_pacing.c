/*
 * test_pacing.c - the event trigger's token bucket (planner/daemon/pacing.h): a pose right after a
 * people list starts its cycle at once, a third input waits for the refill, the long-run rate never
 * exceeds one cycle per period, and burst = 1 is the fixed gap after every start.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "pacing.h"

#define MS ((int64_t)1000)
#define L0 ((int64_t)5000000000) /* local time base: monotonic since boot */

/* Runs inputs every `gap_us` from L0 for `n` inputs; each starts a cycle at the earliest time the
 * bucket allows (then, or later when it must wait), as main.c does. Returns the cycles' start
 * times in `starts`. */
static void drive(int64_t period_us, int burst, int64_t gap_us, int n, int64_t *starts)
{
    gmmrrtd_pacing_t p;
    memset(&p, 0, sizeof p);
    int64_t free_at = 0; /* cycles run one at a time: the next input waits for the previous start */
    for (int i = 0; i < n; ++i) {
        int64_t t = L0 + i * gap_us;
        if (t < free_at)
            t = free_at;
        const int64_t earliest = gmmrrtd_pacing_earliest_us(&p, period_us, burst);
        if (t < earliest)
            t = earliest;
        gmmrrtd_pacing_spend(&p, t, period_us, burst);
        starts[i] = t;
        free_at = t;
    }
}

static void test_a_pose_right_after_a_people_list_starts_at_once(void **state)
{
    (void)state;
    gmmrrtd_pacing_t p;
    memset(&p, 0, sizeof p);
    const int64_t period = 5 * MS;
    /* a zeroed bucket is full: the people list starts a cycle at once */
    assert_true(gmmrrtd_pacing_earliest_us(&p, period, 2) <= L0);
    gmmrrtd_pacing_spend(&p, L0, period, 2);
    /* the pose 0.3 ms later: the second token */
    assert_true(gmmrrtd_pacing_earliest_us(&p, period, 2) <= L0 + 300);
    gmmrrtd_pacing_spend(&p, L0 + 300, period, 2);
    /* a third input waits until one token has come back: one period after the first start's refill */
    assert_int_equal(gmmrrtd_pacing_earliest_us(&p, period, 2), L0 + 5 * MS);
    /* with burst = 1 the same pose would have waited the whole gap */
    gmmrrtd_pacing_t q;
    memset(&q, 0, sizeof q);
    gmmrrtd_pacing_spend(&q, L0, period, 1);
    assert_int_equal(gmmrrtd_pacing_earliest_us(&q, period, 1), L0 + 5 * MS);
}

static void test_the_long_run_rate_is_one_per_period(void **state)
{
    (void)state;
    enum { N = 1000 };
    static int64_t starts[N];
    const int64_t period = 5 * MS;
    for (int burst = 1; burst <= 4; ++burst) {
        drive(period, burst, 100, N, starts); /* inputs every 0.1 ms: far faster than allowed */
        /* in any window [starts[i], starts[j]] there are at most burst + span / period starts */
        for (int i = 0; i < N; ++i)
            for (int j = i; j < N && j < i + 64; ++j)
                assert_true((int64_t)(j - i + 1) <= burst + (starts[j] - starts[i]) / period);
        /* and the bucket is used: the first `burst` go at once, then one per period exactly */
        for (int i = 0; i < burst; ++i)
            assert_int_equal(starts[i], L0 + i * 100);
        assert_int_equal(starts[N - 1] - starts[burst], (int64_t)(N - 1 - burst) * period);
    }
}

static void test_slow_inputs_never_wait(void **state)
{
    (void)state;
    enum { N = 200 };
    int64_t starts[N];
    drive(20 * MS, 2, 50 * MS, N, starts); /* 20 Hz poses against a 20 ms period */
    for (int i = 0; i < N; ++i)
        assert_int_equal(starts[i], L0 + i * 50 * MS);
}

static void test_ticks_faster_than_the_period_leave_no_debt(void **state)
{
    (void)state;
    /* rate_hz 100 (10 ms ticks) against min_period_ms 20 for a minute: ticks spend, the bucket
     * empties but does not go into debt (without the bound its full time would be 2 minutes out). */
    gmmrrtd_pacing_t p;
    memset(&p, 0, sizeof p);
    const int64_t period = 20 * MS;
    int64_t last = L0;
    for (int i = 0; i < 6000; ++i) {
        last = L0 + i * 10 * MS;
        gmmrrtd_pacing_spend(&p, last, period, 2);
    }
    /* an input after the last tick waits at most one period ... */
    assert_true(gmmrrtd_pacing_earliest_us(&p, period, 2) <= last + period);
    /* ... and once the ticks stop (a reload lowered rate_hz) the bucket is full after two */
    assert_true(p.full_at_us <= last + 2 * period);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_pose_right_after_a_people_list_starts_at_once),
        cmocka_unit_test(test_the_long_run_rate_is_one_per_period),
        cmocka_unit_test(test_slow_inputs_never_wait),
        cmocka_unit_test(test_ticks_faster_than_the_period_leave_no_debt),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
