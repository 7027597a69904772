/*
 * pacing.h - how often the event trigger may start a cycle: a token bucket of `burst` cycles that
 * refills one cycle per `period_us` (min_period_ms), kept as one number, the generic cell rate
 * algorithm's theoretical arrival time (ITU-T I.371): the time the bucket would be full again if
 * nothing more were spent.
 *
 * Why a bucket and not a fixed gap: inputs from different sources come out of phase. A people list
 * starts a cycle; the pose that comes a millisecond later should plan at once, not wait out the
 * gap (its wait is the robot's reaction time). With burst = 2 the pose goes at once; over any
 * time t the event trigger still starts at most burst + t / period_us cycles, so min_period_ms
 * keeps bounding the CPU it takes. burst = 1 is a fixed gap of period_us after each cycle start.
 *
 * Pure functions on a caller-owned struct: no I/O, no allocation, no clock reads.
 */
#ifndef GMMRRTD_PACING_H
#define GMMRRTD_PACING_H

#include <stdint.h>

/* Zeroed: a full bucket (local times are >= 0). */
typedef struct {
    int64_t full_at_us; /* when the bucket is full again */
} gmmrrtd_pacing_t;

/* The earliest local time a cycle may start: now or earlier when a token is left. burst >= 1,
 * period_us >= 0. */
int64_t gmmrrtd_pacing_earliest_us(const gmmrrtd_pacing_t *p, int64_t period_us, int burst);

/* A cycle started at now_us: spends one token, if one is left. Every cycle spends, tick or event,
 * so events right after a tick wait for the refill; ticks themselves are not held by the bucket
 * (they run at rate_hz), and an empty bucket stays empty rather than going into debt, so the
 * event trigger never waits more than one period. */
void gmmrrtd_pacing_spend(gmmrrtd_pacing_t *p, int64_t now_us, int64_t period_us, int burst);

#endif
