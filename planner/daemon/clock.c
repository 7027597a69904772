/*
 * clock.c - per-source clock models of gmmrrtd (the contract is in clock.h).
 */
#include "clock.h"

#include <stddef.h>

/* Longest local interval whose slew allowance is computed (us): keeps the product with
 * slew_us_per_s (<= 1e6, settings.c) far inside int64. */
#define SLEW_ELAPSED_CAP_US ((int64_t)1000000000)

static void start_at(gmmrrtd_source_clock_t *s, int64_t utime, int64_t local_us, int confirmed)
{
    s->have = 1;
    s->confirmed = confirmed;
    s->offset_us = utime - local_us;
    s->offset_local_us = local_us;
    s->last_utime = utime;
    s->data_local_us = local_us;
    s->off_dir = 0;
    s->off_run = 0;
}

static int64_t abs64(int64_t v) { return v < 0 ? -v : v; }

gmmrrtd_stamp_t gmmrrtd_clock_judge(gmmrrtd_source_clock_t *s, const gmmrrtd_clock_params_t *p, int64_t utime,
                                    int64_t local_us, int64_t *resid_us, int64_t *step_us)
{
    int64_t dummy_r, dummy_s;
    if (resid_us == NULL)
        resid_us = &dummy_r;
    if (step_us == NULL)
        step_us = &dummy_s;
    *resid_us = 0;
    *step_us = 0;
    if (utime < 0 || utime > GMMRRTD_MAX_UTIME || local_us < 0 || local_us > GMMRRTD_MAX_UTIME)
        return GMMRRTD_STAMP_RANGE;
    if (!s->have) {
        start_at(s, utime, local_us, 0);
        return GMMRRTD_STAMP_FIRST;
    }
    /* |offset| <= 2^53 and both times in 0..2^53: |r| < 2^55. */
    const int64_t r = utime - local_us - s->offset_us;
    *resid_us = r;
    int32_t dir = 0;
    if (r > p->max_off_us)
        dir = +1;
    else if (r < -p->max_off_us || utime < s->last_utime)
        dir = -1;

    if (dir != 0 && !s->confirmed && abs64(r) > p->max_off_us) {
        /* Only one message stood for this offset: the new one is as good a witness. */
        *step_us = r;
        start_at(s, utime, local_us, 0);
        return GMMRRTD_STAMP_FIRST;
    }
    if (dir != 0) {
        if (s->off_dir != dir || s->off_run == 0 || abs64(r - s->off_first_resid_us) > p->max_off_us) {
            s->off_dir = dir;
            s->off_run = 0;
            s->off_first_local_us = local_us;
            s->off_first_resid_us = r;
        }
        s->off_run++;
        if (s->off_run >= p->resync_count && local_us - s->off_first_local_us >= p->resync_us) {
            *step_us = r;
            start_at(s, utime, local_us, 1);
            return GMMRRTD_STAMP_RESYNC;
        }
        return dir > 0 ? GMMRRTD_STAMP_AHEAD : GMMRRTD_STAMP_BACKWARDS;
    }

    /* On its source's clock: accepted. */
    s->off_dir = 0;
    s->off_run = 0;
    s->confirmed = 1;
    int64_t elapsed = local_us - s->offset_local_us;
    if (elapsed > SLEW_ELAPSED_CAP_US)
        elapsed = SLEW_ELAPSED_CAP_US;
    if (elapsed < 0)
        elapsed = 0;
    const int64_t allow = elapsed * p->slew_us_per_s / 1000000;
    const int64_t move = r > allow ? allow : r < -allow ? -allow : r;
    s->offset_us += move;
    s->offset_local_us = local_us;
    const int64_t expected = local_us + s->offset_us; /* the source's clock now */
    const int64_t order = utime < expected ? utime : expected;
    if (order > s->last_utime)
        s->last_utime = order;
    const int64_t data = utime - s->offset_us;
    s->data_local_us = data < local_us ? data : local_us;
    return GMMRRTD_STAMP_OK;
}

int64_t gmmrrtd_clock_age_us(const gmmrrtd_source_clock_t *s, int64_t now_us)
{
    if (!s->have)
        return INT64_MAX;
    const int64_t age = now_us - s->data_local_us;
    return age > 0 ? age : 0;
}
