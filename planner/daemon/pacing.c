/*
 * pacing.c - the event trigger's token bucket (pacing.h).
 */
#include "pacing.h"

int64_t gmmrrtd_pacing_earliest_us(const gmmrrtd_pacing_t *p, int64_t period_us, int burst)
{
    /* Cycle start times and periods are far below 2^62 us, so this does not overflow. */
    return p->full_at_us - (int64_t)(burst - 1) * period_us;
}

void gmmrrtd_pacing_spend(gmmrrtd_pacing_t *p, int64_t now_us, int64_t period_us, int burst)
{
    const int64_t from = p->full_at_us > now_us ? p->full_at_us : now_us;
    /* An empty bucket stays empty, it does not go into debt: ticks start cycles without asking it
     * (they keep their rate), and with ticks faster than period_us an unbounded debt would hold
     * the event trigger off for as long as they ran. Empty = an event waits at most one period. */
    const int64_t empty_at = now_us + (int64_t)burst * period_us;
    p->full_at_us = from + period_us < empty_at ? from + period_us : empty_at;
}
