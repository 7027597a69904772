/*
 * pacing.c - the event trigger's token bucket (pacing.h).
 */
#include "pacing.h"

int64_t gmmrrtd_pacing_earliest_us(const gmmrrtd_pacing_t *p, int64_t period_us, int burst)
{
    /* Cycle start times and periods are far below 2^62 us, so this does not overflow. */
    return p->full_at_us - (int64_t)(burst - 1) * period_us;
}

void gmmrrtd_pacing_spend(gmmrrtd_pacing_t *p, int64_t now_us, int64_t period_us)
{
    const int64_t from = p->full_at_us > now_us ? p->full_at_us : now_us;
    p->full_at_us = from + period_us;
}
